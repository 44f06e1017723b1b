/* Clutter map of the whitened residual (pft_pre.h, pft_pre_clutter_*; docs/algorithms.md
 * 9.9). Integer arithmetic only: the map m in sigma^2 Q6.10 (u16), the mean mu in sigma Q4.11
 * (u16, offset by 2^15), residuals in Q8.8 sigma; the warp's weights in Q8. */
#include <string.h>

#include "pft/pft_pre.h"
#include "../core/config_int.h"
#include "pre_int.h"

#define CL_ONE_ 1024u          /* 1 sigma^2 in Q6.10: the map's value where nothing is known */
#define CL_MMAX_ 65535u        /* largest map value (64 sigma^2 less one unit) */
#define CL_SQMAX_ 4194304u     /* 64 sigma^2 in Q16 (a squared Q8.8 value) */
#define CL_MUMAX_ 16384        /* 8 sigma in Q4.11 */
#define CL_MUOFF_ 32768u       /* offset of mu while warped (unsigned arithmetic) */

void pft_pre_clutter_config_default(pft_pre_clutter_config_t *cfg)
{
    if (cfg == NULL) {
        return;
    }
    memset(cfg, 0, sizeof(*cfg));
    cfg->width = 384u;
    cfg->height = 288u;
    cfg->alpha = 6554u;
    cfg->blur = 1u;
    cfg->box = true;
    cfg->mean = false;
    cfg->thr = 2048u;
    cfg->veto = 0u;
    cfg->persist = 0u;
    cfg->excess = 384u;
    cfg->inplace = false;
    cfg->block = 0u;
}

pft_status_t pft_pre_clutter_config_check(const pft_pre_clutter_config_t *cfg, const char **field)
{
    const char *bad = NULL;
    if (cfg == NULL) {
        return pft_config_verdict_(false, NULL, field);
    }
    if (cfg->width < 8u || cfg->width > PFT_CFG_MAX_IMAGE_SIDE) {
        bad = "width";
    } else if (cfg->height < 8u || cfg->height > PFT_CFG_MAX_IMAGE_SIDE) {
        bad = "height";
    } else if (cfg->alpha == 0u) {
        bad = "alpha";
    } else if (cfg->blur > PFT_PRE_CLUTTER_MAX_BLUR) {
        bad = "blur";
    } else if (cfg->thr < CL_ONE_) {
        bad = "thr";
    } else if (cfg->veto != 0u && cfg->veto < cfg->thr) {
        bad = "veto";
    } else if (cfg->persist > PFT_PRE_CLUTTER_MAX_PERSIST || (cfg->persist != 0u && !cfg->mean)) {
        bad = "persist";
    } else if (cfg->persist != 0u && (cfg->excess == 0u || cfg->excess > 32767u)) {
        bad = "excess";
    } else if (cfg->block != 0u && cfg->block != 2u && cfg->block != 4u) {
        bad = "block";
    } else {
        /* accepted */
    }
    return pft_config_verdict_(true, bad, field);
}

size_t pft_pre_clutter_workspace_size(const pft_pre_clutter_config_t *cfg)
{
    if (pft_pre_clutter_config_check(cfg, NULL) != PFT_OK) {
        return 0u;
    }
    return PFT_PRE_CLUTTER_WORKSPACE_BYTES_BLOCK(cfg->width, cfg->height, cfg->mean ? 1u : 0u,
                                                 cfg->blur, cfg->persist != 0u ? 1u : 0u,
                                                 cfg->block, cfg->inplace ? 1u : 0u);
}

