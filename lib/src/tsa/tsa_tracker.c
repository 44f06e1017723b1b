/*
 * The TSA-AK particle filter (docs/algorithms.md 4.4) and its NCV / TS baselines: resampling,
 * conservative fit and pioneer, free-model propagation, kernel-histogram weights with the
 * rho_min discard, estimate, beta adaptation and reference-point rule, template update with
 * bounded snake passes.
 */
#include <string.h>

#include "pft/pft_resample.h"
#include "../core/acc_int.h"
#include "tsa_int.h"

/* Particles are kept within +-POS_LIMIT_ px: positions and their differences stay far inside
 * the Q16.16 range (32768). */
#define POS_LIMIT_ PFT_C(16000.0)
/* The reported contour box is clamped to +-BOX_LIMIT_ px (int16 fields). */
#define BOX_LIMIT_ 32000
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
    st = pft_ws_status(&ws);
    if (st != PFT_OK) {
        memset(t, 0, sizeof(*t));
        return st;
    }
    t->kern.cap = (uint32_t)kcap;
    t->kern_alt.cap = (uint32_t)kcap;
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

/* Similarity of the template to the kernel placed at (x, y), in the scratch histogram. */
static pft_real_t rho_at_(pft_tsa_t *t, const pft_frame_t *f, pft_real_t x, pft_real_t y)
{
    if (pft_tsa_hist(f, &t->kern, pft_round_int(x), pft_round_int(y), &t->h) != PFT_OK) {
        return PFT_C(0.0);
    }
    return pft_tsa_bhattacharyya(&t->h, &t->q);
}

/* A real >= 0 stored in a weight with the same bits: q16 keeps the Q16.16 value (a weight
 * 2^-14 of its Q2.30 scale), float the value. Weights are only compared and normalised, and on
 * this scale (at most 2^16 per particle) the 64-bit sums of the weighted mean cannot overflow. */
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

/* Area change within [1/r, r] (r = max_area_change, Q4) and a nonzero area. */
static bool contour_acceptable_(const pft_tsa_t *t, const pft_tsa_pt_t *p, int64_t area2_ref)
{
    const int32_t r = pft_round_int(pft_mul_i(t->cfg.max_area_change, 16));
    const int64_t a = abs64_(pft_tsa_poly_area2(p, t->cfg.snake_points));
    const int64_t b = abs64_(area2_ref);
    if (a == 0 || b == 0) {
        return false;
    }
    return a * 16 <= b * r && b * 16 <= a * r;
}

/* Builds kernel and template from cwork (frame coordinates) into the alternate kernel and
 * commits them (kernel, template, contour, area); returns the new origin. On an error
 * nothing is committed: PFT_ERR_DEGENERATE for an empty kernel or template, PFT_ERR_LOST when
 * anchor is set and the new template drifted away from the first one. */
static pft_status_t rebuild_(pft_tsa_t *t, const pft_frame_t *f, pft_tsa_pt_t *origin, bool anchor)
{
    const uint16_t cq4 = (uint16_t)pft_round_int(pft_mul_i(t->cfg.kernel_c, 16));
    pft_status_t st =
        pft_tsa_kernel_build(&t->kern_alt, t->cwork, t->cfg.snake_points, cq4, t->cross, origin);
    if (st != PFT_OK) {
        return st;
    }
    pft_tsa_hist_t hq;
    st = pft_tsa_hist(f, &t->kern_alt, origin->x, origin->y, &hq);
    if (st != PFT_OK) {
        return st;
    }
    if (hq.total == 0u) {
        return PFT_ERR_DEGENERATE;
    }
    if (anchor && t->cfg.anchor_rho_min > PFT_C(0.0) &&
        pft_tsa_bhattacharyya(&hq, &t->q0) < t->cfg.anchor_rho_min) {
        return PFT_ERR_LOST;
    }
    const pft_tsa_kernel_t tmp = t->kern;
    t->kern = t->kern_alt;
    t->kern_alt = tmp;
    t->q = hq;
    for (uint32_t i = 0; i < t->cfg.snake_points; ++i) {
        t->contour[i].x = (int16_t)(t->cwork[i].x - origin->x);
        t->contour[i].y = (int16_t)(t->cwork[i].y - origin->y);
    }
    t->area2 = pft_tsa_poly_area2(t->cwork, t->cfg.snake_points);
    return PFT_OK;
}

/* ----------------------------------------- start ------------------------------------------ */

/* The initial contour in cwork: poly resampled to snake_points points, refined by init_passes
 * snake passes when the result is acceptable (else the resampled polygon again). Returns the
 * passes run, or -1 for a resampled polygon of zero area. */
