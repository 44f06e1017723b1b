/*
 * Resampling: exact indices for hand-computed cases (every scheme, M != N included), the
 * c_{j-1} <= T < c_j convention on exact boundaries, agreement with a double reference on
 * random cases, unbiasedness of the counts over many draws, residual copies, scale
 * invariance, and error handling (all-zero weights leave idx untouched).
 */
#include <math.h>
#include <string.h>
#include "pft_test_support.h"

void setUp(void) {}
void tearDown(void) {}

static void note_begin(const char *label)
{
    UnityPrint(label);
    UnityPrint(":");
}
static void note(const char *name, double v)
{
    UnityPrint(" ");
    UnityPrint(name);
    UnityPrint("=");
    UnityPrintFloat(v);
}
static void note_end(void)
{
    UNITY_PRINT_EOL();
}

/* A weight of value x (q16: Q2.30, rounded; x < 4). */
static pft_weight_t wt(double x)
{
#ifdef PFT_NUMERIC_Q16
    return (pft_weight_t)floor(x * 1073741824.0 + 0.5);
#else
    return (pft_weight_t)x;
#endif
}

static double wd(pft_weight_t w)
{
    return (double)w;
}

/* Fraction x in [0, 1) as a 32-bit uniform. */
static uint32_t uf(double x)
{
    return (uint32_t)floor(x * 4294967296.0);
}

static void fill_weights(pft_weight_t *w, const double *x, size_t m)
{
    for (size_t i = 0; i < m; ++i) {
        w[i] = wt(x[i]);
    }
}

static const pft_resample_scheme_t k_schemes[4] = {PFT_RESAMPLE_SYSTEMATIC, PFT_RESAMPLE_STRATIFIED,
                                                   PFT_RESAMPLE_RESIDUAL, PFT_RESAMPLE_MULTINOMIAL};

/* ---------------------------------- hand-computed cases ----------------------------------- */
static void test_systematic_exact(void)
{
    static const double x4[4] = {0.1, 0.2, 0.3, 0.4};
    pft_weight_t w[8];
    uint32_t idx[8];
    fill_weights(w, x4, 4);
    /* T_k = (k + 1/2)/4 = .125 .375 .625 .875; c = .1 .3 .6 1 */
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_resample_systematic_u(w, 4, idx, 4, uf(0.5)));
    {
        static const uint32_t e[4] = {1, 2, 3, 3};
        TEST_ASSERT_EQUAL_UINT32_ARRAY(e, idx, 4);
    }
    /* N < M: T = .25 .75 */
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_resample_systematic_u(w, 4, idx, 2, uf(0.5)));
    TEST_ASSERT_EQUAL_UINT32(1, idx[0]);
    TEST_ASSERT_EQUAL_UINT32(3, idx[1]);
    /* N > M: w = .5 .3 .2, N = 6, T = 1/12 .. 11/12 */
    {
        static const double x3[3] = {0.5, 0.3, 0.2};
        static const uint32_t e[6] = {0, 0, 0, 1, 1, 2};
        fill_weights(w, x3, 3);
        TEST_ASSERT_EQUAL_INT(PFT_OK, pft_resample_systematic_u(w, 3, idx, 6, uf(0.5)));
        TEST_ASSERT_EQUAL_UINT32_ARRAY(e, idx, 6);
    }
}

/* Targets exactly on cumulative sums go to the next index (c_{j-1} <= T < c_j); zero weights,
 * leading or trailing, are never selected, even for u0 at its extremes. */
