/*
 * The calls behind the pf golden vectors (pf_q16_vectors.h), shared by the generator
 * gen_pf_vectors.c (host q16) and the replay test tests/unit/test_pf_golden.c (every preset).
 *
 * The engine's SIS, SIR and APF on
 *   - the bearings-only model (scale 1000, 300 particles, 14 steps of a constant-velocity truth),
 *   - the linear-Gaussian model (position-velocity, 200 particles, 12 steps),
 *   - the engine's TBD pixel model (SIR and APF, 400 particles, 20 frames of the gv_scene.h
 *     scene with one target),
 * and, for one APF run per model, the same steps with a known initial set written through the
 * engine's write access. Every step gives one row: the estimate, the statistics, a hash of the
 * particle states, one of the weights and one of pft_pf_mean_cov. For the TBD model the
 * position components are kept out of the hashes and recorded as sums over the particles with
 * E != 0 instead (so a change of the coordinate convention shows as a pure shift).
 */
#ifndef PFT_PF_VECTORS_SPEC_H
#define PFT_PF_VECTORS_SPEC_H
#include <string.h>
#include "pft/pft.h"
#include "pft/pft_pf_models.h"
#include "gv_scene.h"

/* row: est[6], ess_ratio, ess_first, log_evidence, flags, hash states, hash weights,
 * hash mean/cov, n_live, sum x (live), sum y (live) */
#define PFT_PV_ROW 16
#define PFT_PV_BRG_STEPS 14
#define PFT_PV_LG_STEPS 12
#define PFT_PV_TBD_STEPS 20
#define PFT_PV_NB 300u
#define PFT_PV_NL 200u
#define PFT_PV_NTBD 400u

typedef struct {
    uint32_t brg[4][PFT_PV_BRG_STEPS][PFT_PV_ROW]; /* SIS, SIR, APF, APF from a known set */
    uint32_t lg[4][PFT_PV_LG_STEPS][PFT_PV_ROW];
    uint32_t tbd[2][PFT_PV_TBD_STEPS][PFT_PV_ROW]; /* SIR, APF */
} pft_pv_results_t;

static uint64_t pft_pv_work[PFT_PF_WORKSPACE_BYTES(PFT_PV_NTBD, 6) / 8u + 1u];
static pft_pf_t pft_pv_pf;
static pft_real_t pft_pv_x[PFT_PV_NTBD * 6];
static pft_weight_t pft_pv_w[PFT_PV_NTBD];
static pft_real_t pft_pv_cov[6 * 6];
static uint16_t pft_pv_dim; /* state dimension of the model of the current run */

/* Integer Irwin-Hall N(0, 1) draw as a real (exact conversion in both builds). */
static inline pft_real_t pft_pv_gauss(pft_rng_t *r)
{
    int32_t n = 0;
    for (int q = 0; q < 12; ++q) {
        n += (int32_t)(pft_rng_u32(r) >> 16);
    }
    return pft_ratio(n - 6 * 65536, 65536);
}

/* One row after an update; tbd: the TBD model's state layout. */
static inline void pft_pv_row(const pft_pf_t *pf, int tbd, uint32_t *row)
{
    memset(row, 0, PFT_PV_ROW * sizeof(uint32_t));
    uint16_t dim = pft_pv_dim;
    pft_real_t est[6];
    memset(est, 0, sizeof est);
    (void)pft_pf_estimate(pf, est);
    for (uint16_t c = 0; c < dim && c < 6u; ++c) {
        row[c] = pft_gv_r(est[c]);
    }
    pft_pf_stats_t s;
    memset(&s, 0, sizeof s);
    (void)pft_pf_stats(pf, &s);
    row[6] = pft_gv_r(s.ess_ratio);
    row[7] = pft_gv_r(s.ess_first);
    row[8] = pft_gv_r(s.log_evidence);
    row[9] = s.step | (s.resampled ? 1u << 30 : 0u) | (s.resample_pending ? 1u << 31 : 0u);
    uint32_t n = (uint32_t)pft_pf_states(pf, pft_pv_x, PFT_PV_NTBD);
    (void)pft_pf_weights(pf, pft_pv_w, PFT_PV_NTBD);
    uint32_t hs = PFT_GV_FNV0, hw = PFT_GV_FNV0;
    uint32_t live = 0, sx = 0, sy = 0;
    for (uint32_t i = 0; i < n; ++i) {
        const pft_real_t *xi = pft_pv_x + (size_t)i * dim;
        for (uint16_t c = 0; c < dim; ++c) {
            if (tbd && (c == PFT_PF_TBD_X || c == PFT_PF_TBD_Y)) {
                continue;
            }
            hs = pft_gv_fnv(hs, pft_gv_r(xi[c]));
        }
        if (tbd && xi[PFT_PF_TBD_E] != PFT_C(0.0)) {
            ++live;
            sx += pft_gv_r(xi[PFT_PF_TBD_X]);
            sy += pft_gv_r(xi[PFT_PF_TBD_Y]);
        }
        hw = pft_gv_fnv(hw, pft_gv_w(pft_pv_w[i]));
    }
    row[10] = hs;
    row[11] = hw;
    if (!tbd) {
        pft_real_t mean[6];
        (void)pft_pf_mean_cov(pf, mean, pft_pv_cov);
        uint32_t hm = PFT_GV_FNV0;
        for (uint16_t c = 0; c < dim; ++c) {
            hm = pft_gv_fnv(hm, pft_gv_r(mean[c]));
        }
        for (uint32_t c = 0; c < (uint32_t)dim * dim; ++c) {
            hm = pft_gv_fnv(hm, pft_gv_r(pft_pv_cov[c]));
        }
        row[12] = hm;
    }
    row[13] = live;
    row[14] = sx;
    row[15] = sy;
}


