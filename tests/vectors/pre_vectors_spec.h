/*
 * The calls behind the preprocessing golden vectors (pft_pre.h), shared by the generator (host
 * q16) and the replay test (every target). The frames are made by integer code only, so they
 * are identical everywhere: a 64 x 48 14-bit scene (a smooth hashed texture interpolated at a
 * drifting sub-pixel offset, a sky gradient), column fixed-pattern offsets, noise from an
 * integer generator, two dead pixels and a saturated one, a dim target crossing the frame, a
 * jump of several pixels, and one constant frame. pre_gv_compute() runs the temporal and the
 * local stage over it (the local one whitening with the last frame's sigma, and a U8 local
 * case with sigma held per tile) and records, per frame, the status, the
 * statistics, hashes of the residual frame and of the tile sigmas, and the first peaks; a
 * fourth case runs the temporal stage with the edge term (edge_k); three clutter maps
 * (pft_pre_clutter_*) run on the temporal case's residual. The
 * stage is integer arithmetic only, so the float and q16 builds must give the same values.
 */
#ifndef PFT_PRE_VECTORS_SPEC_H
#define PFT_PRE_VECTORS_SPEC_H
#include <string.h>
#include "pft/pft.h"
#include "pft/pft_pre.h"

#define PRE_GV_W 64
#define PRE_GV_H 48
#define PRE_GV_FRAMES 14u
#define PRE_GV_CASES 4u
#define PRE_GV_NF 24u     /* values per frame, see pre_gv_record */
#define PRE_GV_PEAKS 4u   /* peaks recorded per frame (x, y, value) */
#define PRE_GV_CLUT 4u    /* clutter map cases on the temporal case's residual */
#define PRE_GV_CF 5u      /* clutter values per frame, see pre_gv_clutter */

typedef struct {
    int32_t frame[PRE_GV_CASES][PRE_GV_FRAMES][PRE_GV_NF];
    int32_t peaks[PRE_GV_CASES][PRE_GV_FRAMES][PRE_GV_PEAKS * 3u];
    int32_t ws[PRE_GV_CASES];
    int32_t clut[PRE_GV_CLUT][PRE_GV_FRAMES][PRE_GV_CF];
} pre_gv_results_t;

/* FNV-1a over 32-bit words. */
static inline uint32_t pre_gv_hash(uint32_t h, int32_t v)
{
    const uint32_t u = (uint32_t)v;
    for (uint32_t b = 0; b < 4u; ++b) {
        h ^= (u >> (8u * b)) & 0xFFu;
        h *= 16777619u;
    }
    return h;
}
#define PRE_GV_HASH0 2166136261u

/* Integer hash of a lattice point, 0..4095. */
static inline int32_t pre_gv_lattice(int32_t i, int32_t j)
{
    uint32_t h = (uint32_t)i * 73856093u ^ (uint32_t)j * 19349663u;
    h ^= h >> 13;
    h *= 0x5bd1e995u;
    h ^= h >> 15;
    return (int32_t)(h & 4095u);
}

/* Texture at (x, y) in Q8 pixels: a lattice of cell 8 px, bilinear, 0..4095 (Q8 result). */
static inline int32_t pre_gv_texture_q8(int32_t xq8, int32_t yq8)
{
    const int32_t cx = xq8 >> 11, cy = yq8 >> 11; /* cells of 8 px = 2048 in Q8 */
    const int32_t fx = xq8 & 2047, fy = yq8 & 2047;
    const int32_t a = pre_gv_lattice(cx, cy), b = pre_gv_lattice(cx + 1, cy);
    const int32_t c = pre_gv_lattice(cx, cy + 1), d = pre_gv_lattice(cx + 1, cy + 1);
    const int32_t top = a * (2048 - fx) + b * fx, bot = c * (2048 - fx) + d * fx; /* Q11 */
    return (int32_t)(((int64_t)top * (2048 - fy) + (int64_t)bot * fy) >> 14); /* Q8 */
}

