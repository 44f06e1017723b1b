/* PTE-TBD: parameterized track enhancement (He, Liao, Yang & Sun 2015) as reconstructed in
 * docs/algorithms.md 5.2-5.3: batch DP initiation, L matched line operators per axis set by
 * the track state (the track step is in pte_track.c), per-direction Kalman updates,
 * likelihood-weighted fusion, closed-loop feedback, termination and re-initiation, several
 * targets with cancellation. This file: configuration, workspace, initiation, reports. */
#include "pte_int.h"
#include "../core/config_int.h"

#define SV_ PFT_PTE_SV_
#define SA_ PFT_PTE_SA_

void pft_pte_config_default(pft_pte_config_t *cfg)
{
    if (cfg == NULL) {
        return;
    }
    memset(cfg, 0, sizeof(*cfg));
    pft_pte_input_default(&cfg->in);
    cfg->init_frames = 10u;
    cfg->init_gate[0] = 1u;
    cfg->init_gate[1] = 1u;
    cfg->init_threshold = PFT_C(18.9);
    cfg->init_period = 10u;
    cfg->init_spread = 4u;
    cfg->max_len = 40u;
    cfg->n_dir[0] = 5u;
    cfg->n_dir[1] = 5u;
    cfg->motion = PFT_PTE_MOTION_CA;
    cfg->sigma_r[0] = PFT_C(0.5);
    cfg->sigma_r[1] = PFT_C(0.5);
    cfg->q_sd[0] = PFT_C(0.002);
    cfg->q_sd[1] = PFT_C(0.002);
    cfg->acc_sd0[0] = PFT_C(0.003);
    cfg->acc_sd0[1] = PFT_C(0.003);
    cfg->q_amp = PFT_C(0.01);
    cfg->dtheta_min = PFT_C(0.02);
    cfg->c_step = PFT_C(0.25);
    cfg->scan_steps = 16u;
    cfg->scan_sigmas = PFT_C(3.0);
    cfg->sigma_w_max = PFT_C(2.0);
    cfg->eta_t = PFT_C(3.5);
    cfg->max_misses = 3u;
    cfg->max_tracks = 4u;
    cfg->dup_cells = PFT_C(1.0);
    cfg->op = PFT_PTE_OP_AUTO;
    cfg->short_len = 0u;
    cfg->man_z = PFT_C(1.25);
    cfg->man_acc_sd = PFT_C(0.03);
    cfg->steady_dirs = 0u;
    cfg->slope_hold = PFT_C(0.0);
}

/* 1/c_step when it is an integer 1..8, else 0. */
static uint8_t period_(pft_real_t c_step)
{
    for (int32_t k = 1; k <= 8; ++k) {
        if (pft_mul_i(c_step, k) == PFT_REAL_ONE) {
            return (uint8_t)k;
        }
    }
    return 0u;
}

/* The operator evaluation AUTO stands for. */
static pft_pte_op_t op_of_(const pft_pte_config_t *c)
{
    if (c->op == PFT_PTE_OP_AUTO) {
        return c->in.n_doppler > 1u ? PFT_PTE_OP_EXACT : PFT_PTE_OP_TABLE;
    }
    return c->op;
}

/* Per-axis fields (struct order), NULL when both axes are usable. */
static const char *bad_axis_field_(const pft_pte_config_t *c)
{
    static const char *const nd[2] = {"n_dir[0]", "n_dir[1]"};
    static const char *const sr[2] = {"sigma_r[0]", "sigma_r[1]"};
    static const char *const qs[2] = {"q_sd[0]", "q_sd[1]"};
    static const char *const as[2] = {"acc_sd0[0]", "acc_sd0[1]"};
    for (uint32_t a = 0; a < 2u; ++a) {
        if (c->n_dir[a] < 1u || c->n_dir[a] > PFT_PTE_MAX_DIRS || (c->n_dir[a] & 1u) == 0u) {
            return nd[a];
        }
    }
    if (c->motion != PFT_PTE_MOTION_CV && c->motion != PFT_PTE_MOTION_CA) {
        return "motion";
    }
    for (uint32_t a = 0; a < 2u; ++a) {
        /* in float a subnormal sigma_r gave NaN tables (reliability.md F6) */
        if (!pft_cfg_real_pos_(c->sigma_r[a]) || c->sigma_r[a] > PFT_C(100.0)) {
            return sr[a];
        }
    }
    for (uint32_t a = 0; a < 2u; ++a) {
        if (!(c->q_sd[a] >= PFT_C(0.0)) || c->q_sd[a] > PFT_C(1.0)) {
            return qs[a];
        }
    }
    for (uint32_t a = 0; a < 2u; ++a) {
        if (!(c->acc_sd0[a] >= PFT_C(0.0)) || c->acc_sd0[a] > PFT_C(0.1)) {
            return as[a];
        }
    }
    return NULL;
}

/* Operator fields (struct order), NULL when usable. */
static const char *bad_operator_field_(const pft_pte_config_t *c)
{
    if (!(c->q_amp >= PFT_C(0.0)) || !pft_cfg_real_ok_(c->q_amp)) {
        return "q_amp";
    }
    if (!pft_cfg_real_pos_(c->dtheta_min)) {
        return "dtheta_min";
    }
    if (!pft_cfg_real_pos_(c->c_step) || c->c_step > PFT_C(4.0)) {
        return "c_step";
    }
    if (c->scan_steps < 1u || c->scan_steps > PFT_PTE_MAX_SCAN_STEPS) {
        return "scan_steps";
    }
    /* in float a scan_sigmas of 8.5e37 reached an out-of-range conversion (reliability.md F6) */
    if (!pft_cfg_real_pos_(c->scan_sigmas)) {
        return "scan_sigmas";
    }
    if (!pft_cfg_real_pos_(c->sigma_w_max) ||
        c->sigma_w_max > pft_ratio((int32_t)PFT_PTE_MAX_TAPS - 1, 6)) {
        return "sigma_w_max";
    }
    if (!pft_cfg_real_ok_(c->init_threshold)) {
        return "init_threshold";
    }
    if (!pft_cfg_real_ok_(c->eta_t)) {
        return "eta_t";
    }
    return NULL;
}

