/*
 * RNG: bit-exact integer stream (the same on every build and target), unbiased bounded
 * integers, and the statistics of the uniform and Gaussian reals for a fixed seed.
 *
 * Statistical checks use a fixed seed, so they are deterministic; their tolerances are stated
 * in standard errors (SE) or as chi-square quantiles, chosen so that a correct generator
 * passes for any seed with probability > 99.8 %, while the defects they target (modulo bias,
 * missing rejection, wrong scale or offset, broken Box-Muller) fail by many SE.
 */
#include <math.h>
#include "pft_test_support.h"

void setUp(void) {}
void tearDown(void) {}

/* Prints "label: name=value ..." lines (measured statistics, for the record). */
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

/* ---- independent reference: splitmix64 + xoshiro128** (Vigna's published algorithms) ---- */
typedef struct {
    uint32_t s[4];
} ref_xo_t;

static uint64_t ref_splitmix64(uint64_t *x)
{
    uint64_t z = (*x += UINT64_C(0x9E3779B97F4A7C15));
    z = (z ^ (z >> 30)) * UINT64_C(0xBF58476D1CE4E5B9);
    z = (z ^ (z >> 27)) * UINT64_C(0x94D049BB133111EB);
    return z ^ (z >> 31);
}

static uint32_t ref_rotl(uint32_t x, int k)
{
    return (x << k) | (x >> (32 - k));
}

static uint32_t ref_next(ref_xo_t *r)
{
    uint32_t *s = r->s;
    const uint32_t result = ref_rotl(s[1] * 5, 7) * 9;
    const uint32_t t = s[1] << 9;
    s[2] ^= s[0];
    s[3] ^= s[1];
    s[1] ^= s[2];
    s[0] ^= s[3];
    s[2] ^= t;
    s[3] = ref_rotl(s[3], 11);
    return result;
}

/* Library convention: s[0..1] = low, high word of the first splitmix64 output; s[2..3] of the
 * second. */
static void ref_seed(ref_xo_t *r, uint64_t seed)
{
    uint64_t x = seed;
    uint64_t a = ref_splitmix64(&x);
    uint64_t b = ref_splitmix64(&x);
    r->s[0] = (uint32_t)a;
    r->s[1] = (uint32_t)(a >> 32);
    r->s[2] = (uint32_t)b;
    r->s[3] = (uint32_t)(b >> 32);
}

/* First 8 outputs for three seeds, computed once (Python big-integer transcription of the
 * same published algorithms) and frozen here: every build and target must reproduce them. */
static const uint64_t k_seeds[3] = {UINT64_C(0x0123456789ABCDEF), UINT64_C(0), UINT64_C(42)};
static const uint32_t k_expected[3][8] = {
    {0x3DEC9F5Du, 0xE7CDCD35u, 0xE39F89B5u, 0x13921962u, 0x84618E7Fu, 0xDFDBD178u, 0x67C12E2Au, 0xC2E8BC40u},
    {0xDEC9045Du, 0x9A089D75u, 0xAB77D362u, 0xC3E16405u, 0x5C95A8DAu, 0x60DEA056u, 0xC25A5140u, 0xA4290614u},
    {0x69E85A2Au, 0xF843FAD0u, 0x0105185Fu, 0x8A1F1EA6u, 0xA66BE2A9u, 0x9844904Eu, 0xAF4213E7u, 0x85C95CD7u},
};

static void test_reference_vectors(void)
{
    /* Sanity of the reference itself against the published test vectors. */
    uint64_t x = 0;
    ref_xo_t r = {{1u, 2u, 3u, 4u}};
    TEST_ASSERT_EQUAL_HEX64(UINT64_C(0xE220A8397B1DCDAF), ref_splitmix64(&x));
    TEST_ASSERT_EQUAL_HEX64(UINT64_C(0x6E789E6AA1B965F4), ref_splitmix64(&x));
    TEST_ASSERT_EQUAL_HEX32(11520u, ref_next(&r));
    TEST_ASSERT_EQUAL_HEX32(0u, ref_next(&r));
    TEST_ASSERT_EQUAL_HEX32(5927040u, ref_next(&r));
}