pft_status_t pft_pre_clutter_init(pft_pre_clutter_t *c, const pft_pre_clutter_config_t *cfg,
                                  void *work, size_t work_len)
{
    if (c == NULL || cfg == NULL || work == NULL) {
        return PFT_ERR_INVAL;
    }
    if (pft_pre_clutter_config_check(cfg, NULL) != PFT_OK) {
        return PFT_ERR_CONFIG;
    }
    const size_t w = cfg->width, h = cfg->height;
    /* the map's grid: pixels, or blocks of block x block pixels (the last ones cut) */
    uint32_t lb = 0u; /* per pixel */
    if (cfg->block == 4u) {
        lb = 2u;
    } else if (cfg->block == 2u) {
        lb = 1u;
    } else {
        /* block 0: the grid is the frame */
    }
    const size_t k = (size_t)1u << lb;
    const size_t gw = (w + k - 1u) / k, gh = (h + k - 1u) / k;
    pft_ws_t ws;
    pft_ws_init(&ws, work, work_len);
    uint16_t *m = pft_ws_take(&ws, gw * gh * 2u);
    int16_t *out = cfg->inplace ? NULL : pft_ws_take(&ws, w * h * 2u);
    uint16_t *mu = cfg->mean ? pft_ws_take(&ws, gw * gh * 2u) : NULL;
    uint16_t *pc = cfg->persist != 0u ? pft_ws_take(&ws, gw * gh * 2u) : NULL;
    uint16_t *ring = pft_ws_take(&ws, ((size_t)cfg->blur + 1u) * gw * 2u);
    uint32_t *vs = pft_ws_take(&ws, gw * 4u);
    uint32_t *hs = pft_ws_take(&ws, gw * 4u);
    uint32_t *acc = lb != 0u ? pft_ws_take(&ws, gw * 8u) : NULL;
    int32_t *sacc = lb != 0u ? pft_ws_take(&ws, gw * 8u) : NULL;
    if (pft_ws_status(&ws) != PFT_OK) {
        return PFT_ERR_NOMEM;
    }
    memset(c, 0, sizeof(*c));
    c->cfg = *cfg;
    c->gw = (uint32_t)gw;
    c->gh = (uint32_t)gh;
    c->lb = lb;
    c->acc = acc;
    c->sacc = sacc;
    c->m = m;
    c->out = out;
    c->mu = mu;
    c->pc = pc;
    c->ring = ring;
    c->vs = vs;
    c->hs = hs;
    return pft_pre_clutter_reset(c);
}

pft_status_t pft_pre_clutter_reset(pft_pre_clutter_t *c)
{
    if (c == NULL || c->m == NULL) {
        return PFT_ERR_INVAL;
    }
    const size_t npix = (size_t)c->cfg.width * (size_t)c->cfg.height;
    const size_t gw = c->gw, ng = gw * (size_t)c->gh; /* the map's grid */
    for (size_t i = 0u; i < ng; ++i) {
        c->m[i] = (uint16_t)CL_ONE_;
    }
    if (c->cfg.inplace) {
        c->out = NULL; /* the caller's buffer of the next update */
    } else {
        memset(c->out, 0, npix * 2u);
    }
    for (size_t i = 0u; c->mu != NULL && i < ng; ++i) {
        c->mu[i] = (uint16_t)CL_MUOFF_;
    }
    if (c->pc != NULL) {
        memset(c->pc, 0, ng * 2u);
    }
    memset(c->ring, 0, ((size_t)c->cfg.blur + 1u) * gw * 2u);
    memset(c->vs, 0, gw * 4u);
    memset(c->hs, 0, gw * 4u);
    if (c->acc != NULL) {
        memset(c->acc, 0, gw * 8u);
        memset(c->sacc, 0, gw * 8u);
    }
    c->frames = 0u;
    c->updates = 0u;
    c->seq = 0u;
    c->timestamp_us = 0u;
    return PFT_OK;
}

/* a * d / 2^16 rounded half away from zero (|a| <= 2^16, |d| < 2^17). */
static int32_t cl_scale_(uint32_t a, int32_t d)
{
    const uint64_t mag = (uint64_t)a * (uint64_t)(d < 0 ? -(int64_t)d : (int64_t)d);
    const int32_t q = (int32_t)((mag + 32768u) >> 16);
    return d < 0 ? -q : q;
}

/* n / d rounded half away from zero (d > 0). */
static int32_t cl_div_(int32_t n, int32_t d)
{
    const int32_t mag = n < 0 ? -n : n;
    const int32_t q = (mag + d / 2) / d;
    return n < 0 ? -q : q;
}

/* Floor and Q8 fraction of a Q16.16 shift of s / 2^lb grid steps (lb 0: pixels), the fraction
 * rounded to 1/256 step. */
static void cl_split_(int32_t s, uint32_t lb, int32_t *ip, uint32_t *fp)
{
    const int64_t d = (int64_t)((uint64_t)256u << lb);
    const int64_t q8 = ((int64_t)s + d / 2) / d - (((int64_t)s + d / 2) % d < 0 ? 1 : 0);
    /* q8 = floor((s + d / 2) / d): the shift in Q8 steps, rounded (lb 0: floor((s + 128) / 256)) */
    const int64_t i = q8 / 256 - ((q8 % 256) < 0 ? 1 : 0);
    *ip = (int32_t)i;
    *fp = (uint32_t)(q8 - i * 256);
}

/* Source value of the warp: v[sy][sx], or border b outside the frame. */
static uint32_t cl_src_(const uint16_t *v, int32_t sx, int32_t sy, int32_t w, int32_t h,
                        uint32_t b)
{
    if (sx < 0 || sy < 0 || sx >= w || sy >= h) {
        return b;
    }
    return v[(size_t)sy * (size_t)w + (size_t)sx];
}