#ifdef PFT_NUMERIC_Q16
#define U_HI 0xFFFFFFFFu /* q16 targets are exact rationals: 1 - 2^-32 stays below a boundary */
#else
#define U_HI 0xFFF00000u /* float targets resolve 2^-24 relative: stay clear of rounding to it */
#endif
static void test_boundaries_and_zero_weights(void)
{
    pft_weight_t w[6];
    uint32_t idx[4];
    static const double ones[4] = {1.0, 1.0, 1.0, 1.0};
    static const uint32_t e0[4] = {0, 1, 2, 3};
    fill_weights(w, ones, 4);
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_resample_systematic_u(w, 4, idx, 4, 0u));
    TEST_ASSERT_EQUAL_UINT32_ARRAY(e0, idx, 4);
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_resample_systematic_u(w, 4, idx, 4, U_HI));
    TEST_ASSERT_EQUAL_UINT32_ARRAY(e0, idx, 4);

    static const double z[6] = {0.0, 1.0, 0.0, 0.0, 1.0, 0.0};
    static const uint32_t e1[4] = {1, 1, 4, 4};
    fill_weights(w, z, 6);
    /* W = 2, T = 0 .5 1 1.5, c = 0 1 1 1 2 2 */
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_resample_systematic_u(w, 6, idx, 4, 0u));
    TEST_ASSERT_EQUAL_UINT32_ARRAY(e1, idx, 4);
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_resample_systematic_u(w, 6, idx, 4, U_HI));
    TEST_ASSERT_EQUAL_UINT32_ARRAY(e1, idx, 4);
    {
        const uint32_t ulo[4] = {0u, 0u, 0u, 0u};
        const uint32_t uhi[4] = {U_HI, U_HI, U_HI, U_HI};
        TEST_ASSERT_EQUAL_INT(PFT_OK, pft_resample_stratified_u(w, 6, idx, 4, ulo));
        TEST_ASSERT_EQUAL_UINT32_ARRAY(e1, idx, 4);
        TEST_ASSERT_EQUAL_INT(PFT_OK, pft_resample_stratified_u(w, 6, idx, 4, uhi));
        TEST_ASSERT_EQUAL_UINT32_ARRAY(e1, idx, 4);
        TEST_ASSERT_EQUAL_INT(PFT_OK, pft_resample_multinomial_u(w, 6, idx, 4, ulo));
        TEST_ASSERT_EACH_EQUAL_UINT32(1, idx, 4);
        TEST_ASSERT_EQUAL_INT(PFT_OK, pft_resample_multinomial_u(w, 6, idx, 4, uhi));
        TEST_ASSERT_EACH_EQUAL_UINT32(4, idx, 4);
    }
    /* a single positive weight takes every draw */
    static const double one[5] = {0.0, 0.0, 0.7, 0.0, 0.0};
    fill_weights(w, one, 5);
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_resample_systematic_u(w, 5, idx, 4, U_HI));
    TEST_ASSERT_EACH_EQUAL_UINT32(2, idx, 4);
}

static void test_stratified_exact(void)
{
    static const double x4[4] = {0.1, 0.2, 0.3, 0.4};
    pft_weight_t w[4];
    uint32_t idx[6];
    fill_weights(w, x4, 4);
    /* T = (k + u_k)/4 with u = 0, ~1, .5, .25: T = 0, ~.5, .625, .8125 */
    const uint32_t u[4] = {0u, 0xFFFFFFFFu, uf(0.5), uf(0.25)};
    static const uint32_t e[4] = {0, 2, 3, 3};
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_resample_stratified_u(w, 4, idx, 4, u));
    TEST_ASSERT_EQUAL_UINT32_ARRAY(e, idx, 4);
    /* N = 6 > M: T = (k + u_k)/6 with u = .9 .1 .5 .5 .1 .9:
     * .15 .183 .417 .583 .683 .983 -> 1 1 2 2 3 3 */
    const uint32_t u6[6] = {uf(0.9), uf(0.1), uf(0.5), uf(0.5), uf(0.1), uf(0.9)};
    static const uint32_t e6[6] = {1, 1, 2, 2, 3, 3};
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_resample_stratified_u(w, 4, idx, 6, u6));
    TEST_ASSERT_EQUAL_UINT32_ARRAY(e6, idx, 6);
}

