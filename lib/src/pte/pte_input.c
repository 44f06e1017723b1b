/* Input stage of the pte family: frame conversion, noise normalisation (fixed or CA-CFAR)
 * and the ring of the last normalised frames. */
#include <string.h>

#include "pte_int.h"
#include "../core/seq_int.h"
#include "../core/config_int.h"

void pft_pte_input_default(pft_pte_input_t *in)
{
    if (in == NULL) {
        return;
    }
    memset(in, 0, sizeof(*in));
    in->n_range = 150u;
    in->n_doppler = 1u;
    in->pixel_gain = PFT_C(1.0);
    in->pixel_offset = PFT_C(0.0);
    in->noise = PFT_PTE_NOISE_FIXED;
    in->noise_sigma = PFT_C(1.0);
    in->cfar_ref = 16u;
    in->cfar_guard = 2u;
    in->zeta_clip = PFT_C(20.0);
    in->seq_mode = PFT_SEQ_IGNORE;
    in->max_gap = (uint16_t)PFT_SEQ_DEFAULT_GAP;
}

const char *pft_pte_input_bad_(const pft_pte_input_t *in)
{
    if (in->n_range < 2u || in->n_range > PFT_CFG_MAX_IMAGE_SIDE) {
        return "in.n_range";
    }
    if (in->n_doppler < 1u || in->n_doppler > PFT_CFG_MAX_IMAGE_SIDE) {
        return "in.n_doppler";
    }
    if (in->noise != PFT_PTE_NOISE_FIXED && in->noise != PFT_PTE_NOISE_CFAR) {
        return "in.noise";
    }
    /* reals in the configuration domain shared by both builds (core/config_int.h) */
    if (!pft_cfg_real_pos_(in->noise_sigma)) {
        return "in.noise_sigma";
    }
    if (!pft_cfg_real_ok_(in->pixel_gain)) {
        return "in.pixel_gain";
    }
    if (!pft_cfg_real_ok_(in->pixel_offset)) {
        return "in.pixel_offset";
    }
    if (!pft_cfg_real_pos_(in->zeta_clip) || in->zeta_clip > PFT_C(1000.0)) {
        return "in.zeta_clip";
    }
    if (in->cfar_ref < 1u || in->cfar_ref > PFT_PTE_MAX_CFAR_REF) {
        return "in.cfar_ref";
    }
    if (in->seq_mode != PFT_SEQ_IGNORE && in->seq_mode != PFT_SEQ_USE) {
        return "in.seq_mode";
    }
    if (in->max_gap < 1u || in->max_gap > PFT_SEQ_MAX_GAP) {
        return "in.max_gap";
    }
    return NULL;
}

pft_status_t pft_pte_input_check(const pft_pte_input_t *in, const char **field)
{
    if (field != NULL) {
        *field = NULL;
    }
    if (in == NULL) {
        return PFT_ERR_INVAL;
    }
    const char *bad = pft_pte_input_bad_(in);
    /* the names without the "in." of a tracker configuration */
    return pft_pte_check_done_(bad == NULL ? NULL : bad + 3, field);
}

pft_status_t pft_pte_seq_check_(const pft_pte_input_t *in, const pft_pte_seq_t *s,
                                const pft_frame_t *frame, uint32_t *k)
{
    *k = 1u;
    if (frame == NULL) {
        return PFT_OK; /* values without a seq: the next frame */
    }
    pft_status_t st = pft_pte_frame_check_(in, frame);
    if (st == PFT_OK) {
        st = pft_seq_gap_(in->seq_mode, in->max_gap, s->set, s->last, frame->seq, k);
    }
    return st;
}