/* step_budget = B >= 1: the longest template, max_len + 1 - ceil(max_tracks / B) frames (a
 * track waits at most ceil(max_tracks / B) frames between two steps, and its slope entries
 * slide over them with the frames leaving its window still in the ring of max_len + 1). */
static uint32_t budget_len_(const pft_pte_config_t *c)
{
    const uint32_t wait = ((uint32_t)c->max_tracks + c->step_budget - 1u) / c->step_budget;
    return (uint32_t)c->max_len + 1u < wait + 2u ? 0u : (uint32_t)c->max_len + 1u - wait;
}

/* Smallest line_budget: two line sums (one frame in, one out) of every line of every window
 * of every slope entry of one track, so that a track's entries always gain on the frames. */
static uint32_t line_budget_min_(const pft_pte_config_t *c)
{
    uint32_t nwin = 1u;
    if (c->short_len != 0u) {
        nwin = 2u;
    }
    return 2u * (2u * (uint32_t)c->scan_steps + 1u) * (uint32_t)c->n_dir[0] * nwin;
}

/* First refused field in struct order (TABLE's requirements name op, c_step, in.zeta_clip). */
static const char *bad_field_(const pft_pte_config_t *c)
{
    const char *bad = pft_pte_input_bad_(&c->in);
    if (bad != NULL) {
        return bad;
    }
    if (c->init_frames < 2u || c->init_frames > PFT_PTE_MAX_FRAMES) {
        return "init_frames";
    }
    if (c->init_gate[0] > PFT_PTE_MAX_GATE) {
        return "init_gate[0]";
    }
    if (c->init_gate[1] > PFT_PTE_MAX_GATE) {
        return "init_gate[1]";
    }
    if (c->init_period < 1u) {
        return "init_period";
    }
    if (c->max_len < 2u || c->max_len > PFT_PTE_MAX_FRAMES) {
        return "max_len";
    }
    bad = bad_axis_field_(c);
    if (bad == NULL) {
        bad = bad_operator_field_(c);
    }
    if (bad != NULL) {
        return bad;
    }
    if (c->max_misses < 1u) {
        return "max_misses";
    }
    if (c->max_tracks < 1u || c->max_tracks > PFT_PTE_MAX_TRACKS) {
        return "max_tracks";
    }
    if (!(c->dup_cells >= PFT_C(0.0)) || !pft_cfg_real_ok_(c->dup_cells)) {
        return "dup_cells";
    }
    if (c->op != PFT_PTE_OP_EXACT && c->op != PFT_PTE_OP_TABLE && c->op != PFT_PTE_OP_AUTO) {
        return "op";
    }
    if (op_of_(c) == PFT_PTE_OP_TABLE) {
        if (c->in.n_doppler != 1u) {
            return "op"; /* TABLE operators are range-time only */
        }
        if (period_(c->c_step) == 0u) {
            return "c_step"; /* TABLE needs c_step = 1/Q, Q = 1..8 */
        }
        if (c->in.zeta_clip > PFT_C(64.0)) {
            return "in.zeta_clip"; /* TABLE's plain sums need zeta_clip <= 64 */
        }
    }
    /* the manoeuvre test reads the slope entries' second window (TABLE only) */
    if (c->short_len != 0u &&
        (c->short_len < 2u || c->short_len >= c->max_len || op_of_(c) != PFT_PTE_OP_TABLE)) {
        return "short_len";
    }
    if (!pft_cfg_real_pos_(c->man_z) || c->man_z > PFT_C(100.0)) {
        return "man_z";
    }
    if (!(c->man_acc_sd >= PFT_C(0.0)) || c->man_acc_sd > PFT_C(0.1)) {
        return "man_acc_sd";
    }
    if (c->step_budget > c->max_tracks ||
        (c->step_budget != 0u && (budget_len_(c) < 2u || c->short_len >= budget_len_(c)))) {
        return "step_budget";
    }
    /* line_budget: TABLE slope entries only; at least one slide of every entry of a track */
    if (c->line_budget != 0u &&
        (op_of_(c) != PFT_PTE_OP_TABLE || c->line_budget < line_budget_min_(c))) {
        return "line_budget";
    }
    /* steady_dirs: odd, 3 or more (a single direction's slope, the lattice point nearest the
     * prediction, would say nothing of the slope) and below n_dir[0]; TABLE slope entries */
    if (c->steady_dirs != 0u &&
        ((c->steady_dirs & 1u) == 0u || c->steady_dirs < 3u ||
         (uint32_t)c->steady_dirs + 2u > c->n_dir[0] ||
         op_of_(c) != PFT_PTE_OP_TABLE)) {
        return "steady_dirs";
    }
    /* slope_hold: up to half a lattice step beyond the midpoint; TABLE slope entries */
    if (!(c->slope_hold >= PFT_C(0.0)) || c->slope_hold > PFT_C(0.5) ||
        (c->slope_hold > PFT_C(0.0) && op_of_(c) != PFT_PTE_OP_TABLE)) {
        return "slope_hold";
    }
    return NULL;
}

