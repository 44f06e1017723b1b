/*
 * The tracker's fast path to kernel histograms (docs/algorithms.md 4.3): a per-frame code map of
 * the region the kernel placements cover, the kernel as row spans, a 110-bin joint histogram
 * folded into the 30 bins. Integer arithmetic; the sums equal pft_tsa_hist's.
 */
#include <string.h>

#include "tsa_int.h"

/* Joint bins: 10 r + g (0..99), then 100 + b. */
#define JBINS_ 110u

/* The bin of a channel value, (v * 10) >> 8, and its multiples used by the codes, as constant
 * tables (read-only memory, not stack: they were three 256-byte arrays of every view). */
#define BIN_(v) ((uint8_t)(((uint32_t)(v) * 10u) >> 8))
#define BIN10_(v) ((uint8_t)(10u * BIN_(v)))
#define BIN100_(v) ((uint8_t)(100u + BIN_(v)))
#define R16_(F, b)                                                                            \
    F((b) + 0u), F((b) + 1u), F((b) + 2u), F((b) + 3u), F((b) + 4u), F((b) + 5u), F((b) + 6u), \
        F((b) + 7u), F((b) + 8u), F((b) + 9u), F((b) + 10u), F((b) + 11u), F((b) + 12u),      \
        F((b) + 13u), F((b) + 14u), F((b) + 15u)
#define T256_(F)                                                                              \
    R16_(F, 0u), R16_(F, 16u), R16_(F, 32u), R16_(F, 48u), R16_(F, 64u), R16_(F, 80u),          \
        R16_(F, 96u), R16_(F, 112u), R16_(F, 128u), R16_(F, 144u), R16_(F, 160u),            \
        R16_(F, 176u), R16_(F, 192u), R16_(F, 208u), R16_(F, 224u), R16_(F, 240u)
static const uint8_t bin_[256] = {T256_(BIN_)};
static const uint8_t bin10_[256] = {T256_(BIN10_)};
static const uint8_t bin100_[256] = {T256_(BIN100_)};

uint32_t pft_tsa_spans_(const pft_tsa_kernel_t *k, pft_tsa_span_t *out, uint32_t cap,
                        uint16_t *w)
{
    for (uint32_t i = 0; i < k->n; ++i) {
        w[i] = k->pix[i].w;
    }
    uint32_t n = 0u;
    uint32_t i = 0u;
    while (i < k->n) { /* bounded: i grows by the span's length (at least 1) */
        const pft_tsa_kpix_t *p = &k->pix[i];
        uint32_t len = 1u;
        while (i + len < k->n && len < 65535u && k->pix[i + len].dy == p->dy &&
               k->pix[i + len].dx == p->dx + (int32_t)len) {
            ++len;
        }
        if (n == cap) {
            return cap + 1u;
        }
        out[n].dy = p->dy;
        out[n].dx0 = p->dx;
        out[n].n = (uint16_t)len;
        ++n;
        i += len;
    }
    return n;
}

void pft_tsa_view_init_(pft_tsa_view_t_ *v, const pft_frame_t *frame)
{
    v->f = frame;
    pft_tsa_channels_(frame->format, &v->off[0], &v->off[1], &v->off[2], &v->bpp);
    v->map = NULL;
    v->map_b = NULL;
    v->mx0 = 0;
    v->my0 = 0;
    v->mw = 0;
    v->mh = 0;
}

/* The code of the pixel at p: the joint bin 10 r + g in the low byte, 100 + b in the high. */
static inline uint32_t code_(const pft_tsa_view_t_ *v, const uint8_t *p)
{
    return ((uint32_t)bin10_[p[v->off[0]]] + bin_[p[v->off[1]]]) |
           ((uint32_t)bin100_[p[v->off[2]]] << 8);
}

void pft_tsa_view_map_(pft_tsa_view_t_ *v, uint8_t *map, size_t cap, int32_t x0, int32_t y0,
                       int32_t x1, int32_t y1)
{
    const int32_t W = (int32_t)v->f->width;
    const int32_t H = (int32_t)v->f->height;
    v->mw = 0;
    v->mh = 0;
    x0 = x0 < 0 ? 0 : x0;
    y0 = y0 < 0 ? 0 : y0;
    x1 = x1 >= W ? W - 1 : x1;
    y1 = y1 >= H ? H - 1 : y1;
    if (map == NULL || x1 < x0 || y1 < y0 ||
        (size_t)(x1 - x0 + 1) * (size_t)(y1 - y0 + 1) > cap) {
        return;
    }
    const int32_t mw = x1 - x0 + 1;
    const int32_t mh = y1 - y0 + 1;
    const size_t plane = (size_t)mw * (size_t)mh;
    for (int32_t y = 0; y < mh; ++y) {
        const uint8_t *p = pft_frame_row(v->f, (uint32_t)(y0 + y)) + (uint32_t)x0 * v->bpp;
        uint8_t *m = &map[(size_t)y * (size_t)mw];
        uint8_t *mb = m + plane;
        const uint8_t *p0 = p + v->off[0];
        const uint8_t *p1 = p + v->off[1];
        const uint8_t *p2 = p + v->off[2];
        for (int32_t x = 0; x < mw; ++x) {
            const uint32_t o = (uint32_t)x * v->bpp;
            m[x] = (uint8_t)(bin10_[p0[o]] + bin_[p1[o]]);
            mb[x] = bin100_[p2[o]];
        }
    }
    v->map = map;
    v->map_b = map + plane;
    v->mx0 = x0;
    v->my0 = y0;
    v->mw = mw;
    v->mh = mh;
}

