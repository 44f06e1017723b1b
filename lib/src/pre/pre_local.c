/* Spatial local background with a guard window (docs/algorithms.md 9.2): the mean of the
 * unmasked pixels of the (2 ro + 1)^2 window minus those of the (2 rg + 1)^2 guard window,
 * both clipped to the image, from column sums slid down the rows and window sums slid along
 * each row (O(1) per pixel). Pixels are packed as raw | 1 << 24 (0 when masked), so one
 * 32-bit sum carries the count in its top byte and the sum of raw values below (at most 225
 * pixels of 16 bits: 14.7e6 < 2^24). */
#include <string.h>

#include "pre_int.h"

/* col[x] += add[x] - sub[x] (either may be NULL). */
static void col_slide_(uint32_t *col, const uint32_t *add, const uint32_t *sub, uint32_t w)
{
    if (add != NULL && sub != NULL) {
        for (uint32_t x = 0; x < w; ++x) {
            col[x] += add[x] - sub[x];
        }
    } else if (add != NULL) {
        for (uint32_t x = 0; x < w; ++x) {
            col[x] += add[x];
        }
    } else if (sub != NULL) {
        for (uint32_t x = 0; x < w; ++x) {
            col[x] -= sub[x];
        }
    } else {
        /* neither row: the column sums stay */
    }
}

/* Packs row y of f into out (raw | PFT_PRE_ONE_, 0 when masked) and counts its masked pixels. */
static void pack_row_(const pft_pre_cls_t *c, const pft_frame_t *f, uint32_t y, uint32_t *out,
                      pft_pre_acc_t *acc)
{
    const uint8_t *row = pft_frame_row(f, y);
    const uint32_t w = f->width, lo = c->lo, span = c->span, mask = c->mask;
    uint32_t nmask = 0u;
    if (c->u8) {
        for (uint32_t x = 0; x < w; ++x) {
            const uint32_t v = row[x];
            const bool ok = v - lo < span;
            out[x] = ok ? v | PFT_PRE_ONE_ : 0u;
            nmask += ok ? 0u : 1u;
        }
    } else {
        for (uint32_t x = 0; x < w; ++x) {
            uint16_t r16;
            memcpy(&r16, row + 2u * x, 2u);
            const uint32_t v = (uint32_t)r16 & mask;
            const bool ok = v - lo < span;
            out[x] = ok ? v | PFT_PRE_ONE_ : 0u;
            nmask += ok ? 0u : 1u;
        }
    }
    if (c->map != NULL) {
        for (uint32_t x = 0; x < w; ++x) {
            if (out[x] != 0u && pft_pre_bad_(c, x, y)) {
                out[x] = 0u;
                nmask++;
            }
        }
    }
    for (uint32_t x = 0; nmask > 0u && x < w; ++x) {
        if (out[x] == 0u) {
            pft_pre_count_masked_(c, pft_pre_raw_(row, x, c), acc);
            nmask--;
        }
    }
}

