/*
 * SIS, SIR and APF against the exact Kalman filter on a linear-Gaussian model
 * (pft_pf_lg_model_t): constant velocity [p, v], T = 1, q = 0.05 (Q = q [[1/3, 1/2], [1/2, 1]]),
 * position measured with sd 1, prior N([0, 0.5], diag(4, 0.25)), K = 10 steps of measurements
 * simulated from the model with a fixed double-precision generator (two sequences), N = 1500.
 *
 * At every step the particle mean and variance of p and v are compared with the Kalman
 * posterior, and the log evidence log p^(z_k | z_1..k-1) with the Kalman filter's exact
 * value (plus the constant log(sqrt(2 pi) r) the model drops).
 *
 * Statistical tolerance. The weighted mean of a set of effective size ESS has standard error
 * sqrt(P / ESS); after resampling the set keeps the diversity of its worst step, so ESS here
 * is the smallest ESS seen so far (APF: of its first-stage and second-stage weights), and an
 * inflation kappa covers what resampling adds. Asserted, per step and component:
 *   |m_pf - m_kf|        <= 4 sqrt(kappa P / ESS)
 *   |v_pf / v_kf - 1|    <= 4 sqrt(2 kappa / ESS) + 0.02   (0.02: q16 rounding of squares)
 *   |lev_pf - lev_kf|    <= 4 sqrt(kappa / ESS) + 0.01
 * kappa = 3 for SIS and APF, 8 for SIR (resampling every step). Calibration (host, float and
 * q16, 400 PF seeds each): on the two test sequences the largest |error| / tolerance was 0.56
 * (SIS), 0.82 (SIR), 0.64 (APF): no failure; on 400 random sequences one SIR case in q16
 * reached 1.02 (a measurement in the far tail of the prior predictive, where the bootstrap
 * proposal is poor). With the filter's measurement sd set to 1.5 instead of 1 (a wrong but not
 * absurd posterior) every one of the 400 runs of every engine fails the same checks (smallest
 * worst ratio 1.59): test_comparison_detects_a_wrong_posterior asserts it on one run.
 * SIS is compared over the first 5 steps (its ESS collapses afterwards, which is asserted too).
 * The APF's second-stage weights (no double-counted parent weight) are tested exactly in
 * test_pf_engine.c.
 */
#include <math.h>
#include <string.h>

#include "pft_test_support.h"
#include "pft/pft_pf_models.h"

void setUp(void) {}
void tearDown(void) {}

static pft_real_t R(double v) { return pft_test_from_double(v); }
static double D(pft_real_t v) { return pft_test_to_double(v); }

#define K_STEPS 10
#define N_PART 1500
#define KAPPA_SIS 3.0
#define KAPPA_SIR 8.0
#define KAPPA_APF 3.0

static const double Q_ = 0.05;
static const double RSD = 1.0;
static double g_z[K_STEPS];

/* ------------------------ deterministic measurement generator ----------------------------- */
static uint64_t g_lcg;
static double urand(void)
{
    g_lcg = g_lcg * 6364136223846793005ull + 1442695040888963407ull;
    return ((double)(g_lcg >> 11) + 0.5) / 9007199254740992.0;
}
static double nrand(void)
{
    double u1 = urand(), u2 = urand();
    return sqrt(-2.0 * log(u1)) * cos(6.283185307179586 * u2);
}
static void simulate(uint64_t seed)
{
    double l11 = sqrt(Q_ / 3.0), l21 = (Q_ / 2.0) / l11, l22 = sqrt(Q_ / 4.0);
    g_lcg = seed;
    double p = 0.0 + 2.0 * nrand();
    double v = 0.5 + 0.5 * nrand();
    for (int k = 0; k < K_STEPS; ++k) {
        double g1 = nrand(), g2 = nrand();
        p = p + v + l11 * g1;
        v = v + l21 * g1 + l22 * g2;
        g_z[k] = p + RSD * nrand();
    }
}

/* -------------------------------- exact Kalman filter ------------------------------------- */
typedef struct {
    double m[2], P[3]; /* P: pp, pv, vv */
    double loglik;     /* log N(z; H m_pred, S) */
} kf_t;

