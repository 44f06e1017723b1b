/* Arithmetic of the particle kernels (private, not installed): the per-particle steps written
 * once for both number types, so that tracker sources never test the build's number type.
 * Every function here is inline; the q16 ones round once and saturate once per result, with
 * int64 intermediates whose ranges are proven in the comments (docs/fixed_point.md, "Particle
 * kernels"). Right shifts of negative int64 values are arithmetic (as everywhere in the
 * library, docs/fixed_point.md).
 *
 * - pft_kmad1_, pft_kmad2_: a + b c (+ d e), one rounding.
 * - pft_kwexp_: exp(x - m) for x <= m as a weight (q16: 2^-y from a 128-step table with linear
 *   interpolation; float: 2^y by a degree-5 polynomial and the exponent bits).
 * - pft_krecip_, pft_kwnorm_, pft_kess_: normalisation by one reciprocal per set instead of a
 *   division per particle, and the effective sample size from the sums.
 * - pft_kcell_: the pixel of a position (round to nearest, ties up) and the offset from its
 *   centre, or "outside".
 * - pft_ktaps_: three tabulated PSF taps and the sum of their squares at an offset
 *   (PFT_KTAP_STEPS rows per pixel of values and differences, linear interpolation).
 * - pft_kspot3_, pft_kspot_: the log likelihood ratio of a separable spot of amplitude a on a
 *   whitened (noise-normalised) window: a sum_ij tx_i ty_j z_ij - a^2/2 (sum tx^2)(sum ty^2).
 * - pft_kmulq_: a b rounded (ties up), saturated: a cheaper pft_mul for products of proven
 *   range; pft_kmulr_ the same without saturation where the caller proves the range;
 *   pft_kspread_: a position difference limited (q16) so that its square fits;
 *   pft_kmula_, pft_kaddr_: pft_mul and pft_add without saturation (the same bits where the
 *   caller proves the range); pft_kres16_: a RES16 pixel (Q8.8) as a real, exactly;
 *   pft_kmul_r16_: pft_kmula_ of a tap (prepared by pft_kr16_tap_) and a RES16 value (or the
 *   sum of two) given as integers, the same bits without converting them; pft_kmul_u_:
 *   pft_kmula_ of a tap in [0, 1] and a value below 2^14 in 32-bit arithmetic;
 *   pft_kr16_one_pays_: whether pft_kres16_ should stand for pft_kmul_r16_ of the tap 1.
 * - pft_kspot3_r16_: pft_kspot3_ on a 3 x 3 window of RES16 pixels read in place, the same
 *   bits from the integers (the scale 1/256 applied once per window instead of per pixel; in
 *   float only where pft_kr16_sum_ok_ holds for every tap the window can get); in float with
 *   16-byte vectors (SSE2, NEON) the window's first eight pixels in one array of 16-bit lanes.
 * - pft_kspot3_r16t_ (float with SSE2 or AArch64 NEON only): pft_ktaps_ of both axes' table
 *   rows and pft_kspot3_r16_ in one, the taps as vectors and the window's rows as lanes
 *   (intrinsics), the same bits.
 * - pft_kwexp_lanes_ (float with 16-byte vectors): pft_kwexp_ of a row of values in place,
 *   every test as a bit mask, so that the row vectorises (the same bits).
 * - pft_kfrom_f32_: pft_from_f32 inline where it is the identity (float).
 * - pft_kround64_: pft_round_int(pft_mul_i(pft_clamp(a, -257, 257), 64)) (the integration's
 *   bins, tbd_meas.c), the same value in plain 32-bit lanes (no int64, no floorf, float
 *   selections as bit masks) so that a row of them vectorises.
 */
#ifndef PFT_CORE_KERN_INT_H
#define PFT_CORE_KERN_INT_H

#include <string.h>

#include "pft/pft_real.h"

#if !defined(PFT_NUMERIC_Q16) && defined(__SSE2__)
#include <emmintrin.h>
#elif !defined(PFT_NUMERIC_Q16) && defined(__aarch64__) && defined(__ARM_NEON)
#include <arm_neon.h>
#endif

/** Rows of a tap table per pixel: offsets f = -1/2 + n / PFT_KTAP_STEPS, n = 0..STEPS - 1; a
 *  row holds the values of four lanes at f_n and their differences to f_{n+1}. */
#define PFT_KTAP_STEPS 64u

extern const uint32_t pft_kexp2_tab[129];

/* A RES16 pixel as an integer, a masked pixel 0 (pft_kres16_ of it is the pixel's real). */
static inline int32_t pft_kr16_int_(const uint8_t *p)
{
    int16_t v;
    memcpy(&v, p, 2u);
    return v != INT16_MIN ? (int32_t)v : 0; /* INT16_MIN: PFT_RES16_MASKED */
}
/* The same value as an addition to the pixel: x, or x + 2^15 = 0 for the masked value (gcc
 * 12 makes the constant's select a flag, no branch). The float build's pft_kspot3_r16_ reads
 * its pixels with it where the compiler has no 16-byte vectors (with them: its ninth pixel):
 * there gcc (12, AArch64 and x86-64) turned pft_kr16_int_'s select into a branch around each
 * pixel's conversion, nine per 3 x 3 window, and no instruction is scheduled across a branch,
 * so an in-order core (the Cortex-A53) waited on each pixel's load, conversion and product in
 * turn. The q16 build keeps
 * pft_kr16_int_ (its products take the integer, and a mask form there cost more). */
static inline int32_t pft_kr16_intb_(const uint8_t *p)
{
    int16_t v;
    int32_t x;
    memcpy(&v, p, 2u);
    x = (int32_t)v;
    return x + (x == (int32_t)INT16_MIN ? 32768 : 0);
}

#ifdef PFT_NUMERIC_Q16

typedef uint64_t pft_krecip_t;

/* pft_sat64_ for values that are almost always in range: one unsigned comparison decides (v is
 * in [-INT32_MAX, INT32_MAX] exactly when v + INT32_MAX is in [0, 2 INT32_MAX]), the clamp
 * is the rare branch. */
static inline pft_real_t pft_ksat_(int64_t v)
{
    if ((uint64_t)(v + INT32_MAX) > (uint64_t)2 * INT32_MAX) {
        return v > 0 ? PFT_REAL_MAX : PFT_REAL_MIN;
    }
    return (pft_real_t)v;
}