/* Adds the weights w[0..n) to the joint bins a[0..n) and b[0..n) (four pixels a round). */
static inline void add_codes_(uint32_t *jb, const uint8_t *a, const uint8_t *b, const uint16_t *w,
                              uint32_t n)
{
    uint32_t j = 0u;
    for (; j + 3u < n; j += 4u) {
        const uint32_t w0 = w[j];
        const uint32_t w1 = w[j + 1u];
        const uint32_t w2 = w[j + 2u];
        const uint32_t w3 = w[j + 3u];
        jb[a[j]] += w0;
        jb[b[j]] += w0;
        jb[a[j + 1u]] += w1;
        jb[b[j + 1u]] += w1;
        jb[a[j + 2u]] += w2;
        jb[b[j + 2u]] += w2;
        jb[a[j + 3u]] += w3;
        jb[b[j + 3u]] += w3;
    }
    for (; j < n; ++j) {
        jb[a[j]] += w[j];
        jb[b[j]] += w[j];
    }
}

/* The same, coding the frame pixels from p on. */
static inline void add_pixels_(const pft_tsa_view_t_ *v, uint32_t *jb, const uint8_t *p,
                               const uint16_t *kw, uint32_t n)
{
    for (uint32_t j = 0; j < n; ++j) {
        const uint32_t code = code_(v, p);
        const uint32_t w = kw[j];
        jb[code & 0xFFu] += w;
        jb[code >> 8] += w;
        p += v->bpp;
    }
}

void pft_tsa_view_hist_(const pft_tsa_view_t_ *v, const pft_tsa_kernel_t *k,
                        const pft_tsa_span_t *sp, uint32_t nsp, const uint16_t *kw, int32_t cx,
                        int32_t cy, pft_tsa_hist_t *h, uint32_t *jb)
{
    const int32_t W = (int32_t)v->f->width;
    const int32_t H = (int32_t)v->f->height;
    memset(jb, 0, JBINS_ * sizeof(uint32_t));
    uint32_t total = 0u;
    const bool inside = cx + k->x0 >= 0 && cy + k->y0 >= 0 && cx + k->x1 < W && cy + k->y1 < H;
    const bool mapped = v->mw > 0 && cx + k->x0 >= v->mx0 && cy + k->y0 >= v->my0 &&
                        cx + k->x1 < v->mx0 + v->mw && cy + k->y1 < v->my0 + v->mh;
    const uint16_t *kp = kw;
    if (mapped) {
        /* the map lies inside the frame: every pixel is in view */
        const int32_t o = (cy - v->my0) * v->mw + (cx - v->mx0);
        for (uint32_t i = 0; i < nsp; ++i) {
            const int32_t oi = o + sp[i].dy * v->mw + sp[i].dx0;
            add_codes_(jb, v->map + oi, v->map_b + oi, kp, sp[i].n);
            kp += sp[i].n;
        }
        total = k->sum;
    } else if (inside) {
        for (uint32_t i = 0; i < nsp; ++i) {
            const uint8_t *p = pft_frame_row(v->f, (uint32_t)(cy + sp[i].dy)) +
                               (uint32_t)(cx + sp[i].dx0) * v->bpp;
            add_pixels_(v, jb, p, kp, sp[i].n);
            kp += sp[i].n;
        }
        total = k->sum;
    } else {
        for (uint32_t i = 0; i < nsp; ++i) {
            const int32_t y = cy + sp[i].dy;
            int32_t x0 = cx + sp[i].dx0;
            int32_t x1 = x0 + (int32_t)sp[i].n; /* exclusive */
            const uint16_t *kq = kp;
            kp += sp[i].n;
            if (y < 0 || y >= H || x1 <= 0 || x0 >= W) {
                continue;
            }
            if (x0 < 0) {
                kq += -x0;
                x0 = 0;
            }
            x1 = x1 > W ? W : x1;
            const uint32_t n = (uint32_t)(x1 - x0);
            add_pixels_(v, jb, pft_frame_row(v->f, (uint32_t)y) + (uint32_t)x0 * v->bpp, kq, n);
            for (uint32_t j = 0; j < n; ++j) {
                total += kq[j];
            }
        }
    }
    /* fold: R bin r = sum over g of joint (r, g), G bin g = sum over r, B bins as they are */
    uint32_t sg[10];
    memcpy(sg, jb, sizeof(sg));
    h->bin[0] = jb[0] + jb[1] + jb[2] + jb[3] + jb[4] + jb[5] + jb[6] + jb[7] + jb[8] + jb[9];
    for (uint32_t r = 1; r < 10u; ++r) {
        const uint32_t *row = &jb[r * 10u];
        uint32_t sr = 0u;
        for (uint32_t g = 0; g < 10u; ++g) {
            sr += row[g];
            sg[g] += row[g];
        }
        h->bin[r] = sr;
    }
    memcpy(&h->bin[10], sg, sizeof(sg));
    memcpy(&h->bin[20], &jb[100], 10u * sizeof(uint32_t));
    h->total = total;
}
