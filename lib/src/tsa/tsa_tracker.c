/*
 * The TSA-AK particle filter (docs/algorithms.md 4.4) and its NCV / TS baselines: resampling,
 * conservative fit and pioneer, free-model propagation, kernel-histogram weights with the
 * rho_min discard, estimate, beta adaptation and reference-point rule, template update with
 * bounded snake passes; the loss handling (search, confirmation, re-acquisition) and the
 * per-frame appearance context (code map, similarity cache).
 */
#include <string.h>

#include "pft/pft_resample.h"
#include "../core/acc_int.h"
#include "tsa_int.h"
#include "../core/seq_int.h"

/* The reported contour box is clamped to +-BOX_LIMIT_ px (int16 fields). */
#define BOX_LIMIT_ 32000
/* The smallest initial polygon: its bounding box spans at least this many pixels each way. */
#define MIN_EXTENT_ 3
/* Floor of rho in N_iter = ceil(k_s / rho) (no division by zero). */
#define RHO_FLOOR_ PFT_C(0.01)

/* ----------------------------------------- setup ------------------------------------------ */

pft_status_t pft_tsa_init(pft_tsa_t *t, const pft_tsa_config_t *cfg, void *work, size_t work_len)
{
    if (t == NULL || work == NULL) {
        return PFT_ERR_INVAL;
    }
    pft_status_t st = pft_tsa_config_check(cfg, NULL);
    if (st != PFT_OK) {
        return st;
    }
    if (work_len < pft_tsa_workspace_size(cfg)) {
        return PFT_ERR_NOMEM;
    }
    memset(t, 0, sizeof(*t));
    t->cfg = *cfg;
    t->cfg.snake.max_w = cfg->max_target_w;
    t->cfg.snake.max_h = cfg->max_target_h;
    const size_t n = cfg->n_particles;
    const size_t n1 = n + 1u;
    const size_t kcap = (size_t)cfg->max_target_w * cfg->max_target_h;
    const size_t np = cfg->snake_points;
    pft_ws_t ws;
    pft_ws_init(&ws, work, work_len);
    t->px = (pft_real_t *)pft_ws_take(&ws, n1 * sizeof(pft_real_t));
    t->py = (pft_real_t *)pft_ws_take(&ws, n1 * sizeof(pft_real_t));
    t->pvx = (pft_real_t *)pft_ws_take(&ws, n1 * sizeof(pft_real_t));
    t->pvy = (pft_real_t *)pft_ws_take(&ws, n1 * sizeof(pft_real_t));
    t->tx = (pft_real_t *)pft_ws_take(&ws, n * sizeof(pft_real_t));
    t->ty = (pft_real_t *)pft_ws_take(&ws, n * sizeof(pft_real_t));
    t->tvx = (pft_real_t *)pft_ws_take(&ws, n * sizeof(pft_real_t));
    t->tvy = (pft_real_t *)pft_ws_take(&ws, n * sizeof(pft_real_t));
    t->rho = (pft_real_t *)pft_ws_take(&ws, n1 * sizeof(pft_real_t));
    t->w = (pft_weight_t *)pft_ws_take(&ws, n1 * sizeof(pft_weight_t));
    t->idx = (uint32_t *)pft_ws_take(&ws, n * sizeof(uint32_t));
    t->kern.pix = (pft_tsa_kpix_t *)pft_ws_take(&ws, kcap * sizeof(pft_tsa_kpix_t));
    t->kern_alt.pix = (pft_tsa_kpix_t *)pft_ws_take(&ws, kcap * sizeof(pft_tsa_kpix_t));
    t->cross = (int32_t *)pft_ws_take(&ws, np * sizeof(int32_t));
    t->contour = (pft_tsa_pt_t *)pft_ws_take(&ws, np * sizeof(pft_tsa_pt_t));
    t->cwork = (pft_tsa_pt_t *)pft_ws_take(&ws, np * sizeof(pft_tsa_pt_t));
    t->bflags = (uint8_t *)pft_ws_take(&ws, np);
    t->snake_ws_len =
        pft_tsa_snake_work_size(cfg->max_target_w, cfg->max_target_h, cfg->snake.margin);
    t->snake_ws = pft_ws_take(&ws, t->snake_ws_len);
    const size_t span_cap = PFT_TSA_SPAN_CAP(cfg->max_target_w, cfg->max_target_h, np);
    t->spans = (pft_tsa_span_t *)pft_ws_take(&ws, span_cap * sizeof(pft_tsa_span_t));
    t->spans_alt = (pft_tsa_span_t *)pft_ws_take(&ws, span_cap * sizeof(pft_tsa_span_t));
    t->kw = (uint16_t *)pft_ws_take(&ws, kcap * sizeof(uint16_t));
    t->kw_alt = (uint16_t *)pft_ws_take(&ws, kcap * sizeof(uint16_t));
    t->span_cap = (uint32_t)span_cap;
    if (cfg->map_margin > 0u) {
        t->map_cap = ((size_t)cfg->max_target_w + 2u * (size_t)cfg->map_margin) *
                     ((size_t)cfg->max_target_h + 2u * (size_t)cfg->map_margin);
        t->map = (uint8_t *)pft_ws_take(&ws, 2u * t->map_cap);
    }
    t->memo_cap = (uint32_t)(2u * n + 4u);
    t->memo_key = (uint32_t *)pft_ws_take(&ws, (size_t)t->memo_cap * sizeof(uint32_t));
    t->memo_rho = (pft_real_t *)pft_ws_take(&ws, (size_t)t->memo_cap * sizeof(pft_real_t));
    st = pft_ws_status(&ws);
    if (st != PFT_OK) {
        memset(t, 0, sizeof(*t));
        return st;
    }
    t->kern.cap = (uint32_t)kcap;
    t->kern_alt.cap = (uint32_t)kcap;
    /* scratch that refusable calls use is kept zero between calls (see pft_tsa_start) */
    memset(t->cwork, 0, np * sizeof(pft_tsa_pt_t));
    memset(t->cross, 0, np * sizeof(int32_t));
    pft_rng_seed(&t->rng, cfg->seed);
    t->est.state = PFT_TSA_IDLE;
    return PFT_OK;
}

pft_status_t pft_tsa_reset(pft_tsa_t *t)
{
    if (t == NULL || t->px == NULL) {
        return PFT_ERR_INVAL;
    }
    /* px is the first buffer carved, at the aligned start of the caller's workspace: carving
     * again from there (no start padding) gives the same buffers */
    const pft_tsa_config_t cfg = t->cfg;
    return pft_tsa_init(t, &cfg, t->px, pft_tsa_workspace_size(&cfg));
}

/* ----------------------------------- appearance helpers ----------------------------------- */

/* The frame of this update as the appearance model reads it, and the similarity cache. */
typedef struct {
    pft_tsa_view_t_ v;
    pft_real_t lo_x, hi_x, lo_y, hi_y; /* the box every position is kept in */
} frame_ctx_t_;

/* The key of pixel (cx, cy) in the similarity cache (positions are kept within the frame
 * enlarged by the kernel, |c| < 2^15 - 1). */
static uint32_t memo_key_of_(int32_t cx, int32_t cy)
{
    return ((uint32_t)(cx + 32768) << 16) | (uint32_t)(cy + 32768);
}

/* The cache slot that holds key, or else the first empty slot on its probe path; memo_cap
 * when neither (a full table: more distinct positions than 2 N + 4, not reached). */
static uint32_t memo_slot_(const pft_tsa_t *t, uint32_t key)
{
    uint32_t i = (uint32_t)(((uint64_t)(key * 2654435761u) * t->memo_cap) >> 32);
    for (uint32_t probe = 0; probe < t->memo_cap; ++probe) {
        if (t->memo_key[i] == key || t->memo_key[i] == 0u) {
            return i;
        }
        i = i + 1u == t->memo_cap ? 0u : i + 1u;
    }
    return t->memo_cap;
}

/* rho against the template of gain g as the tracker uses it: with bg_ring scaled by qg_scale
 * (the weighted template's similarity to the unweighted target at its build taken as 1; not
 * clamped, so a placement that matches better than the target did scores above 1 and the
 * order of the placements is kept); without, r itself. */
static pft_real_t rho_scaled_(const pft_tsa_t *t, uint32_t g, pft_real_t r)
{
    return t->cfg.bg_ring > PFT_REAL_ONE ? pft_mul(r, t->qg_scale[g]) : r;
}

/* Similarity of the template to the kernel placed at pixel (cx, cy), cached per position for
 * this frame (the particles of a cloud often share pixels). */