/* a + b c rounded once, saturated: |a 2^16| <= 2^47, |b c| <= 2^62, sum < 2^63. */
static inline pft_real_t pft_kmad1_(pft_real_t a, pft_real_t b, pft_real_t c)
{
    return pft_ksat_(((int64_t)a * 65536 + (int64_t)b * c + 32768) >> 16);
}
/* a + b c + d e rounded once, saturated; |e| < 2^24 (|e| < 256, e.g. a Gaussian draw), so
 * |d e| < 2^55 and the sum stays below 2^62 + 2^55 + 2^48 < 2^63. */
static inline pft_real_t pft_kmad2_(pft_real_t a, pft_real_t b, pft_real_t c, pft_real_t d,
                                    pft_real_t e)
{
    return pft_ksat_(((int64_t)a * 65536 + (int64_t)b * c + (int64_t)d * e + 32768) >> 16);
}

/* exp(x - m), x <= m, in Q2.30: t = m - x exactly as a uint32 (< 2^32); y = t log2(e) in
 * Q24 (t < 22 2^16 times log2(e) in Q28 < 2^50), 2^-frac(y) from the Q30 table by linear
 * interpolation ((T[j] - T[j+1]) < 2^23 times a 9-bit fraction < 2^32), shifted right by
 * floor(y) with rounding. Relative error below 4e-6 plus the final rounding; x = m gives
 * exactly PFT_W_ONE, m - x >= 22 gives 0. */
static inline pft_weight_t pft_kwexp_(pft_real_t x, pft_real_t m)
{
    uint32_t t, u, k, fr, j, r, d, v;
    if (x >= m) {
        return PFT_W_ONE;
    }
    t = (uint32_t)m - (uint32_t)x;
    if (t >= (22u << 16)) {
        return 0u;
    }
    u = (uint32_t)(((uint64_t)t * 387270501u) >> 20); /* log2(e) in Q28 */
    k = u >> 24;
    fr = u & 0xFFFFFFu;
    j = fr >> 17;
    r = (fr >> 8) & 0x1FFu;
    d = pft_kexp2_tab[j] - pft_kexp2_tab[j + 1u];
    v = pft_kexp2_tab[j] - ((d * r) >> 9);
    return (v + ((1u << k) >> 1)) >> k;
}

/* pft_kwexp_ of two values (the float build overlaps their polynomials). */
static inline void pft_kwexp2_(pft_real_t xa, pft_real_t xb, pft_real_t m, pft_weight_t *ea,
                               pft_weight_t *eb)
{
    *ea = pft_kwexp_(xa, m);
    *eb = pft_kwexp_(xb, m);
}

/* 2^62 / s for a weight sum s >= 2^30 (the largest weight is PFT_W_ONE): at most 2^32. */
static inline pft_krecip_t pft_krecip_(pft_wacc_t s)
{
    return s > 0u ? ((uint64_t)1 << 62) / s : 0u;
}
/* e / s in Q2.30 from e <= 2^30 and r = 2^62 / s: e r <= 2^62. */
static inline pft_weight_t pft_kwnorm_(pft_weight_t e, pft_krecip_t r)
{
    return (pft_weight_t)(((uint64_t)e * r) >> 32);
}
/* ESS = w^2 / w2 for w = sum of normalised weights (<= 2^30, so w^2 <= 2^60) and w2 = their
 * sum of squares (>= w^2 / n >= 2^38 for n <= 2^22), as Q16.16 saturated at 32768. */
static inline pft_real_t pft_kess_(pft_wacc_t w, pft_wacc_t w2)
{
    uint64_t d = w2 >> 16;
    uint64_t q;
    if (d == 0u) {
        return 0;
    }
    q = (w * w + d / 2u) / d;
    return q > (uint64_t)INT32_MAX ? PFT_REAL_MAX : (pft_real_t)q;
}

/* The offset f of a position from its pixel's centre, kept as (f + 1/2) 2^16 in [0, 2^16):
 * the tap table's row is its top 6 bits, the interpolation fraction the next 10. */
typedef uint32_t pft_kfrac_t;

/* The pixel i in [1, n] whose centre (at i) is nearest to u (ties up) and the offset of u from
 * it; false when u is outside [1/2, hi) with hi = n + 1/2 (n <= 2^14, so no sum overflows). */
static inline bool pft_kcell_(pft_real_t u, pft_real_t hi, int32_t n, int32_t *i, pft_kfrac_t *g)
{
    uint32_t t;
    (void)n;
    /* u in [2^15, hi) as one unsigned comparison (u - 2^15 wraps for u < 2^15) */
    if ((uint32_t)u - 32768u >= (uint32_t)hi - 32768u) {
        return false;
    }
    t = (uint32_t)u + 32768u;
    *i = (int32_t)(t >> 16);
    *g = t & 0xFFFFu;
    return true;
}

/* pft_kcell_ of both coordinates of a position: (u, pixel i, offset g) and (v, j, h). */
static inline bool pft_kcell2_(pft_real_t u, pft_real_t v, pft_real_t hu, pft_real_t hv,
                               int32_t nu, int32_t nv, int32_t *i, pft_kfrac_t *g, int32_t *j,
                               pft_kfrac_t *h)
{
    return pft_kcell_(u, hu, nu, i, g) && pft_kcell_(v, hv, nv, j, h);
}

/* f = u - i as a real. */
static inline pft_real_t pft_kfrac_off_(pft_kfrac_t g) { return (pft_real_t)g - 32768; }

/* t[k] = tab(f)[k], k = 0..3 (lane 3: the sum of the squared taps): row n = g >> 10,
 * t = v + (d r) >> 10 with r = g mod 2^10 (|d| <= 2^17, so the product stays below 2^27; the
 * floor costs at most 1 LSB, far below the interpolation error). */
static inline void pft_ktaps_(const pft_real_t (*tab)[8], pft_kfrac_t g, pft_real_t t[4])
{
    const int32_t r = (int32_t)(g & 1023u);
    const pft_real_t *a = tab[g >> 10];
    for (int k = 0; k < 4; ++k) {
        t[k] = a[k] + ((a[k + 4] * r) >> 10);
    }
}

/* A position difference for second moments: clamped to +-181 so that a product of two stays
 * below 32768 (181^2 = 32761). */
