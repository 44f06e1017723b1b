/* Internals shared by the tsa sources (private, not installed): integer square roots, reals as
 * Q16.16 integers, the channel layout of the accepted pixel formats, bounding boxes. */
#ifndef PFT_TSA_INT_H
#define PFT_TSA_INT_H

#include "pft/pft_tsa.h"

/* The pixel formats the appearance model reads. */
#define PFT_TSA_FMT_MASK_ \
    (PFT_FMT_BIT(PFT_PIX_U8) | PFT_FMT_BIT(PFT_PIX_RGB888) | PFT_FMT_BIT(PFT_PIX_BGR888))

/* Square roots at the starts of the 192 intervals of 2^24 that cover [2^30, 2^32): entry i is
 * round(sqrt((i + 64) 2^24)), i = 0..192 (tsa_hist.c). */
extern const uint32_t pft_tsa_sqrt_tab_[193];

/* Even shifts that put a byte b (1..255) into [64, 256): 6 for 1..3, 4 for 4..15, 2 for 16..63,
 * 0 above (tsa_hist.c). */
extern const uint8_t pft_tsa_norm_tab_[256];

/* v shifted left by the even s (returned) that puts it into [2^30, 2^32); v > 0. */
static inline uint32_t pft_tsa_norm_(uint32_t *v)
{
    uint32_t x = *v;
    uint32_t s = 0u;
    if (x < 0x1000000u) { /* the usual case, x >= 2^24, takes one test */
        if (x < 0x10000u) {
            x <<= 16;
            s = 16u;
        }
        if (x < 0x1000000u) {
            x <<= 8;
            s += 8u;
        }
    }
    const uint32_t t = pft_tsa_norm_tab_[x >> 24];
    *v = x << t;
    return s + t;
}

/* The chord of the table's interval at x in [2^30, 2^32): sqrt(x) - 2 < result <= sqrt(x) + 1. */
static inline uint32_t pft_tsa_sqrt_chord_(uint32_t x)
{
    const uint32_t i = (x >> 24) - 64u;
    const uint32_t a = pft_tsa_sqrt_tab_[i];
    return a + (((pft_tsa_sqrt_tab_[i + 1u] - a) * ((x >> 8) & 0xFFFFu)) >> 16);
}

/* sqrt(v) to within 2 of sqrt(v 2^s) / 2^(s/2), where s puts v into [2^30, 2^32) (so within
 * 2^-14 relative for v >= 2^30 ...): the chord without the corrections, for the Bhattacharyya
 * coefficient, whose bins are scaled up first. This one for v > 0: */
static inline uint32_t pft_tsa_sqrt_approx_nz_(uint32_t v)
{
    const uint32_t s = pft_tsa_norm_(&v);
    return pft_tsa_sqrt_chord_(v) >> (s / 2u);
}
/* The same for any v (0 for 0). */
static inline uint32_t pft_tsa_sqrt_approx_(uint32_t v)
{
    return v == 0u ? 0u : pft_tsa_sqrt_approx_nz_(v);
}

/* floor(sqrt(v)) for a 32-bit v, exactly, without a division: v is shifted left by an even s
 * into [2^30, 2^32), the chord of the table's interval gives sqrt within 2 (sqrt is concave,
 * the chord lies below it by at most 1/4), two correction steps each way make it exact, and
 * floor(sqrt(v)) = floor(sqrt(v 2^s)) >> s/2. About 25 operations instead of the 16 rounds of
 * the bit-by-bit method (tests/unit/test_tsa_hist.c compares the two). */
static inline uint32_t pft_tsa_isqrt32_(uint32_t v)
{
    if (v == 0u) {
        return 0u;
    }
    uint32_t x = v;
    const uint32_t s = pft_tsa_norm_(&x);
    uint32_t r = pft_tsa_sqrt_chord_(x);
    if ((uint64_t)r * r > x) {
        --r;
    }
    if ((uint64_t)r * r > x) {
        --r;
    }
    if ((uint64_t)(r + 1u) * (r + 1u) <= x) {
        ++r;
    }
    if ((uint64_t)(r + 1u) * (r + 1u) <= x) {
        ++r;
    }
    return r >> (s / 2u);
}

/* floor(sqrt(v)), bit by bit (16 rounds): the reference the unit test compares
 * pft_tsa_isqrt32_ with. */
static inline uint32_t pft_tsa_isqrt32_ref_(uint32_t v)
{
    uint32_t r = 0u;
    uint32_t bit = (uint32_t)1u << 30;
    while (bit > v) {
        bit >>= 2;
    }
    while (bit != 0u) {
        if (v >= r + bit) {
            v -= r + bit;
            r = (r >> 1) + bit;
        } else {
            r >>= 1;
        }
        bit >>= 2;
    }
    return r;
}

