/*
 * The number layer (pft_real.h): saturation, rounding, and the measured error of every
 * transcendental helper against a double reference, asserted against the bounds documented in
 * docs/fixed_point.md.
 *
 * Errors are in LSB of the result: q16 one LSB is 2^-16; float one LSB is the ulp of the
 * reference value (so float bounds are relative). Each grid test prints its measured maximum.
 * Build with -DPFT_TEST_DENSE=64 (e.g. CMAKE_C_FLAGS) for a 64x denser host sweep.
 */
#include <math.h>
#include <string.h>

#include "pft_test_support.h"

#ifndef PFT_TEST_DENSE
#define PFT_TEST_DENSE 1
#endif

/* Bounds in LSB (see docs/fixed_point.md). q16: measured maximum rounded up a little; a
 * function twice as bad fails. float: the libm's own error (glibc, newlib) plus margin. */
#ifdef PFT_NUMERIC_Q16
#define B_DIV 0.5
#define B_RECIP 0.5
#define B_SQRT 0.5
#define B_EXP 1.1
#define B_LOG 0.51
#define B_ATAN2 0.51
#define B_SINCOS 0.51
#define B_F32 0.5
#else
#define B_DIV 0.5
#define B_RECIP 0.5
#define B_SQRT 0.5
#define B_EXP 0.75
#define B_LOG 1.0
#define B_ATAN2 1.5
#define B_SINCOS 0.75
#define B_F32 0.0
#endif

void setUp(void) {}
void tearDown(void) {}

/* ---- helpers ------------------------------------------------------------------------------ */

static uint32_t lcg_state;
static uint32_t lcg(void)
{
    lcg_state = lcg_state * 1664525u + 1013904223u;
    return lcg_state;
}
/* uniform double in [lo, hi) */
static double urand(double lo, double hi)
{
    uint32_t u = lcg();
    return lo + (hi - lo) * ((double)(u >> 8) / 16777216.0);
}
/* log-uniform in [lo, hi), lo > 0 */
static double lrand(double lo, double hi)
{
    return exp(urand(log(lo), log(hi)));
}

typedef struct {
    double max; /* largest error seen, in LSB */
    double at;  /* input (first argument) where it was seen */
    long n;     /* points measured */
} err_t;

static void err_init(err_t *e)
{
    e->max = 0.0;
    e->at = 0.0;
    e->n = 0;
}

/* Accumulate |got - ref| in LSB of the result. */
static void err_add(err_t *e, pft_real_t got, double ref, double x)
{
    double d = fabs(pft_test_to_double(got) - ref) / pft_test_lsb(ref);
    if (d > e->max) {
        e->max = d;
        e->at = x;
    }
    ++e->n;
}

static void err_report(const char *name, const err_t *e, double bound)
{
    UnityPrint("  measured ");
    UnityPrint(name);
    UnityPrint(": max error ");
    UnityPrintFloat(e->max);
    UnityPrint(" LSB (bound ");
    UnityPrintFloat(bound);
    UnityPrint(") at x = ");
    UnityPrintFloat(e->at);
    UnityPrint(" over ");
    UnityPrintNumber(e->n);
    UnityPrint(" points");
    UNITY_PRINT_EOL();
    TEST_ASSERT_TRUE_MESSAGE(e->n > 0, name);
    TEST_ASSERT_TRUE_MESSAGE(e->max <= bound + 1e-9, name);
}

/* an input as the library sees it, and its exact value */
static pft_real_t in_real(double x, double *exact)
{
    pft_real_t r = pft_test_from_double(x);
    *exact = pft_test_to_double(r);
    return r;
}

#define R(x) pft_test_from_double(x)
#define TEST_ASSERT_REAL_EQ(expected, actual) \
    TEST_ASSERT_TRUE(pft_test_to_double(actual) == pft_test_to_double(expected))

/* ---- saturation and rounding -------------------------------------------------------------- */

