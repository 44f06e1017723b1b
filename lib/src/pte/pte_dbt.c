/* Kalman detect-before-track baseline of the pte family (docs/algorithms.md 5.5). */
#include <string.h>

#include "pte_int.h"
#include "pft/pft_kalman.h"

void pft_pte_dbt_config_default(pft_pte_dbt_config_t *cfg)
{
    if (cfg == NULL) {
        return;
    }
    memset(cfg, 0, sizeof(*cfg));
    pft_pte_input_default(&cfg->in);
    cfg->threshold = PFT_C(2.3263478740);
    cfg->sigma_r[0] = PFT_C(0.5);
    cfg->sigma_r[1] = PFT_C(0.5);
    cfg->q[0] = PFT_C(0.0002);
    cfg->q[1] = PFT_C(0.0002);
    cfg->vel_var0[0] = PFT_C(0.04);
    cfg->vel_var0[1] = PFT_C(0.04);
    cfg->gate = PFT_C(0.0); /* by the number of axes at init */
    cfg->confirm_m = 2u;
    cfg->confirm_n = 3u;
    cfg->max_misses = 3u;
    cfg->max_tracks = 32u;
    cfg->max_dets = 64u;
}

static const char *bad_field_(const pft_pte_dbt_config_t *c)
{
    static const char *const sr[2] = {"sigma_r[0]", "sigma_r[1]"};
    static const char *const q[2] = {"q[0]", "q[1]"};
    static const char *const vv[2] = {"vel_var0[0]", "vel_var0[1]"};
    const char *bad = pft_pte_input_bad_(&c->in);
    if (bad != NULL) {
        return bad;
    }
    for (uint32_t a = 0; a < 2u; ++a) {
        if (!(c->sigma_r[a] > PFT_C(0.0))) {
            return sr[a];
        }
    }
    for (uint32_t a = 0; a < 2u; ++a) {
        if (!(c->q[a] >= PFT_C(0.0))) {
            return q[a];
        }
    }
    for (uint32_t a = 0; a < 2u; ++a) {
        if (!(c->vel_var0[a] > PFT_C(0.0))) {
            return vv[a];
        }
    }
    if (!(c->gate >= PFT_C(0.0))) {
        return "gate";
    }
    if (c->confirm_m < 1u || c->confirm_m > 8u) {
        return "confirm_m";
    }
    if (c->confirm_n < 1u || c->confirm_n > 8u) {
        return "confirm_n";
    }
    if (c->confirm_m > c->confirm_n) {
        return "confirm_m"; /* more hits than frames */
    }
    if (c->max_misses < 1u) {
        return "max_misses";
    }
    if (c->max_tracks < 1u || c->max_tracks > PFT_PTE_DBT_MAX_TRACKS) {
        return "max_tracks";
    }
    if (c->max_dets < 1u || c->max_dets > PFT_PTE_DBT_MAX_DETS) {
        return "max_dets";
    }
    return NULL;
}

pft_status_t pft_pte_dbt_config_check(const pft_pte_dbt_config_t *cfg, const char **field)
{
    if (field != NULL) {
        *field = NULL;
    }
    if (cfg == NULL) {
        return PFT_ERR_INVAL;
    }
    return pft_pte_check_done_(bad_field_(cfg), field);
}

size_t pft_pte_dbt_workspace_size(const pft_pte_dbt_config_t *c)
{
    if (pft_pte_dbt_config_check(c, NULL) != PFT_OK) {
        return 0u;
    }
    return PFT_PTE_DBT_WORKSPACE_BYTES(c->in.n_range, c->in.n_doppler, c->max_tracks, c->max_dets);
}