static void kf_init(kf_t *k)
{
    k->m[0] = 0.0;
    k->m[1] = 0.5;
    k->P[0] = 4.0;
    k->P[1] = 0.0;
    k->P[2] = 0.25;
}
static void kf_step(kf_t *k, double z)
{
    /* predict with F = [[1, 1], [0, 1]] */
    double m0 = k->m[0] + k->m[1], m1 = k->m[1];
    double pp = k->P[0] + 2.0 * k->P[1] + k->P[2] + Q_ / 3.0;
    double pv = k->P[1] + k->P[2] + Q_ / 2.0;
    double vv = k->P[2] + Q_;
    double S = pp + RSD * RSD, nu = z - m0;
    double k0 = pp / S, k1 = pv / S;
    k->loglik = -0.5 * log(2.0 * 3.141592653589793 * S) - 0.5 * nu * nu / S;
    k->m[0] = m0 + k0 * nu;
    k->m[1] = m1 + k1 * nu;
    k->P[0] = pp - k0 * pp;
    k->P[1] = pv - k0 * pv;
    k->P[2] = vv - k1 * pv;
}

/* ----------------------------------- the model -------------------------------------------- */
static void lg_config(pft_pf_lg_config_t *c)
{
    double l11 = sqrt(Q_ / 3.0), l21 = (Q_ / 2.0) / l11, l22 = sqrt(Q_ / 4.0);
    memset(c, 0, sizeof(*c));
    c->dim = 2;
    c->meas = 1;
    c->F[0] = R(1.0);
    c->F[1] = R(1.0);
    c->F[2] = R(0.0);
    c->F[3] = R(1.0);
    c->Lq[0] = R(l11);
    c->Lq[1] = R(0.0);
    c->Lq[2] = R(l21);
    c->Lq[3] = R(l22);
    c->H[0] = R(1.0);
    c->H[1] = R(0.0);
    c->r_sd[0] = R(RSD);
    c->m0[0] = R(0.0);
    c->m0[1] = R(0.5);
    c->L0[0] = R(2.0);
    c->L0[3] = R(0.5);
}

static uint64_t g_work[PFT_PF_WORKSPACE_BYTES(N_PART, 2) / 8 + 1];

/* Worst ratio |error| / tolerance over the checked steps, and the last ESS ratio. */
typedef struct {
    double worst_mean, worst_var, worst_lev, last_ess;
} outcome_t;

static outcome_t run_case(pft_pf_kind_t kind, uint64_t seed, int steps, double kappa,
                          double filter_rsd)
{
    pft_pf_lg_config_t lc;
    pft_pf_lg_model_t lm;
    pft_pf_model_t md;
    pft_pf_config_t c;
    pft_pf_t pf;
    kf_t kf;
    outcome_t o = {0.0, 0.0, 0.0, 0.0};
    lg_config(&lc);
    lc.r_sd[0] = R(filter_rsd);
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_pf_lg_model_init(&lm, &lc, &md));
    pft_pf_config_default(&c);
    c.kind = kind;
    c.n_particles = N_PART;
    c.model = md;
    c.seed = seed;
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_pf_init(&pf, &c, g_work, sizeof(g_work)));
    kf_init(&kf);
    const double lconst = log(sqrt(2.0 * 3.141592653589793) * filter_rsd);
    double ess = (double)N_PART;
    for (int k = 0; k < steps; ++k) {
        pft_real_t z = R(g_z[k]);
        pft_real_t mean[2], cov[4];
        pft_pf_stats_t st;
        TEST_ASSERT_EQUAL_INT(PFT_OK, pft_pf_update(&pf, &z));
        kf_step(&kf, g_z[k]);
        TEST_ASSERT_EQUAL_INT(PFT_OK, pft_pf_mean_cov(&pf, mean, cov));
        TEST_ASSERT_EQUAL_INT(PFT_OK, pft_pf_stats(&pf, &st));
        /* the smallest ESS so far: a resampled set keeps the diversity of its worst step */
        double e_now = D(st.ess_first < st.ess_ratio ? st.ess_first : st.ess_ratio) * N_PART;
        ess = e_now < ess ? e_now : ess;
        double kv[2] = {kf.P[0], kf.P[2]};
        for (int a = 0; a < 2; ++a) {
            double tm = 4.0 * sqrt(kappa * kv[a] / ess);
            double tv = 4.0 * sqrt(2.0 * kappa / ess) + 0.02;
            double em = fabs(D(mean[a]) - kf.m[a]) / tm;
            double ev = fabs(D(cov[a * 3]) / kv[a] - 1.0) / tv;
            o.worst_mean = em > o.worst_mean ? em : o.worst_mean;
            o.worst_var = ev > o.worst_var ? ev : o.worst_var;
        }
        TEST_ASSERT_TRUE(cov[1] == cov[2]);
        double tl = 4.0 * sqrt(kappa / ess) + 0.01;
        double el = fabs(D(st.log_evidence) - (kf.loglik + lconst)) / tl;
        o.worst_lev = el > o.worst_lev ? el : o.worst_lev;
        o.last_ess = D(st.ess_ratio);
    }
    return o;
}