/* Columns [xa, xb) of row y of the warp (see cl_warp_) into t, sources tested one by one. */
static void cl_warp_cols_(const uint16_t *v, uint32_t *t, int32_t xa, int32_t xb, int32_t y,
                          int32_t ix, int32_t iy, int32_t w, int32_t h, uint32_t fx, uint32_t fy,
                          uint32_t b)
{
    const int32_t y1 = y - iy, y0 = y1 - 1;
    for (int32_t x = xa; x < xb; ++x) {
        const uint32_t a1 = cl_src_(v, x - ix, y1, w, h, b) * (256u - fx) +
                            cl_src_(v, x - ix - 1, y1, w, h, b) * fx;
        const uint32_t a0 = cl_src_(v, x - ix, y0, w, h, b) * (256u - fx) +
                            cl_src_(v, x - ix - 1, y0, w, h, b) * fx;
        t[x] = (a1 * (256u - fy) + a0 * fy + 32768u) >> 16;
    }
}

/* Warps v (u16 values) in place by (ix + fx / 256, iy + fy / 256) px: out(p) = v(p - shift),
 * bilinear, b outside. Each row is made in t (w values) and copied back; rows are visited in
 * the order that reads every source row before it is overwritten (descending where the
 * sources lie at lower rows). */
static void cl_warp_(uint16_t *v, uint32_t *t, int32_t w, int32_t h, int32_t ix, uint32_t fx,
                     int32_t iy, uint32_t fy, uint32_t b)
{
    const bool ydown = iy >= 0;
    const uint32_t gx = 256u - fx, gy = 256u - fy;
    /* columns whose two sources are inside: x - ix - 1 >= 0 and x - ix < w */
    const int32_t xlo = ix + 1 < 0 ? 0 : (ix + 1 > w ? w : ix + 1);
    const int32_t xhi = ix > 0 ? w : (w + ix < xlo ? xlo : w + ix);
    for (int32_t k = 0; k < h; ++k) {
        const int32_t y = ydown ? h - 1 - k : k;
        const int32_t y1 = y - iy, y0 = y1 - 1; /* weights 256 - fy, fy */
        const bool in1 = y1 >= 0 && y1 < h, in0 = y0 >= 0 && y0 < h;
        if (in1 && in0 && xlo < xhi) {
            const size_t c0 = (size_t)(xlo - ix - 1); /* >= 0: the first interior column's x0 */
            const uint16_t *r1 = v + (size_t)y1 * (size_t)w + c0;
            const uint16_t *r0 = v + (size_t)y0 * (size_t)w + c0;
            /* r[i] is column xlo - ix - 1 + i: x0 of x = xlo + i */
            for (int32_t x = xlo; x < xhi; ++x) {
                const int32_t i = x - xlo;
                const uint32_t a1 = (uint32_t)r1[i + 1] * gx + (uint32_t)r1[i] * fx;
                const uint32_t a0 = (uint32_t)r0[i + 1] * gx + (uint32_t)r0[i] * fx;
                t[x] = (a1 * gy + a0 * fy + 32768u) >> 16;
            }
        } else {
            cl_warp_cols_(v, t, xlo, xhi, y, ix, iy, w, h, fx, fy, b);
        }
        cl_warp_cols_(v, t, 0, xlo, y, ix, iy, w, h, fx, fy, b);
        cl_warp_cols_(v, t, xhi, w, y, ix, iy, w, h, fx, fy, b);
        uint16_t *o = v + (size_t)y * (size_t)w;
        for (int32_t x = 0; x < w; ++x) {
            o[x] = (uint16_t)t[x];
        }
    }
}

/* The map's former row r (0..h-1) while row y is updated: rows above y come from the ring. */
static const uint16_t *cl_row_(const pft_pre_clutter_t *c, int32_t r, int32_t y)
{
    const int32_t h = (int32_t)c->gh;
    const int32_t rr = r < 0 ? 0 : (r >= h ? h - 1 : r);
    if (rr <= y) {
        return c->ring + (size_t)((uint32_t)rr % ((uint32_t)c->cfg.blur + 1u)) * c->gw;
    }
    return c->m + (size_t)rr * c->gw;
}

/* Read value of the map at every pixel of row y (before its update): the sum over the square
 * (box) or its largest value, Q6.10, into c->hs (c->vs: the vertical pass). */
