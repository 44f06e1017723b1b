/*
 * Greedy snake (Williams & Shah 1992) with a balloon force (Cohen 1991) and corner
 * relaxation, ALGORITHMS.md 4.3. Integer arithmetic in both builds: energies are Q16
 * fractions, distances Q8, the gradient an 8-bit Sobel magnitude on a patch around the
 * contour that is recomputed every margin - 2 passes.
 */
#include <string.h>

#include "tsa_int.h"

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

typedef struct {
    const pft_frame_t *f;
    uint8_t *grey;  /* (pw + 2) x (ph + 2), origin (ox - 1, oy - 1) */
    uint8_t *grad;  /* pw x ph, origin (ox, oy) */
    int32_t ox, oy, pw, ph;
} patch_t;

static uint8_t grey_at(const pft_frame_t *f, int32_t x, int32_t y)
{
    const int32_t W = (int32_t)f->width, H = (int32_t)f->height;
    const uint8_t *p;
    x = x < 0 ? 0 : (x >= W ? W - 1 : x);
    y = y < 0 ? 0 : (y >= H ? H - 1 : y);
    if (f->format == PFT_PIX_U8) {
        return pft_frame_row(f, (uint32_t)y)[x];
    }
    p = pft_frame_row(f, (uint32_t)y) + 3u * (uint32_t)x;
    if (f->format == PFT_PIX_RGB888) {
        return (uint8_t)((77u * p[0] + 150u * p[1] + 29u * p[2]) >> 8);
    }
    return (uint8_t)((77u * p[2] + 150u * p[1] + 29u * p[0]) >> 8);
}

static void patch_fill(patch_t *pt)
{
    const int32_t gw = pt->pw + 2;
    for (int32_t y = 0; y < pt->ph + 2; ++y) {
        for (int32_t x = 0; x < gw; ++x) {
            pt->grey[y * gw + x] = grey_at(pt->f, pt->ox - 1 + x, pt->oy - 1 + y);
        }
    }
    for (int32_t y = 0; y < pt->ph; ++y) {
        for (int32_t x = 0; x < pt->pw; ++x) {
            const uint8_t *g = &pt->grey[(y + 1) * gw + (x + 1)];
            const int32_t gx = (g[-gw + 1] + 2 * g[1] + g[gw + 1]) - (g[-gw - 1] + 2 * g[-1] + g[gw - 1]);
            const int32_t gy = (g[gw - 1] + 2 * g[gw] + g[gw + 1]) - (g[-gw - 1] + 2 * g[-gw] + g[-gw + 1]);
            uint32_t m = tsa_isqrt32_((uint32_t)(gx * gx + gy * gy)) / 4u;
            pt->grad[y * pt->pw + x] = (uint8_t)(m > 255u ? 255u : m);
        }
    }
}

static uint8_t grad_at(const patch_t *pt, int32_t x, int32_t y)
{
    x -= pt->ox;
    y -= pt->oy;
    if (x < 0 || y < 0 || x >= pt->pw || y >= pt->ph) {
        return 0u;
    }
    return pt->grad[y * pt->pw + x];
}

/* |(dx, dy)| in Q8 */
static int32_t len_q8(int32_t dx, int32_t dy)
{
    return (int32_t)tsa_isqrt32_((uint32_t)(dx * dx + dy * dy) << 16);
}

/* Q16 fraction a / b (b > 0), a >= 0 */
static int32_t frac_q16(int64_t a, int64_t b)
{
    return b > 0 ? (int32_t)((a * 65536) / b) : 0;
}