/* Noise: a sum of four uniforms (-2048..2047 each), 0..~ +-8192, standard deviation ~2365. */
static inline int32_t pre_gv_noise(uint32_t *s)
{
    int32_t v = 0;
    for (int i = 0; i < 4; ++i) {
        *s ^= *s << 13;
        *s ^= *s >> 17;
        *s ^= *s << 5;
        v += (int32_t)(*s >> 20) - 2048;
    }
    return v;
}

/* Frame k of the sequence into img (14-bit values in a u16 container). */
static inline void pre_gv_render(uint32_t k, uint16_t *img)
{
    /* scene offset in Q8 px: 0.3, -0.2 px per frame, a jump of (+5, -3) px at frame 9 */
    int32_t ox = (int32_t)k * 77, oy = -(int32_t)k * 51;
    if (k >= 9u) {
        ox += 5 * 256;
        oy -= 3 * 256;
    }
    uint32_t s = 0x1234567u + k * 7919u;
    for (int32_t y = 0; y < PRE_GV_H; ++y) {
        for (int32_t x = 0; x < PRE_GV_W; ++x) {
            /* pixel p shows the texture at p - offset */
            const int32_t t = pre_gv_texture_q8(((x + 40) << 8) - ox, ((y + 40) << 8) - oy);
            int32_t v = 3000 + t / 256 + 20 * y + 5 * x;         /* texture, sky gradient */
            v += ((x * 37) % 7 - 3) * 6;                          /* column offsets */
            v += pre_gv_noise(&s) / 118;                          /* noise, sigma ~20 */
            img[y * PRE_GV_W + x] = (uint16_t)(v < 0 ? 0 : (v > 16383 ? 16383 : v));
        }
    }
    /* a target of ~10 sigma crossing the frame */
    const int32_t tx = 8 + 3 * (int32_t)k, ty = 30 - (int32_t)k;
    img[ty * PRE_GV_W + tx] = (uint16_t)(img[ty * PRE_GV_W + tx] + 200);
    img[5 * PRE_GV_W + 7] = 0;       /* dead */
    img[40 * PRE_GV_W + 50] = 0;     /* dead */
    img[20 * PRE_GV_W + 33] = 16383; /* saturated */
    if (k == 6u) { /* a constant frame */
        for (int32_t i = 0; i < PRE_GV_W * PRE_GV_H; ++i) {
            img[i] = 5000;
        }
    }
}

/* One frame's record: status then the statistics, hashes and counts. */
static inline void pre_gv_record(const pft_pre_t *p, pft_status_t st, int32_t *out, int32_t *pk)
{
    pft_pre_stats_t s;
    memset(&s, 0, sizeof s);
    (void)pft_pre_stats(p, &s);
    pft_frame_t r;
    memset(&r, 0, sizeof r);
    uint32_t hr = PRE_GV_HASH0, hs = PRE_GV_HASH0;
    if (pft_pre_frame(p, &r) == PFT_OK) {
        const int16_t *v = r.data;
        for (int32_t i = 0; i < PRE_GV_W * PRE_GV_H; ++i) {
            hr = pre_gv_hash(hr, v[i]);
        }
    }
    uint32_t sig[16];
    const size_t nt = pft_pre_sigma(p, sig, 16);
    for (size_t i = 0; i < nt && i < 16u; ++i) {
        hs = pre_gv_hash(hs, (int32_t)sig[i]);
    }
    const int32_t rec[PRE_GV_NF] = {
        (int32_t)st, (int32_t)s.flags, s.shift[0], s.shift[1], s.shift_sd[0], s.shift_sd[1],
        s.shift_coarse[0], s.shift_coarse[1], (int32_t)s.reg_rms, (int32_t)s.sigma_min,
        (int32_t)s.sigma_mean, (int32_t)s.sigma_max, (int32_t)s.n_masked,
        (int32_t)s.n_saturated, (int32_t)s.n_dead, (int32_t)s.n_bad, (int32_t)s.n_peaks,
        (int32_t)s.n_candidates, (int32_t)hr, (int32_t)hs, (int32_t)s.seq,
        (int32_t)s.frames, (int32_t)nt, (int32_t)(s.timestamp_us & 0x7FFFFFFFu)};
    memcpy(out, rec, sizeof rec);
    pft_pre_peak_t peaks[PRE_GV_PEAKS];
    memset(peaks, 0, sizeof peaks);
    (void)pft_pre_peaks(p, peaks, PRE_GV_PEAKS);
    for (uint32_t i = 0; i < PRE_GV_PEAKS; ++i) {
        pk[3u * i] = peaks[i].x;
        pk[3u * i + 1u] = peaks[i].y;
        pk[3u * i + 2u] = peaks[i].value;
    }
}

