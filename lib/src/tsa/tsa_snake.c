/*
 * Greedy snake (Williams & Shah 1992) with a balloon force (Cohen 1991) and corner
 * relaxation, docs/algorithms.md 4.3. Integer arithmetic in both builds: energies are Q16
 * fractions, distances Q8, the gradient an 8-bit Sobel magnitude on a patch around the
 * contour that is recomputed every margin - 2 passes.
 */
#include <string.h>

#include "tsa_int.h"

/* 1/sqrt(2) in Q16: the balloon energy of a diagonal step equals that of a straight one. */
#define INV_SQRT2_Q16_ 46341
/* A pass that moves fewer than 1 in STOP_FRACTION_ of the points ends the snake. */
#define STOP_FRACTION_ 10u
/* Smallest edge-strength range of a neighbourhood (keeps the image term bounded). */
#define MIN_GRAD_RANGE_ 5

void pft_tsa_snake_params_default(pft_tsa_snake_params_t *p, uint16_t max_w, uint16_t max_h)
{
    if (p == NULL) {
        return;
    }
    p->alpha = PFT_C(1.0);
    p->beta = PFT_C(1.0);
    p->gamma = PFT_C(1.2);
    p->kb = PFT_C(0.3);
    p->corner_c = PFT_C(0.25);
    p->corner_g = 100u;
    p->margin = 6u;
    p->max_w = max_w;
    p->max_h = max_h;
}

size_t pft_tsa_snake_work_size(uint16_t max_w, uint16_t max_h, uint8_t margin)
{
    return PFT_TSA_SNAKE_WORK_BYTES((size_t)max_w, (size_t)max_h, (size_t)margin);
}

/* The grey and gradient patches around the contour. */
typedef struct {
    const pft_frame_t *f;
    uint8_t *grey; /* (pw + 2) x (ph + 2), origin (ox - 1, oy - 1) */
    uint8_t *grad; /* pw x ph, origin (ox, oy) */
    int32_t ox, oy, pw, ph;
} patch_t_;

/* The snake weights as Q16 integers: alpha, beta, gamma, k_b; the corner threshold. */
typedef struct {
    int32_t w[4];
    int32_t corner_c;
} weights_t_;

static uint8_t grey_at_(const pft_frame_t *f, int32_t x, int32_t y)
{
    const int32_t W = (int32_t)f->width;
    const int32_t H = (int32_t)f->height;
    x = x < 0 ? 0 : (x >= W ? W - 1 : x);
    y = y < 0 ? 0 : (y >= H ? H - 1 : y);
    if (f->format == PFT_PIX_U8) {
        return pft_frame_row(f, (uint32_t)y)[x];
    }
    const uint8_t *p = pft_frame_row(f, (uint32_t)y) + 3u * (uint32_t)x;
    if (f->format == PFT_PIX_RGB888) {
        return (uint8_t)((77u * p[0] + 150u * p[1] + 29u * p[2]) >> 8);
    }
    return (uint8_t)((77u * p[2] + 150u * p[1] + 29u * p[0]) >> 8);
}

/* Grey values (edge pixels replicated) and the Sobel magnitude / 4 of the patch. */
static void patch_fill_(patch_t_ *pt)
{
    const int32_t gw = pt->pw + 2;
    for (int32_t y = 0; y < pt->ph + 2; ++y) {
        for (int32_t x = 0; x < gw; ++x) {
            pt->grey[y * gw + x] = grey_at_(pt->f, pt->ox - 1 + x, pt->oy - 1 + y);
        }
    }
    for (int32_t y = 0; y < pt->ph; ++y) {
        for (int32_t x = 0; x < pt->pw; ++x) {
            const uint8_t *g = &pt->grey[(y + 1) * gw + (x + 1)];
            const int32_t gx =
                (g[-gw + 1] + 2 * g[1] + g[gw + 1]) - (g[-gw - 1] + 2 * g[-1] + g[gw - 1]);
            const int32_t gy =
                (g[gw - 1] + 2 * g[gw] + g[gw + 1]) - (g[-gw - 1] + 2 * g[-gw] + g[-gw + 1]);
            const uint32_t m = pft_tsa_isqrt32_((uint32_t)(gx * gx + gy * gy)) / 4u;
            pt->grad[y * pt->pw + x] = (uint8_t)(m > 255u ? 255u : m);
        }
    }
}

