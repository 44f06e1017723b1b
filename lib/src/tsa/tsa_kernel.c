/*
 * Polygon geometry of the appearance model (ALGORITHMS.md 4.3): signed area, even-odd
 * rasterisation of pixel centres, distance to the contour, perimeter resampling, and the
 * asymmetric kernel K(p) = c + d(p) stored as offsets from the rounded area centroid.
 * Integer arithmetic only.
 */
#include "tsa_int.h"

int64_t pft_tsa_poly_area2(const pft_tsa_pt_t *poly, uint32_t n)
{
    int64_t a = 0;
    if (poly == NULL || n < 3u) {
        return 0;
    }
    for (uint32_t i = 0; i < n; ++i) {
        const pft_tsa_pt_t *p = &poly[i], *q = &poly[(i + 1u) % n];
        a += (int64_t)p->x * q->y - (int64_t)q->x * p->y;
    }
    return a;
}

/* Crossings (Q16 x) of row y with the polygon edges, half-open in y; returns the count. */
static uint32_t row_crossings(const pft_tsa_pt_t *poly, uint32_t n, int32_t y, int32_t *cross)
{
    uint32_t m = 0u;
    for (uint32_t i = 0; i < n; ++i) {
        const pft_tsa_pt_t *a = &poly[i], *b = &poly[(i + 1u) % n];
        if ((a->y > y) != (b->y > y)) {
            const int64_t num = (int64_t)(y - a->y) * (b->x - a->x) * 65536;
            const int64_t den = (int64_t)(b->y - a->y);
            int64_t q = num / den;
            if ((num % den != 0) && ((num < 0) != (den < 0))) {
                q -= 1; /* floor */
            }
            cross[m++] = (int32_t)(q + (int64_t)a->x * 65536);
        }
    }
    /* insertion sort (m <= n <= PFT_TSA_MAX_POINTS) */
    for (uint32_t i = 1; i < m; ++i) {
        int32_t v = cross[i];
        uint32_t j = i;
        while (j > 0u && cross[j - 1u] > v) {
            cross[j] = cross[j - 1u];
            --j;
        }
        cross[j] = v;
    }
    return m;
}

bool pft_tsa_poly_inside(const pft_tsa_pt_t *poly, uint32_t n, int32_t x, int32_t y)
{
    uint32_t cnt = 0u;
    if (poly == NULL || n < 3u) {
        return false;
    }
    for (uint32_t i = 0; i < n; ++i) {
        const pft_tsa_pt_t *a = &poly[i], *b = &poly[(i + 1u) % n];
        if ((a->y > y) != (b->y > y)) {
            /* crossing x_c = a.x + (y - a.y)(b.x - a.x)/(b.y - a.y); count x_c > x exactly */
            const int64_t lhs = (int64_t)(x - a->x) * (b->y - a->y);
            const int64_t rhs = (int64_t)(y - a->y) * (b->x - a->x);
            const bool gt = (b->y - a->y) > 0 ? rhs > lhs : rhs < lhs;
            cnt += gt ? 1u : 0u;
        }
    }
    return (cnt & 1u) != 0u;
}

/* Squared distance times 256 (floor) from (x, y) to the polygon's nearest edge. Coordinates
 * are taken relative to the first vertex, so any frame-sized polygon stays in range. */
static uint64_t dist2_q8(const pft_tsa_pt_t *poly, uint32_t n, int32_t x, int32_t y)
{
    uint64_t best = UINT64_MAX;
    for (uint32_t i = 0; i < n; ++i) {
        const pft_tsa_pt_t *a = &poly[i], *b = &poly[(i + 1u) % n];
        const int64_t ex = b->x - a->x, ey = b->y - a->y;
        const int64_t wx = x - a->x, wy = y - a->y;
        const int64_t t = wx * ex + wy * ey, L = ex * ex + ey * ey;
        uint64_t d;
        if (L == 0 || t <= 0) {
            d = (uint64_t)(wx * wx + wy * wy) << 8;
        } else if (t >= L) {
            const int64_t bx = x - b->x, by = y - b->y;
            d = (uint64_t)(bx * bx + by * by) << 8;
        } else {
            const int64_t c = wx * ey - wy * ex;
            d = ((uint64_t)(c * c) << 8) / (uint64_t)L;
        }
        if (d < best) {
            best = d;
        }
    }
    return best;
}

uint32_t pft_tsa_poly_dist_q4(const pft_tsa_pt_t *poly, uint32_t n, int32_t x, int32_t y)
{
    if (poly == NULL || n == 0u) {
        return 0u;
    }
    return tsa_isqrt64_(dist2_q8(poly, n, x, y));
}

static int64_t floordiv(int64_t a, int64_t b) /* b > 0 */
{
    int64_t q = a / b;
    return (a % b != 0 && a < 0) ? q - 1 : q;
}

