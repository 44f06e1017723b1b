/*
 * TSA dynamics (docs/algorithms.md 4.1, 4.2, eq. 24-25): free-model coefficients against the
 * closed forms in double (and the exact NCV limits at beta = 0), the conservative fit
 * recovering a known quadratic exactly and agreeing with a double solve of the adjugate
 * normal equations on noisy data, its fallbacks, the beta adaptation formula and the
 * reference-point rule.
 * Tolerances: coefficients 2e-4 absolute in q16 (a few LSB through the series and pft_exp),
 * 2e-6 relative in float; fit 2e-3 px in q16, 2e-4 px in float.
 */
#include <math.h>
#include "pft_test_support.h"
#include "pft/pft_tsa.h"

void setUp(void) {}
void tearDown(void) {}

#define R_(v) pft_test_from_double(v)
#define D_(v) pft_test_to_double(v)
#ifdef PFT_NUMERIC_Q16
#define COEF_TOL 2e-4
#define FIT_TOL 2e-3
#else
#define COEF_TOL 2e-5
#define FIT_TOL 2e-4
#endif

static void ref_coef(double b, double q, double *o)
{
    double E = exp(-b), f1, f2;
    if (b == 0.0) {
        o[0] = 1; o[1] = 1; o[2] = 0; o[3] = 0; o[4] = q / 3; o[5] = q / 2; o[6] = q;
        return;
    }
    f1 = (1 - E) / b;
    f2 = (1 - exp(-2 * b)) / (2 * b);
    o[0] = f1;                       /* phi12 */
    o[1] = E;                        /* phi22 */
    o[2] = (b - 1 + E) / b;          /* gamma1 */
    o[3] = 1 - E;                    /* gamma2 */
    o[4] = q / (b * b) * (1 - 2 * (1 - E) / b + (1 - exp(-2 * b)) / (2 * b)); /* Q11 */
    o[5] = q / (2 * b * b) * (1 - E) * (1 - E);                             /* Q12 */
    o[6] = q * f2;                                                         /* Q22 */
}

static void test_free_coefficients(void)
{
    static const double betas[] = {0.0, 0.05, 0.3, 0.7, 0.999, 1.0, 2.0, 4.5, 6.0, 20.0};
    const double q = 4.07;
    for (unsigned i = 0; i < sizeof betas / sizeof betas[0]; ++i) {
        pft_tsa_motion_free_t c;
        double r[7], g[7];
        TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tsa_motion_free_coef(&c, R_(betas[i]), R_(q)));
        ref_coef(D_(R_(betas[i])), D_(R_(q)), r);
        g[0] = D_(c.phi12); g[1] = D_(c.phi22); g[2] = D_(c.gamma1); g[3] = D_(c.gamma2);
        g[4] = D_(c.q11); g[5] = D_(c.q12); g[6] = D_(c.q22);
        for (int k = 0; k < 7; ++k) {
            const double tol = COEF_TOL * (k >= 4 ? q : 1.0) * (fabs(r[k]) > 1 ? fabs(r[k]) : 1.0);
            if (fabs(g[k] - r[k]) > tol) {
                UnityPrint("beta=");
                UnityPrintFloat(betas[i]);
                UnityPrint(" k=");
                UnityPrintNumber(k);
                UnityPrint(" got ");
                UnityPrintFloat(g[k]);
                UnityPrint(" ref ");
                UnityPrintFloat(r[k]);
                TEST_FAIL_MESSAGE("free-model coefficient off");
            }
        }
        /* Cholesky factor reproduces Q */
        TEST_ASSERT_DOUBLE_WITHIN(COEF_TOL * 10 * q, r[4], D_(c.l11) * D_(c.l11));
        TEST_ASSERT_DOUBLE_WITHIN(COEF_TOL * 10 * q, r[5], D_(c.l11) * D_(c.l21));
        TEST_ASSERT_DOUBLE_WITHIN(COEF_TOL * 10 * q, r[6], D_(c.l21) * D_(c.l21) + D_(c.l22) * D_(c.l22));
    }
}