static uint8_t grad_at_(const patch_t_ *pt, int32_t x, int32_t y)
{
    x -= pt->ox;
    y -= pt->oy;
    if (x < 0 || y < 0 || x >= pt->pw || y >= pt->ph) {
        return 0u;
    }
    return pt->grad[y * pt->pw + x];
}

/* |(dx, dy)| in Q8 */
static int32_t len_q8_(int32_t dx, int32_t dy)
{
    return (int32_t)pft_tsa_isqrt32_((uint32_t)(dx * dx + dy * dy) << 16);
}

/* Q16 fraction a / b (b > 0), a >= 0 */
static int32_t frac_q16_(int64_t a, int64_t b)
{
    return b > 0 ? (int32_t)((a * 65536) / b) : 0;
}

/* The energy terms of the 3x3 candidates of one point (index j = 3 (dy + 1) + (dx + 1)) and
 * the ranges of the valid ones. */
typedef struct {
    int32_t econt[9], ecurv[9], ebal[9], g[9];
    bool valid[9];
    int32_t maxc, maxk, gmin, gmax;
} cand_t_;

/* Fills c for the point cur between prev and next: continuity against the mean spacing dbar
 * (Q8), curvature, edge strength and the balloon term along the outward normal (nx, ny), Q16.
 * A candidate is valid inside [xlo, xhi] x [ylo, yhi] and off both neighbours. */
static void candidates_(const patch_t_ *pt, pft_tsa_pt_t prev, pft_tsa_pt_t cur, pft_tsa_pt_t next,
                        int32_t dbar, int32_t nx, int32_t ny, const pft_tsa_box_t_ *lim, cand_t_ *c)
{
    c->maxc = 0;
    c->maxk = 0;
    c->gmin = 255;
    c->gmax = 0;
    for (int32_t j = 0; j < 9; ++j) {
        const int32_t dx = (j % 3) - 1;
        const int32_t dy = (j / 3) - 1;
        const int32_t cx = cur.x + dx;
        const int32_t cy = cur.y + dy;
        const bool on_neighbour = (cx == prev.x && cy == prev.y) || (cx == next.x && cy == next.y);
        c->valid[j] = (cx >= lim->x0 && cx <= lim->x1 && cy >= lim->y0 && cy <= lim->y1) &&
                      (j == 4 || !on_neighbour);
        const int32_t ec = dbar - len_q8_(cx - prev.x, cy - prev.y);
        c->econt[j] = ec < 0 ? -ec : ec;
        const int32_t kx = prev.x - 2 * cx + next.x;
        const int32_t ky = prev.y - 2 * cy + next.y;
        c->ecurv[j] = kx * kx + ky * ky;
        c->g[j] = grad_at_(pt, cx, cy);
        /* -<c - v, n> / sqrt(2), Q16 */
        c->ebal[j] = (int32_t)(-((int64_t)dx * nx + (int64_t)dy * ny) * INV_SQRT2_Q16_ / 65536);
        if (c->valid[j]) {
            c->maxc = c->econt[j] > c->maxc ? c->econt[j] : c->maxc;
            c->maxk = c->ecurv[j] > c->maxk ? c->ecurv[j] : c->maxk;
            c->gmin = c->g[j] < c->gmin ? c->g[j] : c->gmin;
            c->gmax = c->g[j] > c->gmax ? c->g[j] : c->gmax;
        }
    }
}