static inline pft_real_t pft_kspread_(pft_real_t d)
{
    if ((uint32_t)(d + PFT_C(181.0)) > (uint32_t)PFT_C(362.0)) { /* |d| > 181, rare */
        return d > 0 ? PFT_C(181.0) : PFT_C(-181.0);
    }
    return d;
}

/* a b rounded to nearest (ties up) for |a b| < 32768 (the caller proves it). */
static inline pft_real_t pft_kmulr_(pft_real_t a, pft_real_t b)
{
    return (pft_real_t)(((int64_t)a * b + 32768) >> 16);
}

/* a b rounded to nearest, ties away from zero (pft_mul's rounding, so the same bits as
 * pft_mul) without saturation, for |a b| < 2^46 (the caller proves it). */
static inline pft_real_t pft_kmula_(pft_real_t a, pft_real_t b)
{
    const int64_t p = (int64_t)a * b;
    return (pft_real_t)((p + (p >= 0 ? (int64_t)32768 : (int64_t)32767)) >> 16);
}
/* a + b without saturation (pft_add's bits where the caller proves |a + b| <= INT32_MAX). */
static inline pft_real_t pft_kaddr_(pft_real_t a, pft_real_t b) { return a + b; }
/* A RES16 value (Q8.8 sigma) as a real, exactly (res / 256). */
static inline pft_real_t pft_kres16_(int16_t res) { return (pft_real_t)((int32_t)res * 256); }
/* Whether a caller should take pft_kres16_(a) for pft_kmul_r16_(pft_kr16_tap_(1), a, 0) (the
 * same value in both builds): q16 yes (one shift against two widening products and the
 * rounding); float no (one product either way, so the caller keeps one loop). */
static inline bool pft_kr16_one_pays_(void) { return true; }
/* A tap prepared for pft_kmul_r16_ (q16: the tap itself), and whether the helpers below apply
 * to it (q16: 0 <= t <= 1). */
static inline pft_real_t pft_kr16_tap_(pft_real_t t) { return t; }
static inline bool pft_kr16_tap_ok_(pft_real_t t) { return t >= 0 && t <= PFT_REAL_ONE; }
/* pft_kmula_(t, z) for z = (a + b) / 256 with RES16 integers a, b (|a|, |b| <= 32767, as
 * pft_kres16_ reads them; b = 0 for one value) and 0 <= t <= 2^16, in 32-bit arithmetic: z is
 * 256 (a + b) in Q16, so p = 256 q with q = t (a + b), and (p + 32768) >> 16 = (q + 128) >> 8
 * for p >= 0, (p + 32767) >> 16 = (q + 127) >> 8 for p < 0 (256 (q + 127) + 255 never reaches
 * the next multiple of 2^16). With t = 256 th + tl (th <= 256, tl < 256): the result is
 * th (a + b) + (tl (a + b) + 128 - [a + b < 0]) >> 8, every term below 2^25, each product
 * of two int16 values (compilers vectorise them as widening multiplies). The same bits,
 * without the conversion. */
static inline pft_real_t pft_kmul_r16_(pft_real_t t, int16_t a, int16_t b)
{
    const int16_t th = (int16_t)(t >> 8);
    const int16_t tl = (int16_t)(t & 255);
    const int32_t sum = (int32_t)a + (int32_t)b;
    const int32_t neg = sum < 0 ? (int32_t)1 : (int32_t)0;
    /* products of two int16 values (widening multiplies) */
    return (int32_t)th * a + (int32_t)th * b +
           (((int32_t)tl * a + (int32_t)tl * b + 128 - neg) >> 8);
}
/* pft_kmula_(t, z) for 0 <= t <= 2^16 and |z| < 2^30 in 32-bit arithmetic: with z = 2^16 zh +
 * zl (zh = z >> 16, 0 <= zl < 2^16), p = 2^16 t zh + t zl, so the rounded product is
 * t zh + (t zl + 32768 - [z < 0]) >> 16 (t zl + 32768 < 2^32 in unsigned arithmetic;
 * |t zh| <= 2^30). The same bits as pft_kmula_. */
static inline bool pft_kmul_u_ok_(pft_real_t t) { return t >= 0 && t <= PFT_REAL_ONE; }
static inline pft_real_t pft_kmul_u_(pft_real_t t, pft_real_t z)
{
    const uint32_t zl = (uint32_t)z & 0xFFFFu;
    const int32_t zh = z >> 16;
    const uint32_t r = ((uint32_t)t * zl + 32768u - (z < 0 ? 1u : 0u)) >> 16;
    return t * zh + (int32_t)r;
}

/* An F32 pixel as a real: pft_from_f32 (q16: the IEEE decoding). */
static inline pft_real_t pft_kfrom_f32_(float v) { return pft_from_f32(v); }
/* a clamped to [-257, 257] (in 2^16 units); then |a| 64 + 2^15 <= 16448 * 2^16 + 2^15 < 2^31, so
 * pft_mul_i does not saturate and the sum fits 32 bits; the shift is pft_round_int's
 * (arithmetic). */
static inline int32_t pft_kround64_(pft_real_t a)
{
    const pft_real_t lim = 257 * 65536;
    const pft_real_t a1 = a < -lim ? -lim : a;
    const pft_real_t a2 = a1 > lim ? lim : a1;
    return (a2 * 64 + 32768) >> 16;
}

/* a b rounded to nearest (ties up) and saturated. */
static inline pft_real_t pft_kmulq_(pft_real_t a, pft_real_t b)
{
    return pft_ksat_(((int64_t)a * b + 32768) >> 16);
}

/* The spot LLR from the window sums: s1 = sum ty (sum tx z) in Q32, sx2, sy2 = sums of
 * squared taps in Q16 (<= 9 2^16). q = sx2 sy2 in Q16 (< 81 2^16); d = s1 - a q / 2 in Q32
 * (|s1| < 2^53.4 for 9 x 9 windows of |z| < 2^31 and taps <= 2^16, |a q| < 2^54);
 * result a d in Q16 via d16 = round(d / 2^16) = h 2^16 + l, a h + round(a l / 2^16),
 * |a h| < 2^55. One saturation. */