static void test_add_sub_saturate(void)
{
    TEST_ASSERT_REAL_EQ(R(3.75), pft_add(R(1.5), R(2.25)));
    TEST_ASSERT_REAL_EQ(R(-0.75), pft_sub(R(1.5), R(2.25)));
#ifdef PFT_NUMERIC_Q16
    TEST_ASSERT_EQUAL_INT32(PFT_REAL_MAX, pft_add(PFT_REAL_MAX, 1));
    TEST_ASSERT_EQUAL_INT32(PFT_REAL_MAX, pft_add(PFT_REAL_MAX, PFT_REAL_MAX));
    TEST_ASSERT_EQUAL_INT32(PFT_REAL_MIN, pft_add(PFT_REAL_MIN, -1));
    TEST_ASSERT_EQUAL_INT32(PFT_REAL_MIN, pft_add(INT32_MIN, INT32_MIN));
    TEST_ASSERT_EQUAL_INT32(PFT_REAL_MIN, pft_add(INT32_MIN, 0)); /* clamps to symmetric range */
    TEST_ASSERT_EQUAL_INT32(PFT_REAL_MAX, pft_sub(PFT_REAL_MAX, PFT_REAL_MIN));
    TEST_ASSERT_EQUAL_INT32(PFT_REAL_MIN, pft_sub(PFT_REAL_MIN, PFT_REAL_MAX));
    TEST_ASSERT_EQUAL_INT32(PFT_REAL_MAX, pft_sub(0, INT32_MIN));
    TEST_ASSERT_EQUAL_INT32(PFT_REAL_MAX - 1, pft_add(PFT_REAL_MAX, -1));
#else
    TEST_ASSERT_TRUE(pft_add(PFT_REAL_MAX, PFT_REAL_MIN) == 0.0f);
#endif
}

static void test_neg_abs(void)
{
    TEST_ASSERT_REAL_EQ(R(-2.5), pft_neg(R(2.5)));
    TEST_ASSERT_REAL_EQ(R(2.5), pft_abs(R(-2.5)));
    TEST_ASSERT_REAL_EQ(PFT_REAL_MAX, pft_abs(PFT_REAL_MIN));
#ifdef PFT_NUMERIC_Q16
    TEST_ASSERT_EQUAL_INT32(PFT_REAL_MAX, pft_neg(INT32_MIN));
    TEST_ASSERT_EQUAL_INT32(PFT_REAL_MAX, pft_abs(INT32_MIN));
    TEST_ASSERT_EQUAL_INT32(PFT_REAL_MIN, pft_neg(PFT_REAL_MAX));
#endif
}

static void test_mul_rounding_and_saturation(void)
{
    TEST_ASSERT_REAL_EQ(R(-3.375), pft_mul(R(1.5), R(-2.25)));
    TEST_ASSERT_REAL_EQ(R(6.25), pft_sq(R(-2.5)));
#ifdef PFT_NUMERIC_Q16
    /* products of raw LSBs with 0.5 (= 32768): exact halves round away from zero */
    TEST_ASSERT_EQUAL_INT32(1, pft_mul(1, 32768));
    TEST_ASSERT_EQUAL_INT32(-1, pft_mul(-1, 32768));
    TEST_ASSERT_EQUAL_INT32(2, pft_mul(3, 32768));
    TEST_ASSERT_EQUAL_INT32(-2, pft_mul(-3, 32768));
    TEST_ASSERT_EQUAL_INT32(0, pft_mul(1, 32767));  /* 0.49998 LSB */
    TEST_ASSERT_EQUAL_INT32(0, pft_mul(-1, 32767));
    TEST_ASSERT_EQUAL_INT32(1, pft_mul(1, 32769));  /* 0.50002 LSB */
    TEST_ASSERT_EQUAL_INT32(-1, pft_mul(-1, 32769));
    TEST_ASSERT_EQUAL_INT32(PFT_REAL_MAX, pft_mul(PFT_REAL_MAX, R(2.0)));
    TEST_ASSERT_EQUAL_INT32(PFT_REAL_MIN, pft_mul(PFT_REAL_MAX, R(-2.0)));
    TEST_ASSERT_EQUAL_INT32(PFT_REAL_MAX, pft_mul(INT32_MIN, INT32_MIN));
    TEST_ASSERT_EQUAL_INT32(PFT_REAL_MIN, pft_mul(INT32_MIN, PFT_REAL_MAX));
    TEST_ASSERT_EQUAL_INT32(PFT_REAL_MAX, pft_mul(R(200.0), R(200.0)));
    TEST_ASSERT_EQUAL_INT32(R(181.0 * 181.0), pft_mul(R(181.0), R(181.0)));
    /* random products against the double product rounded half away from zero */
    lcg_state = 11u;
    for (int i = 0; i < 2000; ++i) {
        int32_t a = (int32_t)lcg() >> (lcg() & 15u), b = (int32_t)lcg() >> (lcg() & 15u);
        double p = (double)a * (double)b / 65536.0;
        double want = p >= 0 ? floor(p + 0.5) : -floor(-p + 0.5);
        if (want > 2147483647.0) {
            want = 2147483647.0;
        } else if (want < -2147483647.0) {
            want = -2147483647.0;
        }
        TEST_ASSERT_EQUAL_INT32((int32_t)want, pft_mul(a, b));
    }
    TEST_ASSERT_EQUAL_INT32(PFT_REAL_MAX, pft_mul_i(R(20000.0), 2));
    TEST_ASSERT_EQUAL_INT32(PFT_REAL_MIN, pft_mul_i(R(20000.0), -2));
    TEST_ASSERT_EQUAL_INT32(PFT_REAL_MAX, pft_mul_i(INT32_MIN, INT32_MIN));
    TEST_ASSERT_EQUAL_INT32(PFT_REAL_MAX, pft_from_int(32768));
    TEST_ASSERT_EQUAL_INT32(PFT_REAL_MIN, pft_from_int(-32768));
    TEST_ASSERT_EQUAL_INT32(R(-32767.0), pft_from_int(-32767));
#endif
}