pft_status_t pft_pte_config_check(const pft_pte_config_t *cfg, const char **field)
{
    if (field != NULL) {
        *field = NULL;
    }
    if (cfg == NULL) {
        return PFT_ERR_INVAL;
    }
    return pft_pte_check_done_(bad_field_(cfg), field);
}

/* Grid points per cell of the TABLE operators (0: EXACT). */
static uint32_t yq_of_(const pft_pte_config_t *c)
{
    return op_of_(c) == PFT_PTE_OP_TABLE ? period_(c->c_step) : 0u;
}

size_t pft_pte_workspace_size(const pft_pte_config_t *c)
{
    if (pft_pte_config_check(c, NULL) != PFT_OK) {
        return 0u;
    }
    return PFT_PTE_WORKSPACE_BYTES(c->in.n_range, c->in.n_doppler, c->max_len, c->init_frames,
                                   c->max_tracks, c->scan_steps, c->n_dir[0], c->n_dir[1],
                                   yq_of_(c));
}

/* The buffers of an instance, carved from its workspace in the order of
 * PFT_PTE_WORKSPACE_BYTES. */
typedef struct {
    pft_real_t *ring, *row, *ma, *mb;
    uint8_t *psi, *mask;
    int16_t *path;
    pft_real_t *gtab, *gw[2];
    pft_pte_track_t *tracks;
    pft_pte_report_t *rep;
    pft_real_t *sE, *sG, *sL, *tw[2];
    int16_t *tlo[2];
    pft_pte_dir_t *dir;
    pft_pte_scratch_t *scr;
    pft_real_t *yring, *gq;
    uint8_t *yflag;
    pft_pte_bank_t *bank;
    pft_real_t *bsum;
} layout_;

static pft_status_t carve_(const pft_pte_config_t *cfg, uint32_t yq, void *work, size_t len,
                           layout_ *l)
{
    const uint32_t cells = (uint32_t)cfg->in.n_range * cfg->in.n_doppler;
    const uint32_t nring = (uint32_t)PFT_PTE_RING_(cfg->max_len, cfg->init_frames);
    const uint32_t n = cfg->init_frames;
    const bool two = cfg->in.n_doppler > 1u;
    const uint32_t ns0 = 2u * cfg->scan_steps + 1u;
    const uint32_t ns1 = two ? ns0 : 1u;
    const uint32_t nd = (uint32_t)cfg->n_dir[0] * (two ? cfg->n_dir[1] : 1u);
    const uint32_t ny = ((uint32_t)cfg->in.n_range + 2u * PFT_PTE_YPAD) * yq;
    const uint32_t nyblk = ((uint32_t)cfg->in.n_range + 2u * PFT_PTE_YPAD + 7u) / 8u;
    pft_ws_t ws;
    pft_ws_init(&ws, work, len);
    memset(l, 0, sizeof(*l));
    l->ring = pft_ws_take(&ws, (size_t)nring * cells * sizeof(pft_real_t));
    l->row = pft_ws_take(&ws, (size_t)cfg->in.n_range * sizeof(pft_real_t));
    l->ma = pft_ws_take(&ws, (size_t)cells * sizeof(pft_real_t));
    l->mb = pft_ws_take(&ws, (size_t)cells * sizeof(pft_real_t));
    l->psi = pft_ws_take(&ws, (size_t)n * cells);
    l->mask = pft_ws_take(&ws, (size_t)n * cells);
    l->path = pft_ws_take(&ws, (size_t)n * 2u * sizeof(int16_t));
    l->gtab = pft_ws_take(&ws, (size_t)PFT_PTE_GTAB_SIZE * sizeof(pft_real_t));
    l->gw[0] = pft_ws_take(&ws, (size_t)PFT_PTE_GW_SIZE * sizeof(pft_real_t));
    l->gw[1] = two ? pft_ws_take(&ws, (size_t)PFT_PTE_GW_SIZE * sizeof(pft_real_t)) : l->gw[0];
    l->tracks = pft_ws_take(&ws, (size_t)cfg->max_tracks * sizeof(pft_pte_track_t));
    l->rep = pft_ws_take(&ws, (size_t)cfg->max_tracks * sizeof(pft_pte_report_t));
    l->sE = pft_ws_take(&ws, (size_t)ns0 * ns1 * sizeof(pft_real_t));
    l->sG = pft_ws_take(&ws, (size_t)ns0 * ns1 * sizeof(pft_real_t));
    l->sL = pft_ws_take(&ws, (size_t)ns0 * ns1 * sizeof(pft_real_t));
    l->tw[0] = pft_ws_take(&ws, (size_t)ns0 * PFT_PTE_MAX_TAPS * sizeof(pft_real_t));
    l->tw[1] = pft_ws_take(&ws, (size_t)ns1 * PFT_PTE_MAX_TAPS * sizeof(pft_real_t));
    l->tlo[0] = pft_ws_take(&ws, (size_t)ns0 * 4u * sizeof(int16_t));
    l->tlo[1] = pft_ws_take(&ws, (size_t)ns1 * 4u * sizeof(int16_t));
    l->dir = pft_ws_take(&ws, (size_t)nd * sizeof(pft_pte_dir_t));
    l->scr = pft_ws_take(&ws, sizeof(pft_pte_scratch_t));
    if (yq > 0u) {
        l->yring = pft_ws_take(&ws, (size_t)nring * ny * sizeof(pft_real_t));
        l->gq = pft_ws_take(&ws, (size_t)ny * sizeof(pft_real_t));
        l->yflag = pft_ws_take(&ws, (size_t)nring * nyblk);
        l->bank = pft_ws_take(&ws, (size_t)cfg->max_tracks * PFT_PTE_NBANK_(cfg->n_dir[0]) *
                                       sizeof(pft_pte_bank_t));
        l->bsum = pft_ws_take(&ws, (size_t)cfg->max_tracks * PFT_PTE_NBANK_(cfg->n_dir[0]) *
                                       PFT_PTE_NWIN_ * ns0 * sizeof(pft_real_t));
    }
    return pft_ws_status(&ws);
}

