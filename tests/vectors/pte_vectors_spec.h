/*
 * The calls behind the pte golden vectors (PTE-TBD, DP-TBD sliding and batch, Kalman DBT),
 * shared by the generator (host q16) and the replay test (every target), so both run exactly
 * the same code. The scenes are U16 frames made by integer code only (identical everywhere):
 *  - range-time, 64 cells x 72 frames: target A (2.5 sigma) from cell 12 at +0.25 cells/frame
 *    in frames 0..47, then gone; target B (3 sigma) from frame 16 at cell 50 accelerating
 *    towards lower range (-0.125 k' - k'^2/256 cells, k' = frame - 16);
 *  - range-Doppler, 24 x 8 cells x 24 frames: one target (6 sigma) from (6, 6) moving
 *    (+0.25, -0.125) cells/frame.
 * Background: 4096 plus the sum of four uniform integers in [0, 111) (mean 220, sigma 64.1);
 * targets: a triangle of half-width 1.5 cells per axis, amplitude in raw units. The trackers
 * see z = raw/64 - 67.4375 (both exact in Q16.16), so sigma is about 1.
 * Per frame and instance the spec records the report count, the first report's id, position,
 * velocity and score, and a 32-bit FNV-1a hash of every field of every report (and of the DP
 * peak / DBT plots) in Q16.16 raw units.
 */
#ifndef PFT_PTE_VECTORS_SPEC_H
#define PFT_PTE_VECTORS_SPEC_H
#include <string.h>
#include "pft/pft.h"
#include "pft/pft_pte.h"
#include "core_vectors_spec.h" /* PFT_GV_REAL / PFT_GV_RAW (Q16.16 raw <-> pft_real_t) */

#define PFT_PV_NR 64u      /* range-time scene */
#define PFT_PV_FRAMES 72u
#define PFT_PV_NR2 24u     /* range-Doppler scene */
#define PFT_PV_ND2 8u
#define PFT_PV_FRAMES2 24u
#define PFT_PV_BASE 4316   /* 4096 + mean of the background */

/* instances (rows of the per-frame records) */
enum {
    PFT_PV_PTE_TABLE = 0, /* range-time, defaults (TABLE operators, CA), M = 20, frames */
    PFT_PV_PTE_EXACT,     /* range-time, EXACT operators, CV, L = 3, M = 12, values, a cue */
    PFT_PV_DP_SLIDE,      /* range-time, sliding K = 10 */
    PFT_PV_DP_BATCH,      /* range-time, disjoint batches of K = 6, gate 2, known amplitude, CFAR */
    PFT_PV_DBT,           /* range-time, defaults */
    PFT_PV_DBT_CFAR,      /* range-time, CA-CFAR input */
    PFT_PV_PTE_RD,        /* range-Doppler, EXACT 2-D operators */
    PFT_PV_DP_RD,         /* range-Doppler, sliding K = 6 */
    PFT_PV_DBT_RD,        /* range-Doppler */
    PFT_PV_PTE_EDGE,      /* as PTE_TABLE, with a cue at the low end moving inward (its
                             operator lines run off the response grid: the edge normaliser) */
    PFT_PV_N_INST
};

#define PFT_PV_MAXF PFT_PV_FRAMES

typedef struct {
    int32_t count[PFT_PV_N_INST][PFT_PV_MAXF];
    uint32_t hash[PFT_PV_N_INST][PFT_PV_MAXF];
    int32_t id0[PFT_PV_N_INST][PFT_PV_MAXF];
    int32_t pos0[PFT_PV_N_INST][PFT_PV_MAXF];
    int32_t vel0[PFT_PV_N_INST][PFT_PV_MAXF];
    int32_t score0[PFT_PV_N_INST][PFT_PV_MAXF];
    int32_t status[PFT_PV_N_INST]; /* first update status other than PFT_OK (0: none) */
    int32_t thr[2];  /* DP and PTE noise-only Monte Carlo thresholds */
    int32_t cue_status, cue_id;
} pft_pv_results_t;

/* ----------------------------------------------------------------------------- scenes */

static inline uint32_t pft_pv_xs32(uint32_t *s)
{
    uint32_t x = *s;
    x ^= x << 13;
    x ^= x >> 17;
    x ^= x << 5;
    *s = x;
    return x;
}