static void test_div_error(void)
{
    err_t e;
    err_init(&e);
    lcg_state = 21u;
    for (int i = 0; i < 3000 * PFT_TEST_DENSE; ++i) {
        double xa, xb;
        double sa = (lcg() & 1u) ? 1.0 : -1.0, sb = (lcg() & 1u) ? 1.0 : -1.0;
        pft_real_t a = in_real(sa * lrand(1.0 / 65536.0, 32767.0), &xa);
        pft_real_t b = in_real(sb * lrand(1.0 / 65536.0, 32767.0), &xb);
        double q = xa / xb;
        if (fabs(q) >= 32767.0 || xb == 0.0) {
            continue;
        }
        err_add(&e, pft_div(a, b), q, xa);
    }
    err_report("pft_div", &e, B_DIV);
}

static void test_div_special(void)
{
    TEST_ASSERT_REAL_EQ(PFT_REAL_MAX, pft_div(R(1.0), R(0.0)));
    TEST_ASSERT_REAL_EQ(PFT_REAL_MIN, pft_div(R(-1.0), R(0.0)));
    TEST_ASSERT_REAL_EQ(R(0.0), pft_div(R(0.0), R(0.0)));
    TEST_ASSERT_REAL_EQ(R(-2.5), pft_div(R(5.0), R(-2.0)));
    TEST_ASSERT_REAL_EQ(PFT_REAL_MAX, pft_recip(R(0.0)));
    TEST_ASSERT_REAL_EQ(R(0.25), pft_recip(R(4.0)));
    /* pft_div_i: k <= 0 saturates like a division by zero, in both builds */
    TEST_ASSERT_REAL_EQ(R(2.5), pft_div_i(R(7.5), 3));
    TEST_ASSERT_REAL_EQ(R(-2.5), pft_div_i(R(-7.5), 3));
    TEST_ASSERT_REAL_EQ(PFT_REAL_MAX, pft_div_i(R(1.0), 0));
    TEST_ASSERT_REAL_EQ(PFT_REAL_MIN, pft_div_i(R(-1.0), -3));
    TEST_ASSERT_REAL_EQ(R(0.0), pft_div_i(R(0.0), 0));
    /* pft_ratio */
    TEST_ASSERT_REAL_EQ(R(0.75), pft_ratio(3, 4));
    TEST_ASSERT_REAL_EQ(R(-0.75), pft_ratio(3, -4));
    TEST_ASSERT_REAL_EQ(R(0.75), pft_ratio(-3, -4));
    TEST_ASSERT_REAL_EQ(PFT_REAL_MAX, pft_ratio(3, 0));
    TEST_ASSERT_REAL_EQ(PFT_REAL_MIN, pft_ratio(-3, 0));
    TEST_ASSERT_REAL_EQ(R(0.0), pft_ratio(0, 0));
#ifdef PFT_NUMERIC_Q16
    /* ties of the quotient (in LSB) round away from zero */
    TEST_ASSERT_EQUAL_INT32(1, pft_div(1, R(2.0)));   /* 0.5 LSB */
    TEST_ASSERT_EQUAL_INT32(-1, pft_div(-1, R(2.0)));
    TEST_ASSERT_EQUAL_INT32(2, pft_div(3, R(2.0)));   /* 1.5 LSB */
    TEST_ASSERT_EQUAL_INT32(-2, pft_div(3, R(-2.0)));
    TEST_ASSERT_EQUAL_INT32(2, pft_div_i(3, 2));   /* 1.5 LSB */
    TEST_ASSERT_EQUAL_INT32(3, pft_div_i(5, 2));
    TEST_ASSERT_EQUAL_INT32(-3, pft_div_i(-5, 2));
    TEST_ASSERT_EQUAL_INT32(1, pft_div_i(4, 3));   /* 1.33 LSB */
    TEST_ASSERT_EQUAL_INT32(-2, pft_div_i(-5, 3)); /* -1.67 LSB */
    TEST_ASSERT_EQUAL_INT32(1, pft_ratio(1, 131072));  /* 0.5 LSB */
    TEST_ASSERT_EQUAL_INT32(-1, pft_ratio(-1, 131072));
    TEST_ASSERT_EQUAL_INT32(-1, pft_ratio(1, -131072));
    /* quotient overflow and INT32_MIN operands */
    TEST_ASSERT_EQUAL_INT32(PFT_REAL_MAX, pft_div(PFT_REAL_MAX, 1));
    TEST_ASSERT_EQUAL_INT32(PFT_REAL_MIN, pft_div(PFT_REAL_MAX, -1));
    TEST_ASSERT_EQUAL_INT32(PFT_REAL_MAX, pft_div(INT32_MIN, -R(1.0)));
    TEST_ASSERT_EQUAL_INT32(PFT_REAL_MIN, pft_div(INT32_MIN, R(1.0)));
    TEST_ASSERT_EQUAL_INT32(R(1.0), pft_div(INT32_MIN, INT32_MIN));
    TEST_ASSERT_EQUAL_INT32(R(0.5), pft_div(INT32_MIN / 2, INT32_MIN));
    TEST_ASSERT_EQUAL_INT32(PFT_REAL_MIN, pft_div(INT32_MIN, 0));
    TEST_ASSERT_EQUAL_INT32(PFT_REAL_MIN, pft_div_i(INT32_MIN, 1));
    TEST_ASSERT_EQUAL_INT32(-R(16384.0), pft_div_i(INT32_MIN, 2));
    TEST_ASSERT_EQUAL_INT32(PFT_REAL_MAX, pft_recip(1));
    TEST_ASSERT_EQUAL_INT32(PFT_REAL_MIN, pft_recip(-1));
    TEST_ASSERT_EQUAL_INT32(2, pft_recip(PFT_REAL_MAX)); /* 2^16/32768 = 2^-15 -> 2 LSB */
#endif
}