void pft_pte_seq_take_(const pft_pte_input_t *in, pft_pte_seq_t *s, const pft_frame_t *frame,
                       pft_pte_report_t *rep, uint32_t n_rep)
{
    uint32_t gap = 1u;
    if (frame != NULL && !s->set) {
        gap = 0u;
    } else if (frame != NULL && in->seq_mode == PFT_SEQ_USE) {
        gap = frame->seq - s->last;
    } else {
        /* consecutive */
    }
    if (frame != NULL) {
        s->last = frame->seq;
        s->ts = frame->timestamp_us;
        s->set = true;
    } else if (s->set) {
        s->last++;
    } else {
        /* no numbered frame yet: reports carry 0 */
    }
    for (uint32_t i = 0; i < n_rep; ++i) {
        rep[i].last_seq = s->last;
        rep[i].last_timestamp_us = s->ts;
        rep[i].gap = gap;
    }
}

pft_status_t pft_pte_frame_check_(const pft_pte_input_t *in, const pft_frame_t *frame)
{
    uint32_t fmts = PFT_FMT_BIT(PFT_PIX_U8) | PFT_FMT_BIT(PFT_PIX_U16) | PFT_FMT_BIT(PFT_PIX_F32);
    pft_status_t st = pft_frame_check(frame, in->n_range, in->n_doppler, fmts);
    if (st != PFT_OK || frame->format != PFT_PIX_F32) {
        return st;
    }
    /* pft_frame_check_finite without the early exit (one branch-free pass per row) */
    for (uint32_t y = 0; y < frame->height; ++y) {
        const uint8_t *row = pft_frame_row(frame, y);
        uint32_t bad = 0u;
        for (uint32_t x = 0; x < frame->width; ++x) {
            uint32_t bits;
            memcpy(&bits, row + 4u * x, 4u); /* integer test: no float ops (q16 builds) */
            /* all ones or 0: a vector compare's own lanes, no masking to 0/1 */
            bad |= (bits & 0x7F800000u) == 0x7F800000u ? 0xFFFFFFFFu : 0u;
        }
        if (bad != 0u) {
            return PFT_ERR_FORMAT;
        }
    }
    return PFT_OK;
}

/* A finite F32 pixel as a real clamped to +-32767, as pft_from_f32 followed by the clamp of
 * pft_frame_row_to_real (q16: the same IEEE decoding, inlined; float: the value). */
static inline pft_real_t f32_in_(const uint8_t *px)
{
#ifdef PFT_NUMERIC_Q16
    uint32_t bits;
    memcpy(&bits, px, 4u);
    const uint32_t ex = (bits >> 23) & 0xFFu;
    const int32_t s = (int32_t)ex - 134; /* value = mant 2^(ex - 150), Q16: mant 2^(ex - 134) */
    const uint32_t mant = (bits & 0x7FFFFFu) | 0x800000u;
    uint32_t mag; /* magnitude clamped to 32767 in Q16.16 (2147418112) */
    if (ex == 0u || s < -25) {
        mag = 0u; /* zero, subnormal or below half an LSB */
    } else if (s < 0) {
        mag = (mant + (1u << (-s - 1))) >> (-s); /* nearest, ties away */
    } else if (s <= 7 && ((uint64_t)mant << s) <= 2147418112u) {
        mag = mant << s;
    } else {
        mag = 2147418112u;
    }
    return (bits >> 31) != 0u ? -(pft_real_t)mag : (pft_real_t)mag;
#else
    float v;
    memcpy(&v, px, 4u);
    return pft_clamp(v, PFT_C(-32767.0), PFT_C(32767.0));
#endif
}

void pft_pte_frame_row_(const pft_pte_input_t *in, const pft_frame_t *frame, uint32_t d,
                        pft_real_t *z)
{
    if (frame->format == PFT_PIX_F32) {
        const uint8_t *row = pft_frame_row(frame, d);
        for (uint32_t u = 0; u < in->n_range; ++u) {
            z[u] = f32_in_(row + 4u * u);
        }
        return;
    }
    pft_frame_row_to_real(frame, d, in->n_range, in->pixel_gain, in->pixel_offset, z);
}

/* Fixed-noise input of row d straight into zeta (F32 pixels: one pass, the same values as
 * pft_pte_frame_row_ followed by pft_pte_norm_row_). */
