/*
 * Particle weights (pft_real.h, weights section): pft_wexp, pft_wacc_log, pft_lognormalize,
 * pft_ess, pft_ess_ratio, against double references, with the bounds of docs/fixed_point.md.
 *
 * Weight errors are in LSB of the weight: q16 2^-30 (Q2.30); float the ulp of the reference.
 * Real errors are in LSB of pft_real_t (q16 2^-16; float the ulp of the reference).
 * Log-weights in the grids are multiples of 2^-10, exact in both builds, so differences
 * lw - max are exact and the float bounds measure the library, not input rounding.
 */
#include <math.h>
#include <string.h>

#include "pft_test_support.h"

#ifndef PFT_TEST_DENSE
#define PFT_TEST_DENSE 1
#endif

#ifdef PFT_NUMERIC_Q16
#define B_WEXP 0.73       /* Q2.30 LSB */
#define B_WACCLOG 0.51
#define B_NORM_W 1.75     /* each normalised weight, Q2.30 LSB: 1 (carry) + wexp's 0.73 */
#define B_LOGSUM 0.51     /* returned log-sum, Q16.16 LSB (n <= 4096) */
#define B_ESS 0.5         /* against the double ESS of the very same weights */
#define B_SUM_LSB 0.0     /* normalised weights sum to exactly PFT_W_ONE */
#define B_ESS_UNIFORM 0.5 /* uniform weights: ESS = n, ESS / n = 1 */
#else
#define B_WEXP 0.75
#define B_WACCLOG 0.75
#define B_NORM_W 2.5
#define B_LOGSUM 0.8 /* ulps of max(|max lw|, |log-sum|, |log sum exp(lw - max)|) */
#define B_ESS 1.2
#define B_SUM_LSB 0.75 /* in ulps of 1.0 */
#define B_ESS_UNIFORM 4.0
#endif

void setUp(void) {}
void tearDown(void) {}

static uint32_t lcg_state;
static uint32_t lcg(void)
{
    lcg_state = lcg_state * 1664525u + 1013904223u;
    return lcg_state;
}

/* weight <-> double, and one LSB of a weight of value v */
static double w_to_double(pft_weight_t w)
{
#ifdef PFT_NUMERIC_Q16
    return (double)w / 1073741824.0;
#else
    return (double)w;
#endif
}
static double w_lsb(double v)
{
#ifdef PFT_NUMERIC_Q16
    (void)v;
    return 1.0 / 1073741824.0;
#else
    return pft_test_lsb(v);
#endif
}

/* a multiple of 2^-10 as a real (exact in both builds) */
static pft_real_t lw_of(int32_t k1024)
{
    return pft_test_from_double((double)k1024 / 1024.0);
}

static void report(const char *name, double max, double bound, long n)
{
    UnityPrint("  measured ");
    UnityPrint(name);
    UnityPrint(": max error ");
    UnityPrintFloat(max);
    UnityPrint(" LSB (bound ");
    UnityPrintFloat(bound);
    UnityPrint(") over ");
    UnityPrintNumber(n);
    UnityPrint(" points");
    UNITY_PRINT_EOL();
    TEST_ASSERT_TRUE_MESSAGE(n > 0, name);
    TEST_ASSERT_TRUE_MESSAGE(max <= bound + 1e-9, name);
}

#define NMAX 4096
static pft_real_t g_lw[NMAX];
static pft_weight_t g_w[NMAX];
static pft_weight_t g_w2[NMAX];
#define NBIG 65536
static pft_weight_t g_big[NBIG];

