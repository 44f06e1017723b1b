/*
 * Kernel-weighted 30-bin RGB histogram and Bhattacharyya coefficient (ALGORITHMS.md 4.3,
 * eq. 21), in integer arithmetic in both builds.
 */
#include <string.h>

#include "tsa_int.h"

pft_status_t pft_tsa_hist(const pft_frame_t *frame, const pft_tsa_kernel_t *k, int32_t cx,
                          int32_t cy, pft_tsa_hist_t *h)
{
    uint32_t o0, o1, o2, bpp, total = 0u;
    uint32_t bin[PFT_TSA_BINS];
    pft_status_t st;
    const int32_t W = frame != NULL ? (int32_t)frame->width : 0;
    const int32_t H = frame != NULL ? (int32_t)frame->height : 0;

    if (k == NULL || h == NULL || (k->n > 0u && k->pix == NULL)) {
        return PFT_ERR_INVAL;
    }
    st = pft_frame_check(frame, 0u, 0u, TSA_FMT_MASK_);
    if (st != PFT_OK) {
        return st;
    }
    tsa_channels_(frame->format, &o0, &o1, &o2, &bpp);
    memset(bin, 0, sizeof bin);
    if (cx + k->x0 >= 0 && cy + k->y0 >= 0 && cx + k->x1 < W && cy + k->y1 < H) {
        /* fast path: the whole kernel lies inside the frame */
        for (uint32_t i = 0; i < k->n; ++i) {
            const pft_tsa_kpix_t *kp = &k->pix[i];
            const uint8_t *p = pft_frame_row(frame, (uint32_t)(cy + kp->dy)) +
                               (uint32_t)(cx + kp->dx) * bpp;
            bin[((uint32_t)p[o0] * 10u) >> 8] += kp->w;
            bin[10u + (((uint32_t)p[o1] * 10u) >> 8)] += kp->w;
            bin[20u + (((uint32_t)p[o2] * 10u) >> 8)] += kp->w;
            total += kp->w;
        }
    } else {
        for (uint32_t i = 0; i < k->n; ++i) {
            const pft_tsa_kpix_t *kp = &k->pix[i];
            const int32_t x = cx + kp->dx, y = cy + kp->dy;
            const uint8_t *p;
            if (x < 0 || y < 0 || x >= W || y >= H) {
                continue;
            }
            p = pft_frame_row(frame, (uint32_t)y) + (uint32_t)x * bpp;
            bin[((uint32_t)p[o0] * 10u) >> 8] += kp->w;
            bin[10u + (((uint32_t)p[o1] * 10u) >> 8)] += kp->w;
            bin[20u + (((uint32_t)p[o2] * 10u) >> 8)] += kp->w;
            total += kp->w;
        }
    }
    memcpy(h->bin, bin, sizeof bin);
    h->total = total;
    return PFT_OK;
}

pft_real_t pft_tsa_bhattacharyya(const pft_tsa_hist_t *p, const pft_tsa_hist_t *q)
{
    uint64_t num = 0u, den;
    if (p == NULL || q == NULL || p->total == 0u || q->total == 0u) {
        return 0;
    }
    for (uint32_t u = 0; u < PFT_TSA_BINS; ++u) {
        if (p->bin[u] != 0u && q->bin[u] != 0u) {
            num += tsa_isqrt64_(((uint64_t)p->bin[u] * q->bin[u]) << 8);
        }
    }
    den = 3u * (uint64_t)tsa_isqrt64_(((uint64_t)p->total * q->total) << 8);
    if (den == 0u) {
        return 0;
    }
    if (num >= den) {
        return PFT_REAL_ONE;
    }
#ifdef PFT_NUMERIC_Q16
    return (pft_real_t)(((num << 16) + den / 2u) / den);
#else
    return (float)num / (float)den;
#endif
}