static void test_multinomial_exact(void)
{
    static const double x4[4] = {0.1, 0.2, 0.3, 0.4};
    pft_weight_t w[4];
    uint32_t idx[5];
    fill_weights(w, x4, 4);
    /* unsorted u = .95 .05 .5 .35 .65 -> sorted .05 .35 .5 .65 .95 -> 0 2 2 3 3 */
    const uint32_t u[5] = {uf(0.95), uf(0.05), uf(0.5), uf(0.35), uf(0.65)};
    static const uint32_t e[5] = {0, 2, 2, 3, 3};
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_resample_multinomial_u(w, 4, idx, 5, u));
    TEST_ASSERT_EQUAL_UINT32_ARRAY(e, idx, 5);
    /* N = 2 < M */
    const uint32_t u2[2] = {uf(0.99), uf(0.15)};
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_resample_multinomial_u(w, 4, idx, 2, u2));
    TEST_ASSERT_EQUAL_UINT32(1, idx[0]);
    TEST_ASSERT_EQUAL_UINT32(3, idx[1]);
}

/* Residual: dyadic weights with N w_i / W integral give exactly floor(N w_i / W) copies and no
 * random draws; with a remainder the copies come first and one draw follows. */
static void test_residual_exact(void)
{
    static const double x5[5] = {1.0 / 16, 2.0 / 16, 3.0 / 16, 4.0 / 16, 6.0 / 16};
    static const uint32_t e[16] = {0, 1, 1, 2, 2, 2, 3, 3, 3, 3, 4, 4, 4, 4, 4, 4};
    static pft_weight_t scratch[8];
    pft_weight_t w[5];
    uint32_t idx[16];
    pft_rng_t rng;
    TEST_ASSERT_EQUAL_UINT64((uint64_t)5 * sizeof(pft_weight_t),
                             pft_resample_scratch_size(PFT_RESAMPLE_RESIDUAL, 5, 16));
    fill_weights(w, x5, 5);
    for (uint64_t seed = 0; seed < 4; ++seed) {
        pft_rng_seed(&rng, seed);
        TEST_ASSERT_EQUAL_INT(PFT_OK, pft_resample(PFT_RESAMPLE_RESIDUAL, w, 5, idx, 16, &rng,
                                                   scratch, sizeof scratch));
        TEST_ASSERT_EQUAL_UINT32_ARRAY(e, idx, 16);
    }
    /* w = .5 .3 .2, N = 4: copies 2, 1, 0; residuals 0, .2, .8 for the last draw */
    static const double x3[3] = {0.5, 0.3, 0.2};
    fill_weights(w, x3, 3);
    int last2 = 0;
    const int trials = 2000;
    for (int t = 0; t < trials; ++t) {
        pft_rng_seed(&rng, (uint64_t)t);
        TEST_ASSERT_EQUAL_INT(PFT_OK, pft_resample(PFT_RESAMPLE_RESIDUAL, w, 3, idx, 4, &rng,
                                                   scratch, sizeof scratch));
        TEST_ASSERT_EQUAL_UINT32(0, idx[0]);
        TEST_ASSERT_EQUAL_UINT32(0, idx[1]);
        TEST_ASSERT_EQUAL_UINT32(1, idx[2]);
        TEST_ASSERT_TRUE(idx[3] == 1 || idx[3] == 2);
        last2 += idx[3] == 2;
    }
    /* P(idx[3] = 2) = 0.8, SE = sqrt(.16 / 2000) = 0.0089 */
    TEST_ASSERT_DOUBLE_WITHIN(4.0 * 0.0089, 0.8, (double)last2 / trials);
}