void pft_pre_local_pass_(pft_pre_t *p, const pft_frame_t *f, pft_pre_acc_t *acc)
{
    const uint32_t w = p->cfg.width, h = p->cfg.height, t = p->cfg.tile;
    const uint32_t ro = p->cfg.local_outer, rg = p->cfg.local_guard, nring = 2u * ro + 2u;
    const uint32_t rs = p->rs, pad = ro + 1u;
    /* pixels of a window wholly inside the image: divided by a reciprocal, exact for sums
     * below 2^32 / nfull (here below 2^23: 225 pixels of 15 bits, or of 16 bits with rs 0) */
    const uint32_t nfull = (2u * ro + 1u) * (2u * ro + 1u) - (2u * rg + 1u) * (2u * rg + 1u);
    const uint64_t rfull = (((uint64_t)1 << 32) + nfull - 1u) / nfull;
    pft_pre_cls_t cls;
    pft_pre_cls_init_(p, &cls);
    /* column sums, padded by ro + 1 zero columns each side: colo[x + pad] */
    uint32_t *colo = p->colo, *colg = p->colg;
    memset(colo, 0, ((size_t)w + 2u * pad) * 4u);
    memset(colg, 0, ((size_t)w + 2u * pad) * 4u);
    uint32_t *co = colo + pad, *cg = colg + pad;
#define RING_(r) (p->ring + (size_t)((r) % nring) * w)
    for (uint32_t r = 0; r <= ro && r < h; ++r) {
        pack_row_(&cls, f, r, RING_(r), acc);
        col_slide_(co, RING_(r), NULL, w);
        if (r <= rg) {
            col_slide_(cg, RING_(r), NULL, w);
        }
    }
    for (uint32_t y = 0; y < h; ++y) {
        if (y > 0u) {
            const bool in_o = y + ro < h, out_o = y >= ro + 1u;
            const bool in_g = y + rg < h, out_g = y >= rg + 1u;
            if (in_o) {
                pack_row_(&cls, f, y + ro, RING_(y + ro), acc);
            }
            col_slide_(co, in_o ? RING_(y + ro) : NULL, out_o ? RING_(y - ro - 1u) : NULL, w);
            col_slide_(cg, in_g ? RING_(y + rg) : NULL, out_g ? RING_(y - rg - 1u) : NULL, w);
        }
        const uint32_t *zrow = RING_(y);
        int16_t *rrow = p->res + (size_t)y * w;
        const int32_t *cn = p->colnow;
        int32_t *bl = p->line;
        const uint32_t j = y / t;
        /* background of the row into bl (R units; -1: no unmasked pixel in the ring) */
        uint32_t so = 0u, sg = 0u; /* window sums at x = -1 */
        for (uint32_t i = 0; i < 2u * ro + 1u; ++i) {
            so += colo[i]; /* colo[i] is column i - pad */
        }
        for (uint32_t i = 0; i < 2u * rg + 1u; ++i) {
            sg += colg[pad - 1u - rg + i];
        }
        const uint32_t *oa = co + ro, *os = co - ro - 1, *ga = cg + rg, *gs = cg - rg - 1;
        for (uint32_t x = 0; x < w; ++x) {
            so += oa[x] - os[x];
            sg += ga[x] - gs[x];
            const uint32_t d = so - sg, n = d >> 24;
            const uint32_t a = ((d & PFT_PRE_VAL_) << rs) + n / 2u;
            bl[x] = n == nfull ? (int32_t)((a * rfull) >> 32) : (n == 0u ? -1 : (int32_t)(a / n));
        }
        for (uint32_t x = 0; x < w; ++x) { /* vectorisable: residual */
            const uint32_t z = zrow[x];
            const int32_t b = bl[x];
            const int32_t r = pft_pre_rclamp_((int32_t)((z & PFT_PRE_VAL_) << rs) - b - cn[x]);
            rrow[x] = (int16_t)(z == 0u || b < 0 ? PFT_RES16_MASKED : r);
        }
        /* a window clipped by the border is off-centre: on a gradient its mean is biased (by
         * the gradient times the shift of its centroid), so the border band of width ro is
         * masked */
        const uint32_t band = ro < w / 2u ? ro : w / 2u;
        if (y < ro || y + ro >= h) {
            for (uint32_t x = 0; x < w; ++x) {
                rrow[x] = PFT_RES16_MASKED;
            }
        } else {
            for (uint32_t x = 0; x < band; ++x) {
                rrow[x] = PFT_RES16_MASKED;
                rrow[w - 1u - x] = PFT_RES16_MASKED;
            }
        }
        acc->n_masked += pft_pre_row_out_(p, y);
        if (y + 1u == h || (y + 1u) % t == 0u) {
            pft_pre_tilerow_done_(p, j);
        }
    }
#undef RING_
}