static void test_recip_error(void)
{
    err_t e;
    err_init(&e);
    lcg_state = 31u;
    for (int i = 0; i < 2000 * PFT_TEST_DENSE; ++i) {
        double x, s = (i & 1) ? 1.0 : -1.0;
        pft_real_t a = in_real(s * lrand(1.0 / 16000.0, 32767.0), &x); /* 1/x representable */
        err_add(&e, pft_recip(a), 1.0 / x, x);
    }
    err_report("pft_recip", &e, B_RECIP);
}

static void test_round_floor_negatives(void)
{
    TEST_ASSERT_EQUAL_INT32(-1, pft_floor_int(R(-0.5)));
    TEST_ASSERT_EQUAL_INT32(-2, pft_floor_int(R(-1.25)));
    TEST_ASSERT_EQUAL_INT32(-3, pft_floor_int(R(-3.0)));
    TEST_ASSERT_EQUAL_INT32(2, pft_floor_int(R(2.75)));
    TEST_ASSERT_EQUAL_INT32(0, pft_round_int(R(-0.5)));  /* ties up */
    TEST_ASSERT_EQUAL_INT32(-1, pft_round_int(R(-1.5)));
    TEST_ASSERT_EQUAL_INT32(-2, pft_round_int(R(-1.75)));
    TEST_ASSERT_EQUAL_INT32(-1, pft_round_int(R(-1.25)));
    TEST_ASSERT_EQUAL_INT32(3, pft_round_int(R(2.5)));
    TEST_ASSERT_EQUAL_INT32(2, pft_round_int(R(2.25)));
    TEST_ASSERT_EQUAL_INT32(-32767, pft_round_int(R(-32767.0)));
#ifdef PFT_NUMERIC_Q16
    TEST_ASSERT_EQUAL_INT32(-1, pft_floor_int(-1)); /* one LSB below zero */
    TEST_ASSERT_EQUAL_INT32(0, pft_round_int(-1));
    TEST_ASSERT_EQUAL_INT32(-1, pft_round_int(-32769)); /* -0.5000153 */
    TEST_ASSERT_EQUAL_INT32(0, pft_round_int(-32768));  /* -0.5 exactly */
    TEST_ASSERT_EQUAL_INT32(32768, pft_round_int(PFT_REAL_MAX));
    TEST_ASSERT_EQUAL_INT32(-32768, pft_round_int(PFT_REAL_MIN));
    TEST_ASSERT_EQUAL_INT32(-32768, pft_floor_int(INT32_MIN));
#else
    /* the largest float below 0.5 must round down (floorf(a + 0.5f) would give 1) */
    TEST_ASSERT_EQUAL_INT32(0, pft_round_int(0.49999997f));
    TEST_ASSERT_EQUAL_INT32(-1, pft_round_int(-0.50000006f));
    TEST_ASSERT_EQUAL_INT32(8388609, pft_round_int(8388609.0f));
    /* out of the int32 range: saturated, never a conversion with undefined behaviour (the fuzzer
     * found 1.3e13 reaching pft_floor_int through pft_pte_start; reliability.md F1) */
    TEST_ASSERT_EQUAL_INT32(INT32_MAX, pft_floor_int(1.3e13f));
    TEST_ASSERT_EQUAL_INT32(INT32_MIN, pft_floor_int(-1.3e13f));
    TEST_ASSERT_EQUAL_INT32(INT32_MAX, pft_round_int(PFT_REAL_MAX));
    TEST_ASSERT_EQUAL_INT32(INT32_MIN, pft_round_int(PFT_REAL_MIN));
    TEST_ASSERT_EQUAL_INT32(INT32_MAX, pft_round_int(2147483648.0f));
    TEST_ASSERT_EQUAL_INT32(INT32_MIN, pft_floor_int(-2147483648.0f));
    TEST_ASSERT_EQUAL_INT32(2147483520, pft_floor_int(2147483520.0f)); /* largest float below 2^31 */
    {
        volatile float zero = 0.0f;
        float nan = zero / zero;
        TEST_ASSERT_EQUAL_INT32(0, pft_floor_int(nan));
        TEST_ASSERT_EQUAL_INT32(0, pft_round_int(nan));
    }
#endif
}

