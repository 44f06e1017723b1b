/* DP-TBD baseline: batch over the last K frames, re-run at every frame (sliding mode), with
 * multi-target extraction by cancellation and id association between frames. */
#include <string.h>

#include "pte_int.h"

void pft_pte_dp_config_default(pft_pte_dp_config_t *cfg)
{
    if (cfg == NULL) {
        return;
    }
    memset(cfg, 0, sizeof(*cfg));
    pft_pte_input_default(&cfg->in);
    cfg->frames = 10u;
    cfg->gate[0] = 1u;
    cfg->gate[1] = 1u;
    cfg->amplitude = PFT_C(0.0);
    cfg->threshold = PFT_C(17.0);
    cfg->max_targets = 4u;
    cfg->cancel = 3u;
}

static const char *bad_field_(const pft_pte_dp_config_t *c)
{
    const char *bad = pft_pte_input_bad_(&c->in);
    if (bad != NULL) {
        return bad;
    }
    if (c->frames < 2u || c->frames > PFT_PTE_MAX_FRAMES) {
        return "frames";
    }
    if (c->gate[0] > PFT_PTE_MAX_GATE) {
        return "gate[0]";
    }
    if (c->gate[1] > PFT_PTE_MAX_GATE) {
        return "gate[1]";
    }
    if (!(c->amplitude >= PFT_C(0.0)) || c->amplitude > PFT_C(100.0)) {
        return "amplitude";
    }
    if (c->max_targets < 1u || c->max_targets > PFT_PTE_MAX_TRACKS) {
        return "max_targets";
    }
    return NULL;
}

pft_status_t pft_pte_dp_config_check(const pft_pte_dp_config_t *cfg, const char **field)
{
    if (field != NULL) {
        *field = NULL;
    }
    if (cfg == NULL) {
        return PFT_ERR_INVAL;
    }
    return pft_pte_check_done_(bad_field_(cfg), field);
}

size_t pft_pte_dp_workspace_size(const pft_pte_dp_config_t *cfg)
{
    if (pft_pte_dp_config_check(cfg, NULL) != PFT_OK) {
        return 0u;
    }
    return PFT_PTE_DP_WORKSPACE_BYTES(cfg->in.n_range, cfg->in.n_doppler, cfg->frames,
                                      cfg->max_targets);
}

static void core_(const pft_pte_dp_t *dp, pft_pte_core_t_ *c)
{
    c->ring = &dp->ring;
    c->nr = dp->cfg.in.n_range;
    c->nd = dp->cfg.in.n_doppler;
    c->k = dp->cfg.frames;
    c->g0 = dp->cfg.gate[0];
    c->g1 = dp->cfg.gate[1];
    c->amp = dp->cfg.amplitude;
    c->ma = dp->ma;
    c->mb = dp->mb;
    c->psi = dp->psi;
    c->mask = dp->mask;
}

pft_status_t pft_pte_dp_init(pft_pte_dp_t *dp, const pft_pte_dp_config_t *cfg, void *work,
                             size_t work_len)
{
    if (dp == NULL || cfg == NULL || work == NULL) {
        return PFT_ERR_INVAL;
    }
    if (pft_pte_dp_config_check(cfg, NULL) != PFT_OK) {
        return PFT_ERR_CONFIG;
    }
    const uint32_t cells = (uint32_t)cfg->in.n_range * cfg->in.n_doppler;
    const uint32_t k = cfg->frames;
    pft_ws_t ws;
    pft_ws_init(&ws, work, work_len);
    pft_real_t *ring = pft_ws_take(&ws, (size_t)k * cells * sizeof(pft_real_t));
    pft_real_t *row = pft_ws_take(&ws, (size_t)cfg->in.n_range * sizeof(pft_real_t));
    pft_real_t *ma = pft_ws_take(&ws, (size_t)cells * sizeof(pft_real_t));
    pft_real_t *mb = pft_ws_take(&ws, (size_t)cells * sizeof(pft_real_t));
    uint8_t *psi = pft_ws_take(&ws, (size_t)k * cells);
    uint8_t *mask = pft_ws_take(&ws, (size_t)k * cells);
    int16_t *paths = pft_ws_take(&ws, (size_t)cfg->max_targets * k * 2u * sizeof(int16_t));
    pft_pte_report_t *rep = pft_ws_take(&ws, (size_t)cfg->max_targets * sizeof(pft_pte_report_t));
    pft_pte_report_t *prev = pft_ws_take(&ws, (size_t)cfg->max_targets * sizeof(pft_pte_report_t));
    if (pft_ws_status(&ws) != PFT_OK) {
        return PFT_ERR_NOMEM;
    }
    memset(dp, 0, sizeof(*dp));
    dp->cfg = *cfg;
    pft_pte_ring_setup_(&dp->ring, ring, (uint16_t)k, cells);
    dp->row = row;
    dp->ma = ma;
    dp->mb = mb;
    dp->psi = psi;
    dp->mask = mask;
    dp->paths = paths;
    dp->rep = rep;
    dp->prev = prev;
    (void)pft_pte_dp_reset(dp);
    return PFT_OK;
}

