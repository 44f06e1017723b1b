/*
 * The TSA-AK particle filter (ALGORITHMS.md 4.4) and its NCV / TS baselines: resampling,
 * conservative fit and pioneer, free-model propagation, kernel-histogram weights with the
 * rho_min discard, estimate, beta adaptation and reference-point rule, template update with
 * bounded snake passes.
 */
#include <string.h>

#include "pft/pft_resample.h"
#include "tsa_int.h"

void pft_tsa_config_default(pft_tsa_config_t *cfg, uint16_t width, uint16_t height)
{
    if (cfg == NULL) {
        return;
    }
    memset(cfg, 0, sizeof *cfg);
    cfg->width = width;
    cfg->height = height;
    cfg->max_target_w = 64u;
    cfg->max_target_h = 64u;
    cfg->n_particles = 100u;
    cfg->motion = PFT_TSA_MOTION_TSA;
    cfg->beta0 = PFT_C(2.0);
    cfg->beta_max = PFT_C(6.0);
    cfg->q = PFT_C(4.07);
    cfg->pos_sd = PFT_C(2.0);
    cfg->fit_k = 10u;
    cfg->fit_sigma = PFT_C(5.0);
    cfg->fit_rho_weights = false;
    cfg->fit_a_max = PFT_C(0.5);
    cfg->fit_v_max = PFT_C(12.0);
    cfg->rho_min = PFT_C(0.75);
    cfg->lik_lambda = PFT_C(300.0);
    cfg->theta_u = PFT_C(0.9);
    cfg->update_rho_min = PFT_C(0.85);
    cfg->anchor_rho_min = PFT_C(0.8);
    cfg->k_s = PFT_C(1.5);
    cfg->update_max_passes = 3u;
    cfg->init_passes = 50u;
    cfg->snake_points = 40u;
    pft_tsa_snake_params_default(&cfg->snake, cfg->max_target_w, cfg->max_target_h);
    cfg->kernel_c = PFT_C(1.0);
    cfg->max_area_change = PFT_C(2.0);
    cfg->lost_frames = 10u;
    cfg->seed = 1u;
}

pft_status_t pft_tsa_config_check(const pft_tsa_config_t *c)
{
    if (c == NULL) {
        return PFT_ERR_INVAL;
    }
    if (c->width < 8u || c->height < 8u || c->width > PFT_CFG_MAX_IMAGE_SIDE ||
        c->height > PFT_CFG_MAX_IMAGE_SIDE || c->max_target_w < 4u || c->max_target_h < 4u ||
        c->max_target_w > PFT_TSA_MAX_SIDE || c->max_target_h > PFT_TSA_MAX_SIDE ||
        c->n_particles == 0u || c->n_particles > 65535u ||
        c->n_particles > PFT_CFG_MAX_PARTICLES - 1u) {
        return PFT_ERR_INVAL;
    }
    if ((unsigned)c->motion > (unsigned)PFT_TSA_MOTION_TSA || !(c->beta0 >= 0) || c->beta0 > PFT_C(64.0) ||
        !(c->beta_max > 0) || c->beta_max > PFT_C(64.0) || !(c->q >= 0) || c->q > PFT_C(10000.0) ||
        !(c->pos_sd >= 0) || c->pos_sd > PFT_C(1000.0) || c->fit_k == 0u ||
        c->fit_k > PFT_TSA_MOTION_MAX_K || !(c->fit_sigma > 0) || !(c->fit_a_max >= 0) ||
        c->fit_a_max > PFT_C(1000.0) || !(c->fit_v_max >= 0) || c->fit_v_max > PFT_C(1000.0)) {
        return PFT_ERR_INVAL;
    }
    if (!(c->rho_min >= 0) || c->rho_min > PFT_REAL_ONE || !(c->lik_lambda >= 0) ||
        c->lik_lambda > PFT_C(1000.0) || !(c->theta_u >= 0) ||
        c->theta_u > PFT_REAL_ONE || !(c->update_rho_min >= 0) || c->update_rho_min > PFT_REAL_ONE ||
        !(c->anchor_rho_min >= 0) || c->anchor_rho_min > PFT_REAL_ONE ||
        !(c->k_s > 0) || c->k_s > PFT_C(100.0) ||
        c->snake_points < PFT_TSA_MIN_POINTS || c->snake.margin < 3u ||
        !(c->kernel_c >= 0) || c->kernel_c > PFT_C(1000.0) || !(c->max_area_change >= PFT_REAL_ONE) ||
        c->max_area_change > PFT_C(1000.0)) {
        return PFT_ERR_INVAL;
    }
    return PFT_OK;
}