static pft_real_t rho_px_(pft_tsa_t *t, const frame_ctx_t_ *fc, int32_t cx, int32_t cy)
{
    const uint32_t key = memo_key_of_(cx, cy);
    const uint32_t i = memo_slot_(t, key);
    if (i < t->memo_cap && t->memo_key[i] == key) {
        return t->memo_rho[i];
    }
    pft_tsa_view_hist_(&fc->v, &t->kern, t->spans, t->n_spans, t->kw, cx, cy, &t->h, t->jb);
    const pft_real_t r =
        rho_scaled_(t, t->gsel, pft_tsa_rho_hist_(&t->h, &t->qg[t->gsel], &t->qg_root[t->gsel]));
    if (i < t->memo_cap) {
        t->memo_key[i] = key;
        t->memo_rho[i] = r;
    }
    return r;
}

/* Stores rho of the template at pixel (cx, cy) in the similarity cache (a full table: not
 * stored). */
static void rho_put_(pft_tsa_t *t, int32_t cx, int32_t cy, pft_real_t r)
{
    const uint32_t key = memo_key_of_(cx, cy);
    const uint32_t i = memo_slot_(t, key);
    if (i < t->memo_cap) {
        t->memo_key[i] = key;
        t->memo_rho[i] = r;
    }
}

static pft_real_t rho_at_(pft_tsa_t *t, const frame_ctx_t_ *fc, pft_real_t x, pft_real_t y)
{
    return rho_px_(t, fc, pft_round_int(x), pft_round_int(y));
}

/* The box positions are kept in: the frame enlarged by the kernel's box on each side, so no
 * estimate leaves the frame by more than the target's size. */
static void position_box_(const pft_tsa_t *t, frame_ctx_t_ *fc)
{
    const int32_t kw = t->kern.x1 - t->kern.x0 + 1;
    const int32_t kh = t->kern.y1 - t->kern.y0 + 1;
    fc->lo_x = pft_from_int(-kw);
    fc->lo_y = pft_from_int(-kh);
    fc->hi_x = pft_from_int((int32_t)t->cfg.width - 1 + kw);
    fc->hi_y = pft_from_int((int32_t)t->cfg.height - 1 + kh);
}

/* The offsets of gain_select_'s placements from the prior mean: a quarter of the kernel's width
 * and height, at least 1. */
static int32_t probe_dx_(const pft_tsa_t *t)
{
    const int32_t s = (t->kern.x1 - t->kern.x0 + 1) / 4;
    return s < 1 ? 1 : s;
}

static int32_t probe_dy_(const pft_tsa_t *t)
{
    const int32_t s = (t->kern.y1 - t->kern.y0 + 1) / 4;
    return s < 1 ? 1 : s;
}

/* Codes the region that the placements of the first m particles cover (with probes, also
 * gain_select_'s placements around the prior mean), and clears the similarity cache. */
static void frame_prepare_(pft_tsa_t *t, frame_ctx_t_ *fc, uint32_t m, bool probes)
{
    memset(t->memo_key, 0, (size_t)t->memo_cap * sizeof(uint32_t));
    int32_t x0 = INT32_MAX;
    int32_t y0 = INT32_MAX;
    int32_t x1 = INT32_MIN;
    int32_t y1 = INT32_MIN;
    if (probes) {
        const int32_t px = pft_round_int(pft_clamp(t->prior_x, fc->lo_x, fc->hi_x));
        const int32_t py = pft_round_int(pft_clamp(t->prior_y, fc->lo_y, fc->hi_y));
        x0 = px - probe_dx_(t);
        x1 = px + probe_dx_(t);
        y0 = py - probe_dy_(t);
        y1 = py + probe_dy_(t);
    }
    for (uint32_t i = 0; i < m; ++i) {
        const int32_t x = pft_round_int(t->px[i]);
        const int32_t y = pft_round_int(t->py[i]);
        x0 = x < x0 ? x : x0;
        x1 = x > x1 ? x : x1;
        y0 = y < y0 ? y : y0;
        y1 = y > y1 ? y : y1;
    }
    pft_tsa_view_map_(&fc->v, t->map, t->map_cap, x0 + t->kern.x0, y0 + t->kern.y0,
                      x1 + t->kern.x1, y1 + t->kern.y1);
}

/* A real >= 0 stored in a weight with the same bits: q16 keeps the Q16.16 value (a weight
 * 2^-14 of its Q2.30 scale), float the value. Weights are only compared and normalised, and on
 * this scale (at most 2^16 per particle, positions below 2^13 px, at most 65535 particles) the
 * 64-bit sums of the weighted mean cannot overflow. */
static pft_weight_t weight_on_rho_scale_(pft_real_t v)
{
    return (pft_weight_t)v;
}

/* Particle weight from its similarity: rho itself (eq. 22, lik_lambda = 0) or
 * exp(lambda (rho - rho_best)) (lik_lambda > 0), on the scale of rho. */
static pft_weight_t weight_of_(const pft_tsa_t *t, pft_real_t rho, pft_real_t rho_best)
{
    if (!(rho > PFT_C(0.0))) {
        return 0;
    }
    if (!(t->cfg.lik_lambda > PFT_C(0.0))) {
        return weight_on_rho_scale_(rho);
    }
    const pft_weight_t w = pft_wexp(pft_mul(t->cfg.lik_lambda, pft_sub(rho, rho_best)));
    return weight_on_rho_scale_(pft_weight_to_real(w));
}

/* Weighted mean of v[0..n) with weights w (any scale, sum > 0; 0 when the sum is 0). */
static pft_real_t wmean_(const pft_weight_t *w, const pft_real_t *v, uint32_t n)
{
    pft_acc_t_ num = PFT_ACC_ZERO_;
    pft_wacc_t den = 0;
    for (uint32_t i = 0; i < n; ++i) {
        num += pft_acc_wx_(w[i], v[i]);
        den += w[i];
    }
    return pft_acc_div_(num, den);
}

/* The contour's bounding box at the kernel origin (cx, cy) into the estimate. */
static void contour_box_(pft_tsa_t *t, int32_t cx, int32_t cy)
{
    const pft_tsa_box_t_ b = pft_tsa_bbox_(t->contour, t->cfg.snake_points);
    const int32_t v[4] = {b.x0 + cx, b.y0 + cy, b.x1 + cx, b.y1 + cy};
    int16_t c[4];
    for (uint32_t i = 0; i < 4u; ++i) {
        const int32_t lo = v[i] < -BOX_LIMIT_ ? -BOX_LIMIT_ : v[i];
        c[i] = (int16_t)(lo > BOX_LIMIT_ ? BOX_LIMIT_ : lo);
    }
    t->est.box_x0 = c[0];
    t->est.box_y0 = c[1];
    t->est.box_x1 = c[2];
    t->est.box_y1 = c[3];
}

static int64_t abs64_(int64_t a)
{
    return a < 0 ? -a : a;
}

/* Area change within [1/r, r] (r = max_area_change, Q4), a nonzero area and a pixel centre
 * inside. */
static bool contour_acceptable_(pft_tsa_t *t, const pft_tsa_pt_t *p, int64_t area2_ref)
{
    const int32_t r = pft_round_int(pft_mul_i(t->cfg.max_area_change, 16));
    const int64_t a = abs64_(pft_tsa_poly_area2(p, t->cfg.snake_points));
    const int64_t b = abs64_(area2_ref);
    if (a == 0 || b == 0 || !(a * 16 <= b * r && b * 16 <= a * r)) {
        return false;
    }
    return pft_tsa_poly_count_(p, t->cfg.snake_points, t->cross) > 0u;
}

/* The bank's gain i in 1/256: 256 + 13 (i - GAIN_UNITY_), i.e. 0.85 .. 1.15 in steps of 0.05. */
#define GAIN_UNITY_ 3u
/* Placements at which gain_select_ compares the bank's templates. */
#define GAIN_PROBES_ 5u
static uint32_t gain_q8_(uint32_t i)
{
    return 256u + 13u * i - 13u * GAIN_UNITY_;
}

/* Builds kernel, spans and template from cwork (frame coordinates) into the alternate kernel
 * and commits them (kernel, spans, template, contour, area); returns the new origin. On an
 * error nothing is committed: PFT_ERR_DEGENERATE for an empty kernel or template, PFT_ERR_LOST
 * when anchor is set and the new template drifted away from the first one. */
