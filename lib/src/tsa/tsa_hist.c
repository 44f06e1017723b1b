/*
 * Kernel-weighted 30-bin RGB histogram and Bhattacharyya coefficient (docs/algorithms.md 4.3,
 * eq. 21), in integer arithmetic in both builds.
 */
#include <string.h>

#include "../core/acc_int.h"
#include "tsa_int.h"

/* Adds the Q4 weight w of the pixel at p to its bin in each channel ((v * 10) >> 8). */
static inline void add_pixel_(uint32_t *bin, const uint8_t *p, const uint32_t off[3], uint32_t w)
{
    bin[((uint32_t)p[off[0]] * 10u) >> 8] += w;
    bin[10u + (((uint32_t)p[off[1]] * 10u) >> 8)] += w;
    bin[20u + (((uint32_t)p[off[2]] * 10u) >> 8)] += w;
}

pft_status_t pft_tsa_hist(const pft_frame_t *frame, const pft_tsa_kernel_t *k, int32_t cx,
                          int32_t cy, pft_tsa_hist_t *h)
{
    if (k == NULL || h == NULL || (k->n > 0u && k->pix == NULL)) {
        return PFT_ERR_INVAL;
    }
    pft_status_t st = pft_frame_check(frame, 0u, 0u, PFT_TSA_FMT_MASK_);
    if (st != PFT_OK) {
        return st;
    }
    const int32_t W = (int32_t)frame->width;
    const int32_t H = (int32_t)frame->height;
    uint32_t off[3];
    uint32_t bpp;
    pft_tsa_channels_(frame->format, &off[0], &off[1], &off[2], &bpp);
    uint32_t bin[PFT_TSA_BINS];
    uint32_t total = 0u;
    memset(bin, 0, sizeof(bin));
    if (cx + k->x0 >= 0 && cy + k->y0 >= 0 && cx + k->x1 < W && cy + k->y1 < H) {
        /* fast path: the whole kernel lies inside the frame */
        for (uint32_t i = 0; i < k->n; ++i) {
            const pft_tsa_kpix_t *kp = &k->pix[i];
            const uint8_t *p = pft_frame_row(frame, (uint32_t)(cy + kp->dy)) +
                               (uint32_t)(cx + kp->dx) * bpp;
            add_pixel_(bin, p, off, kp->w);
            total += kp->w;
        }
    } else {
        for (uint32_t i = 0; i < k->n; ++i) {
            const pft_tsa_kpix_t *kp = &k->pix[i];
            const int32_t x = cx + kp->dx;
            const int32_t y = cy + kp->dy;
            if (x < 0 || y < 0 || x >= W || y >= H) {
                continue;
            }
            add_pixel_(bin, pft_frame_row(frame, (uint32_t)y) + (uint32_t)x * bpp, off, kp->w);
            total += kp->w;
        }
    }
    memcpy(h->bin, bin, sizeof(bin));
    h->total = total;
    return PFT_OK;
}

pft_real_t pft_tsa_bhattacharyya(const pft_tsa_hist_t *p, const pft_tsa_hist_t *q)
{
    if (p == NULL || q == NULL || p->total == 0u || q->total == 0u) {
        return PFT_C(0.0);
    }
    uint64_t num = 0u;
    for (uint32_t u = 0; u < PFT_TSA_BINS; ++u) {
        if (p->bin[u] != 0u && q->bin[u] != 0u) {
            num += pft_tsa_isqrt64_(((uint64_t)p->bin[u] * q->bin[u]) << 8);
        }
    }
    const uint64_t den = 3u * (uint64_t)pft_tsa_isqrt64_(((uint64_t)p->total * q->total) << 8);
    if (den == 0u) {
        return PFT_C(0.0);
    }
    if (num >= den) {
        return PFT_REAL_ONE;
    }
    /* num < den: the quotient in [0, 1), rounded to nearest in q16 */
    return pft_wratio_((pft_wacc_t)num, (pft_wacc_t)den);
}