/* ---------------------------------- errors ------------------------------------------------ */
static void test_all_zero_weights_refused(void)
{
    pft_weight_t w[5] = {0, 0, 0, 0, 0};
    uint32_t idx[6];
    static pft_weight_t scratch[8];
    const uint32_t u[6] = {1, 2, 3, 4, 5, 6};
    pft_rng_t rng;
    pft_rng_seed(&rng, 1);
    for (int s = 0; s < 4; ++s) {
        for (int i = 0; i < 6; ++i) {
            idx[i] = 0xDEADBEEFu;
        }
        TEST_ASSERT_EQUAL_INT(PFT_ERR_DEGENERATE, pft_resample(k_schemes[s], w, 5, idx, 6, &rng, scratch,
                                                          sizeof scratch));
        TEST_ASSERT_EACH_EQUAL_HEX32(0xDEADBEEFu, idx, 6);
        TEST_ASSERT_EQUAL_INT(PFT_ERR_DEGENERATE, pft_resample(k_schemes[s], w, 0, idx, 6, &rng, scratch,
                                                          sizeof scratch));
        TEST_ASSERT_EACH_EQUAL_HEX32(0xDEADBEEFu, idx, 6);
    }
    TEST_ASSERT_EQUAL_INT(PFT_ERR_DEGENERATE, pft_resample_systematic_u(w, 5, idx, 6, 7u));
    TEST_ASSERT_EQUAL_INT(PFT_ERR_DEGENERATE, pft_resample_stratified_u(w, 5, idx, 6, u));
    TEST_ASSERT_EQUAL_INT(PFT_ERR_DEGENERATE, pft_resample_multinomial_u(w, 5, idx, 6, u));
    TEST_ASSERT_EQUAL_INT(PFT_ERR_DEGENERATE, pft_resample_systematic_u(w, 0, idx, 6, 7u));
    TEST_ASSERT_EACH_EQUAL_HEX32(0xDEADBEEFu, idx, 6);
#ifdef PFT_NUMERIC_FLOAT
    /* float: negative weights count as zero */
    w[1] = -1.0f;
    TEST_ASSERT_EQUAL_INT(PFT_ERR_DEGENERATE, pft_resample_systematic_u(w, 5, idx, 6, 7u));
    TEST_ASSERT_EACH_EQUAL_HEX32(0xDEADBEEFu, idx, 6);
    /* float: a total that overflows to infinity is a range error, not a degenerate set */
    w[1] = 3.0e38f;
    w[2] = 3.0e38f;
    TEST_ASSERT_EQUAL_INT(PFT_ERR_RANGE, pft_resample_systematic_u(w, 5, idx, 6, 7u));
    TEST_ASSERT_EQUAL_INT(PFT_ERR_RANGE, pft_resample(PFT_RESAMPLE_SYSTEMATIC, w, 5, idx, 6, &rng, NULL, 0));
    TEST_ASSERT_EACH_EQUAL_HEX32(0xDEADBEEFu, idx, 6);
#endif
}

static void test_bad_arguments(void)
{
    pft_weight_t w[3];
    uint32_t idx[4];
    pft_weight_t scratch[3];
    pft_rng_t rng;
    static const double x3[3] = {0.5, 0.3, 0.2};
    fill_weights(w, x3, 3);
    pft_rng_seed(&rng, 1);
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_resample(PFT_RESAMPLE_SYSTEMATIC, NULL, 3, idx, 4, &rng, NULL, 0));
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_resample(PFT_RESAMPLE_SYSTEMATIC, w, 3, NULL, 4, &rng, NULL, 0));
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_resample(PFT_RESAMPLE_SYSTEMATIC, w, 3, idx, 4, NULL, NULL, 0));
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_resample((pft_resample_scheme_t)9, w, 3, idx, 4, &rng, NULL, 0));
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_resample_stratified_u(w, 3, idx, 4, NULL));
    /* residual scratch: one element short, or missing, is NOMEM */
    TEST_ASSERT_EQUAL_INT(PFT_ERR_NOMEM, pft_resample(PFT_RESAMPLE_RESIDUAL, w, 3, idx, 4, &rng, scratch,
                                                      sizeof scratch - 1));
    TEST_ASSERT_EQUAL_INT(PFT_ERR_NOMEM, pft_resample(PFT_RESAMPLE_RESIDUAL, w, 3, idx, 4, &rng, NULL, 0));
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_resample(PFT_RESAMPLE_RESIDUAL, w, 3, idx, 4, &rng, scratch,
                                               sizeof scratch));
    /* other schemes need none */
    for (int s = 0; s < 4; ++s) {
        if (k_schemes[s] != PFT_RESAMPLE_RESIDUAL) {
            TEST_ASSERT_EQUAL_UINT64(0, (uint64_t)pft_resample_scratch_size(k_schemes[s], 100, 100));
            TEST_ASSERT_EQUAL_INT(PFT_OK, pft_resample(k_schemes[s], w, 3, idx, 4, &rng, NULL, 0));
        }
    }
    /* N = 0 is a valid no-op */
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_resample(PFT_RESAMPLE_MULTINOMIAL, w, 3, idx, 0, &rng, NULL, 0));
}

