/* Temporal background registered to a drifting scene (docs/algorithms.md 9.3): the global
 * translation of each frame against the background (integer search on row and column
 * projections, then Lucas-Kanade Gauss-Newton steps), the bilinear warp of the background by
 * it and the recursive update b <- warp(b) + alpha (z - c - warp(b)), in place.
 * Background values are U units (counts * 2^bf, uint16); shifts Q16.16 px; the warp uses the
 * shift rounded to 1/256 px. */
#include <string.h>

#include "pre_int.h"

#if defined(__SSE2__)
#include <emmintrin.h> /* anchor_view_'s passes (PFT_PRE_VIEW_SPLIT_), the anchored residual (pft_pre_ares_span_),
                        * the gated update (PFT_PRE_GATE_SPLIT_) */
#elif defined(__aarch64__) && defined(__ARM_NEON)
/* AArch64 (the Cortex-A53 class): the same three kernels in NEON's forms on the 32-bit values
 * (PFT_PRE_NEON_: anchor_view_'s horizontal pass, pft_pre_ares_span_, gate_clip_split_) */
#include <arm_neon.h>
#define PFT_PRE_NEON_ 1
#endif

/* Largest predicted standard deviation of a sub-pixel shift that is used (Q16.16 px). */
#define PFT_PRE_SD_MAX_ 3277

/* floor(a / 2^k) and round(a / 2^k) for signed a (arithmetic shift, as the number layer). */
static int32_t fl_(int32_t a, uint32_t k) { return a >> k; }
static int32_t rnd_(int32_t a, uint32_t k) { return (int32_t)(((int64_t)a + (1 << k >> 1)) >> k); }

static int64_t abs64_(int64_t v) { return v < 0 ? -v : v; }

static int32_t clampi_(int32_t v, int32_t lo, int32_t hi)
{
    return v < lo ? lo : (v > hi ? hi : v);
}

/* ------------------------------------------------------------------ integer search */

/* Projections of z (counts) and b (U units) on the columns (every step-th row) and on the
 * rows (every column). */
static void projections_(pft_pre_t *p, const pft_frame_t *f, const pft_pre_cls_t *c)
{
    const uint32_t w = p->cfg.width, h = p->cfg.height, st = p->cfg.reg_step, mask = c->mask;
    int32_t *pzc = p->pzc, *pbc = p->pbc;
    memset(pzc, 0, (size_t)w * 4u);
    memset(pbc, 0, (size_t)w * 4u);
    for (uint32_t y = 0; y < h; ++y) {
        const uint8_t *row = pft_frame_row(f, y);
        const uint16_t *b = p->bgv + (size_t)y * p->bgs;
        const bool col = y % st == 0u;
        int32_t sz = 0, sb = 0;
        if (c->u8) {
            for (uint32_t x = 0; x < w; ++x) {
                sz += row[x];
                pzc[x] += col ? (int32_t)row[x] : 0;
            }
        } else {
            for (uint32_t x = 0; x < w; ++x) {
                uint16_t v;
                memcpy(&v, row + 2u * x, 2u);
                const int32_t z = (int32_t)((uint32_t)v & mask);
                sz += z;
                pzc[x] += col ? z : 0;
            }
        }
        for (uint32_t x = 0; x < w; ++x) {
            sb += b[x];
            pbc[x] += col ? (int32_t)b[x] : 0;
        }
        p->pzr[y] = sz;
        p->pbr[y] = sb;
    }
}

/* Best integer shift i of z against b along one axis from the projections pz (counts) and
 * pb (U units) of n elements: the smallest sum of |dz(x) - db(x - i)| over their first
 * differences, on the same m values of x for every candidate and away from the ends (where
 * the warped background repeats its border). A shift other than the prediction is taken only
 * when its cost is below the prediction's by more than 6/sqrt(m) of it, several times the
 * cost's relative noise (the best of up to 65 noisy candidates): a flat or one-directional
 * scene has no shift to find, and its noise must not make one up. dz carries the column offsets off (cofs, NULL for rows, times
 * the rows summed). Sets *edge when the shift taken is at the end of the searched range.
 * The differences are formed once, in place (pz and pb are not read again): dz(x) for x in
 * [x0, x1) into pz[x], db(j) = pb[j + 1] - pb[j] for j in [x0 - hi, x1 - lo) into pb[j], each
 * read before it is overwritten. Both fit int32: a projection sums at most 8192 values
 * (PFT_CFG_MAX_IMAGE_SIDE) of at most 65535 U (counts times 2^bf), so |pz[x + 1] - pz[x]| 2^bf
 * and |pb[j + 1] - pb[j]| stay below 2^29; a column offset lies within +-65535 U (colq is
 * clamped to +-32767 * 256, colnow = colq 2^k / 256 with k <= 1), so the offsets' term
 * |cofs[x + 1] - cofs[x]| nsum stays below 2^30, and |dz| below 2^29 + 2^30 < 2^31. */
static int32_t search_axis_(int32_t *pz, int32_t *pb, uint32_t n, uint32_t bf,
                            const int32_t *cofs, int32_t nsum, int32_t centre, int32_t radius,
                            bool *edge)
{
    const int32_t lim = (int32_t)n / 4; /* compare at least half the axis */
    const int32_t c = clampi_(centre, -lim, lim);
    const int32_t rad = clampi_(radius, 0, lim - (c < 0 ? -c : c));
    const int32_t lo = c - rad, hi = c + rad;
    /* x and x - i inside [2, n - 3) for every candidate i */
    const int32_t x0 = 2 + (hi > 0 ? hi : 0), x1 = (int32_t)n - 3 + (lo < 0 ? lo : 0);
    for (int32_t x = x0; x < x1; ++x) {
        int64_t dz = ((int64_t)pz[x + 1] - pz[x]) * (1 << bf);
        if (cofs != NULL) {
            dz -= ((int64_t)cofs[x + 1] - cofs[x]) * nsum;
        }
        pz[x] = (int32_t)dz;
    }
    for (int32_t j = x0 - hi; j < x1 - lo; ++j) {
        pb[j] = pb[j + 1] - pb[j];
    }
    int32_t best = c;
    int64_t best_cost = -1, centre_cost = 0;
    for (int32_t i = lo; i <= hi; ++i) {
        int64_t cost = 0;
        for (int32_t x = x0; x < x1; ++x) {
            cost += abs64_((int64_t)pz[x] - pb[x - i]);
        }
        if (i == c) {
            centre_cost = cost;
        }
        const int32_t di = i > c ? i - c : c - i, db_ = best > c ? best - c : c - best;
        if (best_cost < 0 || cost < best_cost || (cost == best_cost && di < db_)) {
            best_cost = cost;
            best = i;
        }
    }
    const int64_t m = x1 > x0 ? x1 - x0 : 1;
    const int64_t margin = 6144 / (int64_t)pft_pre_isqrt64_((uint64_t)m); /* 6/sqrt(m), Q10 */
    if (best != c && best_cost * (1024 + margin) >= centre_cost * 1024) {
        best = c;
    }
    *edge = rad > 0 && best != c && (best == lo || best == hi);
    return best;
}

/* A jump found by the projections is checked in two dimensions: the mean |z - c - b(p - s)|
 * over every 4th pixel of every 4th row, for the integer shifts within 2 px of the
 * projections' (ix, iy) and for the prediction (cx, cy), on the pixels inside the image for
 * all of them. The projections of a scene shifted along both axes also change with the
 * rows (columns) that enter and leave, which can pull a one-axis estimate by a pixel or two.
 * Returns false when no candidate beats the prediction by 6/sqrt(n) of its cost (no jump). */
static bool jump_2d_(const pft_pre_t *p, const pft_frame_t *f, const pft_pre_cls_t *c,
                     int32_t cx, int32_t cy, int32_t *ix, int32_t *iy)
{
    const int32_t w = p->cfg.width, h = p->cfg.height, st = 4;
    const int32_t ax = *ix, ay = *iy;
    int32_t mx = (ax < 0 ? -ax : ax) + 2, my = (ay < 0 ? -ay : ay) + 2;
    mx = (cx < 0 ? -cx : cx) > mx ? (cx < 0 ? -cx : cx) : mx;
    my = (cy < 0 ? -cy : cy) > my ? (cy < 0 ? -cy : cy) : my;
    if (2 * mx + st >= w || 2 * my + st >= h) {
        return true; /* no room to check: keep the projections' answer */
    }
    int64_t best = -1, pred_cost = 0;
    int32_t bx = ax, by = ay;
    uint32_t n = 0u;
    for (int32_t k = 0; k < 26; ++k) { /* 25 candidates around (ax, ay), then the prediction */
        const int32_t sx = k < 25 ? ax + k % 5 - 2 : cx, sy = k < 25 ? ay + k / 5 - 2 : cy;
        int64_t cost = 0;
        n = 0u;
        for (int32_t y = my; y < h - my; y += st) {
            const uint8_t *row = pft_frame_row(f, (uint32_t)y);
            const uint16_t *b = p->bgv + (size_t)(y - sy) * (size_t)p->bgs; /* y - sy >= 0 */
            for (int32_t x = mx; x < w - mx; x += st) {
                const uint32_t v = pft_pre_raw_(row, (uint32_t)x, c);
                if (!pft_pre_valid_(c, v, (uint32_t)x, (uint32_t)y)) {
                    continue;
                }
                const int32_t e = (int32_t)(v << p->bf) - p->colnow[x] - b[x - sx];
                cost += e < 0 ? -e : e;
                n++;
            }
        }
        if (k == 25) {
            pred_cost = cost;
        } else if (best < 0 || cost < best) {
            best = cost;
            bx = sx;
            by = sy;
        } else {
            /* not better than the best so far */
        }
    }
    const int64_t margin = 6144 / (int64_t)(n > 0u ? pft_pre_isqrt64_(n) : 1u);
    if ((bx == cx && by == cy) || best * (1024 + margin) >= pred_cost * 1024) {
        return false;
    }
    *ix = bx;
    *iy = by;
    return true;
}

/* bg_anchor: the grid read at the last frame's position into the residual buffer (free until
 * the residual pass), the background that registration compares the frame with (pre_config.c
 * points p->bgv there). */
static void anchor_view_(pft_pre_t *p);

/* ------------------------------------------------------------------ Lucas-Kanade */

typedef struct {
    int64_t sxx, sxy, syy, sxe, sye, see;
    uint32_t n;
} lk_sums_t;

/* One Lucas-Kanade sample added to the sums: gradient (gx, gy), error e. */
static inline void lk_add_(lk_sums_t *a, int32_t gx, int32_t gy, int32_t e)
{
    a->sxx += (int64_t)gx * gx;
    a->sxy += (int64_t)gx * gy;
    a->syy += (int64_t)gy * gy;
    a->sxe += (int64_t)gx * e;
    a->sye += (int64_t)gy * e;
    a->see += (int64_t)e * e;
    a->n++;
}

/* Warp geometry of a shift s (Q16.16): the sample of pixel x is b at x - s, taps x + k and
 * x + k + 1 with weights 256 - fr and fr (per axis). */
typedef struct {
    int32_t kx, ky;
    uint32_t fx, fy;
} warp_t;

static warp_t warp_of_(const int32_t s[2])
{
    warp_t g;
    const int32_t dx = -rnd_(s[0], 8), dy = -rnd_(s[1], 8); /* Q8 sample offsets */
    g.kx = fl_(dx, 8);
    g.ky = fl_(dy, 8);
    g.fx = (uint32_t)(dx - g.kx * 256);
    g.fy = (uint32_t)(dy - g.ky * 256);
    return g;
}

/* Catmull-Rom weights of taps -1, 0, 1, 2 for the fraction f/256, Q8, summing to 256
 * (f = 0: 0, 256, 0, 0). The cubic reproduces quadratics, so warping the background again
 * and again neither blurs nor skews it the way bilinear weights (1 - f, f) do. */
static void cubic_q8_(uint32_t f, int32_t w[4])
{
    const int64_t t1 = f, t2 = (int64_t)f * f, t3 = t2 * f; /* Q8, Q16, Q24 */
    const int64_t one = (int64_t)1 << 24;
    const int64_t q[4] = {(-t3 + 2 * t2 * 256 - t1 * 65536) / 2,
                          (3 * t3 - 5 * t2 * 256 + 2 * one) / 2,
                          (-3 * t3 + 4 * t2 * 256 + t1 * 65536) / 2,
                          (t3 - t2 * 256) / 2};
    int32_t sum = 0;
    for (uint32_t i = 0; i < 4u; ++i) {
        w[i] = (int32_t)((q[i] >= 0 ? q[i] + 32768 : q[i] - 32768) / 65536);
        sum += w[i];
    }
    w[f < 128u ? 1 : 2] += 256 - sum;
}

/* Warp weights of taps -1, 0, 1, 2: Catmull-Rom, or bilinear (0, 256 - f, f, 0). */
static void warp_q8_(uint32_t f, bool cubic, int32_t w[4])
{
    if (cubic) {
        cubic_q8_(f, w);
        return;
    }
    w[0] = 0;
    w[1] = 256 - (int32_t)f;
    w[2] = (int32_t)f;
    w[3] = 0;
}

#if defined(PFT_PRE_NEON_)
/* With NEON (AArch64), lk_loop_'s sums (a U16 frame without a bad-pixel map) four samples at a
 * time in 32-bit lanes: the same gx, gy, e as the loop in int32 (the bilinear sample
 * bw = (h0 gy0 + h1 fy + 32768) >> 16 is below 2^32 before the shift, so the rounding
 * narrowing rshrn gives it), an invalid sample's gx, gy, e set to 0 instead of skipped (its
 * products add 0), the products summed in 64-bit lanes (smlal): integer sums in another order,
 * the same totals. par: mask, lo, span, bf, fx, fy. */
typedef struct {
    uint16x4_t vm, vgx0, vfx;
    uint32x4_t vlo, vspan, vgy0, vfy;
    int32x4_t vbf;
} lk_npar_t;

typedef struct {
    int64x2_t sxx, sxy, syy, sxe, sye, see;
    uint32x4_t n;
} lk_nacc_t;

static inline void lk_npar_(const uint32_t par[6], lk_npar_t *q, lk_nacc_t *a)
{
    q->vm = vdup_n_u16((uint16_t)(par[0] & 0xFFFFu));
    q->vlo = vdupq_n_u32(par[1]);
    q->vspan = vdupq_n_u32(par[2]);
    q->vbf = vdupq_n_s32((int32_t)par[3]);
    q->vgx0 = vdup_n_u16((uint16_t)(256u - par[4]));
    q->vfx = vdup_n_u16((uint16_t)par[4]);
    q->vgy0 = vdupq_n_u32(256u - par[5]);
    q->vfy = vdupq_n_u32(par[5]);
    a->sxx = vdupq_n_s64(0);
    a->sxy = a->sxx;
    a->syy = a->sxx;
    a->sxe = a->sxx;
    a->sye = a->sxx;
    a->see = a->sxx;
    a->n = vdupq_n_u32(0u);
}

/* The taps of four samples: t0 .. t3 = b0[i], b0[i + 1], b0[i + 2], b0[i + 3] of each, u0 .. u3
 * the same of b1, m1, m2 = bm[i + 1], bm[i + 2], d1, d2 = b2[i + 1], b2[i + 2] (values, not an
 * array: gcc 12 keeps an array of vectors on the stack). */
typedef struct {
    uint16x4_t t0, t1, t2, t3, u0, u1, u2, u3, m1, m2, d1, d2;
} lk_ntaps_t;

/* Four samples: raw their pixels, k their taps, czv colnow. */
static inline void lk_block_n_(const lk_npar_t *q, uint16x4_t raw, lk_ntaps_t k, int32x4_t czv, lk_nacc_t *a)
{
    const uint32x4_t v = vmovl_u16(vand_u16(raw, q->vm));
    const uint32x4_t ok = vcltq_u32(vsubq_u32(v, q->vlo), q->vspan);
    const int32x4_t okm = vreinterpretq_s32_u32(ok);
    const uint32x4_t h0 = vmlal_u16(vmull_u16(k.t1, q->vgx0), k.t2, q->vfx);
    const uint32x4_t h1 = vmlal_u16(vmull_u16(k.u1, q->vgx0), k.u2, q->vfx);
    const uint16x4_t bw = vrshrn_n_u32(vmlaq_u32(vmulq_u32(h0, q->vgy0), h1, q->vfy), 16);
    const int32x4_t e = vandq_s32(vsubq_s32(vreinterpretq_s32_u32(vsubw_u16(vshlq_u32(v, q->vbf), bw)), czv), okm);
    const int32x4_t gx = vandq_s32(vreinterpretq_s32_u32(vaddq_u32(vsubl_u16(k.t3, k.t0), vsubl_u16(k.u3, k.u0))), okm);
    const int32x4_t gy = vandq_s32(vreinterpretq_s32_u32(vaddq_u32(vsubl_u16(k.d1, k.m1), vsubl_u16(k.d2, k.m2))), okm);
    const int32x2_t gxl = vget_low_s32(gx), gyl = vget_low_s32(gy), el = vget_low_s32(e);
    a->n = vsubq_u32(a->n, ok);
    a->sxx = vmlal_high_s32(vmlal_s32(a->sxx, gxl, gxl), gx, gx);
    a->sxy = vmlal_high_s32(vmlal_s32(a->sxy, gxl, gyl), gx, gy);
    a->syy = vmlal_high_s32(vmlal_s32(a->syy, gyl, gyl), gy, gy);
    a->sxe = vmlal_high_s32(vmlal_s32(a->sxe, gxl, el), gx, e);
    a->sye = vmlal_high_s32(vmlal_s32(a->sye, gyl, el), gy, e);
    a->see = vmlal_high_s32(vmlal_s32(a->see, el, el), e, e);
}

static inline void lk_nsum_(const lk_nacc_t *a, lk_sums_t *s)
{
    s->sxx += vaddvq_s64(a->sxx);
    s->sxy += vaddvq_s64(a->sxy);
    s->syy += vaddvq_s64(a->syy);
    s->sxe += vaddvq_s64(a->sxe);
    s->sye += vaddvq_s64(a->sye);
    s->see += vaddvq_s64(a->see);
    s->n += vaddvq_u32(a->n);
}

/* Step 2: samples i, i + 2, i + 4, i + 6 of a row for i = 0, 8, 16, ... while i + 7 <= n (the
 * block reads pixels and colnow to i + 7, the background's row columns to i + 9, all inside
 * the loop's own reads for samples up to n). Adds to s; returns the first sample left to the
 * loop. */
static inline int32_t lk_row2v_(const uint8_t *rz, const int32_t *cz, const uint16_t *bm, int32_t bs,
                                const uint32_t par[6], int32_t n, lk_sums_t *s)
{
    const uint16_t *b0 = bm + bs, *b1 = b0 + bs, *b2 = b1 + bs;
    lk_npar_t q;
    lk_nacc_t a;
    lk_npar_(par, &q, &a);
    int32_t i = 0;
    for (; i + 7 <= n; i += 8) {
        const uint16x8_t r16 = vreinterpretq_u16_u8(vld1q_u8(rz + 2 * i));
        const uint16x4x2_t p0 = vld2_u16(b0 + i), q0 = vld2_u16(b0 + i + 2); /* b0[i .. i + 3] */
        const uint16x4x2_t p1 = vld2_u16(b1 + i), q1 = vld2_u16(b1 + i + 2);
        const uint16x4x2_t pm = vld2_u16(bm + i + 1), p2 = vld2_u16(b2 + i + 1); /* [i + 1], [i + 2] */
        const lk_ntaps_t k = {p0.val[0], p0.val[1], q0.val[0], q0.val[1], p1.val[0], p1.val[1],
                              q1.val[0], q1.val[1], pm.val[0], pm.val[1], p2.val[0], p2.val[1]};
        lk_block_n_(&q, vget_low_u16(vuzp1q_u16(r16, r16)), k, vld2q_s32(cz + i).val[0], &a);
    }
    lk_nsum_(&a, s);
    return i;
}

/* Step 4 (reg_step 2's iterations before the last): samples i, i + 4, i + 8, i + 12 for
 * i = 0, 16, 32, ... while i + 15 <= n (reads pixels, colnow and the background's row
 * columns to i + 15, inside the loop's own reads for samples up to n). */
static inline int32_t lk_row4v_(const uint8_t *rz, const int32_t *cz, const uint16_t *bm, int32_t bs,
                                const uint32_t par[6], int32_t n, lk_sums_t *s)
{
    const uint16_t *b0 = bm + bs, *b1 = b0 + bs, *b2 = b1 + bs;
    lk_npar_t q;
    lk_nacc_t a;
    lk_npar_(par, &q, &a);
    int32_t i = 0;
    for (; i + 15 <= n; i += 16) {
        const uint16x8_t r0 = vreinterpretq_u16_u8(vld1q_u8(rz + 2 * i));
        const uint16x8_t r1 = vreinterpretq_u16_u8(vld1q_u8(rz + 2 * i + 16));
        const uint16x8_t r02 = vuzp1q_u16(r0, r1); /* pixels i, i + 2, ..., i + 14 */
        const uint16x4x4_t p0 = vld4_u16(b0 + i), p1 = vld4_u16(b1 + i); /* [i .. i + 3] */
        const uint16x4x4_t pm = vld4_u16(bm + i), p2 = vld4_u16(b2 + i);
        const lk_ntaps_t k = {p0.val[0], p0.val[1], p0.val[2], p0.val[3], p1.val[0], p1.val[1],
                              p1.val[2], p1.val[3], pm.val[1], pm.val[2], p2.val[1], p2.val[2]};
        lk_block_n_(&q, vget_low_u16(vuzp1q_u16(r02, r02)), k, vld4q_s32(cz + i).val[0], &a);
    }
    lk_nsum_(&a, s);
    return i;
}
#elif defined(__SSE2__)
/* Where the compiler has SSE2 (x86-64), lk_loop_'s sums (a U16 frame without a bad-pixel map)
 * four samples at a time in 32-bit lanes, the same gx, gy, e as the loop, an invalid sample's
 * gx, gy, e set to 0 instead of skipped (its products add 0). SSE2 has no 32-bit lane
 * multiply, so the bilinear sample goes through pmaddwd on 16-bit pairs: a lane holds the
 * sample's two taps (b[i + 1], b[i + 2]) of a background row, biased by -32768 into int16
 * (xor 0x8000), and pmaddwd with the pair (256 - fx, fx) gives P = h - 2^23 (h = the loop's h0
 * or h1, below 2^24), exactly. P = 2^15 ph + pl (ph = P >> 15 in [-256, 255], pl in
 * [0, 32767]); the pairs (ph0, ph1) and (pl0, pl1) with (256 - fy, fy) give A and B, and
 * h0 (256 - fy) + h1 fy = 2^15 A + B + 2^31 (the weights sum to 256). So the loop's
 * bw = (that + 32768) >> 16 = ((A + ((B + 32768) >> 15)) >> 1) + 32768 exactly (B + 32768 >= 0;
 * for any integer Q and 0 <= r < 2^15, floor((2^15 Q + r) / 2^16) = floor(Q / 2)). gy is two
 * pmaddwd of the biased pairs of rows b2 and bm with (1, 1) (the biases cancel), gx the 16-bit
 * halves of b0, b1 at i and i + 3. v - lo < span (unsigned) is the signed compare of both sides
 * xor 2^31.
 * The six products are summed as integers mod 2^64 in 64-bit lanes (paddq) from pmuludq, the
 * unsigned 32 x 32 -> 64 product of lanes 0 and 2 (lanes 1 and 3 moved there by pshufd), on
 * biased values that are never negative: ux = gx + B, uy = gy + B (B = 2^17; |gx|, |gy| <= 131070,
 * two u16 differences each, so 0 < ux, uy < 2^18) and ue = e + C (C = 2^31: e xor 2^31, the
 * unsigned pattern of any int32 e). Each product is exact, and
 * ux uy = gx gy + B (gx + gy) + B^2, ux ue = gx e + C gx + B e + B C, ue ue = e e + 2 C e + C^2
 * (likewise the others), so with N the lanes taken (4 a block, an invalid sample's lanes too:
 * its gx, gy, e are 0) and Sx = sum ux - B N, Sy = sum uy - B N, Se = sum ue - C N the sums of
 * gx, gy, e: sxx = sum ux ux - 2 B Sx - B^2 N, sxy = sum ux uy - B (Sx + Sy) - B^2 N,
 * sxe = sum ux ue - C Sx - B Se - B C N, see = sum ue ue - 2 C Se - C^2 N, the same for y, all
 * mod 2^64 (uint64 arithmetic), which gives the loop's int64 sums exactly (integer sums in
 * another order). sum ux and sum uy are kept in 32-bit lanes (exact: a lane takes at most
 * n / 8 + 1 samples of ux < 2^18, below 2^32 for rows below 2^17 pixels; a row has at most
 * PFT_CFG_MAX_IMAGE_SIDE = 8192), sum ue in 64-bit lanes. par: mask, lo, span, bf, fx, fy. */
typedef struct {
    __m128i vm, vlo, vspan, vbf, wx, wy, flip, ones, m16, m15, k15, sgn, bias, lo32;
} lk_spar_t;

typedef struct {
    __m128i sxx, sxy, syy, sxe, sye, see; /* 64-bit lanes: sums of the biased products */
    __m128i ux, uy;                       /* 32-bit lanes: sums of ux, uy */
    __m128i ue;                           /* 64-bit lanes: the sum of ue */
    __m128i n;
} lk_sacc_t;

static inline void lk_spar_(const uint32_t par[6], lk_spar_t *q, lk_sacc_t *a)
{
    q->vm = _mm_set1_epi32((int)(par[0] & 0xFFFFu));
    q->vlo = _mm_set1_epi32((int)par[1]);
    q->sgn = _mm_set1_epi32((int)INT32_MIN);
    q->vspan = _mm_xor_si128(_mm_set1_epi32((int)par[2]), q->sgn);
    q->vbf = _mm_cvtsi32_si128((int)par[3]);
    q->wx = _mm_set1_epi32((int)((256u - par[4]) | (par[4] << 16)));
    q->wy = _mm_set1_epi32((int)((256u - par[5]) | (par[5] << 16)));
    q->flip = _mm_set1_epi16((short)-32768);
    q->ones = _mm_set1_epi16(1);
    q->m16 = _mm_set1_epi32(0xFFFF);
    q->m15 = _mm_set1_epi32(32767);
    q->k15 = _mm_set1_epi32(32768);
    q->bias = _mm_set1_epi32(131072);
    q->lo32 = _mm_set_epi32(0, -1, 0, -1);
    a->sxx = _mm_setzero_si128();
    a->sxy = a->sxx;
    a->syy = a->sxx;
    a->sxe = a->sxx;
    a->sye = a->sxx;
    a->see = a->sxx;
    a->ux = a->sxx;
    a->uy = a->sxx;
    a->ue = a->sxx;
    a->n = a->sxx;
}

/* The taps of four samples, one per 32-bit lane: p0, p1 the pairs (b[i + 1], b[i + 2]) of rows
 * b0, b1; r0, r1 with b[i] in the low halves; t0, t1 with b[i + 3] in the high halves; pm, p2
 * the pairs (b[i + 1], b[i + 2]) of rows bm, b2. */
typedef struct {
    __m128i p0, p1, r0, r1, t0, t1, pm, p2;
} lk_staps_t;

/* The products a b of lanes 0, 2 and of lanes 1, 3 (ao, bo: a, b with lanes 1, 3 moved to 0, 2)
 * as unsigned 32-bit values, added in 64-bit lanes to s. */
static inline __m128i lk_smul2_(__m128i s, __m128i a, __m128i b, __m128i ao, __m128i bo)
{
    return _mm_add_epi64(_mm_add_epi64(s, _mm_mul_epu32(a, b)), _mm_mul_epu32(ao, bo));
}

