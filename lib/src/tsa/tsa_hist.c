/*
 * Kernel-weighted 30-bin RGB histogram and Bhattacharyya coefficient (docs/algorithms.md 4.3,
 * eq. 21), in integer arithmetic in both builds.
 */
#include <string.h>
#ifndef PFT_NUMERIC_Q16
#include <math.h>
#endif

#include "../core/acc_int.h"
#include "tsa_int.h"

/* Adds the Q4 weight w of the pixel at p to its bin in each channel ((v * 10) >> 8). */
static inline void add_pixel_(uint32_t *bin, const uint8_t *p, const uint32_t off[3], uint32_t w)
{
    bin[((uint32_t)p[off[0]] * 10u) >> 8] += w;
    bin[10u + (((uint32_t)p[off[1]] * 10u) >> 8)] += w;
    bin[20u + (((uint32_t)p[off[2]] * 10u) >> 8)] += w;
}

/* The channel value v under the gain g / 256, rounded and clamped to 255 (v itself for g =
 * 256). */
static inline uint32_t gained_(uint32_t v, uint32_t g)
{
    const uint32_t u = (v * g + 128u) >> 8;
    return u > 255u ? 255u : u;
}

/* add_pixel_ of the pixel's values under the gain g / 256. */
static inline void add_pixel_gain_(uint32_t *bin, const uint8_t *p, const uint32_t off[3],
                                   uint32_t w, uint32_t g)
{
    bin[(gained_((uint32_t)p[off[0]], g) * 10u) >> 8] += w;
    bin[10u + ((gained_((uint32_t)p[off[1]], g) * 10u) >> 8)] += w;
    bin[20u + ((gained_((uint32_t)p[off[2]], g) * 10u) >> 8)] += w;
}

/* The channel offsets and bytes per pixel of the frame's format, and h emptied: the start of
 * the two histograms that skip pixels outside the frame. */
static void hist_start_(const pft_frame_t *frame, uint32_t off[3], uint32_t *bpp,
                        pft_tsa_hist_t *h)
{
    pft_tsa_channels_(frame->format, &off[0], &off[1], &off[2], bpp);
    memset(h->bin, 0, sizeof(h->bin));
    h->total = 0u;
}

void pft_tsa_hist_gain_(const pft_frame_t *frame, const pft_tsa_kernel_t *k, int32_t cx,
                        int32_t cy, uint32_t gain, pft_tsa_hist_t *h)
{
    const int32_t W = (int32_t)frame->width;
    const int32_t H = (int32_t)frame->height;
    uint32_t off[3];
    uint32_t bpp;
    hist_start_(frame, off, &bpp, h);
    for (uint32_t i = 0; i < k->n; ++i) {
        const pft_tsa_kpix_t *kp = &k->pix[i];
        const int32_t x = cx + kp->dx;
        const int32_t y = cy + kp->dy;
        if (x < 0 || y < 0 || x >= W || y >= H) {
            continue;
        }
        add_pixel_gain_(h->bin, pft_frame_row(frame, (uint32_t)y) + (uint32_t)x * bpp, off,
                        kp->w, gain);
        h->total += kp->w;
    }
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
    if (cx + k->x0 < 0 || cy + k->y0 < 0 || cx + k->x1 >= (int32_t)frame->width ||
        cy + k->y1 >= (int32_t)frame->height) {
        /* the kernel is clipped by the frame: the gain loop, which skips the pixels outside,
         * at gain 256 / 256 (every value as it is) */
        pft_tsa_hist_gain_(frame, k, cx, cy, 256u, h);
        return PFT_OK;
    }
    /* fast path: the whole kernel lies inside the frame */
    uint32_t off[3];
    uint32_t bpp;
    pft_tsa_channels_(frame->format, &off[0], &off[1], &off[2], &bpp);
    uint32_t bin[PFT_TSA_BINS];
    uint32_t total = 0u;
    memset(bin, 0, sizeof(bin));
    for (uint32_t i = 0; i < k->n; ++i) {
        const pft_tsa_kpix_t *kp = &k->pix[i];
        const uint8_t *p = pft_frame_row(frame, (uint32_t)(cy + kp->dy)) +
                           (uint32_t)(cx + kp->dx) * bpp;
        add_pixel_(bin, p, off, kp->w);
        total += kp->w;
    }
    memcpy(h->bin, bin, sizeof(bin));
    h->total = total;
    return PFT_OK;
}