pft_status_t pft_pte_init(pft_pte_t *p, const pft_pte_config_t *cfg, void *work, size_t work_len)
{
    if (p == NULL || cfg == NULL || work == NULL) {
        return PFT_ERR_INVAL;
    }
    if (pft_pte_config_check(cfg, NULL) != PFT_OK) {
        return PFT_ERR_CONFIG;
    }
    const uint32_t yq = yq_of_(cfg);
    layout_ l;
    if (carve_(cfg, yq, work, work_len, &l) != PFT_OK) {
        return PFT_ERR_NOMEM;
    }
    memset(p, 0, sizeof(*p));
    p->cfg = *cfg;
    p->cfg.op = op_of_(cfg);
    const uint32_t nring = (uint32_t)PFT_PTE_RING_(cfg->max_len, cfg->init_frames);
    pft_pte_ring_setup_(&p->ring, l.ring, (uint16_t)nring,
                        (uint32_t)cfg->in.n_range * cfg->in.n_doppler);
    p->row = l.row;
    p->ma = l.ma;
    p->mb = l.mb;
    p->psi = l.psi;
    p->mask = l.mask;
    p->path = l.path;
    p->gtab = l.gtab;
    p->gw[0] = l.gw[0];
    p->gw[1] = l.gw[1];
    p->tracks = l.tracks;
    p->rep = l.rep;
    p->sE = l.sE;
    p->sG = l.sG;
    p->sL = l.sL;
    p->tw[0] = l.tw[0];
    p->tw[1] = l.tw[1];
    p->tlo[0] = l.tlo[0];
    p->tlo[1] = l.tlo[1];
    p->dir = l.dir;
    p->scr = l.scr;
    p->naxes = cfg->in.n_doppler > 1u ? 2u : 1u;
    pft_pte_model_setup_(p);
    /* scan positions one cell apart share their tap weights when c_step = 1/period */
    p->period = period_(cfg->c_step);
    /* g(t) = exp(-t^2/2), t = i/64 */
    for (uint32_t i = 0; i < PFT_PTE_GTAB_SIZE; ++i) {
        pft_real_t t = pft_ratio((int32_t)i, 64);
        p->gtab[i] = pft_exp(pft_neg(pft_mul(pft_sq(t), PFT_C(0.5))));
    }
    p->yq = (uint8_t)yq;
    p->short_len = cfg->short_len; /* 0 unless TABLE (config check) */
    p->ny = ((uint32_t)cfg->in.n_range + 2u * PFT_PTE_YPAD) * yq;
    p->yring = l.yring;
    p->gq = l.gq;
    p->yflag = l.yflag;
    p->nyblk = (uint16_t)(((uint32_t)cfg->in.n_range + 2u * PFT_PTE_YPAD + 7u) / 8u);
    p->bank = l.bank;
    p->bsum = l.bsum;
    p->nbank = (uint16_t)PFT_PTE_NBANK_(cfg->n_dir[0]);
    p->nline = (uint16_t)(2u * cfg->scan_steps + 1u);
    if (yq > 0u) {
        pft_pte_ytable_setup_(p);
    }
#ifdef PFT_NUMERIC_Q16
    pft_pte_f32_table_(&p->cfg.in, p->f32t);
#endif
    return pft_pte_reset(p);
}

pft_status_t pft_pte_reset(pft_pte_t *p)
{
    if (p == NULL || p->ring.buf == NULL) {
        return PFT_ERR_INVAL;
    }
    p->ring.count = 0u;
    p->ring.head = (uint16_t)(p->ring.len - 1u);
    memset(p->tracks, 0, (size_t)p->cfg.max_tracks * sizeof(pft_pte_track_t));
    if (p->bank != NULL) {
        memset(p->bank, 0, (size_t)p->cfg.max_tracks * p->nbank * sizeof(pft_pte_bank_t));
    }
    p->frames_in = 0u;
    memset(&p->seq, 0, sizeof(p->seq));
    p->next_id = 1u;
    p->since_search = 0u;
    p->init_stage = 0u;
    p->init_todo = 0u;
    p->init_run = 0u;
    p->n_steps = 0u;
    p->n_line_ops = 0u;
    p->line_used = 0u;
    p->n_rep = 0u;
    memset(p->miss, 0, sizeof(p->miss));
    return PFT_OK;
}

static void core_(const pft_pte_t *p, pft_pte_core_t_ *c)
{
    c->ring = &p->ring;
    c->nr = p->cfg.in.n_range;
    c->nd = p->cfg.in.n_doppler;
    c->k = p->cfg.init_frames;
    c->g0 = p->cfg.init_gate[0];
    c->g1 = p->cfg.init_gate[1];
    c->amp = PFT_C(0.0);
    c->ma = p->ma;
    c->mb = p->mb;
    c->psi = p->psi;
    c->mask = p->mask;
}

/* ----------------------------------------------------------------------- initiation */

static int32_t half_cells_(pft_real_t sw)
{
    /* ceil(3 sigma_w) */
    return -pft_floor_int(pft_neg(pft_mul_i(sw, 3)));
}

