/*
 * Bounds on the conservative fit (pft_tsa_motion_fit_bound, pft_tsa_config_t.fit_a_max /
 * fit_v_max): a quadratic with a = 2 is clamped to a_max and its v_hat / pioneer step to
 * v_max in both directions; bounds of 0 (and bounds the fit stays inside) leave the fit
 * bit-for-bit unchanged; a closed loop that feeds the pioneer back as the next reference
 * point (the runaway seen on vtest.avi) accelerates without limit unbounded and stays within
 * v_max bounded; the configuration check rejects negative bounds.
 * Tolerances: 2e-3 px in q16, 2e-4 px in float (the fit's own accuracy, test_tsa_motion.c).
 */
#include <math.h>
#include <string.h>
#include "pft_test_support.h"
#include "pft/pft_tsa.h"

void setUp(void) {}
void tearDown(void) {}

#define R_(v) pft_test_from_double(v)
#define D_(v) pft_test_to_double(v)
#ifdef PFT_NUMERIC_Q16
#define FIT_TOL 2e-3
#else
#define FIT_TOL 2e-4
#endif

/* o(tau) = s + v tau + a tau^2 at tau = -(n-1)..0 */
static void quad(pft_real_t *o, uint32_t n, double s, double v, double a)
{
    for (uint32_t i = 0; i < n; ++i) {
        const double t = (double)i - (double)(n - 1u);
        o[i] = R_(s + v * t + a * t * t);
    }
}

static void fit_of(const pft_real_t *o, uint32_t n, pft_tsa_motion_fit_t *f)
{
    memset(f, 0, sizeof *f);
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tsa_motion_fit(o, NULL, n, R_(5.0), 2u, f));
}

static void test_bound_clamps_runaway_fit(void)
{
    for (int sign = -1; sign <= 1; sign += 2) {
        pft_real_t o[10];
        pft_tsa_motion_fit_t f, g;
        const double sg = (double)sign;
        quad(o, 10u, 100.0, sg * 3.0, sg * 2.0);
        fit_of(o, 10u, &f);
        TEST_ASSERT_EQUAL_UINT8(2u, f.order);
        TEST_ASSERT_DOUBLE_WITHIN(FIT_TOL, sg * 2.0, D_(f.a));
        TEST_ASSERT_DOUBLE_WITHIN(FIT_TOL * 4, sg * 7.0, D_(f.v_pred));

        /* a bound only: a clamped, v_pred and x_pred recomputed from it */
        g = f;
        pft_tsa_motion_fit_bound(&g, R_(0.5), 0);
        TEST_ASSERT_DOUBLE_WITHIN(1e-9, sg * 0.5, D_(g.a));
        TEST_ASSERT_TRUE(f.s == g.s);
        TEST_ASSERT_TRUE(f.v == g.v);
        TEST_ASSERT_DOUBLE_WITHIN(FIT_TOL * 4, sg * 4.0, D_(g.v_pred));
        TEST_ASSERT_DOUBLE_WITHIN(FIT_TOL * 4, 100.0 + sg * 3.5, D_(g.x_pred));

        /* v bound only: v_hat and the pioneer step clamped, a untouched */
        g = f;
        pft_tsa_motion_fit_bound(&g, 0, R_(4.0));
        TEST_ASSERT_TRUE(f.a == g.a);
        TEST_ASSERT_DOUBLE_WITHIN(1e-9, sg * 4.0, D_(g.v_pred));
        TEST_ASSERT_DOUBLE_WITHIN(FIT_TOL * 4, 100.0 + sg * 4.0, D_(g.x_pred));

        /* both */
        g = f;
        pft_tsa_motion_fit_bound(&g, R_(0.5), R_(2.0));
        TEST_ASSERT_DOUBLE_WITHIN(1e-9, sg * 0.5, D_(g.a));
        TEST_ASSERT_DOUBLE_WITHIN(1e-9, sg * 2.0, D_(g.v_pred));
        TEST_ASSERT_DOUBLE_WITHIN(FIT_TOL * 4, 100.0 + sg * 2.0, D_(g.x_pred));
    }
}

