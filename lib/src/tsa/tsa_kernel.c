/*
 * Polygon geometry of the appearance model (docs/algorithms.md 4.3): signed area, even-odd
 * rasterisation of pixel centres, distance to the contour, perimeter resampling, and the
 * asymmetric kernel K(p) = c + d(p) stored as offsets from the rounded area centroid.
 * Integer arithmetic only.
 */
#include "tsa_int.h"

pft_tsa_box_t_ pft_tsa_bbox_(const pft_tsa_pt_t *pts, uint32_t n)
{
    pft_tsa_box_t_ b = {pts[0].x, pts[0].y, pts[0].x, pts[0].y};
    for (uint32_t i = 1; i < n; ++i) {
        b.x0 = pts[i].x < b.x0 ? pts[i].x : b.x0;
        b.x1 = pts[i].x > b.x1 ? pts[i].x : b.x1;
        b.y0 = pts[i].y < b.y0 ? pts[i].y : b.y0;
        b.y1 = pts[i].y > b.y1 ? pts[i].y : b.y1;
    }
    return b;
}

int64_t pft_tsa_poly_area2(const pft_tsa_pt_t *poly, uint32_t n)
{
    if (poly == NULL || n < 3u) {
        return 0;
    }
    int64_t a = 0;
    for (uint32_t i = 0; i < n; ++i) {
        const pft_tsa_pt_t *p = &poly[i];
        const pft_tsa_pt_t *q = &poly[(i + 1u) % n];
        a += (int64_t)p->x * q->y - (int64_t)q->x * p->y;
    }
    return a;
}

/* Crossings (Q16 x) of row y with the polygon edges, half-open in y, sorted; returns the
 * count. */