static inline int32_t pft_pv_noise(uint32_t *s)
{
    int32_t v = 0;
    for (int i = 0; i < 4; ++i) {
        v += (int32_t)((pft_pv_xs32(s) >> 8) % 111u);
    }
    return v;
}

/* triangle of half-width 1.5 cells (24 sixteenths): weight in 1/24 at distance d16 */
static inline int32_t pft_pv_tri(int32_t d16)
{
    int32_t a = d16 < 0 ? -d16 : d16;
    return a < 24 ? 24 - a : 0;
}

/* range-time frame k into pix[64] */
static inline void pft_pv_scene1(uint32_t *s, uint32_t k, uint16_t *pix)
{
    int32_t pa = 192 + 4 * (int32_t)k; /* 1/16 cells */
    int32_t kb = (int32_t)k - 16;
    int32_t pb = 800 - 2 * kb - (kb * kb) / 16;
    for (uint32_t u = 0; u < PFT_PV_NR; ++u) {
        int32_t v = 4096 + pft_pv_noise(s);
        int32_t u16 = 16 * (int32_t)u;
        if (k < 48u) {
            v += 160 * pft_pv_tri(u16 - pa) / 24;
        }
        if (kb >= 0) {
            v += 192 * pft_pv_tri(u16 - pb) / 24;
        }
        pix[u] = (uint16_t)v;
    }
}

/* range-Doppler frame k into pix[8][24] */
static inline void pft_pv_scene2(uint32_t *s, uint32_t k, uint16_t *pix)
{
    int32_t pr = 96 + 4 * (int32_t)k;
    int32_t pd = 96 - 2 * (int32_t)k;
    for (uint32_t d = 0; d < PFT_PV_ND2; ++d) {
        for (uint32_t u = 0; u < PFT_PV_NR2; ++u) {
            int32_t v = 4096 + pft_pv_noise(s);
            int32_t w = pft_pv_tri(16 * (int32_t)u - pr) * pft_pv_tri(16 * (int32_t)d - pd);
            v += 384 * w / (24 * 24);
            pix[d * PFT_PV_NR2 + u] = (uint16_t)v;
        }
    }
}

static inline void pft_pv_frame(pft_frame_t *f, const uint16_t *pix, uint16_t w, uint16_t h)
{
    memset(f, 0, sizeof(*f));
    f->data = pix;
    f->width = w;
    f->height = h;
    f->stride_bytes = 2u * w;
    f->format = PFT_PIX_U16;
}

/* pixels of the current frame (both scenes) */
#define PFT_PV_PIX (PFT_PV_NR2 * PFT_PV_ND2 > PFT_PV_NR ? PFT_PV_NR2 * PFT_PV_ND2 : PFT_PV_NR)
static uint16_t pft_pv_pix[PFT_PV_PIX];

/* frame k of the range-time (rd false) or range-Doppler scene into pft_pv_pix and *f */
static inline void pft_pv_next(uint32_t *s, uint32_t k, bool rd, pft_frame_t *f)
{
    if (rd) {
        pft_pv_scene2(s, k, pft_pv_pix);
        pft_pv_frame(f, pft_pv_pix, PFT_PV_NR2, PFT_PV_ND2);
    } else {
        pft_pv_scene1(s, k, pft_pv_pix);
        pft_pv_frame(f, pft_pv_pix, PFT_PV_NR, 1);
    }
}

/* the same frame as values in input units (z = raw/64 - 67.4375, exact) */
static inline void pft_pv_values(const uint16_t *pix, uint32_t n, pft_real_t *z)
{
    for (uint32_t i = 0; i < n; ++i) {
        z[i] = PFT_GV_REAL(((int32_t)pix[i] - PFT_PV_BASE) * 1024);
    }
}

static inline void pft_pv_input(pft_pte_input_t *in)
{
    in->pixel_gain = PFT_C(0.015625);
    in->pixel_offset = PFT_C(-67.4375);
}

/* ------------------------------------------------------------------------- recording */

static inline uint32_t pft_pv_fnv(uint32_t h, int32_t v)
{
    uint32_t u = (uint32_t)v;
    for (int i = 0; i < 4; ++i) {
        h ^= (u >> (8 * i)) & 0xFFu;
        h *= 16777619u;
    }
    return h;
}