static void cl_read_row_(pft_pre_clutter_t *c, int32_t y)
{
    const int32_t b = (int32_t)c->cfg.blur, w = (int32_t)c->gw;
    uint32_t *vs = c->vs;
    const uint16_t *r0 = cl_row_(c, y - b, y);
    for (int32_t x = 0; x < w; ++x) {
        vs[x] = r0[x];
    }
    for (int32_t k = -b + 1; k <= b; ++k) {
        const uint16_t *r = cl_row_(c, y + k, y);
        if (c->cfg.box) {
            for (int32_t x = 0; x < w; ++x) {
                vs[x] += r[x];
            }
        } else {
            for (int32_t x = 0; x < w; ++x) {
                vs[x] = r[x] > vs[x] ? r[x] : vs[x];
            }
        }
    }
    /* horizontal: sum (box) or largest value over 2 b + 1 columns, edges replicated */
    uint32_t *hs = c->hs;
    if (c->cfg.box) {
        /* interior columns b .. w - b - 1: the 2 b + 1 terms summed directly, one plain
         * (vectorisable) pass per term; the same sums as the running box of the edges */
        const int32_t xi0 = b, xi1 = w - b > b ? w - b : b;
        for (int32_t x = xi0; x < xi1; ++x) {
            hs[x] = vs[x - b];
        }
        for (int32_t k = -b + 1; k <= b; ++k) {
            for (int32_t x = xi0; x < xi1; ++x) {
                hs[x] += vs[x + k];
            }
        }
        /* the edge columns: the same sum with the columns beyond the edge replicated */
        for (int32_t e = 0; e < 2 * b; ++e) {
            const int32_t x = e < b ? e : xi1 + (e - b); /* columns 0 .. b - 1, w - b .. w - 1 */
            uint32_t acc = 0u;
            for (int32_t k = -b; k <= b; ++k) {
                acc += vs[x + k < 0 ? 0 : (x + k >= w ? w - 1 : x + k)];
            }
            hs[x] = acc;
        }
    } else {
        for (int32_t x = 0; x < w; ++x) {
            uint32_t acc = vs[x];
            for (int32_t k = -b; k <= b; ++k) {
                const int32_t xx = x + k < 0 ? 0 : (x + k >= w ? w - 1 : x + k);
                acc = vs[xx] > acc ? vs[xx] : acc;
            }
            hs[x] = acc;
        }
    }
}

/* Row y without the running mean (the default): the same values as the general loop of
 * pft_pre_clutter_update in plain passes: the map's update (it reads r), then the output
 * (which may be r itself, inplace). The output is the residual itself except
 * where the square's read exceeds thr (a masked pixel stays PFT_RES16_MASKED, any other
 * value is within +-PFT_PRE_RMAX_ already), and 0 where it exceeds veto; the map's update runs on every pixel and is kept
 * where the pixel is not masked. Its ranges: t and m in 0..65535, so |t - m| <= 65535 and
 * a |t - m| + 32768 < 2^32 for a <= 2^16 (cl_scale_ in 32 bits). */
static void cl_row_plain_(const int16_t *r, int16_t *o, uint16_t *mrow, const uint32_t *hs,
                          int32_t w, uint32_t a, uint32_t thr, uint32_t veto, uint32_t area)
{
    /* the map's update first: it reads the residual, which o may be (inplace) */
    for (int32_t x = 0; x < w; ++x) {
        const int32_t v = r[x];
        const uint32_t ac = (uint32_t)(v < 0 ? -v : v); /* <= 2^15 */
        const uint32_t sq = ac * ac;                    /* <= 2^30 */
        /* sq >= 2^22 (CL_SQMAX_) gives (sq + 32) >> 6 >= 65536: the clamp alone is the
         * general loop's two tests */
        const uint32_t t0 = (sq + 32u) >> 6;
        const uint32_t t = t0 > CL_MMAX_ ? CL_MMAX_ : t0;
        const uint32_t m = mrow[x];
        const uint32_t q = (a * (t >= m ? t - m : m - t) + 32768u) >> 16;
        const uint32_t nm = t >= m ? m + q : m - q; /* between m and t: no clamp needed */
        mrow[x] = v == PFT_RES16_MASKED ? (uint16_t)m : (uint16_t)nm;
    }
    if (o != r) {
        memcpy(o, r, (size_t)w * 2u);
    }
    uint32_t any = 0u; /* whether some read of the row exceeds thr (a plain pass) */
    for (int32_t x = 0; x < w; ++x) {
        any |= hs[x] > thr ? 1u : 0u;
    }
    for (int32_t x = 0; any != 0u && x < w; ++x) {
        const int32_t v = o[x]; /* r[x]: o is its copy, or r itself */
        if (hs[x] > thr && v != PFT_RES16_MASKED) {
            const uint32_t mm = (hs[x] + area / 2u) / area; /* the square's mean, Q6.10 */
            const uint32_t s = pft_pre_isqrt64_((uint64_t)mm << 10); /* sqrt(M) in Q10 */
            o[x] = hs[x] > veto ? (int16_t)0 : (int16_t)pft_pre_rclamp_(cl_div_(v * 1024, (int32_t)s));
        }
    }
}