static void test_stream_matches_frozen_and_reference(void)
{
    for (int si = 0; si < 3; ++si) {
        pft_rng_t rng;
        ref_xo_t ref;
        pft_rng_seed(&rng, k_seeds[si]);
        ref_seed(&ref, k_seeds[si]);
        for (int i = 0; i < 8; ++i) {
            const uint32_t v = pft_rng_u32(&rng);
            TEST_ASSERT_EQUAL_HEX32(k_expected[si][i], v);
            TEST_ASSERT_EQUAL_HEX32(k_expected[si][i], ref_next(&ref));
        }
        /* and a longer stretch against the reference */
        for (int i = 0; i < 10000; ++i) {
            TEST_ASSERT_EQUAL_HEX32(ref_next(&ref), pft_rng_u32(&rng));
        }
    }
    /* raw state stepping: published xoshiro128** vector */
    {
        pft_rng_t rng;
        pft_rng_seed(&rng, 0);
        rng.s[0] = 1u;
        rng.s[1] = 2u;
        rng.s[2] = 3u;
        rng.s[3] = 4u;
        TEST_ASSERT_EQUAL_HEX32(11520u, pft_rng_u32(&rng));
        TEST_ASSERT_EQUAL_HEX32(0u, pft_rng_u32(&rng));
        TEST_ASSERT_EQUAL_HEX32(5927040u, pft_rng_u32(&rng));
    }
}

static void test_seed_resets_and_differs(void)
{
    pft_rng_t a;
    pft_rng_t b;
    pft_rng_seed(&a, 7);
    (void)pft_rng_gauss(&a); /* leaves a spare cached */
    pft_rng_seed(&a, 7);
    pft_rng_seed(&b, 7);
    TEST_ASSERT_EQUAL_UINT8(0u, a.has_spare);
    for (int i = 0; i < 16; ++i) {
        TEST_ASSERT_EQUAL_HEX32(pft_rng_u32(&b), pft_rng_u32(&a));
    }
    pft_rng_seed(&a, 7);
    pft_rng_seed(&b, 8);
    int same = 0;
    for (int i = 0; i < 16; ++i) {
        same += pft_rng_u32(&a) == pft_rng_u32(&b);
    }
    TEST_ASSERT_LESS_THAN_INT(2, same);
}

/* Gaussian draws consume exactly two u32 per pair: the spare is cached, not redrawn. */
static void test_gauss_consumes_two_words_per_pair(void)
{
    pft_rng_t a;
    pft_rng_t b;
    pft_rng_seed(&a, 99);
    pft_rng_seed(&b, 99);
    (void)pft_rng_gauss(&a);
    TEST_ASSERT_EQUAL_UINT8(1u, a.has_spare);
    (void)pft_rng_gauss(&a);
    TEST_ASSERT_EQUAL_UINT8(0u, a.has_spare);
    (void)pft_rng_u32(&b);
    (void)pft_rng_u32(&b);
    TEST_ASSERT_EQUAL_HEX32(pft_rng_u32(&b), pft_rng_u32(&a));
}

/* ---------------------------------- uniform reals ----------------------------------------- */
#define N_UNI 100000

/* Chi-square quantiles used below (upper 0.999 and lower 0.001). */
#define CHI2_15_HI 37.70
#define CHI2_15_LO 3.48
#define CHI2_9_HI 27.88
#define CHI2_9_LO 1.15
#define CHI2_13_HI 34.53
#define CHI2_13_LO 2.62

static void test_uniform_moments_and_chi2(void)
{
    pft_rng_t rng;
    double sum = 0.0, sum2 = 0.0;
    long bins[16] = {0};
    pft_rng_seed(&rng, 12345);
    for (int i = 0; i < N_UNI; ++i) {
        const double u = pft_test_to_double(pft_rng_uniform(&rng));
        TEST_ASSERT_TRUE(u >= 0.0 && u < 1.0);
        sum += u;
        sum2 += u * u;
        bins[(int)(u * 16.0)]++;
    }
    const double mean = sum / N_UNI;
    const double var = sum2 / N_UNI - mean * mean;
    /* The real is the truncated top 16 (q16) or 24 (float) bits: mean is 0.5 - lsb/2. */
#ifdef PFT_NUMERIC_Q16
    const double lsb = 1.0 / 65536.0;
#else
    const double lsb = 1.0 / 16777216.0;
#endif
    const double se_mean = sqrt(1.0 / 12.0 / N_UNI);
    const double se_var = sqrt((1.0 / 80.0 - 1.0 / 144.0) / N_UNI);
    double chi2 = 0.0;
    const double e = N_UNI / 16.0;
    for (int b = 0; b < 16; ++b) {
        chi2 += (bins[b] - e) * (bins[b] - e) / e;
    }
    note_begin("uniform");
    note("mean", mean);
    note("mean_dev_SE", (mean - (0.5 - lsb / 2)) / se_mean);
    note("var", var);
    note("var_dev_SE", (var - 1.0 / 12.0) / se_var);
    note("chi2_15", chi2);
    note_end();
    TEST_ASSERT_DOUBLE_WITHIN(4.0 * se_mean, 0.5 - lsb / 2, mean);
    TEST_ASSERT_DOUBLE_WITHIN(4.0 * se_var, 1.0 / 12.0, var);
    TEST_ASSERT_TRUE(chi2 < CHI2_15_HI);
    TEST_ASSERT_TRUE(chi2 > CHI2_15_LO);
}

