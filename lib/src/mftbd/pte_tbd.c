/* PTE-TBD: parameterized track enhancement (He, Liao, Yang & Sun 2015) as reconstructed in
 * ALGORITHMS.md 5.2-5.3: batch DP initiation, L matched line operators per axis set by the
 * track state, per-direction Kalman updates, likelihood-weighted fusion, closed-loop
 * feedback, termination and re-initiation, several targets with cancellation. */
#include <string.h>

#include "mftbd_internal_.h"
#include "pft/pft_kalman.h"

#define DRES_ PFT_MFTBD_DRES_

void pft_mftbd_pte_config_default(pft_mftbd_pte_config_t *cfg, uint16_t n_range,
                                  uint16_t n_doppler)
{
    if (cfg == NULL) {
        return;
    }
    memset(cfg, 0, sizeof(*cfg));
    pft_mftbd_input_default(&cfg->in, n_range, n_doppler);
    cfg->init_frames = 10u;
    cfg->init_gate[0] = 1u;
    cfg->init_gate[1] = 1u;
    cfg->init_threshold = PFT_C(18.9);
    cfg->init_period = 10u;
    cfg->max_len = 40u;
    cfg->n_dir[0] = 5u;
    cfg->n_dir[1] = 5u;
    cfg->motion = PFT_MFTBD_MOTION_CA;
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
    cfg->op = n_doppler > 1u ? PFT_MFTBD_OP_EXACT : PFT_MFTBD_OP_TABLE;
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

pft_status_t pft_mftbd_pte_config_check(const pft_mftbd_pte_config_t *c)
{
    if (c == NULL || pft_mftbd_input_check(&c->in) != PFT_OK) {
        return PFT_ERR_INVAL;
    }
    bool ok = c->init_frames >= 2u && c->init_frames <= PFT_MFTBD_MAX_FRAMES;
    ok = ok && c->init_gate[0] <= PFT_MFTBD_MAX_GATE && c->init_gate[1] <= PFT_MFTBD_MAX_GATE;
    ok = ok && c->init_period >= 1u;
    ok = ok && c->max_len >= 2u && c->max_len <= PFT_MFTBD_MAX_FRAMES;
    for (uint32_t a = 0; a < 2u; ++a) {
        ok = ok && c->n_dir[a] >= 1u && c->n_dir[a] <= PFT_MFTBD_MAX_DIRS && (c->n_dir[a] & 1u) == 1u;
        ok = ok && c->sigma_r[a] > PFT_C(0.0) && c->sigma_r[a] <= PFT_C(100.0);
        ok = ok && c->q_sd[a] >= PFT_C(0.0) && c->q_sd[a] <= PFT_C(1.0);
        ok = ok && c->acc_sd0[a] >= PFT_C(0.0) && c->acc_sd0[a] <= PFT_C(0.1);
    }
    ok = ok && (c->motion == PFT_MFTBD_MOTION_CV || c->motion == PFT_MFTBD_MOTION_CA);
    ok = ok && c->q_amp >= PFT_C(0.0) && c->dtheta_min > PFT_C(0.0);
    ok = ok && c->c_step > PFT_C(0.0) && c->c_step <= PFT_C(4.0);
    ok = ok && c->scan_steps >= 1u && c->scan_steps <= PFT_MFTBD_MAX_SCAN_STEPS;
    ok = ok && c->scan_sigmas > PFT_C(0.0);
    ok = ok && c->sigma_w_max > PFT_C(0.0) &&
         c->sigma_w_max <= pft_ratio((int32_t)PFT_MFTBD_MAX_TAPS - 1, 6);
    ok = ok && c->max_misses >= 1u;
    ok = ok && c->max_tracks >= 1u && c->max_tracks <= PFT_MFTBD_MAX_TRACKS;
    ok = ok && c->dup_cells >= PFT_C(0.0);
    ok = ok && (c->op == PFT_MFTBD_OP_EXACT ||
                (c->op == PFT_MFTBD_OP_TABLE && c->in.n_doppler == 1u && period_(c->c_step) != 0u &&
                 c->in.zeta_clip <= PFT_C(64.0)));
    return ok ? PFT_OK : PFT_ERR_INVAL;
}

size_t pft_mftbd_pte_workspace_size(const pft_mftbd_pte_config_t *c)
{
    if (pft_mftbd_pte_config_check(c) != PFT_OK) {
        return 0u;
    }
    return PFT_MFTBD_PTE_WORKSPACE_BYTES(c->in.n_range, c->in.n_doppler, c->max_len,
                                         c->init_frames, c->max_tracks, c->scan_steps,
                                         c->n_dir[0], c->n_dir[1],
                                         c->op == PFT_MFTBD_OP_TABLE ? period_(c->c_step) : 0u);
}

/* TABLE operators: tap weights of each grid phase (width sigma_y = sigma_r, clamped) and the
 * normaliser sum g^2 of every response point (edges included). */
static void ytable_setup_(pft_mftbd_pte_t *p)
{
    const int32_t q = p->yq;
    const int32_t nr = p->cfg.in.n_range;
    p->sigma_y = pft_min(p->cfg.sigma_r[0], p->cfg.sigma_w_max);
    pft_real_t inv = pft_recip(p->sigma_y);
    pft_real_t reach = pft_mul_i(p->sigma_y, 3);
    for (int32_t ph = 0; ph < q; ++ph) {
        pft_real_t f = pft_ratio(ph, q);
        int32_t lo = -pft_floor_int(pft_neg(pft_sub(f, reach)));
        int32_t hi = pft_floor_int(pft_add(f, reach));
        if (hi - lo + 1 > (int32_t)PFT_MFTBD_MAX_TAPS) {
            hi = lo + (int32_t)PFT_MFTBD_MAX_TAPS - 1;
        }
        int32_t n = hi >= lo ? hi - lo + 1 : 0;
        for (int32_t k = 0; k < n; ++k) {
            pft_real_t t = pft_mul(pft_abs(pft_sub(pft_from_int(lo + k), f)), inv);
            int32_t idx = pft_round_int(pft_mul_i(t, 64));
            p->ytap[ph][k] = idx < (int32_t)PFT_MFTBD_GTAB_SIZE ? p->gtab[idx] : PFT_C(0.0);
        }
        p->ytap_lo[ph] = (int16_t)lo;
        p->ytap_n[ph] = (uint8_t)n;
    }
    for (uint32_t i = 0; i < p->ny; ++i) {
        int32_t ph = (int32_t)i % q;
        int32_t u0 = (int32_t)i / q - (int32_t)PFT_MFTBD_YPAD + p->ytap_lo[ph];
        pft_real_t g2 = PFT_C(0.0);
        for (int32_t k = 0; k < p->ytap_n[ph]; ++k) {
            if (u0 + k >= 0 && u0 + k < nr) {
                g2 = pft_add(g2, pft_sq(p->ytap[ph][k]));
            }
        }
        p->gq[i] = g2;
    }
}

/* TABLE operators: responses are computed lazily, one block of 8 cells at a time, the first
 * time an operator reads them, and kept beside the frame in the ring; only the neighbourhood
 * of live tracks is ever computed. */
#define YBLK_ 8

static void yblock_(pft_mftbd_pte_t *p, uint32_t slot, uint32_t back, int32_t blk)
{
    const int32_t q = p->yq;
    const int32_t nr = p->cfg.in.n_range;
    const pft_real_t *z = pft_mftbd_ring_get_(&p->ring, back);
    pft_real_t *y = p->yring + (size_t)slot * p->ny;
    const int32_t ncell = (int32_t)(p->ny / (uint32_t)q);
    int32_t c1 = (blk + 1) * YBLK_ < ncell ? (blk + 1) * YBLK_ : ncell;
    for (int32_t cell = blk * YBLK_; cell < c1; ++cell) {
        for (int32_t ph = 0; ph < q; ++ph) {
            int32_t u0 = cell - (int32_t)PFT_MFTBD_YPAD + p->ytap_lo[ph];
            int32_t n = p->ytap_n[ph];
            const pft_real_t *w = p->ytap[ph];
            pft_real_t acc = PFT_C(0.0);
            if (u0 >= 0 && u0 + n <= nr) {
                const pft_real_t *zz = z + u0;
                for (int32_t k = 0; k < n; ++k) {
                    acc = pft_add(acc, pft_mul(w[k], zz[k]));
                }
            } else {
                for (int32_t k = 0; k < n; ++k) {
                    if (u0 + k >= 0 && u0 + k < nr) {
                        acc = pft_add(acc, pft_mul(w[k], z[u0 + k]));
                    }
                }
            }
            y[cell * q + ph] = acc;
        }
    }
    p->yflag[(size_t)slot * p->nyblk + (size_t)blk] = 1u;
}

/* TABLE operators: response of the frame `back` frames ago, valid at points [i0, i1). */
static const pft_real_t *yframe_(pft_mftbd_pte_t *p, uint32_t back, int32_t i0, int32_t i1)
{
    uint32_t len = p->ring.len;
    uint32_t slot = ((uint32_t)p->ring.head + len - (back % len)) % len;
    int32_t bp = YBLK_ * (int32_t)p->yq;
    i0 = i0 < 0 ? 0 : i0;
    i1 = i1 > (int32_t)p->ny ? (int32_t)p->ny : i1;
    for (int32_t blk = i0 / bp; i1 > i0 && blk <= (i1 - 1) / bp; ++blk) {
        if (p->yflag[(size_t)slot * p->nyblk + (size_t)blk] == 0u) {
            yblock_(p, slot, back, blk);
        }
    }
    return p->yring + (size_t)slot * p->ny;
}

pft_status_t pft_mftbd_pte_init(pft_mftbd_pte_t *p, const pft_mftbd_pte_config_t *cfg, void *work,
                                size_t len)
{
    if (p == NULL || pft_mftbd_pte_config_check(cfg) != PFT_OK) {
        return PFT_ERR_INVAL;
    }
    const uint32_t cells = (uint32_t)cfg->in.n_range * cfg->in.n_doppler;
    const uint32_t nring = cfg->max_len > cfg->init_frames ? cfg->max_len : cfg->init_frames;
    const uint32_t n = cfg->init_frames;
    const bool two = cfg->in.n_doppler > 1u;
    const uint32_t ns0 = 2u * cfg->scan_steps + 1u;
    const uint32_t ns1 = two ? ns0 : 1u;
    const uint32_t nd = (uint32_t)cfg->n_dir[0] * (two ? cfg->n_dir[1] : 1u);
    pft_ws_t ws;
    pft_ws_init(&ws, work, len);
    pft_real_t *ring = pft_ws_take(&ws, (size_t)nring * cells * sizeof(pft_real_t));
    pft_real_t *row = pft_ws_take(&ws, (size_t)cfg->in.n_range * sizeof(pft_real_t));
    pft_real_t *ma = pft_ws_take(&ws, (size_t)cells * sizeof(pft_real_t));
    pft_real_t *mb = pft_ws_take(&ws, (size_t)cells * sizeof(pft_real_t));
    uint8_t *psi = pft_ws_take(&ws, (size_t)n * cells);
    uint8_t *mask = pft_ws_take(&ws, (size_t)n * cells);
    int16_t *path = pft_ws_take(&ws, (size_t)n * 2u * sizeof(int16_t));
    pft_real_t *gtab = pft_ws_take(&ws, (size_t)PFT_MFTBD_GTAB_SIZE * sizeof(pft_real_t));
    pft_real_t *gw0 = pft_ws_take(&ws, (size_t)PFT_MFTBD_GW_SIZE * sizeof(pft_real_t));
    pft_real_t *gw1 = two ? pft_ws_take(&ws, (size_t)PFT_MFTBD_GW_SIZE * sizeof(pft_real_t)) : gw0;
    pft_mftbd_pte_track_t *tracks = pft_ws_take(&ws, (size_t)cfg->max_tracks * sizeof(pft_mftbd_pte_track_t));
    pft_mftbd_report_t *rep = pft_ws_take(&ws, (size_t)cfg->max_tracks * sizeof(pft_mftbd_report_t));
    pft_real_t *sE = pft_ws_take(&ws, (size_t)ns0 * ns1 * sizeof(pft_real_t));
    pft_real_t *sG = pft_ws_take(&ws, (size_t)ns0 * ns1 * sizeof(pft_real_t));
    pft_real_t *sL = pft_ws_take(&ws, (size_t)ns0 * ns1 * sizeof(pft_real_t));
    pft_real_t *tw0 = pft_ws_take(&ws, (size_t)ns0 * PFT_MFTBD_MAX_TAPS * sizeof(pft_real_t));
    pft_real_t *tw1 = pft_ws_take(&ws, (size_t)ns1 * PFT_MFTBD_MAX_TAPS * sizeof(pft_real_t));
    int16_t *tlo0 = pft_ws_take(&ws, (size_t)ns0 * 4u * sizeof(int16_t));
    int16_t *tlo1 = pft_ws_take(&ws, (size_t)ns1 * 4u * sizeof(int16_t));
    pft_real_t *dres = pft_ws_take(&ws, (size_t)nd * DRES_ * sizeof(pft_real_t));
    pft_weight_t *dw = pft_ws_take(&ws, (size_t)nd * sizeof(pft_weight_t));
    const uint32_t yq = cfg->op == PFT_MFTBD_OP_TABLE ? period_(cfg->c_step) : 0u;
    const uint32_t ny = ((uint32_t)cfg->in.n_range + 2u * PFT_MFTBD_YPAD) * yq;
    pft_real_t *yring = NULL;
    pft_real_t *gq = NULL;
    const uint32_t nyblk = ((uint32_t)cfg->in.n_range + 2u * PFT_MFTBD_YPAD + 7u) / 8u;
    uint8_t *yflag = NULL;
    if (yq > 0u) {
        yring = pft_ws_take(&ws, (size_t)nring * ny * sizeof(pft_real_t));
        gq = pft_ws_take(&ws, (size_t)ny * sizeof(pft_real_t));
        yflag = pft_ws_take(&ws, (size_t)nring * nyblk);
    }
    if (pft_ws_status(&ws) != PFT_OK) {
        return PFT_ERR_NOMEM;
    }
    memset(p, 0, sizeof(*p));
    p->cfg = *cfg;
    pft_mftbd_ring_setup_(&p->ring, ring, (uint16_t)nring, cells);
    p->row = row;
    p->ma = ma;
    p->mb = mb;
    p->psi = psi;
    p->mask = mask;
    p->path = path;
    p->gtab = gtab;
    p->gw[0] = gw0;
    p->gw[1] = gw1;
    p->tracks = tracks;
    p->rep = rep;
    p->sE = sE;
    p->sG = sG;
    p->sL = sL;
    p->tw[0] = tw0;
    p->tw[1] = tw1;
    p->tlo[0] = tlo0;
    p->tlo[1] = tlo1;
    p->dres = dres;
    p->dw = dw;
    p->naxes = two ? 2u : 1u;
    /* scan positions one cell apart share their tap weights when c_step = 1/period */
    p->period = period_(cfg->c_step);
    /* g(t) = exp(-t^2/2), t = i/64 */
    for (uint32_t i = 0; i < PFT_MFTBD_GTAB_SIZE; ++i) {
        pft_real_t t = pft_ratio((int32_t)i, 64);
        gtab[i] = pft_exp(pft_neg(pft_mul(pft_sq(t), PFT_C(0.5))));
    }
    p->yq = (uint8_t)yq;
    p->ny = ny;
    p->yring = yring;
    p->gq = gq;
    p->yflag = yflag;
    p->nyblk = (uint16_t)nyblk;
    if (yq > 0u) {
        ytable_setup_(p);
    }
    pft_mftbd_pte_reset(p);
    return PFT_OK;
}

void pft_mftbd_pte_reset(pft_mftbd_pte_t *p)
{
    if (p == NULL || p->ring.buf == NULL) {
        return;
    }
    p->ring.count = 0u;
    p->ring.head = (uint16_t)(p->ring.len - 1u);
    memset(p->tracks, 0, (size_t)p->cfg.max_tracks * sizeof(pft_mftbd_pte_track_t));
    p->frames_in = 0u;
    p->next_id = 1u;
    p->since_search = 0u;
    p->n_rep = 0u;
}

static void core_(const pft_mftbd_pte_t *p, pft_mftbd_dpcore_t_ *c)
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

/* ------------------------------------------------------------------- operator geometry */

/* The state per axis is [r, SV r', SA r'', 0] with SV = 16, SA = 256 (exact in q16), so the
 * small velocity and acceleration variances are far above one LSB. */
#define SV_ 16
#define SA_ 256

/* Per-axis operator parameters of one track at one frame. The operators are straight lines
 * over the last M frames; their best end position c* and slope theta* are the least-squares
 * line of the path, so for a state [r, v, a] they measure r + hc a and v + hv a with
 * hc = -(M-1)(M-2)/12 and hv = -(M-1)/2 (zero in the CV model, where a = 0). */
typedef struct {
    pft_real_t H[8];                   /* measurement matrix of [c*, SV theta*] (scaled state) */
    pft_real_t zc, zt;                 /* predicted measurement (end position, scaled slope) */
    pft_real_t sw2, sw, inv_sw, reach; /* sigma_w^2, sigma_w, 1/sigma_w, 3 sigma_w */
    pft_real_t dth;                    /* direction step, scaled (SV cells/frame) */
    pft_real_t prior_k;                /* dth^2 / (2 (S_tt + dth^2/12)): prior per k^2 */
    pft_real_t c0;                     /* first scan position */
    pft_real_t sc2;                    /* S_cc + sigma_r^2 */
    int32_t ns;                        /* scan positions */
    int32_t L;                         /* directions */
    int32_t ncell;                     /* cells along the axis */
} axis_par_;

static void axis_setup_(const pft_mftbd_pte_t *p, const pft_real_t x[4], const pft_real_t P[16],
                        uint32_t a, int32_t M, axis_par_ *ap)
{
    const pft_mftbd_pte_config_t *c = &p->cfg;
    memset(ap->H, 0, sizeof(ap->H));
    ap->H[0] = PFT_C(1.0);
    ap->H[5] = PFT_C(1.0);
    if (c->motion == PFT_MFTBD_MOTION_CA) {
        /* hc / SA and hv SV / SA on the scaled acceleration */
        ap->H[2] = pft_neg(pft_ratio((M - 1) * (M - 2), 12 * SA_));
        ap->H[6] = pft_neg(pft_ratio((M - 1) * SV_, 2 * SA_));
    }
    ap->zc = pft_add(x[0], pft_mul(ap->H[2], x[2]));
    ap->zt = pft_add(x[1], pft_mul(ap->H[6], x[2]));
    /* S = H P H' (rows [1 0 h2 0], [0 1 h6 0]) */
    pft_real_t h2 = ap->H[2];
    pft_real_t h6 = ap->H[6];
    pft_real_t scc = pft_add(pft_add(P[0], pft_mul_i(pft_mul(h2, P[2]), 2)), pft_mul(pft_sq(h2), P[10]));
    pft_real_t stt = pft_add(pft_add(P[5], pft_mul_i(pft_mul(h6, P[6]), 2)), pft_mul(pft_sq(h6), P[10]));
    scc = pft_max(scc, PFT_C(0.0));
    stt = pft_max(stt, PFT_C(0.0));
    pft_real_t sr2 = pft_sq(c->sigma_r[a]);
    ap->sw2 = pft_add(sr2, scc);
    ap->sw = p->yq > 0u ? p->sigma_y : pft_min(pft_sqrt(ap->sw2), c->sigma_w_max);
    ap->sw2 = pft_sq(ap->sw);
    ap->inv_sw = pft_recip(ap->sw);
    ap->reach = pft_mul_i(ap->sw, 3);
    ap->L = (int32_t)c->n_dir[a];
    ap->dth = pft_mul_i(c->dtheta_min, SV_);
    if (ap->L > 1) {
        ap->dth = pft_max(pft_div_i(pft_mul_i(pft_sqrt(stt), 4), ap->L - 1), ap->dth);
    }
    /* dth^2 / (2 (S_tt + dth^2/12)) = 1 / (2 (S_tt/dth^2 + 1/12)) (scale-free) */
    pft_real_t rho = pft_div(stt, pft_sq(ap->dth));
    ap->prior_k = pft_recip(pft_mul_i(pft_add(rho, PFT_C(0.0833333333333)), 2));
    ap->sc2 = pft_add(scc, sr2);
    int32_t half = pft_floor_int(pft_div(pft_mul(c->scan_sigmas, pft_sqrt(ap->sc2)), c->c_step));
    if (half < 1) {
        half = 1;
    }
    if (half > (int32_t)c->scan_steps) {
        half = (int32_t)c->scan_steps;
    }
    ap->ns = 2 * half + 1;
    ap->c0 = pft_sub(ap->zc, pft_mul_i(c->c_step, half));
    ap->ncell = a == 0u ? (int32_t)c->in.n_range : (int32_t)c->in.n_doppler;
}

/* floor(x / 64) for any sign */
static int32_t fdiv64_(int32_t x)
{
    return x >= 0 ? x / 64 : -((-x + 63) / 64);
}

/* Per-frame weight table of one axis: gw[k] = g(k / (64 sigma_w)) for k = 0 .. R, R the
 * reach 3 sigma_w in 1/64 cells; path positions are quantised to 1/64 cell (error <= 1/128
 * cell), so every tap is an integer distance and a table read, identical in both builds. */
static int32_t gw_setup_(const pft_mftbd_pte_t *p, uint32_t a, const axis_par_ *ap)
{
    pft_real_t *gw = p->gw[a];
    int32_t R = pft_floor_int(pft_mul_i(ap->reach, 64));
    if (R > (int32_t)PFT_MFTBD_GW_SIZE - 1) {
        R = (int32_t)PFT_MFTBD_GW_SIZE - 1;
    }
    for (int32_t k = 0; k <= R; ++k) {
        int32_t idx = pft_round_int(pft_mul_i(ap->inv_sw, k));
        gw[k] = idx < (int32_t)PFT_MFTBD_GTAB_SIZE ? p->gtab[idx] : PFT_C(0.0);
    }
    return R;
}

/* Tap lists of every scan position of one axis for a path displaced by -shift cells at this
 * frame; writes the sums of squared weights into gs[]. Positions one cell apart have the same
 * weights, so when c_step = 1/period only `period` phases are computed and the others reuse
 * them shifted by whole cells (clipped at the image edges). tlo[4j..]: first cell, count,
 * offset of the first weight in tw. */
static void taps_(const pft_mftbd_pte_t *p, uint32_t a, const axis_par_ *ap, int32_t R,
                  pft_real_t shift, pft_real_t *gs)
{
    pft_real_t *tw = p->tw[a];
    const pft_real_t *gw = p->gw[a];
    int16_t *tl = p->tlo[a];
    int32_t blo[2u * PFT_MFTBD_MAX_SCAN_STEPS + 1u];
    int32_t bcnt[2u * PFT_MFTBD_MAX_SCAN_STEPS + 1u];
    pft_real_t bg[2u * PFT_MFTBD_MAX_SCAN_STEPS + 1u];
    int32_t np = (p->period == 0u || (int32_t)p->period > ap->ns) ? ap->ns : (int32_t)p->period;
    for (int32_t ph = 0; ph < np; ++ph) {
        pft_real_t pos = pft_sub(pft_add(ap->c0, pft_mul_i(p->cfg.c_step, ph)), shift);
        int32_t q = pft_round_int(pft_mul_i(pft_clamp(pos, PFT_C(-30000.0), PFT_C(30000.0)), 64));
        int32_t lo = -fdiv64_(R - q); /* ceil((q - R) / 64) */
        int32_t hi = fdiv64_(q + R);
        if (hi - lo + 1 > (int32_t)PFT_MFTBD_MAX_TAPS) {
            hi = lo + (int32_t)PFT_MFTBD_MAX_TAPS - 1;
        }
        int32_t cnt = hi >= lo ? hi - lo + 1 : 0;
        pft_real_t g2 = PFT_C(0.0);
        pft_real_t *w = tw + (size_t)ph * PFT_MFTBD_MAX_TAPS;
        for (int32_t i = 0; i < cnt; ++i) {
            int32_t k = (lo + i) * 64 - q;
            pft_real_t g = gw[k < 0 ? -k : k];
            w[i] = g;
            g2 = pft_add(g2, pft_sq(g));
        }
        blo[ph] = lo;
        bcnt[ph] = cnt;
        bg[ph] = g2;
    }
    for (int32_t j = 0; j < ap->ns; ++j) {
        int32_t ph = j % np;
        int32_t lo = blo[ph] + j / np;
        int32_t cnt = bcnt[ph];
        int32_t off = 0;
        if (lo < 0) {
            off = -lo;
            cnt -= off;
            lo = 0;
        }
        if (lo + cnt > ap->ncell) {
            cnt = ap->ncell - lo;
        }
        if (cnt < 0) {
            cnt = 0;
            lo = 0;
            off = 0;
        }
        const pft_real_t *w = tw + (size_t)ph * PFT_MFTBD_MAX_TAPS + off;
        pft_real_t g2 = bg[ph];
        if (cnt != bcnt[ph]) {
            g2 = PFT_C(0.0);
            for (int32_t i = 0; i < cnt; ++i) {
                g2 = pft_add(g2, pft_sq(w[i]));
            }
        }
        tl[4 * j] = (int16_t)lo;
        tl[4 * j + 1] = (int16_t)cnt;
        tl[4 * j + 2] = (int16_t)((size_t)ph * PFT_MFTBD_MAX_TAPS + (size_t)off);
        gs[j] = g2;
    }
}

/* Range-time operator sums of one frame: for every scan position j, E[j] += sum g zeta and
 * G[j] += sum g^2 along the path displaced by -shift cells (taps as in taps_, fused with the
 * multiply-accumulate). */
static void accum_1d_(const pft_mftbd_pte_t *p, const axis_par_ *ap, int32_t R, pft_real_t shift,
                      const pft_real_t *zf)
{
    const pft_real_t *gw = p->gw[0];
    pft_real_t w[PFT_MFTBD_MAX_TAPS];
    int32_t np = (p->period == 0u || (int32_t)p->period > ap->ns) ? ap->ns : (int32_t)p->period;
    for (int32_t ph = 0; ph < np; ++ph) {
        pft_real_t pos = pft_sub(pft_add(ap->c0, pft_mul_i(p->cfg.c_step, ph)), shift);
        int32_t q = pft_round_int(pft_mul_i(pft_clamp(pos, PFT_C(-30000.0), PFT_C(30000.0)), 64));
        int32_t lo = -fdiv64_(R - q);
        int32_t hi = fdiv64_(q + R);
        if (hi - lo + 1 > (int32_t)PFT_MFTBD_MAX_TAPS) {
            hi = lo + (int32_t)PFT_MFTBD_MAX_TAPS - 1;
        }
        int32_t cnt = hi >= lo ? hi - lo + 1 : 0;
        pft_real_t g2 = PFT_C(0.0);
        for (int32_t i = 0; i < cnt; ++i) {
            int32_t k = (lo + i) * 64 - q;
            w[i] = gw[k < 0 ? -k : k];
            g2 = pft_add(g2, pft_sq(w[i]));
        }
        for (int32_t j = ph, u = lo; j < ap->ns; j += np, ++u) {
            pft_real_t e = PFT_C(0.0);
            pft_real_t g = g2;
            if (u >= 0 && u + cnt <= ap->ncell) {
                for (int32_t i = 0; i < cnt; ++i) {
                    e = pft_add(e, pft_mul(w[i], zf[u + i]));
                }
            } else {
                g = PFT_C(0.0);
                for (int32_t i = 0; i < cnt; ++i) {
                    if (u + i >= 0 && u + i < ap->ncell) {
                        e = pft_add(e, pft_mul(w[i], zf[u + i]));
                        g = pft_add(g, pft_sq(w[i]));
                    }
                }
            }
            p->sE[j] = pft_add(p->sE[j], e);
            p->sG[j] = pft_add(p->sG[j], g);
        }
    }
}

/* Displacement theta*tau' - r''*tau'^2/2 of a path tau' frames back (scaled theta and acc). */
static pft_real_t shift_(pft_real_t th, pft_real_t acc, int32_t tau)
{
    pft_real_t v = pft_div_i(pft_mul_i(th, tau), SV_);
    pft_real_t q = pft_div_i(pft_mul_i(acc, tau * tau), 2 * SA_);
    return pft_sub(v, q);
}

/* Displacement of a straight operator path (scaled slope). */
static pft_real_t line_shift_(pft_real_t th, int32_t tau)
{
    return pft_div_i(pft_mul_i(th, tau), SV_);
}

/* Transition and process noise of the scaled state (T = 1 frame). The noise intensity is
 * q = q_sd^2; it is formed as (q_sd SV)^2 and (q_sd SA)^2 so that it stays representable in
 * q16 (q itself, e.g. 4e-6, is below the q16 LSB). */
static void model_(const pft_mftbd_pte_config_t *c, uint32_t a, pft_real_t F[16], pft_real_t Q[16])
{
    pft_real_t qv = pft_sq(pft_mul_i(c->q_sd[a], SV_)); /* SV^2 q */
    memset(F, 0, 16u * sizeof(pft_real_t));
    memset(Q, 0, 16u * sizeof(pft_real_t));
    F[0] = PFT_C(1.0);
    F[1] = pft_ratio(1, SV_);
    F[5] = PFT_C(1.0);
    F[10] = PFT_C(1.0);
    F[15] = PFT_C(1.0);
    if (c->motion == PFT_MFTBD_MOTION_CA) {
        pft_real_t qa = pft_sq(pft_mul_i(c->q_sd[a], SA_)); /* SA^2 q */
        F[2] = pft_ratio(1, 2 * SA_);
        F[6] = pft_ratio(SV_, SA_);
        /* white jerk: q [[1/20, 1/8, 1/6], [1/8, 1/3, 1/2], [1/6, 1/2, 1]], scaled by S Q S */
        Q[0] = pft_div_i(qv, SV_ * SV_ * 20);
        Q[1] = pft_div_i(qv, SV_ * 8);
        Q[2] = pft_div_i(qv, 6);             /* SA q / 6 = SV^2 q / 6 (SA = SV^2) */
        Q[5] = pft_div_i(qv, 3);
        Q[6] = pft_div_i(qa, 2 * SV_);       /* SV SA q / 2 */
        Q[10] = qa;
    } else {
        /* white acceleration: q [[1/3, 1/2], [1/2, 1]] */
        Q[0] = pft_div_i(qv, SV_ * SV_ * 3);
        Q[1] = pft_div_i(qv, SV_ * 2);
        Q[5] = qv;
    }
    Q[4] = Q[1];
    Q[8] = Q[2];
    Q[9] = Q[6];
}

/* v as a signed 16.16 fixed-point integer (any range of pft_real_t, both builds). */
static int64_t fix16_(pft_real_t v)
{
    int32_t ip = pft_floor_int(v);
    pft_real_t fr = pft_sub(v, pft_from_int(ip));
    return (int64_t)ip * 65536 + 2 * (int64_t)pft_round_int(pft_mul_i(fr, 32768));
}

/* TABLE: grid index of the path ending at c0 (cfix = 16.16 of c0, times SV) with scaled
 * slope tfix (16.16), tau frames back: round(yq (c0 - theta tau)) + YPAD yq. */
static int32_t grid_index_(int64_t cfix, int64_t tfix, int32_t tau, int32_t yq)
{
    int64_t num = (cfix - tfix * tau) * yq + ((int64_t)1 << 19);
    int64_t f = num >= 0 ? num / ((int64_t)1 << 20) : -((-num + ((int64_t)1 << 20) - 1) / ((int64_t)1 << 20));
    return (int32_t)f + (int32_t)PFT_MFTBD_YPAD * yq;
}

/* ------------------------------------------------------------------------ track step */

static void track_step_(pft_mftbd_pte_t *p, pft_mftbd_pte_track_t *t)
{
    const pft_mftbd_pte_config_t *c = &p->cfg;
    const uint32_t na = p->naxes;
    const uint32_t nr = c->in.n_range;
    axis_par_ ap[2];
    pft_real_t lc[2][2u * PFT_MFTBD_MAX_SCAN_STEPS + 1u];
    pft_real_t gs[2][2u * PFT_MFTBD_MAX_SCAN_STEPS + 1u];
    pft_real_t lw[PFT_MFTBD_MAX_DIRS * PFT_MFTBD_MAX_DIRS];

    /* 1. predict */
    for (uint32_t a = 0; a < na; ++a) {
        pft_real_t F[16];
        pft_real_t Q[16];
        model_(c, a, F, Q);
        pft_kf4_predict(t->x[a], t->P[a], F, Q);
    }
    t->amp_var = pft_add(t->amp_var, c->q_amp);

    /* 2. operator parameters */
    int32_t M = t->n_acc;
    if (M > (int32_t)c->max_len) {
        M = (int32_t)c->max_len;
    }
    if (M > (int32_t)p->ring.count) {
        M = (int32_t)p->ring.count;
    }
    if (M < 1) {
        M = 1;
    }
    memset(ap, 0, sizeof(ap));
    for (uint32_t a = 0; a < na; ++a) {
        axis_setup_(p, t->x[a], t->P[a], a, M, &ap[a]);
        for (int32_t j = 0; j < ap[a].ns; ++j) {
            pft_real_t d = pft_mul_i(c->c_step, j - (ap[a].ns - 1) / 2);
            lc[a][j] = pft_neg(pft_div(pft_sq(d), pft_mul_i(ap[a].sc2, 2)));
        }
    }
    int32_t reach64[2] = {0, 0};
    for (uint32_t a = 0; a < na && p->yq == 0u; ++a) {
        reach64[a] = gw_setup_(p, a, &ap[a]);
    }
    if (na == 1u) {
        ap[1].ns = 1;
        ap[1].L = 1;
        lc[1][0] = PFT_C(0.0);
    }
    const int32_t n0 = ap[0].ns;
    const int32_t n1 = ap[1].ns;
    const int32_t ndir = ap[0].L * ap[1].L;
    const int32_t nsc = n0 * n1;
    int32_t m1 = M > 1 ? M : 2;
    int32_t mm = m1 * m1 - 1;

    /* TABLE: per frame, the responses every direction may read (computed once) */
    const pft_real_t *yrow[PFT_MFTBD_MAX_FRAMES];
    int64_t cfix = 0;
    if (p->yq > 0u) {
        int32_t h = (ap[0].L - 1) / 2;
        cfix = fix16_(ap[0].c0) * SV_;
        int64_t tlo = fix16_(pft_sub(ap[0].zt, pft_mul_i(ap[0].dth, h)));
        int64_t thi = fix16_(pft_add(ap[0].zt, pft_mul_i(ap[0].dth, h)));
        for (int32_t tau = 0; tau < M; ++tau) {
            int32_t b0 = grid_index_(cfix, thi, tau, p->yq);
            int32_t b1 = grid_index_(cfix, tlo, tau, p->yq);
            yrow[tau] = yframe_(p, (uint32_t)tau, b0, b1 + n0);
        }
    }

    /* 3-5. per direction: operators, likelihood, Kalman update */
    pft_real_t tmax = PFT_REAL_MIN;
    for (int32_t li = 0; li < ndir; ++li) {
        int32_t l[2];
        l[0] = li % ap[0].L;
        l[1] = li / ap[0].L;
        pft_real_t th[2] = {PFT_C(0.0), PFT_C(0.0)};
        pft_real_t prior = PFT_C(0.0);
        for (uint32_t a = 0; a < na; ++a) {
            int32_t k = l[a] - (ap[a].L - 1) / 2;
            th[a] = pft_add(ap[a].zt, pft_mul_i(ap[a].dth, k));
            prior = pft_sub(prior, pft_mul_i(ap[a].prior_k, k * k));
        }
        for (int32_t j = 0; j < nsc; ++j) {
            p->sE[j] = PFT_C(0.0);
            p->sG[j] = PFT_C(0.0);
        }
        const int64_t tfix = p->yq > 0u ? fix16_(th[0]) : 0;
        for (int32_t tau = 0; tau < M; ++tau) {
            if (p->yq > 0u) {
                /* TABLE: one response read per scan position */
                int32_t b = grid_index_(cfix, tfix, tau, p->yq);
                int32_t ny = (int32_t)p->ny;
                const pft_real_t *yv = yrow[tau];
                if (b >= 0 && b + n0 <= ny) {
                    pft_real_t *restrict se = p->sE;
                    pft_real_t *restrict sg = p->sG;
                    const pft_real_t *restrict yb = yv + b;
                    const pft_real_t *restrict gb = p->gq + b;
                    /* plain additions: |y| <= zeta_clip * sum g <= 64 * 6.9 and at most 64
                     * frames are summed, so |E| < 28300 and G < 64 * 4.2 never overflow the q16
                     * range (TABLE mode requires zeta_clip <= 64, see config_check) */
                    for (int32_t j0 = 0; j0 < n0; ++j0) {
                        se[j0] = se[j0] + yb[j0];
                        sg[j0] = sg[j0] + gb[j0];
                    }
                } else {
                    for (int32_t j0 = 0; j0 < n0; ++j0) {
                        if (b + j0 >= 0 && b + j0 < ny) {
                            p->sE[j0] = pft_add(p->sE[j0], yv[b + j0]);
                            p->sG[j0] = pft_add(p->sG[j0], p->gq[b + j0]);
                        }
                    }
                }
                continue;
            }
            const pft_real_t *zf = pft_mftbd_ring_get_(&p->ring, (uint32_t)tau);
            if (na == 1u) {
                accum_1d_(p, &ap[0], reach64[0], line_shift_(th[0], tau), zf);
                continue;
            }
            taps_(p, 0u, &ap[0], reach64[0], line_shift_(th[0], tau), gs[0]);
            taps_(p, 1u, &ap[1], reach64[1], line_shift_(th[1], tau), gs[1]);
            for (int32_t j1 = 0; j1 < n1; ++j1) {
                int32_t lo1 = p->tlo[1][4 * j1];
                int32_t cnt1 = p->tlo[1][4 * j1 + 1];
                const pft_real_t *w1 = p->tw[1] + p->tlo[1][4 * j1 + 2];
                for (int32_t j0 = 0; j0 < n0; ++j0) {
                    int32_t lo0 = p->tlo[0][4 * j0];
                    int32_t cnt0 = p->tlo[0][4 * j0 + 1];
                    const pft_real_t *w0 = p->tw[0] + p->tlo[0][4 * j0 + 2];
                    pft_real_t e = PFT_C(0.0);
                    for (int32_t i1 = 0; i1 < cnt1; ++i1) {
                        const pft_real_t *zr = zf + (size_t)(lo1 + i1) * nr + (size_t)lo0;
                        pft_real_t s = PFT_C(0.0);
                        for (int32_t i0 = 0; i0 < cnt0; ++i0) {
                            s = pft_add(s, pft_mul(w0[i0], zr[i0]));
                        }
                        e = pft_add(e, pft_mul(w1[i1], s));
                    }
                    int32_t j = j1 * n0 + j0;
                    p->sE[j] = pft_add(p->sE[j], e);
                    p->sG[j] = pft_add(p->sG[j], pft_mul(gs[0][j0], gs[1][j1]));
                }
            }
        }
        /* test statistic and log summand; best scan position */
        pft_real_t lmax = PFT_REAL_MIN;
        int32_t jb = 0;
        for (int32_t j = 0; j < nsc; ++j) {
            /* max(T, 0)^2 = E (E / G) for E > 0, clamped at 150^2 (no square root here; q16:
             * the product saturates at 32768 before the clamp, with the same result) */
            pft_real_t t2 = PFT_C(0.0);
            if (p->sE[j] > PFT_C(0.0) && p->sG[j] > PFT_C(0.0)) {
                t2 = pft_min(pft_mul(p->sE[j], pft_div(p->sE[j], p->sG[j])), PFT_C(22500.0));
            }
            pft_real_t ls = pft_add(pft_add(lc[0][j % n0], lc[1][j / n0]), pft_mul(t2, PFT_C(0.5)));
            p->sL[j] = ls;
            if (ls > lmax) {
                lmax = ls;
                jb = j;
            }
        }
        pft_real_t ssum = PFT_C(0.0);
        for (int32_t j = 0; j < nsc; ++j) {
            ssum = pft_add(ssum, pft_exp(pft_sub(p->sL[j], lmax)));
        }
        pft_real_t lse = pft_add(lmax, pft_log(ssum));
        int32_t jb0 = jb % n0;
        int32_t jb1 = jb / n0;
        pft_real_t cstar[2];
        for (uint32_t a = 0; a < na; ++a) {
            int32_t ja = a == 0u ? jb0 : jb1;
            int32_t na_ = a == 0u ? n0 : n1;
            int32_t stride = a == 0u ? 1 : n0;
            pft_real_t off = PFT_C(0.0);
            if (ja > 0 && ja < na_ - 1) {
                off = pft_mftbd_parabola_(p->sL[jb - stride], p->sL[jb], p->sL[jb + stride]);
            }
            cstar[a] = pft_add(ap[a].c0, pft_mul(c->c_step, pft_add(pft_from_int(ja), off)));
        }
        pft_real_t Tb = PFT_C(0.0);
        if (p->sG[jb] > PFT_C(0.0)) {
            Tb = pft_clamp(pft_div(p->sE[jb], pft_sqrt(p->sG[jb])), PFT_C(-150.0), PFT_C(150.0));
        }
        if (Tb > tmax) {
            tmax = Tb;
        }
        pft_real_t tc = pft_max(pft_sq(Tb), PFT_C(1.0));
        /* per-direction Kalman update with [c*, theta] */
        pft_real_t *res = p->dres + (size_t)li * DRES_;
        for (uint32_t a = 0; a < 2u; ++a) {
            pft_real_t *xa = res + 4u * a;
            pft_real_t *Pa = res + 8u + 16u * a;
            memcpy(xa, t->x[a], 4u * sizeof(pft_real_t));
            memcpy(Pa, t->P[a], 16u * sizeof(pft_real_t));
            if (a >= na) {
                continue;
            }
            pft_real_t z[2] = {cstar[a], th[a]};
            pft_real_t R[4];
            R[0] = pft_add(pft_div(ap[a].sw2, tc), pft_div_i(pft_sq(c->c_step), 12));
            /* slope variance 12 sigma_w^2 / ((M^2 - 1) T^2), scaled by SV^2 */
            R[3] = pft_add(pft_div_i(pft_sq(ap[a].dth), 12),
                           pft_div_i(pft_div(pft_mul_i(ap[a].sw2, 12 * SV_ * SV_), tc), mm));
            R[1] = PFT_C(0.0);
            R[2] = PFT_C(0.0);
            (void)pft_kf4_update2(xa, Pa, ap[a].H, z, R); /* on PFT_ERR_RANGE the prediction stays */
        }
        /* amplitude: measurement E/G with variance 1/G */
        pft_real_t am = t->amp;
        pft_real_t av = t->amp_var;
        if (p->sG[jb] > PFT_C(0.0)) {
            pft_real_t meas = pft_div(p->sE[jb], p->sG[jb]);
            pft_real_t r = pft_recip(p->sG[jb]);
            pft_real_t k = pft_div(av, pft_add(av, r));
            am = pft_add(am, pft_mul(k, pft_sub(meas, am)));
            av = pft_sub(av, pft_mul(k, av));
        }
        res[40] = am;
        res[41] = av;
        res[42] = pft_add(prior, lse);
        res[43] = Tb;
        lw[li] = res[42];
    }

    /* 6. fusion. Deviations from the prediction are fused (X = X_pred + sum W (X_l - X_pred))
     * so that weights summing to 1 - epsilon after rounding (q16) cannot bias the state. */
    (void)pft_lognormalize(lw, p->dw, (size_t)ndir);
    pft_real_t xs[2][4];
    pft_real_t Ps[2][16];
    memset(xs, 0, sizeof(xs));
    memset(Ps, 0, sizeof(Ps));
    pft_real_t as = PFT_C(0.0);
    for (int32_t li = 0; li < ndir; ++li) {
        pft_real_t w = pft_weight_to_real(p->dw[li]);
        const pft_real_t *res = p->dres + (size_t)li * DRES_;
        for (uint32_t a = 0; a < na; ++a) {
            for (uint32_t i = 0; i < 3u; ++i) {
                xs[a][i] = pft_add(xs[a][i], pft_mul(w, pft_sub(res[4u * a + i], t->x[a][i])));
            }
        }
        as = pft_add(as, pft_mul(w, pft_sub(res[40], t->amp)));
    }
    for (uint32_t a = 0; a < na; ++a) {
        for (uint32_t i = 0; i < 3u; ++i) {
            xs[a][i] = pft_add(t->x[a][i], xs[a][i]);
        }
    }
    as = pft_add(t->amp, as);
    pft_real_t avs = PFT_C(0.0);
    for (int32_t li = 0; li < ndir; ++li) {
        pft_real_t w = pft_weight_to_real(p->dw[li]);
        const pft_real_t *res = p->dres + (size_t)li * DRES_;
        for (uint32_t a = 0; a < na; ++a) {
            const pft_real_t *Pa = res + 8u + 16u * a;
            pft_real_t d[3];
            for (uint32_t i = 0; i < 3u; ++i) {
                d[i] = pft_sub(res[4u * a + i], xs[a][i]);
            }
            for (uint32_t i = 0; i < 3u; ++i) {
                for (uint32_t j = i; j < 3u; ++j) {
                    Ps[a][i * 4u + j] = pft_add(Ps[a][i * 4u + j],
                                                pft_mul(w, pft_add(Pa[i * 4u + j], pft_mul(d[i], d[j]))));
                }
            }
        }
        avs = pft_add(avs, pft_mul(w, pft_add(res[41], pft_sq(pft_sub(res[40], as)))));
    }
    for (uint32_t a = 0; a < na; ++a) {
        for (uint32_t i = 0; i < 3u; ++i) {
            t->x[a][i] = xs[a][i];
            for (uint32_t j = i; j < 3u; ++j) {
                t->P[a][i * 4u + j] = Ps[a][i * 4u + j];
                t->P[a][j * 4u + i] = Ps[a][i * 4u + j];
            }
        }
        t->P[a][0] = pft_max(t->P[a][0], PFT_REAL_EPS);
        t->P[a][5] = pft_max(t->P[a][5], PFT_REAL_EPS);
    }
    t->amp = as;
    t->amp_var = pft_max(avs, PFT_REAL_EPS);

    /* 7. detection and maintenance */
    t->score = tmax;
    t->detected = tmax >= c->eta_t;
    t->misses = t->detected ? 0u : (uint8_t)(t->misses + 1u);
    if (t->n_acc < c->max_len) {
        t->n_acc++;
    }
    t->age++;
    if (t->misses >= c->max_misses) {
        t->live = false;
    }
    /* a track that left the image has no data left */
    for (uint32_t a = 0; a < na; ++a) {
        int32_t n = a == 0u ? (int32_t)c->in.n_range : (int32_t)c->in.n_doppler;
        if (t->x[a][0] < PFT_C(-2.0) || t->x[a][0] > pft_from_int(n + 1)) {
            t->live = false;
        }
    }
}

/* ----------------------------------------------------------------------- initiation */

static int32_t half_cells_(pft_real_t sw)
{
    /* ceil(3 sigma_w) */
    return -pft_floor_int(pft_neg(pft_mul_i(sw, 3)));
}

/* New track from unscaled position/velocity moments per axis (na axes used). */
static void track_new_(pft_mftbd_pte_t *p, pft_mftbd_pte_track_t *t, const pft_real_t pos[2],
                       const pft_real_t vel[2], const pft_real_t pv[2], const pft_real_t vv[2],
                       const pft_real_t cv[2], pft_real_t amp, uint8_t n_acc)
{
    memset(t, 0, sizeof(*t));
    for (uint32_t a = 0; a < p->naxes; ++a) {
        t->x[a][0] = pos[a];
        t->x[a][1] = pft_mul_i(vel[a], SV_);
        t->P[a][0] = pv[a];
        t->P[a][1] = pft_mul_i(cv[a], SV_);
        t->P[a][4] = t->P[a][1];
        t->P[a][5] = pft_mul_i(vv[a], SV_ * SV_);
        if (p->cfg.motion == PFT_MFTBD_MOTION_CA) {
            t->P[a][10] = pft_sq(pft_mul_i(p->cfg.acc_sd0[a], SA_));
        }
    }
    t->amp = amp;
    t->amp_var = PFT_C(1.0);
    t->n_acc = n_acc;
    t->live = true;
    t->detected = true;
    t->id = pft_mftbd_new_id_(&p->next_id);
}

static uint32_t n_live_(const pft_mftbd_pte_t *p)
{
    uint32_t n = 0;
    for (uint32_t i = 0; i < p->cfg.max_tracks; ++i) {
        n += p->tracks[i].live ? 1u : 0u;
    }
    return n;
}

static void initiate_(pft_mftbd_pte_t *p)
{
    const pft_mftbd_pte_config_t *c = &p->cfg;
    pft_mftbd_dpcore_t_ core;
    core_(p, &core);
    const uint32_t N = c->init_frames;
    const uint32_t cells = (uint32_t)c->in.n_range * c->in.n_doppler;
    const bool two = p->naxes == 2u;
    memset(p->mask, 0, (size_t)N * cells);
    /* cancel live tracks, extrapolated back over the batch */
    for (uint32_t i = 0; i < c->max_tracks; ++i) {
        const pft_mftbd_pte_track_t *t = &p->tracks[i];
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
                                ? pft_round_int(pft_sub(t->x[a][0], shift_(t->x[a][1], t->x[a][2], back)))
                                : 0;
                u = u < -30000 ? -30000 : (u > 30000 ? 30000 : u);
                p->path[2u * j + a] = (int16_t)u;
            }
        }
        pft_mftbd_dp_cancel_(&core, p->path, h[0], h[1]);
    }
    /* extract targets */
    uint32_t live = n_live_(p);
    for (uint32_t guard = 0; guard < c->max_tracks && live < c->max_tracks; ++guard) {
        int32_t cell;
        pft_real_t best = pft_mftbd_dp_run_(&core, &cell);
        if (cell < 0 || !(best > c->init_threshold)) {
            break;
        }
        pft_mftbd_dp_backtrack_(&core, cell, p->path);
        pft_real_t pos[2] = {PFT_C(0.0), PFT_C(0.0)};
        pft_real_t vel[2] = {PFT_C(0.0), PFT_C(0.0)};
        pft_real_t pv[2] = {PFT_C(1.0), PFT_C(1.0)};
        pft_real_t vv[2] = {PFT_C(1.0), PFT_C(1.0)};
        pft_real_t cv[2] = {PFT_C(0.0), PFT_C(0.0)};
        int32_t h[2] = {0, 0};
        int32_t n = (int32_t)N;
        for (uint32_t a = 0; a < p->naxes; ++a) {
            pft_mftbd_path_fit_(&core, p->path, a, &pos[a], &vel[a]);
            pft_real_t s2 = pft_sq(c->sigma_r[a]);
            pv[a] = pft_mul(s2, pft_ratio(2 * (2 * n - 1), n * (n + 1)));
            cv[a] = pft_mul(s2, pft_ratio(6, n * (n + 1)));
            vv[a] = pft_mul(s2, pft_ratio(12, n * (n * n - 1)));
            pft_real_t sw = pft_min(pft_sqrt(pft_add(s2, pv[a])), c->sigma_w_max);
            h[a] = half_cells_(sw);
        }
        if (!two) {
            pv[1] = PFT_C(1.0);
            vv[1] = PFT_C(1.0);
        }
        for (uint32_t i = 0; i < c->max_tracks; ++i) {
            if (!p->tracks[i].live) {
                track_new_(p, &p->tracks[i], pos, vel, pv, vv, cv,
                           pft_mftbd_path_amp_(&core, p->path), (uint8_t)N);
                p->tracks[i].score = best;
                live++;
                break;
            }
        }
        pft_mftbd_dp_cancel_(&core, p->path, h[0], h[1]);
    }
}