/* The map on blocks (cfg.block): block row j (rows j B .. j B + B - 1 of the frame, B =
 * 2^lb) is read once over the block grid (cl_read_row_), every pixel of it is scored with its
 * block's read, then each block of the row is updated with the means over its unmasked pixels
 * of this frame's terms (t = min(c^2, 64), the mean's clamp(r, -8, 8), the gate's r): the
 * formulas of the per-pixel map with the pixel's terms replaced by their block means. A block
 * without an unmasked pixel keeps its values. Each residual row is read before its output row
 * is written (inplace). */
static void cl_update_blocks_(pft_pre_clutter_t *c, const pft_frame_t *res, uint32_t a,
                              uint32_t thr, uint32_t veto, uint32_t area)
{
    const int32_t w = (int32_t)c->cfg.width, h = (int32_t)c->cfg.height;
    const int32_t gw = (int32_t)c->gw, gh = (int32_t)c->gh;
    const uint32_t lb = c->lb, nring = (uint32_t)c->cfg.blur + 1u;
    const uint32_t rs = res->stride_bytes / 2u;
    const uint32_t pk = (uint32_t)c->cfg.persist * 256u, pcap = 2u * pk;
    const uint32_t exc = c->cfg.excess;
    uint32_t *st = c->acc, *sn = c->acc + gw;       /* sum of t (<= 16 * 65535), count */
    int32_t *smu = c->sacc, *sv = c->sacc + gw;     /* sum of clamp(8 r) (Q4.11), sum of r (Q8.8) */
    uint32_t *sc = c->vs;                           /* per block: 0 plain, UINT32_MAX veto, else sqrt(M) Q10 */
    for (int32_t j = 0; j < gh; ++j) {
        uint16_t *mrow = c->m + (size_t)j * (size_t)gw;
        memcpy(c->ring + (size_t)((uint32_t)j % nring) * (size_t)gw, mrow, (size_t)gw * 2u);
        cl_read_row_(c, j);
        for (int32_t i = 0; i < gw; ++i) {
            const uint32_t mb = c->hs[i];
            if (mb > thr) {
                const uint32_t mm = (mb + area / 2u) / area; /* the square's mean, Q6.10 */
                sc[i] = mb > veto ? UINT32_MAX : pft_pre_isqrt64_((uint64_t)mm << 10);
            } else {
                sc[i] = 0u;
            }
        }
        memset(st, 0, (size_t)gw * 8u);
        memset(smu, 0, (size_t)gw * 8u);
        uint16_t *mu = c->mu != NULL ? c->mu + (size_t)j * (size_t)gw : NULL;
        uint16_t *pc = c->pc != NULL ? c->pc + (size_t)j * (size_t)gw : NULL;
        const uint32_t y0 = (uint32_t)j << lb;
        uint32_t y1 = y0 + (1u << lb) < (uint32_t)h ? y0 + (1u << lb) : (uint32_t)h;
        if (mu == NULL) {
            /* without the mean (c = r): plain passes per row, the same values: the block sums
             * of t first (they read r), then the output (r itself where the block's read is
             * not above thr, which may be r's own buffer, inplace) */
            uint32_t any = 0u;
            for (int32_t i = 0; i < gw; ++i) {
                any |= sc[i];
            }
            for (uint32_t y = y0; y < y1; ++y) {
                const int16_t *r = (const int16_t *)res->data + (size_t)y * rs;
                int16_t *o = c->out + (size_t)y * (size_t)w;
                for (int32_t x = 0; x < w; ++x) {
                    const int32_t v = r[x];
                    const uint32_t ac = (uint32_t)(v < 0 ? -v : v); /* <= 2^15 */
                    const uint32_t t0 = (ac * ac + 32u) >> 6;       /* >= 65536 where sq >= CL_SQMAX_ */
                    uint32_t in = 1u; /* whether the pixel enters its block's sums */
                    if (v == PFT_RES16_MASKED) {
                        in = 0u;
                    }
                    const uint32_t i = (uint32_t)x >> lb;
                    st[i] += in * (t0 > CL_MMAX_ ? CL_MMAX_ : t0);
                    sn[i] += in;
                }
                if (o != r) {
                    memcpy(o, r, (size_t)w * 2u);
                }
                for (int32_t x = 0; any != 0u && x < w; ++x) {
                    const int32_t v = o[x]; /* r[x] */
                    const uint32_t sv_ = sc[(uint32_t)x >> lb];
                    if (sv_ != 0u && v != PFT_RES16_MASKED) {
                        o[x] = sv_ == UINT32_MAX ? (int16_t)0 : (int16_t)pft_pre_rclamp_(cl_div_(v * 1024, (int32_t)sv_));
                    }
                }
            }
            y1 = y0; /* the rows are done */
        }
        for (uint32_t y = y0; y < y1; ++y) {
            const int16_t *r = (const int16_t *)res->data + (size_t)y * rs;
            int16_t *o = c->out + (size_t)y * (size_t)w;
            for (int32_t x = 0; x < w; ++x) {
                const int32_t v = r[x];
                if (v == PFT_RES16_MASKED) {
                    o[x] = PFT_RES16_MASKED;
                    continue;
                }
                const uint32_t i = (uint32_t)x >> lb;
                const int32_t cv = mu != NULL ? v - cl_div_((int32_t)mu[i] - (int32_t)CL_MUOFF_, 8) : v;
                const uint32_t s = sc[i];
                const int32_t wv = s == 0u ? cv : (s == UINT32_MAX ? 0 : cl_div_(cv * 1024, (int32_t)s));
                o[x] = (int16_t)pft_pre_rclamp_(wv);
                const uint32_t ac = (uint32_t)(cv < 0 ? -cv : cv);
                const uint64_t sq = (uint64_t)ac * ac;
                st[i] += sq >= CL_SQMAX_ ? CL_MMAX_ : (uint32_t)((sq + 32u) >> 6);
                sn[i] += 1u;
                if (mu != NULL) {
                    smu[i] += v * 8 > CL_MUMAX_ ? CL_MUMAX_ : (v * 8 < -CL_MUMAX_ ? -CL_MUMAX_ : v * 8);
                    sv[i] += v;
                }
            }
        }
        for (int32_t i = 0; i < gw; ++i) {
            const uint32_t n = sn[i];
            if (n == 0u) {
                continue; /* every pixel of the block masked: its values kept */
            }
            const uint32_t t = (st[i] + n / 2u) / n;
            const int32_t nm = (int32_t)mrow[i] + cl_scale_(a, (int32_t)t - (int32_t)mrow[i]);
            mrow[i] = (uint16_t)(nm < 0 ? 0 : (nm > (int32_t)CL_MMAX_ ? (int32_t)CL_MMAX_ : nm));
            if (mu == NULL) {
                continue;
            }
            bool learn = true;
            if (pc != NULL) {
                const int32_t rb = cl_div_(sv[i], (int32_t)n); /* the block's mean r, Q8.8 */
                const uint32_t av = (uint32_t)(rb < 0 ? -rb : rb);
                const uint32_t p0 = pc[i];
                const uint32_t p1 = av > exc ? (p0 + 256u > pcap ? pcap : p0 + 256u)
                                             : (p0 > 128u ? p0 - 128u : 0u);
                pc[i] = (uint16_t)p1;
                learn = av <= exc || p1 >= pk;
            }
            if (learn) {
                const int32_t tv = cl_div_(smu[i], (int32_t)n);
                const int32_t mv = (int32_t)mu[i] - (int32_t)CL_MUOFF_;
                mu[i] = (uint16_t)(mv + cl_scale_(a, tv - mv) + (int32_t)CL_MUOFF_);
            }
        }
    }
}