pft_status_t pft_tsa_kernel_build(pft_tsa_kernel_t *k, const pft_tsa_pt_t *poly, uint32_t n,
                                  uint16_t c_q4, int32_t *cross, pft_tsa_pt_t *origin)
{
    int32_t xmin = INT16_MAX, xmax = INT16_MIN, ymin = INT16_MAX, ymax = INT16_MIN;
    int64_t sx = 0, sy = 0;
    uint32_t count = 0u, sum = 0u;
    int32_t cx, cy;
    int16_t bx0 = INT16_MAX, by0 = INT16_MAX, bx1 = INT16_MIN, by1 = INT16_MIN;

    if (k == NULL || poly == NULL || cross == NULL || origin == NULL || n < 3u ||
        n > PFT_TSA_MAX_POINTS) {
        return PFT_ERR_INVAL;
    }
    if (pft_tsa_poly_area2(poly, n) == 0) {
        return PFT_ERR_INVAL;
    }
    for (uint32_t i = 0; i < n; ++i) {
        xmin = poly[i].x < xmin ? poly[i].x : xmin;
        xmax = poly[i].x > xmax ? poly[i].x : xmax;
        ymin = poly[i].y < ymin ? poly[i].y : ymin;
        ymax = poly[i].y > ymax ? poly[i].y : ymax;
    }
    if (xmax - xmin + 1 > (int32_t)PFT_TSA_MAX_SIDE || ymax - ymin + 1 > (int32_t)PFT_TSA_MAX_SIDE) {
        return PFT_ERR_RANGE;
    }
    /* pass 1: count and centroid */
    for (int32_t y = ymin; y <= ymax; ++y) {
        const uint32_t m = row_crossings(poly, n, y, cross);
        for (uint32_t j = 0; j + 1u < m; j += 2u) {
            const int32_t x0 = (int32_t)((cross[j] + 65535) >> 16);      /* ceil */
            const int32_t x1 = (int32_t)((cross[j + 1u] + 65535) >> 16); /* exclusive */
            for (int32_t x = x0; x < x1; ++x) {
                sx += x;
                sy += y;
                ++count;
            }
        }
    }
    if (count == 0u) {
        return PFT_ERR_RANGE;
    }
    if (count > k->cap || k->pix == NULL) {
        return PFT_ERR_NOMEM;
    }
    cx = (int32_t)floordiv(2 * sx + (int64_t)count, 2 * (int64_t)count); /* round, ties up */
    cy = (int32_t)floordiv(2 * sy + (int64_t)count, 2 * (int64_t)count);
    /* pass 2: weights c + d(p) */
    count = 0u;
    for (int32_t y = ymin; y <= ymax; ++y) {
        const uint32_t m = row_crossings(poly, n, y, cross);
        for (uint32_t j = 0; j + 1u < m; j += 2u) {
            const int32_t x0 = (int32_t)((cross[j] + 65535) >> 16);
            const int32_t x1 = (int32_t)((cross[j + 1u] + 65535) >> 16);
            for (int32_t x = x0; x < x1; ++x) {
                uint32_t w = (uint32_t)c_q4 + tsa_isqrt64_(dist2_q8(poly, n, x, y));
                pft_tsa_kpix_t *kp = &k->pix[count++];
                w = w > 65535u ? 65535u : (w == 0u ? 1u : w);
                kp->dx = (int16_t)(x - cx);
                kp->dy = (int16_t)(y - cy);
                kp->w = (uint16_t)w;
                sum += w;
                bx0 = kp->dx < bx0 ? kp->dx : bx0;
                bx1 = kp->dx > bx1 ? kp->dx : bx1;
                by0 = kp->dy < by0 ? kp->dy : by0;
                by1 = kp->dy > by1 ? kp->dy : by1;
            }
        }
    }
    k->n = count;
    k->sum = sum;
    k->x0 = bx0;
    k->y0 = by0;
    k->x1 = bx1;
    k->y1 = by1;
    origin->x = (int16_t)cx;
    origin->y = (int16_t)cy;
    return PFT_OK;
}

pft_status_t pft_tsa_poly_resample(const pft_tsa_pt_t *in, uint32_t n_in, pft_tsa_pt_t *out,
                                   uint32_t n_out)
{
    uint64_t total = 0u, seg_start = 0u;
    uint32_t e = 0u;
    if (in == NULL || out == NULL || n_in < 3u || n_out == 0u || n_in > 65535u) {
        return PFT_ERR_INVAL;
    }
    for (uint32_t i = 0; i < n_in; ++i) {
        const pft_tsa_pt_t *a = &in[i], *b = &in[(i + 1u) % n_in];
        const int64_t dx = b->x - a->x, dy = b->y - a->y;
        total += tsa_isqrt64_((uint64_t)(dx * dx + dy * dy) << 16); /* Q8 */
    }
    if (total == 0u) {
        return PFT_ERR_INVAL;
    }
    for (uint32_t j = 0; j < n_out; ++j) {
        const uint64_t s = total * j / n_out;
        uint64_t len;
        const pft_tsa_pt_t *a, *b;
        int64_t dx, dy, f;
        for (;;) { /* bounded: e < n_in */
            a = &in[e];
            b = &in[(e + 1u) % n_in];
            dx = b->x - a->x;
            dy = b->y - a->y;
            len = tsa_isqrt64_((uint64_t)(dx * dx + dy * dy) << 16);
            if (s < seg_start + len || e + 1u >= n_in) {
                break;
            }
            seg_start += len;
            ++e;
        }
        f = len > 0u ? (int64_t)(((s - seg_start) << 16) / len) : 0; /* Q16 fraction */
        if (f > 65536) {
            f = 65536;
        }
        out[j].x = (int16_t)(a->x + ((dx * f + 32768) >> 16));
        out[j].y = (int16_t)(a->y + ((dy * f + 32768) >> 16));
    }
    return PFT_OK;
}