static void test_zero_or_loose_bounds_leave_fit_unchanged(void)
{
    static const double cases[][3] = {{100.0, 3.0, 2.0}, {50.0, -1.5, 0.3}, {7.0, 0.25, -0.1}};
    for (unsigned c = 0; c < sizeof cases / sizeof cases[0]; ++c) {
        pft_real_t o[10];
        pft_tsa_motion_fit_t f, g;
        quad(o, 10u, cases[c][0], cases[c][1], cases[c][2]);
        o[4] = pft_add(o[4], R_(0.75)); /* a little noise */
        fit_of(o, 10u, &f);
        g = f;
        pft_tsa_motion_fit_bound(&g, 0, 0);
        TEST_ASSERT_EQUAL_MEMORY(&f, &g, sizeof f);
        g = f;
        pft_tsa_motion_fit_bound(&g, R_(100.0), R_(500.0));
        TEST_ASSERT_EQUAL_MEMORY(&f, &g, sizeof f);
    }
    pft_tsa_motion_fit_bound(NULL, R_(1.0), R_(1.0)); /* no-op, no crash */
}

/* The pioneer fed back as the next reference point, K = 10, from a history at rest with
 * one 6 px jump (a 6 px/frame step, as on vtest frame 2): returns max |x_pred - s| over 40 frames, and the last |v_pred|. */
static double closed_loop(pft_real_t a_max, pft_real_t v_max, double *v_last)
{
    pft_real_t o[10];
    double max_step = 0.0;
    for (uint32_t i = 0; i < 10u; ++i) {
        o[i] = R_(i >= 9u ? 6.0 : 0.0);
    }
    for (int k = 0; k < 40; ++k) {
        pft_tsa_motion_fit_t f;
        double step;
        fit_of(o, 10u, &f);
        pft_tsa_motion_fit_bound(&f, a_max, v_max);
        step = fabs(D_(f.x_pred) - D_(f.s));
        max_step = step > max_step ? step : max_step;
        *v_last = fabs(D_(f.v_pred));
        /* re-centre when far from 0 so q16 stays in range (the fit is shift invariant) */
        if (D_(f.x_pred) > 1000.0) {
            const pft_real_t sh = R_(1000.0);
            for (uint32_t i = 0; i < 10u; ++i) {
                o[i] = pft_sub(o[i], sh);
            }
            f.x_pred = pft_sub(f.x_pred, sh);
        }
        memmove(&o[0], &o[1], 9u * sizeof o[0]);
        o[9] = f.x_pred;
        if (max_step > 500.0) {
            break;
        }
    }
    return max_step;
}

static void test_closed_loop_runaway_is_bounded(void)
{
    double v_free = 0.0, v_bounded = 0.0;
    const double free_step = closed_loop(0, 0, &v_free);
    const double bounded_step = closed_loop(R_(0.5), R_(12.0), &v_bounded);
    /* unbounded: the quadratic extrapolation of its own prediction amplifies the 6 px step
     * (float: about 4x within 40 frames) */
    TEST_ASSERT_TRUE(free_step > 18.0);
    TEST_ASSERT_TRUE(v_free > 18.0);
    /* bounded: the pioneer never steps more than v_max, v_hat never exceeds it */
    TEST_ASSERT_TRUE(bounded_step <= 12.0 + FIT_TOL);
    TEST_ASSERT_TRUE(v_bounded <= 12.0 + FIT_TOL);
}

static void test_config_bounds(void)
{
    pft_tsa_config_t c;
    const char *field = NULL;
    pft_tsa_config_default(&c);
    c.width = 160u;
    c.height = 120u;
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tsa_config_check(&c, NULL));
    TEST_ASSERT_TRUE(c.fit_a_max >= 0 && c.fit_v_max >= 0);
    c.fit_a_max = 0;
    c.fit_v_max = 0;
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tsa_config_check(&c, NULL));
    c.fit_a_max = R_(-0.5);
    TEST_ASSERT_EQUAL_INT(PFT_ERR_CONFIG, pft_tsa_config_check(&c, &field));
    TEST_ASSERT_EQUAL_STRING("fit_a_max", field);
    c.fit_a_max = 0;
    c.fit_v_max = R_(-1.0);
    TEST_ASSERT_EQUAL_INT(PFT_ERR_CONFIG, pft_tsa_config_check(&c, &field));
    TEST_ASSERT_EQUAL_STRING("fit_v_max", field);
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_bound_clamps_runaway_fit);
    RUN_TEST(test_zero_or_loose_bounds_leave_fit_unchanged);
    RUN_TEST(test_closed_loop_runaway_is_bounded);
    RUN_TEST(test_config_bounds);
    return UNITY_END();
}