/* A known initial set: the prior's draws with the first component moved by (i mod 5) / 4,
 * then log-weights -(i mod 7) / 100. */
static inline void pft_pv_known_set(pft_pf_t *pf)
{
    static pft_real_t lw[PFT_PV_NTBD];
    uint32_t n = (uint32_t)pft_pf_states(pf, pft_pv_x, PFT_PV_NTBD);
    for (uint32_t i = 0; i < n; ++i) {
        size_t o = (size_t)i * pft_pv_dim;
        pft_pv_x[o] = pft_add(pft_pv_x[o], pft_ratio((int32_t)(i % 5u), 4));
        lw[i] = pft_ratio(-(int32_t)(i % 7u), 100);
    }
    (void)pft_pf_set_states(pf, pft_pv_x, n);
    (void)pft_pf_set_logweights(pf, lw);
}

/* The engine of one run: kind, n particles, seed, the model iface; optionally the known set. */
static inline int pft_pv_start(const pft_pf_model_t *iface, pft_pf_kind_t kind, uint32_t n,
                               uint64_t seed, int known)
{
    pft_pf_config_t c;
    pft_pf_config_default(&c);
    c.kind = kind;
    c.n_particles = n;
    c.seed = seed;
    c.model = *iface;
    pft_pv_dim = iface->dim;
    if (pft_pf_init(&pft_pv_pf, &c, pft_pv_work, sizeof pft_pv_work) != PFT_OK) {
        return 0;
    }
    if (known) {
        pft_pv_known_set(&pft_pv_pf);
    }
    return 1;
}

/* ---- bearings ---- */
static inline void pft_pv_run_bearings(pft_pf_kind_t kind, int known, uint32_t rows[][PFT_PV_ROW])
{
    pft_pf_bearings_config_t bc;
    pft_pf_bearings_config_default(&bc, 1000);
    pft_pf_bearings_model_t m;
    pft_pf_model_t iface;
    if (pft_pf_bearings_model_init(&m, &bc, &iface) != PFT_OK) {
        return;
    }
    if (!pft_pv_start(&iface, kind, PFT_PV_NB, 31u + (uint64_t)kind, known)) {
        return;
    }
    pft_rng_t sim;
    pft_rng_seed(&sim, 301u);
    /* truth: x0 = [-50, 1, 700, -55] (benchmark x 1000), constant velocity */
    pft_real_t tx = PFT_C(-50.0), ty = PFT_C(700.0);
    for (int k = 0; k < PFT_PV_BRG_STEPS; ++k) {
        tx = pft_add(tx, PFT_C(1.0));
        ty = pft_add(ty, PFT_C(-55.0));
        pft_real_t z = pft_add(pft_atan2(ty, tx), pft_mul(PFT_C(0.005), pft_pv_gauss(&sim)));
        (void)pft_pf_update(&pft_pv_pf, &z);
        pft_pv_row(&pft_pv_pf, 0, rows[k]);
    }
}