static inline pft_real_t pft_kspot_end_(int64_t s1, int64_t sx2, int64_t sy2, pft_real_t a)
{
    const int64_t q = (sx2 * sy2 + 32768) >> 16;
    const int64_t d = s1 - (((int64_t)a * q) >> 1);
    const int64_t d16 = (d + 32768) >> 16;
    const int64_t h = d16 >> 16;
    const int64_t l = d16 & 0xFFFF;
    return pft_ksat_((int64_t)a * h + (((int64_t)a * l + 32768) >> 16));
}

/* One row: sum tx z (Q32, |.| < 3 2^47), then to Q16 (int64, rounded). */
static inline int64_t pft_krow3_(const pft_real_t *z, const pft_real_t tx[3])
{
    return ((int64_t)tx[0] * z[0] + (int64_t)tx[1] * z[1] + (int64_t)tx[2] * z[2] + 32768) >> 16;
}

/* The 3 x 3 spot LLR; z points at the window's top-left pixel, rows stride apart; tx[3] and
 * ty[3] are the sums of the squared taps. */
static inline pft_real_t pft_kspot3_(const pft_real_t *z, size_t stride, const pft_real_t tx[4],
                                     const pft_real_t ty[4], pft_real_t a)
{
    const int64_t s1 = ty[0] * pft_krow3_(z, tx) + ty[1] * pft_krow3_(z + stride, tx) +
                       ty[2] * pft_krow3_(z + 2u * stride, tx);
    return pft_kspot_end_(s1, tx[3], ty[3], a);
}

/* Whether the taps of a table row (value t, difference d to the next row; every tap the
 * linear interpolation of pft_ktaps_ can give lies between t and t + d) let pft_kspot3_r16_
 * give pft_kspot3_'s bits: always in q16. */
static inline bool pft_kr16_sum_ok_(pft_real_t t, pft_real_t d)
{
    (void)t;
    (void)d;
    return true;
}

/* pft_kspot3_ on the 3 x 3 RES16 window whose top-left pixel is at p (rows st bytes apart),
 * every pixel read as pft_kres16_ of pft_kr16_int_: with z = 256 v (Q16.16 of v / 256) a row's
 * 2^16-scaled sum is 256 S for S = sum tx v, and floor((256 S + 2^15) / 2^16) =
 * floor((S + 2^7) / 2^8) exactly, so pft_krow3_ is (S + 128) >> 8 without the conversion
 * (|S| < 3 2^31, int64). The rest is pft_kspot3_'s. */
static inline pft_real_t pft_kspot3_r16_(const uint8_t *p, size_t st, const pft_real_t tx[4],
                                         const pft_real_t ty[4], pft_real_t a)
{
    int64_t s1 = 0;
    for (uint32_t b = 0; b < 3u; ++b) {
        const uint8_t *q = p + (size_t)b * st;
        const int64_t r = ((int64_t)tx[0] * pft_kr16_int_(q) + (int64_t)tx[1] * pft_kr16_int_(q + 2u) +
                           (int64_t)tx[2] * pft_kr16_int_(q + 4u) + 128) >>
                          8;
        s1 += ty[b] * r;
    }
    return pft_kspot_end_(s1, tx[3], ty[3], a);
}

/* The same for an nx x ny window (n <= 9): the arithmetic of pft_kspot3_ exactly. */
static inline pft_real_t pft_kspot_(const pft_real_t *z, size_t stride, const pft_real_t *tx,
                                    uint32_t nx, const pft_real_t *ty, uint32_t ny, pft_real_t a)
{
    int64_t s1 = 0, sx2 = 0, sy2 = 0;
    for (uint32_t j = 0; j < ny; ++j) {
        int64_t r = 0;
        for (uint32_t i = 0; i < nx; ++i) {
            r += (int64_t)tx[i] * z[(size_t)j * stride + i];
        }
        s1 += ty[j] * ((r + 32768) >> 16);
        sy2 += (int64_t)ty[j] * ty[j];
    }
    for (uint32_t i = 0; i < nx; ++i) {
        sx2 += (int64_t)tx[i] * tx[i];
    }
    return pft_kspot_end_(s1, (sx2 + 32768) >> 16, (sy2 + 32768) >> 16, a);
}

#else /* ----------------------------------- float --------------------------------------- */

typedef float pft_krecip_t;

static inline pft_real_t pft_kmad1_(pft_real_t a, pft_real_t b, pft_real_t c) { return a + b * c; }
static inline pft_real_t pft_kmad2_(pft_real_t a, pft_real_t b, pft_real_t c, pft_real_t d,
                                    pft_real_t e)
{
    return a + b * c + d * e;
}
/* exp(x) (x = xx - m) = 2^y, y = x log2(e) = k + f with k = trunc(y) in [-125, 0] and f in
 * (-1, 0]: 2^f by
 * a degree-5 polynomial (Chebyshev nodes; relative error below 2.2e-7, measured in
 * test_kern), 2^k from the exponent bits. x = 0 gives exactly 1; x <= -87 gives 0. */
static inline pft_weight_t pft_kwexp_poly_(float x);
static inline pft_weight_t pft_kwexp_(pft_real_t xx, pft_real_t m)
{
    const float x = xx - m;
    if (x >= 0.0f) {
        return 1.0f;
    }
    if (!(x > -87.0f)) {
        return 0.0f;
    }
    return pft_kwexp_poly_(x);
}
/* pft_kwexp_ of two values, the same bits as two calls: when both x - m lie in (-87, 0) (the
 * common case) the two polynomials in one block, so that their chains of dependent FP
 * operations overlap on an in-order core (one after the other in two calls, each behind its
 * range tests' branches). */
static inline void pft_kwexp2_(pft_real_t xa, pft_real_t xb, pft_real_t m, pft_weight_t *ea,
                               pft_weight_t *eb)
{
    const float a = xa - m;
    const float b = xb - m;
    if (a < 0.0f && a > -87.0f && b < 0.0f && b > -87.0f) {
        *ea = pft_kwexp_poly_(a);
        *eb = pft_kwexp_poly_(b);
    } else {
        *ea = pft_kwexp_(xa, m);
        *eb = pft_kwexp_(xb, m);
    }
}
/* pft_kwexp_'s value for x in (-87, 0). */
static inline pft_weight_t pft_kwexp_poly_(float x)
{
    float y, f, p, sc;
    int32_t k;
    uint32_t bits;
    y = x * 1.44269504f;
    k = (int32_t)y;
    f = y - (float)k;
    p = 0.000946877000387758f;
    p = p * f + 0.009209180250763893f;
    p = p * f + 0.05529811978340149f;
    p = p * f + 0.24017895758152008f;
    p = p * f + 0.6931431293487549f;
    p = p * f + 0.9999999403953552f;
    bits = (uint32_t)(k + 127) << 23;
    memcpy(&sc, &bits, sizeof sc);
    return p * sc;
}