/* The valid candidate of least energy (the centre first, so it wins ties); -1 if none. */
static int32_t best_candidate_(const cand_t_ *c, const weights_t_ *wq, bool curv)
{
    const int32_t gr = c->gmax - c->gmin > MIN_GRAD_RANGE_ ? c->gmax - c->gmin : MIN_GRAD_RANGE_;
    int32_t best = -1;
    int64_t ebest = 0;
    for (int32_t jj = 0; jj < 9; ++jj) {
        const int32_t j = jj == 0 ? 4 : (jj <= 4 ? jj - 1 : jj);
        if (!c->valid[j]) {
            continue;
        }
        int64_t e = (int64_t)wq->w[0] * frac_q16_(c->econt[j], c->maxc);
        e += curv ? (int64_t)wq->w[1] * frac_q16_(c->ecurv[j], c->maxk) : 0;
        e += (int64_t)wq->w[2] * (((int64_t)(c->gmin - c->g[j]) * 65536) / gr);
        e += (int64_t)wq->w[3] * c->ebal[j];
        if (best < 0 || e < ebest) {
            best = j;
            ebest = e;
        }
    }
    return best;
}

/* One greedy pass; returns the number of points moved. */
static uint32_t snake_pass_(const patch_t_ *pt, pft_tsa_pt_t *p, uint32_t n, const uint8_t *bflags,
                            const weights_t_ *wq, const pft_tsa_box_t_ *lim)
{
    const int32_t sgn = pft_tsa_poly_area2(p, n) >= 0 ? 1 : -1;
    int64_t dsum = 0;
    for (uint32_t i = 0; i < n; ++i) {
        const pft_tsa_pt_t *a = &p[(i + n - 1u) % n];
        dsum += len_q8_(p[i].x - a->x, p[i].y - a->y);
    }
    const int32_t dbar = (int32_t)(dsum / (int64_t)n);
    uint32_t moved = 0u;
    for (uint32_t i = 0; i < n; ++i) {
        const pft_tsa_pt_t prev = p[(i + n - 1u) % n];
        const pft_tsa_pt_t next = p[(i + 1u) % n];
        const pft_tsa_pt_t cur = p[i];
        const int32_t tx = next.x - prev.x;
        const int32_t ty = next.y - prev.y;
        const int32_t tl = len_q8_(tx, ty);
        int32_t nx = 0; /* outward unit normal, Q16 */
        int32_t ny = 0;
        if (tl > 0) {
            nx = (int32_t)(((int64_t)sgn * ty * 16777216) / tl);
            ny = (int32_t)(((int64_t)sgn * -tx * 16777216) / tl);
        }
        cand_t_ c;
        candidates_(pt, prev, cur, next, dbar, nx, ny, lim, &c);
        const int32_t best = best_candidate_(&c, wq, bflags[i] != 0u);
        if (best >= 0 && best != 4) {
            p[i].x = (int16_t)(cur.x + (best % 3) - 1);
            p[i].y = (int16_t)(cur.y + (best / 3) - 1);
            ++moved;
        }
    }
    return moved;
}

/* Corner relaxation: curvature off at local maxima of the turning above the thresholds. */
static void corners_(const patch_t_ *pt, const pft_tsa_pt_t *p, uint32_t n, uint8_t *bflags,
                     int32_t cth, uint8_t gth)
{
    for (uint32_t k = 0; k < n; ++k) {
        bflags[k] = 1u;
    }
    /* turning c_i = |u_i/|u_i| - u_{i+1}/|u_{i+1}||^2 (Q16), computed on the fly */
    int32_t c[3] = {0, 0, 0};
    for (uint32_t k = 0; k < n + 2u; ++k) {
        /* c for point index (k % n) */
        const uint32_t i = k % n;
        const pft_tsa_pt_t *a = &p[(i + n - 1u) % n];
        const pft_tsa_pt_t *b = &p[i];
        const pft_tsa_pt_t *d = &p[(i + 1u) % n];
        const int32_t ux = b->x - a->x;
        const int32_t uy = b->y - a->y;
        const int32_t wx = d->x - b->x;
        const int32_t wy = d->y - b->y;
        const int32_t lu = len_q8_(ux, uy);
        const int32_t lw = len_q8_(wx, wy);
        int32_t ci = 0;
        if (lu > 0 && lw > 0) {
            /* u/|u| - w/|w| in Q16 */
            const int64_t ex = ((int64_t)ux * 16777216) / lu - ((int64_t)wx * 16777216) / lw;
            const int64_t ey = ((int64_t)uy * 16777216) / lu - ((int64_t)wy * 16777216) / lw;
            ci = (int32_t)((ex * ex + ey * ey) >> 16);
        }
        c[0] = c[1];
        c[1] = c[2];
        c[2] = ci;
        if (k >= 2u) {
            const uint32_t m = (k + n - 1u) % n; /* the middle one */
            if (c[1] > c[0] && c[1] > c[2] && c[1] > cth && grad_at_(pt, p[m].x, p[m].y) > gth) {
                bflags[m] = 0u;
            }
        }
    }
}