/* floor(sqrt(v)) for a 64-bit v: pft_tsa_isqrt32_ below 2^32, else bit by bit (32 rounds). */
static inline uint32_t pft_tsa_isqrt64_(uint64_t v)
{
    if (v <= 0xFFFFFFFFu) {
        return pft_tsa_isqrt32_((uint32_t)v);
    }
    uint64_t r = 0u;
    uint64_t bit = (uint64_t)1u << 62;
    while (bit > v) {
        bit >>= 2;
    }
    while (bit != 0u) {
        if (v >= r + bit) {
            v -= r + bit;
            r = (r >> 1) + bit;
        } else {
            r >>= 1;
        }
        bit >>= 2;
    }
    return (uint32_t)r;
}

/* a in Q16.16 units as an integer, rounded to nearest with ties away from zero and saturated
 * to +-INT32_MAX: the identity in the q16 build, round(65536 a) in the float build. Built from
 * the integer part and two 8-bit steps of the fraction, so no intermediate leaves the Q16.16
 * range in either build. */
static inline int32_t pft_tsa_q16_(pft_real_t a)
{
    const pft_real_t m = pft_abs(a);
    /* the top of the Q16.16 range: PFT_REAL_MAX in q16 (so only PFT_REAL_MAX itself saturates,
     * to itself), 32768 in float */
    if (!(m < pft_ratio(INT32_MAX, 65536))) {
        return a < 0 ? -INT32_MAX : INT32_MAX;
    }
    const int32_t whole = pft_floor_int(m);
    const pft_real_t f256 = pft_mul_i(pft_sub(m, pft_from_int(whole)), 256); /* [0, 256) */
    const int32_t hi = pft_floor_int(f256);
    const int32_t lo = pft_round_int(pft_mul_i(pft_sub(f256, pft_from_int(hi)), 256));
    const int32_t r = whole * 65536 + hi * 256 + lo;
    return a < 0 ? -r : r;
}

/* Channel offsets (R, G, B) of a pixel of format fmt; bytes per pixel in *bpp. */
static inline void pft_tsa_channels_(pft_pixfmt_t fmt, uint32_t *o0, uint32_t *o1, uint32_t *o2,
                                     uint32_t *bpp)
{
    if (fmt == PFT_PIX_RGB888) {
        *o0 = 0u;
        *o1 = 1u;
        *o2 = 2u;
        *bpp = 3u;
    } else if (fmt == PFT_PIX_BGR888) {
        *o0 = 2u;
        *o1 = 1u;
        *o2 = 0u;
        *bpp = 3u;
    } else {
        *o0 = 0u;
        *o1 = 0u;
        *o2 = 0u;
        *bpp = 1u;
    }
}

/* ------------------------------------------------------------ fast appearance path (tsa_appear.c)
 * The tracker computes up to N + 2 kernel histograms per frame. Instead of reading three
 * channels and three bins per kernel pixel and placement, it codes each pixel of the region
 * the placements cover once per frame (a 16-bit code: the joint (R, G) bin 10 r + g in the low
 * byte, 100 + the B bin in the high byte), walks the kernel as row spans, adds each pixel's
 * weight to two bins of a 110-bin joint histogram and folds that into the 30 bins. The sums are
 * the same integers as pft_tsa_hist's. */

/* The spans of k (row-major pixels) and its weights in that order (w: k->n entries); returns
 * the span count, or cap + 1 when they do not fit. */
uint32_t pft_tsa_spans_(const pft_tsa_kernel_t *k, pft_tsa_span_t *out, uint32_t cap,
                        uint16_t *w);

/* One frame as the appearance model reads it: channel offsets (the bin of each channel value
 * comes from constant tables of tsa_appear.c), and (when mw > 0) the codes of the region [mx0, mx0 + mw) x [my0, my0 + mh) in two planes,
 * row-major: map the joint bins 10 r + g, map_b the bins 100 + b. */
typedef struct {
    const pft_frame_t *f;
    uint32_t off[3];
    uint32_t bpp;
    const uint8_t *map, *map_b;
    int32_t mx0, my0, mw, mh;
} pft_tsa_view_t_;

/* A view of frame (checked by the caller) without a code map. */
void pft_tsa_view_init_(pft_tsa_view_t_ *v, const pft_frame_t *frame);

/* Codes the region [x0, x1] x [y0, y1] (clipped to the frame) into map (2 cap bytes) when it
 * has at most cap pixels; otherwise (or for an empty region) the view keeps reading the
 * frame. */
void pft_tsa_view_map_(pft_tsa_view_t_ *v, uint8_t *map, size_t cap, int32_t x0, int32_t y0,
                       int32_t x1, int32_t y1);

/* The histogram of kernel k (with its spans sp[0..nsp) and weights kw) at origin (cx, cy): the
 * same as pft_tsa_hist's. jb: scratch of 110 uint32 (the joint bins; the tracker's instance
 * holds it, so that it is not on the stack of the update). */