/* New track from unscaled position/velocity moments per axis (na axes used). */
static void track_new_(pft_pte_t *p, pft_pte_track_t *t, const pft_real_t pos[2],
                       const pft_real_t vel[2], const pft_real_t pv[2], const pft_real_t vv[2],
                       const pft_real_t cv[2], pft_real_t amp, uint8_t n_acc)
{
    memset(t, 0, sizeof(*t));
    if (p->bank != NULL) { /* TABLE: no slope entry of the slot's previous track survives */
        memset(p->bank + (size_t)(t - p->tracks) * p->nbank, 0, p->nbank * sizeof(pft_pte_bank_t));
    }
    for (uint32_t a = 0; a < p->naxes; ++a) {
        t->x[a][0] = pos[a];
        t->x[a][1] = pft_mul_i(vel[a], SV_);
        t->P[a][0] = pv[a];
        t->P[a][1] = pft_mul_i(cv[a], SV_);
        t->P[a][4] = t->P[a][1];
        t->P[a][5] = pft_mul_i(vv[a], SV_ * SV_);
        if (p->cfg.motion == PFT_PTE_MOTION_CA) {
            t->P[a][10] = pft_sq(pft_mul_i(p->cfg.acc_sd0[a], SA_));
        }
    }
    t->amp = amp;
    t->amp_var = PFT_C(1.0);
    t->n_acc = n_acc;
    t->live = true;
    t->detected = true;
    t->id = pft_pte_new_id_(&p->next_id);
}

static uint32_t n_live_(const pft_pte_t *p)
{
    uint32_t n = 0;
    for (uint32_t i = 0; i < p->cfg.max_tracks; ++i) {
        n += p->tracks[i].live ? 1u : 0u;
    }
    return n;
}

/* Cancels the cells of every live track, its state extrapolated back over the batch. */
static void cancel_live_(pft_pte_t *p, const pft_pte_core_t_ *core)
{
    const pft_pte_config_t *c = &p->cfg;
    const uint32_t N = c->init_frames;
    for (uint32_t i = 0; i < c->max_tracks; ++i) {
        const pft_pte_track_t *t = &p->tracks[i];
        if (!t->live) {
            continue;
        }
        int32_t h[2] = {0, 0};
        for (uint32_t a = 0; a < p->naxes; ++a) {
            pft_real_t sw = pft_min(pft_sqrt(pft_add(pft_sq(c->sigma_r[a]), t->P[a][0])),
                                    c->sigma_w_max);
            h[a] = half_cells_(sw);
        }
        for (uint32_t j = 0; j < N; ++j) {
            int32_t back = (int32_t)N - 1 - (int32_t)j;
            for (uint32_t a = 0; a < 2u; ++a) {
                int32_t u = a < p->naxes
                                ? pft_round_int(pft_sub(t->x[a][0], pft_pte_shift_(t->x[a][1], t->x[a][2], back)))
                                : 0;
                u = u < -30000 ? -30000 : (u > 30000 ? 30000 : u);
                p->path[2u * j + a] = (int16_t)u;
            }
        }
        pft_pte_core_cancel_(core, p->path, h[0], h[1]);
    }
}

/* Starts a track from the backtracked path in p->path (best final merit `best`) in a free
 * slot and cancels its cells in every frame of the batch. */
static void extract_(pft_pte_t *p, const pft_pte_core_t_ *core, pft_real_t best)
{
    const pft_pte_config_t *c = &p->cfg;
    const uint32_t N = c->init_frames;
    pft_real_t pos[2] = {PFT_C(0.0), PFT_C(0.0)};
    pft_real_t vel[2] = {PFT_C(0.0), PFT_C(0.0)};
    pft_real_t pv[2] = {PFT_C(1.0), PFT_C(1.0)};
    pft_real_t vv[2] = {PFT_C(1.0), PFT_C(1.0)};
    pft_real_t cv[2] = {PFT_C(0.0), PFT_C(0.0)};
    int32_t h[2] = {0, 0};
    int32_t n = (int32_t)N;
    for (uint32_t a = 0; a < p->naxes; ++a) {
        pft_pte_core_fit_(core, p->path, a, &pos[a], &vel[a]);
        pft_real_t s2 = pft_sq(c->sigma_r[a]);
        pv[a] = pft_mul(s2, pft_ratio(2 * (2 * n - 1), n * (n + 1)));
        cv[a] = pft_mul(s2, pft_ratio(6, n * (n + 1)));
        vv[a] = pft_mul(s2, pft_ratio(12, n * (n * n - 1)));
        pft_real_t sw = pft_min(pft_sqrt(pft_add(s2, pv[a])), c->sigma_w_max);
        h[a] = half_cells_(sw);
    }
    if (p->naxes != 2u) {
        pv[1] = PFT_C(1.0);
        vv[1] = PFT_C(1.0);
    }
    for (uint32_t i = 0; i < c->max_tracks; ++i) {
        if (!p->tracks[i].live) {
            track_new_(p, &p->tracks[i], pos, vel, pv, vv, cv, pft_pte_core_amp_(core, p->path),
                       (uint8_t)N);
            p->tracks[i].score = best;
            break;
        }
    }
    pft_pte_core_cancel_(core, p->path, h[0], h[1]);
}

/* Step 2: DP batch over the last init_frames frames outside the live tracks; every path
 * above init_threshold starts a track in a free slot and is cancelled for the next one. */