static int32_t initial_contour_(pft_tsa_t *t, const pft_frame_t *frame, const pft_tsa_pt_t *poly,
                                uint32_t n, int64_t area2)
{
    const uint32_t np = t->cfg.snake_points;
    (void)pft_tsa_poly_resample(poly, n, t->cwork, np); /* poly checked: n >= 3, nonzero area */
    if (pft_tsa_poly_area2(t->cwork, np) == 0) {
        return -1;
    }
    if (t->cfg.init_passes == 0u) {
        return 0;
    }
    uint32_t done = 0u;
    const pft_status_t st = pft_tsa_snake(frame, t->cwork, np, &t->cfg.snake, t->cfg.init_passes,
                                          t->bflags, t->snake_ws, t->snake_ws_len, &done);
    if (st != PFT_OK || !contour_acceptable_(t, t->cwork, area2)) {
        (void)pft_tsa_poly_resample(poly, n, t->cwork, np);
    }
    return (int32_t)(done > 255u ? 255u : done);
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
    t->ref_n = 1u;
    t->ref_x[0] = x;
    t->ref_y[0] = y;
    t->ref_w[0] = PFT_REAL_ONE;
    t->beta = t->cfg.motion == PFT_TSA_MOTION_NCV ? PFT_C(0.0) : t->cfg.beta0;
    t->weak_run = 0u;
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
    const int32_t passes = initial_contour_(t, frame, poly, n, a0);
    if (passes < 0) {
        return PFT_ERR_DEGENERATE;
    }
    pft_tsa_pt_t origin;
    st = rebuild_(t, frame, &origin, false);
    if (st != PFT_OK) {
        return st;
    }
    t->q0 = t->q;
    const pft_real_t ox = pft_from_int(origin.x);
    const pft_real_t oy = pft_from_int(origin.y);
    place_particles_(t, ox, oy);
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

/* Step 3: the N normal particles through the free model at beta with the input (vbx, vby) and
 * the extra position diffusion; TSA's pioneer at the fit's prediction. */
static void propagate_(pft_tsa_t *t, uint32_t N, pft_real_t beta, const pft_tsa_motion_fit_t *fx,
                       const pft_tsa_motion_fit_t *fy)
{
    pft_tsa_motion_free_t coef;
    (void)pft_tsa_motion_free_coef(&coef, beta, t->cfg.q); /* beta and q checked by the config */
    const pft_real_t vbx = fx->v_pred;
    const pft_real_t vby = fy->v_pred;
    for (uint32_t i = 0; i < N; ++i) {
        const pft_real_t g1 = pft_rng_gauss(&t->rng);
        const pft_real_t g2 = pft_rng_gauss(&t->rng);
        const pft_real_t g3 = pft_rng_gauss(&t->rng);
        const pft_real_t g4 = pft_rng_gauss(&t->rng);
        const pft_real_t g5 = pft_rng_gauss(&t->rng);
        const pft_real_t g6 = pft_rng_gauss(&t->rng);
        pft_tsa_motion_free_step(&coef, &t->px[i], &t->pvx[i], vbx, g1, g2);
        pft_tsa_motion_free_step(&coef, &t->py[i], &t->pvy[i], vby, g3, g4);
        t->px[i] = pft_clamp(pft_add(t->px[i], pft_mul(t->cfg.pos_sd, g5)), pft_neg(POS_LIMIT_),
                             POS_LIMIT_);
        t->py[i] = pft_clamp(pft_add(t->py[i], pft_mul(t->cfg.pos_sd, g6)), pft_neg(POS_LIMIT_),
                             POS_LIMIT_);
    }
    if (t->cfg.motion == PFT_TSA_MOTION_TSA) {
        t->px[N] = pft_clamp(fx->x_pred, pft_neg(POS_LIMIT_), POS_LIMIT_);
        t->py[N] = pft_clamp(fy->x_pred, pft_neg(POS_LIMIT_), POS_LIMIT_);
        t->pvx[N] = vbx;
        t->pvy[N] = vby;
    }
}

/* What step 4 found. */
typedef struct {
    pft_tsa_state_t state;
    uint32_t alive;   /* normal particles with rho >= rho_min */
    pft_real_t rho_p; /* the pioneer's rho (TSA; else 0) */
} weigh_out_t_;

/* Step 4 when no normal particle is alive: TSA lets the pioneer carry the frame (X_hat =
 * X_tilde; the normal particles recover at the resampling); NCV / TS weigh every particle
 * relative to the best (uniformly when all are zero). */
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
            t->w[i] = PFT_W_ONE;
        }
    }
    return PFT_TSA_WEAK;
}

/* Step 4: similarities, particles below rho_min discarded, weights from rho (eq. 22 or the
 * exponential weighting). */