size_t pft_tsa_workspace_size(const pft_tsa_config_t *cfg)
{
    if (pft_tsa_config_check(cfg) != PFT_OK) {
        return 0u;
    }
    return PFT_TSA_WORKSPACE_BYTES((size_t)cfg->n_particles, (size_t)cfg->max_target_w,
                                   (size_t)cfg->max_target_h, (size_t)cfg->snake_points,
                                   (size_t)cfg->snake.margin);
}

pft_status_t pft_tsa_init(pft_tsa_t *t, const pft_tsa_config_t *cfg, void *work, size_t work_len)
{
    pft_ws_t ws;
    size_t n1, n, kcap;
    pft_status_t st;
    if (t == NULL || work == NULL) {
        return PFT_ERR_INVAL;
    }
    st = pft_tsa_config_check(cfg);
    if (st != PFT_OK) {
        return st;
    }
    if (work_len < pft_tsa_workspace_size(cfg)) {
        return PFT_ERR_NOMEM;
    }
    memset(t, 0, sizeof *t);
    t->cfg = *cfg;
    t->cfg.snake.max_w = cfg->max_target_w;
    t->cfg.snake.max_h = cfg->max_target_h;
    n = cfg->n_particles;
    n1 = n + 1u;
    kcap = (size_t)cfg->max_target_w * cfg->max_target_h;
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
    t->cross = (int32_t *)pft_ws_take(&ws, (size_t)cfg->snake_points * sizeof(int32_t));
    t->contour = (pft_tsa_pt_t *)pft_ws_take(&ws, (size_t)cfg->snake_points * sizeof(pft_tsa_pt_t));
    t->cwork = (pft_tsa_pt_t *)pft_ws_take(&ws, (size_t)cfg->snake_points * sizeof(pft_tsa_pt_t));
    t->bflags = (uint8_t *)pft_ws_take(&ws, (size_t)cfg->snake_points);
    t->snake_ws_len = pft_tsa_snake_work_size(cfg->max_target_w, cfg->max_target_h, cfg->snake.margin);
    t->snake_ws = pft_ws_take(&ws, t->snake_ws_len);
    st = pft_ws_status(&ws);
    if (st != PFT_OK) {
        memset(t, 0, sizeof *t);
        return st;
    }
    t->kern.cap = (uint32_t)kcap;
    t->kern_alt.cap = (uint32_t)kcap;
    pft_rng_seed(&t->rng, cfg->seed);
    t->est.state = PFT_TSA_IDLE;
    return PFT_OK;
}

static pft_real_t rho_at(pft_tsa_t *t, const pft_frame_t *f, pft_real_t x, pft_real_t y)
{
    if (pft_tsa_hist(f, &t->kern, pft_round_int(x), pft_round_int(y), &t->h) != PFT_OK) {
        return 0;
    }
    return pft_tsa_bhattacharyya(&t->h, &t->q);
}

/* Particle weight from its similarity: rho itself (eq. 22, lik_lambda = 0) or
 * exp(lambda (rho - rho_best)) (lik_lambda > 0), on the scale of rho (q16: at most 2^16, so
 * the 64-bit sums of wmean cannot overflow). */