static void initiate_(pft_pte_t *p)
{
    const pft_pte_config_t *c = &p->cfg;
    pft_pte_core_t_ core;
    core_(p, &core);
    const uint32_t N = c->init_frames;
    const uint32_t cells = (uint32_t)c->in.n_range * c->in.n_doppler;
    memset(p->mask, 0, (size_t)N * cells);
    cancel_live_(p, &core);
    uint32_t live = n_live_(p);
    for (uint32_t guard = 0; guard < c->max_tracks && live < c->max_tracks; ++guard) {
        int32_t cell;
        pft_real_t best = pft_pte_core_run_(&core, &cell);
        if (cell < 0 || !(best > c->init_threshold)) {
            break;
        }
        pft_pte_core_backtrack_(&core, cell, p->path);
        extract_(p, &core, best);
        live++;
    }
}

/* init_spread: cancels the cells of every live track at the newest frame in mask row j. */
static void cancel_live_now_(pft_pte_t *p, uint32_t j)
{
    const pft_pte_config_t *c = &p->cfg;
    const int32_t nr = (int32_t)c->in.n_range;
    const int32_t nd = (int32_t)c->in.n_doppler;
    uint8_t *mk = p->mask + (size_t)j * (size_t)nr * (size_t)nd;
    memset(mk, 0, (size_t)nr * (size_t)nd);
    for (uint32_t i = 0; i < c->max_tracks; ++i) {
        const pft_pte_track_t *t = &p->tracks[i];
        if (!t->live) {
            continue;
        }
        int32_t lo[2] = {0, 0};
        int32_t hi[2] = {0, 0};
        const int32_t n[2] = {nr, nd};
        for (uint32_t a = 0; a < 2u; ++a) {
            if (a >= p->naxes) {
                continue; /* range-time: the one Doppler row */
            }
            pft_real_t sw = pft_min(pft_sqrt(pft_add(pft_sq(c->sigma_r[a]), t->P[a][0])),
                                    c->sigma_w_max);
            int32_t h = half_cells_(sw);
            int32_t u = pft_round_int(t->x[a][0]);
            u = u < -30000 ? -30000 : (u > 30000 ? 30000 : u);
            lo[a] = u - h < 0 ? 0 : u - h;
            hi[a] = u + h > n[a] - 1 ? n[a] - 1 : u + h;
        }
        for (int32_t d = lo[1]; d <= hi[1]; ++d) {
            for (int32_t r = lo[0]; r <= hi[0]; ++r) {
                mk[d * nr + r] = 1u;
            }
        }
    }
}

/* Step 2 spread over the frames (init_spread = S): the running search has done init_stage
 * DP stages and init_todo frames of the ring (the newest included) wait for theirs; at most S
 * stages per update, oldest first. At the last stage (the newest frame: the search's batch
 * is the last N frames of the ring) the best path above init_threshold starts a track, and
 * so does every next best one whose path crosses no cancelled cell. Returns true when a
 * search completed. */
static bool initiate_spread_(pft_pte_t *p)
{
    const pft_pte_config_t *c = &p->cfg;
    pft_pte_core_t_ core;
    core_(p, &core);
    const uint32_t N = c->init_frames;
    const pft_real_t *merit = NULL;
    /* init_stage stays below N here: init_stage + init_todo starts at back + 1 <= N -
     * ceil(N / S) + 1 and grows by one per update, and the stages done after u updates are
     * min(S u, that sum), so they reach N exactly when the sum does (spread_start_) */
    for (uint32_t s = 0; s < c->init_spread && p->init_todo > 0u; ++s) {
        const uint32_t j = p->init_stage;
        const uint32_t back = (uint32_t)p->init_todo - 1u;
        cancel_live_now_(p, j);
        merit = pft_pte_core_stage_(&core, j, pft_pte_ring_get_(&p->ring, back));
        p->init_todo--;
        p->init_stage = (uint8_t)(j + 1u);
    }
    if (p->init_stage < N) {
        return false;
    }
    p->init_stage = 0u;
    p->init_todo = 0u;
    p->init_run = 0u;
    uint32_t live = n_live_(p);
    bool more = merit != NULL;
    for (uint32_t guard = 0; guard < c->max_tracks && live < c->max_tracks && more; ++guard) {
        int32_t cell;
        pft_real_t best = pft_pte_core_best_(&core, merit, &cell);
        more = cell >= 0 && best > c->init_threshold;
        if (more) {
            pft_pte_core_backtrack_(&core, cell, p->path);
            /* a path crossing a cancelled cell is left to the next search (a re-run could
             * find another one) */
            more = pft_pte_core_clear_(&core, p->path);
        }
        if (more) {
            extract_(p, &core, best);
            live++;
        }
    }
    return true;
}

/* init_spread: starts a search when none runs. With no live track it starts on frames
 * already held so that, at init_spread stages per update, it ends at the newest frame after
 * ceil(N / init_spread) updates; with live tracks on the newest frame (one stage per update:
 * their cells at earlier frames are not cancelled). */
static void spread_start_(pft_pte_t *p, uint32_t live)
{
    const uint32_t N = p->cfg.init_frames;
    const uint32_t S = p->cfg.init_spread;
    uint32_t back = 0u;
    if (live == 0u) {
        back = N - (N + S - 1u) / S;
        if (back > (uint32_t)p->ring.count - 1u) {
            back = (uint32_t)p->ring.count - 1u;
        }
    }
    p->init_stage = 0u;
    p->init_todo = (uint8_t)back; /* the newest frame is counted by the caller */
    p->init_run = 1u;
}