void pft_tsa_ring_hist_(const pft_frame_t *frame, const pft_tsa_box_t_ *in, int32_t mx, int32_t my,
                        uint32_t gain, pft_tsa_hist_t *h)
{
    const int32_t W = (int32_t)frame->width;
    const int32_t H = (int32_t)frame->height;
    uint32_t off[3];
    uint32_t bpp;
    hist_start_(frame, off, &bpp, h);
    const int32_t x0 = in->x0 - mx < 0 ? 0 : in->x0 - mx;
    const int32_t y0 = in->y0 - my < 0 ? 0 : in->y0 - my;
    const int32_t x1 = in->x1 + mx >= W ? W - 1 : in->x1 + mx;
    const int32_t y1 = in->y1 + my >= H ? H - 1 : in->y1 + my;
    for (int32_t y = y0; y <= y1; ++y) {
        const uint8_t *row = pft_frame_row(frame, (uint32_t)y);
        const bool inner_row = y >= in->y0 && y <= in->y1;
        for (int32_t x = x0; x <= x1; ++x) {
            if (inner_row && x >= in->x0 && x <= in->x1) {
                continue;
            }
            add_pixel_gain_(h->bin, row + (uint32_t)x * bpp, off, 1u, gain);
            ++h->total;
        }
    }
}

void pft_tsa_bg_weight_(pft_tsa_hist_t *q, const pft_tsa_hist_t *o, uint32_t a16)
{
    for (uint32_t c = 0; c < 3u; ++c) {
        uint32_t *qb = &q->bin[10u * c];
        const uint32_t *ob = &o->bin[10u * c];
        uint32_t ostar = 0u;
        for (uint32_t u = 0; u < 10u; ++u) {
            if (ob[u] != 0u && (ostar == 0u || ob[u] < ostar)) {
                ostar = ob[u];
            }
        }
        if (ostar == 0u) {
            continue; /* no background seen in this channel: the bins stay as they are */
        }
        /* v_u q_u with v_u = min(o* / o_u, 1) (1 where o_u = 0), rounded down */
        uint32_t wb[10];
        uint64_t wsum = 0u;
        uint32_t umax = 0u;
        for (uint32_t u = 0; u < 10u; ++u) {
            wb[u] = ob[u] > ostar ? (uint32_t)(((uint64_t)qb[u] * ostar) / ob[u]) : qb[u];
            wsum += wb[u];
            umax = wb[u] > wb[umax] ? u : umax;
        }
        if (wsum == 0u) {
            continue; /* every bin rounded to zero (not reached for a template of this module) */
        }
        /* renormalised to the total (the bins of a channel sum to total, as pft_tsa_rho_hist_
         * assumes); the remainder of the rounding goes to the largest bin */
        uint32_t acc = 0u;
        const uint32_t rest = 65536u - a16;
        for (uint32_t u = 0; u < 10u; ++u) {
            const uint64_t wq = ((uint64_t)wb[u] * q->total) / wsum;
            /* a16 / 65536 of the weighted bin, the rest of the unweighted one */
            qb[u] = (uint32_t)((wq * a16 + (uint64_t)qb[u] * rest) >> 16);
            acc += qb[u];
        }
        qb[umax] += q->total - acc;
    }
}

const uint32_t pft_tsa_sqrt_tab_[193] = {
    32768u, 33023u, 33276u, 33527u, 33776u, 34024u, 34270u, 34514u, 34756u, 34996u, 35235u,
    35472u, 35708u, 35942u, 36175u, 36406u, 36636u, 36864u, 37091u, 37316u, 37540u, 37763u,
    37985u, 38205u, 38424u, 38642u, 38858u, 39073u, 39287u, 39500u, 39712u, 39923u, 40132u,
    40341u, 40548u, 40755u, 40960u, 41164u, 41368u, 41570u, 41771u, 41972u, 42171u, 42369u,
    42567u, 42763u, 42959u, 43154u, 43348u, 43541u, 43733u, 43925u, 44115u, 44305u, 44494u,
    44682u, 44869u, 45056u, 45242u, 45427u, 45611u, 45795u, 45977u, 46160u, 46341u, 46522u,
    46702u, 46881u, 47059u, 47237u, 47415u, 47591u, 47767u, 47942u, 48117u, 48291u, 48465u,
    48637u, 48809u, 48981u, 49152u, 49322u, 49492u, 49661u, 49830u, 49998u, 50166u, 50332u,
    50499u, 50665u, 50830u, 50995u, 51159u, 51323u, 51486u, 51649u, 51811u, 51972u, 52134u,
    52294u, 52454u, 52614u, 52773u, 52932u, 53090u, 53248u, 53405u, 53562u, 53719u, 53874u,
    54030u, 54185u, 54340u, 54494u, 54647u, 54801u, 54954u, 55106u, 55258u, 55410u, 55561u,
    55712u, 55862u, 56012u, 56162u, 56311u, 56459u, 56608u, 56756u, 56903u, 57051u, 57198u,
    57344u, 57490u, 57636u, 57781u, 57926u, 58071u, 58215u, 58359u, 58503u, 58646u, 58789u,
    58931u, 59073u, 59215u, 59357u, 59498u, 59639u, 59779u, 59919u, 60059u, 60199u, 60338u,
    60477u, 60615u, 60753u, 60891u, 61029u, 61166u, 61303u, 61440u, 61576u, 61712u, 61848u,
    61984u, 62119u, 62254u, 62388u, 62523u, 62657u, 62790u, 62924u, 63057u, 63190u, 63323u,
    63455u, 63587u, 63719u, 63850u, 63982u, 64113u, 64243u, 64374u, 64504u, 64634u, 64763u,
    64893u, 65022u, 65151u, 65279u, 65408u, 65536u
};

