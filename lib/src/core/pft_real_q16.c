/*
 * Number layer, out-of-line part.
 *
 * q16 build: Q16.16 division, square root, exp, log, atan2, sin, cos, the Q2.30 weight
 * exponential and the log of a weight accumulator, all in integer arithmetic (no float
 * operation anywhere, so a Cortex-M3 image links no soft-float helper and no libm), and the
 * IEEE single -> Q16.16 conversion by decoding the bits.
 * float build: pft_from_f32 (identity) and pft_wacc_log.
 *
 * Internal precisions (see docs/fixed_point.md): exp works on a Q0.32 mantissa after an exact
 * reduction by ln 2 carried in Q48; log on a Q31 mantissa with an atanh series and ln 2 in Q47;
 * sin/cos reduce modulo pi/2 in Q47 and evaluate Taylor series in Q31; atan2 is a 30-step CORDIC
 * in Q29. Every result is rounded once, at the end, to Q16.16 (or Q2.30).
 * Right shifts of negative signed values are arithmetic (as pft_real.h already assumes).
 */
#include <string.h>

#include "pft/pft_real.h"
#include "q16_int.h"

#ifdef PFT_NUMERIC_Q16

/* ---- constants (each rounded to nearest at the stated scale) ---- */
#define PFT_LN2_Q47_ ((int64_t)97551793252584)     /* ln 2 * 2^47 */
#define PFT_SQRT2_Q32_ ((uint64_t)6074001000u)     /* sqrt 2 * 2^32 */
#define PFT_PI_Q29_ ((int64_t)1686629713)          /* pi * 2^29 */
#define PFT_HALF_PI_Q29_ ((int64_t)843314857)      /* pi/2 * 2^29 */
#define PFT_TWO_PI_Q47_ ((int64_t)884279719003555) /* 2 pi * 2^47 */
#define PFT_HALF_PI_Q47_ ((int64_t)221069929750889) /* pi/2 * 2^47 */
#define PFT_QUARTER_PI_Q47_ ((int64_t)110534964875444) /* pi/4 * 2^47 */
#define PFT_INV_TWO_PI_Q32_ ((int64_t)683565276)   /* 2^32 / (2 pi) */
#define PFT_PI_Q16_ ((pft_real_t)205887)
#define PFT_HALF_PI_Q16_ ((pft_real_t)102944)
#define PFT_P32_ ((uint64_t)1 << 32)

pft_real_t pft_div(pft_real_t a, pft_real_t b)
{
    return pft_q16_div_(a, b); /* round to nearest, ties away from zero; q16_int.h */
}

pft_real_t pft_div_i(pft_real_t a, int32_t k)
{
    return pft_q16_div_i_(a, k);
}

pft_real_t pft_recip(pft_real_t a)
{
    return pft_div(PFT_REAL_ONE, a);
}

pft_real_t pft_sqrt(pft_real_t a)
{
    return pft_q16_sqrt_(a); /* digit by digit, rounded to nearest; q16_int.h */
}

pft_real_t pft_exp(pft_real_t x)
{
    uint64_t v;
    if (x >= (pft_real_t)681392) { /* 15 ln2 = ln 32768 = 681391.6 LSB */
        return PFT_REAL_MAX;
    }
    if (x < -(pft_real_t)(13 * 65536)) { /* exp < 2.3e-6 = 0.15 LSB */
        return 0;
    }
    v = pft_q16_exp_core_(x); /* -18 <= k <= 15 */
    return v > (uint64_t)INT32_MAX ? PFT_REAL_MAX : (pft_real_t)v;
}

pft_weight_t pft_wexp(pft_real_t x)
{
    uint32_t r;
    int32_t k, s;
    uint64_t e;
    if (x >= 0) {
        return PFT_W_ONE;
    }
    if (x < -(pft_real_t)(23 * 65536)) { /* exp < 1.1e-10 = 0.11 LSB of Q2.30 */
        return 0;
    }
    k = pft_q16_exp_split_(x, &r); /* -33 <= k <= 0 */
    e = pft_q16_expneg_q32_(r);
    s = 2 - k; /* Q32 * 2^k -> Q30 */
    return (pft_weight_t)((e + ((uint64_t)1 << (s - 1))) >> s);
}