static void fixed_row_(const pft_pte_input_t *in, const pft_frame_t *frame, uint32_t d,
                       pft_real_t *out)
{
    const pft_real_t inv = pft_recip(in->noise_sigma);
    const pft_real_t clip = in->zeta_clip;
    const uint8_t *row = pft_frame_row(frame, d);
#ifdef PFT_NUMERIC_Q16
    /* The same values as f32_in_, pft_mul and the clamp to +-zeta_clip, on the magnitude
     * (inv > 0; pft_mul rounds half away from zero, so the sign can be applied last): a pixel
     * below 128 in magnitude (exponent below 134, the common case) is
     * (mant + 2^(sh-1)) >> sh with sh = 134 - exponent, which also gives f32_in_'s 0 for
     * sh >= 25 (mant < 2^24), so sh is clamped to 31 instead of tested (below: sh - 1 clamped
     * to 30); larger pixels take f32_in_ itself. */
    const int64_t hi = clip;
    for (uint32_t u = 0; u < in->n_range; ++u) {
        uint32_t bits;
        memcpy(&bits, row + 4u * u, 4u);
        /* sh - 1 = 133 - exponent, as an unsigned difference: above 133 (a wrapped one) for
         * the pixels of 128 or more */
        const uint32_t sh1 = 133u - ((bits >> 23) & 0xFFu);
        int64_t mag;
        if (sh1 <= 30u) {
            /* (mant + 2^(sh-1)) >> sh as ((mant >> (sh - 1)) + 1) >> 1 (sh >= 1): the same
             * floor((mant / 2^(sh-1) + 1) / 2), the dropped low bits never carrying into it */
            const uint32_t mant = (bits & 0x7FFFFFu) | 0x800000u;
            mag = (int64_t)(((mant >> sh1) + 1u) >> 1);
        } else if (sh1 <= 133u) {
            mag = 0; /* sh - 1 clamped to 30: ((mant >> 30) + 1) >> 1 = 0 (mant < 2^24) */
        } else {
            const pft_real_t v = f32_in_(row + 4u * u);
            mag = v < 0 ? -(int64_t)v : (int64_t)v;
        }
        int64_t r = (mag * inv + 32768) >> 16;
        r = r > hi ? hi : r;
        out[u] = (pft_real_t)((bits >> 31) != 0u ? -r : r);
    }
#else
    /* f32_in_'s clamp to +-32767 folded into the clip: v inv is non-decreasing in v (inv > 0,
     * rounded products are monotone), so clamp(clamp(v, +-32767) inv, +-clip) =
     * clamp(v inv, +-hi) with hi = min(clip, 32767 inv) for every finite v of a checked frame
     * (v inv may round to +-inf when inv > 1: clamped alike); the same sign of zero because
     * hi > 0. The clamp as a max then a min, a form the compiler vectorises. */
    const pft_real_t hi = pft_min(clip, pft_mul(PFT_C(32767.0), inv));
    const pft_real_t nhi = pft_neg(hi);
    for (uint32_t u = 0; u < in->n_range; ++u) {
        float x;
        memcpy(&x, row + 4u * u, 4u);
        pft_real_t v = pft_mul(x, inv);
        v = v > nhi ? v : nhi;
        out[u] = v < hi ? v : hi;
    }
#endif
}

#ifdef PFT_NUMERIC_Q16
/* fixed_row_'s clamp: zeta_clip, or what a pixel clamped to +-32767 (f32_in_) becomes when
 * that is less (the same rounded product as fixed_row_) */
static int64_t f32_hi_(const pft_pte_input_t *in)
{
    const int64_t inv = pft_recip(in->noise_sigma);
    const int64_t sat = ((int64_t)2147418112 * inv + 32768) >> 16;
    return (int64_t)in->zeta_clip < sat ? (int64_t)in->zeta_clip : sat;
}