static void test_uniform_range_bounds(void)
{
    pft_rng_t rng;
    pft_rng_seed(&rng, 5);
    const pft_real_t lo = PFT_C(-2.5), hi = PFT_C(3.0);
    double sum = 0.0;
    for (int i = 0; i < 20000; ++i) {
        const pft_real_t v = pft_rng_uniform_range(&rng, lo, hi);
        TEST_ASSERT_TRUE(v >= lo && v < hi);
        sum += pft_test_to_double(v);
    }
    /* mean 0.25, SE = 5.5 / sqrt(12 * 20000) = 0.0112 */
    TEST_ASSERT_DOUBLE_WITHIN(4.0 * 0.0112, 0.25, sum / 20000.0);
    /* extreme and degenerate ranges stay inside [lo, hi) */
    for (int i = 0; i < 2000; ++i) {
        pft_real_t v = pft_rng_uniform_range(&rng, PFT_REAL_MIN, PFT_REAL_MAX);
        TEST_ASSERT_TRUE(v >= PFT_REAL_MIN && v < PFT_REAL_MAX);
        v = pft_rng_uniform_range(&rng, PFT_C(1.0), pft_add(PFT_C(1.0), PFT_REAL_EPS));
        TEST_ASSERT_TRUE(v == PFT_C(1.0));
    }
    TEST_ASSERT_TRUE(pft_rng_uniform_range(&rng, PFT_C(2.0), PFT_C(2.0)) == PFT_C(2.0));
    TEST_ASSERT_TRUE(pft_rng_uniform_range(&rng, PFT_C(2.0), PFT_C(1.0)) == PFT_C(2.0));
}

/* ---------------------------------- bounded integers -------------------------------------- */
static void test_below_bounds(void)
{
    static const uint32_t ns[] = {1u, 2u, 3u, 7u, 10u, 1000u, 65537u, 0x80000001u, 0xFFFFFFFFu};
    pft_rng_t rng;
    pft_rng_seed(&rng, 77);
    for (unsigned k = 0; k < sizeof ns / sizeof ns[0]; ++k) {
        uint32_t maxv = 0;
        for (int i = 0; i < 2000; ++i) {
            const uint32_t v = pft_rng_below(&rng, ns[k]);
            TEST_ASSERT_TRUE(v < ns[k]);
            maxv = v > maxv ? v : maxv;
        }
        /* the top of the range is reached (not stuck low): max of 2000 draws >= 99 % of n */
        if (ns[k] > 1u) {
            TEST_ASSERT_TRUE((double)maxv >= 0.99 * (double)(ns[k] - 1u));
        }
    }
}

static void test_below10_chi2(void)
{
    pft_rng_t rng;
    long bins[10] = {0};
    pft_rng_seed(&rng, 2024);
    for (int i = 0; i < N_UNI; ++i) {
        bins[pft_rng_below(&rng, 10u)]++;
    }
    double chi2 = 0.0;
    const double e = N_UNI / 10.0;
    for (int b = 0; b < 10; ++b) {
        chi2 += (bins[b] - e) * (bins[b] - e) / e;
    }
    note_begin("below(10)");
    note("chi2_9", chi2);
    note_end();
    TEST_ASSERT_TRUE(chi2 < CHI2_9_HI);
    TEST_ASSERT_TRUE(chi2 > CHI2_9_LO);
}

/* n = 3 * 2^30: x mod n would put half the mass below 2^30 (instead of 1/3), and the
 * multiply-shift without rejection would give residue 0 mod 3 half the mass (instead of 1/3).
 * Both are 1/3 +- 4 SE (SE = sqrt(2/9/N) = 0.0033 for N = 20000). */