static pft_status_t rebuild_(pft_tsa_t *t, const pft_frame_t *f, pft_tsa_pt_t *origin, bool anchor)
{
    const uint16_t cq4 = (uint16_t)pft_round_int(pft_mul_i(t->cfg.kernel_c, 16));
    pft_status_t st =
        pft_tsa_kernel_build(&t->kern_alt, t->cwork, t->cfg.snake_points, cq4, t->cross, origin);
    if (st != PFT_OK) {
        return st;
    }
    const uint32_t ns = pft_tsa_spans_(&t->kern_alt, t->spans_alt, t->span_cap, t->kw_alt);
    if (ns > t->span_cap) {
        return PFT_ERR_NOMEM; /* not reached: the cap bounds every contour of the box */
    }
    pft_tsa_hist_t hq;
    st = pft_tsa_hist(f, &t->kern_alt, origin->x, origin->y, &hq);
    if (st != PFT_OK) {
        return st;
    }
    if (hq.total == 0u) {
        return PFT_ERR_DEGENERATE;
    }
    /* hq's bins are at most its total (pft_tsa_hist), so this is pft_tsa_bhattacharyya(&hq,
     * &t->q0) without its copies on the stack */
    if (anchor && t->cfg.anchor_rho_min > PFT_C(0.0) &&
        pft_tsa_rho_hist_(&hq, &t->q0, &t->q0_root) < t->cfg.anchor_rho_min) {
        return PFT_ERR_LOST;
    }
    const pft_tsa_kernel_t tmp = t->kern;
    t->kern = t->kern_alt;
    t->kern_alt = tmp;
    pft_tsa_span_t *sp = t->spans;
    t->spans = t->spans_alt;
    t->spans_alt = sp;
    t->n_spans_alt = t->n_spans;
    t->n_spans = ns;
    uint16_t *kw = t->kw;
    t->kw = t->kw_alt;
    t->kw_alt = kw;
    /* bg_ring: the ring between the kernel's box and that box bg_ring times as large (the same
     * centre), (bg_ring - 1) w / 2 columns and (bg_ring - 1) h / 2 rows on each side */
    const bool bg = t->cfg.bg_ring > PFT_REAL_ONE;
    const pft_tsa_box_t_ kb = {origin->x + t->kern.x0, origin->y + t->kern.y0,
                               origin->x + t->kern.x1, origin->y + t->kern.y1};
    const pft_real_t grow = pft_sub(t->cfg.bg_ring, PFT_REAL_ONE);
    const int32_t mx = bg ? pft_round_int(pft_mul_i(grow, kb.x1 - kb.x0 + 1)) / 2 : 0;
    const int32_t my = bg ? pft_round_int(pft_mul_i(grow, kb.y1 - kb.y0 + 1)) / 2 : 0;
    const uint32_t a16 = (uint32_t)pft_tsa_q16_(t->cfg.bg_alpha); /* 1..65536 (checked) */
    /* the template under each gain of the bank (unity first: hq itself, gain 256/256 leaves
     * every value as it is; then each gain's histogram in hq); with bg_ring each weighted by its
     * ring under the same gain (t->h is the ring's scratch) and its similarities scaled by
     * 1 / rho(hq, weighted template), so that the target as it was seen scores 1 again */
    for (uint32_t i = 0; i < PFT_TSA_GAINS_; ++i) {
        const uint32_t g = i == 0u ? GAIN_UNITY_ : (i <= GAIN_UNITY_ ? i - 1u : i);
        if (g != GAIN_UNITY_) {
            pft_tsa_hist_gain_(f, &t->kern, origin->x, origin->y, gain_q8_(g), &hq);
        }
        t->qg[g] = hq;
        t->qg_scale[g] = PFT_REAL_ONE;
        if (bg && g == GAIN_UNITY_) {
            t->qp = hq;
            pft_tsa_hroot_(&t->qp, &t->qp_root);
        }
        if (bg) {
            pft_tsa_ring_hist_(f, &kb, mx, my, gain_q8_(g), &t->h);
            pft_tsa_bg_weight_(&t->qg[g], &t->h, a16);
        }
        pft_tsa_hroot_(&t->qg[g], &t->qg_root[g]);
        if (bg) {
            const pft_real_t r0 = pft_tsa_rho_hist_(&hq, &t->qg[g], &t->qg_root[g]);
            /* at most 16 (a weighted template that hardly matches its own target) */
            t->qg_scale[g] = r0 > PFT_C(0.0625) ? pft_div(PFT_REAL_ONE, r0) : PFT_C(16.0);
        }
    }
    t->q = t->qg[GAIN_UNITY_];
    t->q_root = t->qg_root[GAIN_UNITY_];
    for (uint32_t i = 0; i < t->cfg.snake_points; ++i) {
        t->contour[i].x = (int16_t)(t->cwork[i].x - origin->x);
        t->contour[i].y = (int16_t)(t->cwork[i].y - origin->y);
    }
    t->area2 = pft_tsa_poly_area2(t->cwork, t->cfg.snake_points);
    return PFT_OK;
}

/* cwork and cross are scratch that pft_tsa_start uses before it may refuse: they are zero
 * between calls, so a refused start leaves the workspace as it found it. */
static void scratch_clear_(pft_tsa_t *t)
{
    memset(t->cwork, 0, (size_t)t->cfg.snake_points * sizeof(pft_tsa_pt_t));
    memset(t->cross, 0, (size_t)t->cfg.snake_points * sizeof(int32_t));
}

/* ----------------------------------------- start ------------------------------------------ */

/* The initial contour in cwork: the resampled polygon (checked by the caller: nonzero area, a
 * pixel centre inside), refined by init_passes snake passes when the result is acceptable
 * (else the resampled polygon again). Returns the passes run. */
static uint32_t initial_contour_(pft_tsa_t *t, const pft_frame_t *frame, const pft_tsa_pt_t *poly,
                                 uint32_t n, int64_t area2)
{
    const uint32_t np = t->cfg.snake_points;
    if (t->cfg.init_passes == 0u) {
        return 0u;
    }
    uint32_t done = 0u;
    const pft_status_t st = pft_tsa_snake(frame, t->cwork, np, &t->cfg.snake, t->cfg.init_passes,
                                          t->bflags, t->snake_ws, t->snake_ws_len, &done);
    if (st != PFT_OK || !contour_acceptable_(t, t->cwork, area2)) {
        (void)pft_tsa_poly_resample(poly, n, t->cwork, np);
    }
    return done > 255u ? 255u : done;
}

/* The reference ring restarted at (x, y). */
static void ref_restart_(pft_tsa_t *t, pft_real_t x, pft_real_t y)
{
    t->ref_n = 1u;
    t->ref_x[0] = x;
    t->ref_y[0] = y;
    t->ref_w[0] = PFT_REAL_ONE;
}

/* All particles at (x, y) at rest, the reference points and beta restarted. */
static void place_particles_(pft_tsa_t *t, pft_real_t x, pft_real_t y)
{
    t->n_state = t->cfg.n_particles + (t->cfg.motion == PFT_TSA_MOTION_TSA ? 1u : 0u);
    for (uint32_t i = 0; i <= t->cfg.n_particles; ++i) {
        t->px[i] = x;
        t->py[i] = y;
        t->pvx[i] = PFT_C(0.0);
        t->pvy[i] = PFT_C(0.0);
        t->rho[i] = PFT_REAL_ONE;
        t->w[i] = PFT_W_ONE;
    }
    ref_restart_(t, x, y);
    t->beta = t->cfg.motion == PFT_TSA_MOTION_NCV ? PFT_C(0.0) : t->cfg.beta0;
    t->weak_run = 0u;
    t->mode = PFT_TSA_MODE_TRACK;
    t->good_x = x;
    t->good_y = y;
    t->cand_x = x;
    t->cand_y = y;
    t->res_x = PFT_C(0.0);
    t->res_y = PFT_C(0.0);
}