#if defined(__SSE2__) || defined(__ARM_NEON)
/* Where the compiler has 16-byte vectors (SSE2, NEON): pft_kwexp_(v, m) of a row of values v
 * in place (tbd_filter.c, weights_: a slot's log-weight in, its weight out, both 32-bit
 * floats, read and written through memcpy). Every value's polynomial and every test's outcome
 * as a bit mask, so that gcc vectorises the row (about 11 x86-64 instructions per value
 * against about 30 for the tests' branches and the polynomial one value at a time). The
 * polynomial's argument is x = v - m where x lies in (-87, 0), else 0 (its value then
 * unused); its operations are pft_kwexp_poly_'s in the same order, so every weight has
 * pft_kwexp_'s bits (1 for x >= 0, 0 for x <= -87 or NaN). Without vectors (Cortex-M) the
 * masks and the polynomial of every value would cost more than the branches: weights_ keeps
 * pft_kwexp2_ there. */
#define PFT_KWEXP_LANES_ 1
static inline void pft_kwexp_lanes_(void *slots, uint32_t n, float m)
{
    unsigned char *q = (unsigned char *)slots;
    uint32_t one;
    const float f1 = 1.0f;
    memcpy(&one, &f1, 4u);
    for (uint32_t s = 0; s < n; ++s) {
        float lw, xs, e;
        uint32_t xb, eb, r;
        memcpy(&lw, q + 4u * (size_t)s, 4u);
        {
            const float x = lw - m;
            const uint32_t in = (x > -87.0f) ? 0xFFFFFFFFu : 0u;
            const uint32_t neg = (x < 0.0f) ? 0xFFFFFFFFu : 0u;
            const uint32_t ok = in & neg;
            memcpy(&xb, &x, 4u);
            xb &= ok;
            memcpy(&xs, &xb, 4u);
            e = pft_kwexp_poly_(xs);
            memcpy(&eb, &e, 4u);
            r = (eb & ok) | (one & in & ~neg);
        }
        memcpy(q + 4u * (size_t)s, &r, 4u);
    }
}
#endif
static inline pft_krecip_t pft_krecip_(pft_wacc_t s) { return s > 0.0f ? 1.0f / s : 0.0f; }
static inline pft_weight_t pft_kwnorm_(pft_weight_t e, pft_krecip_t r) { return e * r; }
static inline pft_real_t pft_kess_(pft_wacc_t w, pft_wacc_t w2)
{
    return w2 > 0.0f ? w * w / w2 : 0.0f;
}

/* The offset f of a position from its pixel's centre as the tap table's row n and the
 * fraction r within it: (f + 1/2) STEPS = n + r. */
typedef struct {
    int32_t n;
    float r;
} pft_kfrac_t;

/* u in [1/2, hi) with hi = n + 1/2 exactly as in q16; t = (u + 1/2) STEPS is truncated once
 * (a floor: t >= STEPS > 0) into the pixel and the row. When u is just below hi the product
 * may round up to (n + 1) STEPS: then the last row of pixel n at r = 1. */
static inline bool pft_kcell_(pft_real_t u, pft_real_t hi, int32_t n, int32_t *i, pft_kfrac_t *g)
{
    float t;
    int32_t q;
    if (!(u >= 0.5f && u < hi)) {
        return false;
    }
    t = (u + 0.5f) * (float)PFT_KTAP_STEPS;
    q = (int32_t)t;
    *i = q >> 6;
    if (*i > n) {
        *i = n;
        g->n = (int32_t)PFT_KTAP_STEPS - 1;
        g->r = 1.0f;
        return true;
    }
    g->n = q & ((int32_t)PFT_KTAP_STEPS - 1);
    g->r = t - (float)q;
    return true;
}

/* pft_kcell_ of both coordinates of a position: (u, pixel i, offset g) and (v, j, h), the same
 * values as two calls. Both range tests come first, then both coordinates' arithmetic in one
 * block, then the rare clamps: two calls put a branch after each coordinate's chain of
 * dependent FP operations, so an in-order core ran the two chains one after the other. */
static inline bool pft_kcell2_(pft_real_t u, pft_real_t v, pft_real_t hu, pft_real_t hv,
                               int32_t nu, int32_t nv, int32_t *i, pft_kfrac_t *g, int32_t *j,
                               pft_kfrac_t *h)
{
    float tu, tv;
    int32_t qu, qv;
    if (!(u >= 0.5f && u < hu) || !(v >= 0.5f && v < hv)) {
        return false;
    }
    tu = (u + 0.5f) * (float)PFT_KTAP_STEPS;
    tv = (v + 0.5f) * (float)PFT_KTAP_STEPS;
    qu = (int32_t)tu;
    qv = (int32_t)tv;
    *i = qu >> 6;
    *j = qv >> 6;
    g->n = qu & ((int32_t)PFT_KTAP_STEPS - 1);
    g->r = tu - (float)qu;
    h->n = qv & ((int32_t)PFT_KTAP_STEPS - 1);
    h->r = tv - (float)qv;
    if (*i > nu) {
        *i = nu;
        g->n = (int32_t)PFT_KTAP_STEPS - 1;
        g->r = 1.0f;
    }
    if (*j > nv) {
        *j = nv;
        h->n = (int32_t)PFT_KTAP_STEPS - 1;
        h->r = 1.0f;
    }
    return true;
}

static inline pft_real_t pft_kfrac_off_(pft_kfrac_t g)
{
    return ((float)g.n + g.r) * (1.0f / (float)PFT_KTAP_STEPS) - 0.5f;
}

static inline void pft_ktaps_(const pft_real_t (*tab)[8], pft_kfrac_t g, pft_real_t t[4])
{
    const pft_real_t *a = tab[g.n];
    for (int k = 0; k < 4; ++k) {
        t[k] = a[k] + g.r * a[k + 4];
    }
}