/* ---------------------------------- random cases vs double -------------------------------- */
/* Reference index for target fraction f (T = f W): smallest j with c_j > T, in double.
 * Returns -1 when T lies within a relative 1e-6 of a cumulative sum (float rounding may then
 * legitimately pick either side). */
static int ref_index(const pft_weight_t *w, size_t m, double f)
{
    double total = 0.0;
    for (size_t j = 0; j < m; ++j) {
        total += wd(w[j]);
    }
    const double t = f * total;
    double c = 0.0;
    for (size_t j = 0; j < m; ++j) {
        c += wd(w[j]);
        if (fabs(c - t) <= 1e-6 * total) {
            return -1;
        }
        if (c > t && wd(w[j]) > 0.0) {
            return (int)j;
        }
    }
    return -1;
}

#define RM 37
#define RN 53

static void test_random_vs_reference(void)
{
    static pft_weight_t w[RM];
    static uint32_t idx[RN];
    static uint32_t u[RN];
    pft_rng_t rng;
    int checked = 0;
    pft_rng_seed(&rng, 555);
    for (int trial = 0; trial < 60; ++trial) {
        const size_t m = 1 + pft_rng_below(&rng, RM);
        const size_t n = 1 + pft_rng_below(&rng, RN);
        for (size_t j = 0; j < m; ++j) {
            /* a third of the weights zero, the rest spread over three decades */
            const uint32_t r = pft_rng_below(&rng, 3);
            w[j] = r == 0 ? wt(0.0) : wt(exp(-6.9 * (double)pft_rng_u32(&rng) / 4294967296.0));
        }
        w[pft_rng_below(&rng, (uint32_t)m)] = wt(0.5); /* at least one positive */
        for (size_t k = 0; k < n; ++k) {
            u[k] = pft_rng_u32(&rng);
        }
        /* systematic */
        TEST_ASSERT_EQUAL_INT(PFT_OK, pft_resample_systematic_u(w, m, idx, n, u[0]));
        for (size_t k = 0; k < n; ++k) {
            const int e = ref_index(w, m, ((double)k + u[0] / 4294967296.0) / (double)n);
            TEST_ASSERT_TRUE(idx[k] < m);
            TEST_ASSERT_TRUE(wd(w[idx[k]]) > 0.0);
            if (e >= 0) {
                TEST_ASSERT_EQUAL_UINT32((uint32_t)e, idx[k]);
                ++checked;
            }
        }
        /* stratified */
        TEST_ASSERT_EQUAL_INT(PFT_OK, pft_resample_stratified_u(w, m, idx, n, u));
        for (size_t k = 0; k < n; ++k) {
            const int e = ref_index(w, m, ((double)k + u[k] / 4294967296.0) / (double)n);
            TEST_ASSERT_TRUE(idx[k] < m);
            if (e >= 0) {
                TEST_ASSERT_EQUAL_UINT32((uint32_t)e, idx[k]);
                ++checked;
            }
        }
        /* multinomial: reference on the sorted uniforms (insertion sort here) */
        TEST_ASSERT_EQUAL_INT(PFT_OK, pft_resample_multinomial_u(w, m, idx, n, u));
        {
            static uint32_t us[RN];
            for (size_t k = 0; k < n; ++k) {
                size_t p = k;
                while (p > 0 && us[p - 1] > u[k]) {
                    us[p] = us[p - 1];
                    --p;
                }
                us[p] = u[k];
            }
            for (size_t k = 0; k < n; ++k) {
                const int e = ref_index(w, m, us[k] / 4294967296.0);
                TEST_ASSERT_TRUE(idx[k] < m);
                if (k > 0) {
                    TEST_ASSERT_TRUE(idx[k] >= idx[k - 1]);
                }
                if (e >= 0) {
                    TEST_ASSERT_EQUAL_UINT32((uint32_t)e, idx[k]);
                    ++checked;
                }
            }
        }
    }
    note_begin("random vs double reference");
    note("indices_checked", checked);
    note_end();
    TEST_ASSERT_TRUE(checked > 3000);
}