pft_status_t pft_tsa_start(pft_tsa_t *t, const pft_frame_t *frame, const pft_tsa_pt_t *poly,
                           uint32_t n)
{
    if (t == NULL || poly == NULL || t->px == NULL || n < 3u || n > 65535u) {
        return PFT_ERR_INVAL;
    }
    pft_status_t st = pft_frame_check(frame, t->cfg.width, t->cfg.height, PFT_TSA_FMT_MASK_);
    if (st != PFT_OK) {
        return st;
    }
    const int64_t a0 = pft_tsa_poly_area2(poly, n);
    if (a0 == 0) {
        return PFT_ERR_DEGENERATE;
    }
    const pft_tsa_box_t_ bb = pft_tsa_bbox_(poly, n);
    const bool in_frame = bb.x0 >= 0 && bb.y0 >= 0 && bb.x1 < (int32_t)frame->width &&
                          bb.y1 < (int32_t)frame->height;
    const bool fits = bb.x1 - bb.x0 + 1 <= (int32_t)t->cfg.max_target_w &&
                      bb.y1 - bb.y0 + 1 <= (int32_t)t->cfg.max_target_h;
    if (!in_frame || !fits) {
        return PFT_ERR_INVAL;
    }
    if (bb.x1 - bb.x0 < MIN_EXTENT_ || bb.y1 - bb.y0 < MIN_EXTENT_) {
        return PFT_ERR_DEGENERATE;
    }
    /* Every remaining refusal is decided on the resampled polygon, in the zeroed scratch
     * (cwork, cross), before anything else is written: from here on nothing fails. */
    const uint32_t np = t->cfg.snake_points;
    (void)pft_tsa_poly_resample(poly, n, t->cwork, np); /* poly checked: n >= 3, nonzero area */
    if (pft_tsa_poly_count_(t->cwork, np, t->cross) == 0u) {
        scratch_clear_(t);
        return PFT_ERR_DEGENERATE;
    }
    const uint32_t passes = initial_contour_(t, frame, poly, n, a0);
    pft_tsa_pt_t origin;
    st = rebuild_(t, frame, &origin, false);
    scratch_clear_(t);
    if (st != PFT_OK) {
        return st; /* not reached: the contour was checked above */
    }
    t->q0 = t->q;
    t->q0_root = t->q_root;
    const pft_real_t ox = pft_from_int(origin.x);
    const pft_real_t oy = pft_from_int(origin.y);
    place_particles_(t, ox, oy);
    t->gsel = GAIN_UNITY_;
    t->started = true;
    memset(&t->est, 0, sizeof(t->est));
    t->est.snake_passes = (uint8_t)passes;
    t->est.state = PFT_TSA_TRACKING;
    t->est.frame = 1u;
    t->est.x = ox;
    t->est.y = oy;
    t->est.pioneer_x = ox;
    t->est.pioneer_y = oy;
    t->est.rho = PFT_REAL_ONE;
    t->est.rho_pioneer = PFT_REAL_ONE;
    t->est.beta = t->beta;
    t->est.beta_next = t->beta;
    t->est.n_alive = t->cfg.n_particles;
    t->est.ref_is_estimate = true;
    t->est.template_updated = true;
    t->est.last_seq = frame->seq;
    t->est.last_timestamp_us = frame->timestamp_us;
    contour_box_(t, origin.x, origin.y);
    return PFT_OK;
}

/* ------------------------------------- one frame: steps ----------------------------------- */

/* Step 1: resample N particles from the M weights of the previous frame (an all-zero weight
 * set, which resampling refuses, keeps the particles in order). */
static void resample_(pft_tsa_t *t, uint32_t N, uint32_t M)
{
    if (pft_resample(PFT_RESAMPLE_SYSTEMATIC, t->w, M, t->idx, N, &t->rng, NULL, 0u) != PFT_OK) {
        for (uint32_t i = 0; i < N; ++i) {
            t->idx[i] = i % M;
        }
    }
    for (uint32_t i = 0; i < N; ++i) {
        const uint32_t j = t->idx[i];
        t->tx[i] = t->px[j];
        t->ty[i] = t->py[j];
        t->tvx[i] = t->pvx[j];
        t->tvy[i] = t->pvy[j];
    }
    memcpy(t->px, t->tx, N * sizeof(pft_real_t));
    memcpy(t->py, t->ty, N * sizeof(pft_real_t));
    memcpy(t->pvx, t->tvx, N * sizeof(pft_real_t));
    memcpy(t->pvy, t->tvy, N * sizeof(pft_real_t));
}

/* Step 2 (TS, TSA): the conservative fit of the reference points per axis, bounded; zero for
 * NCV. */
static void conservative_fit_(const pft_tsa_t *t, pft_tsa_motion_fit_t *fx,
                              pft_tsa_motion_fit_t *fy)
{
    memset(fx, 0, sizeof(*fx));
    memset(fy, 0, sizeof(*fy));
    if (t->cfg.motion == PFT_TSA_MOTION_NCV) {
        return;
    }
    const uint8_t order = t->cfg.motion == PFT_TSA_MOTION_TSA ? 2u : 1u;
    const pft_real_t *pi = t->cfg.fit_rho_weights ? t->ref_w : NULL;
    if (pft_tsa_motion_fit(t->ref_x, pi, t->ref_n, t->cfg.fit_sigma, order, fx) != PFT_OK ||
        pft_tsa_motion_fit(t->ref_y, pi, t->ref_n, t->cfg.fit_sigma, order, fy) != PFT_OK) {
        /* all weights zero: constant position at the newest point */
        (void)pft_tsa_motion_fit(t->ref_x, NULL, t->ref_n, t->cfg.fit_sigma, order, fx);
        (void)pft_tsa_motion_fit(t->ref_y, NULL, t->ref_n, t->cfg.fit_sigma, order, fy);
    }
    pft_tsa_motion_fit_bound(fx, t->cfg.fit_a_max, t->cfg.fit_v_max);
    pft_tsa_motion_fit_bound(fy, t->cfg.fit_a_max, t->cfg.fit_v_max);
}

/* The position diffusion of an axis whose last innovation was res: pos_sd, or spread_gain |res|
 * up to spread_max when that is larger [E]. */
static pft_real_t spread_(const pft_tsa_t *t, pft_real_t res)
{
    const pft_real_t w = pft_min(pft_mul(t->cfg.spread_gain, pft_abs(res)), t->cfg.spread_max);
    return pft_max(t->cfg.pos_sd, w);
}

/* Adds an independent position diffusion of sd px to the free model's noise: the Cholesky
 * factor of [[Q11 + sd^2, Q12], [Q12, Q22]]. */
static void diffusion_(pft_tsa_motion_free_t *c, pft_real_t sd)
{
    const pft_real_t q11 = pft_add(c->q11, pft_sq(sd));
    c->l11 = pft_sqrt(q11);
    c->l21 = c->l11 > PFT_C(0.0) ? pft_div(c->q12, c->l11) : PFT_C(0.0);
    c->l22 = pft_sqrt(pft_max(pft_sub(c->q22, pft_sq(c->l21)), PFT_C(0.0)));
}

/* Step 3: the N normal particles through the free model at beta with the input (vbx, vby) and
 * the extra position diffusion; TSA's pioneer at the fit's prediction. Positions stay in the
 * frame's enlarged box. */
static void propagate_(pft_tsa_t *t, const frame_ctx_t_ *fc, uint32_t N, pft_real_t beta,
                       const pft_tsa_motion_fit_t *fx, const pft_tsa_motion_fit_t *fy)
{
    pft_tsa_motion_free_t coef;
    (void)pft_tsa_motion_free_coef(&coef, beta, t->cfg.q); /* beta and q checked by the config */
    const pft_real_t vbx = fx->v_pred;
    const pft_real_t vby = fy->v_pred;
    /* position diffusion: pos_sd, widened per axis by the last innovation (spread_gain); folded
     * into the free model's noise (x: Q11 + sd^2), so two normal draws per axis */
    pft_tsa_motion_free_t cx = coef;
    pft_tsa_motion_free_t cy = coef;
    diffusion_(&cx, spread_(t, t->res_x));
    diffusion_(&cy, spread_(t, t->res_y));
    /* the prior mean (without the noise, whose mean is 0) is the innovation's reference:
     * mean x + phi12 mean v + gamma1 vbar per axis */
    const pft_weight_t w1 = weight_on_rho_scale_(PFT_REAL_ONE);
    pft_acc_t_ sx = PFT_ACC_ZERO_;
    pft_acc_t_ sy = PFT_ACC_ZERO_;
    pft_acc_t_ svx = PFT_ACC_ZERO_;
    pft_acc_t_ svy = PFT_ACC_ZERO_;
    pft_wacc_t den = 0;
    /* the inputs' terms gamma vbar are the same for every particle */
    const pft_real_t ux = pft_mul(cx.gamma1, vbx);
    const pft_real_t uvx = pft_mul(cx.gamma2, vbx);
    const pft_real_t uy = pft_mul(cy.gamma1, vby);
    const pft_real_t uvy = pft_mul(cy.gamma2, vby);
    for (uint32_t i = 0; i < N; ++i) {
        /* the integer ziggurat: one 32-bit draw per value for nearly all, no log, square root
         * or cosine (Box-Muller's were a tenth of a q16 update) */
        const pft_real_t g1 = pft_rng_gauss_zig(&t->rng);
        const pft_real_t g2 = pft_rng_gauss_zig(&t->rng);
        const pft_real_t g3 = pft_rng_gauss_zig(&t->rng);
        const pft_real_t g4 = pft_rng_gauss_zig(&t->rng);
        sx += pft_acc_wx_(w1, t->px[i]);
        sy += pft_acc_wx_(w1, t->py[i]);
        svx += pft_acc_wx_(w1, t->pvx[i]);
        svy += pft_acc_wx_(w1, t->pvy[i]);
        den += w1;
        pft_tsa_motion_free_step_u_(&cx, &t->px[i], &t->pvx[i], ux, uvx, g1, g2);
        pft_tsa_motion_free_step_u_(&cy, &t->py[i], &t->pvy[i], uy, uvy, g3, g4);
        t->px[i] = pft_clamp(t->px[i], fc->lo_x, fc->hi_x);
        t->py[i] = pft_clamp(t->py[i], fc->lo_y, fc->hi_y);
    }
    t->prior_x = pft_add(pft_acc_div_(sx, den), pft_add(pft_mul(coef.phi12, pft_acc_div_(svx, den)),
                                                        pft_mul(coef.gamma1, vbx)));
    t->prior_y = pft_add(pft_acc_div_(sy, den), pft_add(pft_mul(coef.phi12, pft_acc_div_(svy, den)),
                                                        pft_mul(coef.gamma1, vby)));
    if (t->cfg.motion == PFT_TSA_MOTION_TSA) {
        t->px[N] = pft_clamp(fx->x_pred, fc->lo_x, fc->hi_x);
        t->py[N] = pft_clamp(fy->x_pred, fc->lo_y, fc->hi_y);
        t->pvx[N] = vbx;
        t->pvy[N] = vby;
    }
}