static inline pft_real_t pft_kmulq_(pft_real_t a, pft_real_t b) { return a * b; }
static inline pft_real_t pft_kmulr_(pft_real_t a, pft_real_t b) { return a * b; }
static inline pft_real_t pft_kmula_(pft_real_t a, pft_real_t b) { return a * b; }
static inline pft_real_t pft_kaddr_(pft_real_t a, pft_real_t b) { return a + b; }
static inline pft_real_t pft_kres16_(int16_t res) { return (pft_real_t)res * 0.00390625f; }
static inline bool pft_kr16_one_pays_(void) { return false; }
/* t 2^-8: then t' (a + b) is t ((a + b) 2^-8) to the bit (the same real number, rounded once),
 * when t' is exact (pft_kr16_tap_ok_: t 2^-8 is not a subnormal that lost bits). */
static inline pft_real_t pft_kr16_tap_(pft_real_t t) { return t * 0.00390625f; }
static inline bool pft_kr16_tap_ok_(pft_real_t t) { return (t * 0.00390625f) * 256.0f == t; }
static inline pft_real_t pft_kmul_r16_(pft_real_t t, int16_t a, int16_t b)
{
    return t * (float)((int32_t)a + (int32_t)b);
}
static inline bool pft_kmul_u_ok_(pft_real_t t)
{
    (void)t;
    return true;
}
static inline pft_real_t pft_kmul_u_(pft_real_t t, pft_real_t z) { return t * z; }
static inline pft_real_t pft_kspread_(pft_real_t d) { return d; }
/* pft_from_f32 is the identity in the float build: no call per pixel. */
static inline pft_real_t pft_kfrom_f32_(float v) { return v; }
/* x = 64 a is 64 pft_clamp(a, -257, 257) clamped to [-16448, 16448] (a power of two scales
 * exactly; an overflow gives an infinity, clamped as a would be). The selections as masks
 * from compares of x itself (the compiler vectorises no compare of a selected float): below,
 * above, NaN (0, as pft_round_int). In range, the truncation t of x and f = x - t are exact (|x|
 * < 2^15), and t + (f >= 1/2) - (f < -1/2) is pft_round_int's floorf(x) + (x - floorf(x) >=
 * 1/2) (for x < 0 not integral floorf(x) = t - 1 and x - floorf(x) = f + 1); out of range xs
 * is 0 and the mask picks the limit. */
static inline int32_t pft_kround64_(pft_real_t a)
{
    const float x = a * 64.0f;
    const uint32_t lo = (x < -16448.0f) ? 0xFFFFFFFFu : 0u;
    const uint32_t hi = (x > 16448.0f) ? 0xFFFFFFFFu : 0u;
    const uint32_t ok = ~(lo | hi) & ((x == x) ? 0xFFFFFFFFu : 0u);
    uint32_t bits;
    memcpy(&bits, &x, sizeof bits);
    bits &= ok;
    float xs;
    memcpy(&xs, &bits, sizeof xs);
    const int32_t t = (int32_t)xs;
    const float f = xs - (float)t;
    const uint32_t r = (uint32_t)t + ((f >= 0.5f) ? 1u : 0u) - ((f < -0.5f) ? 1u : 0u);
    return (int32_t)((r & ok) | ((uint32_t)-16448 & lo) | (16448u & hi));
}

static inline pft_real_t pft_kspot3_(const pft_real_t *z, size_t stride, const pft_real_t tx[4],
                                     const pft_real_t ty[4], pft_real_t a)
{
    const pft_real_t *z1 = z + stride;
    const pft_real_t *z2 = z1 + stride;
    const float s1 = ty[0] * (tx[0] * z[0] + tx[1] * z[1] + tx[2] * z[2]) +
                     ty[1] * (tx[0] * z1[0] + tx[1] * z1[1] + tx[2] * z1[2]) +
                     ty[2] * (tx[0] * z2[0] + tx[1] * z2[1] + tx[2] * z2[2]);
    return a * (s1 - 0.5f * a * tx[3] * ty[3]);
}

/* float: tx (v 2^-8) rounds to (tx v) 2^-8 exactly, and sums and products of such values to
 * 2^-8 times those of the unscaled ones, as long as no result is a subnormal that lost bits.
 * With every tap 0 or at least 2^-19 (the interpolated tap t + r d, 0 <= r <= 1, is at least
 * min(t, fl(t + d)): checked on the row), a nonzero product tx v (|v| >= 1) is at least 2^-19,
 * so a multiple of 2^-42, a nonzero row sum at least 2^-42, ty times it at least 2^-61 and the
 * window sum, scaled, at least 2^-92: every scaled value normal or 0 (a clipped tap is 0). */
static inline bool pft_kr16_sum_ok_(pft_real_t t, pft_real_t d)
{
    const float lo = 1.9073486328125e-6f; /* 2^-19 */
    return t >= lo && t + d >= lo;
}

/* pft_kspot3_ on a 3 x 3 RES16 window (pixels v as integers, z = v 2^-8): the window sum from
 * the integers, scaled by 2^-8 once, is pft_kspot3_'s s1 to the bit when every tap passed
 * pft_kr16_sum_ok_ (the same operations in the same order). */
#if defined(__SSE2__) || defined(__ARM_NEON)
/* Where the compiler has 16-byte vectors (SSE2, NEON): the window's first eight pixels go
 * through one array of 16-bit lanes, so that the masked value's 0 (the value times 1 or 0, as
 * peak_hrow_r16_ in tbd_meas.c) and the conversion to float are vector operations (gcc 12
 * x86-64: pcmpeqw, pandn, two cvtdq2ps) instead of five integer instructions and a conversion
 * per pixel; the ninth pixel as pft_kr16_intb_. Every z is the pixel's integer (or 0), exact
 * in a float, and the sums below take them in pft_kr16_intb_'s form's order: the same bits.
 * Without vectors (Cortex-M) the array would go through memory: the form after #else. */
/* gcc unrolls the eight-pixel loop before its vectoriser sees it when the kernel is inlined
 * into a particle loop (the scalar code then is no cheaper than the form after #else): kept
 * rolled, it becomes one vector of eight lanes */