static weigh_out_t_ weigh_(pft_tsa_t *t, const pft_frame_t *frame, uint32_t N, uint32_t M)
{
    pft_real_t best_alive = PFT_C(0.0);
    pft_real_t best_any = PFT_C(0.0);
    for (uint32_t i = 0; i < M; ++i) {
        t->rho[i] = rho_at_(t, frame, t->px[i], t->py[i]);
        best_any = pft_max(best_any, t->rho[i]);
        if (t->rho[i] >= t->cfg.rho_min) {
            best_alive = pft_max(best_alive, t->rho[i]);
        }
    }
    weigh_out_t_ r;
    r.alive = 0u;
    for (uint32_t i = 0; i < M; ++i) {
        t->w[i] = t->rho[i] >= t->cfg.rho_min ? weight_of_(t, t->rho[i], best_alive) : 0;
        if (i < N && t->w[i] > 0) {
            ++r.alive;
        }
    }
    r.rho_p = t->cfg.motion == PFT_TSA_MOTION_TSA ? t->rho[N] : PFT_C(0.0);
    r.state = r.alive == 0u ? weigh_fallback_(t, N, M, best_any, r.rho_p) : PFT_TSA_TRACKING;
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
    if (t->ref_n == t->cfg.fit_k) {
        memmove(&t->ref_x[0], &t->ref_x[1], (t->ref_n - 1u) * sizeof(pft_real_t));
        memmove(&t->ref_y[0], &t->ref_y[1], (t->ref_n - 1u) * sizeof(pft_real_t));
        memmove(&t->ref_w[0], &t->ref_w[1], (t->ref_n - 1u) * sizeof(pft_real_t));
        --t->ref_n;
    }
    t->ref_x[t->ref_n] = ox;
    t->ref_y[t->ref_n] = oy;
    t->ref_w[t->ref_n] = ow;
    ++t->ref_n;
}

/* Lost and out-of-view bookkeeping on top of the weighing's state. */
static pft_tsa_state_t track_state_(pft_tsa_t *t, const pft_frame_t *frame, pft_tsa_state_t state,
                                    pft_real_t rho_e)
{
    if (rho_e < t->cfg.rho_min) {
        ++t->weak_run;
    } else {
        t->weak_run = 0u;
    }
    if (t->weak_run >= t->cfg.lost_frames && t->cfg.lost_frames > 0u) {
        state = PFT_TSA_LOST;
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
            return;
        }
    }
    t->est.snake_passes = (uint8_t)done;
    pft_tsa_pt_t origin;
    if (rebuild_(t, f, &origin, true) != PFT_OK) {
        return;
    }
    t->est.template_updated = true;
    const pft_real_t dx = pft_from_int(origin.x - cx);
    const pft_real_t dy = pft_from_int(origin.y - cy);
    if (dx != PFT_C(0.0) || dy != PFT_C(0.0)) {
        shift_state_(t, dx, dy);
    }
}

/* ------------------------------------------ update ---------------------------------------- */

pft_status_t pft_tsa_update(pft_tsa_t *t, const pft_frame_t *frame)
{
    if (t == NULL || t->px == NULL) {
        return PFT_ERR_INVAL;
    }
    if (!t->started) {
        return PFT_ERR_STATE;
    }
    const pft_status_t st = pft_frame_check(frame, t->cfg.width, t->cfg.height, PFT_TSA_FMT_MASK_);
    if (st != PFT_OK) {
        return st;
    }
    const uint32_t N = t->cfg.n_particles;
    const uint32_t M = t->n_state;
    const bool tsa = t->cfg.motion == PFT_TSA_MOTION_TSA;
    resample_(t, N, M);
    pft_tsa_motion_fit_t fx;
    pft_tsa_motion_fit_t fy;
    conservative_fit_(t, &fx, &fy);
    const pft_real_t beta_used =
        t->cfg.motion == PFT_TSA_MOTION_NCV ? PFT_C(0.0) : (tsa ? t->beta : t->cfg.beta0);
    propagate_(t, N, beta_used, &fx, &fy);
    const weigh_out_t_ wo = weigh_(t, frame, N, M);
    estimate_(t, M, &fx, &fy);
    const pft_real_t rho_e = rho_at_(t, frame, t->est.x, t->est.y);
    t->est.beta = beta_used;
    next_reference_(t, N, rho_e, wo.rho_p);
    t->est.beta_next = tsa ? t->beta : beta_used;
    t->est.rho = rho_e;
    t->est.rho_pioneer = tsa ? wo.rho_p : rho_e;
    t->est.n_alive = wo.alive;
    t->est.fit_order = fx.order;
    t->est.frame += 1u;
    t->est.template_updated = false;
    t->est.snake_passes = 0u;
    t->est.state = track_state_(t, frame, wo.state, rho_e);
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
            out[i].rho = t->rho[i];
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
