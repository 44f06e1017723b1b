/*
 * The calls behind the anchored clutter map's golden vectors (pft_pre.h, pft_pre_clutter_*
 * with anchor), shared by the generator (host q16) and the replay test (every target). The
 * residual frames are made by integer code only, so they are identical everywhere: a 64 x 48
 * Q8.8 residual fixed in a scene that drifts by sub-pixel steps (the shifts of clan_gv_shift,
 * a jump of several pixels among them), rendered at the scene's position rounded to whole
 * pixels, plus a part drawn anew every frame, a 3 x 3 clutter blob of 4 sigma fixed in the
 * scene, a point moving across it, two masked pixels and one frame without evidence.
 * clan_gv_compute() runs three maps over them: 0 the defaults with anchor; 1 anchor with the
 * gated running mean (persist 3, alpha 0.2), read as the largest value over 5 x 5, thr 1.5 and
 * veto 12, and a raise at the blob on frame 9; 2 anchor with map8 and the gated running mean
 * (persist 3, alpha 0.2). Per frame: the status, hashes of the output and of the map
 * (pft_pre_clutter_at), the workspace bytes and the output's seq. Integer arithmetic only: the
 * float and q16 builds must give the same values.
 */
#ifndef PFT_CLUTAN_VECTORS_SPEC_H
#define PFT_CLUTAN_VECTORS_SPEC_H
#include <string.h>
#include "pft/pft.h"
#include "pft/pft_pre.h"

#define CLAN_GV_W 64
#define CLAN_GV_H 48
#define CLAN_GV_FRAMES 16u
#define CLAN_GV_CASES 3u
#define CLAN_GV_NF 5u /* values per frame and case */

typedef struct {
    int32_t rec[CLAN_GV_CASES][CLAN_GV_FRAMES][CLAN_GV_NF];
} clan_gv_results_t;

/* FNV-1a over 32-bit words. */
static inline uint32_t clan_gv_hash(uint32_t h, int32_t v)
{
    const uint32_t u = (uint32_t)v;
    for (uint32_t b = 0; b < 4u; ++b) {
        h ^= (u >> (8u * b)) & 0xFFu;
        h *= 16777619u;
    }
    return h;
}
#define CLAN_GV_HASH0 2166136261u

/* Integer hash of (i, j, k), 0..65535. */
static inline uint32_t clan_gv_lattice(int32_t i, int32_t j, int32_t k)
{
    uint32_t h = (uint32_t)i * 73856093u ^ (uint32_t)j * 19349663u ^ (uint32_t)k * 83492791u;
    h ^= h >> 13;
    h *= 0x5bd1e995u;
    h ^= h >> 15;
    return h & 0xFFFFu;
}

/* The shift given with frame k (Q16.16 px): sub-pixel steps of both signs, a jump of several
 * pixels at frame 7, a half pixel exactly at frame 11. */
static inline void clan_gv_shift(uint32_t k, int32_t *sx, int32_t *sy)
{
    static const int32_t tx[CLAN_GV_FRAMES] = {0, 19661, 22938, 16384, 26214, 19661, 9830, 203162,
                                               -13107, 19661, 22938, 32768, 6554, 19661, 29491, 13107};
    static const int32_t ty[CLAN_GV_FRAMES] = {0, -13107, -9830, -16384, -6554, -19661, 3277, -137626,
                                               9830, -13107, -26214, -32768, -9830, -3277, -19661, -13107};
    *sx = tx[k];
    *sy = ty[k];
}

/* floor(a / 65536 + 1/2) for the scene's position (the same rounding as the map's). */
static inline int32_t clan_gv_round(int64_t a)
{
    const int64_t t = a + 32768;
    return (int32_t)(t / 65536 - (t % 65536 < 0 ? 1 : 0));
}

/* Frame k's residual: the scene's part at scene point (x - px, y - py), (px, py) the rounded
 * sum of the shifts up to frame k, plus a part drawn anew every frame. */
static inline void clan_gv_render(uint32_t k, int32_t px, int32_t py, int16_t *r)
{
    for (int32_t y = 0; y < CLAN_GV_H; ++y) {
        for (int32_t x = 0; x < CLAN_GV_W; ++x) {
            const int32_t sx = x - px, sy = y - py;
            /* scene: 0.75 sigma uniform about, a stronger band at scene rows 30..31 */
            int32_t v = (int32_t)(clan_gv_lattice(sx, sy, 0) % 385u) - 192;
            if (sy == 30 || sy == 31) {
                v *= 4;
            }
            v += (int32_t)(clan_gv_lattice(x, y, (int32_t)k + 1) % 257u) - 128; /* anew */
            if (sx >= 29 && sx <= 31 && sy >= 19 && sy <= 21) {
                v = 1024; /* the clutter blob, 4 sigma, fixed in the scene */
            }
            if (x == 4 + 3 * (int32_t)k && y == 10) {
                v = 1280; /* a point moving in the image */
            }
            r[y * CLAN_GV_W + x] = (int16_t)v;
        }
    }
    r[5 * CLAN_GV_W + 7] = PFT_RES16_MASKED;
    r[40 * CLAN_GV_W + 50] = PFT_RES16_MASKED;
}