/* Four samples: raw their pixels (the low half of each lane), czv colnow. */
static inline void lk_block_s_(const lk_spar_t *q, __m128i raw, const lk_staps_t *k, __m128i czv, lk_sacc_t *a)
{
    const __m128i v = _mm_and_si128(raw, q->vm);
    const __m128i ok = _mm_cmplt_epi32(_mm_xor_si128(_mm_sub_epi32(v, q->vlo), q->sgn), q->vspan);
    const __m128i p0 = _mm_madd_epi16(_mm_xor_si128(k->p0, q->flip), q->wx);
    const __m128i p1 = _mm_madd_epi16(_mm_xor_si128(k->p1, q->flip), q->wx);
    const __m128i ph = _mm_or_si128(_mm_and_si128(_mm_srai_epi32(p0, 15), q->m16),
                                    _mm_slli_epi32(_mm_srai_epi32(p1, 15), 16));
    const __m128i pl = _mm_or_si128(_mm_and_si128(p0, q->m15), _mm_slli_epi32(_mm_and_si128(p1, q->m15), 16));
    const __m128i qa = _mm_madd_epi16(ph, q->wy), qb = _mm_madd_epi16(pl, q->wy);
    const __m128i bw = _mm_add_epi32(_mm_srai_epi32(_mm_add_epi32(qa, _mm_srai_epi32(_mm_add_epi32(qb, q->k15), 15)), 1),
                                     q->k15);
    const __m128i e = _mm_and_si128(_mm_sub_epi32(_mm_sub_epi32(_mm_sll_epi32(v, q->vbf), czv), bw), ok);
    const __m128i gx = _mm_and_si128(_mm_sub_epi32(_mm_add_epi32(_mm_srli_epi32(k->t0, 16), _mm_srli_epi32(k->t1, 16)),
                                                   _mm_add_epi32(_mm_and_si128(k->r0, q->m16), _mm_and_si128(k->r1, q->m16))),
                                     ok);
    const __m128i gy = _mm_and_si128(_mm_sub_epi32(_mm_madd_epi16(_mm_xor_si128(k->p2, q->flip), q->ones),
                                                   _mm_madd_epi16(_mm_xor_si128(k->pm, q->flip), q->ones)),
                                     ok);
    a->n = _mm_sub_epi32(a->n, ok);
    const __m128i ux = _mm_add_epi32(gx, q->bias), uy = _mm_add_epi32(gy, q->bias), ue = _mm_xor_si128(e, q->sgn);
    const __m128i xo = _mm_shuffle_epi32(ux, 0xF5), yo = _mm_shuffle_epi32(uy, 0xF5), eo = _mm_shuffle_epi32(ue, 0xF5);
    a->ux = _mm_add_epi32(a->ux, ux);
    a->uy = _mm_add_epi32(a->uy, uy);
    a->ue = _mm_add_epi64(_mm_add_epi64(a->ue, _mm_and_si128(ue, q->lo32)), _mm_srli_epi64(ue, 32));
    a->sxx = lk_smul2_(a->sxx, ux, ux, xo, xo);
    a->sxy = lk_smul2_(a->sxy, ux, uy, xo, yo);
    a->syy = lk_smul2_(a->syy, uy, uy, yo, yo);
    a->sxe = lk_smul2_(a->sxe, ux, ue, xo, eo);
    a->sye = lk_smul2_(a->sye, uy, ue, yo, eo);
    a->see = lk_smul2_(a->see, ue, ue, eo, eo);
}

/* The sum of a vector's four 32-bit lanes (unsigned; exact for the sums of ux, uy and n). */
static inline uint32_t lk_s32sum_(__m128i c)
{
    const __m128i c2 = _mm_add_epi32(c, _mm_shuffle_epi32(c, 0xEE));
    return (uint32_t)_mm_cvtsi128_si32(_mm_add_epi32(c2, _mm_shuffle_epi32(c2, 0x55)));
}

/* The sum of a vector's two 64-bit lanes, mod 2^64 (a store: the forms 32-bit x86 also has). */
static inline uint64_t lk_s64sum_(__m128i s)
{
    uint64_t l[2];
    _mm_storeu_si128((__m128i *)(void *)l, s);
    return l[0] + l[1];
}

/* The biased sums of nb blocks (4 nb lanes) to the loop's sums, added to s (see above). */
static inline void lk_ssum_(const lk_sacc_t *a, int32_t nb, lk_sums_t *s)
{
    const uint64_t B = 131072u, C = 2147483648u, N = 4u * (uint64_t)(uint32_t)nb;
    const uint64_t sx = (uint64_t)lk_s32sum_(a->ux) - B * N, sy = (uint64_t)lk_s32sum_(a->uy) - B * N;
    const uint64_t se = lk_s64sum_(a->ue) - C * N;
    s->sxx = (int64_t)((uint64_t)s->sxx + lk_s64sum_(a->sxx) - 2u * B * sx - B * B * N);
    s->sxy = (int64_t)((uint64_t)s->sxy + lk_s64sum_(a->sxy) - B * (sx + sy) - B * B * N);
    s->syy = (int64_t)((uint64_t)s->syy + lk_s64sum_(a->syy) - 2u * B * sy - B * B * N);
    s->sxe = (int64_t)((uint64_t)s->sxe + lk_s64sum_(a->sxe) - C * sx - B * se - B * C * N);
    s->sye = (int64_t)((uint64_t)s->sye + lk_s64sum_(a->sye) - C * sy - B * se - B * C * N);
    s->see = (int64_t)((uint64_t)s->see + lk_s64sum_(a->see) - 2u * C * se - C * C * N);
    s->n += lk_s32sum_(a->n);
}

static inline __m128i lk_ld_(const void *p)
{
    return _mm_loadu_si128((const __m128i *)p);
}

/* Lanes 0 and 2 of the 16 bytes at p, then of those at p + 16: the 32-bit words at bytes 0, 8,
 * 16, 24 (step 4's samples). */
static inline __m128i lk_ld4_(const void *p)
{
    const uint8_t *b = (const uint8_t *)p;
    return _mm_castps_si128(_mm_shuffle_ps(_mm_castsi128_ps(lk_ld_(b)), _mm_castsi128_ps(lk_ld_(b + 16)),
                                           _MM_SHUFFLE(2, 0, 2, 0)));
}

/* Step 2: samples i, i + 2, i + 4, i + 6 of a row for i = 0, 8, 16, ... while i + 7 <= n (the
 * block reads pixels and colnow to i + 7, the background's row columns to i + 9, all inside
 * the loop's own reads for samples up to n). Adds to s; returns the first sample left to the
 * loop. */
static inline int32_t lk_row2v_(const uint8_t *rz, const int32_t *cz, const uint16_t *bm, int32_t bs,
                                const uint32_t par[6], int32_t n, lk_sums_t *s)
{
    const uint16_t *b0 = bm + bs, *b1 = b0 + bs, *b2 = b1 + bs;
    lk_spar_t q;
    lk_sacc_t a;
    lk_spar_(par, &q, &a);
    int32_t i = 0;
    for (; i + 7 <= n; i += 8) {
        lk_staps_t k;
        k.p0 = lk_ld_(b0 + i + 1);
        k.p1 = lk_ld_(b1 + i + 1);
        k.r0 = lk_ld_(b0 + i);
        k.r1 = lk_ld_(b1 + i);
        k.t0 = lk_ld_(b0 + i + 2);
        k.t1 = lk_ld_(b1 + i + 2);
        k.pm = lk_ld_(bm + i + 1);
        k.p2 = lk_ld_(b2 + i + 1);
        const __m128i czv = _mm_castps_si128(_mm_shuffle_ps(_mm_castsi128_ps(lk_ld_(cz + i)),
                                                            _mm_castsi128_ps(lk_ld_(cz + i + 4)),
                                                            _MM_SHUFFLE(2, 0, 2, 0)));
        lk_block_s_(&q, lk_ld_(rz + 2 * i), &k, czv, &a);
    }
    lk_ssum_(&a, i / 8, s);
    return i;
}

/* Step 4 (reg_step 2's iterations before the last): samples i, i + 4, i + 8, i + 12 for
 * i = 0, 16, 32, ... while i + 15 <= n (reads pixels and colnow to i + 15, the background's
 * row columns to i + 17, inside the loop's own reads for samples up to n). */
static inline int32_t lk_row4v_(const uint8_t *rz, const int32_t *cz, const uint16_t *bm, int32_t bs,
                                const uint32_t par[6], int32_t n, lk_sums_t *s)
{
    const uint16_t *b0 = bm + bs, *b1 = b0 + bs, *b2 = b1 + bs;
    lk_spar_t q;
    lk_sacc_t a;
    lk_spar_(par, &q, &a);
    int32_t i = 0;
    for (; i + 15 <= n; i += 16) {
        lk_staps_t k;
        k.p0 = lk_ld4_(b0 + i + 1);
        k.p1 = lk_ld4_(b1 + i + 1);
        k.r0 = lk_ld4_(b0 + i);
        k.r1 = lk_ld4_(b1 + i);
        k.t0 = lk_ld4_(b0 + i + 2);
        k.t1 = lk_ld4_(b1 + i + 2);
        k.pm = lk_ld4_(bm + i + 1);
        k.p2 = lk_ld4_(b2 + i + 1);
        const __m128i c01 = _mm_unpacklo_epi32(_mm_cvtsi32_si128(cz[i]), _mm_cvtsi32_si128(cz[i + 4]));
        const __m128i c23 = _mm_unpacklo_epi32(_mm_cvtsi32_si128(cz[i + 8]), _mm_cvtsi32_si128(cz[i + 12]));
        lk_block_s_(&q, lk_ld4_(rz + 2 * i), &k, _mm_unpacklo_epi64(c01, c23), &a);
    }
    lk_ssum_(&a, i / 16, s);
    return i;
}
#endif

#if defined(PFT_PRE_NEON_) || defined(__SSE2__)

/* lk_row2v_ (st 2) or lk_row4v_ (st 4), the NEON or SSE2 form, for a test: the sums of a row's
 * samples 0, st, 2 st, ..., up to the last whole block of four (rz: the row's pixels from the
 * first sample, cz: colnow from it, bm: the background's row y + ky - 1 from column c0 with stride bs, par: mask,
 * lo, span, bf, fx, fy); sums: sxx, sxy, syy, sxe, sye, see added to, *cnt likewise; returns
 * the first sample left. */
int32_t pft_pre_lk_rowv_(const uint8_t *rz, const int32_t *cz, const uint16_t *bm, int32_t bs,
                         const uint32_t par[6], int32_t st, int32_t n, int64_t sums[6], uint32_t *cnt)
{
    lk_sums_t a = {sums[0], sums[1], sums[2], sums[3], sums[4], sums[5], *cnt};
    const int32_t i = st == 4 ? lk_row4v_(rz, cz, bm, bs, par, n, &a) : lk_row2v_(rz, cz, bm, bs, par, n, &a);
    sums[0] = a.sxx;
    sums[1] = a.sxy;
    sums[2] = a.syy;
    sums[3] = a.sxe;
    sums[4] = a.sye;
    sums[5] = a.see;
    *cnt = a.n;
    return i;
}
#endif

/* One pass of sums over the sampled pixels whose taps are inside the image. The gradient of
 * the 2 x 2 cell of the bilinear taps is taken across it, from the columns (rows) just
 * outside: gx = b[.][x0 + 2] - b[.][x0 - 1] summed over the cell's two rows, 6 times the
 * gradient. Built from pixels the sample does not use, its noise is independent of the
 * sample's, so the Gauss-Newton fixed point (sum g e = 0) is not pulled towards the cell
 * centre by the background's own noise (the two forward differences inside the cell would
 * correlate with the sample as 2 fx - 1). plain (a constant of each call: the function is
 * inlined twice) is a U16 frame without a bad-pixel map, whose samples are read without the
 * per-sample tests of the format and the map (the same values, the same sums). */
static inline void lk_loop_(const pft_pre_t *p, const pft_frame_t *f, const pft_pre_cls_t *c,
                            const warp_t *g, int32_t st, lk_sums_t *s, const bool plain)
{
    const int32_t w = p->cfg.width, h = p->cfg.height, bs = (int32_t)p->bgs;
    const uint32_t bf = p->bf;
    /* taps x + kx - 1 .. x + kx + 2 inside [0, w - 1], the same for rows */
    const int32_t xa = 1 - g->kx > 0 ? 1 - g->kx : 0, xb = (w - 3 - g->kx < w - 1 ? w - 3 - g->kx : w - 1);
    const int32_t ya = 1 - g->ky > 0 ? 1 - g->ky : 0, yb = (h - 3 - g->ky < h - 1 ? h - 3 - g->ky : h - 1);
    const uint32_t fx = g->fx, fy = g->fy, gx0 = 256u - fx, gy0 = 256u - fy;
    /* the sampling grid starts at a multiple of st so that it does not move with the shift */
    const int32_t x0 = (xa + st - 1) / st * st, y0 = (ya + st - 1) / st * st;
    const int32_t *cn = p->colnow;
    const uint32_t lo = c->lo, span = c->span, mask = c->mask;
    lk_sums_t acc = {0, 0, 0, 0, 0, 0, 0u}; /* a local, kept in registers */
    /* the rows' columns from c0 = x0 + kx - 1 (>= 0: x0 >= xa >= 1 - kx), the left tap column
     * less one of the first sample, so that one index i = xs - x0 reads every array */
    const int32_t c0 = x0 + g->kx - 1;
    for (int32_t y = y0; x0 <= xb && y <= yb; y += st) {
        const uint8_t *row = pft_frame_row(f, (uint32_t)y);
        const uint8_t *rz = row + 2 * x0;
        const int32_t *cz = cn + x0;
        /* rows y + ky - 1 .. y + ky + 2 of the background from column c0 (all inside: c0 and
         * the last tap column are in [0, w - 1]) */
        const uint16_t *bm = p->bgv + (size_t)(y + g->ky - 1) * (size_t)bs + (size_t)c0;
        const uint16_t *b0 = bm + bs, *b1 = b0 + bs, *b2 = b1 + bs;
#if defined(PFT_PRE_NEON_) || defined(__SSE2__)
        /* AArch64 and x86-64: the samples of the whole blocks of four in NEON's or SSE2's lanes
         * (st 2 or 4, plain) */
        const uint32_t par[6] = {mask, lo, span, bf, fx, fy};
        int32_t ia = 0;
        if (plain && st == 2) {
            ia = lk_row2v_(rz, cz, bm, bs, par, xb - x0, &acc);
        } else if (plain && st == 4) {
            ia = lk_row4v_(rz, cz, bm, bs, par, xb - x0, &acc);
        }
#else
        const int32_t ia = 0;
#endif
        for (int32_t i = ia; i <= xb - x0; i += st) {
            uint32_t v;
            if (plain) {
                uint16_t raw;
                memcpy(&raw, rz + 2 * i, 2u);
                v = (uint32_t)raw & mask;
                if (v - lo >= span) {
                    continue;
                }
            } else {
                const int32_t xs = x0 + i;
                v = pft_pre_raw_(row, (uint32_t)xs, c);
                if (v - lo >= span || (c->map != NULL && pft_pre_bad_(c, (uint32_t)xs, (uint32_t)y))) {
                    continue;
                }
            }
            /* column i + 1 is the left tap column xs + kx */
            const uint32_t b00 = b0[i + 1], b01 = b0[i + 2], b10 = b1[i + 1], b11 = b1[i + 2];
            const uint32_t h0 = b00 * gx0 + b01 * fx, h1 = b10 * gx0 + b11 * fx;
            const int32_t bw = (int32_t)((h0 * gy0 + h1 * fy + 32768u) >> 16);
            const int32_t e = (int32_t)(v << bf) - cz[i] - bw;
            const int32_t gx = ((int32_t)b0[i + 3] - b0[i]) + ((int32_t)b1[i + 3] - b1[i]);
            const int32_t gy = ((int32_t)b2[i + 1] - bm[i + 1]) + ((int32_t)b2[i + 2] - bm[i + 2]);
            lk_add_(&acc, gx, gy, e);
        }
    }
    *s = acc;
}

/* reg_bin (docs/algorithms.md 9.4 [E]): the sums over 2 x 2 boxes of pixels, box
 * (xs, xs + 1) x (y, y + 1) at the samples of lk_loop_: z the box's sum, the background B
 * the box sums of b (B(x, r) = b[r][x] + b[r][x + 1] + b[r + 1][x] + b[r + 1][x + 1]),
 * bilinear in its cell (x, x + 1) x (r, r + 1) with x = xs + kx, r = y + ky, so that e is 4
 * times a pixel's (U units times 4). The gradient is taken across the cell from the background
 * columns just outside the three it uses, b[.][x + 3] - b[.][x - 1] over its rows r, r + 1,
 * r + 2 weighted 1, 2, 1 (4 times the gradient of B; the solver takes gain 4), and the same
 * along y: from pixels the cell does not use, as in lk_loop_. Background columns x - 1 .. x + 3
 * and rows r - 1 .. r + 3. */
static inline void lk_bin_loop_(const pft_pre_t *p, const pft_frame_t *f, const pft_pre_cls_t *c,
                                const warp_t *g, int32_t st, lk_sums_t *s, const bool plain)
{
    const int32_t w = p->cfg.width, h = p->cfg.height, bs = (int32_t)p->bgs;
    const uint32_t bf = p->bf;
    const int32_t xa = 1 - g->kx > 0 ? 1 - g->kx : 0, xb = (w - 4 - g->kx < w - 2 ? w - 4 - g->kx : w - 2);
    const int32_t ya = 1 - g->ky > 0 ? 1 - g->ky : 0, yb = (h - 4 - g->ky < h - 2 ? h - 4 - g->ky : h - 2);
    const uint64_t fx = g->fx, fy = g->fy, gx0 = 256u - fx, gy0 = 256u - fy;
    const int32_t x0 = (xa + st - 1) / st * st, y0 = (ya + st - 1) / st * st;
    const int32_t *cn = p->colnow;
    const uint32_t lo = c->lo, span = c->span, mask = c->mask;
    lk_sums_t acc = {0, 0, 0, 0, 0, 0, 0u}; /* a local, kept in registers */
    for (int32_t y = y0; y <= yb; y += st) {
        const uint8_t *ra = pft_frame_row(f, (uint32_t)y), *rb = pft_frame_row(f, (uint32_t)y + 1u);
        const uint16_t *q1 = p->bgv + (size_t)(y + g->ky - 1) * (size_t)bs; /* row r - 1 */
        const uint16_t *q2 = q1 + bs, *q3 = q2 + bs, *q4 = q3 + bs, *q5 = q4 + bs;
        for (int32_t xs = x0; xs <= xb; xs += st) {
            uint32_t v0, v1, v2, v3;
            if (plain) {
                uint16_t a[2], b[2];
                memcpy(a, ra + 2 * xs, 4u);
                memcpy(b, rb + 2 * xs, 4u);
                v0 = (uint32_t)a[0] & mask;
                v1 = (uint32_t)a[1] & mask;
                v2 = (uint32_t)b[0] & mask;
                v3 = (uint32_t)b[1] & mask;
                if (v0 - lo >= span || v1 - lo >= span || v2 - lo >= span || v3 - lo >= span) {
                    continue;
                }
            } else {
                const uint32_t ux = (uint32_t)xs, uy = (uint32_t)y;
                v0 = pft_pre_raw_(ra, ux, c);
                v1 = pft_pre_raw_(ra, ux + 1u, c);
                v2 = pft_pre_raw_(rb, ux, c);
                v3 = pft_pre_raw_(rb, ux + 1u, c);
                if (!pft_pre_valid_(c, v0, ux, uy) || !pft_pre_valid_(c, v1, ux + 1u, uy) ||
                    !pft_pre_valid_(c, v2, ux, uy + 1u) || !pft_pre_valid_(c, v3, ux + 1u, uy + 1u)) {
                    continue;
                }
            }
            const int32_t x = xs + g->kx; /* the cell's left column */
            /* pairs of the cell's rows r .. r + 2 at columns x and x + 1 */
            const uint32_t m1 = q3[x + 1];
            const uint32_t p20 = (uint32_t)q2[x] + q2[x + 1], p21 = (uint32_t)q2[x + 1] + q2[x + 2];
            const uint32_t p30 = (uint32_t)q3[x] + m1, p31 = m1 + q3[x + 2];
            const uint32_t p40 = (uint32_t)q4[x] + q4[x + 1], p41 = (uint32_t)q4[x + 1] + q4[x + 2];
            const uint64_t h0 = (uint64_t)(p20 + p30) * gx0 + (uint64_t)(p21 + p31) * fx;
            const uint64_t h1 = (uint64_t)(p30 + p40) * gx0 + (uint64_t)(p31 + p41) * fx;
            const int32_t bw = (int32_t)((h0 * gy0 + h1 * fy + 32768u) >> 16);
            const int32_t zs = (int32_t)((v0 + v1 + v2 + v3) << bf) - 2 * (cn[xs] + cn[xs + 1]);
            const int32_t e = zs - bw;
            const int32_t gx = ((int32_t)q2[x + 3] - q2[x - 1]) + 2 * ((int32_t)q3[x + 3] - q3[x - 1]) +
                               ((int32_t)q4[x + 3] - q4[x - 1]);
            const int32_t gy = ((int32_t)q5[x] - q1[x]) + 2 * ((int32_t)q5[x + 1] - q1[x + 1]) +
                               ((int32_t)q5[x + 2] - q1[x + 2]);
            lk_add_(&acc, gx, gy, e);
        }
    }
    *s = acc;
}

static void lk_sums_(const pft_pre_t *p, const pft_frame_t *f, const pft_pre_cls_t *c,
                     const warp_t *g, int32_t st, lk_sums_t *s)
{
    if (p->cfg.reg_bin) {
        if (!c->u8 && c->map == NULL) {
            lk_bin_loop_(p, f, c, g, st, s, true);
        } else {
            lk_bin_loop_(p, f, c, g, st, s, false);
        }
        return;
    }
    if (!c->u8 && c->map == NULL) {
        if (st == 2) { /* the last iteration's step at reg_step 2 (the default), as a
                        * constant: the loop's strides are immediates and free registers
                        * (the same sums) */
            lk_loop_(p, f, c, g, 2, s, true);
        } else {
            lk_loop_(p, f, c, g, st, s, true);
        }
    } else {
        lk_loop_(p, f, c, g, st, s, false);
    }
}

/* Leading zeros of a 64-bit value (64 for 0). */
static uint32_t clz64_(uint64_t v)
{
    uint32_t n = 0u;
    if (v == 0u) {
        return 64u;
    }
    while ((v & ((uint64_t)1 << 63)) == 0u) {
        v <<= 1;
        n++;
    }
    return n;
}

/* num * 2^sh / den for num, den > 0, saturating at 2^62. */
static uint64_t scaled_ratio_(uint64_t num, int32_t sh, uint64_t den)
{
    if (sh < 0) {
        const uint32_t room = clz64_(den) > 1u ? clz64_(den) - 1u : 0u;
        if ((uint32_t)-sh <= room) {
            den <<= (uint32_t)-sh;
        } else {
            den <<= room;
            num >>= ((uint32_t)-sh - room);
        }
        return num / den;
    }
    const uint32_t room = clz64_(num) > 1u ? clz64_(num) - 1u : 0u;
    if ((uint32_t)sh <= room) {
        return (num << (uint32_t)sh) / den;
    }
    num <<= room;
    const uint32_t rest = (uint32_t)sh - room;
    if (rest >= 64u || (den >> rest) == 0u) {
        return (uint64_t)1 << 62;
    }
    return num / (den >> rest);
}

/* Solves the Gauss-Newton step delta = -k A^-1 v (A = [sxx sxy; sxy syy], v = [sxe sye],
 * from g = k grad b, gain k = 6, or 10 with reg_bin) in Q16.16 px; false when A is singular
 * or worse conditioned than 1 : 1000 (too little texture, or texture in one direction only).
 * When sd is not NULL, also the predicted standard deviations sd = sqrt(k^2 (see/n)
 * diag(A^-1)) in Q16.16 px. */
static bool lk_solve_(const lk_sums_t *s, int64_t gain, int32_t delta[2], int32_t sd[2])
{
    if (s->n < 16u || s->sxx <= 0 || s->syy <= 0) {
        return false;
    }
    /* scale every sum below 2^23: products below 2^46, numerators * 2^16 below 2^63 */
    int64_t m = s->sxx > s->syy ? s->sxx : s->syy;
    m = abs64_(s->sxy) > m ? abs64_(s->sxy) : m;
    m = abs64_(s->sxe) > m ? abs64_(s->sxe) : m;
    m = abs64_(s->sye) > m ? abs64_(s->sye) : m;
    uint32_t k = 0u;
    while ((m >> k) >= ((int64_t)1 << 23)) {
        k++;
    }
    const int64_t a = s->sxx >> k, b = s->sxy >> k, d = s->syy >> k;
    const int64_t vx = s->sxe >> k, vy = s->sye >> k;
    const int64_t det = a * d - b * b, tr = a + d;
    if (det <= 0 || det < (tr * tr) / 1024) {
        return false;
    }
    const int64_t nx = -gain * (d * vx - b * vy), ny = -gain * (a * vy - b * vx);
    const int64_t lim = (int64_t)1 << 46;
    const int64_t qx = pft_pre_div_rnd_((nx > lim ? lim : (nx < -lim ? -lim : nx)) * 65536, det);
    const int64_t qy = pft_pre_div_rnd_((ny > lim ? lim : (ny < -lim ? -lim : ny)) * 65536, det);
    const int64_t one = 65536; /* at most one pixel per step */
    delta[0] = (int32_t)(qx > one ? one : (qx < -one ? -one : qx));
    delta[1] = (int32_t)(qy > one ? one : (qy < -one ? -one : qy));
    if (sd != NULL) {
        /* var_x = k^2 (see/n) d / (det 2^k) px^2; in Q32: (k^2 (see/n) d) * 2^(32-k) / det
         * (k^2 e2s d < 100 2^33 2^23 < 2^64) */
        const uint64_t e2 = (uint64_t)s->see / s->n;
        const uint32_t ez = clz64_(e2 > 0u ? e2 : 1u);
        const int32_t se = ez < 31u ? (int32_t)(31u - ez) : 0; /* keep e2 below 2^33 */
        const uint64_t e2s = e2 >> se;
        const int32_t sh = 32 - (int32_t)k + se;
        const uint64_t g2 = (uint64_t)(gain * gain);
        sd[0] = (int32_t)pft_pre_isqrt64_(scaled_ratio_(g2 * e2s * (uint64_t)d, sh, (uint64_t)det));
        sd[1] = (int32_t)pft_pre_isqrt64_(scaled_ratio_(g2 * e2s * (uint64_t)a, sh, (uint64_t)det));
    }
    return true;
}

/* RMS of e over the sums' pixels in counts, Q16.16: sqrt(see/n) * 2^(16 - bf); with reg_bin
 * (box sums) of the boxes' means, sqrt(see/(16 n)) * 2^(16 - bf). */
static uint32_t rms_counts_(const lk_sums_t *s, uint32_t bf, bool bin)
{
    if (s->n == 0u) {
        return 0u;
    }
    const uint64_t m = (uint64_t)s->see / s->n / (bin ? 16u : 1u);
    const uint32_t sh = 32u - 2u * bf;
    return pft_pre_isqrt64_(m >= ((uint64_t)1 << (63u - sh)) ? ~(uint64_t)0 >> 1 : m << sh);
}