/* PFT_OK or PFT_ERR_FORMAT: whether res is a residual frame of the configured size. */
static pft_status_t cl_check_frame_(const pft_pre_clutter_t *c, const pft_frame_t *res)
{
    if (res->format != PFT_PIX_RES16 || res->width != c->cfg.width ||
        res->height != c->cfg.height || res->stride_bytes < 2u * (uint32_t)c->cfg.width ||
        (res->stride_bytes & 1u) != 0u) {
        return PFT_ERR_FORMAT;
    }
    return PFT_OK;
}

/* One accepted frame; the output goes to c->out (packed rows), which is the residual's own
 * buffer with inplace: each residual row is read before its output row is written, and not
 * after. */
static void cl_update_(pft_pre_clutter_t *c, const pft_frame_t *res, int32_t shift_x,
                       int32_t shift_y, bool evidence)
{
    const int32_t w = (int32_t)c->cfg.width, h = (int32_t)c->cfg.height;
    const size_t npix = (size_t)w * (size_t)h;
    c->updates++;
    c->seq = res->seq;
    c->timestamp_us = res->timestamp_us;
    if (!evidence) {
        for (size_t i = 0u; i < npix; ++i) {
            c->out[i] = PFT_RES16_MASKED;
        }
        return;
    }
    if (c->frames > 0u) {
        int32_t ix, iy;
        uint32_t fx, fy;
        const int32_t gw = (int32_t)c->gw, gh = (int32_t)c->gh;
        cl_split_(shift_x, c->lb, &ix, &fx);
        cl_split_(shift_y, c->lb, &iy, &fy);
        if (ix != 0 || iy != 0 || fx != 0u || fy != 0u) {
            /* beyond the frame, every pixel enters: the warp's indices stay in range */
            ix = ix > gw ? gw : (ix < -gw ? -gw : ix);
            iy = iy > gh ? gh : (iy < -gh ? -gh : iy);
            cl_warp_(c->m, c->hs, gw, gh, ix, fx, iy, fy, CL_ONE_);
            if (c->mu != NULL) {
                cl_warp_(c->mu, c->hs, gw, gh, ix, fx, iy, fy, CL_MUOFF_);
            }
            if (c->pc != NULL) {
                cl_warp_(c->pc, c->hs, gw, gh, ix, fx, iy, fy, 0u);
            }
        }
    }
    c->frames++;
    const uint32_t a1 = (65536u + c->frames / 2u) / c->frames;
    const uint32_t a = a1 > c->cfg.alpha ? a1 : c->cfg.alpha;
    const uint32_t rs = res->stride_bytes / 2u;
    const uint32_t nring = (uint32_t)c->cfg.blur + 1u;
    const uint32_t area = c->cfg.box ? (2u * nring - 1u) * (2u * nring - 1u) : 1u;
    const uint32_t thr = (uint32_t)c->cfg.thr * area; /* on the square's sum (box) */
    const uint32_t veto = c->cfg.veto != 0u ? (uint32_t)c->cfg.veto * area : UINT32_MAX;
    /* persistence gate: the counter in frames Q8, its cap 2 k and its opening level k */
    const uint32_t pk = (uint32_t)c->cfg.persist * 256u, pcap = 2u * pk;
    const uint32_t exc = c->cfg.excess;
    if (c->lb != 0u) {
        cl_update_blocks_(c, res, a, thr, veto, area);
        return;
    }
    for (int32_t y = 0; y < h; ++y) {
        uint16_t *mrow = c->m + (size_t)y * (size_t)w;
        memcpy(c->ring + (size_t)((uint32_t)y % nring) * (size_t)w, mrow, (size_t)w * 2u);
        cl_read_row_(c, y);
        const int16_t *r = (const int16_t *)res->data + (size_t)y * rs;
        int16_t *o = c->out + (size_t)y * (size_t)w;
        uint16_t *mu = c->mu != NULL ? c->mu + (size_t)y * (size_t)w : NULL;
        uint16_t *pc = c->pc != NULL ? c->pc + (size_t)y * (size_t)w : NULL;
        if (mu == NULL && pc == NULL) {
            cl_row_plain_(r, o, mrow, c->hs, w, a, thr, veto, area);
            continue;
        }
        for (int32_t x = 0; x < w; ++x) {
            const int32_t v = r[x];
            if (v == PFT_RES16_MASKED) {
                o[x] = PFT_RES16_MASKED;
                continue;
            }
            const int32_t cv = mu != NULL ? v - cl_div_((int32_t)mu[x] - (int32_t)CL_MUOFF_, 8) : v;
            const uint32_t mb = c->hs[x];
            int32_t wv = cv;
            if (mb > thr) {
                const uint32_t mm = (mb + area / 2u) / area; /* the square's mean, Q6.10 */
                const uint32_t s = pft_pre_isqrt64_((uint64_t)mm << 10); /* sqrt(M) in Q10 */
                wv = mb > veto ? 0 : cl_div_(cv * 1024, (int32_t)s);
            }
            o[x] = (int16_t)pft_pre_rclamp_(wv);
            bool learn = true; /* whether the mean takes this frame's residual */
            if (pc != NULL) {
                /* the gate reads the stage's residual v: clutter that the mean has learnt
                 * keeps its counter */
                const uint32_t av = (uint32_t)(v < 0 ? -v : v);
                const uint32_t p0 = pc[x];
                const uint32_t p1 = av > exc ? (p0 + 256u > pcap ? pcap : p0 + 256u)
                                             : (p0 > 128u ? p0 - 128u : 0u);
                pc[x] = (uint16_t)p1;
                learn = av <= exc || p1 >= pk; /* else an excess that has not persisted */
            }
            const uint32_t ac = (uint32_t)(cv < 0 ? -cv : cv);
            const uint64_t sq = (uint64_t)ac * ac;
            const uint32_t t = sq >= CL_SQMAX_ ? CL_MMAX_ : (uint32_t)((sq + 32u) >> 6);
            const int32_t nm = (int32_t)mrow[x] + cl_scale_(a, (int32_t)(t > CL_MMAX_ ? CL_MMAX_ : t) - (int32_t)mrow[x]);
            mrow[x] = (uint16_t)(nm < 0 ? 0 : (nm > (int32_t)CL_MMAX_ ? (int32_t)CL_MMAX_ : nm));
            if (mu != NULL && learn) {
                const int32_t tv = v * 8 > CL_MUMAX_ ? CL_MUMAX_ : (v * 8 < -CL_MUMAX_ ? -CL_MUMAX_ : v * 8);
                const int32_t mv = (int32_t)mu[x] - (int32_t)CL_MUOFF_;
                mu[x] = (uint16_t)(mv + cl_scale_(a, tv - mv) + (int32_t)CL_MUOFF_);
            }
        }
    }
}