pft_status_t pft_pte_dbt_init(pft_pte_dbt_t *b, const pft_pte_dbt_config_t *cfg, void *work,
                              size_t work_len)
{
    if (b == NULL || cfg == NULL || work == NULL) {
        return PFT_ERR_INVAL;
    }
    if (pft_pte_dbt_config_check(cfg, NULL) != PFT_OK) {
        return PFT_ERR_CONFIG;
    }
    const uint32_t cells = (uint32_t)cfg->in.n_range * cfg->in.n_doppler;
    pft_ws_t ws;
    pft_ws_init(&ws, work, work_len);
    pft_real_t *frame = pft_ws_take(&ws, (size_t)cells * sizeof(pft_real_t));
    pft_real_t *row = pft_ws_take(&ws, (size_t)cfg->in.n_range * sizeof(pft_real_t));
    pft_pte_dbt_plot_t *plots = pft_ws_take(&ws, (size_t)cfg->max_dets * sizeof(pft_pte_dbt_plot_t));
    pft_pte_dbt_track_t *tracks = pft_ws_take(&ws, (size_t)cfg->max_tracks * sizeof(pft_pte_dbt_track_t));
    pft_pte_report_t *rep = pft_ws_take(&ws, (size_t)cfg->max_tracks * sizeof(pft_pte_report_t));
    pft_real_t *d2 = pft_ws_take(&ws, (size_t)cfg->max_tracks * cfg->max_dets * sizeof(pft_real_t));
    if (pft_ws_status(&ws) != PFT_OK) {
        return PFT_ERR_NOMEM;
    }
    memset(b, 0, sizeof(*b));
    b->cfg = *cfg;
    pft_pte_ring_setup_(&b->ring, frame, 1u, cells);
    b->row = row;
    b->plots = plots;
    b->tracks = tracks;
    b->rep = rep;
    b->d2 = d2;
    b->naxes = cfg->in.n_doppler > 1u ? 2u : 1u;
    if (b->cfg.gate == PFT_C(0.0)) {
        b->cfg.gate = b->naxes == 2u ? PFT_PTE_DBT_GATE_2AXES : PFT_PTE_DBT_GATE_1AXIS;
    }
    (void)pft_pte_dbt_reset(b);
    return PFT_OK;
}

pft_status_t pft_pte_dbt_reset(pft_pte_dbt_t *b)
{
    if (b == NULL || b->tracks == NULL) {
        return PFT_ERR_INVAL;
    }
    memset(b->tracks, 0, (size_t)b->cfg.max_tracks * sizeof(pft_pte_dbt_track_t));
    b->ring.count = 0u;
    b->frames_in = 0u;
    memset(&b->seq, 0, sizeof(b->seq));
    b->n_plots = 0u;
    b->next_id = 1u;
    b->n_rep = 0u;
    return PFT_OK;
}

/* Adds a plot, keeping the strongest max_dets. */
static void plot_add_(pft_pte_dbt_t *b, pft_real_t p0, pft_real_t p1, pft_real_t peak)
{
    uint32_t i = b->n_plots;
    if (i >= b->cfg.max_dets) {
        uint32_t w = 0;
        for (uint32_t j = 1; j < b->n_plots; ++j) {
            if (b->plots[j].peak < b->plots[w].peak) {
                w = j;
            }
        }
        if (!(peak > b->plots[w].peak)) {
            return;
        }
        i = w;
    } else {
        b->n_plots++;
    }
    b->plots[i].pos[0] = p0;
    b->plots[i].pos[1] = p1;
    b->plots[i].peak = peak;
}