static uint32_t row_crossings_(const pft_tsa_pt_t *poly, uint32_t n, int32_t y, int32_t *cross)
{
    uint32_t m = 0u;
    for (uint32_t i = 0; i < n; ++i) {
        const pft_tsa_pt_t *a = &poly[i];
        const pft_tsa_pt_t *b = &poly[(i + 1u) % n];
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
        const int32_t v = cross[i];
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
    if (poly == NULL || n < 3u) {
        return false;
    }
    uint32_t cnt = 0u;
    for (uint32_t i = 0; i < n; ++i) {
        const pft_tsa_pt_t *a = &poly[i];
        const pft_tsa_pt_t *b = &poly[(i + 1u) % n];
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
 * are taken relative to the edge's first vertex, so any frame-sized polygon stays in range. */
static uint64_t dist2_q8_(const pft_tsa_pt_t *poly, uint32_t n, int32_t x, int32_t y)
{
    uint64_t best = UINT64_MAX;
    for (uint32_t i = 0; i < n; ++i) {
        const pft_tsa_pt_t *a = &poly[i];
        const pft_tsa_pt_t *b = &poly[(i + 1u) % n];
        const int64_t ex = b->x - a->x;
        const int64_t ey = b->y - a->y;
        const int64_t wx = x - a->x;
        const int64_t wy = y - a->y;
        const int64_t t = wx * ex + wy * ey;
        const int64_t len2 = ex * ex + ey * ey;
        uint64_t d;
        if (len2 == 0 || t <= 0) {
            d = (uint64_t)(wx * wx + wy * wy) << 8;
        } else if (t >= len2) {
            const int64_t bx = x - b->x;
            const int64_t by = y - b->y;
            d = (uint64_t)(bx * bx + by * by) << 8;
        } else {
            const int64_t c = wx * ey - wy * ex;
            d = ((uint64_t)(c * c) << 8) / (uint64_t)len2;
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
    return pft_tsa_isqrt64_(dist2_q8_(poly, n, x, y));
}

/* floor(a / b) for b > 0. */
static int64_t floordiv_(int64_t a, int64_t b)
{
    const int64_t q = a / b;
    return (a % b != 0 && a < 0) ? q - 1 : q;
}

/* First pixel column at or right of a Q16 crossing (ceil). */
static int32_t span_col_(int32_t cross_q16)
{
    return (int32_t)((cross_q16 + 65535) >> 16);
}

/* Pass 1 of the kernel: number of interior pixel centres and the sums of their coordinates. */
static uint32_t interior_sums_(const pft_tsa_pt_t *poly, uint32_t n, const pft_tsa_box_t_ *bb,
                               int32_t *cross, int64_t *sx, int64_t *sy)
{
    uint32_t count = 0u;
    *sx = 0;
    *sy = 0;
    for (int32_t y = bb->y0; y <= bb->y1; ++y) {
        const uint32_t m = row_crossings_(poly, n, y, cross);
        for (uint32_t j = 0; j + 1u < m; j += 2u) {
            const int32_t x1 = span_col_(cross[j + 1u]); /* exclusive */
            for (int32_t x = span_col_(cross[j]); x < x1; ++x) {
                *sx += x;
                *sy += y;
                ++count;
            }
        }
    }
    return count;
}

/* Pass 2: the weights c + d(p) (Q4, clamped to [1, 65535]) of the interior pixels as offsets
 * from (cx, cy), their sum and the offsets' bounding box into k (pix has room: pass 1). */
static void interior_weights_(pft_tsa_kernel_t *k, const pft_tsa_pt_t *poly, uint32_t n,
                              const pft_tsa_box_t_ *bb, uint16_t c_q4, int32_t *cross, int32_t cx,
                              int32_t cy)
{
    uint32_t count = 0u;
    uint32_t sum = 0u;
    int16_t bx0 = INT16_MAX;
    int16_t by0 = INT16_MAX;
    int16_t bx1 = INT16_MIN;
    int16_t by1 = INT16_MIN;
    for (int32_t y = bb->y0; y <= bb->y1; ++y) {
        const uint32_t m = row_crossings_(poly, n, y, cross);
        for (uint32_t j = 0; j + 1u < m; j += 2u) {
            const int32_t x1 = span_col_(cross[j + 1u]);
            for (int32_t x = span_col_(cross[j]); x < x1; ++x) {
                uint32_t w = (uint32_t)c_q4 + pft_tsa_isqrt64_(dist2_q8_(poly, n, x, y));
                w = w > 65535u ? 65535u : (w == 0u ? 1u : w);
                pft_tsa_kpix_t *kp = &k->pix[count++];
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
}

uint32_t pft_tsa_poly_count_(const pft_tsa_pt_t *poly, uint32_t n, int32_t *cross)
{
    if (pft_tsa_poly_area2(poly, n) == 0) {
        return 0u;
    }
    const pft_tsa_box_t_ bb = pft_tsa_bbox_(poly, n);
    int64_t sx;
    int64_t sy;
    return interior_sums_(poly, n, &bb, cross, &sx, &sy);
}

pft_status_t pft_tsa_kernel_build(pft_tsa_kernel_t *k, const pft_tsa_pt_t *poly, uint32_t n,
                                  uint16_t c_q4, int32_t *cross, pft_tsa_pt_t *origin)
{
    if (k == NULL || poly == NULL || cross == NULL || origin == NULL || n < 3u ||
        n > PFT_TSA_MAX_POINTS) {
        return PFT_ERR_INVAL;
    }
    if (pft_tsa_poly_area2(poly, n) == 0) {
        return PFT_ERR_DEGENERATE;
    }
    const pft_tsa_box_t_ bb = pft_tsa_bbox_(poly, n);
    if (bb.x1 - bb.x0 + 1 > (int32_t)PFT_TSA_MAX_SIDE ||
        bb.y1 - bb.y0 + 1 > (int32_t)PFT_TSA_MAX_SIDE) {
        return PFT_ERR_RANGE;
    }
    int64_t sx;
    int64_t sy;
    const uint32_t count = interior_sums_(poly, n, &bb, cross, &sx, &sy);
    if (count == 0u) {
        return PFT_ERR_DEGENERATE;
    }
    if (count > k->cap || k->pix == NULL) {
        return PFT_ERR_NOMEM;
    }
    /* the area centroid of the pixel centres, rounded (ties up) */
    const int32_t cx = (int32_t)floordiv_(2 * sx + (int64_t)count, 2 * (int64_t)count);
    const int32_t cy = (int32_t)floordiv_(2 * sy + (int64_t)count, 2 * (int64_t)count);
    interior_weights_(k, poly, n, &bb, c_q4, cross, cx, cy);
    origin->x = (int16_t)cx;
    origin->y = (int16_t)cy;
    return PFT_OK;
}

/* Length of the segment a-b in Q8 pixels (rounded down). */
static uint64_t seg_len_q8_(const pft_tsa_pt_t *a, const pft_tsa_pt_t *b)
{
    const int64_t dx = b->x - a->x;
    const int64_t dy = b->y - a->y;
    return pft_tsa_isqrt64_((uint64_t)(dx * dx + dy * dy) << 16);
}

pft_status_t pft_tsa_poly_resample(const pft_tsa_pt_t *in, uint32_t n_in, pft_tsa_pt_t *out,
                                   uint32_t n_out)
{
    if (in == NULL || out == NULL || n_in < 3u || n_out == 0u || n_in > 65535u) {
        return PFT_ERR_INVAL;
    }
    uint64_t total = 0u;
    for (uint32_t i = 0; i < n_in; ++i) {
        total += seg_len_q8_(&in[i], &in[(i + 1u) % n_in]);
    }
    if (total == 0u) {
        return PFT_ERR_INVAL;
    }
    uint64_t seg_start = 0u;
    uint32_t e = 0u; /* current edge: in[e] to in[e + 1] */
    for (uint32_t j = 0; j < n_out; ++j) {
        const uint64_t s = total * j / n_out; /* arc length of point j */
        uint64_t len = seg_len_q8_(&in[e], &in[(e + 1u) % n_in]);
        while (s >= seg_start + len && e + 1u < n_in) { /* bounded: e < n_in */
            seg_start += len;
            ++e;
            len = seg_len_q8_(&in[e], &in[(e + 1u) % n_in]);
        }
        const pft_tsa_pt_t *a = &in[e];
        const pft_tsa_pt_t *b = &in[(e + 1u) % n_in];
        const int64_t dx = b->x - a->x;
        const int64_t dy = b->y - a->y;
        int64_t f = len > 0u ? (int64_t)(((s - seg_start) << 16) / len) : 0; /* Q16 fraction */
        if (f > 65536) {
            f = 65536;
        }
        out[j].x = (int16_t)(a->x + ((dx * f + 32768) >> 16));
        out[j].y = (int16_t)(a->y + ((dy * f + 32768) >> 16));
    }
    return PFT_OK;
}