static inline uint32_t pft_pv_hash_rep(uint32_t h, const pft_pte_report_t *r)
{
    h = pft_pv_fnv(h, (int32_t)r->id);
    h = pft_pv_fnv(h, r->detected ? 1 : 0);
    for (int a = 0; a < 2; ++a) {
        h = pft_pv_fnv(h, PFT_GV_RAW(r->pos[a]));
        h = pft_pv_fnv(h, PFT_GV_RAW(r->vel[a]));
        h = pft_pv_fnv(h, PFT_GV_RAW(r->var[a]));
    }
    h = pft_pv_fnv(h, PFT_GV_RAW(r->amplitude));
    h = pft_pv_fnv(h, PFT_GV_RAW(r->score));
    return pft_pv_fnv(h, (int32_t)r->age);
}

/* records reports rep[0..n) of instance i at frame k; h0: hash of extra values */
static inline void pft_pv_record(pft_pv_results_t *res, uint32_t i, uint32_t k, pft_status_t st,
                                 const pft_pte_report_t *rep, uint32_t n, uint32_t h0)
{
    uint32_t h = h0;
    for (uint32_t j = 0; j < n; ++j) {
        h = pft_pv_hash_rep(h, &rep[j]);
    }
    if (res->status[i] == 0) {
        res->status[i] = (int32_t)st;
    }
    res->count[i][k] = (int32_t)n;
    res->hash[i][k] = h;
    res->id0[i][k] = n > 0u ? (int32_t)rep[0].id : -1;
    res->pos0[i][k] = n > 0u ? PFT_GV_RAW(rep[0].pos[0]) : 0;
    res->vel0[i][k] = n > 0u ? PFT_GV_RAW(rep[0].vel[0]) : 0;
    res->score0[i][k] = n > 0u ? PFT_GV_RAW(rep[0].score) : 0;
}

/* ------------------------------------------------------------------- configurations */

static inline void pft_pv_cfg_pte_table(pft_pte_config_t *c)
{
    pft_pte_config_default(c);
    c->in.n_range = PFT_PV_NR;
    c->in.n_doppler = 1;
    pft_pv_input(&c->in);
    c->init_threshold = PFT_C(18.0);
    c->max_len = 20u;
}

static inline void pft_pv_cfg_pte_exact(pft_pte_config_t *c)
{
    pft_pte_config_default(c);
    c->in.n_range = PFT_PV_NR;
    c->in.n_doppler = 1;
    pft_pv_input(&c->in);
    c->op = PFT_PTE_OP_EXACT;
    c->motion = PFT_PTE_MOTION_CV;
    c->q_sd[0] = PFT_C(0.014);
    c->n_dir[0] = 3u;
    c->max_len = 12u;
    c->init_frames = 8u;
    c->init_threshold = PFT_C(16.0);
    c->init_period = 5u;
    c->max_tracks = 3u;
    c->init_spread = 0u; /* the whole initiation DP at the search's frame (the table case spreads it) */
}

static inline void pft_pv_cfg_dp_slide(pft_pte_dp_config_t *c)
{
    pft_pte_dp_config_default(c);
    c->in.n_range = PFT_PV_NR;
    c->in.n_doppler = 1;
    pft_pv_input(&c->in);
    c->threshold = PFT_C(18.0);
}

static inline void pft_pv_cfg_dp_batch(pft_pte_dp_config_t *c)
{
    pft_pte_dp_config_default(c);
    c->in.n_range = PFT_PV_NR;
    c->in.n_doppler = 1;
    pft_pv_input(&c->in);
    c->in.noise = PFT_PTE_NOISE_CFAR;
    c->in.cfar_ref = 8u;
    c->in.noise_sigma = PFT_C(0.25);
    c->frames = 6u;
    c->gate[0] = 2u;
    c->amplitude = PFT_C(2.5);
    c->threshold = PFT_C(12.0);
    c->max_targets = 3u;
}

static inline void pft_pv_cfg_dbt(pft_pte_dbt_config_t *c, bool cfar)
{
    pft_pte_dbt_config_default(c);
    c->in.n_range = PFT_PV_NR;
    c->in.n_doppler = 1;
    pft_pv_input(&c->in);
    if (cfar) {
        c->in.noise = PFT_PTE_NOISE_CFAR;
        c->in.cfar_ref = 6u;
        c->in.cfar_guard = 1u;
        c->threshold = PFT_C(2.8);
        c->max_tracks = 8u;
        c->max_dets = 6u;
    }
}