/* What step 4 found. */
typedef struct {
    pft_tsa_state_t state;
    uint32_t alive;   /* normal particles with rho >= rho_min */
    bool any_alive;   /* some particle (the pioneer included) with rho >= rho_min */
    pft_real_t rho_p; /* the pioneer's rho (TSA; else 0) */
    pft_real_t best;  /* the largest rho */
    uint32_t i_best;  /* its particle */
} weigh_out_t_;

/* Step 4 when no normal particle is alive and loss_search is off (the paper's behaviour): TSA
 * lets the pioneer carry the frame (X_hat = X_tilde; the normal particles recover at the
 * resampling); NCV / TS weigh every particle relative to the best (uniformly when all are zero,
 * on the scale of rho, so the weighted sums stay in range). */
static pft_tsa_state_t weigh_fallback_(pft_tsa_t *t, uint32_t N, uint32_t M, pft_real_t best_any,
                                       pft_real_t rho_p)
{
    if (t->cfg.motion == PFT_TSA_MOTION_TSA) {
        for (uint32_t i = 0; i < N; ++i) {
            t->w[i] = 0;
        }
        t->w[N] = PFT_W_ONE;
        return rho_p >= t->cfg.rho_min ? PFT_TSA_PIONEER_ONLY : PFT_TSA_WEAK;
    }
    bool any = false;
    for (uint32_t i = 0; i < M; ++i) {
        t->w[i] = weight_of_(t, t->rho[i], best_any);
        any = any || t->w[i] > 0;
    }
    if (!any) {
        for (uint32_t i = 0; i < M; ++i) {
            t->w[i] = weight_on_rho_scale_(PFT_REAL_ONE);
        }
    }
    return PFT_TSA_WEAK;
}

/* Step 4: similarities, particles below rho_min discarded, weights from rho (eq. 22 or the
 * exponential weighting). With loss_search and nothing kept the weights are left to the
 * caller. */
static weigh_out_t_ weigh_(pft_tsa_t *t, const frame_ctx_t_ *fc, uint32_t N, uint32_t M)
{
    pft_real_t best_alive = PFT_C(0.0);
    weigh_out_t_ r;
    r.best = PFT_C(-1.0);
    r.i_best = 0u;
    for (uint32_t i = 0; i < M; ++i) {
        t->rho[i] = rho_at_(t, fc, t->px[i], t->py[i]);
        if (t->rho[i] > r.best) {
            r.best = t->rho[i];
            r.i_best = i;
        }
        if (t->rho[i] >= t->cfg.rho_min) {
            best_alive = pft_max(best_alive, t->rho[i]);
        }
    }
    r.alive = 0u;
    r.any_alive = false;
    for (uint32_t i = 0; i < M; ++i) {
        t->w[i] = t->rho[i] >= t->cfg.rho_min ? weight_of_(t, t->rho[i], best_alive) : 0;
        if (t->w[i] > 0) {
            r.any_alive = true;
            r.alive += i < N ? 1u : 0u;
        }
    }
    r.rho_p = t->cfg.motion == PFT_TSA_MOTION_TSA ? t->rho[N] : PFT_C(0.0);
    if (r.alive > 0u) {
        r.state = PFT_TSA_TRACKING;
    } else if (t->cfg.loss_search) {
        r.state = r.any_alive ? PFT_TSA_PIONEER_ONLY : PFT_TSA_WEAK;
    } else {
        r.state = weigh_fallback_(t, N, M, pft_max(r.best, PFT_C(0.0)), r.rho_p);
    }
    return r;
}

/* Step 5: the estimate is the weighted mean of the particles; the pioneer fields report the
 * fit (NCV: the estimate). */
static void estimate_(pft_tsa_t *t, uint32_t M, const pft_tsa_motion_fit_t *fx,
                      const pft_tsa_motion_fit_t *fy)
{
    t->est.x = wmean_(t->w, t->px, M);
    t->est.y = wmean_(t->w, t->py, M);
    t->est.vx = wmean_(t->w, t->pvx, M);
    t->est.vy = wmean_(t->w, t->pvy, M);
    t->est.pioneer_x = fx->x_pred;
    t->est.pioneer_y = fy->x_pred;
    t->est.pioneer_vx = fx->v_pred;
    t->est.pioneer_vy = fy->v_pred;
    if (t->cfg.motion == PFT_TSA_MOTION_NCV) {
        t->est.pioneer_x = t->est.x;
        t->est.pioneer_y = t->est.y;
    }
}

/* Appends (x, y) with weight w to the last fit_k reference points. */
static void ref_push_(pft_tsa_t *t, pft_real_t x, pft_real_t y, pft_real_t w)
{
    if (t->ref_n == t->cfg.fit_k) {
        memmove(&t->ref_x[0], &t->ref_x[1], (t->ref_n - 1u) * sizeof(pft_real_t));
        memmove(&t->ref_y[0], &t->ref_y[1], (t->ref_n - 1u) * sizeof(pft_real_t));
        memmove(&t->ref_w[0], &t->ref_w[1], (t->ref_n - 1u) * sizeof(pft_real_t));
        --t->ref_n;
    }
    t->ref_x[t->ref_n] = x;
    t->ref_y[t->ref_n] = y;
    t->ref_w[t->ref_n] = w;
    ++t->ref_n;
}

/* Step 6: TSA's beta for the next frame (eq. 24) and the next reference point (eq. 25: the
 * estimate, or TSA's pioneer), appended to the last fit_k. */
static void next_reference_(pft_tsa_t *t, uint32_t N, pft_real_t rho_e, pft_real_t rho_p)
{
    pft_real_t ox = t->est.x;
    pft_real_t oy = t->est.y;
    pft_real_t ow = rho_e;
    t->est.ref_is_estimate = true;
    if (t->cfg.motion == PFT_TSA_MOTION_TSA) {
        t->beta = pft_tsa_motion_beta_adapt(rho_e, rho_p, t->cfg.beta_max, t->beta);
        if (!pft_tsa_motion_ref_is_estimate(rho_e, rho_p)) {
            ox = t->px[N];
            oy = t->py[N];
            ow = rho_p;
            t->est.ref_is_estimate = false;
        }
    }
    ref_push_(t, ox, oy, ow);
}

/* Lost (without loss_search) and out-of-view bookkeeping on top of the frame's state. */
static pft_tsa_state_t track_state_(pft_tsa_t *t, const pft_frame_t *frame, pft_tsa_state_t state,
                                    pft_real_t rho_e)
{
    if (!t->cfg.loss_search) {
        if (rho_e < t->cfg.rho_min) {
            ++t->weak_run;
        } else {
            t->weak_run = 0u;
        }
        if (t->weak_run >= t->cfg.lost_frames && t->cfg.lost_frames > 0u) {
            state = PFT_TSA_LOST;
        }
    }
    const int32_t cx = pft_round_int(t->est.x);
    const int32_t cy = pft_round_int(t->est.y);
    if (cx < 0 || cy < 0 || cx >= (int32_t)frame->width || cy >= (int32_t)frame->height) {
        state = PFT_TSA_OUT_OF_VIEW;
    }
    return state;
}

