/* Kalman detect-before-track baseline (ALGORITHMS.md 5.5). */
#include <string.h>

#include "../mftbd/mftbd_internal_.h"
#include "pft/pft_dbt.h"
#include "pft/pft_kalman.h"

void pft_dbt_config_default(pft_dbt_config_t *cfg, uint16_t n_range, uint16_t n_doppler)
{
    if (cfg == NULL) {
        return;
    }
    memset(cfg, 0, sizeof(*cfg));
    pft_mftbd_input_default(&cfg->in, n_range, n_doppler);
    cfg->threshold = PFT_C(2.3263478740);
    cfg->sigma_r[0] = PFT_C(0.5);
    cfg->sigma_r[1] = PFT_C(0.5);
    cfg->q[0] = PFT_C(0.0002);
    cfg->q[1] = PFT_C(0.0002);
    cfg->vel_var0[0] = PFT_C(0.04);
    cfg->vel_var0[1] = PFT_C(0.04);
    cfg->gate = n_doppler > 1u ? PFT_C(9.21) : PFT_C(6.63);
    cfg->confirm_m = 2u;
    cfg->confirm_n = 3u;
    cfg->max_misses = 3u;
    cfg->max_tracks = 32u;
    cfg->max_dets = 64u;
}

pft_status_t pft_dbt_config_check(const pft_dbt_config_t *c)
{
    if (c == NULL || pft_mftbd_input_check(&c->in) != PFT_OK) {
        return PFT_ERR_INVAL;
    }
    bool ok = c->gate > PFT_C(0.0);
    for (uint32_t a = 0; a < 2u; ++a) {
        ok = ok && c->sigma_r[a] > PFT_C(0.0) && c->q[a] >= PFT_C(0.0) && c->vel_var0[a] > PFT_C(0.0);
    }
    ok = ok && c->confirm_n >= 1u && c->confirm_n <= 8u && c->confirm_m >= 1u &&
         c->confirm_m <= c->confirm_n;
    ok = ok && c->max_misses >= 1u;
    ok = ok && c->max_tracks >= 1u && c->max_tracks <= PFT_DBT_MAX_TRACKS;
    ok = ok && c->max_dets >= 1u && c->max_dets <= PFT_DBT_MAX_DETS;
    return ok ? PFT_OK : PFT_ERR_INVAL;
}

size_t pft_dbt_workspace_size(const pft_dbt_config_t *c)
{
    if (pft_dbt_config_check(c) != PFT_OK) {
        return 0u;
    }
    return PFT_DBT_WORKSPACE_BYTES(c->in.n_range, c->in.n_doppler, c->max_tracks, c->max_dets);
}

pft_status_t pft_dbt_init(pft_dbt_t *b, const pft_dbt_config_t *cfg, void *work, size_t len)
{
    if (b == NULL || pft_dbt_config_check(cfg) != PFT_OK) {
        return PFT_ERR_INVAL;
    }
    const uint32_t cells = (uint32_t)cfg->in.n_range * cfg->in.n_doppler;
    pft_ws_t ws;
    pft_ws_init(&ws, work, len);
    pft_real_t *frame = pft_ws_take(&ws, (size_t)cells * sizeof(pft_real_t));
    pft_real_t *row = pft_ws_take(&ws, (size_t)cfg->in.n_range * sizeof(pft_real_t));
    pft_dbt_plot_t *plots = pft_ws_take(&ws, (size_t)cfg->max_dets * sizeof(pft_dbt_plot_t));
    pft_dbt_track_t *tracks = pft_ws_take(&ws, (size_t)cfg->max_tracks * sizeof(pft_dbt_track_t));
    pft_mftbd_report_t *rep = pft_ws_take(&ws, (size_t)cfg->max_tracks * sizeof(pft_mftbd_report_t));
    pft_real_t *d2 = pft_ws_take(&ws, (size_t)cfg->max_tracks * cfg->max_dets * sizeof(pft_real_t));
    if (pft_ws_status(&ws) != PFT_OK) {
        return PFT_ERR_NOMEM;
    }
    memset(b, 0, sizeof(*b));
    b->cfg = *cfg;
    pft_mftbd_ring_setup_(&b->ring, frame, 1u, cells);
    b->row = row;
    b->plots = plots;
    b->tracks = tracks;
    b->rep = rep;
    b->d2 = d2;
    b->naxes = cfg->in.n_doppler > 1u ? 2u : 1u;
    pft_dbt_reset(b);
    return PFT_OK;
}

void pft_dbt_reset(pft_dbt_t *b)
{
    if (b == NULL || b->tracks == NULL) {
        return;
    }
    memset(b->tracks, 0, (size_t)b->cfg.max_tracks * sizeof(pft_dbt_track_t));
    b->ring.count = 0u;
    b->frames_in = 0u;
    b->n_plots = 0u;
    b->next_id = 1u;
    b->n_rep = 0u;
}

/* Adds a plot, keeping the strongest max_dets. */
static void plot_add_(pft_dbt_t *b, pft_real_t p0, pft_real_t p1, pft_real_t peak)
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