/* Scaling every weight by 4 (exact in both builds) changes no index. */
static void test_scale_invariance(void)
{
    static pft_weight_t w[RM], w4[RM];
    static uint32_t a[RN], b[RN], u[RN];
    pft_rng_t rng;
    pft_rng_seed(&rng, 808);
    for (size_t j = 0; j < RM; ++j) {
        w[j] = wt(0.9 * (double)pft_rng_u32(&rng) / 4294967296.0);
#ifdef PFT_NUMERIC_Q16
        w4[j] = w[j] * 4u;
#else
        w4[j] = w[j] * 4.0f;
#endif
    }
    for (size_t k = 0; k < RN; ++k) {
        u[k] = pft_rng_u32(&rng);
    }
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_resample_stratified_u(w, RM, a, RN, u));
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_resample_stratified_u(w4, RM, b, RN, u));
    TEST_ASSERT_EQUAL_UINT32_ARRAY(a, b, RN);
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_resample_multinomial_u(w, RM, a, RN, u));
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_resample_multinomial_u(w4, RM, b, RN, u));
    TEST_ASSERT_EQUAL_UINT32_ARRAY(a, b, RN);
}

/* ---------------------------------- unbiasedness ------------------------------------------ */
/* Over T draws the mean count of index i must be N w_i / W within 4.5 SE, with
 * SE = sqrt(N p (1 - p) / T) (the multinomial variance, an upper bound for the other schemes).
 * Systematic and residual counts must also stay within {floor, ceil} of N w_i / W, and for the
 * multinomial the pooled counts must pass a chi-square test. */
#define UB_M 7
#define UB_N 10
#define UB_T 4000

static void test_unbiased_counts(void)
{
    static const double x[UB_M] = {0.05, 0.2, 0.0, 0.13, 0.3, 0.07, 0.25};
    static pft_weight_t scratch[UB_M];
    pft_weight_t w[UB_M];
    uint32_t idx[UB_N];
    double p[UB_M];
    double tot = 0.0;
    pft_rng_t rng;
    fill_weights(w, x, UB_M);
    for (int i = 0; i < UB_M; ++i) {
        tot += wd(w[i]);
    }
    for (int i = 0; i < UB_M; ++i) {
        p[i] = wd(w[i]) / tot;
    }
    pft_rng_seed(&rng, 2718);
    for (int s = 0; s < 4; ++s) {
        long sum[UB_M] = {0};
        double worst = 0.0;
        for (int t = 0; t < UB_T; ++t) {
            int cnt[UB_M] = {0};
            TEST_ASSERT_EQUAL_INT(PFT_OK, pft_resample(k_schemes[s], w, UB_M, idx, UB_N, &rng,
                                                       scratch, sizeof scratch));
            for (int k = 0; k < UB_N; ++k) {
                TEST_ASSERT_TRUE(idx[k] < UB_M);
                cnt[idx[k]]++;
                if (k > 0 && k_schemes[s] != PFT_RESAMPLE_RESIDUAL) {
                    TEST_ASSERT_TRUE(idx[k] >= idx[k - 1]);
                }
            }
            for (int i = 0; i < UB_M; ++i) {
                sum[i] += cnt[i];
                if (k_schemes[s] == PFT_RESAMPLE_SYSTEMATIC || k_schemes[s] == PFT_RESAMPLE_RESIDUAL) {
                    const double e = UB_N * p[i];
                    TEST_ASSERT_TRUE(cnt[i] >= (int)floor(e) && cnt[i] <= (int)ceil(e));
                }
            }
        }
        for (int i = 0; i < UB_M; ++i) {
            const double mean = (double)sum[i] / UB_T;
            const double e = UB_N * p[i];
            const double se = sqrt(UB_N * p[i] * (1.0 - p[i]) / UB_T);
            if (p[i] == 0.0) {
                TEST_ASSERT_EQUAL_INT(0, sum[i]);
                continue;
            }
            const double z = fabs(mean - e) / se;
            worst = z > worst ? z : worst;
            TEST_ASSERT_TRUE(z < 4.5);
        }
        if (k_schemes[s] == PFT_RESAMPLE_MULTINOMIAL) {
            /* 6 positive weights: chi2(5), upper 0.999 quantile 20.52 */
            double chi2 = 0.0;
            for (int i = 0; i < UB_M; ++i) {
                if (p[i] > 0.0) {
                    const double e = (double)UB_N * UB_T * p[i];
                    chi2 += (sum[i] - e) * (sum[i] - e) / e;
                }
            }
            note_begin("multinomial pooled");
            note("chi2_5", chi2);
            note_end();
            TEST_ASSERT_TRUE(chi2 < 20.52);
        }
        note_begin("unbiased counts");
        note("scheme", s);
        note("worst_dev_in_multinomial_SE", worst);
        note_end();
    }
}