pft_status_t pft_pre_clutter_update(pft_pre_clutter_t *c, const pft_frame_t *res,
                                    int32_t shift_x, int32_t shift_y, bool evidence)
{
    if (c == NULL || c->m == NULL || res == NULL || res->data == NULL) {
        return PFT_ERR_INVAL;
    }
    if (c->cfg.inplace) {
        return PFT_ERR_STATE; /* pft_pre_clutter_update_inplace: the output has no buffer here */
    }
    const pft_status_t s = cl_check_frame_(c, res);
    if (s != PFT_OK) {
        return s;
    }
    cl_update_(c, res, shift_x, shift_y, evidence);
    return PFT_OK;
}

pft_status_t pft_pre_clutter_update_inplace(pft_pre_clutter_t *c, const pft_frame_t *res,
                                            int16_t *pixels, int32_t shift_x, int32_t shift_y,
                                            bool evidence)
{
    if (c == NULL || c->m == NULL || res == NULL || pixels == NULL) {
        return PFT_ERR_INVAL;
    }
    if (!c->cfg.inplace) {
        return PFT_ERR_STATE;
    }
    if (res->data != (const void *)pixels) {
        return PFT_ERR_INVAL;
    }
    const pft_status_t s = cl_check_frame_(c, res);
    if (s != PFT_OK) {
        return s;
    }
    if (res->stride_bytes != 2u * (uint32_t)res->width) {
        return PFT_ERR_FORMAT; /* the output's rows are packed */
    }
    /* every check is above: from here the residual becomes the output, row by row */
    c->out = pixels;
    cl_update_(c, res, shift_x, shift_y, evidence);
    return PFT_OK;
}

