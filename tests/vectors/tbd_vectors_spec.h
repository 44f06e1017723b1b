/*
 * The calls behind the tbd golden vectors (tbd_q16_vectors.h), shared by the generator
 * gen_tbd_vectors.c (host q16) and the replay test tests/unit/test_tbd_golden.c (every preset).
 *
 * A 20x20 scene of gv_scene.h (two straight-line targets at about 12 dB, frames rendered with
 * integer arithmetic only) runs through
 *   - the standalone RBPF-TBD and PF-TBD filters (24 frames, exclusion regions on some),
 *   - the manager with the paper preset, the recommended preset and a variant that switches on
 *     the other options (PF kind, paper Kalman variant, birth correction, pixel regions from the
 *     current estimates, the short-window ending test), 30 frames each,
 *   - a few direct calls of the measurement model (window region bounds, kept raw; PSF value,
 *     LLR, PSF subtraction).
 * Every frame gives one row of uint32 values. Positions are kept raw (x, y of the estimate,
 * tracks and events, in Q16.16 raw units); everything else of the row is hashed (FNV-1a), so a
 * change of the coordinate convention shows as a pure shift of the position columns.
 */
#ifndef PFT_TBD_VECTORS_SPEC_H
#define PFT_TBD_VECTORS_SPEC_H
#include <string.h>
#include "pft/pft.h"
#include "pft/pft_tbd.h"
#include "gv_scene.h"

#define PFT_TV_FILTER_FRAMES 24
#define PFT_TV_MGR_FRAMES 30
#define PFT_TV_MAXT 3
/* filter row: valid, x, y, p_exist, hash of every other estimate field */
#define PFT_TV_FROW 5
/* manager row: search valid, x, y, p_exist, hash; n_tracks, n_events; tracks[3] x, y;
 * events[4] x, y; hash of every non-position field of the tracks and events */
#define PFT_TV_MROW (5 + 2 + 2 * PFT_TV_MAXT + 2 * (PFT_TV_MAXT + 1) + 1)
#define PFT_TV_MEAS 36

#define PFT_TV_NF 400u
#define PFT_TV_NS 600u
#define PFT_TV_NT 200u

typedef struct {
    uint32_t filt_rbpf[PFT_TV_FILTER_FRAMES][PFT_TV_FROW];
    uint32_t filt_pf[PFT_TV_FILTER_FRAMES][PFT_TV_FROW];
    uint32_t mgr_paper[PFT_TV_MGR_FRAMES][PFT_TV_MROW];
    uint32_t mgr_rec[PFT_TV_MGR_FRAMES][PFT_TV_MROW];
    uint32_t mgr_var[PFT_TV_MGR_FRAMES][PFT_TV_MROW];
    uint32_t mgr_integ[PFT_TV_MGR_FRAMES][PFT_TV_MROW];
    uint32_t meas[PFT_TV_MEAS];
} pft_tv_results_t;

/* T1: frames 3-20 from column 4, row 5, velocity (0.5, 0.25); T2: frames 12-28 from column 14,
 * row 13, velocity (-0.375, -0.25). Peak amplitude 6.5, sigma 1.6 (12.2 dB). */
static const pft_gv_target_t pft_tv_targets[2] = {
    {3, 20, 4 * 16, 5 * 16, 8, 4, 1664},
    {12, 28, 14 * 16, 13 * 16, -6, -4, 1664},
};
#define PFT_TV_SIGMA256 410
#define PFT_TV_SIGMA 1.6015625 /* 410 / 256 */

static inline void pft_tv_config(pft_tbd_config_t *c, int recommended, uint64_t seed)
{
    if (recommended) {
        pft_tbd_config_recommended(c);
    } else {
        pft_tbd_config_default(c);
    }
    c->width = PFT_GV_SCENE_W;
    c->height = PFT_GV_SCENE_H;
    c->noise_sigma = PFT_C(PFT_TV_SIGMA);
    c->pixel_gain = PFT_C(0.00390625);
    c->pixel_offset = PFT_C(-64.0);
    c->n_search = PFT_TV_NS;
    c->n_track = PFT_TV_NT;
    c->max_targets = PFT_TV_MAXT;
    c->seed = seed;
}

