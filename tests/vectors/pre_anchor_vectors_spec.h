/*
 * The calls behind the golden vectors of the stage with bg_anchor (docs/algorithms.md 9.12),
 * shared by the generator (host q16) and the replay test (every target): the temporal stage
 * of pre_vectors_spec.h's case 0 on the same frames (drift 0.3, -0.2 px per frame, a jump of
 * (+5, -3) px at frame 9, a constant frame, dead and saturated pixels, a dim target), with
 * bg_anchor set; per frame the record of pre_gv_record (status, statistics, hashes of the
 * residual and of the tile sigmas) and the first peaks, and the hash of the anchored grid
 * (read from the instance's layout, a test of the stored values). Integer arithmetic only: the
 * float and q16 builds must give the same values.
 */
#ifndef PFT_PRE_ANCHOR_VECTORS_SPEC_H
#define PFT_PRE_ANCHOR_VECTORS_SPEC_H
#include "pre_vectors_spec.h"

typedef struct {
    int32_t frame[PRE_GV_FRAMES][PRE_GV_NF];
    int32_t peaks[PRE_GV_FRAMES][PRE_GV_PEAKS * 3u];
    int32_t grid[PRE_GV_FRAMES][5]; /* hash of the cells, valid ranges x0 x1 y0 y1 */
    int32_t ws;
} pre_agv_results_t;

static inline void pre_agv_compute(pre_agv_results_t *r)
{
    static uint16_t img[PRE_GV_W * PRE_GV_H];
    static uint64_t work[PFT_PRE_WORKSPACE_BYTES_ANCHOR(PRE_GV_W, PRE_GV_H, 4, 16, 8) / 8 + 1];
    memset(r, 0, sizeof(*r));
    pft_pre_config_t cfg;
    pft_pre_config_default(&cfg);
    cfg.width = PRE_GV_W;
    cfg.height = PRE_GV_H;
    cfg.tile = 16;
    cfg.peak_max = 8;
    cfg.bg_anchor = true;
    pft_pre_t pre;
    const size_t need = pft_pre_workspace_size(&cfg);
    r->ws = (int32_t)need;
    if (need == 0u || need > sizeof work || pft_pre_init(&pre, &cfg, work, need) != PFT_OK) {
        return;
    }
    for (uint32_t k = 0; k < PRE_GV_FRAMES; ++k) {
        pre_gv_render(k, img);
        pft_frame_t f;
        memset(&f, 0, sizeof f);
        f.width = PRE_GV_W;
        f.height = PRE_GV_H;
        f.seq = 100u + k;
        f.timestamp_us = 40000u * k;
        f.data = img;
        f.format = PFT_PIX_U16;
        f.bit_depth = 14;
        f.stride_bytes = 2u * PRE_GV_W;
        const pft_status_t st = pft_pre_update(&pre, &f);
        pre_gv_record(&pre, st, r->frame[k], r->peaks[k]);
        uint32_t h = PRE_GV_HASH0;
        for (int32_t i = 0; i < (PRE_GV_W + 3) * (PRE_GV_H + 3); ++i) {
            h = pre_gv_hash(h, pre.bg[i]);
        }
        r->grid[k][0] = (int32_t)h;
        r->grid[k][1] = pre.avlo[0];
        r->grid[k][2] = pre.avhi[0];
        r->grid[k][3] = pre.avlo[1];
        r->grid[k][4] = pre.avhi[1];
    }
}
#endif