pft_status_t pft_pte_dp_reset(pft_pte_dp_t *dp)
{
    if (dp == NULL || dp->ring.buf == NULL) {
        return PFT_ERR_INVAL;
    }
    dp->ring.count = 0u;
    dp->ring.head = (uint16_t)(dp->ring.len - 1u);
    dp->frames_in = 0u;
    memset(&dp->seq, 0, sizeof(dp->seq));
    dp->next_id = 1u;
    dp->n_rep = 0u;
    dp->n_prev = 0u;
    dp->peak = PFT_REAL_MIN;
    return PFT_OK;
}

static void batch_(pft_pte_dp_t *dp)
{
    pft_pte_core_t_ c;
    core_(dp, &c);
    const uint32_t cells = (uint32_t)c.nr * c.nd;
    const uint32_t k = c.k;
    const bool two = c.nd > 1u;
    /* previous reports become the association candidates */
    pft_pte_report_t *t = dp->prev;
    dp->prev = dp->rep;
    dp->rep = t;
    dp->n_prev = dp->n_rep;
    dp->n_rep = 0u;
    memset(dp->mask, 0, (size_t)k * cells);
    bool used[PFT_PTE_MAX_TRACKS];
    memset(used, 0, sizeof(used));
    for (uint32_t n = 0; n < dp->cfg.max_targets; ++n) {
        int32_t cell;
        /* the first search runs without the mask, which is still all zero: the same merits
         * and cell without reading it (docs/results/pte.md, "Branch pte13") */
        c.mask = n == 0u ? NULL : dp->mask;
        pft_real_t best = pft_pte_core_run_(&c, &cell);
        c.mask = dp->mask;
        if (n == 0u) {
            dp->peak = best;
        }
        if (cell < 0 || !(best > dp->cfg.threshold)) {
            break;
        }
        int16_t *path = dp->paths + (size_t)n * k * 2u;
        pft_pte_core_backtrack_(&c, cell, path);
        pft_pte_report_t *r = &dp->rep[n];
        memset(r, 0, sizeof(*r));
        r->detected = true;
        r->score = best;
        r->amplitude = pft_pte_core_amp_(&c, path);
        for (uint32_t a = 0; a < (two ? 2u : 1u); ++a) {
            pft_real_t pos;
            pft_real_t vel;
            pft_pte_core_fit_(&c, path, a, &pos, &vel);
            r->pos[a] = pft_pte_core_refine_(&c, path, k - 1u, a); /* the last state */
            r->vel[a] = vel;
        }
        /* id: nearest unused previous report within +-cancel cells */
        pft_real_t lim = pft_from_int((int32_t)dp->cfg.cancel);
        int32_t bi = -1;
        pft_real_t bd = PFT_REAL_MAX;
        for (uint32_t i = 0; i < dp->n_prev; ++i) {
            pft_real_t d0 = pft_abs(pft_sub(dp->prev[i].pos[0], r->pos[0]));
            pft_real_t d1 = pft_abs(pft_sub(dp->prev[i].pos[1], r->pos[1]));
            if (!used[i] && d0 <= lim && d1 <= lim && pft_add(d0, d1) < bd) {
                bd = pft_add(d0, d1);
                bi = (int32_t)i;
            }
        }
        if (bi >= 0) {
            used[bi] = true;
            r->id = dp->prev[bi].id;
            r->age = dp->prev[bi].age + 1u;
        } else {
            r->id = pft_pte_new_id_(&dp->next_id);
            r->age = 0u;
        }
        dp->n_rep++;
        pft_pte_core_cancel_(&c, path, (int32_t)dp->cfg.cancel, (int32_t)dp->cfg.cancel);
    }
}