/* Shifts every position the tracker holds by (dx, dy): the kernel origin moved. */
static void shift_state_(pft_tsa_t *t, pft_real_t dx, pft_real_t dy)
{
    for (uint32_t i = 0; i <= t->cfg.n_particles; ++i) {
        t->px[i] = pft_add(t->px[i], dx);
        t->py[i] = pft_add(t->py[i], dy);
    }
    for (uint32_t i = 0; i < t->ref_n; ++i) {
        t->ref_x[i] = pft_add(t->ref_x[i], dx);
        t->ref_y[i] = pft_add(t->ref_y[i], dy);
    }
    t->est.x = pft_add(t->est.x, dx);
    t->est.y = pft_add(t->est.y, dy);
    t->est.pioneer_x = pft_add(t->est.pioneer_x, dx);
    t->est.pioneer_y = pft_add(t->est.pioneer_y, dy);
    t->good_x = pft_add(t->good_x, dx);
    t->good_y = pft_add(t->good_y, dy);
}

/* N_iter = min(ceil(k_s / rho), update_max_passes). */
static int32_t update_passes_(const pft_tsa_t *t, pft_real_t rho_e)
{
    const pft_real_t ratio = pft_div(t->cfg.k_s, pft_max(rho_e, RHO_FLOOR_));
    int32_t passes = pft_floor_int(ratio);
    if (pft_from_int(passes) < ratio) {
        ++passes; /* ceil */
    }
    if (passes > (int32_t)t->cfg.update_max_passes) {
        passes = (int32_t)t->cfg.update_max_passes;
    }
    return passes;
}

/* Step 7, template update (eq. 23): contour at the estimate, N_iter snake passes, new kernel
 * and template; the state is shifted by the move of the kernel origin. A contour not wholly in
 * view, a rejected snake result or a drifted template keeps the template. */
static void template_update_(pft_tsa_t *t, const pft_frame_t *f, pft_real_t rho_e)
{
    const uint32_t np = t->cfg.snake_points;
    const int32_t cx = pft_round_int(t->est.x);
    const int32_t cy = pft_round_int(t->est.y);
    const int32_t passes = update_passes_(t, rho_e);
    for (uint32_t i = 0; i < np; ++i) {
        const int32_t x = t->contour[i].x + cx;
        const int32_t y = t->contour[i].y + cy;
        if (x < 1 || y < 1 || x > (int32_t)f->width - 2 || y > (int32_t)f->height - 2) {
            scratch_clear_(t);
            return;
        }
        t->cwork[i].x = (int16_t)x;
        t->cwork[i].y = (int16_t)y;
    }
    uint32_t done = 0u;
    if (passes > 0) {
        const pft_status_t st = pft_tsa_snake(f, t->cwork, np, &t->cfg.snake, (uint32_t)passes,
                                              t->bflags, t->snake_ws, t->snake_ws_len, &done);
        if (st != PFT_OK || !contour_acceptable_(t, t->cwork, t->area2)) {
            t->est.snake_passes = (uint8_t)done;
            scratch_clear_(t);
            return;
        }
    }
    t->est.snake_passes = (uint8_t)done;
    pft_tsa_pt_t origin;
    const pft_status_t st = rebuild_(t, f, &origin, true);
    scratch_clear_(t);
    if (st != PFT_OK) {
        return;
    }
    t->est.template_updated = true;
    const pft_real_t dx = pft_from_int(origin.x - cx);
    const pft_real_t dy = pft_from_int(origin.y - cy);
    if (dx != PFT_C(0.0) || dy != PFT_C(0.0)) {
        shift_state_(t, dx, dy);
    }
}

/* ----------------------------------------- loss handling --------------------------------- */

/* Integer position uniform in cell `cell` of `cells` equal cells of [c - r, c + r] intersected
 * with [0, size - 1] (per axis; one cell: the whole interval). */
static pft_real_t draw_in_(pft_tsa_t *t, pft_real_t c, pft_real_t r, uint16_t size, uint32_t cell,
                           uint32_t cells)
{
    int32_t lo = pft_floor_int(pft_sub(c, r));
    int32_t hi = pft_floor_int(pft_add(c, r));
    lo = lo < 0 ? 0 : (lo > (int32_t)size - 1 ? (int32_t)size - 1 : lo);
    hi = hi < lo ? lo : (hi > (int32_t)size - 1 ? (int32_t)size - 1 : hi);
    /* the interval is at most 2^16 px and cells at most 256: no overflow */
    const int32_t len = hi - lo + 1;
    const int32_t a = lo + (int32_t)(((uint32_t)len * cell) / cells);
    int32_t b = lo + (int32_t)(((uint32_t)len * (cell + 1u)) / cells) - 1;
    b = b < a ? a : b;
    return pft_from_int(a + (int32_t)pft_rng_below(&t->rng, (uint32_t)(b - a + 1)));
}

/* The largest g <= 256 with g * g <= m. */
static uint32_t grid_side_(uint32_t m)
{
    uint32_t g = 1u;
    while (g < 256u && (g + 1u) * (g + 1u) <= m) {
        ++g;
    }
    return g;
}

/* The search's particles: SEARCH spreads them over the window of half-size r around the last
 * good position, CONFIRM over the disc... the box of half-size reacq_radius around the
 * candidate; all at rest. The pioneer (TSA) is placed like a normal particle. */
static void search_place_(pft_tsa_t *t, uint32_t M)
{
    pft_real_t cx = t->good_x;
    pft_real_t cy = t->good_y;
    pft_real_t r;
    if (t->mode == PFT_TSA_MODE_CONFIRM) {
        cx = t->cand_x;
        cy = t->cand_y;
        r = t->cfg.reacq_radius;
    } else {
        const pft_real_t span = pft_from_int((int32_t)(t->cfg.width > t->cfg.height ? t->cfg.width
                                                                                  : t->cfg.height));
        const pft_real_t half = pft_from_int((t->kern.x1 - t->kern.x0 + 1) / 2);
        /* weak_run <= UINT32_MAX: saturated by the clamp to the frame's span */
        const int32_t k = t->weak_run > 4096u ? 4096 : (int32_t)t->weak_run;
        r = pft_min(pft_add(half, pft_mul_i(t->cfg.search_growth, k)), span);
    }
    /* stratified: the first g * g particles one in each cell of a g x g grid over the window
     * (no clumps, no holes), the others anywhere in it */
    const uint32_t g = grid_side_(M);
    for (uint32_t i = 0; i < M; ++i) {
        const bool in_grid = i < g * g;
        t->px[i] = draw_in_(t, cx, r, t->cfg.width, in_grid ? i % g : 0u, in_grid ? g : 1u);
        t->py[i] = draw_in_(t, cy, r, t->cfg.height, in_grid ? i / g : 0u, in_grid ? g : 1u);
        t->pvx[i] = PFT_C(0.0);
        t->pvy[i] = PFT_C(0.0);
    }
}

/* Rounds of the search's local refinement (8 placements each). */
#define REFINE_ROUNDS_ 6u

/* The search's local refinement: a pattern search from particle ib (rho best) over the 8
 * neighbours at a step of a quarter of the kernel's width, halved when none is better, at most
 * REFINE_ROUNDS_ rounds, within the frame; particle ib moves to the best placement found.
 * Returns its rho. A random placement rarely lands where rho reaches rho_acquire (a few px
 * around the target), but often on the target's wider slope: the climb turns those into
 * candidates. */
static pft_real_t search_refine_(pft_tsa_t *t, const frame_ctx_t_ *fc, uint32_t ib,
                                 pft_real_t best)
{
    static const int8_t dx[8] = {1, 1, 0, -1, -1, -1, 0, 1};
    static const int8_t dy[8] = {0, 1, 1, 1, 0, -1, -1, -1};
    int32_t bx = pft_round_int(t->px[ib]);
    int32_t by = pft_round_int(t->py[ib]);
    int32_t step = (t->kern.x1 - t->kern.x0 + 1) / 4;
    step = step < 1 ? 1 : step;
    pft_real_t r_best = best;
    for (uint32_t round = 0; round < REFINE_ROUNDS_; ++round) {
        int32_t nx = bx;
        int32_t ny = by;
        for (uint32_t k = 0; k < 8u; ++k) {
            const int32_t x = bx + (int32_t)dx[k] * step;
            const int32_t y = by + (int32_t)dy[k] * step;
            if (x < 0 || y < 0 || x >= (int32_t)t->cfg.width || y >= (int32_t)t->cfg.height) {
                continue;
            }
            const pft_real_t r = rho_px_(t, fc, x, y);
            if (r > r_best) {
                r_best = r;
                nx = x;
                ny = y;
            }
        }
        if (nx == bx && ny == by) {
            if (step == 1) {
                break;
            }
            step /= 2;
        }
        bx = nx;
        by = ny;
    }
    t->px[ib] = pft_from_int(bx);
    t->py[ib] = pft_from_int(by);
    t->rho[ib] = r_best;
    return r_best;
}