static inline uint32_t pft_tv_hash_est(const pft_tbd_estimate_t *e)
{
    uint32_t h = PFT_GV_FNV0;
    h = pft_gv_fnv(h, pft_gv_r(e->p_exist));
    h = pft_gv_fnv(h, pft_gv_r(e->vx));
    h = pft_gv_fnv(h, pft_gv_r(e->vy));
    h = pft_gv_fnv(h, pft_gv_r(e->intensity));
    for (int i = 0; i < 3; ++i) {
        h = pft_gv_fnv(h, pft_gv_r(e->pos_cov[i]));
    }
    h = pft_gv_fnv(h, pft_gv_r(e->log_mean_lr));
    h = pft_gv_fnv(h, pft_gv_r(e->n_eff));
    h = pft_gv_fnv(h, e->valid ? 1u : 0u);
    return h;
}

static inline void pft_tv_est_row(const pft_tbd_estimate_t *e, uint32_t *row)
{
    row[0] = e->valid ? 1u : 0u;
    row[1] = pft_gv_r(e->x);
    row[2] = pft_gv_r(e->y);
    row[3] = pft_gv_r(e->p_exist);
    row[4] = pft_tv_hash_est(e);
}

/* ---- standalone filter ---- */
static uint64_t pft_tv_fwork[PFT_TBD_FILTER_WORKSPACE_BYTES(PFT_TV_NF, PFT_TBD_RBPF, PFT_GV_SCENE_W,
                                                            PFT_GV_SCENE_H) / 8u + 1u];
static pft_tbd_filter_t pft_tv_filter;
static uint16_t pft_tv_raw[PFT_GV_SCENE_W * PFT_GV_SCENE_H];

static inline void pft_tv_run_filter(pft_tbd_kind_t kind, uint32_t rows[][PFT_TV_FROW])
{
    pft_tbd_config_t c;
    pft_tv_config(&c, 0, 11u);
    c.kind = kind;
    c.n_search = PFT_TV_NF; /* the standalone filter's particle count */
    memset(pft_tv_fwork, 0, sizeof pft_tv_fwork);
    if (pft_tbd_filter_init(&pft_tv_filter, &c, pft_tv_fwork, sizeof pft_tv_fwork) != PFT_OK) {
        return;
    }
    pft_rng_t sim;
    pft_rng_seed(&sim, 101u);
    /* frame columns 15-17, rows 1-3 (frames 8-12, away from the target) and columns 10-12,
     * rows 6-8 (frames 19-22, on the target's path) */
    const pft_tbd_region_t far = {15, 17, 1, 3};
    const pft_tbd_region_t on = {10, 12, 6, 8};
    for (int32_t k = 1; k <= PFT_TV_FILTER_FRAMES; ++k) {
        pft_frame_t f;
        pft_gv_render(&sim, pft_tv_targets, 1, k, PFT_TV_SIGMA256, pft_tv_raw, &f);
        pft_status_t st;
        if (k >= 8 && k <= 12) {
            st = pft_tbd_filter_update_ex(&pft_tv_filter, &f, &far, 1u);
        } else if (k >= 19 && k <= 22) {
            pft_tbd_region_t two[2] = {far, on};
            st = pft_tbd_filter_update_ex(&pft_tv_filter, &f, two, 2u);
        } else {
            st = pft_tbd_filter_update(&pft_tv_filter, &f);
        }
        pft_tbd_estimate_t e;
        memset(&e, 0, sizeof e);
        (void)pft_tbd_filter_estimate(&pft_tv_filter, &e);
        pft_tv_est_row(&e, rows[k - 1]);
        if (st != PFT_OK) {
            rows[k - 1][4] = 0xDEADu;
        }
    }
}

/* ---- manager ---- */
/* birth peaks of the integration case (the recommended preset with births from the peaks of
 * the multi-frame integration, cfg.integ_alpha) */
#define PFT_TV_PEAKS 8u
/* one workspace for every manager case: the larger of the cases without birth peaks and the
 * integration case (init takes exactly its case's pft_tbd_workspace_size) */
#define PFT_TV_MWS_PLAIN                                                                          \
    PFT_TBD_WORKSPACE_BYTES(PFT_TV_NS, PFT_TV_NT, PFT_TV_MAXT, PFT_TBD_RBPF, PFT_GV_SCENE_W, PFT_GV_SCENE_H)