/* ---- pft_from_f32 ------------------------------------------------------------------------- */

static float f_of_bits(uint32_t b)
{
    float f;
    memcpy(&f, &b, sizeof f);
    return f;
}

static void test_from_f32_specials(void)
{
#ifdef PFT_NUMERIC_Q16
    TEST_ASSERT_EQUAL_INT32(0, pft_from_f32(f_of_bits(0x7FC00000u)));  /* quiet NaN */
    TEST_ASSERT_EQUAL_INT32(0, pft_from_f32(f_of_bits(0xFF800001u)));  /* negative sNaN */
    TEST_ASSERT_EQUAL_INT32(PFT_REAL_MAX, pft_from_f32(f_of_bits(0x7F800000u))); /* +inf */
    TEST_ASSERT_EQUAL_INT32(PFT_REAL_MIN, pft_from_f32(f_of_bits(0xFF800000u))); /* -inf */
    TEST_ASSERT_EQUAL_INT32(PFT_REAL_MAX, pft_from_f32(f_of_bits(0x7F7FFFFFu))); /* FLT_MAX */
    TEST_ASSERT_EQUAL_INT32(PFT_REAL_MIN, pft_from_f32(f_of_bits(0xFF7FFFFFu)));
    TEST_ASSERT_EQUAL_INT32(PFT_REAL_MAX, pft_from_f32(f_of_bits(0x47000000u))); /* 32768 */
    TEST_ASSERT_EQUAL_INT32(PFT_REAL_MIN, pft_from_f32(f_of_bits(0xC7000000u))); /* -32768 */
    TEST_ASSERT_EQUAL_INT32(0x7FFFFF80, pft_from_f32(f_of_bits(0x46FFFFFFu))); /* 32767.998 */
    TEST_ASSERT_EQUAL_INT32(0, pft_from_f32(f_of_bits(0x00000000u)));
    TEST_ASSERT_EQUAL_INT32(0, pft_from_f32(f_of_bits(0x80000000u))); /* -0 */
    TEST_ASSERT_EQUAL_INT32(0, pft_from_f32(f_of_bits(0x00000001u))); /* subnormals */
    TEST_ASSERT_EQUAL_INT32(0, pft_from_f32(f_of_bits(0x807FFFFFu)));
    TEST_ASSERT_EQUAL_INT32(98304, pft_from_f32(f_of_bits(0x3FC00000u))); /* 1.5 */
    TEST_ASSERT_EQUAL_INT32(-98304, pft_from_f32(f_of_bits(0xBFC00000u)));
    TEST_ASSERT_EQUAL_INT32(1, pft_from_f32(f_of_bits(0x37000000u)));  /* 2^-17: tie -> away */
    TEST_ASSERT_EQUAL_INT32(-1, pft_from_f32(f_of_bits(0xB7000000u)));
    TEST_ASSERT_EQUAL_INT32(0, pft_from_f32(f_of_bits(0x36FFFFFFu)));  /* just below */
    TEST_ASSERT_EQUAL_INT32(1, pft_from_f32(f_of_bits(0x37000001u)));  /* just above */
    TEST_ASSERT_EQUAL_INT32(0, pft_from_f32(f_of_bits(0x36800000u)));  /* 2^-18 */
    TEST_ASSERT_EQUAL_INT32(2, pft_from_f32(f_of_bits(0x37C00000u)));  /* 1.5 LSB -> 2 */
#else
    TEST_ASSERT_TRUE(isnan(pft_from_f32(f_of_bits(0x7FC00000u))));
    TEST_ASSERT_TRUE(isinf(pft_from_f32(f_of_bits(0x7F800000u))));
    TEST_ASSERT_TRUE(pft_from_f32(1.5f) == 1.5f);
    TEST_ASSERT_TRUE(pft_from_f32(f_of_bits(0x00000001u)) == f_of_bits(0x00000001u));
#endif
}