static void dedup_(pft_mftbd_pte_t *p)
{
    const pft_mftbd_pte_config_t *c = &p->cfg;
    if (!(c->dup_cells > PFT_C(0.0))) {
        return;
    }
    for (uint32_t i = 0; i < c->max_tracks; ++i) {
        for (uint32_t j = i + 1u; j < c->max_tracks; ++j) {
            pft_mftbd_pte_track_t *a = &p->tracks[i];
            pft_mftbd_pte_track_t *b = &p->tracks[j];
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

static void reports_(pft_mftbd_pte_t *p)
{
    uint32_t n = 0;
    for (uint32_t i = 0; i < p->cfg.max_tracks; ++i) {
        const pft_mftbd_pte_track_t *t = &p->tracks[i];
        if (!t->live) {
            continue;
        }
        pft_mftbd_report_t *r = &p->rep[n++];
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

static pft_status_t update_(pft_mftbd_pte_t *p, const pft_frame_t *frame, const pft_real_t *z)
{
    if (p == NULL || p->ring.buf == NULL) {
        return PFT_ERR_INVAL;
    }
    pft_status_t st = pft_mftbd_push_(&p->cfg.in, &p->ring, p->row, frame, z);
    if (st != PFT_OK) {
        return st;
    }
    if (p->yq > 0u) {
        memset(p->yflag + (size_t)p->ring.head * p->nyblk, 0, p->nyblk);
    }
    p->frames_in++;
    for (uint32_t i = 0; i < p->cfg.max_tracks; ++i) {
        if (p->tracks[i].live) {
            track_step_(p, &p->tracks[i]);
        }
    }
    dedup_(p);
    if (p->since_search < 0xFFFFu) {
        p->since_search++;
    }
    uint32_t live = n_live_(p);
    if (p->ring.count >= p->cfg.init_frames && live < p->cfg.max_tracks &&
        (live == 0u || p->since_search >= p->cfg.init_period)) {
        p->since_search = 0u;
        initiate_(p);
    }
    reports_(p);
    return PFT_OK;
}

pft_status_t pft_mftbd_pte_update(pft_mftbd_pte_t *p, const pft_frame_t *frame)
{
    if (frame == NULL) {
        return PFT_ERR_INVAL;
    }
    return update_(p, frame, NULL);
}

pft_status_t pft_mftbd_pte_update_real(pft_mftbd_pte_t *p, const pft_real_t *z)
{
    if (z == NULL) {
        return PFT_ERR_INVAL;
    }
    return update_(p, NULL, z);
}

uint32_t pft_mftbd_pte_reports(const pft_mftbd_pte_t *p, const pft_mftbd_report_t **out)
{
    if (p == NULL) {
        if (out != NULL) {
            *out = NULL;
        }
        return 0u;
    }
    if (out != NULL) {
        *out = p->rep;
    }
    return p->n_rep;
}

pft_status_t pft_mftbd_pte_start(pft_mftbd_pte_t *p, const pft_real_t pos[2],
                                 const pft_real_t vel[2], const pft_real_t pos_var[2],
                                 const pft_real_t vel_var[2], pft_real_t amp, uint8_t n_acc,
                                 uint16_t *id)
{
    if (p == NULL || p->ring.buf == NULL || pos == NULL || vel == NULL || pos_var == NULL ||
        vel_var == NULL || id == NULL || n_acc == 0u) {
        return PFT_ERR_INVAL;
    }
    for (uint32_t a = 0; a < p->naxes; ++a) {
        if (!(pos_var[a] > PFT_C(0.0)) || !(vel_var[a] > PFT_C(0.0)) ||
            !(pos[a] >= PFT_REAL_MIN && pos[a] <= PFT_REAL_MAX) ||
            !(vel[a] >= PFT_REAL_MIN && vel[a] <= PFT_REAL_MAX)) {
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
    return PFT_ERR_RANGE;
}

pft_status_t pft_mftbd_pte_threshold(pft_mftbd_pte_t *p, pft_real_t pfa, uint32_t runs,
                                     uint64_t seed, pft_real_t *vt)
{
    if (p == NULL || p->ring.buf == NULL) {
        return PFT_ERR_INVAL;
    }
    pft_mftbd_dpcore_t_ c;
    core_(p, &c);
    pft_status_t st = pft_mftbd_dp_mc_(&p->cfg.in, &c, &p->ring, p->row, pfa, runs, seed, vt);
    if (st == PFT_OK) {
        pft_mftbd_pte_reset(p);
    }
    return st;
}