pft_status_t pft_pre_clutter_frame(const pft_pre_clutter_t *c, pft_frame_t *out)
{
    if (c == NULL || out == NULL) {
        return PFT_ERR_INVAL;
    }
    if (c->updates == 0u) {
        return PFT_ERR_STATE;
    }
    memset(out, 0, sizeof(*out));
    out->data = c->out;
    out->width = c->cfg.width;
    out->height = c->cfg.height;
    out->stride_bytes = 2u * (uint32_t)c->cfg.width;
    out->format = PFT_PIX_RES16;
    out->bit_depth = 16u;
    out->timestamp_us = c->timestamp_us;
    out->seq = c->seq;
    return PFT_OK;
}

pft_status_t pft_pre_clutter_raise(pft_pre_clutter_t *c, uint32_t x, uint32_t y, uint16_t level)
{
    if (c == NULL || c->m == NULL || x >= c->cfg.width || y >= c->cfg.height) {
        return PFT_ERR_INVAL;
    }
    const uint32_t w = c->cfg.width, h = c->cfg.height, lb = c->lb;
    const uint32_t y0 = y > 0u ? y - 1u : 0u, y1 = y + 1u < h ? y + 1u : h - 1u;
    const uint32_t x0 = x > 0u ? x - 1u : 0u, x1 = x + 1u < w ? x + 1u : w - 1u;
    /* the entries of the map that hold those pixels (blocks: each once) */
    for (uint32_t yy = y0 >> lb; yy <= y1 >> lb; ++yy) {
        for (uint32_t xx = x0 >> lb; xx <= x1 >> lb; ++xx) {
            uint16_t *m = &c->m[(size_t)yy * c->gw + xx];
            *m = *m < level ? level : *m;
        }
    }
    return PFT_OK;
}

uint32_t pft_pre_clutter_at(const pft_pre_clutter_t *c, uint32_t x, uint32_t y)
{
    if (c == NULL || c->m == NULL || x >= c->cfg.width || y >= c->cfg.height) {
        return 0u;
    }
    return c->m[(size_t)(y >> c->lb) * c->gw + (x >> c->lb)];
}