static inline void pft_pv_cfg_pte_rd(pft_pte_config_t *c)
{
    pft_pte_config_default(c);
    c->in.n_range = PFT_PV_NR2;
    c->in.n_doppler = PFT_PV_ND2;
    pft_pv_input(&c->in);
    c->max_len = 10u;
    c->init_frames = 6u;
    c->max_tracks = 2u;
    c->scan_steps = 4u;
    c->n_dir[0] = 3u;
    c->n_dir[1] = 3u;
    c->init_threshold = PFT_C(20.0);
}

static inline void pft_pv_cfg_dp_rd(pft_pte_dp_config_t *c)
{
    pft_pte_dp_config_default(c);
    c->in.n_range = PFT_PV_NR2;
    c->in.n_doppler = PFT_PV_ND2;
    pft_pv_input(&c->in);
    c->frames = 6u;
    c->threshold = PFT_C(20.0);
    c->max_targets = 2u;
}

/* ---------------------------------------------------------------------------- runs */

/* workspaces (static: 8-aligned, large enough for every configuration above) */
#define PFT_PV_WS_WORDS 24000u
static uint64_t pft_pv_ws[PFT_PV_WS_WORDS];

/* What one tracker does with frame k: update, then its reports into rep (count in *n) and
 * the hash of anything else to record into *h. */
typedef pft_status_t (*pft_pv_step_t)(void *ctx, uint32_t k, const pft_frame_t *f,
                                      pft_pte_report_t *rep, uint32_t *n, uint32_t *h);

static pft_pte_report_t pft_pv_rep[PFT_PTE_DBT_MAX_TRACKS];

/* Runs a tracker over its scene (range-Doppler when rd) and records every frame. */
static inline void pft_pv_loop(pft_pv_results_t *res, uint32_t inst, bool rd, pft_pv_step_t step,
                               void *ctx)
{
    const uint32_t frames = rd ? PFT_PV_FRAMES2 : PFT_PV_FRAMES;
    uint32_t s = rd ? 0x2D0B1E5u : 0x1234567u;
    for (uint32_t k = 0; k < frames; ++k) {
        pft_frame_t f;
        pft_pv_next(&s, k, rd, &f);
        uint32_t n = 0;
        uint32_t h = 2166136261u;
        pft_status_t st = step(ctx, k, &f, pft_pv_rep, &n, &h);
        pft_pv_record(res, inst, k, st, pft_pv_rep, n, h);
    }
}

typedef struct {
    pft_pte_t p;
    bool values;     /* frames as values in input units (update_real) */
    bool cue;        /* a cue at frame 30 */
    bool edge;       /* a cue at frame 30 at cell 0.5 moving inward (not recorded) */
    pft_pv_results_t *res;
} pft_pv_pte_ctx_t;

static inline pft_status_t pft_pv_pte_step(void *ctx, uint32_t k, const pft_frame_t *f,
                                           pft_pte_report_t *rep, uint32_t *n, uint32_t *h)
{
    static pft_real_t z[PFT_PV_PIX];
    pft_pv_pte_ctx_t *c = (pft_pv_pte_ctx_t *)ctx;
    pft_status_t st;
    if (c->values) {
        pft_pv_values(pft_pv_pix, (uint32_t)f->width * f->height, z);
        st = pft_pte_update_real(&c->p, z);
    } else {
        st = pft_pte_update(&c->p, f);
    }
    if (c->cue && k == 30u) {
        /* a cue on target B (cell 50 - 1.75 - 0.77 at frame 30) */
        pft_real_t pos[2] = {PFT_C(47.5), PFT_C(0.0)};
        pft_real_t vel[2] = {PFT_C(-0.2), PFT_C(0.0)};
        pft_real_t pv[2] = {PFT_C(0.2), PFT_C(1.0)};
        pft_real_t vv[2] = {PFT_C(0.01), PFT_C(1.0)};
        uint16_t id = 0;
        c->res->cue_status = (int32_t)pft_pte_start(&c->p, pos, vel, pv, vv, PFT_C(3.0), 10u, &id);
        c->res->cue_id = (int32_t)id;
    }
    if (c->edge && k == 30u) {
        /* 20 frames of template back from cell 0.5 at 0.6 cells per frame: the operator
         * lines' older points lie beyond the response grid's padding */
        pft_real_t pos[2] = {PFT_C(0.5), PFT_C(0.0)};
        pft_real_t vel[2] = {PFT_C(0.6), PFT_C(0.0)};
        pft_real_t pv[2] = {PFT_C(0.2), PFT_C(1.0)};
        pft_real_t vv[2] = {PFT_C(0.01), PFT_C(1.0)};
        uint16_t id = 0;
        (void)pft_pte_start(&c->p, pos, vel, pv, vv, PFT_C(3.0), 20u, &id);
    }
    *n = (uint32_t)pft_pte_reports(&c->p, rep, PFT_PTE_MAX_TRACKS);
    for (uint32_t j = 0; c->edge && j < *n; ++j) {
        /* every report, not only the first: the cue's track is not the oldest */
        *h = pft_pv_fnv(*h, PFT_GV_RAW(rep[j].pos[0]));
        *h = pft_pv_fnv(*h, PFT_GV_RAW(rep[j].vel[0]));
        *h = pft_pv_fnv(*h, PFT_GV_RAW(rep[j].var[0]));
        *h = pft_pv_fnv(*h, PFT_GV_RAW(rep[j].score));
    }
    return st;
}