static pft_weight_t weight_of(const pft_tsa_t *t, pft_real_t rho, pft_real_t rho_best)
{
    if (!(rho > 0)) {
        return 0;
    }
    if (!(t->cfg.lik_lambda > 0)) {
#ifdef PFT_NUMERIC_Q16
        return (pft_weight_t)rho;
#else
        return rho;
#endif
    }
#ifdef PFT_NUMERIC_Q16
    return pft_wexp(pft_mul(t->cfg.lik_lambda, pft_sub(rho, rho_best))) >> 14;
#else
    return pft_wexp(pft_mul(t->cfg.lik_lambda, pft_sub(rho, rho_best)));
#endif
}

/* Weighted mean of v[0..n) with weights w (any scale, sum > 0). */
static pft_real_t wmean(const pft_weight_t *w, const pft_real_t *v, uint32_t n)
{
#ifdef PFT_NUMERIC_Q16
    int64_t num = 0, den = 0, q;
    for (uint32_t i = 0; i < n; ++i) {
        num += (int64_t)w[i] * v[i];
        den += (int64_t)w[i];
    }
    if (den <= 0) {
        return 0;
    }
    q = (num >= 0 ? num + den / 2 : num - den / 2) / den;
    return pft_sat64_(q);
#else
    float num = 0.0f, den = 0.0f;
    for (uint32_t i = 0; i < n; ++i) {
        num += w[i] * v[i];
        den += w[i];
    }
    return den > 0.0f ? num / den : 0.0f;
#endif
}

static void contour_box(pft_tsa_t *t, int32_t cx, int32_t cy)
{
    int32_t x0 = INT16_MAX, x1 = INT16_MIN, y0 = INT16_MAX, y1 = INT16_MIN;
    for (uint32_t i = 0; i < t->cfg.snake_points; ++i) {
        x0 = t->contour[i].x < x0 ? t->contour[i].x : x0;
        x1 = t->contour[i].x > x1 ? t->contour[i].x : x1;
        y0 = t->contour[i].y < y0 ? t->contour[i].y : y0;
        y1 = t->contour[i].y > y1 ? t->contour[i].y : y1;
    }
    t->est.box_x0 = (int16_t)(x0 + cx < -32000 ? -32000 : (x0 + cx > 32000 ? 32000 : x0 + cx));
    t->est.box_x1 = (int16_t)(x1 + cx < -32000 ? -32000 : (x1 + cx > 32000 ? 32000 : x1 + cx));
    t->est.box_y0 = (int16_t)(y0 + cy < -32000 ? -32000 : (y0 + cy > 32000 ? 32000 : y0 + cy));
    t->est.box_y1 = (int16_t)(y1 + cy < -32000 ? -32000 : (y1 + cy > 32000 ? 32000 : y1 + cy));
}

static int64_t abs64(int64_t a) { return a < 0 ? -a : a; }

/* Area change within [1/r, r] and a box within the limits. */
static bool contour_acceptable(const pft_tsa_t *t, const pft_tsa_pt_t *p, int64_t area2_ref)
{
    const int32_t r = pft_round_int(pft_mul_i(t->cfg.max_area_change, 16)); /* Q4 ratio */
    const int64_t a = abs64(pft_tsa_poly_area2(p, t->cfg.snake_points));
    const int64_t b = abs64(area2_ref);
    if (a == 0 || b == 0) {
        return false;
    }
    return a * 16 <= b * r && b * 16 <= a * r;
}

/* Builds kernel and template from cwork (frame coordinates) into the alternate kernel and
 * commits them; returns the new origin. */