#define PFT_TV_MWS_INTEG                                                                          \
    (PFT_TBD_WORKSPACE_BYTES_PEAKS(PFT_TV_NS, PFT_TV_NT, PFT_TV_MAXT, PFT_TBD_RBPF, PFT_GV_SCENE_W, \
                                   PFT_GV_SCENE_H, PFT_TV_PEAKS) +                                \
     PFT_TBD_INTEG_BYTES(PFT_GV_SCENE_W, PFT_GV_SCENE_H))
static uint64_t pft_tv_mwork[(PFT_TV_MWS_PLAIN > PFT_TV_MWS_INTEG ? PFT_TV_MWS_PLAIN : PFT_TV_MWS_INTEG) / 8u +
                             1u];
static pft_tbd_t pft_tv_mgr;

static inline void pft_tv_run_manager(const pft_tbd_config_t *c, uint64_t sim_seed,
                                      uint32_t rows[][PFT_TV_MROW])
{
    memset(pft_tv_mwork, 0, sizeof pft_tv_mwork);
    const size_t need = pft_tbd_workspace_size(c);
    if (need == 0u || need > sizeof pft_tv_mwork || pft_tbd_init(&pft_tv_mgr, c, pft_tv_mwork, need) != PFT_OK) {
        return; /* all-zero rows: the replay's comparison and test_scene_has_events fail */
    }
    pft_rng_t sim;
    pft_rng_seed(&sim, sim_seed);
    for (int32_t k = 1; k <= PFT_TV_MGR_FRAMES; ++k) {
        pft_frame_t f;
        pft_gv_render(&sim, pft_tv_targets, 2, k, PFT_TV_SIGMA256, pft_tv_raw, &f);
        pft_status_t st = pft_tbd_update(&pft_tv_mgr, &f);
        uint32_t *row = rows[k - 1];
        memset(row, 0, PFT_TV_MROW * sizeof(uint32_t));
        pft_tbd_estimate_t e;
        memset(&e, 0, sizeof e);
        (void)pft_tbd_search_estimate(&pft_tv_mgr, &e);
        pft_tv_est_row(&e, row);
        pft_tbd_track_t tr[PFT_TV_MAXT];
        pft_tbd_event_t ev[PFT_TV_MAXT + 1];
        size_t nt = pft_tbd_tracks(&pft_tv_mgr, tr, PFT_TV_MAXT);
        size_t ne = pft_tbd_events(&pft_tv_mgr, ev, PFT_TV_MAXT + 1);
        row[5] = (uint32_t)nt;
        row[6] = (uint32_t)ne;
        uint32_t h = PFT_GV_FNV0;
        h = pft_gv_fnv(h, st == PFT_OK ? 0u : 1u);
        h = pft_gv_fnv(h, pft_tbd_frame(&pft_tv_mgr));
        for (size_t i = 0; i < nt && i < PFT_TV_MAXT; ++i) {
            row[7 + 2 * i] = pft_gv_r(tr[i].x);
            row[8 + 2 * i] = pft_gv_r(tr[i].y);
            h = pft_gv_fnv(h, tr[i].id);
            h = pft_gv_fnv(h, pft_gv_r(tr[i].vx));
            h = pft_gv_fnv(h, pft_gv_r(tr[i].vy));
            h = pft_gv_fnv(h, pft_gv_r(tr[i].intensity));
            for (int q = 0; q < 3; ++q) {
                h = pft_gv_fnv(h, pft_gv_r(tr[i].pos_cov[q]));
            }
            h = pft_gv_fnv(h, pft_gv_r(tr[i].p_exist));
            h = pft_gv_fnv(h, pft_gv_r(tr[i].log_mean_lr));
            h = pft_gv_fnv(h, tr[i].first_frame);
            h = pft_gv_fnv(h, tr[i].age);
        }
        for (size_t i = 0; i < ne && i < PFT_TV_MAXT + 1; ++i) {
            row[7 + 2 * PFT_TV_MAXT + 2 * i] = pft_gv_r(ev[i].x);
            row[8 + 2 * PFT_TV_MAXT + 2 * i] = pft_gv_r(ev[i].y);
            h = pft_gv_fnv(h, (uint32_t)ev[i].kind);
            h = pft_gv_fnv(h, ev[i].id);
            h = pft_gv_fnv(h, ev[i].frame);
        }
        row[PFT_TV_MROW - 1] = h;
    }
}