void pft_pte_f32_table_(const pft_pte_input_t *in, uint32_t tab[256])
{
    /* A finite pixel of exponent ex (1..254) is mant 2^(ex - 150) with 2^23 <= mant < 2^24,
     * so its zeta in Q16.16 is mant inv 2^(ex - 150), inv = pft_recip(noise_sigma) in Q16.16:
     * (mant T + 2^27) >> 28 with T = inv 2^(ex - 122) (exact for ex >= 122, rounded below).
     * From the first exponent whose smallest pixel, inv 2^(ex - 127), reaches the clamp hi,
     * T = 32 hi, which gives at least hi for every mantissa (and every larger exponent is
     * clamped too). Every other T is below 32 hi < 2^31 (hi <= zeta_clip <= 1000), and
     * mant T < 2^55. Exponent 0 (zero, subnormals) and 255 (refused by the frame check): 0. */
    const int64_t inv = pft_recip(in->noise_sigma);
    const int64_t hi = f32_hi_(in);
    bool cap = false;
    for (uint32_t ex = 0; ex < 256u; ++ex) {
        int64_t t = 0;
        if (ex >= 1u && ex <= 254u && inv > 0) {
            if (!cap) {
                if (ex >= 127u) {
                    cap = ex - 127u >= 31u || (inv << (ex - 127u)) >= hi;
                } else {
                    cap = 127u - ex < 32u && inv >= (hi << (127u - ex));
                }
            }
            if (cap) {
                t = 32 * hi;
            } else if (ex >= 122u) {
                t = inv << (ex - 122u);
            } else if (122u - ex < 40u) {
                const uint32_t sh = 122u - ex;
                t = (inv + ((int64_t)1 << (sh - 1u))) >> sh;
            } else {
                t = 0; /* below 2^-40 of inv: rounds to 0 */
            }
        }
        tab[ex] = (uint32_t)t;
    }
}

/* One pixel of table_row_: zeta = (mant T[ex] + 2^27) >> 28, clamped to hi, with the sign. */
static inline pft_real_t table_px_(const uint8_t *px, const uint32_t *tab, uint64_t hi)
{
    uint32_t bits;
    memcpy(&bits, px, 4u);
    const uint32_t m32 = (bits & 0x7FFFFFu) | 0x800000u;
    const uint64_t mant = m32;
    uint64_t r = (mant * tab[(bits >> 23) & 0xFFu] + ((uint64_t)1 << 27)) >> 28;
    r = r > hi ? hi : r;
    const int32_t s = -(int32_t)(bits >> 31); /* 0 or -1 */
    return ((pft_real_t)r ^ s) - s;
}

/* Fixed-noise F32 row by one product per pixel (PTE-TBD, q16): the magnitude
 * (mant T[ex] + 2^27) >> 28 rounded once (half up), clamped to hi, then the pixel's sign.
 * It is fixed_row_'s value whenever inv 2^(ex - 122) is an integer for every exponent that
 * rounds to a nonzero zeta (e.g. noise_sigma = 1: inv = 2^16, every exponent >= 106), else
 * within 1 LSB of it (fixed_row_ rounds twice). docs/fixed_point.md, "PTE-TBD F32 input row
 * by one product". */
static void table_row_(const pft_pte_input_t *in, const pft_frame_t *frame, uint32_t d,
                       const uint32_t *tab, pft_real_t *out)
{
    const uint64_t hi = (uint64_t)f32_hi_(in);
    const uint8_t *row = pft_frame_row(frame, d);
    const uint32_t n = in->n_range;
    uint32_t u = 0u;
    /* two pixels per pass (the same per-pixel expression; half the loop's own instructions) */
    for (; u + 2u <= n; u += 2u) {
        out[u] = table_px_(row + 4u * u, tab, hi);
        out[u + 1u] = table_px_(row + 4u * u + 4u, tab, hi);
    }
    if (u < n) {
        out[u] = table_px_(row + 4u * u, tab, hi);
    }
}
#endif

/* |z| / ref: one CFAR term (the same expression when a cell enters and leaves a window, so
 * the q16 running sums are exact). */
static pft_real_t cfar_term_(const pft_real_t *z, int32_t i, pft_real_t inv_ref)
{
    return pft_mul(pft_abs(z[i]), inv_ref);
}