static void test_wexp_error(void)
{
    double max = 0.0;
    long n = 0;
    /* every 37th Q16.16 input over [-23, 0] (41k points), plus the top in full detail */
    for (int32_t x = -23 * 65536; x <= 0; x += (37 + PFT_TEST_DENSE - 1) / PFT_TEST_DENSE) {
        pft_real_t r = pft_test_from_double((double)x / 65536.0);
        double xd = pft_test_to_double(r), ref = exp(xd);
        double e = fabs(w_to_double(pft_wexp(r)) - ref) / w_lsb(ref);
        max = e > max ? e : max;
        ++n;
    }
    for (int32_t x = -2048; x <= 0; ++x) {
        pft_real_t r = pft_test_from_double((double)x / 65536.0);
        double xd = pft_test_to_double(r), ref = exp(xd);
        double e = fabs(w_to_double(pft_wexp(r)) - ref) / w_lsb(ref);
        max = e > max ? e : max;
        ++n;
    }
    report("pft_wexp", max, B_WEXP, n);
    TEST_ASSERT_TRUE(pft_wexp(pft_test_from_double(0.0)) == PFT_W_ONE);
    TEST_ASSERT_TRUE(pft_wexp(pft_test_from_double(3.0)) == PFT_W_ONE);
    TEST_ASSERT_TRUE(pft_wexp(PFT_REAL_MAX) == PFT_W_ONE);
    TEST_ASSERT_TRUE(pft_wexp(PFT_REAL_MIN) == 0);
#ifdef PFT_NUMERIC_Q16
    TEST_ASSERT_EQUAL_UINT32(0u, pft_wexp(INT32_MIN));
    TEST_ASSERT_EQUAL_UINT32(1u, pft_wexp(pft_test_from_double(-20.5))); /* 1.33 LSB */
    TEST_ASSERT_EQUAL_UINT32(0u, pft_wexp(pft_test_from_double(-21.6))); /* 0.44 LSB */
    TEST_ASSERT_EQUAL_UINT32(PFT_W_ONE - 16384u, pft_wexp(-1));         /* 1 - 2^-16 */
#endif
}

static void test_wacc_log(void)
{
    double max = 0.0;
    long n = 0;
    lcg_state = 5u;
    for (int i = 0; i < 3000 * PFT_TEST_DENSE; ++i) {
#ifdef PFT_NUMERIC_Q16
        /* any uint64: random mantissa, random bit length 1..64 */
        uint64_t acc = ((uint64_t)lcg() << 32) | lcg();
        acc >>= lcg() % 64u;
        if (acc == 0) {
            continue;
        }
        double ref = log((double)acc / 1073741824.0);
#else
        float acc = (float)exp((double)(lcg() % 20000u) / 400.0 - 25.0);
        double ref = log((double)acc);
#endif
        pft_real_t got = pft_wacc_log(acc);
        double e = fabs(pft_test_to_double(got) - ref) / pft_test_lsb(ref);
        max = e > max ? e : max;
        ++n;
    }
    report("pft_wacc_log", max, B_WACCLOG, n);
    TEST_ASSERT_TRUE(pft_wacc_log(0) == PFT_REAL_MIN);
    TEST_ASSERT_TRUE(pft_wacc_log(PFT_W_ONE) == 0);
}

/* The weight helpers agree with the real ones (pft_exp, pft_log) they parallel. */
static void test_consistent_with_real_helpers(void)
{
    for (int32_t k = -10 * 1024; k <= 0; k += 7) {
        pft_real_t x = lw_of(k);
        double d = pft_test_to_double(pft_weight_to_real(pft_wexp(x))) -
                   pft_test_to_double(pft_exp(x));
        TEST_ASSERT_TRUE(fabs(d) <= 2.0 * pft_test_lsb(1.0)); /* q16: truncation + pft_exp */
    }
    for (int32_t k = 1; k <= 3000; k += 3) {
#ifdef PFT_NUMERIC_Q16
        pft_wacc_t acc = (pft_wacc_t)k << 30;
#else
        pft_wacc_t acc = (float)k;
#endif
        double d = pft_test_to_double(pft_wacc_log(acc)) -
                   pft_test_to_double(pft_log(pft_from_int(k)));
        TEST_ASSERT_TRUE(fabs(d) <= pft_test_lsb(8.0));
    }
}