void pft_pre_register_(pft_pre_t *p, const pft_frame_t *f, pft_pre_acc_t *acc)
{
    pft_pre_cls_t c;
    pft_pre_cls_init_(p, &c);
    p->st.shift[0] = 0;
    p->st.shift[1] = 0;
    p->st.shift_sd[0] = 0;
    p->st.shift_sd[1] = 0;
    p->st.shift_coarse[0] = 0;
    p->st.shift_coarse[1] = 0;
    p->st.reg_rms = 0u;
    p->jumped = false;
    if (p->bg_frames == 0u) {
        return; /* the background starts from this frame */
    }
    if ((acc->flags & PFT_PRE_FLAG_HELD) != 0u) {
        acc->flags |= PFT_PRE_FLAG_REG_WEAK;
        return; /* a constant frame: nothing to register; background and offsets held */
    }
    if (p->cfg.bg_anchor) {
        anchor_view_(p); /* the grid read at the last frame's position: the step as in 9.4 */
    }
    projections_(p, f, &c);
    /* prediction: the last shift times the frame gap (1..16) */
    uint32_t gap = f->seq - p->last_seq;
    gap = gap >= 1u && gap <= 16u ? gap : 1u;
    int32_t pred[2];
    for (uint32_t a = 0; a < 2u; ++a) {
        const int64_t v = (int64_t)p->shift_prev[a] * gap;
        const int64_t lim = (int64_t)PFT_PRE_MAX_SEARCH << 16;
        pred[a] = (int32_t)(v > lim ? lim : (v < -lim ? -lim : v));
    }
    const int32_t rad = p->cfg.reg_search;
    const int32_t cx = rnd_(pred[0], 16), cy = rnd_(pred[1], 16);
    bool ex = false, ey = false;
    const int32_t nrows = (int32_t)((p->cfg.height + p->cfg.reg_step - 1u) / p->cfg.reg_step);
    int32_t ix = search_axis_(p->pzc, p->pbc, p->cfg.width, p->bf, p->colnow, nrows, cx,
                                    rad, &ex);
    /* the row projections sum every column: their column offsets are one constant */
    int32_t iy = search_axis_(p->pzr, p->pbr, p->cfg.height, p->bf, NULL, 0, cy, rad, &ey);
    /* an integer answer within 0.75 px of the sub-pixel prediction on both axes is the
     * rounding of a shift near a half pixel (drift plus jitter), not a jump: no 2-D check (it
     * costs 26 sums over 1/16 of the frame's pixels), the prediction stands */
    const bool near = abs64_((int64_t)ix * 65536 - pred[0]) <= 49152 &&
                      abs64_((int64_t)iy * 65536 - pred[1]) <= 49152;
    if ((ix != cx || iy != cy) && !ex && !ey && (near || !jump_2d_(p, f, &c, cx, cy, &ix, &iy))) {
        ix = cx; /* the projections' jump is not confirmed */
        iy = cy;
    }
    p->jumped = ix != cx || iy != cy; /* a jump does not feed the next prediction */
    p->st.shift_coarse[0] = ix;
    p->st.shift_coarse[1] = iy;
    if (ex || ey) {
        acc->flags |= PFT_PRE_FLAG_REG_LOST;
        p->bg_frames = 0u; /* the scene jumped beyond the search: restart the background */
        p->shift_prev[0] = 0;
        p->shift_prev[1] = 0;
        return;
    }
    int32_t s[2];
    s[0] = ix == cx ? pred[0] : ix * 65536;
    s[1] = iy == cy ? pred[1] : iy * 65536;
    bool ok = p->cfg.reg_iters > 0u;
    int32_t sd[2] = {0, 0};
    uint32_t rms = 0u;
    for (uint32_t it = 0; ok && it < p->cfg.reg_iters; ++it) {
        const warp_t g = warp_of_(s);
        lk_sums_t sums;
        /* iterations before the last sample every 2 step-th pixel of every 2 step-th row */
        const int32_t st = (int32_t)p->cfg.reg_step * (it + 1u < p->cfg.reg_iters ? 2 : 1);
        lk_sums_(p, f, &c, &g, st, &sums);
        int32_t dl[2];
        const bool last = it + 1u == p->cfg.reg_iters;
        rms = rms_counts_(&sums, p->bf, p->cfg.reg_bin);
        if (!lk_solve_(&sums, p->cfg.reg_bin ? 4 : 6, dl, sd)) {
            ok = false;
            break;
        }
        s[0] += dl[0];
        s[1] += dl[1];
        if (last || (dl[0] < 64 && dl[0] > -64 && dl[1] < 64 && dl[1] > -64)) {
            break; /* converged below 1/1024 px */
        }
    }
    /* the sub-pixel estimate must stay within 1.5 px of the integer search, and be precise:
     * a predicted standard deviation above 0.05 px means too little texture (a flat or
     * one-directional scene, where the noise alone would move the estimate) */
    if (ok && (abs64_((int64_t)s[0] - ix * 65536) > 98304 ||
               abs64_((int64_t)s[1] - iy * 65536) > 98304 || sd[0] > PFT_PRE_SD_MAX_ ||
               sd[1] > PFT_PRE_SD_MAX_)) {
        ok = false;
    }
    if (!ok) { /* not measurable: the integer search's shift (the rounded prediction when it
                * found nothing better); extrapolating a sub-pixel drift instead would move a
                * featureless background off a still scene frame after frame */
        if (p->cfg.reg_iters > 0u) {
            acc->flags |= PFT_PRE_FLAG_REG_WEAK;
        }
        s[0] = ix * 65536;
        s[1] = iy * 65536;
        sd[0] = 0;
        sd[1] = 0;
    }
    p->st.shift[0] = s[0];
    p->st.shift[1] = s[1];
    p->st.shift_sd[0] = sd[0];
    p->st.shift_sd[1] = sd[1];
    p->st.reg_rms = rms;
}

/* The vertical 4-tap sum of column x of the update pass (pft_pre_temporal_pass_): 16 x
 * 16-bit products, the taps biased by -32768 into int16, the bias added back as 32768 times
 * the weights' sum (256). */
static inline int32_t vtap_(const uint16_t *t0, const uint16_t *t1, const uint16_t *t2,
                            const uint16_t *t3, int16_t w0, int16_t w1, int16_t w2, int16_t w3,
                            int32_t x)
{
    const int16_t s0 = (int16_t)((int32_t)t0[x] - 32768);
    const int16_t s1 = (int16_t)((int32_t)t1[x] - 32768);
    const int16_t s2 = (int16_t)((int32_t)t2[x] - 32768);
    const int16_t s3 = (int16_t)((int32_t)t3[x] - 32768);
    const int32_t v = w0 * s0 + w1 * s1 + w2 * s2 + w3 * s3;
    return (v + 256 * 32768 + 8) >> 4;
}

/* ------------------------------------------------------------------ update pass */

#if defined(__SSE2__)
/* Where the compiler has SSE2 (x86-64), zspan_'s loop for pixels x0 .. x1 - 1 of a U16 row in
 * blocks of 8: v = raw & mask in 16-bit lanes, widened to 32 bits; zu = (v << bf) - cn[x] in
 * int32 lanes (the loop's wrapping 32-bit arithmetic), clamped to [0, 65535] without pmaxsd /
 * pminsd: a negative zu cleared by its own sign, one above 65535 or-ed with all ones, then the
 * low 16 bits kept; valid iff v - lo < span unsigned (the signed compare of both sides xor
 * 2^31); an invalid pixel -1 (all ones or-ed in) and counted into *ninv. The same values as
 * the loop. Returns the first pixel left to it. */
static inline uint32_t zspan8_(const uint8_t *row, const pft_pre_cls_t *c, uint32_t bf, const int32_t *cn,
                               int32_t *zl, uint32_t x0, uint32_t x1, uint32_t *ninv)
{
    const __m128i vm = _mm_set1_epi16((int16_t)(c->mask & 0xFFFFu)), sh = _mm_cvtsi32_si128((int32_t)bf);
    const __m128i top = _mm_set1_epi32(INT32_MIN), vlo = _mm_set1_epi32((int32_t)c->lo);
    const __m128i vsp = _mm_set1_epi32((int32_t)(c->span ^ 0x80000000u)), k16 = _mm_set1_epi32(65535);
    const __m128i zero = _mm_setzero_si128(), ones = _mm_cmpeq_epi32(zero, zero);
    __m128i nb = zero;
    uint32_t x = x0;
    for (; x + 8u <= x1; x += 8u) {
        const __m128i r = _mm_and_si128(_mm_loadu_si128((const __m128i *)(const void *)(row + 2u * x)), vm);
        const __m128i v2[2] = {_mm_unpacklo_epi16(r, zero), _mm_unpackhi_epi16(r, zero)};
        for (uint32_t h = 0u; h < 2u; ++h) {
            const __m128i v = v2[h];
            const __m128i zu = _mm_sub_epi32(_mm_sll_epi32(v, sh),
                                             _mm_loadu_si128((const __m128i *)(const void *)(cn + x + 4u * h)));
            const __m128i zc = _mm_and_si128(_mm_or_si128(_mm_andnot_si128(_mm_srai_epi32(zu, 31), zu),
                                                          _mm_cmpgt_epi32(zu, k16)), k16);
            const __m128i bad = _mm_xor_si128(_mm_cmplt_epi32(_mm_xor_si128(_mm_sub_epi32(v, vlo), top), vsp), ones);
            _mm_storeu_si128((__m128i *)(void *)(zl + x + 4u * h), _mm_or_si128(zc, bad));
            nb = _mm_sub_epi32(nb, bad);
        }
    }
    nb = _mm_add_epi32(nb, _mm_shuffle_epi32(nb, 0x4E));
    nb = _mm_add_epi32(nb, _mm_shuffle_epi32(nb, 0xB1));
    *ninv += (uint32_t)_mm_cvtsi128_si32(nb);
    return x;
}

/* zspan8_ for a test: pixels x0 .. x1 - 1 of a U16 row (mask, lo, span) in blocks of 8 into zl,
 * their masked pixels added to *ninv; returns the first pixel not done. */
uint32_t pft_pre_zspan8_(const uint8_t *row, uint32_t mask, uint32_t lo, uint32_t span, uint32_t bf,
                         const int32_t *cn, int32_t *zl, uint32_t x0, uint32_t x1, uint32_t *ninv)
{
    pft_pre_cls_t c;
    memset(&c, 0, sizeof(c));
    c.mask = mask;
    c.lo = lo;
    c.span = span;
    c.map = NULL;
    return zspan8_(row, &c, bf, cn, zl, x0, x1, ninv);
}
#endif

/* Row y of the frame in U units with the column offsets off, clamped to [0, 65535]; -1 for a
 * masked pixel. Returns the number of masked pixels. */
static uint32_t zspan_(const pft_pre_cls_t *c, const pft_frame_t *f, uint32_t y, uint32_t bf,
                       const int32_t *cn, int32_t *zl, uint32_t x0, uint32_t x1)
{
    const uint8_t *row = pft_frame_row(f, y);
    const uint32_t lo = c->lo, span = c->span, mask = c->mask;
    uint32_t ninv = 0u;
#if defined(__SSE2__)
    const uint32_t xs = c->u8 ? x0 : zspan8_(row, c, bf, cn, zl, x0, x1, &ninv);
#else
    const uint32_t xs = x0;
#endif
    for (uint32_t x = xs; x < x1; ++x) {
        const uint32_t v = pft_pre_raw_(row, x, c) & mask;
        int32_t zu = (int32_t)(v << bf) - cn[x];
        zu = zu < 0 ? 0 : (zu > 65535 ? 65535 : zu);
        const bool ok = v - lo < span;
        zl[x] = ok ? zu : -1;
        ninv += ok ? 0u : 1u;
    }
    if (c->map != NULL) {
        for (uint32_t x = x0; x < x1; ++x) {
            if (zl[x] >= 0 && pft_pre_bad_(c, x, y)) {
                zl[x] = -1;
                ninv++;
            }
        }
    }
    return ninv;
}

static uint32_t zrow_(const pft_pre_cls_t *c, const pft_frame_t *f, uint32_t y, uint32_t bf,
                      const int32_t *cn, int32_t *zl)
{
    return zspan_(c, f, y, bf, cn, zl, 0u, f->width);
}

/* The covered columns [x0, x1) of a U16 row without a bad-pixel map in one pass (the frame
 * row's conversion of zrow_, the horizontal taps of hcubic_ unclamped, and the update and
 * residual of the row loop of pft_pre_temporal_pass_, the same integer operations on each
 * pixel, without the two intermediate lines): the background b and the residual r of those
 * columns; returns their masked pixels. */
typedef struct {
    const int32_t *vb, *cn;
    int32_t kx, w0, w1, w2, w3, a15, k1;
    uint32_t bf;
} fused_t;

/* k1 (0 or 1) is a constant of each call (the function is inlined twice): with k1 = 1 the
 * residual (e + 1) / 2 of an unmasked pixel is at least -32767 (|e| <= 65535), so only its
 * upper clamp can act. The masked pixels are counted, and among them the dead ones (*ndead:
 * raw below lo; without a bad-pixel map the others are saturated), so that the raw row is not
 * read again after the residual is written: in place (pft_pre_update_inplace) r is that row. */
static inline uint32_t fused_loop_(const pft_pre_cls_t *c, const uint8_t *row, const fused_t *u,
                                   uint16_t *b, int16_t *r, int32_t x0, int32_t x1,
                                   const int32_t k1, uint32_t *ndead)
{
    const uint32_t lo = c->lo, span = c->span, mask = c->mask, bf = u->bf;
    const int32_t *vb = u->vb + u->kx, *cn = u->cn;
    const int32_t w0 = u->w0, w1 = u->w1, w2 = u->w2, w3 = u->w3, a15 = u->a15;
    uint32_t ninv = 0u, nd = 0u;
    for (int32_t x = x0; x < x1; ++x) { /* vectorisable */
        uint16_t raw;
        memcpy(&raw, row + 2 * x, 2u);
        const uint32_t v = (uint32_t)raw & mask;
        int32_t zu = (int32_t)(v << bf) - cn[x];
        zu = zu < 0 ? 0 : (zu > 65535 ? 65535 : zu);
        const bool ok = v - lo < span;
        zu = ok ? zu : -1;
        ninv += ok ? 0u : 1u;
        nd += v < lo ? 1u : 0u;
        const int32_t s = (w0 * vb[x - 1] + w1 * vb[x] + w2 * vb[x + 1] + w3 * vb[x + 2] + 2048) >> 12;
        const int32_t bx = s < 0 ? 0 : (s > 65535 ? 65535 : s);
        const int32_t e = zu - bx;
        /* the update's step masked by and-ing (a select here stops gcc's vectoriser) */
        const int32_t okm = ok ? -1 : 0;
        const int32_t nb = bx + (((e * a15 + 16384) >> 15) & okm);
        const int32_t rh = (e + k1) >> k1;
        const int32_t rr = k1 != 0 ? (rh > PFT_PRE_RMAX_ ? PFT_PRE_RMAX_ : rh) : pft_pre_rclamp_(rh);
        b[x] = (uint16_t)nb;
        r[x] = (int16_t)(zu < 0 ? PFT_RES16_MASKED : rr);
    }
    *ndead = nd;
    return ninv;
}

static uint32_t fused_span_(const pft_pre_cls_t *c, const uint8_t *row, const fused_t *u,
                            uint16_t *b, int16_t *r, int32_t x0, int32_t x1, uint32_t *ndead)
{
    return u->k1 != 0 ? fused_loop_(c, row, u, b, r, x0, x1, 1, ndead)
                      : fused_loop_(c, row, u, b, r, x0, x1, 0, ndead);
}

/* Counts the masked pixels of row y in columns [x0, x1) by cause. */
static void count_span_(const pft_pre_cls_t *c, const pft_frame_t *f, uint32_t y, uint32_t x0,
                        uint32_t x1, pft_pre_acc_t *acc)
{
    const uint8_t *row = pft_frame_row(f, y);
    for (uint32_t x = x0; x < x1; ++x) {
        const uint32_t v = pft_pre_raw_(row, x, c);
        if (!pft_pre_valid_(c, v, x, y)) {
            pft_pre_count_masked_(c, v, acc);
        }
    }
}

/* Counts the masked pixels of row y by cause (rows with masked pixels only). */
#if defined(PFT_PRE_NEON_)
/* With NEON (AArch64), count_row_ of a U16 frame without a bad-pixel map for pixels
 * 0 .. 8 (w / 8) - 1 in 32-bit lanes: a pixel v (masked by mask) is counted iff
 * v - lo >= span (unsigned), dead if v < lo, else saturated (pft_pre_count_masked_ without
 * the map's case). Adds to n_dead, n_sat; returns the first pixel left to the loop. */
static uint32_t count_row_v_(const uint8_t *row, uint32_t w, const pft_pre_cls_t *c, pft_pre_acc_t *acc)
{
    const uint16x8_t vm = vdupq_n_u16((uint16_t)(c->mask & 0xFFFFu));
    const uint32x4_t vlo = vdupq_n_u32(c->lo), vspan = vdupq_n_u32(c->span);
    uint32x4_t nd = vdupq_n_u32(0u), ns = nd;
    uint32_t x = 0u;
    for (; x + 8u <= w; x += 8u) {
        const uint16x8_t v16 = vandq_u16(vreinterpretq_u16_u8(vld1q_u8(row + 2u * x)), vm);
        const uint32x4_t va = vmovl_u16(vget_low_u16(v16)), vb = vmovl_high_u16(v16);
        const uint32x4_t ma = vcgeq_u32(vsubq_u32(va, vlo), vspan), mb = vcgeq_u32(vsubq_u32(vb, vlo), vspan);
        const uint32x4_t da = vcltq_u32(va, vlo), db = vcltq_u32(vb, vlo);
        nd = vsubq_u32(vsubq_u32(nd, vandq_u32(ma, da)), vandq_u32(mb, db));
        ns = vsubq_u32(vsubq_u32(ns, vbicq_u32(ma, da)), vbicq_u32(mb, db));
    }
    acc->n_dead += vaddvq_u32(nd);
    acc->n_sat += vaddvq_u32(ns);
    return x;
}
#elif defined(__SSE2__)
/* Where the compiler has SSE2 (x86-64), count_row_ of a U16 frame without a bad-pixel map for
 * pixels 0 .. 8 (w / 8) - 1 in 16-bit lanes: a pixel v (masked by mask, so below 2^16) is
 * counted iff v - lo >= span (unsigned), that is iff v < lo (dead) or v >= t = lo + span
 * (saturated), when lo < 2^16, span >= 1 and span <= 2^32 - 2^16 (then v < lo wraps v - lo to
 * at least 2^32 - 65535 > span, and t > lo); pft_pre_count_masked_ without the map's case. The
 * unsigned compares are the signed ones of both sides xor 0x8000 (t above 65535 as 65536: no
 * pixel saturated); a lane counts at most w / 8 <= 1024 pixels (PFT_CFG_MAX_IMAGE_SIDE). Other
 * limits leave the row to the loop (returns 0). Adds to n_dead, n_sat; returns the first pixel
 * left to the loop. */
static uint32_t count_row_v_(const uint8_t *row, uint32_t w, const pft_pre_cls_t *c, pft_pre_acc_t *acc)
{
    if (c->lo > 65535u || c->span < 1u || c->span > 0xFFFF0000u) {
        return 0u;
    }
    const uint64_t t = (uint64_t)c->lo + c->span;
    const uint32_t tm = t > 65536u ? 65535u : (uint32_t)t - 1u; /* t - 1, at most 65535 */
    const __m128i vm = _mm_set1_epi16((short)(int32_t)(c->mask & 0xFFFFu));
    const __m128i flip = _mm_set1_epi16((short)-32768);
    const __m128i vlo = _mm_set1_epi16((short)((int32_t)c->lo - 32768));
    const __m128i vtm = _mm_set1_epi16((short)((int32_t)tm - 32768));
    __m128i nd = _mm_setzero_si128(), ns = nd;
    uint32_t x = 0u;
    for (; x + 8u <= w; x += 8u) {
        const __m128i v = _mm_xor_si128(_mm_and_si128(_mm_loadu_si128((const __m128i *)(const void *)(row + 2u * x)), vm), flip);
        nd = _mm_sub_epi16(nd, _mm_cmplt_epi16(v, vlo));
        ns = _mm_sub_epi16(ns, _mm_cmpgt_epi16(v, vtm));
    }
    const __m128i one = _mm_set1_epi16(1);
    const __m128i d4 = _mm_madd_epi16(nd, one), s4 = _mm_madd_epi16(ns, one);
    __m128i s = _mm_add_epi32(_mm_unpacklo_epi32(d4, s4), _mm_unpackhi_epi32(d4, s4));
    s = _mm_add_epi32(s, _mm_shuffle_epi32(s, 0x4E)); /* lanes 0, 1: dead, saturated */
    acc->n_dead += (uint32_t)_mm_cvtsi128_si32(s);
    acc->n_sat += (uint32_t)_mm_cvtsi128_si32(_mm_shuffle_epi32(s, 0x55));
    return x;
}
#endif

#if defined(PFT_PRE_NEON_) || defined(__SSE2__)
/* count_row_v_ (count_row_'s NEON or SSE2 form) for a test: pixels 0 .. 8 (w / 8) - 1 of a U16
 * row (mask, lo, span) where the form takes them (the SSE2 form only within its limits, else
 * none); adds to cnt[0] (dead) and cnt[1] (saturated); returns the pixels done. */
uint32_t pft_pre_count_rowv_(const uint8_t *row, uint32_t w, uint32_t mask, uint32_t lo, uint32_t span,
                             uint32_t cnt[2])
{
    pft_pre_cls_t c;
    pft_pre_acc_t a;
    memset(&c, 0, sizeof(c));
    memset(&a, 0, sizeof(a));
    c.mask = mask;
    c.lo = lo;
    c.span = span;
    c.map = NULL;
    a.n_dead = cnt[0];
    a.n_sat = cnt[1];
    const uint32_t x = count_row_v_(row, w, &c, &a);
    cnt[0] = a.n_dead;
    cnt[1] = a.n_sat;
    return x;
}
#endif

static void count_row_(const pft_pre_cls_t *c, const pft_frame_t *f, uint32_t y,
                       pft_pre_acc_t *acc)
{
    const uint8_t *row = pft_frame_row(f, y);
#if defined(PFT_PRE_NEON_) || defined(__SSE2__)
    const uint32_t xa = (!c->u8 && c->map == NULL) ? count_row_v_(row, f->width, c, acc) : 0u;
#else
    const uint32_t xa = 0u;
#endif
    for (uint32_t x = xa; x < f->width; ++x) {
        const uint32_t v = pft_pre_raw_(row, x, c);
        if (!pft_pre_valid_(c, v, x, y)) {
            pft_pre_count_masked_(c, v, acc);
        }
    }
}

/* Background prediction of row pixels [x0, x1) from the vertical blends vb (U * 16) with the
 * horizontal cubic weights wx at columns x + kx - 1 .. x + kx + 2, clamped to the image when
 * clamp is set; into bw (U). */
static void hcubic_(const int32_t *vb, int32_t kx, const int32_t wx[4], int32_t w, int32_t x0,
                    int32_t x1, bool clamp, int32_t *bw)
{
    const int32_t w0 = wx[0], w1 = wx[1], w2 = wx[2], w3 = wx[3];
    if (!clamp) {
        for (int32_t x = x0; x < x1; ++x) { /* vectorisable; x + kx - 1 >= 0 here */
            const int32_t c = x + kx;
            const int32_t s = (w0 * vb[c - 1] + w1 * vb[c] + w2 * vb[c + 1] + w3 * vb[c + 2] + 2048) >> 12;
            bw[x] = s < 0 ? 0 : (s > 65535 ? 65535 : s);
        }
        return;
    }
    for (int32_t x = x0; x < x1; ++x) {
        const int32_t c = x + kx;
        const int32_t s = (w0 * vb[clampi_(c - 1, 0, w - 1)] + w1 * vb[clampi_(c, 0, w - 1)] +
                           w2 * vb[clampi_(c + 1, 0, w - 1)] + w3 * vb[clampi_(c + 2, 0, w - 1)] +
                           2048) >> 12;
        bw[x] = s < 0 ? 0 : (s > 65535 ? 65535 : s);
    }
}

/* ------------------------------------------------------------------ the anchored residual */

#if defined(__SSE2__) || defined(PFT_PRE_NEON_)
/* Where the compiler has SSE2 (x86-64), the anchored pass's residual (pft_pre_ares_span_) reads
 * its vertical blends in a split form and takes its horizontal 4-tap blend as one 16-bit
 * multiply-add (pmaddwd) per tap and 4 pixels, with the clamps and the residual in 16-bit
 * lanes, instead of 32 x 32-bit products (SSE2 has none: pmuludq pairs and shuffles), 32-bit
 * clamps and the narrowing to 16 bits. With NEON (AArch64) the "split" words are the 32-bit
 * values themselves (vsplit_, vjoin_: the identity; NEON has 32-bit mla) and the blend's
 * clamp, the narrowing and the residual take 16-bit lanes (sqrshrun, see ares_blocks_). The
 * Cortex-M builds keep the 32-bit loop (the same object code as before for the pass). */
#define PFT_PRE_RES_SPLIT_ 1
#endif

/* A vertical blend v (U * 16) as vl = v & 127 in the word's low 16 bits and vh = v >> 7 in its
 * high 16 bits: v = 128 vh + vl. v lies within [-2^21, 2^21) when the vertical weights' absolute
 * sum is at most 512 (grid values 0 .. 65535: |v| <= 512 * 65535 / 16 < 2^21; the Q8 weights of
 * warp_q8_ sum to at most 294), so vh is within [-16384, 16383] and the word is vl + 65536 vh;
 * a 16-bit multiply-add of the word with the pair (-w, -128 w) is -w v, exact in 32 bits for
 * w in [-255, 256] (-128 w within int16). */
static inline int32_t vsplit_(int32_t v)
{
#if defined(PFT_PRE_NEON_)
    return v; /* NEON's form reads the values themselves */
#else
    return (v & 127) | (int32_t)((uint32_t)(v >> 7) << 16);
#endif
}

int32_t pft_pre_vsplit_(int32_t v)
{
    return vsplit_(v);
}

/* v of a word made by vsplit_. */
static inline int32_t vjoin_(int32_t s)
{
#if defined(PFT_PRE_NEON_)
    return s;
#else
    return (s >> 16) * 128 + (s & 65535);
#endif
}

#if defined(PFT_PRE_RES_SPLIT_)
/* Whether the pass can take the split form: the read weights wx within [-255, 256] and both
 * axes' absolute sums at most 512 (vsplit_'s bounds, and |S| < 2^30 below; the Q8 weights of
 * warp_q8_ always are). */
static bool res_split_ok_(const int32_t wx[4], const int32_t wy[4])
{
#if defined(PFT_PRE_NEON_)
    (void)wx; /* NEON's form is the 32-bit loop's arithmetic: any weights */
    (void)wy;
    return true;
#else
    int32_t sx = 0, sy = 0;
    bool ok = true;
    for (int32_t i = 0; i < 4; ++i) {
        ok = ok && wx[i] >= -255 && wx[i] <= 256;
        sx += wx[i] < 0 ? -wx[i] : wx[i];
        sy += wy[i] < 0 ? -wy[i] : wy[i];
    }
    return ok && sx <= 512 && sy <= 512;
#endif
}

#if defined(PFT_PRE_NEON_)
/* NEON: the 4-tap sums of eight pixels, S = sum of w_i q[x + i] in int32 (mul, mla), then
 * (S + 2048) >> 12 clamped to [0, 65535] in one rounding, saturating narrowing (sqrshrun); the
 * anchored residual (ares_blocks_) and the view's horizontal pass (view_h8n_) share it. */
static inline uint16x8_t tap4_u16n_(const int32_t *q, int32x4_t w0, int32x4_t w1, int32x4_t w2,
                                    int32x4_t w3)
{
    int32x4_t sa = vmulq_s32(vld1q_s32(q), w0);
    int32x4_t sb = vmulq_s32(vld1q_s32(q + 4), w0);
    sa = vmlaq_s32(sa, vld1q_s32(q + 1), w1);
    sb = vmlaq_s32(sb, vld1q_s32(q + 5), w1);
    sa = vmlaq_s32(sa, vld1q_s32(q + 2), w2);
    sb = vmlaq_s32(sb, vld1q_s32(q + 6), w2);
    sa = vmlaq_s32(sa, vld1q_s32(q + 3), w3);
    sb = vmlaq_s32(sb, vld1q_s32(q + 7), w3);
    return vqrshrun_high_n_s32(vqrshrun_n_s32(sa, 12), sb, 12);
}

/* pft_pre_ares_span_'s pixels x .. x + 8 n - 1 (n blocks of 8) with NEON, k1 a constant of each
 * call: the 4-tap sum S of the 32-bit loop (mul, mla: the same int32 arithmetic), bx =
 * (S + 2048) >> 12 clamped to [0, 65535] in one rounding, saturating narrowing to uint16
 * (sqrshrun; its rounding is done before the saturation, in wider precision, as the loop's
 * int32 add: |S| < 2^30). zl's low halves (uzp1) are zl for an unmasked pixel (0 .. 65535),
 * its high halves' sign (uzp2, cmlt) is zl's. k1 0: with both biased by -32768 into int16 the
 * saturating difference is e = zl - bx clamped to [-32768, 32767], then the lower clamp at
 * -32767. k1 1: the unsigned halving difference (bx - zl) >> 1 (uhsub, exact before the
 * narrowing: within [-32768, 32767]) is -ceil(e / 2) = t, so (e + 1) >> 1 clamped to +-32767 is
 * -max(t, -32767). A masked pixel (zl < 0): PFT_RES16_MASKED. */
static inline void ares_blocks_(const int32_t *v, const int32_t *zl, int16_t *r, int32_t x,
                                int32_t n, const int32_t wr[4], const uint32_t k1)
{
    const int32x4_t w0 = vdupq_n_s32(wr[0]), w1 = vdupq_n_s32(wr[1]);
    const int32x4_t w2 = vdupq_n_s32(wr[2]), w3 = vdupq_n_s32(wr[3]);
    const uint16x8_t bias = vdupq_n_u16(32768u);
    const int16x8_t rmin = vdupq_n_s16(-PFT_PRE_RMAX_), msk = vdupq_n_s16(PFT_RES16_MASKED);
    for (int32_t i = 0; i < n; ++i, x += 8) {
        const int32_t *q = v + x;
        const uint16x8_t bx = tap4_u16n_(q, w0, w1, w2, w3);
        const uint16x8_t za = vreinterpretq_u16_s32(vld1q_s32(zl + x));
        const uint16x8_t zb = vreinterpretq_u16_s32(vld1q_s32(zl + x + 4));
        const uint16x8_t zlo = vuzp1q_u16(za, zb);
        const uint16x8_t masked = vcltzq_s16(vreinterpretq_s16_u16(vuzp2q_u16(za, zb)));
        int16x8_t rr;
        if (k1 == 0u) {
            rr = vqsubq_s16(vreinterpretq_s16_u16(veorq_u16(zlo, bias)),
                            vreinterpretq_s16_u16(veorq_u16(bx, bias)));
            rr = vmaxq_s16(rr, rmin);
        } else {
            rr = vnegq_s16(vmaxq_s16(vreinterpretq_s16_u16(vhsubq_u16(bx, zlo)), rmin));
        }
        vst1q_s16(r + x, vbslq_s16(masked, msk, rr));
    }
}
#else
/* The weight pair (-w, -128 w) of a tap as a 32-bit word (low, high 16 bits). */
static inline int32_t wpair_(int32_t w)
{
    return (int32_t)(((uint32_t)(-128 * w) << 16) | ((uint32_t)(-w) & 65535u));
}