#if defined(__GNUC__) && !defined(__clang__)
#define PFT_KLANES_LOOP_ _Pragma("GCC unroll 1")
#else
#define PFT_KLANES_LOOP_
#endif
static inline pft_real_t pft_kspot3_r16_(const uint8_t *p, size_t st, const pft_real_t tx[4],
                                         const pft_real_t ty[4], pft_real_t a)
{
    int16_t v[8];
    float z[9];
    memcpy(v, p, 6u);
    memcpy(v + 3, p + st, 6u);
    memcpy(v + 6, p + 2u * st, 4u);
    PFT_KLANES_LOOP_
    for (uint32_t k = 0; k < 8u; ++k) {
        const int16_t y = (int16_t)((int32_t)v[k] * (v[k] != INT16_MIN ? 1 : 0));
        z[k] = (float)y;
    }
    z[8] = (float)pft_kr16_intb_(p + 2u * st + 4u);
    {
        const float r0 = tx[0] * z[0] + tx[1] * z[1] + tx[2] * z[2];
        const float r1 = tx[0] * z[3] + tx[1] * z[4] + tx[2] * z[5];
        const float r2 = tx[0] * z[6] + tx[1] * z[7] + tx[2] * z[8];
        const float s1 = (ty[0] * r0 + ty[1] * r1 + ty[2] * r2) * 0.00390625f;
        return a * (s1 - 0.5f * a * tx[3] * ty[3]);
    }
}
#else
static inline pft_real_t pft_kspot3_r16_(const uint8_t *p, size_t st, const pft_real_t tx[4],
                                         const pft_real_t ty[4], pft_real_t a)
{
    const uint8_t *p1 = p + st;
    const uint8_t *p2 = p1 + st;
    const float r0 = tx[0] * (float)pft_kr16_intb_(p) + tx[1] * (float)pft_kr16_intb_(p + 2u) +
                     tx[2] * (float)pft_kr16_intb_(p + 4u);
    const float r1 = tx[0] * (float)pft_kr16_intb_(p1) + tx[1] * (float)pft_kr16_intb_(p1 + 2u) +
                     tx[2] * (float)pft_kr16_intb_(p1 + 4u);
    const float r2 = tx[0] * (float)pft_kr16_intb_(p2) + tx[1] * (float)pft_kr16_intb_(p2 + 2u) +
                     tx[2] * (float)pft_kr16_intb_(p2 + 4u);
    const float s1 = (ty[0] * r0 + ty[1] * r1 + ty[2] * r2) * 0.00390625f;
    return a * (s1 - 0.5f * a * tx[3] * ty[3]);
}
#endif

#if defined(__SSE2__)
/* pft_ktaps_ of both axes and pft_kspot3_r16_ in one (x86-64, SSE2 intrinsics): the taps as
 * one vector per axis (a + r d in each lane: pft_ktaps_'s product and sum), and the window's
 * rows as the lanes of its columns, read with three 32-bit and three 16-bit loads and put in
 * column order by four unpacks (c0 = z0 z3 z6, c1 = z1 z4 z7, c2 = z2 z5 z8, lane 3 zero), the
 * masked value's 0 as in the eight-lane form (compare, and-not), each lane sign-extended and
 * converted. Lane b of (tx0 c0 + tx1 c1) + tx2 c2 is row b's sum in pft_kspot3_r16_'s order,
 * and (ty0 r0 + ty1 r1) + ty2 r2 its window sum in its order: every operation the same IEEE
 * single operation on the same values (lane 3 is not used), so the same bits. About 60
 * instructions per window against about 120 for the taps and the eight-lane form (gcc 12,
 * whose vectoriser found no such form in plain C). Defined here and for AArch64 (below,
 * PFT_KSPOT3_R16T_LANES_): the Cortex-M builds and q16 keep pft_ktaps_ and pft_kspot3_r16_
 * (tbd_int.h, pft_tbd_llr3_r16_v_), the same code as before. */
#define PFT_KSPOT3_R16T_LANES_ 1
static inline pft_real_t pft_kspot3_r16t_(const uint8_t *p, size_t st, const pft_real_t (*tabx)[8],
                                          pft_kfrac_t gx, const pft_real_t (*taby)[8],
                                          pft_kfrac_t gy, pft_real_t a)
{
    const float *ax = tabx[gx.n];
    const float *ay = taby[gy.n];
    const __m128 tx =
        _mm_add_ps(_mm_loadu_ps(ax), _mm_mul_ps(_mm_set1_ps(gx.r), _mm_loadu_ps(ax + 4)));
    const __m128 ty =
        _mm_add_ps(_mm_loadu_ps(ay), _mm_mul_ps(_mm_set1_ps(gy.r), _mm_loadu_ps(ay + 4)));
    const uint8_t *p1 = p + st;
    const uint8_t *p2 = p1 + st;
    int32_t w0, w1, w2;
    int16_t e0, e1, e2; /* signed: the lane insert takes a short (GCC -O0 builds it as a macro) */
    memcpy(&w0, p, 4u);
    memcpy(&w1, p1, 4u);
    memcpy(&w2, p2, 4u);
    memcpy(&e0, p + 4u, 2u);
    memcpy(&e1, p1 + 4u, 2u);
    memcpy(&e2, p2 + 4u, 2u);
    {
        const __m128i zero = _mm_setzero_si128();
        const __m128i mk = _mm_set1_epi16(INT16_MIN); /* PFT_RES16_MASKED */
        const __m128i v0 = _mm_insert_epi16(_mm_cvtsi32_si128(w0), e0, 2);
        const __m128i v1 = _mm_insert_epi16(_mm_cvtsi32_si128(w1), e1, 2);
        const __m128i v2 = _mm_insert_epi16(_mm_cvtsi32_si128(w2), e2, 2);
        const __m128i v01 = _mm_unpacklo_epi16(v0, v1);   /* z0 z3 z1 z4 z2 z5 0 0 */
        const __m128i v2z = _mm_unpacklo_epi16(v2, zero); /* z6 0 z7 0 z8 0 0 0 */
        __m128i c01 = _mm_unpacklo_epi32(v01, v2z);       /* z0 z3 z6 0 z1 z4 z7 0 */
        __m128i c2 = _mm_unpackhi_epi32(v01, v2z);        /* z2 z5 z8 0 0 0 0 0 */
        c01 = _mm_andnot_si128(_mm_cmpeq_epi16(c01, mk), c01);
        c2 = _mm_andnot_si128(_mm_cmpeq_epi16(c2, mk), c2);
        {
            const __m128 f0 = _mm_cvtepi32_ps(_mm_srai_epi32(_mm_unpacklo_epi16(c01, c01), 16));
            const __m128 f1 = _mm_cvtepi32_ps(_mm_srai_epi32(_mm_unpackhi_epi16(c01, c01), 16));
            const __m128 f2 = _mm_cvtepi32_ps(_mm_srai_epi32(_mm_unpacklo_epi16(c2, c2), 16));
            const __m128 r = _mm_add_ps(
                _mm_add_ps(_mm_mul_ps(_mm_shuffle_ps(tx, tx, 0x00), f0),
                           _mm_mul_ps(_mm_shuffle_ps(tx, tx, 0x55), f1)),
                _mm_mul_ps(_mm_shuffle_ps(tx, tx, 0xAA), f2));
            const __m128 t = _mm_mul_ps(ty, r);
            const float s = (_mm_cvtss_f32(t) + _mm_cvtss_f32(_mm_shuffle_ps(t, t, 0x55))) +
                            _mm_cvtss_f32(_mm_movehl_ps(t, t));
            const float s1 = s * 0.00390625f;
            const float tx3 = _mm_cvtss_f32(_mm_shuffle_ps(tx, tx, 0xFF));
            const float ty3 = _mm_cvtss_f32(_mm_shuffle_ps(ty, ty, 0xFF));
            return a * (s1 - 0.5f * a * tx3 * ty3);
        }
    }
}
#elif defined(__aarch64__) && defined(__ARM_NEON)
/* The same on AArch64 (NEON intrinsics, float; the Cortex-A53 presets), in the rows' order: the
 * taps as one vector per axis (a + r d, lane by lane, a product then a sum: no fused
 * multiply-add, as in pft_ktaps_), each of the window's rows read with a 32-bit and a 16-bit
 * load into the lanes 0-2 of a vector of four 16-bit lanes (lane 3 zero), the masked value's 0
 * by a compare and a bit clear, the lanes widened and converted. Row b's products with the taps
 * with lane 3 set to -0 are tx0 z0, tx1 z1, tx2 z2 and -0 (-0 times the +0 of lane 3); two
 * pairwise additions give (tx0 z0 + tx1 z1) + (tx2 z2 + -0), and x + -0 is x for every x
 * (also for x = +0 and -0), so each lane of r is row b's sum in pft_kspot3_r16_'s order; then
 * (ty0 r0 + ty1 r1) + ty2 r2 and the rest as written there: the same IEEE single operations on
 * the same values, so the same bits. No fused multiply-add anywhere: vmulq_f32 and vaddq_f32
 * are separate operations, and -std=c99 keeps gcc from contracting the scalar ones. */