/* ln(x / 2^f) for x > 0, rounded to Q16.16. */
static pft_real_t pft_ln_(uint64_t x, int32_t f)
{
    static const int64_t c[7] = {2147483648, 715827883, 429496730, 306783378,
                                 238609294,  195225786, 165191050}; /* 2^31/(2j+1) */
    int32_t p = 0, e, j;
    uint64_t m, mm;
    int64_t num, den, z, z2, s, l, total;
    for (j = 32; j > 0; j >>= 1) { /* p = index of the top set bit */
        if ((x >> (p + j)) != 0) {
            p += j;
        }
    }
    if (p > 31) { /* mantissa m in Q31, [2^31, 2^32], rounded */
        m = (x + ((uint64_t)1 << (p - 32))) >> (p - 31);
        if ((m >> 32) != 0) {
            m >>= 1;
            ++p;
        }
    } else {
        m = x << (31 - p);
    }
    e = p - f; /* x / 2^f = (m / 2^31) * 2^e */
    mm = m << 1; /* the mantissa in Q32, [1, 2) */
    if (mm > PFT_SQRT2_Q32_) { /* bring it into [sqrt(1/2), sqrt 2] */
        mm = m;
        ++e;
    }
    /* ln mm = 2 atanh z, z = (mm - 1) / (mm + 1), |z| <= 0.1716; z in Q31 rounded */
    num = ((int64_t)mm - (int64_t)PFT_P32_) * ((int64_t)1 << 31);
    den = (int64_t)mm + (int64_t)PFT_P32_;
    z = (num >= 0 ? num + den / 2 : num - den / 2) / den;
    z2 = (z * z + ((int64_t)1 << 30)) >> 31;
    s = c[6];
    for (j = 5; j >= 0; --j) {
        s = c[j] + ((z2 * s + ((int64_t)1 << 30)) >> 31);
    }
    l = (z * s + ((int64_t)1 << 29)) >> 30; /* 2 z s, Q31 */
    total = (int64_t)e * PFT_LN2_Q47_ + l * 65536; /* Q47 */
    return (pft_real_t)((total + ((int64_t)1 << 30)) >> 31);
}

pft_real_t pft_log(pft_real_t a)
{
    return a <= 0 ? PFT_REAL_MIN : pft_ln_((uint64_t)a, 16);
}

pft_real_t pft_wacc_log(pft_wacc_t acc)
{
    return acc == 0 ? PFT_REAL_MIN : pft_ln_(acc, 30);
}

pft_real_t pft_atan2(pft_real_t y, pft_real_t x)
{
    static const int32_t at[30] = {
        421657428, 248918915, 131521918, 66762579, 33510843, 16771758, 8387925, 4194219,
        2097141,   1048575,   524288,    262144,   131072,   65536,    32768,    16384,
        8192,      4096,      2048,      1024,     512,      256,      128,      64,
        32,        16,        8,         4,        2,        1}; /* atan(2^-i) * 2^29 */
    int64_t bx = x, by = y, off = 0, total;
    uint64_t mag;
    int32_t cx, cy, z = 0, nx, i, sh = 0;
    if (y == 0) {
        return x < 0 ? PFT_PI_Q16_ : 0; /* includes atan2(0, 0) = 0 */
    }
    if (x == 0) {
        return y > 0 ? PFT_HALF_PI_Q16_ : -PFT_HALF_PI_Q16_;
    }
    if (bx < 0) { /* rotate by pi into the right half plane */
        bx = -bx;
        by = -by;
        off = y > 0 ? PFT_PI_Q29_ : -PFT_PI_Q29_;
    }
    /* scale so that max(|x|, |y|) is in [2^28, 2^29): CORDIC growth 1.65 * sqrt 2 < 2^31 / 2^29 */
    mag = (uint64_t)(bx > (by < 0 ? -by : by) ? bx : (by < 0 ? -by : by));
    for (i = 0; i < 32 && (mag << sh) < ((uint64_t)1 << 28); ++i) {
        ++sh;
    }
    if (sh > 0) {
        cx = (int32_t)(bx * ((int64_t)1 << sh));
        cy = (int32_t)(by * ((int64_t)1 << sh));
    } else {
        for (i = 0; i < 3 && (mag >> sh) >= ((uint64_t)1 << 29); ++i) {
            ++sh;
        }
        cx = (int32_t)(bx >> sh);
        cy = (int32_t)(by >> sh);
    }
    /* vectoring CORDIC: drive cy to 0, accumulating the rotation in z (Q29) */
    for (i = 0; i < 30; ++i) {
        if (cy > 0) {
            nx = cx + (cy >> i);
            cy = cy - (cx >> i);
            z += at[i];
        } else {
            nx = cx - (cy >> i);
            cy = cy + (cx >> i);
            z -= at[i];
        }
        cx = nx;
    }
    total = (int64_t)z + off;
    total = (total + 4096) >> 13; /* Q29 -> Q16 */
    if (total > PFT_PI_Q16_) {
        total = PFT_PI_Q16_;
    } else if (total < -PFT_PI_Q16_) {
        total = -PFT_PI_Q16_;
    } else {
        /* already in [-pi, pi] */
    }
    return (pft_real_t)total;
}