/* pft_pre_ares_span_'s pixels x .. x + 8 n - 1 (n blocks of 8) from split words, k1 a constant
 * of each call. T = sum of the multiply-adds = -S (S the 4-tap sum of the 32-bit loop), and
 * s - 32768 = (2048 - 2^27 - T) >> 12 (|S| < 2^30, so no overflow), saturated to int16: that is
 * bx - 32768 with bx = s clamped to [0, 65535]. With a = zl - 32768 (exact for an unmasked
 * pixel, zl in [0, 65535]) the residual e = zl - bx is a - (bx - 32768): for k1 0 the
 * saturating difference then the lower clamp at -32767 is e clamped to +-32767; for k1 1 the
 * unsigned rounding average of bx and 65535 - zl is (65536 - e) >> 1 = 32768 - ceil(e / 2), so
 * its top bit flipped is q = -ceil(e / 2) within int16, and (e + 1) >> 1 = ceil(e / 2) clamped
 * to +-32767 is -max(q, -32767). A masked pixel (zl < 0): PFT_RES16_MASKED. */
static inline void ares_blocks_(const int32_t *v, const int32_t *zl, int16_t *r, int32_t x,
                                int32_t n, const int32_t wr[4], const uint32_t k1)
{
    const __m128i m0 = _mm_set1_epi32(wpair_(wr[0])), m1 = _mm_set1_epi32(wpair_(wr[1]));
    const __m128i m2 = _mm_set1_epi32(wpair_(wr[2])), m3 = _mm_set1_epi32(wpair_(wr[3]));
    const __m128i c27 = _mm_set1_epi32(2048 - 134217728), c15 = _mm_set1_epi32(32768);
    const __m128i zero = _mm_setzero_si128(), top = _mm_set1_epi16(INT16_MIN);
    const __m128i low = _mm_set1_epi16(INT16_MAX), rmin = _mm_set1_epi16(-PFT_PRE_RMAX_);
    for (int32_t i = 0; i < n; ++i, x += 8) {
        const int32_t *q = v + x;
        __m128i ta = _mm_madd_epi16(_mm_loadu_si128((const __m128i *)(const void *)q), m0);
        ta = _mm_add_epi32(ta, _mm_madd_epi16(_mm_loadu_si128((const __m128i *)(const void *)(q + 1)), m1));
        ta = _mm_add_epi32(ta, _mm_madd_epi16(_mm_loadu_si128((const __m128i *)(const void *)(q + 2)), m2));
        ta = _mm_add_epi32(ta, _mm_madd_epi16(_mm_loadu_si128((const __m128i *)(const void *)(q + 3)), m3));
        __m128i tb = _mm_madd_epi16(_mm_loadu_si128((const __m128i *)(const void *)(q + 4)), m0);
        tb = _mm_add_epi32(tb, _mm_madd_epi16(_mm_loadu_si128((const __m128i *)(const void *)(q + 5)), m1));
        tb = _mm_add_epi32(tb, _mm_madd_epi16(_mm_loadu_si128((const __m128i *)(const void *)(q + 6)), m2));
        tb = _mm_add_epi32(tb, _mm_madd_epi16(_mm_loadu_si128((const __m128i *)(const void *)(q + 7)), m3));
        const __m128i b16 = _mm_packs_epi32(_mm_srai_epi32(_mm_sub_epi32(c27, ta), 12),
                                            _mm_srai_epi32(_mm_sub_epi32(c27, tb), 12));
        const __m128i za = _mm_loadu_si128((const __m128i *)(const void *)(zl + x));
        const __m128i zb = _mm_loadu_si128((const __m128i *)(const void *)(zl + x + 4));
        const __m128i msk = _mm_packs_epi32(_mm_cmplt_epi32(za, zero), _mm_cmplt_epi32(zb, zero));
        const __m128i a16 = _mm_packs_epi32(_mm_sub_epi32(za, c15), _mm_sub_epi32(zb, c15));
        __m128i rr;
        if (k1 == 0u) {
            rr = _mm_max_epi16(_mm_subs_epi16(a16, b16), rmin);
        } else {
            const __m128i pa = _mm_avg_epu16(_mm_xor_si128(b16, top), _mm_xor_si128(a16, low));
            rr = _mm_sub_epi16(zero, _mm_max_epi16(_mm_xor_si128(pa, top), rmin));
        }
        rr = _mm_or_si128(_mm_and_si128(msk, top), _mm_andnot_si128(msk, rr));
        _mm_storeu_si128((__m128i *)(void *)(r + x), rr);
    }
}
#endif
#endif

/* The anchored pass's residual of row pixels [x0, x1]: the background bx (the 4-tap blend of
 * v[x] .. v[x + 3] with the read weights wr, clamped to [0, 65535]) and r[x] =
 * ((zl[x] - bx + k1) >> k1) clamped to +-PFT_PRE_RMAX_, PFT_RES16_MASKED where zl[x] < 0. With
 * split the words of v are vsplit_'s (res_split_ok_'s weights), taken 8 pixels at a time with
 * SSE2 or NEON where the compiler has it; the same values. */
void pft_pre_ares_span_(const int32_t *v, const int32_t *zl, int16_t *r, int32_t x0, int32_t x1,
                        const int32_t wr[4], uint32_t k1, bool split)
{
    const int32_t w0 = wr[0], w1 = wr[1], w2 = wr[2], w3 = wr[3];
    int32_t x = x0;
    if (split) {
#if defined(PFT_PRE_RES_SPLIT_)
        const int32_t nb = x1 >= x0 ? (x1 - x0 + 1) / 8 : 0;
        if (k1 == 0u) {
            ares_blocks_(v, zl, r, x0, nb, wr, 0u);
        } else {
            ares_blocks_(v, zl, r, x0, nb, wr, 1u);
        }
        x += 8 * nb;
#endif
        for (; x <= x1; ++x) {
            const int32_t sv = (w0 * vjoin_(v[x]) + w1 * vjoin_(v[x + 1]) + w2 * vjoin_(v[x + 2]) +
                                w3 * vjoin_(v[x + 3]) + 2048) >> 12;
            const int32_t bx = sv < 0 ? 0 : (sv > 65535 ? 65535 : sv);
            const int32_t rr = pft_pre_rclamp_((zl[x] - bx + (int32_t)k1) >> k1);
            r[x] = (int16_t)(zl[x] < 0 ? PFT_RES16_MASKED : rr);
        }
        return;
    }
    for (; x <= x1; ++x) { /* vectorisable */
        const int32_t sv = (w0 * v[x] + w1 * v[x + 1] + w2 * v[x + 2] + w3 * v[x + 3] + 2048) >> 12;
        const int32_t bx = sv < 0 ? 0 : (sv > 65535 ? 65535 : sv);
        const int32_t rr = pft_pre_rclamp_((zl[x] - bx + (int32_t)k1) >> k1);
        r[x] = (int16_t)(zl[x] < 0 ? PFT_RES16_MASKED : rr);
    }
}

/* ------------------------------------------------------------------ bg_anchor (9.12) */

/* Value of an invalid interpolated sample (a masked tap or a tap outside the frame). */
#define PFT_PRE_ANONE_ ((int32_t)-4194304) /* -2^22: below any interpolated row value (U * 16,
                                            * above -2^21), and times the weights (their |sum|
                                            * below 512) still inside int32 */

/* Geometry of one axis of the anchored grid for the position fraction phi (Q16): the read
 * (pixel x reads cells x + k - 1 .. x + k + 2 with weights wr, non-zero from rlo to rhi) and
 * the update (cell j is frame position j - phi: taps j + ub - 1 .. j + ub + 2 with weights wu,
 * non-zero from ulo to uhi), both at the fraction rounded to 1/256 px. */
typedef struct {
    int32_t k, ub;
    int32_t wr[4], wu[4];
    int32_t rlo, rhi, ulo, uhi;
} agx_t;

static void agx_of_(int32_t phi, bool cubic, agx_t *g)
{
    const int32_t u = (phi + 128) >> 8; /* 0 .. 256 */
    const uint32_t fr = (uint32_t)(u & 255);
    g->k = u >> 8;
    warp_q8_(fr, cubic, g->wr);
    if (fr == 0u) {
        g->ub = -g->k; /* the cell is a pixel */
        warp_q8_(0u, cubic, g->wu);
    } else {
        g->ub = -g->k - 1; /* pixel j - k - 1 plus the fraction 1 - fr / 256 */
        warp_q8_(256u - fr, cubic, g->wu);
    }
    g->rlo = g->wr[0] != 0 ? -1 : 0;
    g->rhi = g->wr[3] != 0 ? 2 : (g->wr[2] != 0 ? 1 : 0);
    g->ulo = g->wu[0] != 0 ? -1 : 0;
    g->uhi = g->wu[3] != 0 ? 2 : (g->wu[2] != 0 ? 1 : 0);
}

/* bg_gate_young: the ages of n grid columns (or rows) after a whole-cell move by d: new
 * entry i holds old entry i + d; the entries that come in are 0 (they hold no scene yet). */
static void age_move_(uint8_t *age, int32_t n, int32_t d)
{
    if (d > 0 && d < n) {
        memmove(age, age + d, (size_t)(n - d));
        memset(age + (n - d), 0, (size_t)d);
    } else if (d < 0 && -d < n) {
        memmove(age - d, age, (size_t)(n + d));
        memset(age, 0, (size_t)-d);
    } else if (d != 0) {
        memset(age, 0, (size_t)n);
    } else {
        /* no move */
    }
}

/* bg_gate_young: after a frame's update, the columns (rows) in the valid range both before
 * (ovlo .. ovhi) and after it (avlo .. avhi) one frame older (at most 255), the others 0 (they
 * entered with this frame or hold no scene). Cell j is entry j + 1. */
static void age_step_(uint8_t *age, int32_t n, int32_t ovlo, int32_t ovhi, int32_t avlo, int32_t avhi)
{
    for (int32_t i = 0; i < n; ++i) {
        const int32_t j = i - 1;
        const bool kept = j >= ovlo && j <= ovhi && j >= avlo && j <= avhi;
        age[i] = (uint8_t)(kept ? (age[i] < 255u ? age[i] + 1u : 255u) : 0u);
    }
}

/* A whole-cell move of the anchor by (dx, dy): new cell (j, J) holds old cell (j + dx,
 * J + dy), by one memmove of the stored values (exact; the cells that wrap around a row end
 * are outside the valid ranges, moved with the anchor and cut to the grid). */
static void anchor_move_(pft_pre_t *p, int32_t dx, int32_t dy)
{
    const int32_t sw = (int32_t)p->cfg.width + 3, sh = (int32_t)p->cfg.height + 3;
    const int64_t n = (int64_t)sw * sh, d = (int64_t)dy * sw + dx;
    if (d > 0 && d < n) {
        memmove(p->bg, p->bg + d, (size_t)(n - d) * 2u);
    } else if (d < 0 && -d < n) {
        memmove(p->bg - d, p->bg, (size_t)(n + d) * 2u);
    } else {
        /* no move, or none of the cells stays in the grid */
    }
    if (p->sage != NULL) { /* bg_stale_reinit: the ages move with their cells */
        if (d > 0 && d < n) {
            memmove(p->sage, p->sage + d, (size_t)(n - d));
        } else if (d < 0 && -d < n) {
            memmove(p->sage - d, p->sage, (size_t)(n + d));
        } else {
            /* no move, or none of the cells stays in the grid */
        }
        /* the rows' largest ages, an upper bound: new row r holds cells of old rows r + dy and
         * r + dy + 1 (dx > 0) or r + dy - 1 (dx < 0) */
        if (d != 0) {
            const int32_t e = dx > 0 ? 1 : (dx < 0 ? -1 : 0);
            uint8_t *sr = p->srow, *tmp = p->sline;
            memcpy(tmp, sr, (size_t)sh);
            for (int32_t r = 0; r < sh; ++r) {
                const int32_t r1 = r + dy, r2 = r + dy + e;
                const uint32_t m1 = r1 >= 0 && r1 < sh ? tmp[r1] : 0u;
                const uint32_t m2 = r2 >= 0 && r2 < sh ? tmp[r2] : 0u;
                sr[r] = (uint8_t)(m1 > m2 ? m1 : m2);
            }
        }
    }
    const int32_t dd[2] = {dx, dy}, top[2] = {sw - 2, sh - 2};
    if (p->agex != NULL) {
        age_move_(p->agex, sw, dx);
        age_move_(p->agey, sh, dy);
    }
    for (uint32_t a = 0; a < 2u; ++a) {
        const int64_t lo = (int64_t)p->avlo[a] - dd[a], hi = (int64_t)p->avhi[a] - dd[a];
        p->avlo[a] = (int32_t)(lo < -1 ? -1 : (lo > top[a] ? top[a] + 1 : lo));
        p->avhi[a] = (int32_t)(hi > top[a] ? top[a] : (hi < -1 ? -2 : hi));
    }
}

#if defined(__SSE2__)
/* Where the compiler has SSE2 (x86-64), anchor_view_'s horizontal 4-tap pass takes 16 x 16-bit
 * products: each vertical blend vb is kept as two int16 halves, vh = vb >> 15 and
 * vl = vb & 32767 (vb = 32768 vh + vl), and the pass forms hs = sum of w vh in 16-bit lanes and
 * ls = sum of w vl from 16 x 16-bit products, with the clamp in 16-bit lanes, instead
 * of 32 x 32-bit products, 32-bit clamps and the narrowing to 16 bits, which SSE2 lacks
 * (pmuludq and shuffles). NEON has them (32-bit mla, shrn: the 32-bit pass is 39 AArch64
 * instructions per 8 pixels; view_h32_ takes its horizontal pass in 22), and a scalar core
 * (Cortex-M) would pay twice the multiplies: those keep the 32-bit form (the same object code
 * as before). Both passes are written with
 * SSE2 intrinsics (view_vrow_, view_hrow_): pmaddwd takes two taps' products
 * and their sum in one instruction, and the saturating pack makes the clamp; the last pixels
 * of a row (fewer than 8) take the same values from the scalar form. */
#define PFT_PRE_VIEW_SPLIT_ 1

/* Two Q8 weights as the int16 pair (lo, hi) of each 32-bit lane: pmaddwd's second operand. */
static __m128i view_wpair_(int32_t lo, int32_t hi)
{
    return _mm_set1_epi32((int)((uint32_t)(uint16_t)(int16_t)lo | ((uint32_t)(uint16_t)(int16_t)hi << 16)));
}

/* The four-tap blend of 8 lanes of int16 taps s0 .. s3 with the weight pairs w01, w23
 * (view_wpair_): w0 s0 + w1 s1 + w2 s2 + w3 s3 + k, as two pmaddwd of the interleaved pairs
 * (exact in int32 while each product is within +-256 * 32768); lanes 0 .. 3 in *lo, 4 .. 7 in
 * *hi. */
static inline void blend4_8_(__m128i s0, __m128i s1, __m128i s2, __m128i s3, __m128i w01, __m128i w23,
                             __m128i k, __m128i *lo, __m128i *hi)
{
    *lo = _mm_add_epi32(_mm_add_epi32(_mm_madd_epi16(_mm_unpacklo_epi16(s0, s1), w01),
                                      _mm_madd_epi16(_mm_unpacklo_epi16(s2, s3), w23)), k);
    *hi = _mm_add_epi32(_mm_add_epi32(_mm_madd_epi16(_mm_unpackhi_epi16(s0, s1), w01),
                                      _mm_madd_epi16(_mm_unpackhi_epi16(s2, s3), w23)), k);
}

/* blend4_8_ of the storage rows t0 .. t3 at columns i .. i + 7, each tap biased by -32768 into
 * int16 (t xor 0x8000: the same bits as vtap_'s s). */
static inline void vblend8_(const uint16_t *t0, const uint16_t *t1, const uint16_t *t2, const uint16_t *t3,
                            int32_t i, __m128i w01, __m128i w23, __m128i k, __m128i *lo, __m128i *hi)
{
    const __m128i flip = _mm_set1_epi16((short)-32768);
    blend4_8_(_mm_xor_si128(_mm_loadu_si128((const __m128i *)(const void *)(t0 + i)), flip),
              _mm_xor_si128(_mm_loadu_si128((const __m128i *)(const void *)(t1 + i)), flip),
              _mm_xor_si128(_mm_loadu_si128((const __m128i *)(const void *)(t2 + i)), flip),
              _mm_xor_si128(_mm_loadu_si128((const __m128i *)(const void *)(t3 + i)), flip), w01, w23, k, lo, hi);
}

/* The vertical pass of 8 columns i .. i + 7: v = vtap_ of the storage rows t0 .. t3 (weight
 * pairs w01, w23) as the halves vh = v >> 15 and vl = v & 32767. The taps biased by -32768
 * (t xor 0x8000 as int16: the same bits as vtap_'s s), pmaddwd forms w0 s0 + w1 s1 and
 * w2 s2 + w3 s3 (each product within +-256 * 32768, no overflow), the bias and rounding added
 * as vtap_'s; vh in [-4, 35] and vl in [0, 32767] pack to int16 unsaturated (packssdw). */
static inline void view_v8_(const uint16_t *t0, const uint16_t *t1, const uint16_t *t2,
                            const uint16_t *t3, __m128i w01, __m128i w23, int16_t *vh, int16_t *vl,
                            int32_t i)
{
    const __m128i add = _mm_set1_epi32(256 * 32768 + 8), m15 = _mm_set1_epi32(32767);
    __m128i lo, hi;
    vblend8_(t0, t1, t2, t3, i, w01, w23, add, &lo, &hi);
    lo = _mm_srai_epi32(lo, 4);
    hi = _mm_srai_epi32(hi, 4);
    _mm_storeu_si128((__m128i *)(void *)(vh + i),
                     _mm_packs_epi32(_mm_srai_epi32(lo, 15), _mm_srai_epi32(hi, 15)));
    _mm_storeu_si128((__m128i *)(void *)(vl + i),
                     _mm_packs_epi32(_mm_and_si128(lo, m15), _mm_and_si128(hi, m15)));
}

/* The vertical pass of one row, columns 0 .. n - 1 (view_v8_; a row of 8 or more columns
 * ends with the 8 up to n - 1 again, overlapping, a shorter one is taken by vtap_). */
static inline void view_vrow_(const uint16_t *t0, const uint16_t *t1, const uint16_t *t2,
                              const uint16_t *t3, const int32_t w[4], int16_t *vh, int16_t *vl,
                              int32_t n)
{
    const __m128i w01 = view_wpair_(w[0], w[1]), w23 = view_wpair_(w[2], w[3]);
    if (n >= 8) {
        for (int32_t i = 0; i + 8 <= n; i += 8) {
            view_v8_(t0, t1, t2, t3, w01, w23, vh, vl, i);
        }
        if ((n & 7) != 0) {
            view_v8_(t0, t1, t2, t3, w01, w23, vh, vl, n - 8);
        }
        return;
    }
    const int16_t g0 = (int16_t)w[0], g1 = (int16_t)w[1], g2 = (int16_t)w[2], g3 = (int16_t)w[3];
    for (int32_t i = 0; i < n; ++i) {
        const int32_t v = vtap_(t0, t1, t2, t3, g0, g1, g2, g3, i);
        vh[i] = (int16_t)(v >> 15);
        vl[i] = (int16_t)(v & 32767);
    }
}

void pft_pre_view_vrow_(const uint16_t *t0, const uint16_t *t1, const uint16_t *t2,
                        const uint16_t *t3, const int32_t w[4], int16_t *vh, int16_t *vl,
                        int32_t n)
{
    view_vrow_(t0, t1, t2, t3, w, vh, vl, n);
}

/* Weights of the horizontal pass: each of the four in 16-bit lanes, and as pmaddwd pairs. */
typedef struct {
    __m128i h0, h1, h2, h3, w01, w23;
} view_hw_t;

/* The horizontal pass of pixels x .. x + 7 from a = vh + k, l = vl + k (no clamped tap): the
 * ranges and the form at pft_pre_view_hrow_. */
static inline void view_h8_(const int16_t *a, const int16_t *l, const view_hw_t *g, uint16_t *o,
                            int32_t x)
{
    const __m128i add = _mm_set1_epi32(2048 - 134217728), zero = _mm_setzero_si128();
    const __m128i flip = _mm_set1_epi16((short)-32768);
    const __m128i a0 = _mm_loadu_si128((const __m128i *)(const void *)(a + x));
    const __m128i a1 = _mm_loadu_si128((const __m128i *)(const void *)(a + x + 1));
    const __m128i a2 = _mm_loadu_si128((const __m128i *)(const void *)(a + x + 2));
    const __m128i a3 = _mm_loadu_si128((const __m128i *)(const void *)(a + x + 3));
    const __m128i hs = _mm_add_epi16(_mm_add_epi16(_mm_mullo_epi16(a0, g->h0), _mm_mullo_epi16(a1, g->h1)),
                                     _mm_add_epi16(_mm_mullo_epi16(a2, g->h2), _mm_mullo_epi16(a3, g->h3)));
    const __m128i l0 = _mm_loadu_si128((const __m128i *)(const void *)(l + x));
    const __m128i l1 = _mm_loadu_si128((const __m128i *)(const void *)(l + x + 1));
    const __m128i l2 = _mm_loadu_si128((const __m128i *)(const void *)(l + x + 2));
    const __m128i l3 = _mm_loadu_si128((const __m128i *)(const void *)(l + x + 3));
    __m128i lo = _mm_add_epi32(_mm_madd_epi16(_mm_unpacklo_epi16(l0, l1), g->w01),
                               _mm_madd_epi16(_mm_unpacklo_epi16(l2, l3), g->w23));
    __m128i hi = _mm_add_epi32(_mm_madd_epi16(_mm_unpackhi_epi16(l0, l1), g->w01),
                               _mm_madd_epi16(_mm_unpackhi_epi16(l2, l3), g->w23));
    /* 8 hs in int32: hs in the high half of a lane, shifted down by 13 */
    lo = _mm_add_epi32(_mm_srai_epi32(_mm_add_epi32(lo, add), 12),
                       _mm_srai_epi32(_mm_unpacklo_epi16(zero, hs), 13));
    hi = _mm_add_epi32(_mm_srai_epi32(_mm_add_epi32(hi, add), 12),
                       _mm_srai_epi32(_mm_unpackhi_epi16(zero, hs), 13));
    _mm_storeu_si128((__m128i *)(void *)(o + x), _mm_xor_si128(_mm_packs_epi32(lo, hi), flip));
}

/* The horizontal pass of one row: o[x] = (sum over i of w[i] vb[x + k + i] + 2048) >> 12,
 * clamped to [0, 65535], for x in [0, n), with vb = 32768 vh + vl of sw storage columns (the
 * taps past sw - 1 clamped to it). The ranges (every bit depth: the grid holds U values,
 * 0 .. 65535; the bound is per pixel, so for any frame size and width): the weights are Q8
 * summing to 256, bilinear in [0, 256], Catmull-Rom (cubic_q8_, all 256 fractions) in
 * [-19, 256] with the positive ones summing to at most 288 and the negative ones to at least
 * -32. So vb = (sum of w t + 8) >> 4 lies in [(-32 * 65535 + 8) >> 4, (288 * 65535 + 8) >> 4] =
 * [-131070, 1179630], vh = vb >> 15 in [-4, 35] and vl in [0, 32767]; each product w vh within
 * +-256 * 35 = 8960 and hs = sum of w vh within [-32 * 35 - 288 * 4, 288 * 35 + 32 * 4] =
 * [-2272, 10208] (int16: pmullw's low halves summed mod 2^16 are hs itself); ls = sum of w vl
 * within [-32 * 32767, 288 * 32767] (< 2^24, int32; pmaddwd: w0 l0 + w1 l1, w2 l2 + w3 l3).
 * The sum of w vb is 32768 hs + ls, so (sum + 2048) >> 12 = 8 hs + ((ls + 2048) >> 12)
 * exactly (32768 = 8 * 4096). The clamp: sv - 32768 = 8 hs + ((ls + 2048 - 2^27) >> 12)
 * (2^27 = 32768 * 4096: exact) in int32, packed with signed saturation to int16 (clamp to
 * [-32768, 32767]) and the sign bit flipped: the clamp of sv to [0, 65535] as uint16. The
 * pixels whose taps stay below sw (x < xv) go 8 at a time, the last 8 of them again
 * (overlapping) when xv is not a multiple of 8; the rest, and rows shorter than 8, in the
 * scalar form. */
static inline void view_hrow_(const int16_t *vh, const int16_t *vl, int32_t sw, int32_t k,
                              const int32_t w[4], uint16_t *o, int32_t n)
{
    const int16_t *a = vh + k, *l = vl + k;
    view_hw_t g;
    g.h0 = _mm_set1_epi16((short)w[0]);
    g.h1 = _mm_set1_epi16((short)w[1]);
    g.h2 = _mm_set1_epi16((short)w[2]);
    g.h3 = _mm_set1_epi16((short)w[3]);
    g.w01 = view_wpair_(w[0], w[1]);
    g.w23 = view_wpair_(w[2], w[3]);
    /* x + 7 + k + 3 <= sw - 1: the vector form reads no clamped tap */
    const int32_t xv = sw - 3 - k < n ? sw - 3 - k : n;
    int32_t x = 0;
    if (xv >= 8) {
        for (; x + 8 <= xv; x += 8) {
            view_h8_(a, l, &g, o, x);
        }
        if (x < xv) {
            view_h8_(a, l, &g, o, xv - 8);
            x = xv;
        }
    }
    for (; x < n; ++x) {
        int32_t sv = 2048;
        for (int32_t i = 0; i < 4; ++i) {
            const int32_t c = clampi_(x + k + i, 0, sw - 1);
            sv += w[i] * (vh[c] * 32768 + vl[c]);
        }
        sv >>= 12;
        o[x] = (uint16_t)(sv < 0 ? 0 : (sv > 65535 ? 65535 : sv));
    }
}

void pft_pre_view_hrow_(const int16_t *vh, const int16_t *vl, int32_t sw, int32_t k,
                        const int32_t w[4], uint16_t *o, int32_t n)
{
    view_hrow_(vh, vl, sw, k, w, o, n);
}
#endif

#if defined(PFT_PRE_NEON_)
/* With NEON (AArch64), anchor_view_'s horizontal pass of the 32-bit form for pixels 0 .. 8 m - 1
 * (m = xe / 8 blocks): o[x] = (sum of w[i] v[x + i] + 2048) >> 12 clamped to [0, 65535], the
 * same int32 sum (mul, mla) and the rounding, clamp and narrowing in one instruction
 * (sqrshrun: the rounding add in wider precision, then the unsigned saturation to 16 bits)
 * instead of the add, shift, two clamps and narrowing of the loop gcc makes; reads
 * v[0 .. 8 m + 2]. Returns 8 m, the first pixel left to the loop. */
static inline void view_h8n_(const int32_t *q, int32x4_t w0, int32x4_t w1, int32x4_t w2,
                             int32x4_t w3, uint16_t *o)
{
    vst1q_u16(o, tap4_u16n_(q, w0, w1, w2, w3));
}

static inline int32_t view_h32_(const int32_t *v, const int32_t w[4], uint16_t *o, int32_t xe)
{
    const int32x4_t w0 = vdupq_n_s32(w[0]), w1 = vdupq_n_s32(w[1]);
    const int32x4_t w2 = vdupq_n_s32(w[2]), w3 = vdupq_n_s32(w[3]);
    int32_t x = 0;
    for (; x + 8 <= xe; x += 8) {
        view_h8n_(v + x, w0, w1, w2, w3, o + x);
    }
    return x;
}

/* view_h32_ for a test: pixels 0 .. 8 (xe / 8) - 1 of a row of vertical blends v
 * (v[0 .. xe + 2]), the rest (xe mod 8 pixels) left as they are; returns the pixels done. */
int32_t pft_pre_view_h32_(const int32_t *v, const int32_t w[4], uint16_t *o, int32_t xe)
{
    return view_h32_(v, w, o, xe);
}
#endif

