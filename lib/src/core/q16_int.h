/* Q16.16 kernels of the number layer as inline functions (private, not installed, q16 build
 * only): pft_real_q16.c defines pft_div, pft_div_i, pft_sqrt and pft_exp with them, and a hot
 * loop that calls one of these many times per step (PTE-TBD's track step) uses them directly,
 * so both compute the same bits from one source. docs/fixed_point.md, "Number layer" and
 * "PTE-TBD Kalman algebra and square root".
 */
#ifndef PFT_CORE_Q16_INT_H
#define PFT_CORE_Q16_INT_H

#include "pft/pft_real.h"

#ifdef PFT_NUMERIC_Q16

#define PFT_Q16_LN2_Q48_ ((int64_t)195103586505167) /* ln 2 * 2^48 */
#define PFT_Q16_INV_LN2_Q30_ ((int64_t)1549082005)  /* 2^30 / ln 2 */

/* Magnitude of an int32 as uint32 (INT32_MIN -> 2^31, no overflow). */
static inline uint32_t pft_q16_umag_(int32_t a)
{
    return a < 0 ? 0u - (uint32_t)a : (uint32_t)a;
}

/* Saturating signed result from a magnitude and a sign. */
static inline pft_real_t pft_q16_signed_sat_(uint64_t mag, bool neg)
{
    if (mag > (uint64_t)INT32_MAX) {
        return neg ? PFT_REAL_MIN : PFT_REAL_MAX;
    }
    return neg ? -(pft_real_t)mag : (pft_real_t)mag;
}

/* a / b rounded to nearest, ties away from zero (on the magnitude), saturating; b = 0 gives
 * the saturated sign of a (0 for a = 0). */
static inline pft_real_t pft_q16_div_(pft_real_t a, pft_real_t b)
{
    if (b == 0) {
        return a > 0 ? PFT_REAL_MAX : (a < 0 ? PFT_REAL_MIN : 0);
    }
    const uint64_t n = (uint64_t)pft_q16_umag_(a) << 16; /* < 2^48 */
    const uint64_t d = pft_q16_umag_(b);
    return pft_q16_signed_sat_((n + (d >> 1)) / d, (a < 0) != (b < 0));
}

/* a / k for an integer k > 0, rounded as pft_q16_div_; k <= 0 as a division by 0. */
static inline pft_real_t pft_q16_div_i_(pft_real_t a, int32_t k)
{
    if (k <= 0) {
        return pft_q16_div_(a, 0);
    }
    const uint64_t d = (uint64_t)k;
    return pft_q16_signed_sat_(((uint64_t)pft_q16_umag_(a) + (d >> 1)) / d, a < 0);
}

/* Square root, rounded to nearest; 0 for a <= 0. Digit-by-digit on N = a * 2^16 (a in Q32,
 * so the root is Q16): 24 result bits from bit 2^46 down. A step whose bit is above n leaves
 * root = 0 and n unchanged (n < root + bit), so the steps start at the highest power of 4 not
 * above n: the same root in fewer steps. */
static inline pft_real_t pft_q16_sqrt_(pft_real_t a)
{
    if (a <= 0) {
        return 0;
    }
    uint64_t n = (uint64_t)(uint32_t)a << 16; /* >= 2^16, so the first loop ends by bit 2^16 */
    uint64_t root = 0;
    uint64_t bit = (uint64_t)1 << 46;
    while (bit > n) {
        bit >>= 2;
    }
    while (bit != 0u) { /* at most 24 steps, one result bit each */
        if (n >= root + bit) {
            n -= root + bit;
            root = (root >> 1) + bit;
        } else {
            root >>= 1;
        }
        bit >>= 2;
    }
    /* root = floor(sqrt(N)), n = N - root^2; round up iff N > root^2 + root */
    if (n > root) {
        ++root;
    }
    return (pft_real_t)root;
}

/* Splits x (Q16.16) as x = k ln2 - r with r in [0, ln 2); returns k, r in Q0.32 (rounded). */
static inline int32_t pft_q16_exp_split_(pft_real_t x, uint32_t *r32)
{
    const int64_t xq = (int64_t)x * ((int64_t)1 << 32); /* x in Q48, exact */
    int64_t k = (((int64_t)x * PFT_Q16_INV_LN2_Q30_) >> 46) + 1; /* ceil(x / ln2), +-1 */
    int64_t r = k * PFT_Q16_LN2_Q48_ - xq;
    for (int32_t i = 0; i < 2; ++i) {
        if (r < 0) {
            r += PFT_Q16_LN2_Q48_;
            ++k;
        } else if (r >= PFT_Q16_LN2_Q48_) {
            r -= PFT_Q16_LN2_Q48_;
            --k;
        } else {
            /* r already in [0, ln 2) */
        }
    }
    *r32 = (uint32_t)((r + 32768) >> 16);
    return (int32_t)k;
}

/* exp(-r) for r in [0, ln 2], r in Q0.32; result in Q0.32, in [2^31, 2^32].
 * Taylor to degree 11 (remainder < 2.6e-11), Horner with rounding, all terms positive. */
static inline uint64_t pft_q16_expneg_q32_(uint32_t r)
{
    static const uint64_t c[12] = {4294967296u, 4294967296u, 2147483648u, 715827883u,
                                   178956971u,  35791394u,   5965232u,    852176u,
                                   106522u,     11836u,      1184u,       108u};
    uint64_t p = c[11];
    for (int32_t i = 10; i >= 0; --i) {
        p = c[i] - ((p * r + 0x80000000u) >> 32);
    }
    return p;
}

/* exp(x) in Q16.16 for -18 ln 2 <= x < 15 ln 2 (k of the split in [-18, 15]): the split, the
 * Horner step and one rounding shift; the callers handle the range outside. */
static inline uint64_t pft_q16_exp_core_(pft_real_t x)
{
    uint32_t r;
    const int32_t k = pft_q16_exp_split_(x, &r);
    const uint64_t e = pft_q16_expneg_q32_(r); /* exp(x) = e * 2^(k - 32) */
    const int32_t s = 16 - k; /* Q32 -> Q16 with the 2^k factor: shift right by s >= 1 */
    return (e + ((uint64_t)1 << (s - 1))) >> s;
}

#endif /* PFT_NUMERIC_Q16 */

#endif