static void test_ncv_limit_and_step(void)
{
    pft_tsa_motion_free_t c;
    pft_real_t x = R_(10.0), v = R_(2.5);
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tsa_motion_free_coef(&c, 0, R_(4.0)));
    TEST_ASSERT_TRUE(c.phi12 == PFT_REAL_ONE && c.phi22 == PFT_REAL_ONE);
    TEST_ASSERT_TRUE(c.gamma1 == 0 && c.gamma2 == 0);
    /* NCV: vbar has no effect, x += v */
    pft_tsa_motion_free_step(&c, &x, &v, R_(100.0), 0, 0);
    TEST_ASSERT_DOUBLE_WITHIN(1e-6, 12.5, D_(x));
    TEST_ASSERT_DOUBLE_WITHIN(1e-6, 2.5, D_(v));
    /* beta = 6: velocity pulled almost entirely to vbar (e^-6 = 0.0025) */
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tsa_motion_free_coef(&c, R_(6.0), R_(4.0)));
    x = R_(0.0);
    v = R_(0.0);
    pft_tsa_motion_free_step(&c, &x, &v, R_(10.0), 0, 0);
    TEST_ASSERT_DOUBLE_WITHIN(1e-3, 10.0 * (1 - exp(-6.0)), D_(v));
    TEST_ASSERT_DOUBLE_WITHIN(1e-3, 10.0 * (6 - 1 + exp(-6.0)) / 6, D_(x));
    /* noise enters through the Cholesky factor */
    x = R_(0.0);
    v = R_(0.0);
    pft_tsa_motion_free_step(&c, &x, &v, 0, R_(1.0), R_(-1.0));
    TEST_ASSERT_DOUBLE_WITHIN(1e-3, D_(c.l11), D_(x));
    TEST_ASSERT_DOUBLE_WITHIN(1e-3, D_(c.l21) - D_(c.l22), D_(v));
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_tsa_motion_free_coef(&c, R_(-0.5), R_(4.0)));
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_tsa_motion_free_coef(&c, R_(65.0), R_(4.0)));
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_tsa_motion_free_coef(NULL, R_(1.0), R_(4.0)));
}

static void test_fit_recovers_quadratic(void)
{
    /* o(tau) = 300 + 3 tau + 0.5 tau^2 (a = 0.5: physical acceleration 1 px/frame^2) */
    for (unsigned n = 3; n <= PFT_TSA_MOTION_MAX_K; ++n) {
        pft_real_t o[PFT_TSA_MOTION_MAX_K];
        pft_tsa_motion_fit_t f;
        for (unsigned i = 0; i < n; ++i) {
            const double tau = (double)i - (double)(n - 1);
            o[i] = R_(300.0 + 3.0 * tau + 0.5 * tau * tau);
        }
        TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tsa_motion_fit(o, NULL, n, R_(n / 2.0), 2, &f));
        TEST_ASSERT_EQUAL_UINT8(2, f.order);
        TEST_ASSERT_DOUBLE_WITHIN(FIT_TOL, 300.0, D_(f.s));
        TEST_ASSERT_DOUBLE_WITHIN(FIT_TOL, 3.0, D_(f.v));
        TEST_ASSERT_DOUBLE_WITHIN(FIT_TOL, 0.5, D_(f.a));
        TEST_ASSERT_DOUBLE_WITHIN(FIT_TOL, 4.0, D_(f.v_pred));   /* v + 2a */
        TEST_ASSERT_DOUBLE_WITHIN(FIT_TOL, 303.5, D_(f.x_pred)); /* s + v + a */
    }
}