static void test_from_f32_grid(void)
{
    err_t e;
    err_init(&e);
    lcg_state = 41u;
    for (int i = 0; i < 4000 * PFT_TEST_DENSE; ++i) {
        uint32_t b = lcg();
        float f;
        /* exponents from 2^-20 to 2^14, either sign, random mantissa */
        b = (b & 0x807FFFFFu) | ((uint32_t)(107u + lcg() % 35u) << 23);
        f = f_of_bits(b);
#ifdef PFT_NUMERIC_Q16
        err_add(&e, pft_from_f32(f), (double)f, (double)f);
#else
        {
            float g = pft_from_f32(f);
            TEST_ASSERT_EQUAL_MEMORY(&f, &g, sizeof f); /* identity, bit for bit */
            err_add(&e, g, (double)f, (double)f);
        }
#endif
    }
    err_report("pft_from_f32", &e, B_F32);
}

/* ---- transcendental helpers --------------------------------------------------------------- */

static void test_sqrt_error(void)
{
    err_t e;
    double x;
    err_init(&e);
    lcg_state = 51u;
    for (int i = 0; i < 3000 * PFT_TEST_DENSE; ++i) {
        pft_real_t a = in_real(lrand(1.0 / 65536.0, 32767.99), &x);
        err_add(&e, pft_sqrt(a), sqrt(x), x);
    }
    for (int i = 0; i < 1000 * PFT_TEST_DENSE; ++i) { /* small arguments, where sqrt is steep */
        pft_real_t a = in_real(urand(0.0, 0.01), &x);
        err_add(&e, pft_sqrt(a), sqrt(x), x);
    }
    err_report("pft_sqrt", &e, B_SQRT);
    TEST_ASSERT_REAL_EQ(R(0.0), pft_sqrt(R(0.0)));
    TEST_ASSERT_REAL_EQ(R(0.0), pft_sqrt(R(-4.0)));
    TEST_ASSERT_REAL_EQ(R(3.0), pft_sqrt(R(9.0)));
    TEST_ASSERT_REAL_EQ(R(181.0), pft_sqrt(R(32761.0)));
#ifdef PFT_NUMERIC_Q16
    TEST_ASSERT_EQUAL_INT32(0, pft_sqrt(INT32_MIN));
    TEST_ASSERT_EQUAL_INT32(11863283, pft_sqrt(PFT_REAL_MAX)); /* sqrt(32768) * 65536 */
    TEST_ASSERT_EQUAL_INT32(256, pft_sqrt(1));                  /* sqrt(2^-16) = 2^-8 */
#endif
}