static inline void clan_gv_compute(clan_gv_results_t *res)
{
    static int16_t img[CLAN_GV_W * CLAN_GV_H];
    static uint64_t work[CLAN_GV_CASES][PFT_PRE_CLUTTER_WORKSPACE_BYTES(CLAN_GV_W, CLAN_GV_H, 1, 2, 1) / 8 + 1];
    static pft_pre_clutter_t cl[CLAN_GV_CASES];
    memset(res, 0, sizeof(*res));
    size_t need[CLAN_GV_CASES];
    bool ok[CLAN_GV_CASES];
    for (uint32_t j = 0; j < CLAN_GV_CASES; ++j) {
        pft_pre_clutter_config_t cfg;
        pft_pre_clutter_config_default(&cfg);
        cfg.width = CLAN_GV_W;
        cfg.height = CLAN_GV_H;
        cfg.anchor = true;
        if (j == 1u) {
            cfg.mean = true;
            cfg.persist = 3u;
            cfg.alpha = 13107u;
            cfg.box = false;
            cfg.blur = 2u;
            cfg.thr = 1536u;
            cfg.veto = 12288u;
        }
        if (j == 2u) {
            cfg.map8 = true;
            cfg.mean = true;
            cfg.persist = 3u;
            cfg.alpha = 13107u;
        }
        need[j] = pft_pre_clutter_workspace_size(&cfg);
        ok[j] = need[j] != 0u && need[j] <= sizeof work[j] &&
                pft_pre_clutter_init(&cl[j], &cfg, work[j], need[j]) == PFT_OK;
    }
    int64_t ax = 0, ay = 0;
    for (uint32_t k = 0; k < CLAN_GV_FRAMES; ++k) {
        int32_t sx, sy;
        clan_gv_shift(k, &sx, &sy);
        ax += sx;
        ay += sy;
        clan_gv_render(k, clan_gv_round(ax), clan_gv_round(ay), img);
        pft_frame_t f;
        memset(&f, 0, sizeof f);
        f.data = img;
        f.width = CLAN_GV_W;
        f.height = CLAN_GV_H;
        f.stride_bytes = 2u * CLAN_GV_W;
        f.format = PFT_PIX_RES16;
        f.bit_depth = 16u;
        f.seq = 200u + k;
        f.timestamp_us = 40000u * k;
        const bool ev = k != 5u;
        for (uint32_t j = 0; j < CLAN_GV_CASES; ++j) {
            if (!ok[j]) {
                continue;
            }
            const pft_status_t st = pft_pre_clutter_update(&cl[j], &f, sx, sy, ev);
            if (j == 1u && k == 9u) {
                const int32_t bx = 30 + clan_gv_round(ax), by = 20 + clan_gv_round(ay);
                if (bx >= 0 && bx < CLAN_GV_W && by >= 0 && by < CLAN_GV_H) {
                    (void)pft_pre_clutter_raise(&cl[j], (uint32_t)bx, (uint32_t)by, 20000u);
                }
            }
            uint32_t ho = CLAN_GV_HASH0, hm = CLAN_GV_HASH0;
            pft_frame_t o;
            memset(&o, 0, sizeof o);
            if (pft_pre_clutter_frame(&cl[j], &o) == PFT_OK) {
                const int16_t *v = o.data;
                for (int32_t i = 0; i < CLAN_GV_W * CLAN_GV_H; ++i) {
                    ho = clan_gv_hash(ho, v[i]);
                }
            }
            for (uint32_t y = 0; y < CLAN_GV_H; ++y) {
                for (uint32_t x = 0; x < CLAN_GV_W; ++x) {
                    hm = clan_gv_hash(hm, (int32_t)pft_pre_clutter_at(&cl[j], x, y));
                }
            }
            res->rec[j][k][0] = (int32_t)st;
            res->rec[j][k][1] = (int32_t)ho;
            res->rec[j][k][2] = (int32_t)hm;
            res->rec[j][k][3] = (int32_t)need[j];
            res->rec[j][k][4] = (int32_t)o.seq;
        }
    }
}
#endif