static void test_below_no_bias_large_n(void)
{
    pft_rng_t rng;
    const uint32_t n = 0xC0000000u;
    const int N = 20000;
    int low = 0, res0 = 0;
    pft_rng_seed(&rng, 31337);
    for (int i = 0; i < N; ++i) {
        const uint32_t v = pft_rng_below(&rng, n);
        TEST_ASSERT_TRUE(v < n);
        low += v < 0x40000000u;
        res0 += (v % 3u) == 0u;
    }
    const double se = sqrt(2.0 / 9.0 / N);
    note_begin("below(3*2^30)");
    note("P_below_2^30", (double)low / N);
    note("P_0_mod_3", (double)res0 / N);
    note("SE", se);
    note_end();
    TEST_ASSERT_DOUBLE_WITHIN(4.0 * se, 1.0 / 3.0, (double)low / N);
    TEST_ASSERT_DOUBLE_WITHIN(4.0 * se, 1.0 / 3.0, (double)res0 / N);
}

/* ---------------------------------- Gaussian ---------------------------------------------- */
static double phi(double x)
{
    return 0.5 * erfc(-x / sqrt(2.0));
}

static void test_gauss_moments_and_shape(void)
{
    /* 14 bins: (-inf,-3], (-3,-2.5], ..., (2.5,3], (3,inf) */
    static const double edges[13] = {-3.0, -2.5, -2.0, -1.5, -1.0, -0.5, 0.0,
                                     0.5,  1.0,  1.5,  2.0,  2.5,  3.0};
    long bins[14] = {0};
    pft_rng_t rng;
    double sum = 0.0, sum2 = 0.0, sum4 = 0.0, maxabs = 0.0;
    pft_rng_seed(&rng, 4242);
    for (int i = 0; i < N_UNI; ++i) {
        const double g = pft_test_to_double(pft_rng_gauss(&rng));
        int b = 0;
        sum += g;
        sum2 += g * g;
        sum4 += g * g * g * g;
        maxabs = fabs(g) > maxabs ? fabs(g) : maxabs;
        while (b < 13 && g > edges[b]) {
            ++b;
        }
        bins[b]++;
    }
    const double mean = sum / N_UNI;
    const double var = sum2 / N_UNI - mean * mean;
    const double kurt = sum4 / N_UNI / (var * var);
    double chi2 = 0.0;
    for (int b = 0; b < 14; ++b) {
        const double plo = b == 0 ? 0.0 : phi(edges[b - 1]);
        const double phi_ = b == 13 ? 1.0 : phi(edges[b]);
        const double e = N_UNI * (phi_ - plo);
        chi2 += (bins[b] - e) * (bins[b] - e) / e;
    }
    const double se_mean = sqrt(1.0 / N_UNI);
    const double se_var = sqrt(2.0 / N_UNI);
    const double se_kurt = sqrt(24.0 / N_UNI);
#ifdef PFT_NUMERIC_Q16
    const double gmax = 4.71; /* sqrt(-2 ln 2^-16) = 4.7096 */
#else
    const double gmax = 5.77; /* sqrt(-2 ln 2^-24) = 5.7686 */
#endif
    note_begin("gauss");
    note("mean", mean);
    note("mean_SE", mean / se_mean);
    note("var", var);
    note("var_dev_SE", (var - 1.0) / se_var);
    note("kurtosis", kurt);
    note("kurt_dev_SE", (kurt - 3.0) / se_kurt);
    note("chi2_13", chi2);
    note("max_abs", maxabs);
    note_end();
    TEST_ASSERT_DOUBLE_WITHIN(4.0 * se_mean, 0.0, mean);
    TEST_ASSERT_DOUBLE_WITHIN(4.0 * se_var, 1.0, var);
    TEST_ASSERT_DOUBLE_WITHIN(4.0 * se_kurt, 3.0, kurt);
    TEST_ASSERT_TRUE(chi2 < CHI2_13_HI);
    TEST_ASSERT_TRUE(chi2 > CHI2_13_LO);
    /* documented truncation (a few LSB of transcendental error allowed) */
    TEST_ASSERT_TRUE(maxabs <= gmax + 1e-3);
}