static void test_exp_error(void)
{
    err_t e;
    double x;
    err_init(&e);
    lcg_state = 61u;
    for (int i = 0; i < 4000 * PFT_TEST_DENSE; ++i) {
        pft_real_t a = in_real(urand(-12.0, 10.3972), &x);
        err_add(&e, pft_exp(a), exp(x), x);
    }
    for (int i = 0; i < 1000 * PFT_TEST_DENSE; ++i) { /* top of the range, largest results */
        pft_real_t a = in_real(urand(9.0, 10.3972), &x);
        err_add(&e, pft_exp(a), exp(x), x);
    }
#if defined(PFT_NUMERIC_Q16) && PFT_TEST_DENSE >= 64
    for (int32_t a = -13 * 65536; a < 681392; ++a) { /* every input below saturation */
        err_add(&e, pft_exp(a), exp((double)a / 65536.0), (double)a / 65536.0);
    }
#endif
    err_report("pft_exp", &e, B_EXP);
    TEST_ASSERT_REAL_EQ(PFT_REAL_ONE, pft_exp(R(0.0)));
#ifdef PFT_NUMERIC_Q16
    TEST_ASSERT_EQUAL_INT32(PFT_REAL_MAX, pft_exp(681392));  /* just above ln 32768 */
    TEST_ASSERT_EQUAL_INT32(PFT_REAL_MAX, pft_exp(R(11.0)));
    TEST_ASSERT_EQUAL_INT32(PFT_REAL_MAX, pft_exp(PFT_REAL_MAX));
    TEST_ASSERT_TRUE(pft_exp(681391) < PFT_REAL_MAX && pft_exp(681391) > R(32767.0));
    TEST_ASSERT_EQUAL_INT32(1, pft_exp(R(-11.0)));           /* 1.09 LSB */
    TEST_ASSERT_EQUAL_INT32(0, pft_exp(R(-11.8)));           /* 0.49 LSB */
    TEST_ASSERT_EQUAL_INT32(0, pft_exp(PFT_REAL_MIN));
    TEST_ASSERT_EQUAL_INT32(0, pft_exp(INT32_MIN));
#endif
}

static void test_log_error(void)
{
    err_t e;
    double x;
    err_init(&e);
    lcg_state = 71u;
    for (int i = 0; i < 4000 * PFT_TEST_DENSE; ++i) {
        pft_real_t a = in_real(lrand(1.0 / 65536.0, 32767.99), &x);
        err_add(&e, pft_log(a), log(x), x);
    }
    for (int i = 0; i < 1000 * PFT_TEST_DENSE; ++i) { /* around 1, where log crosses zero */
        pft_real_t a = in_real(urand(0.7, 1.4), &x);
        err_add(&e, pft_log(a), log(x), x);
    }
    err_report("pft_log", &e, B_LOG);
    TEST_ASSERT_REAL_EQ(R(0.0), pft_log(PFT_REAL_ONE));
    TEST_ASSERT_REAL_EQ(PFT_REAL_MIN, pft_log(R(0.0)));
    TEST_ASSERT_REAL_EQ(PFT_REAL_MIN, pft_log(R(-1.0)));
#ifdef PFT_NUMERIC_Q16
    TEST_ASSERT_EQUAL_INT32(PFT_REAL_MIN, pft_log(INT32_MIN));
    TEST_ASSERT_EQUAL_INT32(R(-16.0 * log(2.0)), pft_log(1)); /* smallest argument */
    TEST_ASSERT_EQUAL_INT32(R(log(2147483647.0 / 65536.0)), pft_log(PFT_REAL_MAX));
#endif
}

static void test_atan2_error(void)
{
    err_t e;
    double y, x;
    err_init(&e);
    lcg_state = 81u;
    for (int i = 0; i < 4000 * PFT_TEST_DENSE; ++i) {
        double r = lrand(1e-4, 23000.0), t = urand(-3.14159265358979, 3.14159265358979);
        pft_real_t py = in_real(r * sin(t), &y);
        pft_real_t px = in_real(r * cos(t), &x);
        pft_real_t got = pft_atan2(py, px);
        err_add(&e, got, atan2(y, x), t);
        TEST_ASSERT_TRUE(got >= -PFT_PI && got <= PFT_PI);
    }
#ifdef PFT_NUMERIC_Q16
    for (int32_t iy = -12; iy <= 12; ++iy) { /* tiny raw integer vectors */
        for (int32_t ix = -12; ix <= 12; ++ix) {
            err_add(&e, pft_atan2(iy, ix), atan2((double)iy, (double)ix), (double)iy);
        }
    }
    /* full-range raw integers, including INT32_MIN */
    err_add(&e, pft_atan2(INT32_MIN, INT32_MIN), atan2(-1.0, -1.0), 0.0);
    err_add(&e, pft_atan2(PFT_REAL_MAX, 1), atan2(2147483647.0, 1.0), 0.0);
    err_add(&e, pft_atan2(-1, PFT_REAL_MIN), atan2(-1.0, -2147483647.0), 0.0);
    TEST_ASSERT_EQUAL_INT32(PFT_PI, pft_atan2(0, -5));
    TEST_ASSERT_EQUAL_INT32(PFT_PI, pft_atan2(0, INT32_MIN));
    TEST_ASSERT_EQUAL_INT32(-PFT_PI, pft_atan2(-1, PFT_REAL_MIN)); /* -pi + 2^-31: in range */
#endif
    err_report("pft_atan2", &e, B_ATAN2);
    TEST_ASSERT_REAL_EQ(R(0.0), pft_atan2(R(0.0), R(0.0)));
    TEST_ASSERT_REAL_EQ(R(0.0), pft_atan2(R(0.0), R(2.0)));
    TEST_ASSERT_REAL_EQ(PFT_PI, pft_atan2(R(0.0), R(-2.0)));
    TEST_ASSERT_REAL_EQ(PFT_C(1.57079632679490), pft_atan2(R(3.0), R(0.0)));
    TEST_ASSERT_REAL_EQ(PFT_C(-1.57079632679490), pft_atan2(R(-3.0), R(0.0)));
}