static void plots_(pft_dbt_t *b)
{
    const pft_real_t *z = pft_mftbd_ring_get_(&b->ring, 0u);
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
static void assign_(pft_dbt_t *b, bool confirmed, int16_t *asg, bool *taken)
{
    const uint32_t nt = b->cfg.max_tracks;
    const uint32_t np = b->n_plots;
    for (uint32_t round = 0; round < nt && round < np; ++round) {
        pft_real_t best = PFT_REAL_MAX;
        int32_t bt = -1;
        int32_t bp = -1;
        for (uint32_t t = 0; t < nt; ++t) {
            const pft_dbt_track_t *tr = &b->tracks[t];
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

static pft_status_t update_(pft_dbt_t *b, const pft_frame_t *frame, const pft_real_t *z)
{
    if (b == NULL || b->tracks == NULL) {
        return PFT_ERR_INVAL;
    }
    pft_status_t st = pft_mftbd_push_(&b->cfg.in, &b->ring, b->row, frame, z);
    if (st != PFT_OK) {
        return st;
    }
    b->frames_in++;
    const pft_dbt_config_t *c = &b->cfg;
    const uint32_t na = b->naxes;
    const uint32_t nt = c->max_tracks;
    static const pft_real_t F[4] = {PFT_C(1.0), PFT_C(1.0), PFT_C(0.0), PFT_C(1.0)};
    static const pft_real_t H[2] = {PFT_C(1.0), PFT_C(0.0)};
    plots_(b);
    const uint32_t np = b->n_plots;
    /* predict and gate */
    for (uint32_t t = 0; t < nt; ++t) {
        pft_dbt_track_t *tr = &b->tracks[t];
        if (!tr->live) {
            continue;
        }
        for (uint32_t a = 0; a < na; ++a) {
            pft_real_t Q[4];
            Q[0] = pft_div_i(c->q[a], 3);
            Q[1] = pft_div_i(c->q[a], 2);
            Q[2] = Q[1];
            Q[3] = c->q[a];
            pft_kf2_predict(tr->x[a], tr->P[a], F, Q);
        }
        for (uint32_t p = 0; p < np; ++p) {
            pft_real_t d = PFT_C(0.0);
            for (uint32_t a = 0; a < na; ++a) {
                pft_real_t nu = pft_sub(b->plots[p].pos[a], tr->x[a][0]);
                pft_real_t s = pft_add(tr->P[a][0], pft_sq(c->sigma_r[a]));
                d = pft_add(d, pft_div(pft_sq(nu), s));
            }
            b->d2[t * np + p] = d;
        }
    }
    int16_t asg[PFT_DBT_MAX_TRACKS];
    bool taken[PFT_DBT_MAX_DETS];
    for (uint32_t t = 0; t < nt; ++t) {
        asg[t] = -1;
    }
    memset(taken, 0, sizeof(taken));
    assign_(b, true, asg, taken);
    assign_(b, false, asg, taken);
    /* update, confirm, delete */
    for (uint32_t t = 0; t < nt; ++t) {
        pft_dbt_track_t *tr = &b->tracks[t];
        if (!tr->live) {
            continue;
        }
        tr->age++;
        if (asg[t] >= 0) {
            const pft_dbt_plot_t *pl = &b->plots[asg[t]];
            for (uint32_t a = 0; a < na; ++a) {
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
            continue;
        }
        uint32_t span = tr->age + 1u < c->confirm_n ? tr->age + 1u : c->confirm_n;
        uint32_t win = span >= 8u ? 0xFFu : ((1u << span) - 1u);
        if (popcount_(tr->hist & win) >= c->confirm_m) {
            tr->confirmed = true;
            tr->id = pft_mftbd_new_id_(&b->next_id);
        } else if (tr->age + 1u >= c->confirm_n) {
            tr->live = false;
        }
    }
    /* new tentative tracks from the plots left over */
    uint32_t slot = 0;
    for (uint32_t p = 0; p < np; ++p) {
        if (taken[p]) {
            continue;
        }
        while (slot < nt && b->tracks[slot].live) {
            slot++;
        }
        if (slot >= nt) {
            break;
        }
        pft_dbt_track_t *tr = &b->tracks[slot];
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
            tr->id = pft_mftbd_new_id_(&b->next_id);
        }
    }
    /* reports */
    uint32_t n = 0;
    for (uint32_t t = 0; t < nt; ++t) {
        const pft_dbt_track_t *tr = &b->tracks[t];
        if (!tr->live || !tr->confirmed) {
            continue;
        }
        pft_mftbd_report_t *r = &b->rep[n++];
        memset(r, 0, sizeof(*r));
        r->id = tr->id;
        r->detected = tr->detected;
        for (uint32_t a = 0; a < na; ++a) {
            r->pos[a] = tr->x[a][0];
            r->vel[a] = tr->x[a][1];
            r->var[a] = tr->P[a][0];
        }
        r->score = tr->score;
        r->age = tr->age;
    }
    b->n_rep = (uint8_t)n;
    return PFT_OK;
}

pft_status_t pft_dbt_update(pft_dbt_t *b, const pft_frame_t *frame)
{
    if (frame == NULL) {
        return PFT_ERR_INVAL;
    }
    return update_(b, frame, NULL);
}

pft_status_t pft_dbt_update_real(pft_dbt_t *b, const pft_real_t *z)
{
    if (z == NULL) {
        return PFT_ERR_INVAL;
    }
    return update_(b, NULL, z);
}

uint32_t pft_dbt_reports(const pft_dbt_t *b, const pft_mftbd_report_t **out)
{
    if (b == NULL) {
        if (out != NULL) {
            *out = NULL;
        }
        return 0u;
    }
    if (out != NULL) {
        *out = b->rep;
    }
    return b->n_rep;
}

uint32_t pft_dbt_plots(const pft_dbt_t *b, const pft_dbt_plot_t **out)
{
    if (b == NULL) {
        if (out != NULL) {
            *out = NULL;
        }
        return 0u;
    }
    if (out != NULL) {
        *out = b->plots;
    }
    return b->n_plots;
}