static inline void pft_pv_run_pte(pft_pv_results_t *res, uint32_t inst,
                                  const pft_pte_config_t *c, bool values, bool cue)
{
    static pft_pv_pte_ctx_t ctx;
    ctx.values = values;
    ctx.cue = cue;
    ctx.edge = inst == PFT_PV_PTE_EDGE;
    ctx.res = res;
    if (pft_pte_init(&ctx.p, c, pft_pv_ws, sizeof(pft_pv_ws)) == PFT_OK) {
        pft_pv_loop(res, inst, c->in.n_doppler > 1u, pft_pv_pte_step, &ctx);
    }
}

typedef struct {
    pft_pte_dp_t dp;
    bool batch;      /* disjoint batches: reset every K frames */
    uint32_t k;      /* K */
} pft_pv_dp_ctx_t;

static inline pft_status_t pft_pv_dp_step(void *ctx, uint32_t k, const pft_frame_t *f,
                                          pft_pte_report_t *rep, uint32_t *n, uint32_t *h)
{
    static int16_t path[2u * PFT_PTE_MAX_FRAMES];
    pft_pv_dp_ctx_t *c = (pft_pv_dp_ctx_t *)ctx;
    if (c->batch && k % c->k == 0u) {
        (void)pft_pte_dp_reset(&c->dp);
    }
    pft_status_t st = pft_pte_dp_update(&c->dp, f);
    *n = (uint32_t)pft_pte_dp_reports(&c->dp, rep, PFT_PTE_MAX_TRACKS);
    pft_real_t peak = PFT_C(0.0);
    (void)pft_pte_dp_peak(&c->dp, &peak);
    *h = pft_pv_fnv(*h, PFT_GV_RAW(peak));
    for (uint32_t j = 0; j < *n; ++j) {
        uint32_t len = (uint32_t)pft_pte_dp_path(&c->dp, j, path, 2u * PFT_PTE_MAX_FRAMES);
        for (uint32_t q = 0; q < len; ++q) {
            *h = pft_pv_fnv(*h, path[q]);
        }
    }
    return st;
}

static inline void pft_pv_run_dp(pft_pv_results_t *res, uint32_t inst,
                                 const pft_pte_dp_config_t *c, bool batch)
{
    static pft_pv_dp_ctx_t ctx;
    ctx.batch = batch;
    ctx.k = c->frames;
    if (pft_pte_dp_init(&ctx.dp, c, pft_pv_ws, sizeof(pft_pv_ws)) == PFT_OK) {
        pft_pv_loop(res, inst, c->in.n_doppler > 1u, pft_pv_dp_step, &ctx);
    }
}

static inline pft_status_t pft_pv_dbt_step(void *ctx, uint32_t k, const pft_frame_t *f,
                                           pft_pte_report_t *rep, uint32_t *n, uint32_t *h)
{
    static pft_pte_dbt_plot_t pl[PFT_PTE_DBT_MAX_DETS];
    pft_pte_dbt_t *b = (pft_pte_dbt_t *)ctx;
    (void)k;
    pft_status_t st = pft_pte_dbt_update(b, f);
    uint32_t np = (uint32_t)pft_pte_dbt_plots(b, pl, PFT_PTE_DBT_MAX_DETS);
    *h = pft_pv_fnv(*h, (int32_t)np);
    for (uint32_t j = 0; j < np; ++j) {
        *h = pft_pv_fnv(*h, PFT_GV_RAW(pl[j].pos[0]));
        *h = pft_pv_fnv(*h, PFT_GV_RAW(pl[j].pos[1]));
        *h = pft_pv_fnv(*h, PFT_GV_RAW(pl[j].peak));
    }
    *n = (uint32_t)pft_pte_dbt_reports(b, rep, PFT_PTE_DBT_MAX_TRACKS);
    return st;
}