/* The ziggurat (pft_rng_gauss_zig): 200 000 draws, moments, a chi-square over 28 bins of 0.25
 * with the tails beyond +-3.25, and the frequencies beyond 3, 3.5 and 4 (the tail beyond the
 * base layer's r = 3.44 comes from its own sampler) within 4 binomial SE. Bounds as above
 * (chi-square df 27: 0.1 % and 99.9 % quantiles). The q16 values are exactly the float ones
 * rounded (test_golden), so both builds see the same statistics up to that rounding. */
#define N_ZIG 200000
static void test_gauss_zig_moments_shape_and_tails(void)
{
    long bins[28] = {0};
    long beyond[3] = {0, 0, 0};
    static const double thr[3] = {3.0, 3.5, 4.0};
    pft_rng_t rng;
    double sum = 0.0, sum2 = 0.0, sum4 = 0.0, maxabs = 0.0;
    pft_rng_seed(&rng, 4343);
    for (int i = 0; i < N_ZIG; ++i) {
        const double g = pft_test_to_double(pft_rng_gauss_zig(&rng));
        const double a = fabs(g);
        int b = (int)floor((g + 3.25) / 0.25) + 1; /* 1..26 inside, 0 and 27 the tails */
        b = b < 0 ? 0 : (b > 27 ? 27 : b);
        bins[b]++;
        sum += g;
        sum2 += g * g;
        sum4 += g * g * g * g;
        maxabs = a > maxabs ? a : maxabs;
        for (int t = 0; t < 3; ++t) {
            beyond[t] += a > thr[t];
        }
    }
    const double mean = sum / N_ZIG;
    const double var = sum2 / N_ZIG - mean * mean;
    const double kurt = sum4 / N_ZIG / (var * var);
    double chi2 = 0.0;
    for (int b = 0; b < 28; ++b) {
        const double lo = b == 0 ? 0.0 : phi(-3.25 + 0.25 * (b - 1));
        const double hi = b == 27 ? 1.0 : phi(-3.25 + 0.25 * b);
        const double e = N_ZIG * (hi - lo);
        chi2 += (bins[b] - e) * (bins[b] - e) / e;
    }
    note_begin("gauss_zig");
    note("mean_SE", mean / sqrt(1.0 / N_ZIG));
    note("var_dev_SE", (var - 1.0) / sqrt(2.0 / N_ZIG));
    note("kurt_dev_SE", (kurt - 3.0) / sqrt(24.0 / N_ZIG));
    note("chi2_27", chi2);
    note("max_abs", maxabs);
    for (int t = 0; t < 3; ++t) {
        const double p = 2.0 * phi(-thr[t]);
        note(t == 0 ? "beyond3_SE" : (t == 1 ? "beyond3.5_SE" : "beyond4_SE"),
             (beyond[t] - N_ZIG * p) / sqrt(N_ZIG * p * (1.0 - p)));
    }
    note_end();
    TEST_ASSERT_DOUBLE_WITHIN(4.0 * sqrt(1.0 / N_ZIG), 0.0, mean);
    TEST_ASSERT_DOUBLE_WITHIN(4.0 * sqrt(2.0 / N_ZIG), 1.0, var);
    TEST_ASSERT_DOUBLE_WITHIN(4.0 * sqrt(24.0 / N_ZIG), 3.0, kurt);
    TEST_ASSERT_TRUE(chi2 > 9.80 && chi2 < 55.48);
    for (int t = 0; t < 3; ++t) {
        const double p = 2.0 * phi(-thr[t]);
        TEST_ASSERT_DOUBLE_WITHIN(4.0 * sqrt(N_ZIG * p * (1.0 - p)), N_ZIG * p, (double)beyond[t]);
    }
    TEST_ASSERT_TRUE(maxabs <= 10.2); /* r + 22.9 / r */
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_reference_vectors);
    RUN_TEST(test_stream_matches_frozen_and_reference);
    RUN_TEST(test_seed_resets_and_differs);
    RUN_TEST(test_gauss_consumes_two_words_per_pair);
    RUN_TEST(test_uniform_moments_and_chi2);
    RUN_TEST(test_uniform_range_bounds);
    RUN_TEST(test_below_bounds);
    RUN_TEST(test_below10_chi2);
    RUN_TEST(test_below_no_bias_large_n);
    RUN_TEST(test_gauss_moments_and_shape);
    RUN_TEST(test_gauss_zig_moments_shape_and_tails);
    return UNITY_END();
}