static void plots_(pft_pte_dbt_t *b)
{
    const pft_real_t *z = pft_pte_ring_get_(&b->ring, 0u);
    const int32_t nr = (int32_t)b->cfg.in.n_range;
    const int32_t nd = (int32_t)b->cfg.in.n_doppler;
    const pft_real_t thr = b->cfg.threshold;
    b->n_plots = 0u;
    if (nd == 1) {
        int32_t u = 0;
        while (u < nr) {
            if (!(z[u] > thr)) {
                u++;
                continue;
            }
            /* run [u, v): centroid relative to its start keeps q16 sums small */
            pft_real_t sw = PFT_C(0.0);
            pft_real_t swu = PFT_C(0.0);
            pft_real_t pk = z[u];
            int32_t v = u;
            while (v < nr && z[v] > thr) {
                sw = pft_add(sw, z[v]);
                swu = pft_add(swu, pft_mul_i(z[v], v - u));
                pk = pft_max(pk, z[v]);
                v++;
            }
            plot_add_(b, pft_add(pft_from_int(u), pft_div(swu, sw)), PFT_C(0.0), pk);
            u = v;
        }
        return;
    }
    for (int32_t d = 0; d < nd; ++d) {
        for (int32_t r = 0; r < nr; ++r) {
            pft_real_t v = z[d * nr + r];
            if (!(v > thr)) {
                continue;
            }
            bool peak = true;
            pft_real_t sw = PFT_C(0.0);
            pft_real_t s0 = PFT_C(0.0);
            pft_real_t s1 = PFT_C(0.0);
            for (int32_t dd = -1; dd <= 1 && peak; ++dd) {
                for (int32_t dr = -1; dr <= 1; ++dr) {
                    int32_t rr = r + dr;
                    int32_t dq = d + dd;
                    if (rr < 0 || rr >= nr || dq < 0 || dq >= nd || (dr == 0 && dd == 0)) {
                        continue;
                    }
                    pft_real_t w = z[dq * nr + rr];
                    /* ties: the first cell in scan order is the peak */
                    bool before = dd < 0 || (dd == 0 && dr < 0);
                    if (w > v || (before && w == v)) {
                        peak = false;
                        break;
                    }
                    if (w > thr) {
                        sw = pft_add(sw, w);
                        s0 = pft_add(s0, pft_mul_i(w, dr));
                        s1 = pft_add(s1, pft_mul_i(w, dd));
                    }
                }
            }
            if (!peak) {
                continue;
            }
            sw = pft_add(sw, v);
            plot_add_(b, pft_add(pft_from_int(r), pft_div(s0, sw)),
                      pft_add(pft_from_int(d), pft_div(s1, sw)), v);
        }
    }
}

static uint32_t popcount_(uint32_t v)
{
    uint32_t n = 0;
    for (uint32_t i = 0; i < 8u; ++i) {
        n += (v >> i) & 1u;
    }
    return n;
}

/* Greedy nearest-neighbour assignment of plots to tracks (confirmed or tentative set). */
static void assign_(pft_pte_dbt_t *b, bool confirmed, int16_t *asg, bool *taken)
{
    const uint32_t nt = b->cfg.max_tracks;
    const uint32_t np = b->n_plots;
    for (uint32_t round = 0; round < nt && round < np; ++round) {
        pft_real_t best = PFT_REAL_MAX;
        int32_t bt = -1;
        int32_t bp = -1;
        for (uint32_t t = 0; t < nt; ++t) {
            const pft_pte_dbt_track_t *tr = &b->tracks[t];
            if (!tr->live || tr->confirmed != confirmed || asg[t] >= 0) {
                continue;
            }
            for (uint32_t p = 0; p < np; ++p) {
                pft_real_t d = b->d2[t * np + p];
                if (!taken[p] && d <= b->cfg.gate && d < best) {
                    best = d;
                    bt = (int32_t)t;
                    bp = (int32_t)p;
                }
            }
        }
        if (bt < 0) {
            return;
        }
        asg[bt] = (int16_t)bp;
        taken[bp] = true;
    }
}

/* Lost frames (a seq gap of periods + 1): every live track's Kalman prediction over periods
 * more frames (no update, no miss counted, age unchanged); step 2 adds the last one. */
static void coast_(pft_pte_dbt_t *b, uint32_t periods)
{
    static const pft_real_t F[4] = {PFT_C(1.0), PFT_C(1.0), PFT_C(0.0), PFT_C(1.0)};
    const pft_pte_dbt_config_t *c = &b->cfg;
    for (uint32_t t = 0; t < c->max_tracks; ++t) {
        pft_pte_dbt_track_t *tr = &b->tracks[t];
        for (uint32_t a = 0; tr->live && a < b->naxes; ++a) {
            pft_real_t Q[4];
            Q[0] = pft_div_i(c->q[a], 3);
            Q[1] = pft_div_i(c->q[a], 2);
            Q[2] = Q[1];
            Q[3] = c->q[a];
            for (uint32_t i = 0; i < periods; ++i) {
                pft_kf2_predict(tr->x[a], tr->P[a], F, Q);
            }
        }
    }
}