/* The clutter maps (pft_pre_clutter_*) on the temporal case's residual, its shift and its
 * evidence: 0 the defaults (3 x 3 mean, alpha 0.1, thr 2), 1 with the running mean, read as the
 * largest value over 5 x 5, alpha 0.2, thr 1.5, and a raise at the target's place on frame 10;
 * 2 the map on 2 x 2 blocks (block 2) with the gated running mean (persist 3), alpha 0.2, and
 * the same raise; 3 the map in 8 bits (map8) with the gated running mean (persist 3), alpha
 * 0.2, and the same raise.
 * Record: status, hashes of the output and of the map, the workspace bytes, the frames. */
static inline void pre_gv_clutter(const pft_pre_t *pre, pft_status_t pst, uint32_t k,
                                  pft_pre_clutter_t *cl, int32_t out[PRE_GV_CLUT][PRE_GV_FRAMES][PRE_GV_CF])
{
    static uint64_t cwork[PRE_GV_CLUT][PFT_PRE_CLUTTER_WORKSPACE_BYTES(PRE_GV_W, PRE_GV_H, 1, 2, 1) / 8 + 1];
    pft_pre_stats_t s;
    memset(&s, 0, sizeof s);
    (void)pft_pre_stats(pre, &s);
    const bool ev = pst == PFT_OK &&
                    (s.flags & (PFT_PRE_FLAG_CONSTANT | PFT_PRE_FLAG_ALL_MASKED | PFT_PRE_FLAG_REG_LOST)) == 0u;
    pft_frame_t r;
    memset(&r, 0, sizeof r);
    const pft_status_t fst = pft_pre_frame(pre, &r);
    for (uint32_t j = 0; j < PRE_GV_CLUT; ++j) {
        pft_pre_clutter_config_t cfg;
        pft_pre_clutter_config_default(&cfg);
        cfg.width = PRE_GV_W;
        cfg.height = PRE_GV_H;
        if (j == 1u) {
            cfg.mean = true;
            cfg.box = false;
            cfg.blur = 2u;
            cfg.alpha = 13107u;
            cfg.thr = 1536u;
        }
        if (j == 3u) {
            cfg.map8 = true;
            cfg.mean = true;
            cfg.persist = 3u;
            cfg.alpha = 13107u;
        }
        if (j == 2u) {
            cfg.block = 2u;
            cfg.mean = true;
            cfg.persist = 3u;
            cfg.alpha = 13107u;
        }
        const size_t need = pft_pre_clutter_workspace_size(&cfg);
        if (k == 0u && (need > sizeof cwork[j] ||
                        pft_pre_clutter_init(&cl[j], &cfg, cwork[j], need) != PFT_OK)) {
            continue;
        }
        pft_status_t st = fst == PFT_OK ? pft_pre_clutter_update(&cl[j], &r, s.shift[0], s.shift[1], ev) : fst;
        if (j >= 1u && k == 10u) {
            (void)pft_pre_clutter_raise(&cl[j], 8u + 3u * 10u, 30u - 10u, 20000u);
        }
        uint32_t ho = PRE_GV_HASH0, hm = PRE_GV_HASH0;
        pft_frame_t o;
        memset(&o, 0, sizeof o);
        if (pft_pre_clutter_frame(&cl[j], &o) == PFT_OK) {
            const int16_t *v = o.data;
            for (int32_t i = 0; i < PRE_GV_W * PRE_GV_H; ++i) {
                ho = pre_gv_hash(ho, v[i]);
            }
        }
        for (uint32_t y = 0; y < PRE_GV_H; ++y) {
            for (uint32_t x = 0; x < PRE_GV_W; ++x) {
                hm = pre_gv_hash(hm, (int32_t)pft_pre_clutter_at(&cl[j], x, y));
            }
        }
        out[j][k][0] = (int32_t)st;
        out[j][k][1] = (int32_t)ho;
        out[j][k][2] = (int32_t)hm;
        out[j][k][3] = (int32_t)need;
        out[j][k][4] = (int32_t)o.seq;
    }
}