/* ---- measurement model ---- */
static pft_real_t pft_tv_img[PFT_GV_SCENE_W * PFT_GV_SCENE_H];

static inline void pft_tv_run_meas(uint32_t *out)
{
    pft_tbd_config_t c;
    pft_tv_config(&c, 0, 1u);
    pft_tbd_meas_t m;
    if (pft_tbd_meas_init(&m, &c) != PFT_OK) {
        return;
    }
    /* one frame of the scene at frame 10, converted like the filters do (z = raw/256 - 64) */
    pft_rng_t sim;
    pft_rng_seed(&sim, 5u);
    pft_frame_t f;
    pft_gv_render(&sim, pft_tv_targets, 2, 10, PFT_TV_SIGMA256, pft_tv_raw, &f);
    for (uint32_t r = 0; r < PFT_GV_SCENE_H; ++r) {
        pft_frame_row_to_real(&f, r, PFT_GV_SCENE_W, c.pixel_gain, c.pixel_offset,
                              pft_tv_img + r * PFT_GV_SCENE_W);
    }
    /* 0-based positions: column c is at x = c (dx = 1) */
    const pft_real_t xs[4] = {PFT_C(7.5), PFT_C(0.25), PFT_C(19.4), PFT_C(11.0)};
    const pft_real_t ys[4] = {PFT_C(6.75), PFT_C(-0.4), PFT_C(18.5), PFT_C(10.3)};
    size_t o = 0;
    for (int i = 0; i < 4; ++i) {
        pft_tbd_region_t r = pft_tbd_window_region(&c, xs[i], ys[i]);
        out[o++] = (uint32_t)r.col_lo;
        out[o++] = (uint32_t)r.col_hi;
        out[o++] = (uint32_t)r.row_lo;
        out[o++] = (uint32_t)r.row_hi;
        out[o++] = pft_gv_r(pft_tbd_meas_h(&m, 8, 7, xs[i], ys[i], PFT_C(20.0)));
        out[o++] = pft_gv_r(pft_tbd_meas_llr(&m, pft_tv_img, xs[i], ys[i], PFT_C(20.0)));
        pft_tbd_meas_add_psf(&m, pft_tv_img, xs[i], ys[i], PFT_C(-6.0), 2u);
        uint32_t h = PFT_GV_FNV0;
        for (size_t k = 0; k < PFT_GV_SCENE_W * PFT_GV_SCENE_H; ++k) {
            h = pft_gv_fnv(h, pft_gv_r(pft_tv_img[k]));
        }
        out[o++] = h;
        out[o++] = pft_gv_r(pft_tbd_meas_llr(&m, pft_tv_img, xs[i], ys[i], PFT_C(14.0)));
        out[o++] = pft_gv_r(pft_tbd_meas_h(&m, 0, 19, xs[i], ys[i], PFT_C(14.0)));
    }
}

static inline void pft_tv_compute(pft_tv_results_t *r)
{
    memset(r, 0, sizeof(*r));
    pft_tv_run_filter(PFT_TBD_RBPF, r->filt_rbpf);
    pft_tv_run_filter(PFT_TBD_PF, r->filt_pf);
    pft_tbd_config_t c;
    pft_tv_config(&c, 0, 21u);
    pft_tv_run_manager(&c, 201u, r->mgr_paper);
    pft_tv_config(&c, 1, 22u);
    pft_tv_run_manager(&c, 202u, r->mgr_rec);
    pft_tv_config(&c, 0, 23u);
    c.kind = PFT_TBD_PF;
    c.kf_variant = PFT_TBD_KF_PAPER;
    c.birth_correction = true;
    c.d_region = PFT_TBD_D_PIXEL;
    c.d_margin = 1u;
    c.d_current = true;
    c.dis_ratio_test = false;
    c.theta_end = PFT_C(0.4);
    c.end_lr_frames = 2u;
    c.end_lr_max = PFT_C(-1.0);
    c.residual_tracks = true;
    c.handover_gate = 3u;
    pft_tv_run_manager(&c, 203u, r->mgr_var);
    pft_tv_config(&c, 1, 24u);
    c.birth_peaks = PFT_TV_PEAKS;
    c.integ_alpha = PFT_C(0.7);
    pft_tv_run_manager(&c, 204u, r->mgr_integ);
    pft_tv_run_meas(r->meas);
}

#endif