/* Double reference: weighted normal equations solved by the adjugate (docs/algorithms.md 4.2). */
static void ref_fit(const double *o, const double *pi, unsigned n, double sg, int order,
                    double *s, double *v, double *a)
{
    double A[5] = {0}, B[3] = {0};
    for (unsigned i = 0; i < n; ++i) {
        const double tau = (double)i - (double)(n - 1);
        const double g = (pi ? pi[i] : 1.0) * exp(-tau * tau / (2 * sg * sg));
        double t = 1;
        for (int k = 0; k < 5; ++k) {
            A[k] += g * t;
            if (k < 3) {
                B[k] += g * o[i] * t;
            }
            t *= tau;
        }
    }
    if (order == 2) {
        double c11 = A[2] * A[4] - A[3] * A[3], c12 = A[2] * A[3] - A[1] * A[4];
        double c13 = A[1] * A[3] - A[2] * A[2], c22 = A[0] * A[4] - A[2] * A[2];
        double c23 = A[1] * A[2] - A[0] * A[3], c33 = A[0] * A[2] - A[1] * A[1];
        double D = A[0] * c11 + A[1] * c12 + A[2] * c13;
        *s = (c11 * B[0] + c12 * B[1] + c13 * B[2]) / D;
        *v = (c12 * B[0] + c22 * B[1] + c23 * B[2]) / D;
        *a = (c13 * B[0] + c23 * B[1] + c33 * B[2]) / D;
    } else {
        double D = A[0] * A[2] - A[1] * A[1];
        *s = (A[2] * B[0] - A[1] * B[1]) / D;
        *v = (A[0] * B[1] - A[1] * B[0]) / D;
        *a = 0;
    }
}

static void test_fit_matches_adjugate_on_noisy_data(void)
{
    uint32_t st = 12345u;
    for (int trial = 0; trial < 40; ++trial) {
        const unsigned n = 3u + (unsigned)(trial % 14);
        pft_real_t o[PFT_TSA_MOTION_MAX_K], pi[PFT_TSA_MOTION_MAX_K];
        double od[PFT_TSA_MOTION_MAX_K], pd[PFT_TSA_MOTION_MAX_K], s, v, a;
        const int order = (trial & 1) ? 2 : 1;
        const bool use_pi = (trial % 3) == 0;
        pft_tsa_motion_fit_t f;
        for (unsigned i = 0; i < n; ++i) {
            st = st * 1664525u + 1013904223u;
            o[i] = R_(200.0 + 7.0 * i - 0.3 * i * i + (double)(st >> 24) / 40.0);
            st = st * 1664525u + 1013904223u;
            pi[i] = R_(0.3 + (double)(st >> 24) / 400.0);
            od[i] = D_(o[i]);
            pd[i] = D_(pi[i]);
        }
        TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tsa_motion_fit(o, use_pi ? pi : NULL, n, R_(5.0), (uint8_t)order, &f));
        TEST_ASSERT_EQUAL_UINT8(order, f.order);
        ref_fit(od, use_pi ? pd : NULL, n, D_(R_(5.0)), order, &s, &v, &a);
        TEST_ASSERT_DOUBLE_WITHIN(4 * FIT_TOL, s, D_(f.s));
        TEST_ASSERT_DOUBLE_WITHIN(4 * FIT_TOL, v, D_(f.v));
        TEST_ASSERT_DOUBLE_WITHIN(4 * FIT_TOL, a, D_(f.a));
        TEST_ASSERT_DOUBLE_WITHIN(8 * FIT_TOL, s + v + a, D_(f.x_pred));
        TEST_ASSERT_DOUBLE_WITHIN(8 * FIT_TOL, v + 2 * a, D_(f.v_pred));
    }
}