const uint8_t pft_tsa_norm_tab_[256] = {
    0u, 6u, 6u, 6u, 4u, 4u, 4u, 4u, 4u, 4u, 4u, 4u, 4u, 4u, 4u, 4u, 2u, 2u, 2u, 2u, 2u, 2u, 2u, 2u, 2u, 2u, 2u, 2u, 2u, 2u, 2u, 2u,
    2u, 2u, 2u, 2u, 2u, 2u, 2u, 2u, 2u, 2u, 2u, 2u, 2u, 2u, 2u, 2u, 2u, 2u, 2u, 2u, 2u, 2u, 2u, 2u, 2u, 2u, 2u, 2u, 2u, 2u, 2u, 2u,
    0u, 0u, 0u, 0u, 0u, 0u, 0u, 0u, 0u, 0u, 0u, 0u, 0u, 0u, 0u, 0u, 0u, 0u, 0u, 0u, 0u, 0u, 0u, 0u, 0u, 0u, 0u, 0u, 0u, 0u, 0u, 0u,
    0u, 0u, 0u, 0u, 0u, 0u, 0u, 0u, 0u, 0u, 0u, 0u, 0u, 0u, 0u, 0u, 0u, 0u, 0u, 0u, 0u, 0u, 0u, 0u, 0u, 0u, 0u, 0u, 0u, 0u, 0u, 0u,
    0u, 0u, 0u, 0u, 0u, 0u, 0u, 0u, 0u, 0u, 0u, 0u, 0u, 0u, 0u, 0u, 0u, 0u, 0u, 0u, 0u, 0u, 0u, 0u, 0u, 0u, 0u, 0u, 0u, 0u, 0u, 0u,
    0u, 0u, 0u, 0u, 0u, 0u, 0u, 0u, 0u, 0u, 0u, 0u, 0u, 0u, 0u, 0u, 0u, 0u, 0u, 0u, 0u, 0u, 0u, 0u, 0u, 0u, 0u, 0u, 0u, 0u, 0u, 0u,
    0u, 0u, 0u, 0u, 0u, 0u, 0u, 0u, 0u, 0u, 0u, 0u, 0u, 0u, 0u, 0u, 0u, 0u, 0u, 0u, 0u, 0u, 0u, 0u, 0u, 0u, 0u, 0u, 0u, 0u, 0u, 0u,
    0u, 0u, 0u, 0u, 0u, 0u, 0u, 0u, 0u, 0u, 0u, 0u, 0u, 0u, 0u, 0u, 0u, 0u, 0u, 0u, 0u, 0u, 0u, 0u, 0u, 0u, 0u, 0u, 0u, 0u, 0u, 0u
};

/* The even shift that puts v (> 0) into [2^30, 2^32). */
static uint32_t norm_shift_(uint32_t v) { return pft_tsa_norm_(&v); }

void pft_tsa_hroot_(const pft_tsa_hist_t *h, pft_tsa_hroot_t *r)
{
    memset(r, 0, sizeof(*r));
    if (h->total == 0u) {
        return;
    }
    const uint32_t s = norm_shift_(h->total);
    r->root = pft_tsa_sqrt_approx_(h->total << s);
    for (uint32_t u = 0; u < PFT_TSA_BINS; ++u) {
        /* a bin above the total (not a histogram of this module) is taken as the total */
        const uint32_t b = h->bin[u] < h->total ? h->bin[u] : h->total;
        r->s[u] = pft_tsa_sqrt_approx_(b << s);
        if (r->s[u] != 0u) {
            r->nz[r->n_nz] = (uint8_t)u;
            ++r->n_nz;
        }
    }
}