static void dedup_(pft_pte_t *p)
{
    const pft_pte_config_t *c = &p->cfg;
    if (!(c->dup_cells > PFT_C(0.0))) {
        return;
    }
    for (uint32_t i = 0; i < c->max_tracks; ++i) {
        for (uint32_t j = i + 1u; j < c->max_tracks; ++j) {
            pft_pte_track_t *a = &p->tracks[i];
            pft_pte_track_t *b = &p->tracks[j];
            if (!a->live || !b->live) {
                continue;
            }
            bool near = pft_abs(pft_sub(a->x[0][0], b->x[0][0])) < c->dup_cells;
            if (p->naxes == 2u) {
                near = near && pft_abs(pft_sub(a->x[1][0], b->x[1][0])) < c->dup_cells;
            }
            if (near) {
                /* the lower score ends; on a tie the younger */
                bool drop_b = b->score < a->score || (b->score == a->score && b->age <= a->age);
                (drop_b ? b : a)->live = false;
            }
        }
    }
}

static void reports_(pft_pte_t *p)
{
    uint32_t n = 0;
    for (uint32_t i = 0; i < p->cfg.max_tracks; ++i) {
        const pft_pte_track_t *t = &p->tracks[i];
        if (!t->live) {
            continue;
        }
        pft_pte_report_t *r = &p->rep[n++];
        memset(r, 0, sizeof(*r));
        r->id = t->id;
        r->detected = t->detected;
        for (uint32_t a = 0; a < p->naxes; ++a) {
            r->pos[a] = t->x[a][0];
            r->vel[a] = pft_div_i(t->x[a][1], SV_);
            r->var[a] = t->P[a][0];
        }
        r->amplitude = t->amp;
        r->score = t->score;
        r->age = t->age;
    }
    p->n_rep = (uint8_t)n;
}

/* n lost frames (1 < k = n + 1 <= max_gap; docs/algorithms.md 5.7): each takes a ring slot
 * marked missing with zeta = 0 (the noise mean: the operators' E sums gain nothing from it
 * and their normalisers G skip it; in an initiation batch it is a missing stage, whose merit
 * adds 0), and every live track predicts over its period (no miss counted). The running
 * initiation search ends (its last stage would no longer be the newest frame); the next one
 * starts on the received frame. */
static void lost_frames_(pft_pte_t *p, uint32_t n)
{
    const size_t cells = (size_t)p->cfg.in.n_range * p->cfg.in.n_doppler;
    p->init_run = 0u;
    p->init_stage = 0u;
    p->init_todo = 0u;
    for (uint32_t f = 0; f < n; ++f) {
        memset(pft_pte_ring_next_(&p->ring), 0, cells * sizeof(pft_real_t));
        pft_pte_ring_commit_(&p->ring);
        p->miss[p->ring.head] = 1u;
        if (p->yq > 0u) {
            memset(p->yflag + (size_t)p->ring.head * p->nyblk, 0, p->nyblk);
        }
        p->frames_in++;
        for (uint32_t i = 0; i < p->cfg.max_tracks; ++i) {
            if (p->tracks[i].live) {
                pft_pte_track_coast_(p, &p->tracks[i]);
            }
        }
    }
}

/* Step 3 of every live track, or under step_budget = B the B live tracks that waited
 * longest (ties: the lower slot); the others predict over the frame as over a lost one
 * (pft_pte_track_coast_) and slide their line sums over the frames they missed at their
 * next step. Templates are capped at budget_len_ frames before the steps. Under line_budget
 * the tracks try in the same order (every live one without step_budget) and a track whose
 * slope entries the budget left incomplete predicts over the frame; wait counts the frames
 * since a completed step. */
static void steps_(pft_pte_t *p)
{
    const pft_pte_config_t *c = &p->cfg;
    uint32_t n = 0u;
    if (c->step_budget == 0u && c->line_budget == 0u) {
        for (uint32_t i = 0; i < c->max_tracks; ++i) {
            if (p->tracks[i].live) {
                (void)pft_pte_track_step_(p, &p->tracks[i]);
                n++;
            }
        }
        p->n_steps = (uint8_t)n;
        return;
    }
    const uint8_t cap = c->step_budget != 0u ? (uint8_t)budget_len_(c) : 0xFFu;
    const uint32_t nb = c->step_budget != 0u ? c->step_budget : c->max_tracks;
    bool go[PFT_PTE_MAX_TRACKS];
    for (uint32_t i = 0; i < c->max_tracks; ++i) {
        pft_pte_track_t *t = &p->tracks[i];
        go[i] = false;
        if (t->live) {
            t->n_acc = t->n_acc > cap ? cap : t->n_acc;
            t->wait = (uint8_t)(t->wait < 0xFFu ? t->wait + 1u : t->wait);
        }
    }
    for (uint32_t b = 0; b < nb; ++b) {
        int32_t best = -1;
        for (uint32_t i = 0; i < c->max_tracks; ++i) {
            if (p->tracks[i].live && !go[i] &&
                (best < 0 || p->tracks[i].wait > p->tracks[best].wait)) {
                best = (int32_t)i;
            }
        }
        if (best >= 0) {
            /* in this order (the steps of different tracks share no state but the budget) */
            go[best] = true;
            if (pft_pte_track_step_(p, &p->tracks[best])) {
                p->tracks[best].wait = 0u;
                n++;
            }
        }
    }
    for (uint32_t i = 0; i < c->max_tracks; ++i) {
        pft_pte_track_t *t = &p->tracks[i];
        if (t->live && !go[i]) {
            pft_pte_track_coast_(p, t);
            if (c->line_budget != 0u) {
                pft_pte_track_waited_(p, t);
            }
        }
    }
    p->n_steps = (uint8_t)n;
}