/* acquire_on (with bg_ring): the second similarity of search particle ib (rho best, as the
 * tracker scales it) that must reach rho_acquire: 1, the unweighted template's at gain 1; 2,
 * best unscaled (times rho0). Neither is lifted by the 1 / rho0 scale. */
static pft_real_t acquire_rho_(pft_tsa_t *t, const frame_ctx_t_ *fc, uint32_t ib, pft_real_t best)
{
    if (t->cfg.acquire_on == 2u) {
        return pft_div(best, t->qg_scale[t->gsel]);
    }
    pft_tsa_view_hist_(&fc->v, &t->kern, t->spans, t->n_spans, t->kw, pft_round_int(t->px[ib]),
                       pft_round_int(t->py[ib]), &t->h, t->jb);
    return pft_tsa_rho_hist_(&t->h, &t->qp, &t->qp_root);
}

/* A frame of the search (SEARCH or CONFIRM): the estimate stays at the last good position; the
 * best particle, when it reaches rho_min, climbs to its local best (search_refine_); a
 * candidate with rho >= rho_acquire moves SEARCH to CONFIRM, and a confirmation re-acquires
 * (returns true: the caller weighs the particles as a tracking frame). */
static bool search_frame_(pft_tsa_t *t, const frame_ctx_t_ *fc, uint32_t M)
{
    pft_real_t best = PFT_C(-1.0);
    uint32_t ib = 0u;
    for (uint32_t i = 0; i < M; ++i) {
        t->rho[i] = rho_at_(t, fc, t->px[i], t->py[i]);
        if (t->rho[i] > best) {
            best = t->rho[i];
            ib = i;
        }
    }
    if (best >= t->cfg.rho_min) {
        best = search_refine_(t, fc, ib, best);
    }
    bool found = best >= t->cfg.rho_acquire && best >= t->cfg.rho_min;
    if (found && t->cfg.acquire_on != 0u && t->cfg.bg_ring > PFT_REAL_ONE) {
        found = acquire_rho_(t, fc, ib, best) >= t->cfg.rho_acquire;
    }
    if (found && t->mode == PFT_TSA_MODE_CONFIRM) {
        return true;
    }
    t->mode = found ? PFT_TSA_MODE_CONFIRM : PFT_TSA_MODE_SEARCH;
    if (found) {
        t->cand_x = t->px[ib];
        t->cand_y = t->py[ib];
    }
    for (uint32_t i = 0; i < M; ++i) {
        t->w[i] = weight_on_rho_scale_(PFT_REAL_ONE);
    }
    return false;
}

/* Enters the search at the last good position (the estimate of the previous frame). */
static void search_enter_(pft_tsa_t *t)
{
    t->mode = PFT_TSA_MODE_SEARCH;
    t->weak_run = 0u;
}

/* The state and estimate of a frame without a particle kept (loss_search). */
static pft_tsa_state_t search_report_(pft_tsa_t *t, uint32_t M)
{
    ++t->weak_run;
    t->est.x = t->good_x;
    t->est.y = t->good_y;
    t->est.vx = PFT_C(0.0);
    t->est.vy = PFT_C(0.0);
    t->est.pioneer_x = t->good_x;
    t->est.pioneer_y = t->good_y;
    t->est.pioneer_vx = PFT_C(0.0);
    t->est.pioneer_vy = PFT_C(0.0);
    for (uint32_t i = 0; i < M; ++i) {
        t->w[i] = weight_on_rho_scale_(PFT_REAL_ONE);
    }
    return t->weak_run >= t->cfg.lost_frames ? PFT_TSA_LOST : PFT_TSA_WEAK;
}

/* ------------------------------------------ update ---------------------------------------- */

/* gain_select: the template of the bank that matches the histogram at the prior mean (this
 * frame's prediction) best is this frame's; the camera's gain changes from frame to frame and
 * moves whole bins (docs/results/tsa_ak.md, "gain flicker"). Reads the histograms directly and
 * leaves the prior mean's rho under the chosen gain in the similarity cache. */
static void gain_select_(pft_tsa_t *t, const frame_ctx_t_ *fc)
{
    t->gsel = GAIN_UNITY_;
    if (!t->cfg.gain_select) {
        return;
    }
    const int32_t x = pft_round_int(pft_clamp(t->prior_x, fc->lo_x, fc->hi_x));
    const int32_t y = pft_round_int(pft_clamp(t->prior_y, fc->lo_y, fc->hi_y));
    /* the gain is chosen jointly with the position: at the prior mean and at GAIN_PROBES_ - 1
     * placements a quarter of the kernel's width / height away from it on each axis. At the
     * prior mean alone a prediction a few px off the target chose a darker gain whose template
     * matches the off-target placement best (background in the kernel), and the particles
     * weighed with it held the estimate there (docs/results/tsa_ak.md, branch tsa11) */
    const int32_t sx = probe_dx_(t);
    const int32_t sy = probe_dy_(t);
    const int32_t ox[GAIN_PROBES_] = {0, sx, -sx, 0, 0};
    const int32_t oy[GAIN_PROBES_] = {0, 0, 0, sy, -sy};
    pft_real_t best_unity = PFT_C(-1.0);
    pft_real_t best = PFT_C(-1.0);
    uint32_t gbest = GAIN_UNITY_;
    pft_real_t r0[PFT_TSA_GAINS_]; /* at the prior mean, for the similarity cache */
    for (uint32_t p = 0; p < GAIN_PROBES_; ++p) {
        pft_tsa_view_hist_(&fc->v, &t->kern, t->spans, t->n_spans, t->kw, x + ox[p], y + oy[p],
                           &t->h, t->jb);
        pft_real_t rg[PFT_TSA_GAINS_];
        pft_tsa_rho_bank_(&t->h, t->qg, t->qg_root, PFT_TSA_GAINS_, rg);
        for (uint32_t g = 0; g < PFT_TSA_GAINS_; ++g) {
            const pft_real_t r = rho_scaled_(t, g, rg[g]);
            if (p == 0u) {
                r0[g] = r;
            }
            if (g == GAIN_UNITY_) {
                best_unity = pft_max(best_unity, r);
            } else if (r > best) {
                best = r;
                gbest = g;
            } else {
                /* not better than the other gains' best so far */
            }
        }
    }
    /* another gain only when it matches better and reaches rho_min (the prediction on the
     * target): at a prediction off the target (a sudden reversal) the choice among templates
     * that all match badly only added noise (TS lost tests/unit/test_tsa_reversal.c's
     * reversal in 3 of 8 seeds, q16) */
    if (best > best_unity && best >= t->cfg.rho_min) {
        t->gsel = gbest;
    }
    /* particles often land on the prior mean's pixel: its rho under the chosen gain is known */
    rho_put_(t, x, y, r0[t->gsel]);
}

/* A tracking frame: resample, fit, propagate, weigh; returns the weighing's result. */
static weigh_out_t_ track_frame_(pft_tsa_t *t, frame_ctx_t_ *fc, uint32_t N, uint32_t M,
                                 pft_real_t beta_used, pft_tsa_motion_fit_t *fx,
                                 pft_tsa_motion_fit_t *fy)
{
    resample_(t, N, M);
    conservative_fit_(t, fx, fy);
    propagate_(t, fc, N, beta_used, fx, fy);
    frame_prepare_(t, fc, M, t->cfg.gain_select);
    gain_select_(t, fc);
    return weigh_(t, fc, N, M);
}

/* Lost frames (a seq gap of periods + 1, tracking mode): per lost frame the conservative fit,
 * the propagation of the free model (its noise widens the cloud) and the fit's prediction as
 * the frame's reference point (weighted as the last estimate). */
static void coast_(pft_tsa_t *t, const frame_ctx_t_ *fc, uint32_t N, pft_real_t beta,
                   uint32_t periods)
{
    for (uint32_t i = 0; i < periods; ++i) {
        pft_tsa_motion_fit_t fx;
        pft_tsa_motion_fit_t fy;
        conservative_fit_(t, &fx, &fy);
        propagate_(t, fc, N, beta, &fx, &fy);
        if (t->cfg.motion != PFT_TSA_MOTION_NCV) {
            ref_push_(t, fx.x_pred, fy.x_pred, t->est.rho);
        }
    }
}