/* One greedy pass; returns the number of points moved. */
static uint32_t snake_pass(const patch_t *pt, pft_tsa_pt_t *p, uint32_t n, const uint8_t *bflags,
                           const int32_t wq[4], int32_t xlo, int32_t xhi, int32_t ylo, int32_t yhi)
{
    int64_t dsum = 0;
    int32_t dbar;
    uint32_t moved = 0u;
    const int32_t sgn = pft_tsa_poly_area2(p, n) >= 0 ? 1 : -1;
    for (uint32_t i = 0; i < n; ++i) {
        const pft_tsa_pt_t *a = &p[(i + n - 1u) % n];
        dsum += len_q8(p[i].x - a->x, p[i].y - a->y);
    }
    dbar = (int32_t)(dsum / (int64_t)n);
    for (uint32_t i = 0; i < n; ++i) {
        const pft_tsa_pt_t prev = p[(i + n - 1u) % n], next = p[(i + 1u) % n], cur = p[i];
        int32_t econt[9], ecurv[9], ebal[9], g[9], valid[9];
        int32_t maxc = 0, maxk = 0, gmin = 255, gmax = 0, best = -1;
        int64_t ebest = 0;
        const int32_t tx = next.x - prev.x, ty = next.y - prev.y;
        const int32_t tl = len_q8(tx, ty);
        int32_t nx = 0, ny = 0; /* outward unit normal, Q16 */
        if (tl > 0) {
            nx = (int32_t)(((int64_t)sgn * ty * 16777216) / tl);
            ny = (int32_t)(((int64_t)sgn * -tx * 16777216) / tl);
        }
        for (int32_t j = 0; j < 9; ++j) {
            const int32_t dx = (j % 3) - 1, dy = (j / 3) - 1;
            const int32_t cx = cur.x + dx, cy = cur.y + dy;
            int32_t kx, ky;
            valid[j] = (cx >= xlo && cx <= xhi && cy >= ylo && cy <= yhi) &&
                       (j == 4 || !((cx == prev.x && cy == prev.y) || (cx == next.x && cy == next.y)));
            econt[j] = dbar - len_q8(cx - prev.x, cy - prev.y);
            econt[j] = econt[j] < 0 ? -econt[j] : econt[j];
            kx = prev.x - 2 * cx + next.x;
            ky = prev.y - 2 * cy + next.y;
            ecurv[j] = kx * kx + ky * ky;
            g[j] = grad_at(pt, cx, cy);
            /* -<c - v, n> / sqrt(2), Q16 */
            ebal[j] = (int32_t)(-((int64_t)dx * nx + (int64_t)dy * ny) * 46341 / 65536);
            if (valid[j]) {
                maxc = econt[j] > maxc ? econt[j] : maxc;
                maxk = ecurv[j] > maxk ? ecurv[j] : maxk;
                gmin = g[j] < gmin ? g[j] : gmin;
                gmax = g[j] > gmax ? g[j] : gmax;
            }
        }
        for (int32_t jj = 0; jj < 9; ++jj) {
            const int32_t j = jj == 0 ? 4 : (jj <= 4 ? jj - 1 : jj); /* the centre first */
            int64_t e;
            const int32_t gr = gmax - gmin > 5 ? gmax - gmin : 5;
            if (!valid[j]) {
                continue;
            }
            e = (int64_t)wq[0] * frac_q16(econt[j], maxc);
            e += bflags[i] ? (int64_t)wq[1] * frac_q16(ecurv[j], maxk) : 0;
            e += (int64_t)wq[2] * (((int64_t)(gmin - g[j]) * 65536) / gr);
            e += (int64_t)wq[3] * ebal[j];
            if (best < 0 || e < ebest) {
                best = j;
                ebest = e;
            }
        }
        if (best >= 0 && best != 4) {
            p[i].x = (int16_t)(cur.x + (best % 3) - 1);
            p[i].y = (int16_t)(cur.y + (best / 3) - 1);
            ++moved;
        }
    }
    return moved;
}

/* Corner relaxation: curvature off at local maxima of the turning above the thresholds. */
static void corners(const patch_t *pt, const pft_tsa_pt_t *p, uint32_t n, uint8_t *bflags,
                    int32_t cth, uint8_t gth)
{
    /* turning c_i = |u_i/|u_i| - u_{i+1}/|u_{i+1}||^2 (Q16), computed on the fly */
    int32_t c[3] = {0, 0, 0};
    uint32_t k;
    for (k = 0; k < n; ++k) {
        bflags[k] = 1u;
    }
    for (k = 0; k < n + 2u; ++k) {
        /* c for point index (k % n) */
        const uint32_t i = k % n;
        const pft_tsa_pt_t *a = &p[(i + n - 1u) % n], *b = &p[i], *d = &p[(i + 1u) % n];
        const int32_t ux = b->x - a->x, uy = b->y - a->y, wx = d->x - b->x, wy = d->y - b->y;
        const int32_t lu = len_q8(ux, uy), lw = len_q8(wx, wy);
        int64_t ex, ey;
        int32_t ci = 0;
        if (lu > 0 && lw > 0) {
            ex = ((int64_t)ux * 16777216) / lu - ((int64_t)wx * 16777216) / lw; /* Q16 */
            ey = ((int64_t)uy * 16777216) / lu - ((int64_t)wy * 16777216) / lw;
            ci = (int32_t)((ex * ex + ey * ey) >> 16);
        }
        c[0] = c[1];
        c[1] = c[2];
        c[2] = ci;
        if (k >= 2u) {
            const uint32_t m = (k + n - 1u) % n; /* the middle one */
            if (c[1] > c[0] && c[1] > c[2] && c[1] > cth && grad_at(pt, p[m].x, p[m].y) > gth) {
                bflags[m] = 0u;
            }
        }
    }
}