static pft_status_t update_(pft_pte_t *p, const pft_frame_t *frame, const pft_real_t *z)
{
    if (p == NULL || p->ring.buf == NULL) {
        return PFT_ERR_INVAL;
    }
    uint32_t k = 1u;
    pft_status_t st = pft_pte_seq_check_(&p->cfg.in, &p->seq, frame, &k);
    if (st != PFT_OK) {
        return st; /* nothing touched */
    }
    if (k != 1u) {
        if (k == 0u) {
            /* a gap above max_gap: the window restarts on this frame (tracks end, ids go on) */
            const uint16_t id = p->next_id;
            (void)pft_pte_reset(p);
            p->next_id = id;
        } else {
            lost_frames_(p, k - 1u);
        }
    }
#ifdef PFT_NUMERIC_Q16
    st = pft_pte_push_f32t_(&p->cfg.in, &p->ring, p->row, frame, z, p->f32t);
#else
    st = pft_pte_push_(&p->cfg.in, &p->ring, p->row, frame, z);
#endif
    if (st != PFT_OK) {
        return st;
    }
    if (p->yq > 0u) {
        memset(p->yflag + (size_t)p->ring.head * p->nyblk, 0, p->nyblk);
    }
    p->miss[p->ring.head] = 0u;
    p->frames_in++;
    p->n_line_ops = 0u;
    p->line_used = 0u;
    steps_(p);
    dedup_(p);
    if (p->since_search < 0xFFFFu) {
        p->since_search++;
    }
    uint32_t live = n_live_(p);
    if (p->cfg.init_spread != 0u) {
        /* while tracks are live a search completes every max(init_period, N) frames */
        const int32_t wait = (int32_t)p->cfg.init_period - (int32_t)p->cfg.init_frames + 1;
        if (p->init_run == 0u && live < p->cfg.max_tracks &&
            (live == 0u || (int32_t)p->since_search >= wait)) {
            spread_start_(p, live);
        }
        if (p->init_run != 0u) {
            p->init_todo++; /* the newest frame */
            if (initiate_spread_(p)) {
                p->since_search = 0u;
            }
        }
    } else {
        if (p->ring.count >= p->cfg.init_frames && live < p->cfg.max_tracks &&
            (live == 0u || p->since_search >= p->cfg.init_period)) {
            p->since_search = 0u;
            initiate_(p);
        }
    }
    reports_(p);
    pft_pte_seq_take_(&p->cfg.in, &p->seq, frame, p->rep, p->n_rep);
    return PFT_OK;
}

pft_status_t pft_pte_update(pft_pte_t *p, const pft_frame_t *frame)
{
    if (frame == NULL) {
        return PFT_ERR_INVAL;
    }
    return update_(p, frame, NULL);
}

pft_status_t pft_pte_update_real(pft_pte_t *p, const pft_real_t *z)
{
    if (z == NULL) {
        return PFT_ERR_INVAL;
    }
    return update_(p, NULL, z);
}

size_t pft_pte_reports(const pft_pte_t *p, pft_pte_report_t *out, size_t max)
{
    if (p == NULL || p->ring.buf == NULL) {
        return 0u;
    }
    return pft_pte_copy_out_(p->rep, p->n_rep, sizeof(pft_pte_report_t), out, max);
}

pft_status_t pft_pte_start(pft_pte_t *p, const pft_real_t pos[2],
                           const pft_real_t vel[2], const pft_real_t pos_var[2],
                           const pft_real_t vel_var[2], pft_real_t amp, uint8_t n_acc,
                           uint16_t *id)
{
    if (p == NULL || p->ring.buf == NULL || pos == NULL || vel == NULL || pos_var == NULL ||
        vel_var == NULL || id == NULL || n_acc == 0u) {
        return PFT_ERR_INVAL;
    }
    for (uint32_t a = 0; a < p->naxes; ++a) {
        /* the configuration domain of both builds (core/config_int.h): a float position of
         * 1.3e13 reached an out-of-range conversion in the next update (reliability.md F1) */
        if (!pft_cfg_real_pos_(pos_var[a]) || !pft_cfg_real_pos_(vel_var[a]) ||
            !pft_cfg_real_ok_(pos[a]) || !pft_cfg_real_ok_(vel[a]) || !pft_cfg_real_ok_(amp)) {
            return PFT_ERR_INVAL;
        }
    }
    for (uint32_t i = 0; i < p->cfg.max_tracks; ++i) {
        if (!p->tracks[i].live) {
            pft_real_t ps[2] = {pos[0], p->naxes == 2u ? pos[1] : PFT_C(0.0)};
            pft_real_t vs[2] = {vel[0], p->naxes == 2u ? vel[1] : PFT_C(0.0)};
            pft_real_t pv[2] = {pos_var[0], p->naxes == 2u ? pos_var[1] : PFT_C(1.0)};
            pft_real_t vv[2] = {vel_var[0], p->naxes == 2u ? vel_var[1] : PFT_C(1.0)};
            pft_real_t cv[2] = {PFT_C(0.0), PFT_C(0.0)};
            track_new_(p, &p->tracks[i], ps, vs, pv, vv, cv, amp,
                       n_acc > p->cfg.max_len ? p->cfg.max_len : n_acc);
            *id = p->tracks[i].id;
            reports_(p);
            return PFT_OK;
        }
    }
    return PFT_ERR_STATE; /* every slot is live */
}

pft_status_t pft_pte_threshold(pft_pte_t *p, pft_real_t pfa, uint32_t runs,
                               uint64_t seed, pft_real_t *vt)
{
    if (p == NULL || p->ring.buf == NULL) {
        return PFT_ERR_INVAL;
    }
    pft_pte_core_t_ c;
    core_(p, &c);
    pft_status_t st = pft_pte_core_mc_(&p->cfg.in, &c, &p->ring, p->row, pfa, runs, seed, vt);
    if (st == PFT_OK) {
        (void)pft_pte_reset(p);
    }
    return st;
}