static void test_sin_cos_error(void)
{
    err_t es, ec;
    double x, ssq = 0.0;
    err_init(&es);
    err_init(&ec);
    lcg_state = 91u;
    for (int i = 0; i < 4000 * PFT_TEST_DENSE; ++i) {
        double lo = (i & 3) == 0 ? -32767.0 : -12.6, hi = (i & 3) == 0 ? 32767.0 : 12.6;
        pft_real_t a = in_real(urand(lo, hi), &x);
        pft_real_t s = pft_sin(a), c = pft_cos(a);
        double n2 = pft_test_to_double(s) * pft_test_to_double(s) +
                    pft_test_to_double(c) * pft_test_to_double(c) - 1.0;
        err_add(&es, s, sin(x), x);
        err_add(&ec, c, cos(x), x);
        ssq = fabs(n2) > ssq ? fabs(n2) : ssq;
        TEST_ASSERT_TRUE(s >= -PFT_REAL_ONE && s <= PFT_REAL_ONE);
    }
    err_report("pft_sin", &es, B_SINCOS);
    err_report("pft_cos", &ec, B_SINCOS);
    TEST_ASSERT_TRUE(ssq < 4.0 * pft_test_lsb(1.0));
    TEST_ASSERT_REAL_EQ(R(0.0), pft_sin(R(0.0)));
    TEST_ASSERT_REAL_EQ(PFT_REAL_ONE, pft_cos(R(0.0)));
#ifdef PFT_NUMERIC_Q16
    TEST_ASSERT_EQUAL_INT32(PFT_REAL_ONE, pft_sin(PFT_C(1.5707963267949)));
    TEST_ASSERT_EQUAL_INT32(-PFT_REAL_ONE, pft_cos(PFT_PI));
    TEST_ASSERT_INT32_WITHIN(1, 0, pft_sin(PFT_PI));
    {
        err_t ee; /* extreme arguments */
        err_init(&ee);
        err_add(&ee, pft_sin(PFT_REAL_MAX), sin(2147483647.0 / 65536.0), 0.0);
        err_add(&ee, pft_cos(PFT_REAL_MAX), cos(2147483647.0 / 65536.0), 0.0);
        err_add(&ee, pft_sin(INT32_MIN), sin(-32768.0), 0.0);
        err_add(&ee, pft_cos(INT32_MIN), cos(-32768.0), 0.0);
        err_add(&ee, pft_sin(-1), sin(-1.0 / 65536.0), 0.0);
        TEST_ASSERT_TRUE(ee.max <= B_SINCOS);
    }
#endif
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_add_sub_saturate);
    RUN_TEST(test_neg_abs);
    RUN_TEST(test_mul_rounding_and_saturation);
    RUN_TEST(test_div_error);
    RUN_TEST(test_div_special);
    RUN_TEST(test_recip_error);
    RUN_TEST(test_round_floor_negatives);
    RUN_TEST(test_from_f32_specials);
    RUN_TEST(test_from_f32_grid);
    RUN_TEST(test_sqrt_error);
    RUN_TEST(test_exp_error);
    RUN_TEST(test_log_error);
    RUN_TEST(test_atan2_error);
    RUN_TEST(test_sin_cos_error);
    return UNITY_END();
}