/* Steps 2-3: predicts every live track and fills the gating distances d2[t * np + p]. */
static void predict_gate_(pft_pte_dbt_t *b)
{
    static const pft_real_t F[4] = {PFT_C(1.0), PFT_C(1.0), PFT_C(0.0), PFT_C(1.0)};
    const pft_pte_dbt_config_t *c = &b->cfg;
    const uint32_t np = b->n_plots;
    for (uint32_t t = 0; t < c->max_tracks; ++t) {
        pft_pte_dbt_track_t *tr = &b->tracks[t];
        if (!tr->live) {
            continue;
        }
        for (uint32_t a = 0; a < b->naxes; ++a) {
            pft_real_t Q[4];
            Q[0] = pft_div_i(c->q[a], 3);
            Q[1] = pft_div_i(c->q[a], 2);
            Q[2] = Q[1];
            Q[3] = c->q[a];
            pft_kf2_predict(tr->x[a], tr->P[a], F, Q);
        }
        for (uint32_t p = 0; p < np; ++p) {
            pft_real_t d = PFT_C(0.0);
            for (uint32_t a = 0; a < b->naxes; ++a) {
                pft_real_t nu = pft_sub(b->plots[p].pos[a], tr->x[a][0]);
                pft_real_t s = pft_add(tr->P[a][0], pft_sq(c->sigma_r[a]));
                d = pft_add(d, pft_div(pft_sq(nu), s));
            }
            b->d2[t * np + p] = d;
        }
    }
}

/* Steps 4-5 for one live track: update with its plot (or a miss), confirmation, deletion. */
static void track_update_(pft_pte_dbt_t *b, pft_pte_dbt_track_t *tr, int32_t plot)
{
    static const pft_real_t H[2] = {PFT_C(1.0), PFT_C(0.0)};
    const pft_pte_dbt_config_t *c = &b->cfg;
    tr->age++;
    if (plot >= 0) {
        const pft_pte_dbt_plot_t *pl = &b->plots[plot];
        for (uint32_t a = 0; a < b->naxes; ++a) {
            (void)pft_kf2_update_scalar(tr->x[a], tr->P[a], H, pl->pos[a], pft_sq(c->sigma_r[a]));
        }
        tr->hist = (uint8_t)(((uint32_t)tr->hist << 1) | 1u);
        tr->misses = 0u;
        tr->detected = true;
        tr->score = pl->peak;
    } else {
        tr->hist = (uint8_t)((uint32_t)tr->hist << 1);
        tr->misses++;
        tr->detected = false;
    }
    if (tr->confirmed) {
        if (tr->misses >= c->max_misses) {
            tr->live = false;
        }
        return;
    }
    uint32_t span = tr->age + 1u < c->confirm_n ? tr->age + 1u : c->confirm_n;
    uint32_t win = span >= 8u ? 0xFFu : ((1u << span) - 1u);
    if (popcount_(tr->hist & win) >= c->confirm_m) {
        tr->confirmed = true;
        tr->id = pft_pte_new_id_(&b->next_id);
    } else if (tr->age + 1u >= c->confirm_n) {
        tr->live = false;
    }
}

/* Step 6: a tentative track at every plot left over, while slots are free. */
static void track_births_(pft_pte_dbt_t *b, const bool *taken)
{
    const pft_pte_dbt_config_t *c = &b->cfg;
    const uint32_t nt = c->max_tracks;
    uint32_t slot = 0;
    for (uint32_t p = 0; p < b->n_plots; ++p) {
        if (taken[p]) {
            continue;
        }
        while (slot < nt && b->tracks[slot].live) {
            slot++;
        }
        if (slot >= nt) {
            break;
        }
        pft_pte_dbt_track_t *tr = &b->tracks[slot];
        memset(tr, 0, sizeof(*tr));
        for (uint32_t a = 0; a < 2u; ++a) {
            tr->x[a][0] = b->plots[p].pos[a];
            tr->P[a][0] = pft_sq(c->sigma_r[a]);
            tr->P[a][3] = c->vel_var0[a];
        }
        tr->hist = 1u;
        tr->live = true;
        tr->detected = true;
        tr->score = b->plots[p].peak;
        if (c->confirm_m <= 1u) {
            tr->confirmed = true;
            tr->id = pft_pte_new_id_(&b->next_id);
        }
    }
}