void pft_tsa_view_hist_(const pft_tsa_view_t_ *v, const pft_tsa_kernel_t *k,
                        const pft_tsa_span_t *sp, uint32_t nsp, const uint16_t *kw, int32_t cx,
                        int32_t cy, pft_tsa_hist_t *h, uint32_t *jb);

/* pft_tsa_hist of a checked frame with every channel value v taken as min(255, round(v gain /
 * 256)) (gain 256: the same histogram); kernel and h not NULL. */
void pft_tsa_hist_gain_(const pft_frame_t *frame, const pft_tsa_kernel_t *k, int32_t cx,
                        int32_t cy, uint32_t gain, pft_tsa_hist_t *h);

/* The square-root form (pft_tsa_hroot_t) of a histogram: with the even shift s that puts
 * total << s into [2^30, 2^32) (every bin is at most total), root = isqrt(total << s) and
 * s_u = isqrt(bin_u << s). All zero for an empty histogram. */
void pft_tsa_hroot_(const pft_tsa_hist_t *h, pft_tsa_hroot_t *r);

/* rho of histogram p against the template q (qr: pft_tsa_hroot_ of q): q16 sum_u s_u(p) s_u(q) /
 * (3 root(p) root(q)) with square roots taken only where both bins are nonzero (the loop runs
 * over qr's nonzero bins); float the same
 * coefficient with the FPU's square root (a twin: tests/unit/test_tsa_hist.c bounds both against
 * a 64-bit floating-point value). 1 at most, 0 when either is empty. */
pft_real_t pft_tsa_rho_hist_(const pft_tsa_hist_t *p, const pft_tsa_hist_t *q,
                             const pft_tsa_hroot_t *qr);

/* pft_tsa_rho_hist_ of p against the n templates q[0..n) (roots qr[0..n)) into out[0..n), the
 * same values; q16 takes p's square roots once for all of them. */
void pft_tsa_rho_bank_(const pft_tsa_hist_t *p, const pft_tsa_hist_t *q, const pft_tsa_hroot_t *qr,
                       uint32_t n, pft_real_t *out);

/* pft_tsa_motion_free_step with the input's terms given: ux = gamma1 vbar, uv = gamma2 vbar
 * (the same for every particle of a frame, so computed once). */
static inline void pft_tsa_motion_free_step_u_(const pft_tsa_motion_free_t *c, pft_real_t *x,
                                               pft_real_t *v, pft_real_t ux, pft_real_t uv,
                                               pft_real_t g1, pft_real_t g2)
{
    const pft_real_t v0 = *v;
    *x = pft_add(*x, pft_add(pft_add(pft_mul(c->phi12, v0), ux), pft_mul(c->l11, g1)));
    *v = pft_add(pft_add(pft_mul(c->phi22, v0), uv), pft_add(pft_mul(c->l21, g1), pft_mul(c->l22, g2)));
}

/* Inclusive bounding box of integer points. */
typedef struct {
    int32_t x0, y0, x1, y1;
} pft_tsa_box_t_;

/* Bounding box of pts[0..n) (n >= 1). */
pft_tsa_box_t_ pft_tsa_bbox_(const pft_tsa_pt_t *pts, uint32_t n);

/* The unit-weight histogram of the ring between the box in (frame coordinates, inclusive) and
 * that box grown by mx columns and my rows on each side, clipped to the frame, with every channel
 * value taken under the gain / 256 as in pft_tsa_hist_gain_ (the background-weighted model,
 * config bg_ring); frame checked, h not NULL. */
void pft_tsa_ring_hist_(const pft_frame_t *frame, const pft_tsa_box_t_ *in, int32_t mx, int32_t my,
                        uint32_t gain, pft_tsa_hist_t *h);

/* Weighs the template q (each channel summing to q->total) by the background histogram o: bin u
 * times v_u = min(o* / o_u, 1), o* the smallest nonzero bin of o in u's channel (v_u = 1 where
 * o_u = 0; a channel with no background bin is left as it is), then each channel renormalised to
 * sum to q->total and mixed with the unweighted bins: a16 / 65536 of the weighted bin plus the rest
 * of the unweighted one (a16 = 65536: the weighted template alone), each channel summing to
 * q->total exactly (integer arithmetic, the same in both builds; the remainder of the rounding
 * added to the channel's largest weighted bin). */
void pft_tsa_bg_weight_(pft_tsa_hist_t *q, const pft_tsa_hist_t *o, uint32_t a16);

/* Pixel centres inside the polygon poly[0..n) (n >= 3; 0 for a zero area); cross: scratch of n
 * int32. */
uint32_t pft_tsa_poly_count_(const pft_tsa_pt_t *poly, uint32_t n, int32_t *cross);

#endif