static void anchor_view_(pft_pre_t *p)
{
    const int32_t w = p->cfg.width, h = p->cfg.height, sw = w + 3;
    agx_t gx;
    agx_t gy;
    agx_of_(p->aphi[0], p->cfg.warp_cubic, &gx);
    agx_of_(p->aphi[1], p->cfg.warp_cubic, &gy);
    uint16_t *out = (uint16_t *)(void *)p->res;
#ifdef PFT_PRE_VIEW_SPLIT_
    /* The halves take the scratch's first sw int32 words (2 sw int16 values), as the 32-bit
     * row did (the ranges: pft_pre_view_hrow_). */
    int16_t *vh = (int16_t *)(void *)p->aring;
    int16_t *vl = vh + sw;
    for (int32_t y = 0; y < h; ++y) {
        const uint16_t *t[4];
        for (int32_t i = 0; i < 4; ++i) { /* storage rows y + k .. y + k + 3, clamped */
            t[i] = p->bg + (size_t)clampi_(y + gy.k + i, 0, h + 2) * (size_t)sw;
        }
        view_vrow_(t[0], t[1], t[2], t[3], gy.wr, vh, vl, sw);
        /* storage columns x + k .. x + k + 3; the last pixel's fourth tap (k = 1) clamped */
        view_hrow_(vh, vl, sw, gx.k, gx.wr, out + (size_t)y * (size_t)w, w);
    }
#else
    const int16_t gw0 = (int16_t)gy.wr[0], gw1 = (int16_t)gy.wr[1], gw2 = (int16_t)gy.wr[2];
    const int16_t gw3 = (int16_t)gy.wr[3];
    int32_t *vb = p->aring;
    for (int32_t y = 0; y < h; ++y) {
        const uint16_t *t[4];
        for (int32_t i = 0; i < 4; ++i) { /* storage rows y + k .. y + k + 3, clamped */
            t[i] = p->bg + (size_t)clampi_(y + gy.k + i, 0, h + 2) * (size_t)sw;
        }
        /* (sum of wr t + 8) >> 4 in 16 x 16-bit products (vtap_: the weights sum to 256) */
        for (int32_t i = 0; i < sw; ++i) { /* vectorisable */
            vb[i] = vtap_(t[0], t[1], t[2], t[3], gw0, gw1, gw2, gw3, i);
        }
        uint16_t *o = out + (size_t)y * (size_t)w;
        /* storage columns x + k .. x + k + 3; the last pixel's fourth tap (k = 1) clamped */
        const int32_t *v = vb + gx.k;
        const int32_t w0 = gx.wr[0], w1 = gx.wr[1], w2 = gx.wr[2], w3 = gx.wr[3];
        const int32_t xe = w - gx.k; /* x < xe: x + k + 3 <= w + 2 */
        int32_t xs = 0; /* the first pixel of the loop */
#if defined(PFT_PRE_NEON_)
        xs = view_h32_(v, gx.wr, o, xe);
#endif
        for (int32_t x = xs; x < xe; ++x) { /* vectorisable */
            const int32_t sv = (w0 * v[x] + w1 * v[x + 1] + w2 * v[x + 2] + w3 * v[x + 3] + 2048) >> 12;
            o[x] = (uint16_t)(sv < 0 ? 0 : (sv > 65535 ? 65535 : sv));
        }
        for (int32_t x = xe; x < w; ++x) {
            const int32_t i = x + gx.k;
            const int32_t sv = (w0 * vb[i] + w1 * vb[i + 1] + w2 * vb[i + 2] +
                                w3 * vb[clampi_(i + 3, 0, sw - 1)] + 2048) >> 12;
            o[x] = (uint16_t)(sv < 0 ? 0 : (sv > 65535 ? 65535 : sv));
        }
    }
#endif
}

/* The geometry of one frame's anchored pass: the read and update taps per axis, the valid
 * ranges before the update (ov) and the observed cells (o), alpha in 15 bits. */
typedef struct {
    agx_t gx;
    agx_t gy;
    int32_t ovlo[2], ovhi[2], olo[2], ohi[2];
    int32_t a15;
    bool gate; /* bg_gate set */
    /* bg_edge_narrow: the cells its 3-tap update observes (llo .. lhi; edge false: unused); its
     * weights are made where they are used (edge_uw_, edge_rw_), so that this struct, held
     * through the whole pass, grows by these 20 bytes only (the stage's stack bound) */
    bool edge;
    int32_t llo[2], lhi[2];
} anchor_geom_t;

/* bg_gate (docs/algorithms.md 9.13): the tile of grid cell (j, jy), that of its nearest pixel
 * (j, jy clamped into the frame). */
static uint32_t gate_tile_(const pft_pre_t *p, int32_t jy, int32_t j)
{
    const int32_t t = (int32_t)p->cfg.tile;
    const uint32_t ty = (uint32_t)(clampi_(jy, 0, (int32_t)p->cfg.height - 1) / t);
    const uint32_t tx = (uint32_t)(clampi_(j, 0, (int32_t)p->cfg.width - 1) / t);
    return ty * p->ntx + tx;
}

/* bg_gate: the clip of the update's innovation for grid cell (j, jy), U units: g sigma with
 * sigma the last estimate of the cell's tile (gate_tile_); 65535 (no clip) while that tile has
 * none. */
static int32_t gate_lim_g_(const pft_pre_t *p, int32_t jy, int32_t j, uint32_t gq)
{
    const uint32_t s = p->tsig[gate_tile_(p, jy, j)] & ~PFT_PRE_TILE_STALE_; /* R units Q4 */
    if (s == 0u) {
        return 65535;
    }
    /* g (Q8.8) s (R Q4) 2^(bf - rs) / 2^12, rounded: U units */
    const uint64_t v = (((uint64_t)gq * s << (uint32_t)(p->bf - p->rs)) + 2048u) >> 12;
    return v < 1u ? 1 : (v > 65535u ? 65535 : (int32_t)v);
}

static int32_t gate_lim_(const pft_pre_t *p, int32_t jy, int32_t j)
{
    return gate_lim_g_(p, jy, j, p->cfg.bg_gate);
}

/* bg_young_clip (docs/algorithms.md 9.13): the limit of a young cell's update, U units: no
 * gate (65535) without the option, else the clip bg_young_clip sigma of the cell's tile. */
static int32_t young_lim_(const pft_pre_t *p, int32_t jy, int32_t j)
{
    return p->cfg.bg_young_clip == 0u ? 65535 : gate_lim_g_(p, jy, j, p->cfg.bg_young_clip);
}

/* The last cell of the tile column of cell j (cells -1 and w, w + 1 belong to the first and
 * last tile columns). */
static int32_t gate_span_end_(const pft_pre_t *p, int32_t j)
{
    const int32_t w = (int32_t)p->cfg.width, t = (int32_t)p->cfg.tile;
    const int32_t tx = clampi_(j, 0, w - 1) / t;
    return (tx + 1) * t >= w ? w + 1 : (tx + 1) * t - 1;
}

/* bg_gate_local: the local part m of cell value bx's innovation, U units: the tile's mean
 * (gm, U units) or rho bx (gm: rho, Q16, |rho| <= 1/4), |m| <= 16383. */
static int32_t gate_m_(bool rel, int32_t gm, int32_t bx)
{
    return rel ? (gm * bx + 32768) >> 16 : gm;
}

/* Cell j (observed) of a frame row zl interpolated along x at the update's fraction: taps
 * ulo .. uhi, U * 16, PFT_PRE_ANONE_ when one of them is masked. */
static int32_t hcell_(const agx_t *gx, const int32_t *zl, int32_t j)
{
    const int32_t xb0 = j + gx->ub;
    int32_t sv = 0;
    bool ok = true;
    for (int32_t i = gx->ulo; i <= gx->uhi; ++i) {
        const int32_t z = zl[xb0 + i];
        ok = ok && z >= 0;
        sv += gx->wu[i + 1] * z;
    }
    return ok ? (sv + 8) >> 4 : PFT_PRE_ANONE_;
}

#if defined(__SSE2__)
/* The pair (a, b) of 16-bit values as a 32-bit word (low, high). */
static inline int32_t pair16_(int32_t a, int32_t b)
{
    return (int32_t)(((uint32_t)b << 16) | ((uint32_t)a & 65535u));
}

/* Where the compiler has SSE2 (x86-64), anchor_hrow_'s blend of cells j .. j + 7 (n blocks of
 * 8 from ja) in 16-bit lanes: its four biased int16 taps sb (weights w, the row's int16 casts)
 * as two pmaddwd of interleaved pairs, w0 sb[j - 1] + w1 sb[j] and w2 sb[j + 1] + w3 sb[j + 2],
 * exact in int32 as the loop's sum of 16 x 16-bit products, then (+ 256 * 32768 + 8) >> 4; a
 * cell is PFT_PRE_ANONE_ where one of its tested taps zb (m0, m2, m3 as in anchor_hrow_; the
 * second always) is negative: the signs of the int32 taps survive the saturating pack to
 * int16, so the test is on 8 cells' signs at once. The same values as the loop; the other
 * targets keep the loop. Returns the first cell left to it. */
static inline int32_t hrow8_(const int32_t *zb, const int16_t *sb, const int16_t w[4], int32_t m0,
                             int32_t m2, int32_t m3, int32_t *hz, int32_t ja, int32_t jb)
{
    const __m128i w01 = view_wpair_(w[0], w[1]), w23 = view_wpair_(w[2], w[3]);
    const __m128i kb = _mm_set1_epi32(256 * 32768 + 8), none = _mm_set1_epi32(PFT_PRE_ANONE_);
    const __m128i t0 = _mm_set1_epi16((int16_t)m0), t2 = _mm_set1_epi16((int16_t)m2);
    const __m128i t3 = _mm_set1_epi16((int16_t)m3);
    int32_t j = ja;
    for (; j + 7 <= jb; j += 8) {
        const int32_t *z = zb + j;
        const __m128i z0 = _mm_packs_epi32(_mm_loadu_si128((const __m128i *)(const void *)(z - 1)),
                                           _mm_loadu_si128((const __m128i *)(const void *)(z + 3)));
        const __m128i z1 = _mm_packs_epi32(_mm_loadu_si128((const __m128i *)(const void *)z),
                                           _mm_loadu_si128((const __m128i *)(const void *)(z + 4)));
        const __m128i z2 = _mm_packs_epi32(_mm_loadu_si128((const __m128i *)(const void *)(z + 1)),
                                           _mm_loadu_si128((const __m128i *)(const void *)(z + 5)));
        const __m128i z3 = _mm_packs_epi32(_mm_loadu_si128((const __m128i *)(const void *)(z + 2)),
                                           _mm_loadu_si128((const __m128i *)(const void *)(z + 6)));
        const __m128i inv = _mm_srai_epi16(_mm_or_si128(_mm_or_si128(_mm_and_si128(z0, t0), z1),
                                                        _mm_or_si128(_mm_and_si128(z2, t2), _mm_and_si128(z3, t3))),
                                           15);
        const int16_t *s = sb + j;
        const __m128i s0 = _mm_loadu_si128((const __m128i *)(const void *)(s - 1));
        const __m128i s1 = _mm_loadu_si128((const __m128i *)(const void *)s);
        const __m128i s2 = _mm_loadu_si128((const __m128i *)(const void *)(s + 1));
        const __m128i s3 = _mm_loadu_si128((const __m128i *)(const void *)(s + 2));
        __m128i lo, hi;
        blend4_8_(s0, s1, s2, s3, w01, w23, kb, &lo, &hi);
        lo = _mm_srai_epi32(lo, 4);
        hi = _mm_srai_epi32(hi, 4);
        const __m128i il = _mm_unpacklo_epi16(inv, inv), ih = _mm_unpackhi_epi16(inv, inv);
        _mm_storeu_si128((__m128i *)(void *)(hz + j + 1), _mm_or_si128(_mm_andnot_si128(il, lo), _mm_and_si128(il, none)));
        _mm_storeu_si128((__m128i *)(void *)(hz + j + 5), _mm_or_si128(_mm_andnot_si128(ih, hi), _mm_and_si128(ih, none)));
    }
    return j;
}

/* hrow8_ for a test: cells ja .. jb of a row (zl, its biased int16 copy zs, both indexed by
 * frame column, cell j's taps at j + ub - 1 .. j + ub + 2) into hz (entry j + 1) with the
 * weights w and the tested taps ulo .. uhi; returns the first cell not done. */
int32_t pft_pre_hrow8_(const int32_t *zl, const int16_t *zs, int32_t ub, const int32_t w[4], int32_t ulo,
                       int32_t uhi, int32_t *hz, int32_t ja, int32_t jb)
{
    const int16_t w16[4] = {(int16_t)w[0], (int16_t)w[1], (int16_t)w[2], (int16_t)w[3]};
    return hrow8_(zl + ub, zs + ub, w16, ulo == -1 ? -1 : 0, uhi >= 1 ? -1 : 0, uhi == 2 ? -1 : 0, hz, ja, jb);
}

/* Where the compiler has SSE2 (x86-64), the anchored pass's vertical blends of its residual in
 * pft_pre_ares_span_'s split form, vb[i] = vsplit_(vtap_(...)) for i = i0 .. c1 in blocks of 8:
 * the taps biased by -32768 into int16 (xor of the top bit), vtap_'s sum of 16 x 16-bit products
 * as two pmaddwd of interleaved pairs (exact in int32), v = (sum + 256 * 32768 + 8) >> 4, and
 * the word (v & 127) | ((v >> 7) << 16) with v >> 7 = (sum + ...) >> 11: the same values as the
 * loop. Returns the first column left to it. */
static inline int32_t vsplit8_(const uint16_t *t0, const uint16_t *t1, const uint16_t *t2, const uint16_t *t3,
                               const int16_t w[4], int32_t *vb, int32_t i0, int32_t c1)
{
    const __m128i w01 = view_wpair_(w[0], w[1]), w23 = view_wpair_(w[2], w[3]);
    const __m128i kb = _mm_set1_epi32(256 * 32768 + 8), m7 = _mm_set1_epi32(127);
    int32_t i = i0;
    for (; i + 7 <= c1; i += 8) {
        __m128i lo, hi;
        vblend8_(t0, t1, t2, t3, i, w01, w23, kb, &lo, &hi);
        _mm_storeu_si128((__m128i *)(void *)(vb + i), _mm_or_si128(_mm_and_si128(_mm_srai_epi32(lo, 4), m7),
                                                                   _mm_slli_epi32(_mm_srai_epi32(lo, 11), 16)));
        _mm_storeu_si128((__m128i *)(void *)(vb + i + 4), _mm_or_si128(_mm_and_si128(_mm_srai_epi32(hi, 4), m7),
                                                                       _mm_slli_epi32(_mm_srai_epi32(hi, 11), 16)));
    }
    return i;
}

/* vsplit8_ for a test: columns i0 .. c1 of the tap rows t with the weights w into vb; returns
 * the first column not done. */
int32_t pft_pre_vsplit8_(const uint16_t *const t[4], const int32_t w[4], int32_t *vb, int32_t i0, int32_t c1)
{
    const int16_t w16[4] = {(int16_t)w[0], (int16_t)w[1], (int16_t)w[2], (int16_t)w[3]};
    return vsplit8_(t[0], t[1], t[2], t[3], w16, vb, i0, c1);
}
#endif

/* Frame row zl (U units, -1 masked) interpolated along x at the update's fraction into hz
 * (w + 3 cells, U * 16; PFT_PRE_ANONE_ where a tap is masked or the cell is not observed). */
static void anchor_hrow_(const anchor_geom_t *g, const int32_t *zl, int32_t w, int32_t *hz,
                         int16_t *zs)
{
    const agx_t *gx = &g->gx;
    const int32_t olo = g->olo[0], ohi = g->ohi[0];
    /* the cells whose four taps j + ub - 1 .. j + ub + 2 are all in the row: the loop below
     * with the same values, a tap of weight 0 adding 0; a masked tap (-1) among those the
     * loop below tests (ulo .. uhi) makes the OR of the masked taps negative, a valid one is
     * >= 0 */
    const int32_t fa = olo > 1 - gx->ub ? olo : 1 - gx->ub;
    const int32_t fb = ohi < w - 3 - gx->ub ? ohi : w - 3 - gx->ub;
    if (fa <= fb) {
        const int32_t *zb = zl + gx->ub;
        /* the taps' values biased by -32768 into int16 (a masked one's 65535 - 32768: its
         * cell is tested below), so that the blend takes 16 x 16-bit products as vtap_: the
         * bias comes back as 32768 times the weights' sum (256) */
        for (int32_t x = fa + gx->ub - 1; x <= fb + gx->ub + 2; ++x) { /* vectorisable */
            zs[x] = (int16_t)((int32_t)((uint32_t)zl[x] & 0xFFFFu) - 32768);
        }
        const int16_t *sb = zs + gx->ub;
        const int16_t w0 = (int16_t)gx->wu[0], w1 = (int16_t)gx->wu[1], w2 = (int16_t)gx->wu[2];
        const int16_t w3 = (int16_t)gx->wu[3];
        const int32_t m0 = gx->ulo == -1 ? -1 : 0, m2 = gx->uhi >= 1 ? -1 : 0;
        const int32_t m3 = gx->uhi == 2 ? -1 : 0;
        for (int32_t j = -1; j < olo; ++j) {
            hz[j + 1] = PFT_PRE_ANONE_;
        }
        for (int32_t j = olo; j < fa; ++j) {
            hz[j + 1] = hcell_(gx, zl, j);
        }
#if defined(__SSE2__)
        const int16_t w16[4] = {w0, w1, w2, w3};
        const int32_t fj = hrow8_(zb, sb, w16, m0, m2, m3, hz, fa, fb);
#else
        const int32_t fj = fa;
#endif
        for (int32_t j = fj; j <= fb; ++j) { /* vectorisable */
            const int32_t z0 = zb[j - 1], z1 = zb[j], z2 = zb[j + 1], z3 = zb[j + 2];
            const int32_t v = (w0 * sb[j - 1] + w1 * sb[j] + w2 * sb[j + 1] + w3 * sb[j + 2] +
                               256 * 32768 + 8) >> 4;
            hz[j + 1] = ((z0 & m0) | z1 | (z2 & m2) | (z3 & m3)) < 0 ? PFT_PRE_ANONE_ : v;
        }
        for (int32_t j = fb + 1; j <= ohi; ++j) {
            hz[j + 1] = hcell_(gx, zl, j);
        }
        for (int32_t j = (ohi + 1 > -1 ? ohi + 1 : -1); j <= w + 1; ++j) {
            hz[j + 1] = PFT_PRE_ANONE_;
        }
        return;
    }
    for (int32_t j = -1; j <= w + 1; ++j) {
        hz[j + 1] = j >= olo && j <= ohi ? hcell_(gx, zl, j) : PFT_PRE_ANONE_;
    }
}

/* bg_masked_taps (docs/algorithms.md 9.13): cell j (observed) of frame row zl interpolated
 * along x from its valid taps, their weights renormalised (U * 16, clamped to 0 .. 65535 * 16);
 * PFT_PRE_ANONE_ when the valid taps' weights sum to less than 1/2 (128 of 256). */
static int32_t hcell_renorm_(const agx_t *gx, const int32_t *zl, int32_t j)
{
    const int32_t xb0 = j + gx->ub;
    int32_t sv = 0, ws = 0; /* |sv| <= 294 * 65535 (the weights' absolute sum at most 294) */
    for (int32_t i = gx->ulo; i <= gx->uhi; ++i) {
        const int32_t z = zl[xb0 + i];
        sv += z >= 0 ? gx->wu[i + 1] * z : 0;
        ws += z >= 0 ? gx->wu[i + 1] : 0;
    }
    if (ws < 128) {
        return PFT_PRE_ANONE_;
    }
    const int64_t num = (int64_t)sv * 16;
    const int64_t v = (num >= 0 ? num + ws / 2 : num - ws / 2) / ws;
    return (int32_t)(v < 0 ? 0 : (v > 65535 * 16 ? 65535 * 16 : v));
}

/* bg_masked_taps: the cells of row hz (anchor_hrow_'s) with a masked tap among ulo .. uhi,
 * observed (olo .. ohi) and, with ax, in a column younger than ny (ax[j]: column j's age),
 * from their valid taps (hcell_renorm_). */
static void anchor_hrow_masked_(const anchor_geom_t *g, const int32_t *zl, int32_t w, int32_t *hz,
                                const uint8_t *ax, uint32_t ny)
{
    const agx_t *gx = &g->gx;
    for (int32_t x = 0; x < w; ++x) {
        if (zl[x] >= 0) {
            continue;
        }
        /* the cells whose taps j + ub + ulo .. j + ub + uhi hold x */
        const int32_t ja = x - gx->ub - gx->uhi > g->olo[0] ? x - gx->ub - gx->uhi : g->olo[0];
        const int32_t jb = x - gx->ub - gx->ulo < g->ohi[0] ? x - gx->ub - gx->ulo : g->ohi[0];
        for (int32_t j = ja; j <= jb; ++j) {
            if (hz[j + 1] == PFT_PRE_ANONE_ && (ax == NULL || ax[j] < ny)) {
                hz[j + 1] = hcell_renorm_(gx, zl, j);
            }
        }
    }
}

/* bg_gate_local: m of every tile from the sums of the last frame's update (mean: the mean
 * innovation, rounded, within +-16383; relative: rho = sum e / sum B in Q16 within +-1/4), the
 * sums cleared for this frame. A tile without cells has m 0. */
static void gate_local_start_(pft_pre_t *p)
{
    const uint32_t nt = p->ntx * p->nty;
    const bool rel = p->cfg.bg_gate_local == PFT_PRE_GATE_LOCAL_RELATIVE;
    for (uint32_t i = 0; i < nt; ++i) {
        const int64_t se = p->gsum[2u * i], sl = p->gsum[2u * i + 1u];
        const int64_t n = (int64_t)p->gcnt[i];
        int64_t m = 0;
        if (rel && sl > 0) {
            const int64_t num = se * 65536;
            m = (num >= 0 ? num + sl / 2 : num - sl / 2) / sl;
            m = m > 16384 ? 16384 : (m < -16384 ? -16384 : m);
        } else if (!rel && n > 0) {
            m = (se >= 0 ? se + n / 2 : se - n / 2) / n;
            m = m > 16383 ? 16383 : (m < -16383 ? -16383 : m);
        } else {
            /* no cell: m 0 */
        }
        p->gm[i] = (int32_t)m;
        p->gsum[2u * i] = 0;
        p->gsum[2u * i + 1u] = 0;
        p->gcnt[i] = 0u;
    }
}

/* bg_gate: the update of grid cell value bx with innovation e, local part mc (0 without
 * bg_gate_local), gate lim (U units; 65535: no gate), alpha a15 and beyond the gate ag (the
 * weight form, wsh >= 1): bx + alpha mc plus the gate's update of e - mc (clipped to +-lim with
 * wsh 0), clamped to the background's range (with mc 0 the clamp never acts: the update moves
 * bx toward bx + e, inside 0 .. 65535). */
static inline int32_t gate_nb_(int32_t bx, int32_t e, int32_t mc, int32_t lim, int32_t a15,
                               int32_t ag, int32_t wsh)
{
    int32_t d = e - mc; /* |d| <= 65535 + 16384 */
    const int32_t ad = d < 0 ? -d : d;
    d = wsh == 0 && ad > lim ? (d < 0 ? -lim : lim) : d;
    /* the two products rounded apart, each within 32 bits (a15 <= 2^15): |mc a15| < 2^29;
     * |d| <= lim <= 65535 with a15, |d| <= 81919 only beyond the weight form's gate, with
     * ag <= a15 / 2 */
    const int32_t am = (mc * a15 + 16384) >> 15;
    const int32_t dd = (d * (ad > lim ? ag : a15) + 16384) >> 15;
    const int32_t nb = bx + am + dd;
    return nb < 0 ? 0 : (nb > 65535 ? 65535 : nb);
}

/* bg_gate: gate_run_'s or gate_local_span_'s update of one old grid cell (jy, j) of value bx with
 * innovation e, for the paths that take cells one at a time (the short rows, bg_edge_narrow's
 * cells): the young or the tile's limit, bg_gate_local's part and its tile sums; the new value. */
static int32_t gate_cell_(const pft_pre_t *p, int32_t jy, int32_t j, int32_t bx, int32_t e, int32_t a15)
{
    const bool young = p->agex != NULL && (p->agex[j + 1] < p->cfg.bg_gate_young ||
                                            p->agey[jy + 1] < p->cfg.bg_gate_young);
    const int32_t lim = young ? young_lim_(p, jy, j) : gate_lim_(p, jy, j);
    const int32_t wsh = (int32_t)p->cfg.bg_gate_shift;
    int32_t mc = 0;
    if (p->gsum != NULL) {
        const uint32_t ti = gate_tile_(p, jy, j);
        mc = gate_m_(p->cfg.bg_gate_local == PFT_PRE_GATE_LOCAL_RELATIVE, p->gm[ti], bx);
        p->gsum[2u * ti] += e;
        p->gsum[2u * ti + 1u] += bx;
        p->gcnt[ti]++;
    }
    return gate_nb_(bx, e, mc, lim, a15, wsh == 0 ? a15 : a15 >> wsh, wsh);
}

/* bg_gate: the ring rows of one grid row's update, their vertical weights, the values marking
 * an invalid tap, and the weights inside and beyond the gate. */
typedef struct {
    const int32_t *q[4];
    int32_t w[4], n[4];
    int32_t wsh, ag, a15;
    bool split; /* x86-64, AArch64: gate_clip_split_ applies (gate_split_ok_) */
} gate_row_t;

/* bg_gate: cells ja..jb of grid row b (storage entry j + 1) blended with the ring, gate_nb_
 * without a local part; lim 65535: no gate. A cell with an invalid tap is kept. clip (a
 * constant of each call: the loop is inlined twice) is bg_gate_shift 0, where the innovation
 * beyond the gate is clipped to +-lim and the weight is a15 on both sides of it: e clamped to
 * [-lim, lim] is that value (lim >= 1), in fewer instructions than the test of |e|. */
static inline void gate_run_loop_(const gate_row_t *g, uint16_t *b, int32_t ja, int32_t jb,
                                  int32_t lim, const bool clip)
{
    const int32_t *q0 = g->q[0], *q1 = g->q[1], *q2 = g->q[2], *q3 = g->q[3];
    const int32_t w0 = g->w[0], w1 = g->w[1], w2 = g->w[2], w3 = g->w[3];
    const int32_t n0 = g->n[0], n1 = g->n[1], n2 = g->n[2], n3 = g->n[3];
    const int32_t wsh = g->wsh, ag = g->ag, a15 = g->a15, nlim = -lim;
    for (int32_t j = ja; j <= jb; ++j) { /* vectorisable */
        const int32_t v0 = q0[j], v1 = q1[j], v2 = q2[j], v3 = q3[j];
        const bool inv = (v0 == n0) | (v1 == n1) | (v2 == n2) | (v3 == n3);
        int32_t sv = (w0 * v0 + w1 * v1 + w2 * v2 + w3 * v3 + 2048) >> 12;
        sv = sv < 0 ? 0 : (sv > 65535 ? 65535 : sv);
        const int32_t bx = b[j + 1];
        /* gate_nb_ with mc 0, written out: without the clamp, which cannot act, the loop costs
         * about 0.26 M instructions less per 384 x 288 frame (x86-64) */
        int32_t e = sv - bx;
        int32_t nb;
        if (clip) {
            e = e > lim ? lim : e;
            e = e < nlim ? nlim : e;
            nb = bx + ((e * a15 + 16384) >> 15);
        } else {
            const int32_t ae = e < 0 ? -e : e;
            e = wsh == 0 && ae > lim ? (e < 0 ? -lim : lim) : e;
            nb = bx + ((e * (ae > lim ? ag : a15) + 16384) >> 15);
        }
        b[j + 1] = (uint16_t)(inv ? bx : nb);
    }
}

#if defined(__SSE2__)
/* Where the compiler has SSE2 (x86-64), gate_run_loop_'s clipped form (bg_gate_shift 0) takes 8
 * cells at a time: the vertical blend on the 32-bit ring values themselves, each product by
 * pmuludq (the low 32 bits of the unsigned 32 x 32-bit product are the int32 product modulo
 * 2^32; the even lanes as they are, the odd ones shuffled down), summed in 32-bit lanes: the
 * same 32-bit sum, modulo 2^32, as the 32-bit loop. The value clamped to [0, 65535] is the sum
 * plus 2048 - 2^27, shifted by 12 and saturated to int16 (that value minus 32768), the
 * innovation's clip to [-lim, lim] the value c clamped to [bx - lim, bx + lim] (saturated in 16
 * bits), and bx + ((e a15 + 16384) >> 15) = (bx (32768 - a15) + c a15 + 16384) >> 15 one
 * multiply-add of the biased pair (bx - 32768, c - 32768) with (32768 - a15, a15): the biases
 * add 2^30, which the shift turns into the 32768 of the biased result (|sum| <= 2^30, no
 * overflow). Taken when the weights are within [-32767, 32767] and a15 within [1, 32767] (the
 * pair (32768 - a15, a15) int16), any lim in [1, 65535]; else, and for the last cells of a
 * span, the 32-bit loop. The weights are Q8 with |sum| < 512 and a valid ring value within
 * [-2^21, 2^21), so |S| < 2^30 and S + 2048 - 2^27 stays in int32; a lane with an invalid tap
 * may wrap, and is stored back unchanged. (Until ircost49 the blend split each value into two
 * 16-bit halves for pmaddwd: the same sums in about a quarter more instructions.) AArch64 takes
 * NEON's form below; the Cortex-M builds keep the 32-bit loop (the same object code as before
 * for the update). */