static inline void pft_pv_run_dbt(pft_pv_results_t *res, uint32_t inst, const pft_pte_dbt_config_t *c)
{
    static pft_pte_dbt_t b;
    if (pft_pte_dbt_init(&b, c, pft_pv_ws, sizeof(pft_pv_ws)) == PFT_OK) {
        pft_pv_loop(res, inst, c->in.n_doppler > 1u, pft_pv_dbt_step, &b);
    }
}

/* noise-only Monte Carlo thresholds of a small DP and of a PTE initiation (32 cells) */
static inline void pft_pv_thresholds(pft_pv_results_t *res)
{
    static pft_pte_dp_t dp;
    static pft_pte_t p;
    pft_pte_dp_config_t dc;
    pft_pte_dp_config_default(&dc);
    dc.in.n_range = 32u;
    dc.in.n_doppler = 1u;
    dc.frames = 6u;
    pft_real_t vt = PFT_C(0.0);
    if (pft_pte_dp_init(&dp, &dc, pft_pv_ws, sizeof(pft_pv_ws)) == PFT_OK &&
        pft_pte_dp_threshold(&dp, PFT_C(0.05), 60u, 11u, &vt) == PFT_OK) {
        res->thr[0] = PFT_GV_RAW(vt);
    }
    pft_pte_config_t pc;
    pft_pte_config_default(&pc);
    pc.in.n_range = 32u;
    pc.in.n_doppler = 1u;
    pc.init_frames = 6u;
    pc.in.noise = PFT_PTE_NOISE_CFAR;
    pc.in.cfar_ref = 4u;
    vt = PFT_C(0.0);
    if (pft_pte_init(&p, &pc, pft_pv_ws, sizeof(pft_pv_ws)) == PFT_OK &&
        pft_pte_threshold(&p, PFT_C(0.05), 60u, 12u, &vt) == PFT_OK) {
        res->thr[1] = PFT_GV_RAW(vt);
    }
}

static inline void pft_pv_compute(pft_pv_results_t *res)
{
    memset(res, 0, sizeof(*res));
    pft_pte_config_t pc;
    pft_pte_dp_config_t dc;
    pft_pte_dbt_config_t bc;
    pft_pv_cfg_pte_table(&pc);
    pft_pv_run_pte(res, PFT_PV_PTE_TABLE, &pc, false, false);
    pft_pv_cfg_pte_exact(&pc);
    pft_pv_run_pte(res, PFT_PV_PTE_EXACT, &pc, true, true);
    pft_pv_cfg_dp_slide(&dc);
    pft_pv_run_dp(res, PFT_PV_DP_SLIDE, &dc, false);
    pft_pv_cfg_dp_batch(&dc);
    pft_pv_run_dp(res, PFT_PV_DP_BATCH, &dc, true);
    pft_pv_cfg_dbt(&bc, false);
    pft_pv_run_dbt(res, PFT_PV_DBT, &bc);
    pft_pv_cfg_dbt(&bc, true);
    pft_pv_run_dbt(res, PFT_PV_DBT_CFAR, &bc);
    pft_pv_cfg_pte_rd(&pc);
    pft_pv_run_pte(res, PFT_PV_PTE_RD, &pc, false, false);
    pft_pv_cfg_dp_rd(&dc);
    pft_pv_run_dp(res, PFT_PV_DP_RD, &dc, false);
    pft_pte_dbt_config_default(&bc);
    bc.in.n_range = PFT_PV_NR2;
    bc.in.n_doppler = PFT_PV_ND2;
    pft_pv_input(&bc.in);
    pft_pv_run_dbt(res, PFT_PV_DBT_RD, &bc);
    pft_pv_cfg_pte_table(&pc);
    pft_pv_run_pte(res, PFT_PV_PTE_EDGE, &pc, false, false);
    pft_pv_thresholds(res);
}
#endif