static pft_status_t rebuild(pft_tsa_t *t, const pft_frame_t *f, pft_tsa_pt_t *origin, bool anchor)
{
    pft_tsa_hist_t hq;
    pft_tsa_kernel_t tmp;
    pft_status_t st;
    const uint16_t cq4 = (uint16_t)pft_round_int(pft_mul_i(t->cfg.kernel_c, 16));
    st = pft_tsa_kernel_build(&t->kern_alt, t->cwork, t->cfg.snake_points, cq4, t->cross, origin);
    if (st != PFT_OK) {
        return st;
    }
    st = pft_tsa_hist(f, &t->kern_alt, origin->x, origin->y, &hq);
    if (st != PFT_OK) {
        return st;
    }
    if (hq.total == 0u) {
        return PFT_ERR_RANGE;
    }
    if (anchor && t->cfg.anchor_rho_min > 0 &&
        pft_tsa_bhattacharyya(&hq, &t->q0) < t->cfg.anchor_rho_min) {
        return PFT_ERR_RANGE; /* the new template drifted away from the first one */
    }
    tmp = t->kern;
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

pft_status_t pft_tsa_start(pft_tsa_t *t, const pft_frame_t *frame, const pft_tsa_pt_t *poly,
                           uint32_t n)
{
    int32_t xmin = INT32_MAX, xmax = INT32_MIN, ymin = INT32_MAX, ymax = INT32_MIN;
    pft_tsa_pt_t origin;
    pft_status_t st;
    const uint32_t np = t != NULL ? t->cfg.snake_points : 0u;
    int64_t a0;
    pft_real_t ox, oy;

    if (t == NULL || poly == NULL || t->px == NULL || n < 3u || n > 65535u) {
        return PFT_ERR_INVAL;
    }
    st = pft_frame_check(frame, t->cfg.width, t->cfg.height, TSA_FMT_MASK_);
    if (st != PFT_OK) {
        return st;
    }
    a0 = pft_tsa_poly_area2(poly, n);
    if (a0 == 0) {
        return PFT_ERR_INVAL;
    }
    for (uint32_t i = 0; i < n; ++i) {
        xmin = poly[i].x < xmin ? poly[i].x : xmin;
        xmax = poly[i].x > xmax ? poly[i].x : xmax;
        ymin = poly[i].y < ymin ? poly[i].y : ymin;
        ymax = poly[i].y > ymax ? poly[i].y : ymax;
    }
    if (xmin < 0 || ymin < 0 || xmax >= (int32_t)frame->width || ymax >= (int32_t)frame->height ||
        xmax - xmin + 1 > (int32_t)t->cfg.max_target_w || ymax - ymin + 1 > (int32_t)t->cfg.max_target_h) {
        return PFT_ERR_RANGE;
    }
    st = pft_tsa_poly_resample(poly, n, t->cwork, np);
    if (st != PFT_OK) {
        return st;
    }
    if (pft_tsa_poly_area2(t->cwork, np) == 0) {
        return PFT_ERR_INVAL;
    }
    if (t->cfg.init_passes > 0u) {
        /* snake on a copy in contour[] (not yet committed); accept if sane */
        uint32_t done = 0u;
        memcpy(t->contour, t->cwork, np * sizeof(pft_tsa_pt_t));
        st = pft_tsa_snake(frame, t->contour, np, &t->cfg.snake, t->cfg.init_passes, t->bflags,
                           t->snake_ws, t->snake_ws_len, &done);
        if (st == PFT_OK && contour_acceptable(t, t->contour, a0)) {
            memcpy(t->cwork, t->contour, np * sizeof(pft_tsa_pt_t));
        }
        t->est.snake_passes = (uint8_t)(done > 255u ? 255u : done);
    }
    st = rebuild(t, frame, &origin, false);
    if (st != PFT_OK) {
        return st;
    }
    t->q0 = t->q;
    ox = pft_from_int(origin.x);
    oy = pft_from_int(origin.y);
    t->n_state = t->cfg.n_particles + (t->cfg.motion == PFT_TSA_MOTION_TSA ? 1u : 0u);
    for (uint32_t i = 0; i <= t->cfg.n_particles; ++i) {
        t->px[i] = ox;
        t->py[i] = oy;
        t->pvx[i] = 0;
        t->pvy[i] = 0;
        t->rho[i] = PFT_REAL_ONE;
        t->w[i] = PFT_W_ONE;
    }
    t->ref_n = 1u;
    t->ref_x[0] = ox;
    t->ref_y[0] = oy;
    t->ref_w[0] = PFT_REAL_ONE;
    t->beta = t->cfg.motion == PFT_TSA_MOTION_NCV ? 0 : t->cfg.beta0;
    t->weak_run = 0u;
    t->started = true;
    {
        const uint8_t passes = t->est.snake_passes;
        memset(&t->est, 0, sizeof t->est);
        t->est.snake_passes = passes;
    }
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
    contour_box(t, origin.x, origin.y);
    return PFT_OK;
}

/* Template update (eq. 23): contour at the estimate, N_iter snake passes, new kernel and q;
 * the state is shifted by the move of the kernel origin. */
static void template_update(pft_tsa_t *t, const pft_frame_t *f, pft_real_t rho_e)
{
    const uint32_t np = t->cfg.snake_points;
    const int32_t cx = pft_round_int(t->est.x), cy = pft_round_int(t->est.y);
    pft_real_t ratio = pft_div(t->cfg.k_s, pft_max(rho_e, PFT_C(0.01)));
    int32_t passes = pft_floor_int(ratio);
    pft_tsa_pt_t origin;
    uint32_t done = 0u;
    pft_real_t dx, dy;
    if (pft_from_int(passes) < ratio) {
        ++passes; /* ceil */
    }
    if (passes > (int32_t)t->cfg.update_max_passes) {
        passes = (int32_t)t->cfg.update_max_passes;
    }
    for (uint32_t i = 0; i < np; ++i) {
        const int32_t x = t->contour[i].x + cx, y = t->contour[i].y + cy;
        if (x < 1 || y < 1 || x > (int32_t)f->width - 2 || y > (int32_t)f->height - 2) {
            return; /* contour not wholly in view: keep the template */
        }
        t->cwork[i].x = (int16_t)x;
        t->cwork[i].y = (int16_t)y;
    }
    if (passes > 0) {
        if (pft_tsa_snake(f, t->cwork, np, &t->cfg.snake, (uint32_t)passes, t->bflags, t->snake_ws,
                          t->snake_ws_len, &done) != PFT_OK ||
            !contour_acceptable(t, t->cwork, t->area2)) {
            t->est.snake_passes = (uint8_t)done;
            return;
        }
    }
    t->est.snake_passes = (uint8_t)done;
    if (rebuild(t, f, &origin, true) != PFT_OK) {
        return;
    }
    t->est.template_updated = true;
    dx = pft_from_int(origin.x - cx);
    dy = pft_from_int(origin.y - cy);
    if (dx != 0 || dy != 0) {
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
}

pft_status_t pft_tsa_update(pft_tsa_t *t, const pft_frame_t *frame)
{
    const uint32_t N = t != NULL ? t->cfg.n_particles : 0u;
    const uint32_t M = t != NULL ? t->n_state : 0u;
    const bool tsa = t != NULL && t->cfg.motion == PFT_TSA_MOTION_TSA;
    pft_tsa_motion_free_t coef;
    pft_tsa_motion_fit_t fx, fy;
    pft_real_t vbx = 0, vby = 0, rho_e, rho_p = 0, beta_used;
    uint32_t alive = 0u;
    pft_status_t st;
    pft_tsa_state_t state;

    if (t == NULL || t->px == NULL) {
        return PFT_ERR_INVAL;
    }
    if (!t->started) {
        return PFT_ERR_STATE;
    }
    st = pft_frame_check(frame, t->cfg.width, t->cfg.height, TSA_FMT_MASK_);
    if (st != PFT_OK) {
        return st;
    }
    /* 1. resample N from the M weights of the previous frame */
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

    /* 2. conservative fit on the reference points: v_hat and the pioneer */
    memset(&fx, 0, sizeof fx);
    memset(&fy, 0, sizeof fy);
    if (t->cfg.motion != PFT_TSA_MOTION_NCV) {
        const uint8_t order = tsa ? 2u : 1u;
        const pft_real_t *pi = t->cfg.fit_rho_weights ? t->ref_w : NULL;
        if (pft_tsa_motion_fit(t->ref_x, pi, t->ref_n, t->cfg.fit_sigma, order, &fx) != PFT_OK ||
            pft_tsa_motion_fit(t->ref_y, pi, t->ref_n, t->cfg.fit_sigma, order, &fy) != PFT_OK) {
            /* all weights zero: constant position at the newest point */
            (void)pft_tsa_motion_fit(t->ref_x, NULL, t->ref_n, t->cfg.fit_sigma, order, &fx);
            (void)pft_tsa_motion_fit(t->ref_y, NULL, t->ref_n, t->cfg.fit_sigma, order, &fy);
        }
        pft_tsa_motion_fit_bound(&fx, t->cfg.fit_a_max, t->cfg.fit_v_max);
        pft_tsa_motion_fit_bound(&fy, t->cfg.fit_a_max, t->cfg.fit_v_max);
        vbx = fx.v_pred;
        vby = fy.v_pred;
    }
    /* 3. propagate the normal particles with the free model and diffusion */
    beta_used = t->cfg.motion == PFT_TSA_MOTION_NCV ? 0 : (tsa ? t->beta : t->cfg.beta0);
    (void)pft_tsa_motion_free_coef(&coef, beta_used, t->cfg.q);
    for (uint32_t i = 0; i < N; ++i) {
        const pft_real_t g1 = pft_rng_gauss(&t->rng), g2 = pft_rng_gauss(&t->rng);
        const pft_real_t g3 = pft_rng_gauss(&t->rng), g4 = pft_rng_gauss(&t->rng);
        const pft_real_t g5 = pft_rng_gauss(&t->rng), g6 = pft_rng_gauss(&t->rng);
        pft_tsa_motion_free_step(&coef, &t->px[i], &t->pvx[i], vbx, g1, g2);
        pft_tsa_motion_free_step(&coef, &t->py[i], &t->pvy[i], vby, g3, g4);
        t->px[i] = pft_clamp(pft_add(t->px[i], pft_mul(t->cfg.pos_sd, g5)), PFT_C(-16000.0), PFT_C(16000.0));
        t->py[i] = pft_clamp(pft_add(t->py[i], pft_mul(t->cfg.pos_sd, g6)), PFT_C(-16000.0), PFT_C(16000.0));
    }
    if (tsa) {
        t->px[N] = pft_clamp(fx.x_pred, PFT_C(-16000.0), PFT_C(16000.0));
        t->py[N] = pft_clamp(fy.x_pred, PFT_C(-16000.0), PFT_C(16000.0));
        t->pvx[N] = vbx;
        t->pvy[N] = vby;
    }
    /* 4. similarities, discard below rho_min, weights proportional to rho (or exp(lambda rho)) */
    {
        pft_real_t best_alive = 0, best_any = 0;
        for (uint32_t i = 0; i < M; ++i) {
            t->rho[i] = rho_at(t, frame, t->px[i], t->py[i]);
            best_any = pft_max(best_any, t->rho[i]);
            if (t->rho[i] >= t->cfg.rho_min) {
                best_alive = pft_max(best_alive, t->rho[i]);
            }
        }
        for (uint32_t i = 0; i < M; ++i) {
            t->w[i] = t->rho[i] >= t->cfg.rho_min ? weight_of(t, t->rho[i], best_alive) : 0;
            if (i < N && t->w[i] > 0) {
                ++alive;
            }
        }
        if (tsa) {
            rho_p = t->rho[N];
        }
        state = PFT_TSA_TRACKING;
        if (alive == 0u) {
            if (tsa) {
                /* pioneer only: X_hat = X_tilde; the normal particles recover at the resampling */
                for (uint32_t i = 0; i < N; ++i) {
                    t->w[i] = 0;
                }
                t->w[N] = PFT_W_ONE;
                state = rho_p >= t->cfg.rho_min ? PFT_TSA_PIONEER_ONLY : PFT_TSA_WEAK;
            } else {
                bool any = false;
                for (uint32_t i = 0; i < M; ++i) {
                    t->w[i] = weight_of(t, t->rho[i], best_any);
                    any = any || t->w[i] > 0;
                }
                if (!any) {
                    for (uint32_t i = 0; i < M; ++i) {
                        t->w[i] = PFT_W_ONE;
                    }
                }
                state = PFT_TSA_WEAK;
            }
        }
    }
    /* 5. estimate */
    t->est.x = wmean(t->w, t->px, M);
    t->est.y = wmean(t->w, t->py, M);
    t->est.vx = wmean(t->w, t->pvx, M);
    t->est.vy = wmean(t->w, t->pvy, M);
    t->est.pioneer_x = fx.x_pred;
    t->est.pioneer_y = fy.x_pred;
    t->est.pioneer_vx = vbx;
    t->est.pioneer_vy = vby;
    if (t->cfg.motion == PFT_TSA_MOTION_NCV) {
        t->est.pioneer_x = t->est.x;
        t->est.pioneer_y = t->est.y;
    }
    /* 6. beta and the reference point */
    rho_e = rho_at(t, frame, t->est.x, t->est.y);
    t->est.beta = beta_used;
    t->est.ref_is_estimate = true;
    {
        pft_real_t ox = t->est.x, oy = t->est.y, ow = rho_e;
        if (tsa) {
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
    t->est.beta_next = tsa ? t->beta : beta_used;
    t->est.rho = rho_e;
    t->est.rho_pioneer = tsa ? rho_p : rho_e;
    t->est.n_alive = alive;
    t->est.fit_order = fx.order;
    t->est.frame += 1u;
    t->est.template_updated = false;
    t->est.snake_passes = 0u;
    /* lost bookkeeping */
    if (rho_e < t->cfg.rho_min) {
        ++t->weak_run;
    } else {
        t->weak_run = 0u;
    }
    if (t->weak_run >= t->cfg.lost_frames && t->cfg.lost_frames > 0u) {
        state = PFT_TSA_LOST;
    }
    {
        const int32_t cx = pft_round_int(t->est.x), cy = pft_round_int(t->est.y);
        if (cx < 0 || cy < 0 || cx >= (int32_t)frame->width || cy >= (int32_t)frame->height) {
            state = PFT_TSA_OUT_OF_VIEW;
        }
    }
    t->est.state = state;
    /* 7. template update (only on a trustworthy estimate, rho >= update_rho_min [A]) */
    if (rho_e < t->cfg.theta_u && rho_e >= t->cfg.update_rho_min && state != PFT_TSA_OUT_OF_VIEW) {
        template_update(t, frame, rho_e);
    }
    contour_box(t, pft_round_int(t->est.x), pft_round_int(t->est.y));
    return PFT_OK;
}

const pft_tsa_estimate_t *pft_tsa_estimate(const pft_tsa_t *t)
{
    return t != NULL ? &t->est : NULL;
}

uint32_t pft_tsa_contour(const pft_tsa_t *t, pft_tsa_pt_t *out, uint32_t max)
{
    uint32_t n;
    int32_t cx, cy;
    if (t == NULL || out == NULL || !t->started) {
        return 0u;
    }
    n = t->cfg.snake_points < max ? t->cfg.snake_points : max;
    cx = pft_round_int(t->est.x);
    cy = pft_round_int(t->est.y);
    for (uint32_t i = 0; i < n; ++i) {
        out[i].x = (int16_t)(t->contour[i].x + cx);
        out[i].y = (int16_t)(t->contour[i].y + cy);
    }
    return n;
}

uint32_t pft_tsa_particles(const pft_tsa_t *t, const pft_real_t **x, const pft_real_t **y,
                           const pft_real_t **rho)
{
    if (t == NULL || !t->started) {
        return 0u;
    }
    if (x != NULL) {
        *x = t->px;
    }
    if (y != NULL) {
        *y = t->py;
    }
    if (rho != NULL) {
        *rho = t->rho;
    }
    return t->n_state;
}

const pft_tsa_hist_t *pft_tsa_template(const pft_tsa_t *t) { return t != NULL ? &t->q : NULL; }
const pft_tsa_kernel_t *pft_tsa_kernel(const pft_tsa_t *t) { return t != NULL ? &t->kern : NULL; }
