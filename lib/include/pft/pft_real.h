/**
 * @file pft_real.h
 * @brief The number layer: pft_real_t (float or Q16.16) and its saturating helpers.
 *
 * One algorithm source serves both builds. All arithmetic on pft_real_t goes through these
 * helpers; plain `+`/`-` are allowed only where the operands are known not to overflow
 * (document it at the call site). Comparisons (`<`, `==`) work directly in both builds.
 *
 * Formats (q16 build):
 * - pft_real_t: Q16.16 in int32_t, range [-32768, 32768 - 2^-16], LSB 1.52e-5.
 *   Every helper saturates to [PFT_REAL_MIN, PFT_REAL_MAX] and never invokes undefined
 *   behaviour; products and quotients use a 64-bit intermediate and round to nearest.
 * - pft_weight_t: unsigned Q2.30 in uint32_t (PFT_W_ONE = 2^30 is 1.0). Unnormalised particle
 *   weights are exp(lw - max lw) in (0, 1]; normalised weights sum to PFT_W_ONE (up to
 *   rounding). Sums go into pft_wacc_t (uint64_t): with at most 2^22 particles
 *   (PFT_CFG_MAX_PARTICLES) a sum cannot overflow, and a weighted sum of Q16.16 values
 *   (|w x| < 2^61) cannot either.
 * - Log-likelihoods and log-weights are plain pft_real_t (Q16.16): per-frame TBD
 *   log-likelihood ratios stay within +-32768 by orders of magnitude; accumulators that could
 *   exceed it saturate (pft_add) and say so in their module's docs.
 *
 * In the float build the same names are IEEE single (float) and the helpers map to libm's
 * single-precision functions; pft_weight_t and pft_wacc_t are float.
 */
#ifndef PFT_REAL_H
#define PFT_REAL_H

#include "pft/pft_types.h"

#ifdef PFT_NUMERIC_FLOAT
#include <math.h>
#endif