/* Reports: the confirmed tracks in slot order. */
static void reports_(pft_pte_dbt_t *b)
{
    uint32_t n = 0;
    for (uint32_t t = 0; t < b->cfg.max_tracks; ++t) {
        const pft_pte_dbt_track_t *tr = &b->tracks[t];
        if (!tr->live || !tr->confirmed) {
            continue;
        }
        pft_pte_report_t *r = &b->rep[n++];
        memset(r, 0, sizeof(*r));
        r->id = tr->id;
        r->detected = tr->detected;
        for (uint32_t a = 0; a < b->naxes; ++a) {
            r->pos[a] = tr->x[a][0];
            r->vel[a] = tr->x[a][1];
            r->var[a] = tr->P[a][0];
        }
        r->score = tr->score;
        r->age = tr->age;
    }
    b->n_rep = (uint8_t)n;
}

static pft_status_t update_(pft_pte_dbt_t *b, const pft_frame_t *frame, const pft_real_t *z)
{
    if (b == NULL || b->tracks == NULL) {
        return PFT_ERR_INVAL;
    }
    uint32_t k = 1u;
    pft_status_t st = pft_pte_seq_check_(&b->cfg.in, &b->seq, frame, &k);
    if (st != PFT_OK) {
        return st; /* nothing touched */
    }
    if (k == 0u) {
        /* a gap above max_gap: start over on this frame (ids go on) */
        const uint16_t id = b->next_id;
        (void)pft_pte_dbt_reset(b);
        b->next_id = id;
    } else if (k > 1u) {
        coast_(b, k - 1u);
    } else {
        /* consecutive frames */
    }
    st = pft_pte_push_(&b->cfg.in, &b->ring, b->row, frame, z);
    if (st != PFT_OK) {
        return st;
    }
    b->frames_in++;
    const uint32_t nt = b->cfg.max_tracks;
    plots_(b);
    predict_gate_(b);
    int16_t asg[PFT_PTE_DBT_MAX_TRACKS];
    bool taken[PFT_PTE_DBT_MAX_DETS];
    for (uint32_t t = 0; t < nt; ++t) {
        asg[t] = -1;
    }
    memset(taken, 0, sizeof(taken));
    assign_(b, true, asg, taken);
    assign_(b, false, asg, taken);
    for (uint32_t t = 0; t < nt; ++t) {
        if (b->tracks[t].live) {
            track_update_(b, &b->tracks[t], asg[t]);
        }
    }
    track_births_(b, taken);
    reports_(b);
    pft_pte_seq_take_(&b->cfg.in, &b->seq, frame, b->rep, b->n_rep);
    return PFT_OK;
}

pft_status_t pft_pte_dbt_update(pft_pte_dbt_t *b, const pft_frame_t *frame)
{
    if (frame == NULL) {
        return PFT_ERR_INVAL;
    }
    return update_(b, frame, NULL);
}

pft_status_t pft_pte_dbt_update_real(pft_pte_dbt_t *b, const pft_real_t *z)
{
    if (z == NULL) {
        return PFT_ERR_INVAL;
    }
    return update_(b, NULL, z);
}

size_t pft_pte_dbt_reports(const pft_pte_dbt_t *b, pft_pte_report_t *out, size_t max)
{
    if (b == NULL || b->tracks == NULL) {
        return 0u;
    }
    return pft_pte_copy_out_(b->rep, b->n_rep, sizeof(pft_pte_report_t), out, max);
}

size_t pft_pte_dbt_plots(const pft_pte_dbt_t *b, pft_pte_dbt_plot_t *out, size_t max)
{
    if (b == NULL || b->tracks == NULL) {
        return 0u;
    }
    return pft_pte_copy_out_(b->plots, b->n_plots, sizeof(pft_pte_dbt_plot_t), out, max);
}