#define PFT_PRE_GATE_SPLIT_ 1
#elif defined(PFT_PRE_NEON_)
/* With NEON (AArch64), gate_clip_split_ takes 8 cells at a time on the 32-bit ring values
 * themselves (NEON has 32-bit mla: the loop's own int32 sum), with the rest in 16-bit lanes:
 * the value rounded, clamped to [0, 65535] and narrowed in one instruction (sqrshrun), the
 * innovation's clip as the value c clamped to [bx - lim, bx + lim] (unsigned saturating
 * bounds: beyond 0 or 65535 the bound cannot act on c in [0, 65535], nor does the loop's clip
 * of e = c - bx act there), e = c - bx widened to int32 (usubl), e a15 (|e| <= 65535,
 * a15 <= 32768: within int32, as in the loop), (e a15 + 16384) >> 15 narrowed (rshrn: the
 * low 16 bits, which are all the sum with bx modulo 2^16 needs). Any weights, a15 and lim of the
 * loop (gate_split_ok_ is true); a lane with an invalid tap is stored back unchanged. */
#define PFT_PRE_GATE_SPLIT_ 1
#endif

#if defined(PFT_PRE_GATE_SPLIT_) && defined(PFT_PRE_NEON_)
/* The lanes of 8 ring values at q (two int32x4) equal to n, as 8 x 16-bit masks. */
static inline uint16x8_t gate_inv8_(int32x4_t a, int32x4_t c, int32x4_t n)
{
    return vuzp1q_u16(vreinterpretq_u16_u32(vceqq_s32(a, n)), vreinterpretq_u16_u32(vceqq_s32(c, n)));
}

/* gate_run_loop_ (clip) of cells ja .. ja + 8 n - 1 in NEON's form above. */
static void gate_clip_split_(const gate_row_t *g, uint16_t *b, int32_t ja, int32_t n, int32_t lim)
{
    const int32x4_t w0 = vdupq_n_s32(g->w[0]), w1 = vdupq_n_s32(g->w[1]);
    const int32x4_t w2 = vdupq_n_s32(g->w[2]), w3 = vdupq_n_s32(g->w[3]);
    const int32x4_t n0 = vdupq_n_s32(g->n[0]), n1 = vdupq_n_s32(g->n[1]);
    const int32x4_t n2 = vdupq_n_s32(g->n[2]), n3 = vdupq_n_s32(g->n[3]);
    const uint16x8_t lv = vdupq_n_u16((uint16_t)lim);
    const int32_t a15 = g->a15;
    const int32_t *q0 = g->q[0], *q1 = g->q[1], *q2 = g->q[2], *q3 = g->q[3];
    for (int32_t i = 0; i < n; ++i) {
        const int32_t j = ja + 8 * i;
        const int32x4_t a0 = vld1q_s32(q0 + j), c0 = vld1q_s32(q0 + j + 4);
        const int32x4_t a1 = vld1q_s32(q1 + j), c1 = vld1q_s32(q1 + j + 4);
        const int32x4_t a2 = vld1q_s32(q2 + j), c2 = vld1q_s32(q2 + j + 4);
        const int32x4_t a3 = vld1q_s32(q3 + j), c3 = vld1q_s32(q3 + j + 4);
        const uint16x8_t inv = vorrq_u16(vorrq_u16(gate_inv8_(a0, c0, n0), gate_inv8_(a1, c1, n1)),
                                         vorrq_u16(gate_inv8_(a2, c2, n2), gate_inv8_(a3, c3, n3)));
        int32x4_t sa = vmulq_s32(a0, w0);
        int32x4_t sb = vmulq_s32(c0, w0);
        sa = vmlaq_s32(sa, a1, w1);
        sb = vmlaq_s32(sb, c1, w1);
        sa = vmlaq_s32(sa, a2, w2);
        sb = vmlaq_s32(sb, c2, w2);
        sa = vmlaq_s32(sa, a3, w3);
        sb = vmlaq_s32(sb, c3, w3);
        const uint16x8_t bx = vld1q_u16(b + j + 1);
        uint16x8_t sv = vqrshrun_high_n_s32(vqrshrun_n_s32(sa, 12), sb, 12);
        sv = vminq_u16(vmaxq_u16(sv, vqsubq_u16(bx, lv)), vqaddq_u16(bx, lv));
        const int32x4_t ea = vreinterpretq_s32_u32(vsubl_u16(vget_low_u16(sv), vget_low_u16(bx)));
        const int32x4_t eb = vreinterpretq_s32_u32(vsubl_high_u16(sv, bx));
        const int16x8_t d = vrshrn_high_n_s32(vrshrn_n_s32(vmulq_n_s32(ea, a15), 15), vmulq_n_s32(eb, a15), 15);
        const uint16x8_t nb = vaddq_u16(bx, vreinterpretq_u16_s16(d));
        vst1q_u16(b + j + 1, vbslq_u16(inv, bx, nb));
    }
}
#elif defined(PFT_PRE_GATE_SPLIT_)
/* Four ring values at q times w (pmuludq: the low 32 bits of each product are the int32
 * product modulo 2^32, signed or not) added to the sums of their even lanes (e: lanes 0, 2 in
 * the low words of its 64-bit halves) and odd lanes (o: lanes 1, 3), and the lanes equal to n
 * or-ed into inv (4 x 32-bit masks). */
static inline void gate_mul4_(const int32_t *q, __m128i w, __m128i n, __m128i *e, __m128i *o, __m128i *inv)
{
    const __m128i a = _mm_loadu_si128((const __m128i *)(const void *)q);
    *inv = _mm_or_si128(*inv, _mm_cmpeq_epi32(a, n));
    *e = _mm_add_epi32(*e, _mm_mul_epu32(a, w));
    *o = _mm_add_epi32(*o, _mm_mul_epu32(_mm_shuffle_epi32(a, 0xF5), w));
}

/* The 4 lanes' sums from gate_mul4_'s even and odd halves, in lane order. */
static inline __m128i gate_join4_(__m128i e, __m128i o)
{
    return _mm_unpacklo_epi32(_mm_shuffle_epi32(e, 0x08), _mm_shuffle_epi32(o, 0x08));
}

/* gate_run_loop_ (clip) of cells ja .. ja + 8 n - 1 in the SSE2 form above. */
static void gate_clip_split_(const gate_row_t *g, uint16_t *b, int32_t ja, int32_t n, int32_t lim)
{
    const __m128i w0 = _mm_set1_epi32(g->w[0]), w1 = _mm_set1_epi32(g->w[1]);
    const __m128i w2 = _mm_set1_epi32(g->w[2]), w3 = _mm_set1_epi32(g->w[3]);
    const __m128i ar = _mm_set1_epi32(pair16_(32768 - g->a15, g->a15));
    const __m128i n0 = _mm_set1_epi32(g->n[0]), n1 = _mm_set1_epi32(g->n[1]);
    const __m128i n2 = _mm_set1_epi32(g->n[2]), n3 = _mm_set1_epi32(g->n[3]);
    const __m128i bias = _mm_set1_epi16((int16_t)-32768), lv = _mm_set1_epi16((int16_t)lim);
    const __m128i rb = _mm_set1_epi32(2048 - 134217728), r15 = _mm_set1_epi32(16384);
    const int32_t *q0 = g->q[0], *q1 = g->q[1], *q2 = g->q[2], *q3 = g->q[3];
    for (int32_t i = 0; i < n; ++i) {
        const int32_t j = ja + 8 * i;
        __m128i ia = _mm_setzero_si128(), ic = _mm_setzero_si128();
        __m128i ea = _mm_setzero_si128(), oa = _mm_setzero_si128();
        __m128i ec = _mm_setzero_si128(), oc = _mm_setzero_si128();
        gate_mul4_(q0 + j, w0, n0, &ea, &oa, &ia);
        gate_mul4_(q1 + j, w1, n1, &ea, &oa, &ia);
        gate_mul4_(q2 + j, w2, n2, &ea, &oa, &ia);
        gate_mul4_(q3 + j, w3, n3, &ea, &oa, &ia);
        gate_mul4_(q0 + j + 4, w0, n0, &ec, &oc, &ic);
        gate_mul4_(q1 + j + 4, w1, n1, &ec, &oc, &ic);
        gate_mul4_(q2 + j + 4, w2, n2, &ec, &oc, &ic);
        gate_mul4_(q3 + j + 4, w3, n3, &ec, &oc, &ic);
        const __m128i inv = _mm_packs_epi32(ia, ic);
        /* ((S + 2048) >> 12) - 32768 = (S + 2048 - 2^27) >> 12, saturated: the clamped value
         * minus 32768 */
        const __m128i sl = _mm_srai_epi32(_mm_add_epi32(gate_join4_(ea, oa), rb), 12);
        const __m128i sh = _mm_srai_epi32(_mm_add_epi32(gate_join4_(ec, oc), rb), 12);
        __m128i sv = _mm_packs_epi32(sl, sh);
        const __m128i bx = _mm_loadu_si128((const __m128i *)(const void *)(b + j + 1));
        const __m128i lo = _mm_xor_si128(_mm_subs_epu16(bx, lv), bias);
        const __m128i hi = _mm_xor_si128(_mm_adds_epu16(bx, lv), bias);
        sv = _mm_max_epi16(_mm_min_epi16(sv, hi), lo);
        const __m128i bb = _mm_xor_si128(bx, bias);
        const __m128i pl = _mm_srai_epi32(_mm_add_epi32(_mm_madd_epi16(_mm_unpacklo_epi16(bb, sv), ar), r15), 15);
        const __m128i ph = _mm_srai_epi32(_mm_add_epi32(_mm_madd_epi16(_mm_unpackhi_epi16(bb, sv), ar), r15), 15);
        const __m128i nb = _mm_xor_si128(_mm_packs_epi32(pl, ph), bias); /* the blend, biased back */
        _mm_storeu_si128((__m128i *)(void *)(b + j + 1),
                         _mm_or_si128(_mm_and_si128(inv, bx), _mm_andnot_si128(inv, nb)));
    }
}

#endif

/* Whether gate_clip_split_ applies (see PFT_PRE_GATE_SPLIT_): false without SSE2 or NEON. */
static bool gate_split_ok_(const int32_t w[4], int32_t a15)
{
#if defined(PFT_PRE_NEON_)
    (void)w; /* NEON's form is the loop's arithmetic */
    (void)a15;
    return true;
#elif defined(PFT_PRE_GATE_SPLIT_)
    bool ok = a15 >= 1 && a15 <= 32767;
    for (int32_t i = 0; i < 4; ++i) {
        ok = ok && w[i] >= -32767 && w[i] <= 32767;
    }
    return ok;
#else
    (void)w;
    (void)a15;
    return false;
#endif
}

/* gate_run_loop_'s clipped form (bg_gate_shift 0) of cells ja .. jb: with split (x86-64 where
 * gate_split_ok_) the split form for whole blocks of 8 cells, the 32-bit loop for the rest. */
static inline void gate_clip_(const gate_row_t *g, uint16_t *b, int32_t ja, int32_t jb, int32_t lim, bool split)
{
#if defined(PFT_PRE_GATE_SPLIT_)
    const int32_t nblk = split && jb >= ja ? (jb - ja + 1) / 8 : 0;
    if (nblk > 0) {
        gate_clip_split_(g, b, ja, nblk, lim);
    }
    gate_run_loop_(g, b, ja + 8 * nblk, jb, lim, true);
#else
    (void)split;
    gate_run_loop_(g, b, ja, jb, lim, true);
#endif
}

/* gate_clip_ for a test: ring rows q, weights w, markers n, a15, in the plain (split false) or,
 * where it applies, the split form. */
void pft_pre_gate_clip_(const int32_t *const q[4], const int32_t w[4], const int32_t n[4], int32_t a15,
                        uint16_t *b, int32_t ja, int32_t jb, int32_t lim, bool split)
{
    const gate_row_t g = {{q[0], q[1], q[2], q[3]}, {w[0], w[1], w[2], w[3]}, {n[0], n[1], n[2], n[3]},
                          0, a15, a15, split && gate_split_ok_(w, a15)};
    gate_clip_(&g, b, ja, jb, lim, g.split);
}

static inline void gate_run_(const gate_row_t *g, uint16_t *b, int32_t ja, int32_t jb, int32_t lim)
{
    if (g->wsh == 0) {
#if defined(PFT_PRE_GATE_SPLIT_)
        gate_clip_(g, b, ja, jb, lim, g->split);
#else
        gate_run_loop_(g, b, ja, jb, lim, true);
#endif
    } else {
        gate_run_loop_(g, b, ja, jb, lim, false);
    }
}

/* bg_gate_local: gate_run_ with the local part of tile ti taken off the innovation (gate_m_,
 * written ((gr bx + 32768) >> 16) + gc: relative gr rho, gc 0; mean gr 0, gc the mean;
 * |gr bx| <= 2^14 (2^16 - 1) < 2^30), and the cells' e and B added to this frame's sums of the
 * tile. An invalid cell is stored back unchanged and adds 0 to the sums (selects, so that the
 * loop vectorises; its values stay in gate_nb_'s bounds). clip: bg_gate_shift 0 (g->wsh 0), as
 * in gate_run_loop_; a constant of each call (no wrapper: the stage's stack). */
static inline void gate_local_span_(pft_pre_t *p, const gate_row_t *g, uint32_t ti, uint16_t *b,
                                    int32_t ja, int32_t jb, int32_t lim, const bool clip)
{
    const int32_t *q0 = g->q[0], *q1 = g->q[1], *q2 = g->q[2], *q3 = g->q[3];
    const int32_t w0 = g->w[0], w1 = g->w[1], w2 = g->w[2], w3 = g->w[3];
    const int32_t n0 = g->n[0], n1 = g->n[1], n2 = g->n[2], n3 = g->n[3];
    const int32_t wsh = g->wsh, ag = g->ag, a15 = g->a15, nlim = -lim;
    const bool rel = p->cfg.bg_gate_local == PFT_PRE_GATE_LOCAL_RELATIVE;
    const int32_t gr = rel ? p->gm[ti] : 0, gc = rel ? 0 : p->gm[ti];
    int32_t se = 0, sl = 0, n = 0; /* at most 258 cells: |se|, sl < 2^25 */
    for (int32_t j = ja; j <= jb; ++j) { /* vectorisable */
        const int32_t v0 = q0[j], v1 = q1[j], v2 = q2[j], v3 = q3[j];
        const bool inv = (v0 == n0) | (v1 == n1) | (v2 == n2) | (v3 == n3);
        int32_t sv = (w0 * v0 + w1 * v1 + w2 * v2 + w3 * v3 + 2048) >> 12;
        sv = sv < 0 ? 0 : (sv > 65535 ? 65535 : sv);
        const int32_t bx = b[j + 1];
        const int32_t e = sv - bx;
        const int32_t mc = ((gr * bx + 32768) >> 16) + gc;
        int32_t nb;
        if (clip) {
            /* gate_nb_ with wsh 0 (ag = a15): e - mc clamped to [-lim, lim] */
            int32_t d = e - mc;
            d = d > lim ? lim : d;
            d = d < nlim ? nlim : d;
            nb = bx + ((mc * a15 + 16384) >> 15) + ((d * a15 + 16384) >> 15);
            nb = nb < 0 ? 0 : (nb > 65535 ? 65535 : nb);
        } else {
            nb = gate_nb_(bx, e, mc, lim, a15, ag, wsh);
        }
        se += inv ? 0 : e;
        sl += inv ? 0 : bx;
        n += inv ? 0 : 1;
        b[j + 1] = (uint16_t)(inv ? bx : nb);
    }
    p->gsum[2u * ti] += se;
    p->gsum[2u * ti + 1u] += sl;
    p->gcnt[ti] += (uint32_t)n;
}

/* The update of grid row jy from the ring (the frame rows interpolated along x, taps
 * jy + ub - 1 .. jy + ub + 2, all held); zn is the converted frame row of the cells' nearest
 * pixels (row jy - k clamped), for the cells outside the valid ranges without an interpolated
 * value. */
static void anchor_urow_(pft_pre_t *p, const anchor_geom_t *g, int32_t jy, const int32_t *zn)
{
    const int32_t w = p->cfg.width, sw = w + 3, a15 = g->a15;
    const agx_t *gx = &g->gx;
    const agx_t *gy = &g->gy;
    const int32_t *olo = g->olo, *ohi = g->ohi, *ovlo = g->ovlo, *ovhi = g->ovhi;
    uint16_t *b = p->bg + (size_t)(jy + 1) * (size_t)sw;
    const bool oy = jy >= olo[1] && jy <= ohi[1];
    const int32_t yb = jy + gy->ub; /* taps yb - 1 .. yb + 2 */
    const bool iny = jy >= ovlo[1] && jy <= ovhi[1];
    int32_t fs0 = 0, fs1 = -1; /* the cells done by the fast span (none) */
    if (oy && iny) {
        /* observed cells of a row held so far: the blend of the loop below with the same
         * values (a tap of weight 0 adds 0, and only the taps of non-zero weight, which are
         * frame rows, are tested); a cell with an invalid tap is kept there too */
        const int32_t *q0 = p->aring + (size_t)((yb - 1) & 3) * (size_t)sw + 1;
        const int32_t *q1 = p->aring + (size_t)(yb & 3) * (size_t)sw + 1;
        const int32_t *q2 = p->aring + (size_t)((yb + 1) & 3) * (size_t)sw + 1;
        const int32_t *q3 = p->aring + (size_t)((yb + 2) & 3) * (size_t)sw + 1;
        const int32_t w0 = gy->wu[0], w1 = gy->wu[1], w2 = gy->wu[2], w3 = gy->wu[3];
        /* PFT_PRE_ANONE_ for the taps ulo .. uhi that the loop below tests (the others have
         * weight 0), else a value no ring cell holds (a cell is PFT_PRE_ANONE_ or above -2^18) */
        const int32_t nv = PFT_PRE_ANONE_ + 1;
        const int32_t n0 = gy->ulo == -1 ? PFT_PRE_ANONE_ : nv, n1 = PFT_PRE_ANONE_;
        const int32_t n2 = gy->uhi >= 1 ? PFT_PRE_ANONE_ : nv, n3 = gy->uhi == 2 ? PFT_PRE_ANONE_ : nv;
        fs0 = olo[0] > ovlo[0] ? olo[0] : ovlo[0];
        fs1 = ohi[0] < ovhi[0] ? ohi[0] : ovhi[0];
        if (!g->gate) {
            for (int32_t j = fs0; j <= fs1; ++j) { /* vectorisable */
                const int32_t v0 = q0[j], v1 = q1[j], v2 = q2[j], v3 = q3[j];
                const bool inv = (v0 == n0) | (v1 == n1) | (v2 == n2) | (v3 == n3);
                int32_t sv = (w0 * v0 + w1 * v1 + w2 * v2 + w3 * v3 + 2048) >> 12;
                sv = sv < 0 ? 0 : (sv > 65535 ? 65535 : sv);
                const int32_t bx = b[j + 1];
                const int32_t nb = bx + (((sv - bx) * a15 + 16384) >> 15);
                b[j + 1] = (uint16_t)(inv ? bx : nb);
            }
        } else {
            /* bg_gate: the same blend, per tile column, where |e| > lim the innovation clipped
             * to +-lim (bg_gate_shift 0) or the weight alpha / 2^bg_gate_shift */
            const int32_t wsh = (int32_t)p->cfg.bg_gate_shift;
            const int32_t ag = wsh == 0 ? a15 : a15 >> wsh;
            /* bg_gate_young: no gate (a limit of 65535; bg_young_clip: its clip) in a young row, or
             * at a young column */
            const uint8_t *ax = p->agex != NULL ? p->agex + 1 : NULL; /* ax[j]: column j */
            const uint32_t ny = p->cfg.bg_gate_young;
            const bool ryoung = ax != NULL && p->agey[jy + 1] < ny;
            /* the split form only without bg_gate_local (whose spans take gate_local_span_) */
            const gate_row_t gr = {{q0, q1, q2, q3}, {w0, w1, w2, w3}, {n0, n1, n2, n3}, wsh, ag, a15,
                                   p->gsum == NULL && gate_split_ok_(gy->wu, a15)};
            int32_t je = fs0 - 1; /* the span's last cell: at least its first */
            for (int32_t ja0 = fs0; ja0 <= fs1; ja0 = je + 1) {
                const int32_t se = gate_span_end_(p, ja0);
                je = se < fs1 ? se : fs1;
                const int32_t ylim = young_lim_(p, jy, ja0);
                const int32_t lim = ryoung ? ylim : gate_lim_(p, jy, ja0);
                /* bg_gate_young: the span's young columns ungated. Columns enter only at the
                 * ends of the valid range, so their ages rise from each end inwards: the young
                 * ones are a prefix [ja0, ma) and a suffix (mb, je] of the span */
                int32_t ma = ja0, mb = je;
                if (ax != NULL && !ryoung) {
                    while (ma <= je && ax[ma] < ny) {
                        ma++;
                    }
                    while (mb >= ma && ax[mb] < ny) {
                        mb--;
                    }
                }
                if (p->gsum != NULL) { /* bg_gate_local */
                    const uint32_t ti = gate_tile_(p, jy, ja0);
                    /* clip: bg_gate_shift 0 (gate_run_'s form), a constant of each call */
                    if (wsh == 0) {
                        gate_local_span_(p, &gr, ti, b, ja0, ma - 1, ylim, true);
                        gate_local_span_(p, &gr, ti, b, ma, mb, lim, true);
                        gate_local_span_(p, &gr, ti, b, mb + 1, je, ylim, true);
                    } else {
                        gate_local_span_(p, &gr, ti, b, ja0, ma - 1, ylim, false);
                        gate_local_span_(p, &gr, ti, b, ma, mb, lim, false);
                        gate_local_span_(p, &gr, ti, b, mb + 1, je, ylim, false);
                    }
                    continue;
                }
                gate_run_(&gr, b, ja0, ma - 1, ylim);
                gate_run_(&gr, b, ma, mb, lim);
                gate_run_(&gr, b, mb + 1, je, ylim);
            }
        }
    }
    /* the cells before and after the fast span [fs0, fs1] (done above) */
    const int32_t ja = fs0 <= fs1 ? fs0 : w + 2, jb = fs0 <= fs1 ? fs1 + 1 : w + 2;
    for (int32_t j = ja > -1 ? -1 : jb; j <= w + 1; j = j + 1 == ja ? jb : j + 1) {
        int32_t zt = PFT_PRE_ANONE_;
        if (oy && j >= olo[0] && j <= ohi[0]) {
            int32_t sv = 0;
            bool ok = true;
            for (int32_t i = gy->ulo; i <= gy->uhi; ++i) {
                const int32_t v = p->aring[(size_t)((yb + i) & 3) * (size_t)sw + (size_t)(j + 1)];
                ok = ok && v != PFT_PRE_ANONE_;
                sv += ok ? gy->wu[i + 1] * v : 0;
            }
            if (ok) {
                sv = (sv + 2048) >> 12;
                zt = sv < 0 ? 0 : (sv > 65535 ? 65535 : sv);
            }
        }
        const bool old = iny && j >= ovlo[0] && j <= ovhi[0];
        const int32_t bx = b[j + 1];
        if (zt != PFT_PRE_ANONE_) {
            const int32_t e = zt - bx;
            if (g->gate && old) {
                b[j + 1] = (uint16_t)gate_cell_(p, jy, j, bx, e, a15);
            } else {
                b[j + 1] = (uint16_t)(old ? bx + ((e * a15 + 16384) >> 15) : zt);
            }
        } else if (!old) {
            /* a cell outside the scene held so far without an interpolated value (one that
             * entered, or a margin cell the frame does not cover): from its nearest pixel
             * (j - k, jy - k) clamped into the frame, so that the registration's view of the grid (anchor_view_)
             * holds no cells carried in from the other end of a row by the anchor's move */
            const int32_t z = zn[clampi_(j - gx->k, 0, w - 1)];
            b[j + 1] = (uint16_t)(z >= 0 ? z : bx);
        } else {
            /* kept */
        }
    }
}

/* ------------------------------------------------------------------ bg_stale_reinit (9.14) */

/* Largest age of a background value. A value never learnt (a masked pixel of the first frame,
 * filled from the last unmasked pixel before it) starts at its distance to that pixel, in
 * pixels: a single dead pixel 1, the far side of a block its width. */
#define PFT_PRE_AGE_NEVER_ 127u
/* Flag of an age: the value reads a stale tap on this frame. */
#define PFT_PRE_AGE_STALE_ 128u

/* The ages in byte lanes where the compiler vectorises (x86-64's SSE2, AArch64's NEON): the
 * vectorised loops of max_u8_ and stale_anchor_urow_ then take 16 ages per vector, against 4
 * in 32-bit lanes, the same values. A scalar core (Cortex-M) keeps the 32-bit forms, whose
 * object code is main's. */
#if defined(__SSE2__) || defined(__ARM_NEON)
#define PFT_PRE_AGE_LANES8_ 1
#endif

/* Largest of n bytes. */
static uint32_t max_u8_(const uint8_t *a, int32_t n)
{
#if defined(PFT_PRE_AGE_LANES8_)
    uint8_t m = 0u;
#else
    uint32_t m = 0u;
#endif
    for (int32_t i = 0; i < n; ++i) { /* vectorisable */
        m = a[i] > m ? a[i] : m;
    }
    return m;
}

/* stale_plain_: the new age of the pixel whose taps are around column c of the vertical passes
 * (vm: maxima of the taps of non-zero weight, va: bilinear blends Q8), clamped to the row. */
static uint32_t stale_col_(const int32_t *vm, const int32_t *va, int32_t c, int32_t w, int32_t txlo,
                           int32_t txhi, int32_t fx, int32_t n)
{
    int32_t m = 0;
    for (int32_t i = txlo; i <= txhi; ++i) {
        const int32_t a = vm[clampi_(c + i, 0, w - 1)];
        m = a > m ? a : m;
    }
    const int32_t a = (va[clampi_(c, 0, w - 1)] * (256 - fx) + va[clampi_(c + 1, 0, w - 1)] * fx + 32768) >> 16;
    return (uint32_t)a | (m > n ? PFT_PRE_AGE_STALE_ : 0u);
}

/* bg_stale_reinit without bg_anchor: the ages (w x h, frame coordinates) carried to this frame
 * as the background is (b(p - s)): each the bilinear blend of the ages at p - s (the two central
 * taps per axis, clamped), with PFT_PRE_AGE_STALE_ set where a tap of non-zero weight of the
 * warp (x + kx + txlo .. txhi, y + ky + tylo .. tyhi, clamped) holds an age above n. In place,
 * rows walked as the background's (yup: upwards), the former values of the row written last
 * kept in sline[0 .. w), the new row made in sline[w + 3 ..); the vertical passes in p->vb and
 * p->bwl (free before the update pass). srow[y] is the largest age of row y: a row whose source
 * rows are all 0 is 0 (skipped). */