static pft_status_t update_(pft_pte_dp_t *dp, const pft_frame_t *frame, const pft_real_t *z)
{
    if (dp == NULL || dp->ring.buf == NULL) {
        return PFT_ERR_INVAL;
    }
    uint32_t k = 1u;
    pft_status_t st = pft_pte_seq_check_(&dp->cfg.in, &dp->seq, frame, &k);
    if (st != PFT_OK) {
        return st; /* nothing touched */
    }
    if (k == 0u) {
        /* a gap above max_gap: the batch restarts on this frame (ids go on) */
        const uint16_t id = dp->next_id;
        (void)pft_pte_dp_reset(dp);
        dp->next_id = id;
    } else {
        /* k - 1 lost frames (docs/algorithms.md 5.7): each takes a ring slot with zeta = 0, the
         * noise mean, so it is a missing stage of every path (its merit adds nothing) while
         * the paths move over its period; more than K of them only clear the window */
        const size_t cells = (size_t)dp->cfg.in.n_range * dp->cfg.in.n_doppler;
        for (uint32_t f = 1u; f < k && f <= (uint32_t)dp->cfg.frames; ++f) {
            (void)memset(pft_pte_ring_next_(&dp->ring), 0, cells * sizeof(pft_real_t));
            pft_pte_ring_commit_(&dp->ring);
        }
        dp->frames_in += k - 1u;
    }
    st = pft_pte_push_(&dp->cfg.in, &dp->ring, dp->row, frame, z);
    if (st != PFT_OK) {
        return st;
    }
    dp->frames_in++;
    if (dp->ring.count >= dp->cfg.frames) {
        batch_(dp);
    } else {
        dp->n_rep = 0u;
    }
    pft_pte_seq_take_(&dp->cfg.in, &dp->seq, frame, dp->rep, dp->n_rep);
    return PFT_OK;
}

pft_status_t pft_pte_dp_update(pft_pte_dp_t *dp, const pft_frame_t *frame)
{
    if (frame == NULL) {
        return PFT_ERR_INVAL;
    }
    return update_(dp, frame, NULL);
}

pft_status_t pft_pte_dp_update_real(pft_pte_dp_t *dp, const pft_real_t *z)
{
    if (z == NULL) {
        return PFT_ERR_INVAL;
    }
    return update_(dp, NULL, z);
}

size_t pft_pte_dp_reports(const pft_pte_dp_t *dp, pft_pte_report_t *out, size_t max)
{
    if (dp == NULL || dp->ring.buf == NULL) {
        return 0u;
    }
    return pft_pte_copy_out_(dp->rep, dp->n_rep, sizeof(pft_pte_report_t), out, max);
}

size_t pft_pte_dp_path(const pft_pte_dp_t *dp, size_t i, int16_t *cells, size_t max)
{
    if (dp == NULL || dp->ring.buf == NULL || i >= dp->n_rep) {
        return 0u;
    }
    size_t n = 2u * (size_t)dp->cfg.frames;
    return pft_pte_copy_out_(dp->paths + i * n, n, sizeof(int16_t), cells, max);
}

pft_status_t pft_pte_dp_peak(const pft_pte_dp_t *dp, pft_real_t *peak)
{
    if (dp == NULL || dp->ring.buf == NULL || peak == NULL) {
        return PFT_ERR_INVAL;
    }
    *peak = dp->peak;
    return PFT_OK;
}

pft_status_t pft_pte_dp_threshold(pft_pte_dp_t *dp, pft_real_t pfa, uint32_t runs,
                                  uint64_t seed, pft_real_t *vt)
{
    if (dp == NULL || dp->ring.buf == NULL) {
        return PFT_ERR_INVAL;
    }
    pft_pte_core_t_ c;
    core_(dp, &c);
    pft_status_t st = pft_pte_core_mc_(&dp->cfg.in, &c, &dp->ring, dp->row, pfa, runs, seed, vt);
    if (st == PFT_OK) {
        (void)pft_pte_dp_reset(dp);
    }
    return st;
}