/* ---- linear Gaussian ---- */
static inline void pft_pv_run_lg(pft_pf_kind_t kind, int known, uint32_t rows[][PFT_PV_ROW])
{
    pft_pf_lg_config_t lc;
    memset(&lc, 0, sizeof lc);
    lc.dim = 2;
    lc.meas = 1;
    lc.F[0] = PFT_C(1.0);
    lc.F[1] = PFT_C(1.0);
    lc.F[3] = PFT_C(1.0);
    lc.Lq[0] = PFT_C(0.15);
    lc.Lq[2] = PFT_C(0.3);
    lc.H[0] = PFT_C(1.0);
    lc.r_sd[0] = PFT_C(0.5);
    lc.m0[1] = PFT_C(1.0);
    lc.L0[0] = PFT_C(1.0);
    lc.L0[3] = PFT_C(0.5);
    pft_pf_lg_model_t m;
    pft_pf_model_t iface;
    if (pft_pf_lg_model_init(&m, &lc, &iface) != PFT_OK) {
        return;
    }
    if (!pft_pv_start(&iface, kind, PFT_PV_NL, 41u + (uint64_t)kind, known)) {
        return;
    }
    pft_rng_t sim;
    pft_rng_seed(&sim, 401u);
    for (int k = 0; k < PFT_PV_LG_STEPS; ++k) {
        pft_real_t z = pft_add(pft_from_int(k + 1), pft_mul(PFT_C(0.5), pft_pv_gauss(&sim)));
        (void)pft_pf_update(&pft_pv_pf, &z);
        pft_pv_row(&pft_pv_pf, 0, rows[k]);
    }
}

/* ---- TBD pixel model ---- */
static uint64_t pft_pv_mwork[PFT_PF_TBD_WORKSPACE_BYTES(PFT_GV_SCENE_W, PFT_GV_SCENE_H) / 8u + 1u];
static pft_pf_tbd_model_t pft_pv_tm;
static uint16_t pft_pv_raw[PFT_GV_SCENE_W * PFT_GV_SCENE_H];

static inline void pft_pv_run_tbd(pft_pf_kind_t kind, uint32_t rows[][PFT_PV_ROW])
{
    /* T1 of the tbd spec, a little brighter: frames 3-20 from column 4, row 5 */
    const pft_gv_target_t t = {3, 20, 4 * 16, 5 * 16, 8, 4, 2048};
    pft_tbd_config_t tc;
    pft_tbd_config_default(&tc);
    tc.noise_sigma = PFT_C(1.6015625);
    tc.pixel_gain = PFT_C(0.00390625);
    tc.pixel_offset = PFT_C(-64.0);
    tc.seed = 51u;
    pft_pf_model_t iface;
    if (pft_pf_tbd_model_init(&pft_pv_tm, &tc, pft_pv_mwork, sizeof pft_pv_mwork, &iface) != PFT_OK) {
        return;
    }
    if (!pft_pv_start(&iface, kind, PFT_PV_NTBD, 61u + (uint64_t)kind, 0)) {
        return;
    }
    pft_rng_t sim;
    pft_rng_seed(&sim, 501u);
    for (int32_t k = 1; k <= PFT_PV_TBD_STEPS; ++k) {
        pft_frame_t f;
        pft_gv_render(&sim, &t, 1, k, 410, pft_pv_raw, &f);
        pft_status_t st = pft_pf_update(&pft_pv_pf, &f);
        pft_pv_row(&pft_pv_pf, 1, rows[k - 1]);
        if (st != PFT_OK) {
            rows[k - 1][12] = 0xDEADu;
        }
    }
}

static inline void pft_pv_compute(pft_pv_results_t *r)
{
    memset(r, 0, sizeof(*r));
    pft_pv_run_bearings(PFT_PF_SIS, 0, r->brg[0]);
    pft_pv_run_bearings(PFT_PF_SIR, 0, r->brg[1]);
    pft_pv_run_bearings(PFT_PF_APF, 0, r->brg[2]);
    pft_pv_run_bearings(PFT_PF_APF, 1, r->brg[3]);
    pft_pv_run_lg(PFT_PF_SIS, 0, r->lg[0]);
    pft_pv_run_lg(PFT_PF_SIR, 0, r->lg[1]);
    pft_pv_run_lg(PFT_PF_APF, 0, r->lg[2]);
    pft_pv_run_lg(PFT_PF_SIR, 1, r->lg[3]);
    pft_pv_run_tbd(PFT_PF_SIR, r->tbd[0]);
    pft_pv_run_tbd(PFT_PF_APF, r->tbd[1]);
}

#endif