static void stale_plain_(pft_pre_t *p, const warp_t *g, int32_t txlo, int32_t txhi,
                         int32_t tylo, int32_t tyhi, uint32_t n)
{
    const int32_t w = p->cfg.width, h = p->cfg.height;
    const bool yup = g->ky >= 0;
    uint8_t *prev = p->sline, *nrow = p->sline + w + 3;
    int32_t *vm = p->vb, *va = p->bwl;
    const int32_t fx = (int32_t)g->fx, fy = (int32_t)g->fy;
    int32_t yprev = -1;
    uint32_t mprev = 0u; /* the former largest age of row yprev */
    for (int32_t yi = 0; yi < h; ++yi) {
        const int32_t y = yup ? yi : h - 1 - yi;
        const int32_t r0 = y + g->ky;
        const uint8_t *tr[4];
        uint32_t msrc = 0u;
        for (int32_t i = 0; i < 4; ++i) {
            const int32_t rr = clampi_(r0 - 1 + i, 0, h - 1);
            tr[i] = rr == yprev ? prev : p->sage + (size_t)rr * (size_t)w;
            const uint32_t mr = rr == yprev ? mprev : p->srow[rr];
            msrc = mr > msrc ? mr : msrc;
        }
        uint8_t *ar = p->sage + (size_t)y * (size_t)w;
        const uint32_t mold = p->srow[y];
        if (msrc == 0u) {
            /* every source age 0: the row's ages are 0 */
            if (mold != 0u) {
                memcpy(prev, ar, (size_t)w);
                memset(ar, 0, (size_t)w);
            }
            yprev = mold != 0u ? y : yprev;
            mprev = mold != 0u ? mold : mprev;
            p->srow[y] = 0u;
            continue;
        }
        /* the taps of weight 0 masked out of the maxima (ages >= 0) */
        const int32_t my0 = tylo == -1 ? -1 : 0, my2 = tyhi >= 1 ? -1 : 0, my3 = tyhi == 2 ? -1 : 0;
        const uint8_t *t0 = tr[0], *t1 = tr[1], *t2 = tr[2], *t3 = tr[3];
        for (int32_t x = 0; x < w; ++x) { /* vectorisable */
            const int32_t a0 = (int32_t)t0[x] & my0, a1 = t1[x], a2 = (int32_t)t2[x] & my2;
            const int32_t a3 = (int32_t)t3[x] & my3;
            const int32_t m01 = a0 > a1 ? a0 : a1, m23 = a2 > a3 ? a2 : a3;
            vm[x] = m01 > m23 ? m01 : m23;
            va[x] = a1 * (256 - fy) + (int32_t)t2[x] * fy;
        }
        const int32_t mx0 = txlo == -1 ? -1 : 0, mx2 = txhi >= 1 ? -1 : 0, mx3 = txhi == 2 ? -1 : 0;
        const int32_t kx = g->kx, nn = (int32_t)n;
        /* columns whose taps c - 1 .. c + 2 (c = x + kx) are inside the row: [xa, xb] */
        const int32_t xa = clampi_(1 - kx, 0, w), xb = clampi_(w - 3 - kx, -1, w - 1);
        const bool inner = xa <= xb;
        uint32_t mnew = 0u;
        for (int32_t x = 0; x < (inner ? xa : w); ++x) {
            const uint32_t v = stale_col_(vm, va, x + kx, w, txlo, txhi, fx, nn);
            nrow[x] = (uint8_t)v;
            mnew = v > mnew ? v : mnew;
        }
        for (int32_t x = xa; x <= xb; ++x) { /* vectorisable */
            const int32_t c = x + kx;
            const int32_t a0 = vm[c - 1] & mx0, a1 = vm[c], a2 = vm[c + 1] & mx2, a3 = vm[c + 2] & mx3;
            const int32_t m01 = a0 > a1 ? a0 : a1, m23 = a2 > a3 ? a2 : a3;
            const int32_t m = m01 > m23 ? m01 : m23;
            const int32_t a = (va[c] * (256 - fx) + va[c + 1] * fx + 32768) >> 16;
            const uint32_t v = (uint32_t)a | (m > nn ? PFT_PRE_AGE_STALE_ : 0u);
            nrow[x] = (uint8_t)v;
            mnew = v > mnew ? v : mnew;
        }
        for (int32_t x = (inner ? xb + 1 : w); x < w; ++x) {
            const uint32_t v = stale_col_(vm, va, x + kx, w, txlo, txhi, fx, nn);
            nrow[x] = (uint8_t)v;
            mnew = v > mnew ? v : mnew;
        }
        memcpy(prev, ar, (size_t)w);
        yprev = y;
        mprev = mold;
        memcpy(ar, nrow, (size_t)w);
        p->srow[y] = (uint8_t)mnew;
    }
}

/* bg_stale_reinit without bg_anchor, after row y's update (its masked input pixels ninv): a
 * pixel flagged stale (only on rows made without the fused span: zl whole) has its residual
 * masked and its background restarted from z (when z is valid); the ages become 0 where z is
 * valid (learnt or restarted), one more (at most PFT_PRE_AGE_NEVER_) where it is masked: in the
 * covered span [ua, ub) the residual is masked exactly there, outside it zl tells. */
static void stale_plain_row_(pft_pre_t *p, int32_t y, const int32_t *zl, uint16_t *b, int16_t *r,
                             int32_t ua, int32_t ub, uint32_t ninv)
{
    const int32_t w = p->cfg.width;
    if (p->srow[y] == 0u && ninv == 0u) {
        return; /* ages 0, every pixel learnt: 0 */
    }
    uint8_t *ar = p->sage + (size_t)y * (size_t)w;
    uint32_t mnew = 0u;
    for (int32_t x = 0; x < w; ++x) {
        const uint32_t a = ar[x];
        const bool valid = (x >= ua && x < ub) ? r[x] != PFT_RES16_MASKED : zl[x] >= 0;
        if ((a & PFT_PRE_AGE_STALE_) != 0u) {
            r[x] = PFT_RES16_MASKED;
            b[x] = valid ? (uint16_t)zl[x] : b[x];
        }
        const uint32_t a1 = (a & ~PFT_PRE_AGE_STALE_) + 1u;
        const uint32_t v = valid ? 0u : (a1 > PFT_PRE_AGE_NEVER_ ? PFT_PRE_AGE_NEVER_ : a1);
        ar[x] = (uint8_t)v;
        mnew = v > mnew ? v : mnew;
    }
    p->srow[y] = (uint8_t)mnew;
}

/* bg_stale_reinit with bg_anchor, residual row y (covered, pixels ca .. cb): a pixel whose read
 * taps of non-zero weight (grid rows r0 - 1 + i, columns x + k - 1 + i, storage + 1) reach a
 * cell older than n is masked. Nothing to do when those rows hold no such cell (srow: an upper
 * bound of each grid row's largest age). */
#if defined(PFT_PRE_NEON_)
/* With NEON (AArch64), stale_anchor_res_'s two loops for nr (1 .. 4) age rows a[0 .. nr - 1]
 * (the rows rlo .. rhi of the read, clamped): hm[c] = 1 where the largest of a[.][c] exceeds n,
 * else 0, for c in [0, sw), 16 columns at a time (the byte maximum and compare; n above 255
 * is 255 for the compare: ages are bytes); then r[x] = PFT_RES16_MASKED for x in [ca, cb] where
 * hm[x + k1 + i] is set for an i in [xlo, xhi], 8 pixels at a time where no index needs the
 * clamp to [0, sw - 1], the others as the loop. */
static void stale_res_n_(const uint8_t *const a[4], int32_t nr, int32_t sw, uint32_t n, uint8_t *hm,
                         int32_t k1, int32_t xlo, int32_t xhi, int32_t ca, int32_t cb, int16_t *r)
{
    const uint8x16_t vn = vdupq_n_u8((uint8_t)(n > 255u ? 255u : n)), one = vdupq_n_u8(1u);
    int32_t c = 0;
    for (; c + 16 <= sw; c += 16) {
        uint8x16_t m = vld1q_u8(a[0] + c);
        for (int32_t i = 1; i < nr; ++i) {
            m = vmaxq_u8(m, vld1q_u8(a[i] + c));
        }
        vst1q_u8(hm + c, vandq_u8(vcgtq_u8(m, vn), one));
    }
    for (; c < sw; ++c) {
        uint32_t m = 0u;
        for (int32_t i = 0; i < nr; ++i) {
            m = a[i][c] > m ? a[i][c] : m;
        }
        hm[c] = (uint8_t)(m > n ? 1u : 0u);
    }
    const int16x8_t vmk = vdupq_n_s16((int16_t)PFT_RES16_MASKED);
    int32_t x = ca;
    while (x <= cb) {
        if (x + k1 + xlo >= 0 && x + 7 <= cb && x + 7 + k1 + xhi <= sw - 1) {
            uint8x8_t o = vld1_u8(hm + x + k1 + xlo);
            for (int32_t i = xlo + 1; i <= xhi; ++i) {
                o = vorr_u8(o, vld1_u8(hm + x + k1 + i));
            }
            const uint16x8_t o16 = vmovl_u8(o);
            vst1q_s16(r + x, vbslq_s16(vtstq_u16(o16, o16), vmk, vld1q_s16(r + x)));
            x += 8;
        } else {
            bool st = false;
            for (int32_t i = xlo; i <= xhi; ++i) {
                st = st || hm[clampi_(x + k1 + i, 0, sw - 1)] != 0u;
            }
            r[x] = st ? PFT_RES16_MASKED : r[x];
            x++;
        }
    }
}

/* stale_res_n_ for a test (the same arguments). */
void pft_pre_stale_res_n_(const uint8_t *const a[4], int32_t nr, int32_t sw, uint32_t n, uint8_t *hm,
                          int32_t k1, int32_t xlo, int32_t xhi, int32_t ca, int32_t cb, int16_t *r)
{
    stale_res_n_(a, nr, sw, n, hm, k1, xlo, xhi, ca, cb, r);
}
#endif

static void stale_anchor_res_(pft_pre_t *p, const agx_t *gx, const agx_t *gy, int32_t r0,
                              int32_t ca, int32_t cb, uint32_t n, int16_t *r)
{
    const int32_t w = p->cfg.width, h = p->cfg.height, sw = w + 3;
    uint32_t mr = 0u;
    for (int32_t i = gy->rlo; i <= gy->rhi; ++i) {
        const uint32_t a = p->srow[clampi_(r0 + i + 1, 0, h + 2)];
        mr = a > mr ? a : mr;
    }
    if (mr <= n) {
        return;
    }
    uint8_t *hm = p->sline;
#if defined(PFT_PRE_NEON_)
    if (gy->rlo <= gy->rhi && gy->rhi - gy->rlo < 4 && gx->rlo <= gx->rhi) {
        const uint8_t *a[4] = {NULL, NULL, NULL, NULL};
        for (int32_t i = gy->rlo; i <= gy->rhi; ++i) {
            a[i - gy->rlo] = p->sage + (size_t)clampi_(r0 + i + 1, 0, h + 2) * (size_t)sw;
        }
        stale_res_n_(a, gy->rhi - gy->rlo + 1, sw, n, hm, gx->k + 1, gx->rlo, gx->rhi, ca, cb, r);
        return;
    }
#endif
    for (int32_t c = 0; c < sw; ++c) {
        uint32_t m = 0u;
        for (int32_t i = gy->rlo; i <= gy->rhi; ++i) {
            const uint32_t a = p->sage[(size_t)clampi_(r0 + i + 1, 0, h + 2) * (size_t)sw + (size_t)c];
            m = a > m ? a : m;
        }
        hm[c] = (uint8_t)(m > n ? 1u : 0u);
    }
    for (int32_t x = ca; x <= cb; ++x) {
        bool st = false;
        for (int32_t i = gx->rlo; i <= gx->rhi; ++i) {
            st = st || hm[clampi_(x + gx->k + i + 1, 0, sw - 1)] != 0u;
        }
        r[x] = st ? PFT_RES16_MASKED : r[x];
    }
}

/* bg_stale_reinit with bg_anchor, after grid row jy's update: an observed cell with a frame
 * value (its update taps all valid) older than n restarts from it; its age becomes 0. An
 * observed cell without one (a masked tap) ages by one frame (at most PFT_PRE_AGE_NEVER_); the
 * cells the frame does not observe keep their ages. Nothing to do when the row's ages are 0 and
 * none of its update taps' frame rows holds a masked pixel (mrow: per ring slot). */
static void stale_anchor_urow_(pft_pre_t *p, const anchor_geom_t *g, int32_t jy, uint32_t n,
                               const bool mrow[4])
{
    const int32_t w = p->cfg.width, sw = w + 3;
    const agx_t *gy = &g->gy;
    if (jy < g->olo[1] || jy > g->ohi[1]) {
        return;
    }
    const int32_t yb = jy + gy->ub;
    bool anym = false;
    for (int32_t i = gy->ulo; i <= gy->uhi; ++i) {
        anym = anym || mrow[(yb + i) & 3];
    }
    if (!anym && p->srow[jy + 1] == 0u) {
        return;
    }
    uint16_t *b = p->bg + (size_t)(jy + 1) * (size_t)sw;
    uint8_t *ar = p->sage + (size_t)(jy + 1) * (size_t)sw + 1; /* ar[j]: cell j */
    const int32_t *q0 = p->aring + (size_t)((yb - 1) & 3) * (size_t)sw + 1;
    const int32_t *q1 = p->aring + (size_t)(yb & 3) * (size_t)sw + 1;
    const int32_t *q2 = p->aring + (size_t)((yb + 1) & 3) * (size_t)sw + 1;
    const int32_t *q3 = p->aring + (size_t)((yb + 2) & 3) * (size_t)sw + 1;
    /* PFT_PRE_ANONE_ for the taps ulo .. uhi (the others have weight 0), else a value no ring
     * cell holds (as anchor_urow_) */
    const int32_t nv = PFT_PRE_ANONE_ + 1;
    const int32_t n0 = gy->ulo == -1 ? PFT_PRE_ANONE_ : nv, n1 = PFT_PRE_ANONE_;
    const int32_t n2 = gy->uhi >= 1 ? PFT_PRE_ANONE_ : nv, n3 = gy->uhi == 2 ? PFT_PRE_ANONE_ : nv;
    const int32_t ja = g->olo[0], jb = g->ohi[0];
    if (p->srow[jy + 1] > n) { /* some cell may be older than n: restarts */
        const int32_t w0 = gy->wu[0], w1 = gy->wu[1], w2 = gy->wu[2], w3 = gy->wu[3];
        for (int32_t j = ja; j <= jb; ++j) {
            const int32_t v0 = q0[j], v1 = q1[j], v2 = q2[j], v3 = q3[j];
            const bool inv = (v0 == n0) | (v1 == n1) | (v2 == n2) | (v3 == n3);
            if (!inv && ar[j] > n) {
                int32_t sv = (w0 * v0 + w1 * v1 + w2 * v2 + w3 * v3 + 2048) >> 12;
                b[j + 1] = (uint16_t)(sv < 0 ? 0 : (sv > 65535 ? 65535 : sv));
            }
        }
    }
    for (int32_t j = ja; j <= jb; ++j) { /* vectorisable */
        const bool inv = (q0[j] == n0) | (q1[j] == n1) | (q2[j] == n2) | (q3[j] == n3);
#if defined(PFT_PRE_AGE_LANES8_)
        /* the age plus one, at most PFT_PRE_AGE_NEVER_, in a byte (the same age for every
         * byte value) */
        const uint8_t a = ar[j];
        const uint8_t a1 = (uint8_t)(a < PFT_PRE_AGE_NEVER_ ? a + 1u : PFT_PRE_AGE_NEVER_);
        ar[j] = inv ? a1 : 0u;
#else
        const uint32_t a1 = (uint32_t)ar[j] + 1u;
        ar[j] = (uint8_t)(inv ? (a1 > PFT_PRE_AGE_NEVER_ ? PFT_PRE_AGE_NEVER_ : a1) : 0u);
#endif
    }
    p->srow[jy + 1] = (uint8_t)max_u8_(ar - 1, sw);
}

/* ------------------------------------------------------------------ bg_edge_narrow (9.12) */

/* bg_edge_narrow: the quadratic (3-tap Lagrange) weights of taps -1, 0, 1, 2 for the
 * fraction f/256, Q8, summing to 256: hi, nodes -1, 0, 1 (tap 2 weight 0); else nodes 0, 1, 2
 * (tap -1 weight 0). Like the Catmull-Rom weights they reproduce quadratics, so a smooth scene
 * is read nearly as well as through the 4 taps (a linear read of the texture of
 * test_pre_edge_narrow leaves several sigma at its steep parts); f = 0: 0, 256, 0, 0. */
static void quad_q8_(uint32_t f, bool hi, int32_t w[4])
{
    const int64_t t = f;
    int64_t q[4];
    if (hi) {
        q[0] = t * (t - 256) * 128; /* t (t - 1) / 2, Q16 */
        q[1] = 65536 * 256 - t * t * 256;
        q[2] = t * (t + 256) * 128;
        q[3] = 0;
    } else {
        q[0] = 0;
        q[1] = (t - 256) * (t - 512) * 128; /* (t - 1)(t - 2) / 2 */
        q[2] = t * (512 - t) * 256;
        q[3] = t * (t - 256) * 128;
    }
    int32_t sum = 0;
    for (uint32_t i = 0; i < 4u; ++i) {
        w[i] = (int32_t)((q[i] >= 0 ? q[i] + 32768 : q[i] - 32768) / 65536);
        sum += w[i];
    }
    w[f < 128u ? 1 : 2] += 256 - sum;
}

/* bg_edge_narrow: the update weights of the 3 taps of one end (hi: nodes -1, 0, 1; else 0, 1,
 * 2) along an axis at position fraction phi (Q16), at the inverse fraction as agx_of_'s wu (the
 * same ub), into w; the first and last tap of non-zero weight into *ulo, *uhi. */
static void edge_uw_(int32_t phi, bool hi, int32_t w[4], int32_t *ulo, int32_t *uhi)
{
    const uint32_t fr = (uint32_t)(((phi + 128) >> 8) & 255);
    quad_q8_(fr == 0u ? 0u : 256u - fr, hi, w);
    *ulo = w[0] != 0 ? -1 : (w[1] != 0 ? 0 : 1);
    *uhi = w[3] != 0 ? 2 : (w[2] != 0 ? 1 : 0);
}

/* bg_edge_narrow: the cells its 3-tap update observes per axis (those whose 3 update taps of the
 * low end, of the high end, are in the frame): llo .. lhi. */
static void edge_geom_(const pft_pre_t *p, anchor_geom_t *g)
{
    const int32_t nn[2] = {(int32_t)p->cfg.width, (int32_t)p->cfg.height};
    for (uint32_t a = 0; a < 2u; ++a) {
        const int32_t ub = a == 0u ? g->gx.ub : g->gy.ub;
        int32_t w[4], ulo = 0, uhi = 0;
        edge_uw_(p->aphi[a], false, w, &ulo, &uhi);
        g->llo[a] = clampi_(-ub - ulo, -1, nn[a] + 2);
        edge_uw_(p->aphi[a], true, w, &ulo, &uhi);
        g->lhi[a] = clampi_(nn[a] - 1 - ub - uhi, -2, nn[a] + 1);
    }
}

/* bg_edge_narrow: the read weights of pixel coordinate x along one axis (c: its cubic taps, phi
 * its position fraction) whose cells are held in lo .. hi, into w: the cubic weights when their
 * taps of non-zero weight are held, else the 3 taps of the high end's, else the low end's, when
 * theirs are; false when none is. */
static bool edge_rw_(const agx_t *c, int32_t phi, int32_t x, int32_t lo, int32_t hi, int32_t w[4])
{
    if (x + c->k + c->rlo >= lo && x + c->k + c->rhi <= hi) {
        memcpy(w, c->wr, sizeof c->wr);
        return true;
    }
    const uint32_t fr = (uint32_t)(((phi + 128) >> 8) & 255);
    for (int32_t e = 1; e >= 0; --e) {
        quad_q8_(fr, e == 1, w);
        const int32_t rl = w[0] != 0 ? -1 : (w[1] != 0 ? 0 : 1);
        const int32_t rh = w[3] != 0 ? 2 : (w[2] != 0 ? 1 : 0);
        if (x + c->k + rl >= lo && x + c->k + rh <= hi) {
            return true;
        }
    }
    return false;
}

/* bg_edge_narrow, residual row y (grid taps r0 - 1 .. r0 + 2): the pixels that the cubic read
 * leaves masked (outside ca .. cb, the cubic span of the row; all of them when ca > cb) and
 * whose 3-tap taps (edge_rw_) along x, y or both are held, read with those weights (the cubic
 * ones along the other axis when its taps are held); with bg_stale_reinit a pixel reading a cell older
 * than it stays masked, as stale_anchor_res_. */
static void edge_res_row_(const pft_pre_t *p, const anchor_geom_t *g, int32_t r0, int32_t ca,
                          int32_t cb, const int32_t *zl, uint32_t k1, int16_t *r)
{
    const int32_t w = (int32_t)p->cfg.width, sw = w + 3;
    int32_t wy[4], wx[4];
    if (!edge_rw_(&g->gy, p->aphi[1], r0 - g->gy.k, g->ovlo[1], g->ovhi[1], wy)) {
        return;
    }
    const uint32_t n = p->cfg.bg_stale_reinit;
    /* the pixels whose 3 taps of the low end, of the high end, could be held (edge_rw_ tells) */
    const int32_t xl = clampi_(g->ovlo[0] - g->gx.k, 0, w);
    const int32_t xh = clampi_(g->ovhi[0] - g->gx.k, -1, w - 1);
    for (int32_t x = xl; x <= xh; ++x) {
        if (x >= ca && x <= cb) {
            continue; /* read by the cubic path */
        }
        if (zl[x] < 0 || !edge_rw_(&g->gx, p->aphi[0], x, g->ovlo[0], g->ovhi[0], wx)) {
            continue; /* masked */
        }
        int32_t sv = 2048;
        bool stale = false;
        for (int32_t i = 0; i < 4; ++i) {
            if (wx[i] == 0) {
                continue;
            }
            const int32_t col = x + g->gx.k + i; /* storage column of cell x + k - 1 + i */
            int32_t vt = 8;
            for (int32_t jj = 0; jj < 4; ++jj) {
                if (wy[jj] == 0) {
                    continue;
                }
                const size_t at = (size_t)(r0 + jj) * (size_t)sw + (size_t)col;
                vt += wy[jj] * (int32_t)p->bg[at];
                stale = stale || (p->sage != NULL && p->sage[at] > n);
            }
            sv += wx[i] * (vt >> 4);
        }
        if (stale) {
            continue;
        }
        sv >>= 12;
        const int32_t bx = sv < 0 ? 0 : (sv > 65535 ? 65535 : sv);
        r[x] = (int16_t)pft_pre_rclamp_((zl[x] - bx + (int32_t)k1) >> k1);
    }
}

/* bg_edge_narrow: the cells of ring row hz (anchor_hrow_'s, U * 16) that the 3-tap update taps
 * along x observe but the cubic ones do not (llo .. olo - 1 and ohi + 1 .. lhi), interpolated
 * from frame row zl with the 3-tap weights of that end (PFT_PRE_ANONE_ when a tap is masked). */
static void edge_hrow_(const anchor_geom_t *g, int32_t phi, const int32_t *zl, int32_t *hz)
{
    const int32_t a = g->olo[0] <= g->ohi[0] ? g->olo[0] : g->lhi[0] + 1;
    const int32_t b = g->olo[0] <= g->ohi[0] ? g->ohi[0] : g->lhi[0];
    for (uint32_t e = 0; e < 2u; ++e) {
        int32_t w[4], ulo = 0, uhi = 0;
        edge_uw_(phi, e == 1u, w, &ulo, &uhi);
        const int32_t ja = e == 0u ? g->llo[0] : b + 1, jb = e == 0u ? a - 1 : g->lhi[0];
        for (int32_t j = ja; j <= jb; ++j) { /* hcell_ with these weights */
            const int32_t xb0 = j + g->gx.ub;
            int32_t sv = 0;
            bool ok = true;
            for (int32_t i = ulo; i <= uhi; ++i) {
                const int32_t z = zl[xb0 + i];
                ok = ok && z >= 0;
                sv += w[i + 1] * z;
            }
            hz[j + 1] = ok ? (sv + 8) >> 4 : PFT_PRE_ANONE_;
        }
    }
}

/* bg_edge_narrow: after grid row jy's update (anchor_urow_, stale_anchor_urow_), its cells that
 * the 3-tap update observes and the cubic one does not (a cell of a row outside olo[1] ..
 * ohi[1], or of a column outside olo[0] .. ohi[0]): the frame value from the ring (cubic along y
 * in a row the cubic taps observe, else the 3 taps of that end), and the update of anchor_urow_'s cells after the
 * fast span (a held cell blended or gated, one not held restarts from it); with
 * bg_stale_reinit the cell's age as stale_anchor_urow_. */
static void edge_urow_(pft_pre_t *p, const anchor_geom_t *g, int32_t jy)
{
    if (jy < g->llo[1] || jy > g->lhi[1]) {
        return;
    }
    const int32_t w = (int32_t)p->cfg.width, sw = w + 3, a15 = g->a15;
    const bool cy = jy >= g->olo[1] && jy <= g->ohi[1];
    int32_t wy[4], ylo = g->gy.ulo, yhi = g->gy.uhi;
    if (cy) {
        memcpy(wy, g->gy.wu, sizeof wy);
    } else {
        edge_uw_(p->aphi[1], jy >= g->olo[1], wy, &ylo, &yhi);
    }
    const int32_t yb = jy + g->gy.ub;
    const bool iny = jy >= g->ovlo[1] && jy <= g->ovhi[1];
    uint16_t *b = p->bg + (size_t)(jy + 1) * (size_t)sw;
    uint8_t *ar = p->sage != NULL ? p->sage + (size_t)(jy + 1) * (size_t)sw + 1 : NULL;
    const uint32_t n = p->cfg.bg_stale_reinit;
    /* a row the cubic taps observe: only the columns outside olo[0] .. ohi[0] */
    const bool cx = g->olo[0] <= g->ohi[0];
    const int32_t ja = cy && cx ? g->olo[0] : g->lhi[0] + 1, jb = cy && cx ? g->ohi[0] + 1 : g->lhi[0] + 1;
    uint32_t amax = ar != NULL ? p->srow[jy + 1] : 0u;
    const int32_t j0 = g->llo[0] >= ja && g->llo[0] < jb ? jb : g->llo[0];
    for (int32_t j = j0; j <= g->lhi[0]; j = j + 1 == ja ? jb : j + 1) {
        int32_t sv = 0;
        bool ok = true;
        for (int32_t i = ylo; i <= yhi; ++i) {
            const int32_t v = p->aring[(size_t)((yb + i) & 3) * (size_t)sw + (size_t)(j + 1)];
            ok = ok && v != PFT_PRE_ANONE_;
            sv += ok ? wy[i + 1] * v : 0;
        }
        const bool old = iny && j >= g->ovlo[0] && j <= g->ovhi[0];
        if (!ok) {
            if (ar != NULL) { /* observed without a frame value: one frame older */
                const uint32_t a1 = (uint32_t)ar[j] + 1u;
                ar[j] = (uint8_t)(a1 > PFT_PRE_AGE_NEVER_ ? PFT_PRE_AGE_NEVER_ : a1);
                amax = ar[j] > amax ? ar[j] : amax;
            }
            continue; /* kept, or (not held) anchor_urow_'s restart from the nearest pixel */
        }
        sv = (sv + 2048) >> 12;
        const int32_t zt = sv < 0 ? 0 : (sv > 65535 ? 65535 : sv);
        const int32_t bx = b[j + 1];
        const int32_t e = zt - bx;
        if (ar != NULL && ar[j] > n) {
            b[j + 1] = (uint16_t)zt; /* stale: restarts from the frame value */
        } else if (g->gate && old) {
            b[j + 1] = (uint16_t)gate_cell_(p, jy, j, bx, e, a15);
        } else {
            b[j + 1] = (uint16_t)(old ? bx + ((e * a15 + 16384) >> 15) : zt);
        }
        if (ar != NULL) {
            ar[j] = 0u;
        }
    }
    if (ar != NULL) {
        p->srow[jy + 1] = (uint8_t)amax;
    }
}

/* ------------------------------------------------------------------ bg_young_scale (9.13) */

/* bg_young_scale: the row axis's read weights as shares of their sum of squares (Q16), and the
 * pixels xlo .. xhi whose 4 column taps are all old (age >= PFT_PRE_YOUNG_AGES_; xlo > xhi:
 * none). The columns' excess is in p->prev (the re-warped path's row copy, unused with
 * bg_anchor), one per pixel, Q16. */
typedef struct {
    int32_t qy[4];
    int32_t xlo, xhi;
} young_geom_t;

static void young_q_(const int32_t wr[4], int32_t q[4])
{
    int32_t ss = 0;
    for (int32_t i = 0; i < 4; ++i) {
        ss += wr[i] * wr[i];
    }
    for (int32_t i = 0; i < 4; ++i) {
        q[i] = (int32_t)(((int64_t)wr[i] * wr[i] * 65536 + ss / 2) / ss);
    }
}

/* the mean excess of the 4 taps from age[i0 .. i0 + 3] (clamped to 0 .. n - 1), weighted by
 * q, Q16 (at most 65535) */
static uint32_t young_exc_(const pft_pre_t *p, const uint8_t *age, int32_t i0, int32_t n, const int32_t q[4])
{
    int64_t e = 0;
    for (int32_t i = 0; i < 4; ++i) {
        const uint32_t a = age[clampi_(i0 + i, 0, n - 1)];
        e += (int64_t)q[i] * (a < PFT_PRE_YOUNG_AGES_ ? p->yexc[a] : 0u);
    }
    e = (e + 32768) >> 16;
    return (uint32_t)(e > 65535 ? 65535 : e);
}