static void test_weight_to_real_and_max(void)
{
    pft_real_t v[5];
    TEST_ASSERT_TRUE(pft_weight_to_real(PFT_W_ONE) == PFT_REAL_ONE);
    TEST_ASSERT_TRUE(pft_weight_to_real(0) == 0);
#ifdef PFT_NUMERIC_Q16
    TEST_ASSERT_EQUAL_INT32(32768, pft_weight_to_real(PFT_W_ONE / 2u));
    TEST_ASSERT_EQUAL_INT32(0, pft_weight_to_real(16383u)); /* truncates */
    TEST_ASSERT_EQUAL_INT32(1, pft_weight_to_real(16384u));
    TEST_ASSERT_EQUAL_INT32(262143, pft_weight_to_real(0xFFFFFFFFu)); /* Q2.30 max ~ 4 */
#else
    TEST_ASSERT_TRUE(pft_weight_to_real(0.25f) == 0.25f);
#endif
    v[0] = lw_of(-5000);
    v[1] = lw_of(-3);
    v[2] = PFT_REAL_MIN;
    v[3] = lw_of(-4);
    v[4] = lw_of(-70000);
    TEST_ASSERT_TRUE(pft_real_max_n(v, 5) == lw_of(-3));
    TEST_ASSERT_TRUE(pft_real_max_n(v, 1) == lw_of(-5000));
    TEST_ASSERT_TRUE(pft_real_max_n(&v[2], 1) == PFT_REAL_MIN);
}

/* Fills g_lw[0..n) with multiples of 2^-10 in [base - spread, base]. */
static void fill_lw(size_t n, int32_t base1024, uint32_t spread1024)
{
    for (size_t i = 0; i < n; ++i) {
        g_lw[i] = lw_of(base1024 - (int32_t)(lcg() % (spread1024 + 1u)));
    }
}

/* Runs pft_lognormalize on g_lw and checks sum, each weight and the log-sum against double. */
static void check_lognormalize(size_t n, double *max_w, double *max_ls, double *max_sum)
{
    double m = -1e300, s = 0.0, sumw = 0.0, ref_ls, e;
    pft_real_t ls;
    for (size_t i = 0; i < n; ++i) {
        double v = pft_test_to_double(g_lw[i]);
        m = v > m ? v : m;
    }
    for (size_t i = 0; i < n; ++i) {
        s += exp(pft_test_to_double(g_lw[i]) - m);
    }
    ref_ls = m + log(s);
    ls = pft_lognormalize(g_lw, g_w, n);
    for (size_t i = 0; i < n; ++i) {
        double ref = exp(pft_test_to_double(g_lw[i]) - m) / s;
        e = fabs(w_to_double(g_w[i]) - ref) / w_lsb(ref);
        *max_w = e > *max_w ? e : *max_w;
        sumw += w_to_double(g_w[i]);
    }
    e = fabs(sumw - 1.0) / w_lsb(1.0);
    *max_sum = e > *max_sum ? e : *max_sum;
    /* float: m + log(s) cancels when m < 0 < log s; measure in ulps of the largest term */
    e = fabs(m) > fabs(ref_ls) ? fabs(m) : fabs(ref_ls);
    e = log(s) > e ? log(s) : e;
    e = fabs(pft_test_to_double(ls) - ref_ls) / pft_test_lsb(e);
    *max_ls = e > *max_ls ? e : *max_ls;
#ifdef PFT_NUMERIC_Q16
    {
        uint64_t acc = 0;
        for (size_t i = 0; i < n; ++i) {
            acc += g_w[i];
        }
        TEST_ASSERT_TRUE(acc == PFT_W_ONE); /* exact, not just within n LSB */
    }
#endif
}

static void test_lognormalize_reference(void)
{
    static const size_t ns[] = {1, 2, 3, 7, 100, 1000, 4096};
    double max_w = 0.0, max_ls = 0.0, max_sum = 0.0;
    long pts = 0;
    lcg_state = 17u;
    for (size_t k = 0; k < sizeof ns / sizeof ns[0]; ++k) {
        for (int rep = 0; rep < 3; ++rep) {
            /* spreads of 2, 12 and 30 nats below a max near -40, 0 or +25 */
            static const int32_t base[3] = {-40 * 1024, 0, 25 * 1024};
            static const uint32_t spread[3] = {2 * 1024, 12 * 1024, 30 * 1024};
            fill_lw(ns[k], base[rep], spread[rep]);
            check_lognormalize(ns[k], &max_w, &max_ls, &max_sum);
            pts += (long)ns[k];
        }
    }
    report("pft_lognormalize weights", max_w, B_NORM_W, pts);
    report("pft_lognormalize log-sum", max_ls, B_LOGSUM, pts);
    report("pft_lognormalize |sum - 1|", max_sum, B_SUM_LSB, pts);
}