static inline int16x4_t pft_kr16_row3_(const uint8_t *q)
{
    uint32_t w;
    uint16_t e;
    memcpy(&w, q, 4u);
    memcpy(&e, q + 4u, 2u);
    /* little-endian lanes: z0 z1 in w, z2 in e, lane 3 zero */
    return vreinterpret_s16_u64(vcreate_u64((uint64_t)w | ((uint64_t)e << 32)));
}
static inline pft_real_t pft_kspot3_r16t_(const uint8_t *p, size_t st, const pft_real_t (*tabx)[8],
                                          pft_kfrac_t gx, const pft_real_t (*taby)[8],
                                          pft_kfrac_t gy, pft_real_t a)
{
    const float *ax = tabx[gx.n];
    const float *ay = taby[gy.n];
    const float32x4_t tx = vaddq_f32(vld1q_f32(ax), vmulq_f32(vdupq_n_f32(gx.r), vld1q_f32(ax + 4)));
    const float32x4_t ty = vaddq_f32(vld1q_f32(ay), vmulq_f32(vdupq_n_f32(gy.r), vld1q_f32(ay + 4)));
    const float32x4_t txm = vsetq_lane_f32(-0.0f, tx, 3);
    const int16x8_t mk = vdupq_n_s16(INT16_MIN); /* PFT_RES16_MASKED */
    int16x8_t v01 = vcombine_s16(pft_kr16_row3_(p), pft_kr16_row3_(p + st));
    int16x4_t v2 = pft_kr16_row3_(p + 2u * st);
    v01 = vbicq_s16(v01, vreinterpretq_s16_u16(vceqq_s16(v01, mk)));
    v2 = vbic_s16(v2, vreinterpret_s16_u16(vceq_s16(v2, vget_low_s16(mk))));
    {
        const float32x4_t p0 = vmulq_f32(txm, vcvtq_f32_s32(vmovl_s16(vget_low_s16(v01))));
        const float32x4_t p1 = vmulq_f32(txm, vcvtq_f32_s32(vmovl_high_s16(v01)));
        const float32x4_t p2 = vmulq_f32(txm, vcvtq_f32_s32(vmovl_s16(v2)));
        const float32x4_t h2 = vpaddq_f32(p2, p2);
        const float32x4_t r = vpaddq_f32(vpaddq_f32(p0, p1), h2); /* r0 r1 r2 r2 */
        const float32x4_t t = vmulq_f32(ty, r);
        const float s = (vgetq_lane_f32(t, 0) + vgetq_lane_f32(t, 1)) + vgetq_lane_f32(t, 2);
        const float s1 = s * 0.00390625f;
        const float tx3 = vgetq_lane_f32(tx, 3);
        const float ty3 = vgetq_lane_f32(ty, 3);
        return a * (s1 - 0.5f * a * tx3 * ty3);
    }
}
#define PFT_KSPOT3_R16T_LANES_ 1
#endif

static inline pft_real_t pft_kspot_(const pft_real_t *z, size_t stride, const pft_real_t *tx,
                                    uint32_t nx, const pft_real_t *ty, uint32_t ny, pft_real_t a)
{
    float s1 = 0.0f, sx2 = 0.0f, sy2 = 0.0f;
    for (uint32_t j = 0; j < ny; ++j) {
        float r = 0.0f;
        for (uint32_t i = 0; i < nx; ++i) {
            r += tx[i] * z[(size_t)j * stride + i];
        }
        s1 += ty[j] * r;
        sy2 += ty[j] * ty[j];
    }
    for (uint32_t i = 0; i < nx; ++i) {
        sx2 += tx[i] * tx[i];
    }
    return a * (s1 - 0.5f * a * sx2 * sy2);
}

#endif

#endif