void pft_pte_norm_row_(const pft_pte_input_t *in, const pft_real_t *z, pft_real_t *out)
{
    int32_t n = (int32_t)in->n_range;
    pft_real_t clip = in->zeta_clip;
    if (in->noise == PFT_PTE_NOISE_FIXED) {
        pft_real_t inv = pft_recip(in->noise_sigma);
        for (int32_t u = 0; u < n; ++u) {
            out[u] = pft_clamp(pft_mul(z[u], inv), pft_neg(clip), clip);
        }
        return;
    }
    /* CA-CFAR on |z|: left window [u-G-R, u-G-1], right window [u+G+1, u+G+R], clipped. */
    int32_t R = (int32_t)in->cfar_ref;
    int32_t G = (int32_t)in->cfar_guard;
    pft_real_t inv_ref = pft_ratio(1, R);
    pft_real_t lsum = PFT_C(0.0);
    pft_real_t rsum = PFT_C(0.0);
    const pft_real_t k_gauss = PFT_C(1.2533141373155); /* sqrt(pi/2): sigma from mean |z| */
    for (int32_t i = G + 1; i <= G + R && i < n; ++i) {
        rsum = pft_add(rsum, cfar_term_(z, i, inv_ref));
    }
    for (int32_t u = 0; u < n; ++u) {
        int32_t llo = u - G - R < 0 ? 0 : u - G - R;
        int32_t lhi = u - G - 1;
        int32_t rlo = u + G + 1;
        int32_t rhi = u + G + R > n - 1 ? n - 1 : u + G + R;
        int32_t cnt = (lhi >= llo ? lhi - llo + 1 : 0) + (rhi >= rlo ? rhi - rlo + 1 : 0);
        pft_real_t sigma = in->noise_sigma;
        if (cnt > 0) {
            pft_real_t s = pft_max(pft_add(lsum, rsum), PFT_C(0.0));
            pft_real_t mean = pft_mul(s, pft_ratio(R, cnt));
            sigma = pft_max(pft_mul(mean, k_gauss), in->noise_sigma);
        }
        out[u] = pft_clamp(pft_div(z[u], sigma), pft_neg(clip), clip);
        /* slide to u + 1: subtract first, then add (partial sums stay <= a full window) */
        if (u - G - R >= 0) {
            lsum = pft_sub(lsum, cfar_term_(z, u - G - R, inv_ref));
        }
        if (u - G >= 0) {
            lsum = pft_add(lsum, cfar_term_(z, u - G, inv_ref));
        }
        if (u + G + 1 < n) {
            rsum = pft_sub(rsum, cfar_term_(z, u + G + 1, inv_ref));
        }
        if (u + G + R + 1 < n) {
            rsum = pft_add(rsum, cfar_term_(z, u + G + R + 1, inv_ref));
        }
    }
}

pft_status_t pft_pte_normalize(const pft_pte_input_t *in, const pft_frame_t *frame,
                               pft_real_t *zeta, pft_real_t *scratch)
{
    if (in == NULL || zeta == NULL) {
        return PFT_ERR_INVAL;
    }
    if (pft_pte_input_bad_(in) != NULL) {
        return PFT_ERR_CONFIG;
    }
    if (in->noise == PFT_PTE_NOISE_CFAR && scratch == NULL) {
        return PFT_ERR_INVAL;
    }
    pft_status_t st = pft_pte_frame_check_(in, frame);
    if (st != PFT_OK) {
        return st;
    }
    for (uint32_t d = 0; d < in->n_doppler; ++d) {
        pft_real_t *out = zeta + (size_t)d * in->n_range;
        if (in->noise == PFT_PTE_NOISE_FIXED && frame->format == PFT_PIX_F32) {
            fixed_row_(in, frame, d, out);
        } else if (in->noise == PFT_PTE_NOISE_CFAR) {
            pft_pte_frame_row_(in, frame, d, scratch);
            pft_pte_norm_row_(in, scratch, out);
        } else {
            pft_pte_frame_row_(in, frame, d, out);
            pft_pte_norm_row_(in, out, out); /* fixed mode works element-wise in place */
        }
    }
    return PFT_OK;
}