static void test_lognormalize_shift_invariance(void)
{
    const size_t n = 500;
    pft_real_t ls0, ls1;
    lcg_state = 23u;
    fill_lw(n, -3 * 1024, 15 * 1024);
    ls0 = pft_lognormalize(g_lw, g_w, n);
    for (size_t i = 0; i < n; ++i) {
        g_lw[i] = pft_add(g_lw[i], lw_of(7 * 1024 + 512)); /* + 7.5, exact */
    }
    ls1 = pft_lognormalize(g_lw, g_w2, n);
    /* differences lw - max are unchanged and exact: identical weights in both builds */
    TEST_ASSERT_EQUAL_MEMORY(g_w, g_w2, n * sizeof g_w[0]);
    TEST_ASSERT_TRUE(fabs(pft_test_to_double(ls1) - pft_test_to_double(ls0) - 7.5) <=
                     pft_test_lsb(pft_test_to_double(ls1)));
#ifdef PFT_NUMERIC_Q16
    TEST_ASSERT_EQUAL_INT32(ls0 + lw_of(7 * 1024 + 512), ls1); /* exactly +7.5 */
#endif
}

static void test_lognormalize_edges(void)
{
    pft_real_t ls;
    /* n = 1: the single weight is one, the log-sum is the log-weight itself */
    g_lw[0] = lw_of(-1234567);
    ls = pft_lognormalize(g_lw, g_w, 1);
    TEST_ASSERT_TRUE(g_w[0] == PFT_W_ONE);
    TEST_ASSERT_TRUE(ls == g_lw[0]);
    /* n = 0 writes nothing */
    g_w[0] = 0;
    TEST_ASSERT_TRUE(pft_lognormalize(g_lw, g_w, 0) == PFT_REAL_MIN);
    TEST_ASSERT_TRUE(g_w[0] == 0);
    /* extreme values: saturated log-weights and a huge spread */
    g_lw[0] = PFT_REAL_MAX;
    g_lw[1] = PFT_REAL_MIN;
    g_lw[2] = PFT_REAL_MAX;
    g_lw[3] = lw_of(0);
    ls = pft_lognormalize(g_lw, g_w, 4);
    TEST_ASSERT_TRUE(g_w[1] == 0);
    TEST_ASSERT_TRUE(g_w[3] == 0);
    TEST_ASSERT_TRUE(g_w[0] == g_w[2]);
    TEST_ASSERT_TRUE(fabs(w_to_double(g_w[0]) - 0.5) <= w_lsb(0.5));
#ifdef PFT_NUMERIC_Q16
    TEST_ASSERT_EQUAL_INT32(PFT_REAL_MAX, ls); /* 32768 + ln 2 saturates */
    TEST_ASSERT_EQUAL_UINT32(PFT_W_ONE, g_w[0] + g_w[2]);
#else
    TEST_ASSERT_TRUE(ls >= PFT_REAL_MAX);
#endif
}

static double ess_ref(const pft_weight_t *w, size_t n)
{
    double s2 = 0.0;
    for (size_t i = 0; i < n; ++i) {
        s2 += w_to_double(w[i]) * w_to_double(w[i]);
    }
    return 1.0 / s2;
}