static void test_fit_fallbacks(void)
{
    pft_real_t o[4] = {R_(10.0), R_(14.0), R_(18.0), R_(22.0)};
    pft_real_t pi[4] = {0, 0, 0, R_(1.0)};
    pft_tsa_motion_fit_t f;
    /* one point: v = a = 0 */
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tsa_motion_fit(&o[3], NULL, 1, R_(5.0), 2, &f));
    TEST_ASSERT_EQUAL_UINT8(0, f.order);
    TEST_ASSERT_DOUBLE_WITHIN(1e-6, 22.0, D_(f.x_pred));
    TEST_ASSERT_DOUBLE_WITHIN(1e-6, 0.0, D_(f.v_pred));
    /* two points: the constant-velocity line through them */
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tsa_motion_fit(&o[2], NULL, 2, R_(5.0), 2, &f));
    TEST_ASSERT_EQUAL_UINT8(1, f.order);
    TEST_ASSERT_DOUBLE_WITHIN(FIT_TOL, 4.0, D_(f.v_pred));
    TEST_ASSERT_DOUBLE_WITHIN(FIT_TOL, 26.0, D_(f.x_pred));
    /* max_order 1 (TS) on a line of 4 points */
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tsa_motion_fit(o, NULL, 4, R_(2.0), 1, &f));
    TEST_ASSERT_EQUAL_UINT8(1, f.order);
    TEST_ASSERT_DOUBLE_WITHIN(FIT_TOL, 0.0, D_(f.a));
    TEST_ASSERT_DOUBLE_WITHIN(FIT_TOL, 26.0, D_(f.x_pred));
    /* all weight on one point: order 0 at that point */
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tsa_motion_fit(o, pi, 4, R_(5.0), 2, &f));
    TEST_ASSERT_EQUAL_UINT8(0, f.order);
    TEST_ASSERT_DOUBLE_WITHIN(FIT_TOL, 22.0, D_(f.x_pred));
    /* bad arguments */
    pi[3] = 0;
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_tsa_motion_fit(o, pi, 4, R_(5.0), 2, &f));
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_tsa_motion_fit(o, NULL, 0, R_(5.0), 2, &f));
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_tsa_motion_fit(o, NULL, PFT_TSA_MOTION_MAX_K + 1u, R_(5.0), 2, &f));
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_tsa_motion_fit(o, NULL, 4, 0, 2, &f));
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_tsa_motion_fit(o, NULL, 4, R_(5.0), 3, &f));
}

static void test_beta_adaptation_and_reference_rule(void)
{
    const pft_real_t bm = R_(6.0);
    TEST_ASSERT_DOUBLE_WITHIN(1e-4, 3.0, D_(pft_tsa_motion_beta_adapt(R_(0.8), R_(0.8), bm, R_(2.0))));
    TEST_ASSERT_DOUBLE_WITHIN(1e-4, 6.0 * 0.9 / (0.9 + 0.3), D_(pft_tsa_motion_beta_adapt(R_(0.3), R_(0.9), bm, 0)));
    TEST_ASSERT_DOUBLE_WITHIN(1e-4, 6.0 * 0.1 / (0.1 + 0.95), D_(pft_tsa_motion_beta_adapt(R_(0.95), R_(0.1), bm, 0)));
    TEST_ASSERT_DOUBLE_WITHIN(1e-6, 6.0, D_(pft_tsa_motion_beta_adapt(0, R_(0.7), bm, 0)));
    TEST_ASSERT_DOUBLE_WITHIN(1e-6, 0.0, D_(pft_tsa_motion_beta_adapt(R_(0.7), 0, bm, R_(4.0))));
    TEST_ASSERT_DOUBLE_WITHIN(1e-6, 1.5, D_(pft_tsa_motion_beta_adapt(0, 0, bm, R_(1.5)))); /* keeps beta */
    TEST_ASSERT_TRUE(pft_tsa_motion_ref_is_estimate(R_(0.9), R_(0.8)));
    TEST_ASSERT_FALSE(pft_tsa_motion_ref_is_estimate(R_(0.8), R_(0.9)));
    TEST_ASSERT_TRUE(pft_tsa_motion_ref_is_estimate(R_(0.8), R_(0.8))); /* tie: the estimate [C] */
    TEST_ASSERT_TRUE(pft_tsa_motion_ref_is_estimate(0, 0));
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_free_coefficients);
    RUN_TEST(test_ncv_limit_and_step);
    RUN_TEST(test_fit_recovers_quadratic);
    RUN_TEST(test_fit_matches_adjugate_on_noisy_data);
    RUN_TEST(test_fit_fallbacks);
    RUN_TEST(test_beta_adaptation_and_reference_rule);
    return UNITY_END();
}