/* Residual: counts are floor(N w_i / W) or one more, on random weights with M != N. */
static void test_residual_copies_random(void)
{
    static pft_weight_t w[RM];
    static pft_weight_t scratch[RM];
    static uint32_t idx[RN];
    pft_rng_t rng;
    pft_rng_seed(&rng, 99);
    for (int trial = 0; trial < 50; ++trial) {
        const size_t m = 1 + pft_rng_below(&rng, RM);
        const size_t n = 1 + pft_rng_below(&rng, RN);
        double tot = 0.0;
        int cnt[RM] = {0};
        for (size_t j = 0; j < m; ++j) {
            w[j] = wt(0.01 + 0.99 * pft_rng_u32(&rng) / 4294967296.0);
            tot += wd(w[j]);
        }
        TEST_ASSERT_EQUAL_INT(PFT_OK, pft_resample(PFT_RESAMPLE_RESIDUAL, w, m, idx, n, &rng,
                                                   scratch, sizeof scratch));
        for (size_t k = 0; k < n; ++k) {
            TEST_ASSERT_TRUE(idx[k] < m);
            cnt[idx[k]]++;
        }
        for (size_t j = 0; j < m; ++j) {
            const double e = (double)n * wd(w[j]) / tot;
            TEST_ASSERT_TRUE(cnt[j] >= (int)floor(e + 1e-9) && cnt[j] <= (int)floor(e) + 1);
        }
    }
}

/* Large M and N: bounds, order and total in a single pass (also a timing smoke test). */
#define BIG 4096
static void test_large(void)
{
    static pft_weight_t w[BIG];
    static uint32_t idx[BIG + 100];
    static pft_weight_t scratch[BIG];
    pft_rng_t rng;
    pft_rng_seed(&rng, 4);
    for (size_t j = 0; j < BIG; ++j) {
        w[j] = wt(pft_rng_u32(&rng) / 4294967296.0);
    }
    for (int s = 0; s < 4; ++s) {
        TEST_ASSERT_EQUAL_INT(PFT_OK, pft_resample(k_schemes[s], w, BIG, idx, BIG + 100, &rng,
                                                   scratch, sizeof scratch));
        for (size_t k = 0; k < BIG + 100; ++k) {
            TEST_ASSERT_TRUE(idx[k] < BIG);
        }
    }
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_systematic_exact);
    RUN_TEST(test_boundaries_and_zero_weights);
    RUN_TEST(test_stratified_exact);
    RUN_TEST(test_multinomial_exact);
    RUN_TEST(test_residual_exact);
    RUN_TEST(test_all_zero_weights_refused);
    RUN_TEST(test_bad_arguments);
    RUN_TEST(test_random_vs_reference);
    RUN_TEST(test_scale_invariance);
    RUN_TEST(test_unbiased_counts);
    RUN_TEST(test_residual_copies_random);
    RUN_TEST(test_large);
    return UNITY_END();
}