pft_status_t pft_tsa_update(pft_tsa_t *t, const pft_frame_t *frame)
{
    if (t == NULL || t->px == NULL) {
        return PFT_ERR_INVAL;
    }
    if (!t->started) {
        return PFT_ERR_STATE;
    }
    pft_status_t st = pft_frame_check(frame, t->cfg.width, t->cfg.height, PFT_TSA_FMT_MASK_);
    uint32_t gap = 1u;
    if (st == PFT_OK) {
        st = pft_seq_gap_(t->cfg.seq_mode, t->cfg.max_gap, true, t->est.last_seq, frame->seq,
                          &gap);
    }
    if (st != PFT_OK) {
        return st;
    }
    const uint32_t N = t->cfg.n_particles;
    const uint32_t M = t->n_state;
    const bool tsa = t->cfg.motion == PFT_TSA_MOTION_TSA;
    frame_ctx_t_ fc;
    pft_tsa_view_init_(&fc.v, frame);
    position_box_(t, &fc);
    pft_tsa_motion_fit_t fx;
    pft_tsa_motion_fit_t fy;
    memset(&fx, 0, sizeof(fx));
    memset(&fy, 0, sizeof(fy));
    const pft_real_t beta_used =
        t->cfg.motion == PFT_TSA_MOTION_NCV ? PFT_C(0.0) : (tsa ? t->beta : t->cfg.beta0);
    if (gap == 0u && t->cfg.loss_search && t->mode == PFT_TSA_MODE_TRACK) {
        search_enter_(t); /* a gap above max_gap: search from the last good position */
    } else if (gap != 1u && t->mode == PFT_TSA_MODE_TRACK) {
        coast_(t, &fc, N, beta_used, gap == 0u ? (uint32_t)t->cfg.max_gap - 1u : gap - 1u);
    } else {
        /* consecutive frames, or searching: the search grows per frame as it is */
    }
    t->est.gap = t->cfg.seq_mode == PFT_SEQ_USE ? frame->seq - t->est.last_seq : 1u;
    t->est.last_seq = frame->seq;
    t->est.last_timestamp_us = frame->timestamp_us;
    weigh_out_t_ wo;
    bool reacquired = false;
    if (t->mode == PFT_TSA_MODE_TRACK) {
        wo = track_frame_(t, &fc, N, M, beta_used, &fx, &fy);
    } else {
        t->gsel = GAIN_UNITY_;
        search_place_(t, M);
        frame_prepare_(t, &fc, M, false);
        reacquired = search_frame_(t, &fc, M);
        if (reacquired) {
            /* weigh the confirmation's particles as a tracking frame */
            wo = weigh_(t, &fc, N, M);
        } else {
            wo.state = PFT_TSA_WEAK;
            wo.alive = 0u;
            wo.any_alive = false;
            wo.rho_p = PFT_C(0.0);
        }
    }
    t->est.beta = beta_used;
    t->est.frame += 1u;
    t->est.template_updated = false;
    t->est.snake_passes = 0u;
    t->est.fit_order = fx.order;
    t->est.n_alive = wo.alive;
    pft_real_t rho_e;
    if (t->cfg.loss_search && !wo.any_alive) {
        /* nothing kept: no extrapolation, the estimate stays at the last good position */
        if (t->mode == PFT_TSA_MODE_TRACK) {
            search_enter_(t);
        }
        const pft_tsa_state_t s = search_report_(t, M);
        rho_e = rho_at_(t, &fc, t->est.x, t->est.y);
        t->est.rho = rho_e;
        t->est.rho_pioneer = rho_e;
        t->est.beta_next = t->beta;
        t->est.ref_is_estimate = true;
        t->est.state = track_state_(t, frame, s, rho_e);
        contour_box_(t, pft_round_int(t->est.x), pft_round_int(t->est.y));
        return PFT_OK;
    }
    estimate_(t, M, &fx, &fy);
    if (reacquired) {
        /* tracking restarts at the confirmed position, moving as from the candidate */
        const pft_real_t vx = pft_sub(t->est.x, t->cand_x);
        const pft_real_t vy = pft_sub(t->est.y, t->cand_y);
        ref_restart_(t, t->cand_x, t->cand_y);
        for (uint32_t i = 0; i < M; ++i) {
            t->pvx[i] = vx;
            t->pvy[i] = vy;
        }
        t->est.vx = vx;
        t->est.vy = vy;
        t->est.pioneer_x = t->est.x;
        t->est.pioneer_y = t->est.y;
        t->beta = t->cfg.motion == PFT_TSA_MOTION_NCV ? PFT_C(0.0) : t->cfg.beta0;
        t->mode = PFT_TSA_MODE_TRACK;
        t->weak_run = 0u;
        wo.rho_p = PFT_C(0.0);
    }
    rho_e = rho_at_(t, &fc, t->est.x, t->est.y);
    if (reacquired) {
        ref_push_(t, t->est.x, t->est.y, rho_e);
        t->est.ref_is_estimate = true;
    } else {
        next_reference_(t, N, rho_e, wo.rho_p);
    }
    t->est.beta_next = tsa ? t->beta : beta_used;
    t->est.rho = rho_e;
    t->est.rho_pioneer = tsa && !reacquired ? wo.rho_p : rho_e;
    t->est.state = track_state_(t, frame, reacquired ? PFT_TSA_REACQUIRED : wo.state, rho_e);
    t->good_x = t->est.x;
    t->good_y = t->est.y;
    /* the innovation: how far the frame moved the cloud from its prior mean; after a
     * re-acquisition the motion is barely known: the widest spread */
    if (reacquired) {
        t->res_x = t->cfg.spread_gain > PFT_C(0.0) ? pft_div(t->cfg.spread_max, t->cfg.spread_gain)
                                                   : PFT_C(0.0);
        t->res_y = t->res_x;
    } else {
        t->res_x = pft_sub(t->est.x, t->prior_x);
        t->res_y = pft_sub(t->est.y, t->prior_y);
    }
    /* only on a trustworthy estimate, rho >= update_rho_min [A] */
    if (rho_e < t->cfg.theta_u && rho_e >= t->cfg.update_rho_min &&
        t->est.state != PFT_TSA_OUT_OF_VIEW) {
        template_update_(t, frame, rho_e);
    }
    contour_box_(t, pft_round_int(t->est.x), pft_round_int(t->est.y));
    return PFT_OK;
}

/* ----------------------------------------- results ---------------------------------------- */

pft_status_t pft_tsa_estimate(const pft_tsa_t *t, pft_tsa_estimate_t *out)
{
    if (t == NULL || out == NULL) {
        return PFT_ERR_INVAL;
    }
    *out = t->est;
    /* bg_ring scales the similarities the tracker uses by 1 / rho0 (rho_scaled_): reported at
     * most 1, as the coefficient itself */
    out->rho = pft_min(out->rho, PFT_REAL_ONE);
    out->rho_pioneer = pft_min(out->rho_pioneer, PFT_REAL_ONE);
    return PFT_OK;
}

size_t pft_tsa_particles(const pft_tsa_t *t, pft_tsa_particle_t *out, size_t max)
{
    if (t == NULL || !t->started) {
        return 0u;
    }
    const size_t n = t->n_state;
    if (out != NULL) {
        const size_t m = n < max ? n : max;
        for (size_t i = 0; i < m; ++i) {
            out[i].x = t->px[i];
            out[i].y = t->py[i];
            out[i].rho = t->rho[i]; /* as weighed: with bg_ring scaled, up to 16 */
        }
    }
    return n;
}

size_t pft_tsa_contour(const pft_tsa_t *t, pft_tsa_pt_t *out, size_t max)
{
    if (t == NULL || !t->started) {
        return 0u;
    }
    const size_t n = t->cfg.snake_points;
    if (out != NULL) {
        const size_t m = n < max ? n : max;
        const int32_t cx = pft_round_int(t->est.x);
        const int32_t cy = pft_round_int(t->est.y);
        for (size_t i = 0; i < m; ++i) {
            out[i].x = (int16_t)(t->contour[i].x + cx);
            out[i].y = (int16_t)(t->contour[i].y + cy);
        }
    }
    return n;
}

pft_status_t pft_tsa_template(const pft_tsa_t *t, pft_tsa_hist_t *out)
{
    if (t == NULL || out == NULL) {
        return PFT_ERR_INVAL;
    }
    if (!t->started) {
        return PFT_ERR_STATE;
    }
    *out = t->q;
    return PFT_OK;
}

pft_status_t pft_tsa_kernel(const pft_tsa_t *t, pft_tsa_kernel_t *out)
{
    if (t == NULL || out == NULL || (out->pix == NULL && out->cap > 0u)) {
        return PFT_ERR_INVAL;
    }
    if (!t->started) {
        return PFT_ERR_STATE;
    }
    if (out->cap < t->kern.n) {
        return PFT_ERR_NOMEM;
    }
    memcpy(out->pix, t->kern.pix, (size_t)t->kern.n * sizeof(pft_tsa_kpix_t));
    out->n = t->kern.n;
    out->sum = t->kern.sum;
    out->x0 = t->kern.x0;
    out->y0 = t->kern.y0;
    out->x1 = t->kern.x1;
    out->y1 = t->kern.y1;
    return PFT_OK;
}