pft_status_t pft_tsa_snake(const pft_frame_t *frame, pft_tsa_pt_t *pts, uint32_t n,
                           const pft_tsa_snake_params_t *prm, uint32_t max_passes,
                           uint8_t *bflags, void *work, size_t work_len, uint32_t *passes_done)
{
    patch_t pt;
    int32_t wq[4], cth;
    uint32_t done = 0u;
    pft_status_t st;
    if (passes_done != NULL) {
        *passes_done = 0u;
    }
    if (pts == NULL || prm == NULL || bflags == NULL || work == NULL || n < PFT_TSA_MIN_POINTS ||
        n > PFT_TSA_MAX_POINTS || prm->margin < 3u || prm->max_w == 0u || prm->max_h == 0u) {
        return PFT_ERR_INVAL;
    }
    st = pft_frame_check(frame, 0u, 0u, TSA_FMT_MASK_);
    if (st != PFT_OK) {
        return st;
    }
    if (work_len < pft_tsa_snake_work_size(prm->max_w, prm->max_h, prm->margin)) {
        return PFT_ERR_NOMEM;
    }
    pt.f = frame;
    pt.pw = (int32_t)prm->max_w + 2 * (int32_t)prm->margin;
    pt.ph = (int32_t)prm->max_h + 2 * (int32_t)prm->margin;
    pt.grey = (uint8_t *)work;
    pt.grad = pt.grey + (size_t)(pt.pw + 2) * (size_t)(pt.ph + 2);
    wq[0] = tsa_to_q16_(prm->alpha);
    wq[1] = tsa_to_q16_(prm->beta);
    wq[2] = tsa_to_q16_(prm->gamma);
    wq[3] = tsa_to_q16_(prm->kb);
    cth = tsa_to_q16_(prm->corner_c);
    memset(bflags, 1, n);
    while (done < max_passes) {
        int32_t xmin = INT16_MAX, xmax = INT16_MIN, ymin = INT16_MAX, ymax = INT16_MIN;
        uint32_t chunk;
        int32_t xlo, xhi, ylo, yhi;
        bool converged = false;
        for (uint32_t i = 0; i < n; ++i) {
            xmin = pts[i].x < xmin ? pts[i].x : xmin;
            xmax = pts[i].x > xmax ? pts[i].x : xmax;
            ymin = pts[i].y < ymin ? pts[i].y : ymin;
            ymax = pts[i].y > ymax ? pts[i].y : ymax;
        }
        if (xmax - xmin + 1 > (int32_t)prm->max_w || ymax - ymin + 1 > (int32_t)prm->max_h) {
            if (passes_done != NULL) {
                *passes_done = done;
            }
            return PFT_ERR_RANGE;
        }
        pt.ox = xmin - (int32_t)prm->margin;
        pt.oy = ymin - (int32_t)prm->margin;
        patch_fill(&pt);
        /* points stay inside the patch (1 px in) and the frame (1 px in) */
        xlo = pt.ox + 1 > 1 ? pt.ox + 1 : 1;
        ylo = pt.oy + 1 > 1 ? pt.oy + 1 : 1;
        xhi = pt.ox + pt.pw - 2 < (int32_t)frame->width - 2 ? pt.ox + pt.pw - 2 : (int32_t)frame->width - 2;
        yhi = pt.oy + pt.ph - 2 < (int32_t)frame->height - 2 ? pt.oy + pt.ph - 2 : (int32_t)frame->height - 2;
        chunk = (uint32_t)prm->margin - 2u;
        for (uint32_t c = 0; c < chunk && done < max_passes; ++c) {
            const uint32_t moved = snake_pass(&pt, pts, n, bflags, wq, xlo, xhi, ylo, yhi);
            corners(&pt, pts, n, bflags, cth, prm->corner_g);
            ++done;
            if (moved * 10u < n) {
                converged = true;
                break;
            }
        }
        if (converged) {
            break;
        }
    }
    if (passes_done != NULL) {
        *passes_done = done;
    }
    return PFT_OK;
}