#ifdef PFT_NUMERIC_Q16
/* num / den for 0 < den: 1 when num >= den, else the quotient (rounded to nearest in q16). */
static pft_real_t ratio_(uint64_t num, uint64_t den)
{
    if (num >= den) {
        return PFT_REAL_ONE;
    }
    return pft_wratio_((pft_wacc_t)num, (pft_wacc_t)den);
}

pft_real_t pft_tsa_rho_hist_(const pft_tsa_hist_t *p, const pft_tsa_hist_t *q,
                             const pft_tsa_hroot_t *qr)
{
    (void)q;
    if (p->total == 0u || qr->root == 0u) {
        return PFT_C(0.0);
    }
    const uint32_t s = norm_shift_(p->total);
    uint64_t num = 0u;
    /* only the template's nonzero bins (qr->nz) can contribute; p's bins are at most its total
     * (a histogram of this module; the public pft_tsa_bhattacharyya clamps its inputs), so
     * bin << s < 2^32 and is nonzero for a nonzero bin */
    for (uint32_t k = 0; k < qr->n_nz; ++k) {
        const uint32_t u = qr->nz[k];
        const uint32_t b = p->bin[u];
        if (b != 0u) {
            num += (uint64_t)pft_tsa_sqrt_approx_nz_(b << s) * qr->s[u];
        }
    }
    return ratio_(num, 3u * (uint64_t)pft_tsa_sqrt_approx_nz_(p->total << s) * qr->root);
}
#else
/* float twin: sum_u sqrt(p_u q_u) / (3 sqrt(P Q)) with the FPU's square root (products of two
 * uint32 sums are exact to 2^-24 relative in float) */
pft_real_t pft_tsa_rho_hist_(const pft_tsa_hist_t *p, const pft_tsa_hist_t *q,
                             const pft_tsa_hroot_t *qr)
{
    (void)qr;
    if (p->total == 0u || q->total == 0u) {
        return 0.0f;
    }
    float num = 0.0f;
    for (uint32_t u = 0; u < PFT_TSA_BINS; ++u) {
        if (p->bin[u] != 0u && q->bin[u] != 0u) {
            num += sqrtf((float)p->bin[u] * (float)q->bin[u]);
        }
    }
    const float r = num / (3.0f * sqrtf((float)p->total * (float)q->total));
    return r < 1.0f ? r : 1.0f;
}
#endif

#ifdef PFT_NUMERIC_Q16
void pft_tsa_rho_bank_(const pft_tsa_hist_t *p, const pft_tsa_hist_t *q, const pft_tsa_hroot_t *qr,
                       uint32_t n, pft_real_t *out)
{
    (void)q;
    /* p's square roots once for the n templates: the same values as pft_tsa_rho_hist_ (p's
     * bins are at most its total, so hroot_'s clamp changes nothing; a zero bin has root 0) */
    pft_tsa_hroot_t pr;
    pft_tsa_hroot_(p, &pr);
    for (uint32_t g = 0; g < n; ++g) {
        if (pr.root == 0u || qr[g].root == 0u) {
            out[g] = PFT_C(0.0);
            continue;
        }
        uint64_t num = 0u;
        for (uint32_t k = 0; k < qr[g].n_nz; ++k) {
            const uint32_t u = qr[g].nz[k];
            num += (uint64_t)pr.s[u] * qr[g].s[u];
        }
        out[g] = ratio_(num, 3u * (uint64_t)pr.root * qr[g].root);
    }
}
#else
void pft_tsa_rho_bank_(const pft_tsa_hist_t *p, const pft_tsa_hist_t *q, const pft_tsa_hroot_t *qr,
                       uint32_t n, pft_real_t *out)
{
    for (uint32_t g = 0; g < n; ++g) {
        out[g] = pft_tsa_rho_hist_(p, &q[g], &qr[g]);
    }
}
#endif

pft_real_t pft_tsa_bhattacharyya(const pft_tsa_hist_t *p, const pft_tsa_hist_t *q)
{
    if (p == NULL || q == NULL) {
        return PFT_C(0.0);
    }
    pft_tsa_hist_t pc = *p;
    for (uint32_t u = 0; u < PFT_TSA_BINS; ++u) {
        pc.bin[u] = pc.bin[u] < pc.total ? pc.bin[u] : pc.total;
    }
    pft_tsa_hroot_t qr;
    pft_tsa_hroot_(q, &qr);
    return pft_tsa_rho_hist_(&pc, q, &qr);
}