/* Runs the four cases: 0 temporal, 1 local (U16, sigma_current false), 2 local on the frames
 * as U8 (>> 6, sigma held per tile), 3 temporal with the edge term (edge_k, sigma_current
 * false). */
static inline void pre_gv_compute(pre_gv_results_t *r)
{
    static uint16_t img[PRE_GV_W * PRE_GV_H];
    static uint8_t img8[PRE_GV_W * PRE_GV_H];
    static uint64_t work[PFT_PRE_WORKSPACE_BYTES(PRE_GV_W, PRE_GV_H, PFT_PRE_BG_TEMPORAL, 4, 16,
                                                 8) / 8 + 1];
    memset(r, 0, sizeof(*r));
    for (uint32_t c = 0; c < PRE_GV_CASES; ++c) {
        pft_pre_config_t cfg;
        pft_pre_config_default(&cfg);
        cfg.width = PRE_GV_W;
        cfg.height = PRE_GV_H;
        cfg.tile = 16;
        cfg.peak_max = 8;
        cfg.method = (c == 0u || c == 3u) ? PFT_PRE_BG_TEMPORAL : PFT_PRE_BG_LOCAL;
        cfg.sigma_current = c != 1u && c != 3u; /* cases 1, 3: the last frame's sigma, in one pass */
        if (c == 3u) { /* the edge term (0.16 px) */
            cfg.edge_k = 655u;
        }
        if (c == 2u) {
            cfg.format = PFT_PIX_U8;
            cfg.bit_depth = 8;
            cfg.sigma_current = true;
            cfg.sigma_interp = false;
        }
        pft_pre_t pre;
        pft_pre_clutter_t cl[PRE_GV_CLUT];
        const size_t need = pft_pre_workspace_size(&cfg);
        r->ws[c] = (int32_t)need;
        if (need == 0u || need > sizeof work || pft_pre_init(&pre, &cfg, work, need) != PFT_OK) {
            continue;
        }
        for (uint32_t k = 0; k < PRE_GV_FRAMES; ++k) {
            pre_gv_render(k, img);
            pft_frame_t f;
            memset(&f, 0, sizeof f);
            f.width = PRE_GV_W;
            f.height = PRE_GV_H;
            f.seq = 100u + k;
            f.timestamp_us = 40000u * k;
            if (c == 2u) {
                for (int32_t i = 0; i < PRE_GV_W * PRE_GV_H; ++i) {
                    img8[i] = (uint8_t)(img[i] >> 6);
                }
                f.data = img8;
                f.format = PFT_PIX_U8;
                f.stride_bytes = PRE_GV_W;
            } else {
                f.data = img;
                f.format = PFT_PIX_U16;
                f.bit_depth = 14;
                f.stride_bytes = 2u * PRE_GV_W;
            }
            const pft_status_t st = pft_pre_update(&pre, &f);
            pre_gv_record(&pre, st, r->frame[c][k], r->peaks[c][k]);
            if (c == 0u) {
                pre_gv_clutter(&pre, st, k, cl, r->clut);
            }
        }
    }
}
#endif