pft_status_t pft_tsa_snake(const pft_frame_t *frame, pft_tsa_pt_t *pts, uint32_t n,
                           const pft_tsa_snake_params_t *prm, uint32_t max_passes,
                           uint8_t *bflags, void *work, size_t work_len, uint32_t *passes_done)
{
    if (passes_done != NULL) {
        *passes_done = 0u;
    }
    if (pts == NULL || prm == NULL || bflags == NULL || work == NULL || n < PFT_TSA_MIN_POINTS ||
        n > PFT_TSA_MAX_POINTS || prm->margin < 3u || prm->max_w == 0u || prm->max_h == 0u) {
        return PFT_ERR_INVAL;
    }
    pft_status_t st = pft_frame_check(frame, 0u, 0u, PFT_TSA_FMT_MASK_);
    if (st != PFT_OK) {
        return st;
    }
    if (work_len < pft_tsa_snake_work_size(prm->max_w, prm->max_h, prm->margin)) {
        return PFT_ERR_NOMEM;
    }
    patch_t_ pt;
    pt.f = frame;
    pt.pw = (int32_t)prm->max_w + 2 * (int32_t)prm->margin;
    pt.ph = (int32_t)prm->max_h + 2 * (int32_t)prm->margin;
    pt.grey = (uint8_t *)work;
    pt.grad = pt.grey + (size_t)(pt.pw + 2) * (size_t)(pt.ph + 2);
    weights_t_ wq;
    wq.w[0] = pft_tsa_q16_(prm->alpha);
    wq.w[1] = pft_tsa_q16_(prm->beta);
    wq.w[2] = pft_tsa_q16_(prm->gamma);
    wq.w[3] = pft_tsa_q16_(prm->kb);
    wq.corner_c = pft_tsa_q16_(prm->corner_c);
    memset(bflags, 1, n);
    /* passes in chunks of margin - 2, the gradient patch recomputed around the contour first */
    const uint32_t chunk = (uint32_t)prm->margin - 2u;
    uint32_t done = 0u;
    bool converged = false;
    while (done < max_passes && !converged) {
        const pft_tsa_box_t_ bb = pft_tsa_bbox_(pts, n);
        if (bb.x1 - bb.x0 + 1 > (int32_t)prm->max_w || bb.y1 - bb.y0 + 1 > (int32_t)prm->max_h) {
            if (passes_done != NULL) {
                *passes_done = done;
            }
            return PFT_ERR_NOMEM;
        }
        pt.ox = bb.x0 - (int32_t)prm->margin;
        pt.oy = bb.y0 - (int32_t)prm->margin;
        patch_fill_(&pt);
        /* points stay inside the patch (1 px in) and the frame (1 px in) */
        pft_tsa_box_t_ lim;
        lim.x0 = pt.ox + 1 > 1 ? pt.ox + 1 : 1;
        lim.y0 = pt.oy + 1 > 1 ? pt.oy + 1 : 1;
        const int32_t fx1 = (int32_t)frame->width - 2;
        const int32_t fy1 = (int32_t)frame->height - 2;
        lim.x1 = pt.ox + pt.pw - 2 < fx1 ? pt.ox + pt.pw - 2 : fx1;
        lim.y1 = pt.oy + pt.ph - 2 < fy1 ? pt.oy + pt.ph - 2 : fy1;
        for (uint32_t c = 0; c < chunk && done < max_passes; ++c) {
            const uint32_t moved = snake_pass_(&pt, pts, n, bflags, &wq, &lim);
            corners_(&pt, pts, n, bflags, wq.corner_c, prm->corner_g);
            ++done;
            if (moved * STOP_FRACTION_ < n) {
                converged = true;
                break;
            }
        }
    }
    if (passes_done != NULL) {
        *passes_done = done;
    }
    return PFT_OK;
}