static void check(pft_pf_kind_t kind, int steps, double kappa)
{
    for (uint64_t seed = 11; seed < 13; ++seed) {
        simulate(seed * 7919u);
        outcome_t o = run_case(kind, seed, steps, kappa, RSD);
        TEST_ASSERT_TRUE_MESSAGE(o.worst_mean <= 1.0, "particle mean off the Kalman mean");
        TEST_ASSERT_TRUE_MESSAGE(o.worst_var <= 1.0, "particle variance off the Kalman variance");
        TEST_ASSERT_TRUE_MESSAGE(o.worst_lev <= 1.0, "log evidence off the Kalman value");
    }
}

static void test_sir_matches_kalman(void) { check(PFT_PF_SIR, K_STEPS, KAPPA_SIR); }
static void test_apf_matches_kalman(void) { check(PFT_PF_APF, K_STEPS, KAPPA_APF); }
static void test_sis_matches_kalman_early(void) { check(PFT_PF_SIS, 5, KAPPA_SIS); }

/* SIS degenerates: after 10 steps its ESS is far below the resampling filters'. */
static void test_sis_degenerates(void)
{
    simulate(11u * 7919u);
    outcome_t sis = run_case(PFT_PF_SIS, 11u, K_STEPS, KAPPA_SIS, RSD);
    outcome_t sir = run_case(PFT_PF_SIR, 11u, K_STEPS, KAPPA_SIR, RSD);
    TEST_ASSERT_TRUE(sis.last_ess < 0.5 * sir.last_ess);
}

/* The comparison has power: a filter whose measurement sd is 1.5 instead of 1 (a posterior
 * that is wrong but not absurd) fails it for every engine. */
/* The model refuses reals outside the configuration domain (reliability.md F7) and accepts the
 * reference configuration. */
static void test_lg_config_domain(void)
{
    pft_pf_lg_config_t c;
    pft_pf_lg_model_t m;
    pft_pf_model_t md;
    lg_config(&c);
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_pf_lg_model_init(&m, &c, &md));
    c.r_sd[0] = R(0.0);
    TEST_ASSERT_EQUAL_INT(PFT_ERR_CONFIG, pft_pf_lg_model_init(&m, &c, &md));
#ifndef PFT_NUMERIC_Q16
    lg_config(&c);
    c.L0[0] = 3.4e38f; /* finite, but the prior draws would be infinite */
    TEST_ASSERT_EQUAL_INT(PFT_ERR_CONFIG, pft_pf_lg_model_init(&m, &c, &md));
    lg_config(&c);
    c.r_sd[0] = 1e-39f; /* subnormal: an infinite reciprocal */
    TEST_ASSERT_EQUAL_INT(PFT_ERR_CONFIG, pft_pf_lg_model_init(&m, &c, &md));
    lg_config(&c);
    c.F[5] = 1e30f; /* outside the packed 2 x 2 matrix: not read, not checked */
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_pf_lg_model_init(&m, &c, &md));
#endif
}

static void test_comparison_detects_a_wrong_posterior(void)
{
    const pft_pf_kind_t kinds[3] = {PFT_PF_SIS, PFT_PF_SIR, PFT_PF_APF};
    const double kap[3] = {KAPPA_SIS, KAPPA_SIR, KAPPA_APF};
    for (int k = 0; k < 3; ++k) {
        simulate(11u * 7919u);
        outcome_t o = run_case(kinds[k], 11u, k == 0 ? 5 : K_STEPS, kap[k], 1.5);
        double worst = o.worst_mean > o.worst_var ? o.worst_mean : o.worst_var;
        TEST_ASSERT_TRUE(worst > 1.0);
    }
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_sir_matches_kalman);
    RUN_TEST(test_apf_matches_kalman);
    RUN_TEST(test_sis_matches_kalman_early);
    RUN_TEST(test_sis_degenerates);
    RUN_TEST(test_comparison_detects_a_wrong_posterior);
    RUN_TEST(test_lg_config_domain);
    return UNITY_END();
}