static void young_geom_(pft_pre_t *p, const anchor_geom_t *g, young_geom_t *y)
{
    const int32_t w = p->cfg.width, sw = w + 3;
    int32_t qx[4];
    young_q_(g->gx.wr, qx);
    young_q_(g->gy.wr, y->qy);
    uint16_t *cx = p->prev;
    int32_t lo = w, hi = -1;
    for (int32_t x = 0; x < w; ++x) {
        cx[x] = (uint16_t)young_exc_(p, p->agex, x + g->gx.k, sw, qx);
        if (cx[x] == 0u) {
            lo = lo < x ? lo : x;
            hi = x;
        }
    }
    /* young columns are at the ends of the held range only (as bg_gate_young's spans): the
     * pixels between the first and the last old one are old */
    y->xlo = lo;
    y->xhi = hi;
}

/* bg_young_scale: residual row y (R units, before the whitening) divided by sqrt(1 + E), E
 * the larger of its column's and its row's excess; masked pixels kept. A row on old rows is
 * scaled outside xlo .. xhi only. */
static void young_row_(const pft_pre_t *p, const anchor_geom_t *g, const young_geom_t *yg, int32_t y, int16_t *r)
{
    const int32_t w = p->cfg.width, sh = p->cfg.height + 3;
    const uint32_t ey = young_exc_(p, p->agey, y + g->gy.k, sh, yg->qy);
    const bool all = ey > 0u || yg->xlo > yg->xhi; /* a young row, or no old column */
    const int32_t seg[2][2] = {{0, all ? w : yg->xlo}, {all ? w : yg->xhi + 1, w}};
    const uint16_t *cx = p->prev;
    for (int32_t s = 0; s < 2; ++s) {
        for (int32_t x = seg[s][0]; x < seg[s][1]; ++x) {
            const uint32_t e = cx[x] > ey ? cx[x] : ey;
            if (e == 0u || r[x] == PFT_RES16_MASKED) {
                continue;
            }
            const uint32_t j = e >> 10, fr = e & 1023u;
            const int32_t s0 = p->ysc[j], s1 = p->ysc[j + 1];
            const int32_t sc = s0 - (((s0 - s1) * (int32_t)fr + 512) >> 10);
            r[x] = (int16_t)(((int32_t)r[x] * sc + 16384) >> 15);
        }
    }
}

/* The temporal pass with bg_anchor (not held): the residual z - c - B read at the position's
 * fraction, then B updated with the frame interpolated into the grid. */
static void anchor_pass_(pft_pre_t *p, const pft_frame_t *f, const pft_pre_cls_t *c,
                         pft_pre_acc_t *acc, bool first, int32_t a15, uint32_t k1)
{
    const int32_t w = p->cfg.width, h = p->cfg.height, t = p->cfg.tile, sw = w + 3;
    const bool cubic = p->cfg.warp_cubic;
    int32_t *zl = p->line;
    if (first) {
        /* every cell from its nearest pixel (the last unmasked value for a masked one); the
         * cells of the frame's pixels hold the scene */
        p->aphi[0] = 0;
        p->aphi[1] = 0;
        int32_t carry = 0;
        uint32_t run = 0u; /* bg_stale_reinit: the cells since the last unmasked pixel */
        /* cell (j, jy) from pixel (j, jy) clamped into the frame (its nearest pixel), in the
         * order of the cells; each frame row converted once, its masked pixels counted */
        for (int32_t jy = -1; jy <= h + 1; ++jy) {
            uint16_t *b = p->bg + (size_t)(jy + 1) * (size_t)sw;
            const int32_t y = clampi_(jy, 0, h - 1);
            if ((jy == -1 || (jy == y && jy > 0)) && zrow_(c, f, (uint32_t)y, p->bf, p->colnow, zl) > 0u) {
                count_row_(c, f, (uint32_t)y, acc);
            }
            carry = zl[0] >= 0 ? zl[0] : carry; /* cell -1 */
            b[0] = (uint16_t)carry;
            for (int32_t j = 0; j < w; ++j) {
                carry = zl[j] >= 0 ? zl[j] : carry;
                b[j + 1] = (uint16_t)carry;
            }
            for (int32_t j = w; j <= w + 1; ++j) {
                carry = zl[w - 1] >= 0 ? zl[w - 1] : carry;
                b[j + 1] = (uint16_t)carry;
            }
            if (p->sage != NULL) { /* bg_stale_reinit: a cell whose nearest pixel is masked: never learnt, its age the distance to the pixel it was filled from */
                uint8_t *ar = p->sage + (size_t)(jy + 1) * (size_t)sw;
                for (int32_t j = -1; j <= w + 1; ++j) {
                    run = zl[clampi_(j, 0, w - 1)] >= 0 ? 0u : run + 1u;
                    ar[j + 1] = (uint8_t)(run > PFT_PRE_AGE_NEVER_ ? PFT_PRE_AGE_NEVER_ : run);
                }
                p->srow[jy + 1] = (uint8_t)max_u8_(ar, sw);
            }
        }
        p->avlo[0] = 0;
        p->avlo[1] = 0;
        p->avhi[0] = w - 1;
        p->avhi[1] = h - 1;
        for (int32_t y = 0; y < h; ++y) {
            int16_t *r = p->res + (size_t)y * (size_t)w;
            for (int32_t x = 0; x < w; ++x) {
                r[x] = PFT_RES16_MASKED;
            }
            acc->n_masked += (uint32_t)w;
            if (y + 1 == h || (y + 1) % t == 0) {
                pft_pre_tilerow_done_(p, (uint32_t)(y / t));
            }
        }
        if (p->agex != NULL) { /* every cell enters: age 0 */
            memset(p->agex, 0, (size_t)sw + (size_t)h + 3u);
        }
        p->bg_frames++;
        p->shift_prev[0] = 0;
        p->shift_prev[1] = 0;
        if (p->gsum != NULL) {
            gate_local_start_(p); /* a restart: no sums, m 0 */
        }
        return;
    }
    if (p->gsum != NULL) {
        gate_local_start_(p);
    }
    /* the new position p_k = p_{k-1} - shift (shift: the scene's move) */
    int32_t dA[2];
    for (uint32_t a = 0; a < 2u; ++a) {
        const int64_t v = (int64_t)p->aphi[a] - p->st.shift[a];
        const int64_t fa = v >= 0 ? v / 65536 : -((-v + 65535) / 65536);
        dA[a] = (int32_t)fa;
        p->aphi[a] = (int32_t)(v - fa * 65536);
    }
    anchor_move_(p, dA[0], dA[1]);
    anchor_geom_t g;
    agx_of_(p->aphi[0], cubic, &g.gx);
    agx_of_(p->aphi[1], cubic, &g.gy);
    g.ovlo[0] = p->avlo[0];
    g.ovlo[1] = p->avlo[1];
    g.ovhi[0] = p->avhi[0];
    g.ovhi[1] = p->avhi[1];
    g.a15 = a15;
    g.gate = p->cfg.bg_gate != 0u;
    /* update: cells whose update taps are all inside the frame are observed */
    const int32_t nn[2] = {w, h};
    g.edge = p->cfg.bg_edge_narrow != 0u;
    if (g.edge) {
        edge_geom_(p, &g);
    }
    for (uint32_t a = 0; a < 2u; ++a) {
        const agx_t *ga = a == 0u ? &g.gx : &g.gy;
        g.olo[a] = clampi_(-ga->ub - ga->ulo, -1, nn[a] + 2);
        g.ohi[a] = clampi_(nn[a] - 1 - ga->ub - ga->uhi, -2, nn[a] + 1);
        /* bg_edge_narrow: the cells of the 3-tap update are held after the update too */
        const int32_t nlo = g.edge ? g.llo[a] : g.olo[a], nhi = g.edge ? g.lhi[a] : g.ohi[a];
        const bool empty = g.ovlo[a] > g.ovhi[a];
        p->avlo[a] = empty || nlo < g.ovlo[a] ? nlo : g.ovlo[a];
        p->avhi[a] = empty || nhi > g.ovhi[a] ? nhi : g.ovhi[a];
    }
    young_geom_t yg;
    const bool yscale = p->cfg.bg_young_scale && p->agex != NULL;
    if (yscale) {
        young_geom_(p, &g, &yg);
    }
    const agx_t *gx = &g.gx;
    const agx_t *gy = &g.gy;
    const int16_t gw0 = (int16_t)gy->wr[0], gw1 = (int16_t)gy->wr[1], gw2 = (int16_t)gy->wr[2];
    const int16_t gw3 = (int16_t)gy->wr[3];
    const int32_t *ovlo = g.ovlo, *ovhi = g.ovhi;
    /* residual: pixels whose read taps are all valid cells */
    const int32_t xa = clampi_(ovlo[0] - gx->k - gx->rlo, 0, w), xb = clampi_(ovhi[0] - gx->k - gx->rhi, -1, w - 1);
    /* the residual's vertical blends in pft_pre_ares_span_'s split form (x86-64, AArch64) */
#if defined(PFT_PRE_RES_SPLIT_)
    const bool rsplit = res_split_ok_(gx->wr, gy->wr);
#else
    const bool rsplit = false;
#endif
    /* One pass over the frame rows: row y is converted once (into zl, the row before kept in
     * zp), its residual made from the grid as it was, its horizontal interpolation put in the
     * ring, and then grid row y + k - 1, which no later residual row reads and whose update
     * taps are frame rows up to y, is updated (its cells without an interpolated value from
     * the nearest pixel, frame row y + k - 1 - k clamped: zp, or zl on row 0). */
    int32_t jn = -1; /* the next grid row to update */
    bool mrow[4] = {false, false, false, false}; /* bg_stale_reinit: frame rows of the ring's slots with masked pixels */
    /* two rows that the whitening (pft_pre_row_out_, which uses p->line) leaves alone */
    zl = p->vb;
    int32_t *zp = p->bwl;
    /* anchor_hrow_'s int16 copy of a row (w values) in the column projections, which only the
     * registration reads (projections_ makes them anew each frame) */
    int16_t *zs16 = (int16_t *)(void *)p->pzc;
    for (int32_t y = 0; y < h; ++y) {
        const bool masked = zrow_(c, f, (uint32_t)y, p->bf, p->colnow, zl) > 0u;
        mrow[y & 3] = masked;
        if (masked) {
            count_row_(c, f, (uint32_t)y, acc);
        }
        /* the ring's slot of row y holds row y - 4, read by no update after the last one:
         * (w + 3) cells of scratch for the residual's vertical blends */
        int32_t *vb = p->aring + (size_t)(y & 3) * (size_t)sw;
        int16_t *r = p->res + (size_t)y * (size_t)w;
        const int32_t r0 = y + gy->k; /* taps r0 - 1 .. r0 + 2 */
        const bool covered = r0 + gy->rlo >= ovlo[1] && r0 + gy->rhi <= ovhi[1] && xa <= xb;
        if (covered) {
            /* storage rows r0 .. r0 + 3 (cells r0 - 1 .. r0 + 2), clamped to the grid: a tap
             * outside it has weight 0 (covered) */
            const uint16_t *tr[4];
            for (int32_t i = 0; i < 4; ++i) {
                tr[i] = p->bg + (size_t)clampi_(r0 + i, 0, h + 2) * (size_t)sw;
            }
            const uint16_t *t0 = tr[0], *t1 = tr[1], *t2 = tr[2], *t3 = tr[3];
            /* storage columns of the taps (x + k .. x + k + 3), at most w + 2 */
            const int32_t c0 = xa + gx->k, c1 = xb + gx->k + 3 > w + 2 ? w + 2 : xb + gx->k + 3;
#if defined(PFT_PRE_RES_SPLIT_)
            if (rsplit) { /* the split words of pft_pre_ares_span_ */
#if defined(__SSE2__)
                const int16_t gw[4] = {gw0, gw1, gw2, gw3};
                const int32_t i0 = vsplit8_(t0, t1, t2, t3, gw, vb, c0, c1);
#else
                const int32_t i0 = c0;
#endif
                for (int32_t i = i0; i <= c1; ++i) { /* vectorisable */
                    vb[i] = vsplit_(vtap_(t0, t1, t2, t3, gw0, gw1, gw2, gw3, i));
                }
            } else
#endif
            {
                for (int32_t i = c0; i <= c1; ++i) { /* vectorisable: U * 16, as anchor_view_ */
                    vb[i] = vtap_(t0, t1, t2, t3, gw0, gw1, gw2, gw3, i);
                }
            }
        }
        /* masked outside the covered span [xa, xb] (or the whole row), and where z is */
        const int32_t ca = covered ? xa : w, cb = covered ? xb : w - 1;
        for (int32_t x = 0; x < ca; ++x) {
            r[x] = PFT_RES16_MASKED;
        }
        {
            /* storage columns x + k .. x + k + 3, inside the slot (w + 3 cells) for x < xe;
             * a tap past it (x + k + i > w + 2) is past the covered taps: weight 0, left out */
            const int32_t *v = vb + gx->k;
            const int32_t w0 = gx->wr[0], w1 = gx->wr[1], w2 = gx->wr[2], w3 = gx->wr[3];
            const int32_t xe = cb < w - 1 - gx->k ? cb : w - 1 - gx->k;
#if defined(PFT_PRE_RES_SPLIT_)
            if (rsplit) {
                pft_pre_ares_span_(v, zl, r, ca, xe, gx->wr, k1, true);
            } else
#endif
            {
                for (int32_t x = ca; x <= xe; ++x) { /* vectorisable */
                    const int32_t sv = (w0 * v[x] + w1 * v[x + 1] + w2 * v[x + 2] + w3 * v[x + 3] + 2048) >> 12;
                    const int32_t bx = sv < 0 ? 0 : (sv > 65535 ? 65535 : sv);
                    const int32_t rr = pft_pre_rclamp_((zl[x] - bx + (int32_t)k1) >> k1);
                    r[x] = (int16_t)(zl[x] < 0 ? PFT_RES16_MASKED : rr);
                }
            }
            for (int32_t x = (xe + 1 > ca ? xe + 1 : ca); x <= cb; ++x) {
                int32_t sv = 2048;
                for (int32_t i = 0; i < 4 && x + gx->k + i <= w + 2; ++i) {
                    sv += gx->wr[i] * (rsplit ? vjoin_(v[x + i]) : v[x + i]);
                }
                sv >>= 12;
                const int32_t bx = sv < 0 ? 0 : (sv > 65535 ? 65535 : sv);
                const int32_t rr = pft_pre_rclamp_((zl[x] - bx + (int32_t)k1) >> k1);
                r[x] = (int16_t)(zl[x] < 0 ? PFT_RES16_MASKED : rr);
            }
        }
        for (int32_t x = cb + 1; x < w; ++x) {
            r[x] = PFT_RES16_MASKED;
        }
        if (p->sage != NULL && covered) {
            stale_anchor_res_(p, gx, gy, r0, ca, cb, p->cfg.bg_stale_reinit, r);
        }
        if (g.edge) {
            edge_res_row_(p, &g, r0, covered ? xa : w, covered ? xb : w - 1, zl, k1, r);
        }
        if (yscale) {
            young_row_(p, &g, &yg, y, r);
        }
        acc->n_masked += pft_pre_row_out_(p, (uint32_t)y);
        if (y + 1 == h || (y + 1) % t == 0) {
            pft_pre_tilerow_done_(p, (uint32_t)(y / t));
        }
        anchor_hrow_(&g, zl, w, vb, zs16);
        if (masked && p->cfg.bg_masked_taps != 0u) {
            const bool young = p->cfg.bg_masked_taps == PFT_PRE_MASKED_TAPS_YOUNG && p->agex != NULL;
            anchor_hrow_masked_(&g, zl, w, vb, young ? p->agex + 1 : NULL, p->cfg.bg_gate_young);
        }
        if (g.edge) {
            edge_hrow_(&g, p->aphi[0], zl, vb);
        }
        for (; jn <= y + gy->k - 1; ++jn) { /* at most 2 rows (k <= 1) */
            anchor_urow_(p, &g, jn, clampi_(jn - gy->k, 0, h - 1) == y ? zl : zp);
            if (p->sage != NULL) {
                stale_anchor_urow_(p, &g, jn, p->cfg.bg_stale_reinit, mrow);
            }
            if (g.edge) {
                edge_urow_(p, &g, jn);
            }
        }
        int32_t *zs = zp;
        zp = zl;
        zl = zs;
    }
    for (; jn <= h + 1; ++jn) { /* grid rows past the last frame row's (their pixel: row h - 1) */
        anchor_urow_(p, &g, jn, zp);
        if (p->sage != NULL) {
            stale_anchor_urow_(p, &g, jn, p->cfg.bg_stale_reinit, mrow);
        }
        if (g.edge) {
            edge_urow_(p, &g, jn);
        }
    }
    if (p->agex != NULL) {
        age_step_(p->agex, sw, ovlo[0], ovhi[0], p->avlo[0], p->avhi[0]);
        age_step_(p->agey, h + 3, ovlo[1], ovhi[1], p->avlo[1], p->avhi[1]);
    }
    p->bg_frames++;
    if (!p->jumped) {
        p->shift_prev[0] = p->st.shift[0];
        p->shift_prev[1] = p->st.shift[1];
    }
}

void pft_pre_temporal_pass_(pft_pre_t *p, const pft_frame_t *f, pft_pre_acc_t *acc)
{
    const int32_t w = p->cfg.width, h = p->cfg.height, t = p->cfg.tile;
    pft_pre_cls_t c;
    pft_pre_cls_init_(p, &c);
    const bool first = p->bg_frames == 0u;
    const bool held = (acc->flags & PFT_PRE_FLAG_HELD) != 0u;
    /* alpha, or 1/(n+1) while the background holds fewer than 1/alpha frames */
    int64_t alpha = p->cfg.bg_alpha;
    if (!first && !held) {
        const int64_t avg = (65536 + (int64_t)p->bg_frames / 2) / ((int64_t)p->bg_frames + 1);
        alpha = avg > alpha ? avg : alpha;
    }
    if (held) {
        alpha = 0;
    }
    if (first || alpha > p->cfg.bg_alpha) {
        acc->flags |= PFT_PRE_FLAG_WARMUP;
    }
    const warp_t g = warp_of_(p->st.shift);
    /* in place: rows are walked away from the side their taps come from; each row's taps are
     * blended into vb before the row is written */
    const bool yup = g.ky >= 0;
    int32_t wy[4], wx[4];
    warp_q8_(g.fy, p->cfg.warp_cubic, wy);
    warp_q8_(g.fx, p->cfg.warp_cubic, wx);
    /* taps of non-zero weight: x + kx + tlo .. x + kx + thi (f = 0: the central one only) */
    const int32_t txlo = wx[0] != 0 ? -1 : 0, txhi = wx[3] != 0 ? 2 : (wx[2] != 0 ? 1 : 0);
    const int32_t tylo = wy[0] != 0 ? -1 : 0, tyhi = wy[3] != 0 ? 2 : (wy[2] != 0 ? 1 : 0);
    const int32_t xa = clampi_(-g.kx - txlo, 0, w); /* taps of x in [xa, xb] are inside */
    const int32_t xb = clampi_(w - 1 - g.kx - txhi, -1, w - 1);
    const uint32_t k1 = (uint32_t)(p->bf - p->rs); /* 0 or 1 */
    /* alpha with 15 bits so that e * alpha fits 32 bits (|e| <= 65535) */
    const int32_t a15 = (int32_t)((alpha + 1) >> 1);
    if (p->cfg.bg_anchor && !held) {
        anchor_pass_(p, f, &c, acc, first, a15, k1);
        return;
    }
    int32_t *zl = p->line, *bw = p->bwl;
    int32_t carry = 0;  /* first frame: the last unmasked value, for masked pixels */
    uint32_t run = 0u;  /* first frame, bg_stale_reinit: the pixels since the last unmasked one */
    int32_t yprev = -1; /* the row written last; p->prev holds its former values */
    if (held) {
        /* a constant frame (a glitch, a shutter): the background is kept as it is and the
         * residual, which would only show the background, is masked */
        for (int32_t y = 0; y < h; ++y) {
            if (zrow_(&c, f, (uint32_t)y, p->bf, p->colnow, zl) > 0u) {
                count_row_(&c, f, (uint32_t)y, acc);
            }
            int16_t *r = p->res + (size_t)y * (size_t)w;
            for (int32_t x = 0; x < w; ++x) {
                r[x] = PFT_RES16_MASKED;
            }
            acc->n_masked += pft_pre_row_out_(p, (uint32_t)y);
            if (y + 1 == h || (y + 1) % t == 0) {
                pft_pre_tilerow_done_(p, (uint32_t)(y / t));
            }
        }
        return;
    }
    if (p->sage != NULL && !first) {
        stale_plain_(p, &g, txlo, txhi, tylo, tyhi, p->cfg.bg_stale_reinit);
    }
    /* prediction: exact taps inside [xa, xb] = [ia, ib), clamped outside (for masked pixels) */
    const int32_t ia = xa < w ? xa : w, ib = xb + 1 > ia ? xb + 1 : ia;
    fused_t fu;
    fu.vb = p->vb;
    fu.cn = p->colnow;
    fu.kx = g.kx;
    fu.w0 = wx[0];
    fu.w1 = wx[1];
    fu.w2 = wx[2];
    fu.w3 = wx[3];
    fu.a15 = a15;
    fu.k1 = (int32_t)k1;
    fu.bf = p->bf;
    for (int32_t yi = 0; yi < h; ++yi) {
        const int32_t y = yup ? yi : h - 1 - yi;
        const int32_t r0 = y + g.ky;
        const bool covered = r0 + tylo >= 0 && r0 + tyhi <= h - 1;
        /* a covered row of a U16 frame without a bad-pixel map: its covered columns in one
         * pass (fused_span_), the frame row converted only outside them */
        /* bg_stale_reinit: a row with stale pixels is made without the fused span (zl whole) */
        const bool srow_stale = p->sage != NULL && !first && (p->srow[y] & PFT_PRE_AGE_STALE_) != 0u;
        const bool fast = !first && covered && ia < ib && c.map == NULL && !c.u8 && !srow_stale;
        uint32_t ninv = fast ? zspan_(&c, f, (uint32_t)y, p->bf, p->colnow, zl, 0u, (uint32_t)ia) +
                                   zspan_(&c, f, (uint32_t)y, p->bf, p->colnow, zl, (uint32_t)ib, (uint32_t)w)
                             : zrow_(&c, f, (uint32_t)y, p->bf, p->colnow, zl);
        if (fast && ninv > 0u) { /* the columns outside the fused span, counted by cause now */
            count_span_(&c, f, (uint32_t)y, 0u, (uint32_t)ia, acc);
            count_span_(&c, f, (uint32_t)y, (uint32_t)ib, (uint32_t)w, acc);
        }
        if (!fast && ninv > 0u) {
            count_row_(&c, f, (uint32_t)y, acc);
        }
        uint16_t *b = p->bg + (size_t)y * (size_t)w;
        int16_t *r = p->res + (size_t)y * (size_t)w;
        if (first) {
            for (int32_t x = 0; x < w; ++x) {
                carry = zl[x] >= 0 ? zl[x] : carry;
                b[x] = (uint16_t)carry;
                r[x] = PFT_RES16_MASKED;
            }
            if (p->sage != NULL) { /* bg_stale_reinit: a masked pixel's value was never learnt, its age the distance to the pixel it was filled from */
                uint8_t *ar = p->sage + (size_t)y * (size_t)w;
                for (int32_t x = 0; x < w; ++x) {
                    run = zl[x] >= 0 ? 0u : run + 1u;
                    ar[x] = (uint8_t)(run > PFT_PRE_AGE_NEVER_ ? PFT_PRE_AGE_NEVER_ : run);
                }
                p->srow[y] = (uint8_t)max_u8_(ar, w);
            }
            acc->n_masked += (uint32_t)w;
        } else {
            /* tap rows y + ky - 1 .. y + ky + 2, clamped; the row written last is read from its
             * copy; the row is covered when those of non-zero weight are inside */
            const uint16_t *tr[4];
            for (int32_t i = 0; i < 4; ++i) {
                const int32_t rr = clampi_(r0 - 1 + i, 0, h - 1);
                tr[i] = rr == yprev ? p->prev : p->bg + (size_t)rr * (size_t)w;
            }
            const uint16_t *t0 = tr[0], *t1 = tr[1], *t2 = tr[2], *t3 = tr[3];
            int32_t *vb = p->vb;
            /* 16 x 16-bit products (vectorisable with 16-bit multiplies): the taps biased by
             * -32768 into int16, the bias added back as 32768 times the weights' sum (256) */
            const int16_t w0 = (int16_t)wy[0], w1 = (int16_t)wy[1], w2 = (int16_t)wy[2];
            const int16_t w3 = (int16_t)wy[3];
            /* the row in two halves, a pixel of each per iteration: two independent chains
             * in the vector loop for an in-order core to overlap (the same value per pixel) */
            const int32_t hw = w / 2;
            for (int32_t x = 0; x < hw; ++x) {
                vb[x] = vtap_(t0, t1, t2, t3, w0, w1, w2, w3, x);
                vb[x + hw] = vtap_(t0, t1, t2, t3, w0, w1, w2, w3, x + hw);
            }
            for (int32_t x = 2 * hw; x < w; ++x) {
                vb[x] = vtap_(t0, t1, t2, t3, w0, w1, w2, w3, x);
            }
            memcpy(p->prev, b, (size_t)w * 2u);
            yprev = y;
            if (fast) {
                /* outside [ia, ib): masked, the background restarts from z (as below) */
                hcubic_(vb, g.kx, wx, w, 0, ia, true, bw);
                hcubic_(vb, g.kx, wx, w, ib, w, true, bw);
                const int32_t seg[2][2] = {{0, ia}, {ib, w}};
                for (int32_t s = 0; s < 2; ++s) {
                    for (int32_t x = seg[s][0]; x < seg[s][1]; ++x) {
                        r[x] = PFT_RES16_MASKED;
                        b[x] = (uint16_t)(zl[x] >= 0 ? zl[x] : bw[x]);
                    }
                }
                /* the span's masked pixels counted in the loop (dead, else saturated: no map
                 * here), so that the raw row is not read after it (in place, r is that row) */
                uint32_t nd = 0u;
                const uint32_t nspan = fused_span_(&c, pft_frame_row(f, (uint32_t)y), &fu, b, r, ia, ib, &nd);
                ninv += nspan;
                acc->n_dead += nd;
                acc->n_sat += nspan - nd;
                if (p->sage != NULL) { /* no stale pixel on this row (srow_stale) */
                    stale_plain_row_(p, y, zl, b, r, ia, ib, ninv);
                }
            } else {
                hcubic_(vb, g.kx, wx, w, 0, ia, true, bw);
                hcubic_(vb, g.kx, wx, w, ia, ib, false, bw);
                hcubic_(vb, g.kx, wx, w, ib, w, true, bw);
                for (int32_t x = 0; x < w; ++x) { /* vectorisable: update and residual */
                    const int32_t zu = zl[x], bx = bw[x], e = zu - bx;
                    const int32_t nb = bx + ((e * a15 + 16384) >> 15);
                    const int32_t rr = pft_pre_rclamp_((e + (int32_t)k1) >> k1);
                    b[x] = (uint16_t)(zu < 0 ? bx : nb);
                    r[x] = (int16_t)(zu < 0 ? PFT_RES16_MASKED : rr);
                }
                /* a pixel with a tap outside the image (the last frame's view) sees a part of the
                 * scene the background has not seen, or has only extrapolated: its residual is
                 * masked and its background restarts from z (x outside [xa, xb], or every pixel
                 * of a row that is not covered) */
                const int32_t ua = covered ? ia : w, ub = covered ? ib : w;
                /* the columns before and after the covered ones [ua, ub) */
                const int32_t ea = (ua >= 0 && ua < w) ? ua : w, sb = ea < w ? ub : w;
                const int32_t seg[2][2] = {{0, ea}, {sb, w}};
                for (int32_t s = 0; s < 2; ++s) {
                    for (int32_t x = seg[s][0]; x < seg[s][1]; ++x) {
                        r[x] = PFT_RES16_MASKED;
                        if (zl[x] >= 0) {
                            b[x] = (uint16_t)zl[x];
                        }
                    }
                }
                if (p->sage != NULL) {
                    stale_plain_row_(p, y, zl, b, r, ea, sb, ninv);
                }
            }
            acc->n_masked += pft_pre_row_out_(p, (uint32_t)y);
        }
        const bool tile_end = yup ? (y + 1 == h || (y + 1) % t == 0) : (y % t == 0);
        if (tile_end) {
            pft_pre_tilerow_done_(p, (uint32_t)(y / t));
        }
    }
    if (!held) {
        p->bg_frames++;
        if (!p->jumped) {
            p->shift_prev[0] = p->st.shift[0];
            p->shift_prev[1] = p->st.shift[1];
        }
    }
}