#ifdef __cplusplus
extern "C" {
#endif

/* ------------------------------------------------------------------------------------------ */
#ifdef PFT_NUMERIC_Q16

/** The library's real number: Q16.16 in int32_t (q16 build) or float (float build). */
typedef int32_t pft_real_t;
/** A particle weight: unsigned Q2.30 in uint32_t, 1.0 = PFT_W_ONE (q16) or float. */
typedef uint32_t pft_weight_t;
/** Sum of weights: uint64_t (q16, cannot overflow for PFT_CFG_MAX_PARTICLES) or float. */
typedef uint64_t pft_wacc_t;

/** Fraction bits of pft_real_t in the q16 build (no float counterpart). */
#define PFT_Q_FRAC 16
/** 1.0 as a pft_real_t. */
#define PFT_REAL_ONE ((pft_real_t)65536)
/** Largest pft_real_t (q16: 32768 - 2^-16; float: FLT_MAX); helpers saturate to it. */
#define PFT_REAL_MAX ((pft_real_t)INT32_MAX)
/** Smallest pft_real_t, -PFT_REAL_MAX (symmetric, so negation and abs cannot overflow). */
#define PFT_REAL_MIN ((pft_real_t)(-INT32_MAX))
/** Resolution: one LSB, 2^-16 (q16); FLT_EPSILON (float). */
#define PFT_REAL_EPS ((pft_real_t)1)
/** Compile-time constant from a decimal literal, rounded to nearest (folded by the compiler). */
#define PFT_C(x) ((pft_real_t)((x) >= 0 ? (x) * 65536.0 + 0.5 : (x) * 65536.0 - 0.5))
/** Weight 1.0: 2^30 (q16) or 1.0f (float); normalised weights sum to it. */
#define PFT_W_ONE ((pft_weight_t)1073741824u)
/** Name of the build's number type as a string: "q16" or "float". */
#define PFT_NUMERIC_NAME "q16"

static inline pft_real_t pft_sat64_(int64_t v)
{
    return v > (int64_t)INT32_MAX ? PFT_REAL_MAX
         : v < -(int64_t)INT32_MAX ? PFT_REAL_MIN : (pft_real_t)v;
}
/** a + b, saturating. */
static inline pft_real_t pft_add(pft_real_t a, pft_real_t b) { return pft_sat64_((int64_t)a + b); }
/** a - b, saturating. */
static inline pft_real_t pft_sub(pft_real_t a, pft_real_t b) { return pft_sat64_((int64_t)a - b); }
/** -a (never overflows: the range is symmetric). */
static inline pft_real_t pft_neg(pft_real_t a) { return a == INT32_MIN ? PFT_REAL_MAX : -a; }
/** |a| (never overflows). */
static inline pft_real_t pft_abs(pft_real_t a) { return a < 0 ? pft_neg(a) : a; }
/** a*b rounded to nearest (ties away from zero), saturating. */
static inline pft_real_t pft_mul(pft_real_t a, pft_real_t b)
{
    int64_t p = (int64_t)a * b;
    p += p >= 0 ? (int64_t)32768 : (int64_t)32767;
    return pft_sat64_(p >> 16); /* arithmetic shift (gcc/clang/armcc); rounds to nearest */
}
/** a/b rounded to nearest, saturating; b == 0 gives +-PFT_REAL_MAX (0/0 gives 0). */
pft_real_t pft_div(pft_real_t a, pft_real_t b);
/** real times integer, saturating. */
static inline pft_real_t pft_mul_i(pft_real_t a, int32_t k) { return pft_sat64_((int64_t)a * k); }
/** real divided by a positive integer, rounded to nearest (ties away from zero). k <= 0 is
 *  outside the domain and behaves like a division by zero: +-PFT_REAL_MAX by the sign of a,
 *  0 for a == 0 (same in both builds). */
pft_real_t pft_div_i(pft_real_t a, int32_t k);
/** Integer to real, saturating (q16: |i| above 32767 saturates). */
static inline pft_real_t pft_from_int(int32_t i) { return pft_sat64_((int64_t)i * 65536); }
/** floor(a) as an integer. */
static inline int32_t pft_floor_int(pft_real_t a) { return (int32_t)(a >> 16); }
/** round(a) to nearest integer, ties up. */
static inline int32_t pft_round_int(pft_real_t a) { return (int32_t)(((int64_t)a + 32768) >> 16); }
/** Ratio num/den of integers as a real, rounded to nearest (ties away from zero), saturating.
 *  den == 0 behaves like pft_div by zero (+-PFT_REAL_MAX, 0/0 gives 0). */
static inline pft_real_t pft_ratio(int32_t num, int32_t den)
{
    int64_t n = (int64_t)num * 65536, d = den, q;
    if (d == 0) {
        return num > 0 ? PFT_REAL_MAX : (num < 0 ? PFT_REAL_MIN : 0);
    }
    if (d < 0) {
        n = -n;
        d = -d;
    }
    q = (n >= 0 ? n + d / 2 : n - d / 2) / d;
    return pft_sat64_(q);
}
/** Uniform u32 fraction u/2^32 in [0,1) as a real (top 16 bits, truncating). */
static inline pft_real_t pft_from_u32_frac(uint32_t u) { return (pft_real_t)(u >> 16); }
/** For logging and host code: the value as a float. Never called inside the library (a q16
 *  firmware that calls it links soft-float helpers on a core without FPU). */
static inline float pft_to_float(pft_real_t a) { return (float)a * (1.0f / 65536.0f); }
/** For logging: a Q2.30 weight as a float (same caveat). */
static inline float pft_weight_to_float(pft_weight_t w) { return (float)w * (1.0f / 1073741824.0f); }

#else /* ---------------------------------- float ----------------------------------------- */

typedef float pft_real_t;
typedef float pft_weight_t;
typedef float pft_wacc_t;

#define PFT_REAL_ONE 1.0f
#define PFT_REAL_MAX 3.402823466e+38f
#define PFT_REAL_MIN (-3.402823466e+38f)
#define PFT_REAL_EPS 1.1920929e-07f
#define PFT_C(x) ((pft_real_t)(x))
#define PFT_W_ONE 1.0f
#define PFT_NUMERIC_NAME "float"

static inline pft_real_t pft_add(pft_real_t a, pft_real_t b) { return a + b; }
static inline pft_real_t pft_sub(pft_real_t a, pft_real_t b) { return a - b; }
static inline pft_real_t pft_neg(pft_real_t a) { return -a; }
static inline pft_real_t pft_abs(pft_real_t a) { return fabsf(a); }
static inline pft_real_t pft_mul(pft_real_t a, pft_real_t b) { return a * b; }
static inline pft_real_t pft_div(pft_real_t a, pft_real_t b)
{
    if (b == 0.0f) {
        return a > 0.0f ? PFT_REAL_MAX : (a < 0.0f ? PFT_REAL_MIN : 0.0f);
    }
    return a / b;
}
static inline pft_real_t pft_mul_i(pft_real_t a, int32_t k) { return a * (float)k; }
static inline pft_real_t pft_div_i(pft_real_t a, int32_t k)
{
    return k > 0 ? a / (float)k : pft_div(a, 0.0f);
}
static inline pft_real_t pft_from_int(int32_t i) { return (float)i; }
/* An integral float to int32, saturating: beyond the int32 range INT32_MIN / INT32_MAX, NaN 0
 * (a plain conversion of such a value is undefined behaviour in C). */
static inline int32_t pft_sat_int_(float f)
{
    if (f >= 2147483648.0f) {
        return INT32_MAX;
    }
    if (f < -2147483648.0f) {
        return INT32_MIN;
    }
    return (f == f) ? (int32_t)f : 0;
}
static inline int32_t pft_floor_int(pft_real_t a) { return pft_sat_int_(floorf(a)); }
/* floorf(a + 0.5f) would round 0.49999997f up (the sum rounds to 1.0f): compare the exact
 * fractional part a - floorf(a) instead. Beyond 2^24 every float is an integer, so the sum
 * below is exact wherever it matters. */
static inline int32_t pft_round_int(pft_real_t a)
{
    float f = floorf(a);
    return pft_sat_int_(f + (a - f >= 0.5f ? 1.0f : 0.0f));
}
static inline pft_real_t pft_ratio(int32_t num, int32_t den) { return pft_div((float)num, (float)den); }
/** Uniform u32 fraction u/2^32 in [0,1): top 24 bits, exact in a float. */
static inline pft_real_t pft_from_u32_frac(uint32_t u) { return (float)(u >> 8) * 5.9604645e-08f; }
static inline float pft_to_float(pft_real_t a) { return a; }
static inline float pft_weight_to_float(pft_weight_t w) { return w; }

#endif /* PFT_NUMERIC_Q16 */
/* ------------------------------------------------------------------------------------------ */

/** The smaller of a and b. */
static inline pft_real_t pft_min(pft_real_t a, pft_real_t b) { return a < b ? a : b; }
/** The larger of a and b. */
static inline pft_real_t pft_max(pft_real_t a, pft_real_t b) { return a > b ? a : b; }
/** a limited to [lo, hi] (lo <= hi). */
static inline pft_real_t pft_clamp(pft_real_t a, pft_real_t lo, pft_real_t hi)
{
    return a < lo ? lo : (a > hi ? hi : a);
}
/** a * a, saturating. */
static inline pft_real_t pft_sq(pft_real_t a) { return pft_mul(a, a); }

/*
 * Transcendental helpers. Domains and q16 error bounds (measured against a 64-bit floating-point reference
 * by tests/unit/test_real.c, which asserts them):
 *   pft_recip(a)     1/a; a == 0 saturates.
 *   pft_sqrt(a)      a >= 0 (negative gives 0).
 *   pft_exp(a)       saturates to PFT_REAL_MAX above ln(32768); tends to 0 below -11.1.
 *   pft_log(a)       a > 0; a <= 0 gives PFT_REAL_MIN.
 *   pft_atan2(y, x)  in (-pi, pi]; atan2(0, 0) = 0.
 *   pft_sin, pft_cos any argument (reduced modulo 2 pi).
 * The bounds in LSB are documented in docs/fixed_point.md.
 */
#ifdef PFT_NUMERIC_Q16
/** 1/a; a == 0 saturates. */
pft_real_t pft_recip(pft_real_t a);
/** Square root of a >= 0 (a negative a gives 0). */
pft_real_t pft_sqrt(pft_real_t a);
/** exp(a); saturates to PFT_REAL_MAX above ln(32768), tends to 0 below -11.1 (q16). */
pft_real_t pft_exp(pft_real_t a);
/** Natural logarithm of a > 0; a <= 0 gives PFT_REAL_MIN. */
pft_real_t pft_log(pft_real_t a);
/** atan2(y, x) in (-pi, pi]; atan2(0, 0) = 0. */
pft_real_t pft_atan2(pft_real_t y, pft_real_t x);
/** sin(a), any argument (reduced modulo 2 pi). */
pft_real_t pft_sin(pft_real_t a);
/** cos(a), any argument (reduced modulo 2 pi). */
pft_real_t pft_cos(pft_real_t a);
#else
static inline pft_real_t pft_recip(pft_real_t a) { return pft_div(1.0f, a); }
static inline pft_real_t pft_sqrt(pft_real_t a) { return a > 0.0f ? sqrtf(a) : 0.0f; }
static inline pft_real_t pft_exp(pft_real_t a) { return expf(a); }
static inline pft_real_t pft_log(pft_real_t a) { return a > 0.0f ? logf(a) : PFT_REAL_MIN; }
static inline pft_real_t pft_atan2(pft_real_t y, pft_real_t x) { return atan2f(y, x); }
static inline pft_real_t pft_sin(pft_real_t a) { return sinf(a); }
static inline pft_real_t pft_cos(pft_real_t a) { return cosf(a); }
#endif

/** pi as a pft_real_t. */
#define PFT_PI PFT_C(3.14159265358979)
/** 2 pi as a pft_real_t. */
#define PFT_TWO_PI PFT_C(6.28318530717959)

/* Pixel conversions: U8 and U16 raw values to reals, with an optional gain/offset applied by
 * the caller (pft_mul/pft_add). Values up to 32767 convert exactly in q16. */
/** U8 pixel value to real (exact). */
static inline pft_real_t pft_from_u8(uint8_t v) { return pft_from_int((int32_t)v); }
/** U16 pixel value to real (q16: exact up to 32767, saturating above). */
static inline pft_real_t pft_from_u16(uint16_t v) { return pft_from_int((int32_t)v); }
/** F32 pixel to real. float build: the identity. q16 build: decodes the IEEE bits with integer
 *  operations only (no FPU or soft-float helper needed), rounds to nearest (ties away from
 *  zero), saturates to [PFT_REAL_MIN, PFT_REAL_MAX] (infinities included); NaN gives 0,
 *  subnormals give 0. */
pft_real_t pft_from_f32(float v);

/**
 * Converts the first n pixels of row y of a U8, U16, RES16 or F32 frame (already validated
 * with pft_frame_check) to reals: z = gain*raw + offset for U8 and U16 (U16: only the low
 * bit_depth bits are significant), z = gain*(raw/256) + offset for RES16 (sigma units; a
 * PFT_RES16_MASKED pixel gives offset, the value of a zero residual), F32 as it is
 * (pft_from_f32). Results are clamped to [-32767, 32767], the q16 range, in both builds.
 */
void pft_frame_row_to_real(const pft_frame_t *frame, uint32_t y, uint32_t n, pft_real_t gain,
                           pft_real_t offset, pft_real_t *out);

/* ---------------------------------- weights ----------------------------------------------- */
/** exp(x) for x <= 0 as a weight in [0, 1]; x >= 0 gives exactly PFT_W_ONE.
 *  q16: Q2.30 rounded to nearest, error <= 0.6 LSB (2^-30) over the whole domain; exp(x) below
 *  half an LSB (x < -21.5) gives 0. */
pft_weight_t pft_wexp(pft_real_t x);
/** log(acc / PFT_W_ONE) of a weight accumulator (e.g. a sum of pft_wexp values), as a real;
 *  acc == 0 gives PFT_REAL_MIN. q16: any uint64 value, error <= 0.5 LSB + 2^-14 LSB. */
pft_real_t pft_wacc_log(pft_wacc_t acc);
/** Weight as a real (q16: Q2.30 -> Q16.16, truncating). */
pft_real_t pft_weight_to_real(pft_weight_t w);

/** Largest element of a real array (n >= 1). */
pft_real_t pft_real_max_n(const pft_real_t *v, size_t n);
/**
 * Log-sum-exp normalisation of log-weights: w[i] = exp(lw[i] - max) / sum, so that the w sum
 * to PFT_W_ONE. Returns log(sum_i exp(lw[i])) (the log of the unnormalised total), which
 * callers use for likelihood statistics (e.g. log mean weight = result - log N).
 * lw and w may not alias. n >= 1 (n == 0 returns PFT_REAL_MIN and writes nothing).
 * q16: the w sum to exactly PFT_W_ONE (the rounding residue is carried from one weight to the
 * next, so each w[i] is within 1 LSB of its exact quotient); cost one 64-bit division per
 * particle. Log-weights more than 21.5 below the max get weight 0.
 * float: sums are compensated (Kahan), each w[i] is one correctly rounded division.
 */
pft_real_t pft_lognormalize(const pft_real_t *lw, pft_weight_t *w, size_t n);
/** Effective sample size 1 / sum(w^2) of normalised weights, as a real (at most n).
 *  q16: the sum of squares is exact in uint64 and the quotient is rounded once, but the result
 *  saturates at PFT_REAL_MAX (32768) for larger ESS: use pft_ess_ratio to compare with a
 *  fraction of n when n may exceed 32767. All weights zero gives 0. */
pft_real_t pft_ess(const pft_weight_t *w, size_t n);
/** ESS / n in [1/n, 1] as a real (no saturation for any n <= PFT_CFG_MAX_PARTICLES); the
 *  resampling test "ESS < theta N" is pft_ess_ratio(w, n) < theta. n == 0 or all weights zero
 *  gives 0. */
pft_real_t pft_ess_ratio(const pft_weight_t *w, size_t n);

#ifdef __cplusplus
}
#endif
#endif