/* sin(a + qoff pi/2) for Q16.16 a: reduction modulo pi/2 in Q47 (|a| 2^31 and n 2 pi 2^47
 * stay below 2^62), Taylor series in Q31. */
static pft_real_t pft_sin_q_(pft_real_t a, uint32_t qoff)
{
    static const int64_t cs[6] = {2147483648, 357913941, 17895697, 426088, 5918, 54};
    static const int64_t cc[7] = {2147483648, 1073741824, 89478485, 2982616, 53261, 592, 4};
    int64_t r = (int64_t)a * ((int64_t)1 << 31); /* Q47, exact */
    int64_t n = ((int64_t)a * PFT_INV_TWO_PI_Q32_) >> 48; /* floor(a / 2 pi), +-1 */
    int64_t t, t2, p, v;
    uint32_t q = 0;
    bool use_cos, neg;
    int i;
    r -= n * PFT_TWO_PI_Q47_;
    for (i = 0; i < 2; ++i) {
        if (r < 0) {
            r += PFT_TWO_PI_Q47_;
        } else if (r >= PFT_TWO_PI_Q47_) {
            r -= PFT_TWO_PI_Q47_;
        } else {
            /* r already in [0, 2 pi) */
        }
    }
    for (i = 0; i < 3 && r >= PFT_HALF_PI_Q47_; ++i) {
        r -= PFT_HALF_PI_Q47_;
        ++q;
    }
    q = (q + qoff) & 3u;
    /* value = [sin r, cos r, -sin r, -cos r][q], r in [0, pi/2) */
    use_cos = (q & 1u) != 0;
    neg = q >= 2u;
    if (r > PFT_QUARTER_PI_Q47_) {
        r = PFT_HALF_PI_Q47_ - r;
        use_cos = !use_cos;
    }
    t = (r + 32768) >> 16; /* Q31, <= pi/4 */
    t2 = (t * t + ((int64_t)1 << 30)) >> 31;
    if (use_cos) {
        p = cc[6];
        for (i = 5; i >= 0; --i) {
            p = cc[i] - ((t2 * p + ((int64_t)1 << 30)) >> 31);
        }
        v = p;
    } else {
        p = cs[5];
        for (i = 4; i >= 0; --i) {
            p = cs[i] - ((t2 * p + ((int64_t)1 << 30)) >> 31);
        }
        v = (t * p + ((int64_t)1 << 30)) >> 31;
    }
    v = (v + 16384) >> 15; /* Q31 -> Q16, v >= 0 */
    return neg ? -(pft_real_t)v : (pft_real_t)v;
}

pft_real_t pft_sin(pft_real_t a)
{
    return pft_sin_q_(a, 0u);
}

pft_real_t pft_cos(pft_real_t a)
{
    return pft_sin_q_(a, 1u);
}

pft_real_t pft_from_f32(float v)
{
    uint32_t bits, mant, ex;
    int32_t s;
    uint64_t mag;
    memcpy(&bits, &v, sizeof bits);
    ex = (bits >> 23) & 0xFFu;
    mant = bits & 0x7FFFFFu;
    if (ex == 0xFFu) { /* NaN -> 0, infinities saturate */
        if (mant != 0) {
            return 0;
        }
        return (bits >> 31) != 0 ? PFT_REAL_MIN : PFT_REAL_MAX;
    }
    if (ex == 0) { /* zero or subnormal (< 2^-126): rounds to 0 */
        return 0;
    }
    mant |= 0x800000u;
    /* value = mant * 2^(ex - 150); in Q16: mant * 2^(ex - 134) */
    s = (int32_t)ex - 134;
    if (s > 7) {
        mag = (uint64_t)1 << 32; /* >= 2^31: saturates */
    } else if (s >= 0) {
        mag = (uint64_t)mant << s;
    } else if (s >= -25) {
        mag = ((uint64_t)mant + ((uint64_t)1 << (-s - 1))) >> (-s); /* nearest, ties away */
    } else {
        mag = 0;
    }
    return pft_q16_signed_sat_(mag, (bits >> 31) != 0);
}

#else /* PFT_NUMERIC_FLOAT */

pft_real_t pft_from_f32(float v)
{
    return v;
}

pft_real_t pft_wacc_log(pft_wacc_t acc)
{
    return acc > 0.0f ? logf(acc) : PFT_REAL_MIN;
}

#endif