pft_status_t pft_pte_normalize_real(const pft_pte_input_t *in, const pft_real_t *z,
                                    pft_real_t *zeta)
{
    if (in == NULL || z == NULL || zeta == NULL || z == zeta) {
        return PFT_ERR_INVAL;
    }
    if (pft_pte_input_bad_(in) != NULL) {
        return PFT_ERR_CONFIG;
    }
    for (uint32_t d = 0; d < in->n_doppler; ++d) {
        pft_pte_norm_row_(in, z + (size_t)d * in->n_range, zeta + (size_t)d * in->n_range);
    }
    return PFT_OK;
}

/* --------------------------------------------------------------------------------- ring */

void pft_pte_ring_setup_(pft_pte_ring_t *r, pft_real_t *buf, uint16_t len, uint32_t cells)
{
    r->buf = buf;
    r->len = len;
    r->cells = cells;
    r->count = 0u;
    r->head = (uint16_t)(len - 1u);
}

pft_real_t *pft_pte_ring_next_(const pft_pte_ring_t *r)
{
    uint32_t slot = ((uint32_t)r->head + 1u) % r->len;
    return r->buf + (size_t)slot * r->cells;
}

void pft_pte_ring_commit_(pft_pte_ring_t *r)
{
    r->head = (uint16_t)(((uint32_t)r->head + 1u) % r->len);
    if (r->count < r->len) {
        r->count++;
    }
}

const pft_real_t *pft_pte_ring_get_(const pft_pte_ring_t *r, uint32_t back)
{
    uint32_t slot = ((uint32_t)r->head + r->len - (back % r->len)) % r->len;
    return r->buf + (size_t)slot * r->cells;
}

/* pft_pte_push_ and pft_pte_push_f32t_: f32t NULL, a constant in the first, so DP-TBD and the
 * DBT run the code they ran before the one-product row */
static inline pft_status_t push_(const pft_pte_input_t *in, pft_pte_ring_t *ring,
                                 pft_real_t *row, const pft_frame_t *frame, const pft_real_t *z,
                                 const uint32_t *f32t)
{
    /* a frame was checked by the caller's pft_pte_seq_check_ (the same frame and input stage) */
    if (frame == NULL) {
        if (z == NULL) {
            return PFT_ERR_INVAL;
        }
        /* float build: refuse NaN/Inf values (the comparison is false for them); q16: no-op */
        uint32_t cells = (uint32_t)in->n_range * in->n_doppler;
        for (uint32_t i = 0; i < cells; ++i) {
            if (!(z[i] >= PFT_REAL_MIN && z[i] <= PFT_REAL_MAX)) {
                return PFT_ERR_FORMAT;
            }
        }
    }
    pft_real_t *dst = pft_pte_ring_next_(ring);
    for (uint32_t d = 0; d < in->n_doppler; ++d) {
        pft_real_t *out = dst + (size_t)d * in->n_range;
        if (frame != NULL && frame->format == PFT_PIX_F32 && in->noise == PFT_PTE_NOISE_FIXED) {
#ifdef PFT_NUMERIC_Q16
            if (f32t != NULL) {
                table_row_(in, frame, d, f32t, out);
                continue;
            }
#else
            (void)f32t; /* q16 only */
#endif
            fixed_row_(in, frame, d, out);
        } else if (frame != NULL) {
            pft_pte_frame_row_(in, frame, d, row);
            pft_pte_norm_row_(in, row, out);
        } else {
            pft_pte_norm_row_(in, z + (size_t)d * in->n_range, out);
        }
    }
    pft_pte_ring_commit_(ring);
    return PFT_OK;
}

pft_status_t pft_pte_push_(const pft_pte_input_t *in, pft_pte_ring_t *ring, pft_real_t *row,
                           const pft_frame_t *frame, const pft_real_t *z)
{
    return push_(in, ring, row, frame, z, NULL);
}

#ifdef PFT_NUMERIC_Q16
pft_status_t pft_pte_push_f32t_(const pft_pte_input_t *in, pft_pte_ring_t *ring,
                                pft_real_t *row, const pft_frame_t *frame, const pft_real_t *z,
                                const uint32_t *f32t)
{
    return push_(in, ring, row, frame, z, f32t);
}
#endif