static void test_ess(void)
{
    static const size_t ns[] = {1, 2, 5, 100, 1000, 4096};
    double max = 0.0, max_u = 0.0, e, ref;
    long pts = 0;
    lcg_state = 29u;
    for (size_t k = 0; k < sizeof ns / sizeof ns[0]; ++k) {
        size_t n = ns[k];
        /* uniform: ESS = n */
        for (size_t i = 0; i < n; ++i) {
            g_lw[i] = lw_of(-2000);
        }
        (void)pft_lognormalize(g_lw, g_w, n);
        e = fabs(pft_test_to_double(pft_ess(g_w, n)) - (double)n) / pft_test_lsb((double)n);
        max_u = e > max_u ? e : max_u;
        e = fabs(pft_test_to_double(pft_ess_ratio(g_w, n)) - 1.0) / pft_test_lsb(1.0);
        max_u = e > max_u ? e : max_u;
        /* one-hot: ESS = 1 exactly */
        for (size_t i = 0; i < n; ++i) {
            g_lw[i] = PFT_REAL_MIN;
        }
        g_lw[n / 2] = lw_of(3);
        (void)pft_lognormalize(g_lw, g_w, n);
        TEST_ASSERT_TRUE(pft_ess(g_w, n) == PFT_REAL_ONE);
        /* random: against the double ESS of the same weights */
        for (int rep = 0; rep < 4; ++rep) {
            fill_lw(n, 0, (uint32_t)(1 + rep * 4) * 1024u);
            (void)pft_lognormalize(g_lw, g_w, n);
            ref = ess_ref(g_w, n);
            e = fabs(pft_test_to_double(pft_ess(g_w, n)) - ref) / pft_test_lsb(ref);
            max = e > max ? e : max;
            ref /= (double)n;
            e = fabs(pft_test_to_double(pft_ess_ratio(g_w, n)) - ref) / pft_test_lsb(ref);
            max = e > max ? e : max;
            TEST_ASSERT_TRUE(pft_ess(g_w, n) <= pft_from_int((int32_t)n));
            pts += 2;
        }
    }
    report("pft_ess / pft_ess_ratio", max, B_ESS, pts);
    report("pft_ess / pft_ess_ratio uniform = n, 1", max_u, B_ESS_UNIFORM, 12);
    TEST_ASSERT_TRUE(pft_ess(g_w, 0) == 0);
    TEST_ASSERT_TRUE(pft_ess_ratio(g_w, 0) == 0);
    memset(g_w, 0, sizeof g_w);
    TEST_ASSERT_TRUE(pft_ess(g_w, 10) == 0); /* all weights zero */
}

static void test_ess_large_n(void)
{
    /* 65536 uniform weights: the ratio stays exact where q16 ESS itself saturates */
    for (size_t i = 0; i < NBIG; ++i) {
#ifdef PFT_NUMERIC_Q16
        g_big[i] = PFT_W_ONE / (pft_weight_t)NBIG;
#else
        g_big[i] = 1.0f / (float)NBIG;
#endif
    }
    TEST_ASSERT_TRUE(pft_ess_ratio(g_big, NBIG) == PFT_REAL_ONE);
#ifdef PFT_NUMERIC_Q16
    TEST_ASSERT_EQUAL_INT32(PFT_REAL_MAX, pft_ess(g_big, NBIG));
    /* half the particles at twice the weight: ESS = n / 1.25 ... exact for 2/3, 1/3 split */
    for (size_t i = 0; i < NBIG; ++i) {
        g_big[i] = i < NBIG / 2 ? (PFT_W_ONE / NBIG) * 3u / 2u : (PFT_W_ONE / NBIG) / 2u;
    }
    TEST_ASSERT_EQUAL_INT32(52429, pft_ess_ratio(g_big, NBIG)); /* 1/1.25 = 0.8 */
#else
    TEST_ASSERT_TRUE(fabsf(pft_ess(g_big, NBIG) - 65536.0f) <= 2.0f * 0.0078125f);
#endif
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_wexp_error);
    RUN_TEST(test_wacc_log);
    RUN_TEST(test_consistent_with_real_helpers);
    RUN_TEST(test_weight_to_real_and_max);
    RUN_TEST(test_lognormalize_reference);
    RUN_TEST(test_lognormalize_shift_invariance);
    RUN_TEST(test_lognormalize_edges);
    RUN_TEST(test_ess);
    RUN_TEST(test_ess_large_n);
    return UNITY_END();
}
