/* The TBD pixel likelihood (pft_tbd.h, docs/algorithms.md 1 and 2.9) as a model of the
 * particle-filter engine: with SIR it is the bootstrap PF-TBD, with the APF the APF-TBD.
 * Everything but the engine is the tbd module's, called through its private header: the
 * measurement model, frame conversion and birth candidates, and the PF-TBD existence chain,
 * births, CV step, leave-image test and estimate sums (lib/src/tbd/tbd_dyn.c). */
#include <string.h>

#include "pft/pft_pf_models.h"
#include "../tbd/tbd_int.h"

size_t pft_pf_tbd_model_workspace_size(const pft_tbd_config_t *cfg)
{
    if (pft_tbd_config_check(cfg, NULL) != PFT_OK) {
        return 0u;
    }
    return PFT_PF_TBD_WORKSPACE_BYTES(cfg->width, cfg->height);
}

/* The reset hook: a new sequence starts (the next frame is a first frame). */
static void tbd_reset_(void *ctx)
{
    pft_pf_tbd_model_t *m = (pft_pf_tbd_model_t *)ctx;
    m->frames = 0u;
    m->birth_lw = PFT_C(0.0);
    memset(m->last, 0, sizeof(m->last));
    m->plan_on = false;
    m->pend_x = NULL;
}

/* ---- interface callbacks ---- */

static pft_status_t tbd_begin_(void *ctx, const void *z)
{
    pft_pf_tbd_model_t *m = (pft_pf_tbd_model_t *)ctx;
    const pft_frame_t *frame = (const pft_frame_t *)z;
    if (frame == NULL) {
        return PFT_ERR_INVAL;
    }
    pft_status_t st = pft_tbd_frame_check_(&m->cfg, frame);
    if (st != PFT_OK) {
        return st;
    }
    pft_tbd_frame_convert_(&m->cfg, &m->m, frame, m->img);
    pft_tbd_scene_t_ sc;
    pft_tbd_scene_build_(&m->cfg, m->gamma_w, m->img, NULL, m->cand, &sc);
    m->n_cand = sc.n_cand;
    m->birth_lw = pft_tbd_birth_lw_(&m->cfg, &sc);
    if (m->frames < UINT32_MAX) {
        ++m->frames;
    }
    m->plan_on = false; /* until prepare plans this step */
    m->pend_x = NULL;
    return PFT_OK;
}

/* log(p16 / 65536) for 0 < p16 < 65536 */
static pft_real_t log_p16_(uint32_t p16)
{
    return pft_sub(pft_log_count_(p16), PFT_C(11.0903548889591)); /* 16 log 2 */
}

/* The birth budget's plan of a step (docs/algorithms.md 3.4): count the particles with and
 * without a target, choose the number of births b and the weight corrections. */
static void tbd_prepare_(void *ctx, const pft_real_t *x, uint32_t n)
{
    pft_pf_tbd_model_t *m = (pft_pf_tbd_model_t *)ctx;
    m->plan_on = false;
    m->pend_x = NULL;
    if (m->budget == 0u) {
        return;
    }
    uint32_t n1 = 0u;
    for (uint32_t i = 0; i < n; ++i) {
        if (x[(size_t)i * PFT_PF_TBD_DIM + PFT_PF_TBD_E] != PFT_C(0.0)) {
            ++n1;
        }
    }
    const uint32_t n0 = n - n1;
    const uint32_t p16 = pft_tbd_p_birth_(&m->dyn, m->frames <= 1u);
    if (n0 < 2u || m->n_cand == 0u || p16 == 0u || p16 >= 65536u) {
        return; /* the plain Bernoulli draws */
    }
    uint32_t b = m->budget > n1 ? m->budget - n1 : 0u;
    const uint32_t natural = (uint32_t)(((uint64_t)p16 * n0 + 65535u) >> 16); /* ceil(pb n0) */
    b = b > natural ? b : natural;
    b = b > 1u ? b : 1u;
    b = b < n0 - 1u ? b : n0 - 1u;
    const pft_real_t ln0 = pft_log_count_(n0);
    m->lc_born = pft_sub(pft_add(log_p16_(p16), ln0), pft_log_count_(b));
    m->lc_stay = pft_sub(pft_add(log_p16_(65536u - p16), ln0), pft_log_count_(n0 - b));
    m->n0 = n0;
    m->nb = b;
    m->seen0 = 0u;
    m->sel0 = 0u;
    m->plan_on = true;
}

static void tbd_prior_(void *ctx, pft_real_t *x, pft_rng_t *rng)
{
    (void)ctx;
    (void)rng;
    memset(x, 0, PFT_PF_TBD_DIM * sizeof(pft_real_t)); /* E = 0: no target before frame 1 */
}

/* The kinematic part of a state vector. */
static pft_tbd_kin_t kin_(pft_real_t *x)
{
    pft_tbd_kin_t k = {&x[PFT_PF_TBD_X], &x[PFT_PF_TBD_Y], &x[PFT_PF_TBD_VX], &x[PFT_PF_TBD_VY],
                       &x[PFT_PF_TBD_I]};
    return k;
}

/* The state's position between the public frame (0-based, the engine's states) and the tbd
 * module's internal one (x + dx; see lib/src/tbd/tbd_int.h). */
static void to_int_(const pft_pf_tbd_model_t *m, pft_real_t *x)
{
    x[PFT_PF_TBD_X] = pft_tbd_x_int_(x[PFT_PF_TBD_X], m->m.dx);
    x[PFT_PF_TBD_Y] = pft_tbd_x_int_(x[PFT_PF_TBD_Y], m->m.dy);
}
static void to_pub_(const pft_pf_tbd_model_t *m, pft_real_t *x)
{
    x[PFT_PF_TBD_X] = pft_tbd_x_pub_(x[PFT_PF_TBD_X], m->m.dx);
    x[PFT_PF_TBD_Y] = pft_tbd_x_pub_(x[PFT_PF_TBD_Y], m->m.dy);
}

/* A target whose window centre leaves the image leaves the surveillance region: E = 0
 * (x in the internal frame). */
static void leave_image_(const pft_pf_tbd_model_t *m, pft_real_t *x)
{
    size_t pix = 0;
    if (!pft_tbd_centre_(&m->m, x[PFT_PF_TBD_X], x[PFT_PF_TBD_Y], &pix)) {
        x[PFT_PF_TBD_E] = PFT_C(0.0);
    }
}

/* A birth: E = 2 (born at this step: gets the birth correction), position drawn. */
static void birth_(const pft_pf_tbd_model_t *m, pft_real_t *x, pft_rng_t *rng)
{
    pft_tbd_kin_t k = kin_(x);
    pft_tbd_birth_(&m->cfg, &m->dyn, m->cand, m->n_cand, true, rng, &k);
    x[PFT_PF_TBD_E] = PFT_C(2.0);
    leave_image_(m, x);
    to_pub_(m, x);
}

/* An E = 0 particle under the budget's plan: selection sampling (Knuth's algorithm S) draws
 * exactly nb of the n0 for a birth, each with probability nb / n0; the proposal ratio waits
 * for loglik in pend_c. */
static void planned_(pft_pf_tbd_model_t *m, pft_real_t *x, pft_rng_t *rng)
{
    const uint32_t left = m->n0 - m->seen0;
    const uint32_t need = m->nb - m->sel0;
    const uint32_t r = pft_rng_next_(rng);
    ++m->seen0;
    m->pend_x = x;
    if ((uint64_t)r * left < ((uint64_t)need << 32)) {
        ++m->sel0;
        m->pend_c = m->lc_born;
        birth_(m, x, rng);
    } else {
        m->pend_c = m->lc_stay;
    }
}

static void tbd_propagate_(void *ctx, pft_real_t *x, pft_rng_t *rng)
{
    pft_pf_tbd_model_t *m = (pft_pf_tbd_model_t *)ctx;
    pft_tbd_kin_t k = kin_(x);
    uint32_t u = pft_tbd_exist_draw_(rng); /* one draw per particle, as the tbd module */
    m->pend_x = NULL;
    if (x[PFT_PF_TBD_E] != PFT_C(0.0)) {
        if (u < m->dyn.p16_d) {
            x[PFT_PF_TBD_E] = PFT_C(0.0);
            return;
        }
        to_int_(m, x);
        pft_tbd_pf_move_(&m->dyn, m->cfg.T, rng, &k);
        x[PFT_PF_TBD_E] = PFT_C(1.0);
        leave_image_(m, x);
        to_pub_(m, x);
        return;
    }
    if (m->plan_on && m->seen0 < m->n0) {
        planned_(m, x, rng);
        return;
    }
    if (m->n_cand > 0u && u < pft_tbd_p_birth_(&m->dyn, m->frames <= 1u)) {
        birth_(m, x, rng);
    }
}

/* Log likelihood ratio of a state whose position is in the internal frame. */
static pft_real_t llr_int_(const pft_pf_tbd_model_t *m, const pft_real_t *xi)
{
    if (xi[PFT_PF_TBD_E] == PFT_C(0.0)) {
        return PFT_C(0.0);
    }
    pft_tbd_cell_t c;
    if (!pft_tbd_cell_(&m->m, xi[PFT_PF_TBD_X], xi[PFT_PF_TBD_Y], &c)) {
        return PFT_C(0.0); /* (an APF predicted point outside the image) */
    }
    pft_real_t ll = pft_tbd_llr_(&m->m, m->tab, m->img, &c, xi[PFT_PF_TBD_I]);
    if (xi[PFT_PF_TBD_E] > PFT_C(1.0)) {
        ll = pft_add(ll, m->birth_lw);
    }
    return ll;
}

static pft_real_t tbd_loglik_(void *ctx, const pft_real_t *x, const void *z)
{
    pft_pf_tbd_model_t *m = (pft_pf_tbd_model_t *)ctx;
    (void)z; /* the converted frame of begin() */
    pft_real_t xi[PFT_PF_TBD_DIM];
    memcpy(xi, x, sizeof xi);
    to_int_(m, xi);
    pft_real_t ll = llr_int_(m, xi);
    if (m->pend_x == x) { /* the budget's proposal ratio of the particle just propagated */
        ll = pft_add(ll, m->pend_c);
        m->pend_x = NULL;
    }
    return ll;
}

/* The APF's characteristic point mu = Phi x, kept in the internal frame: it is read only by
 * tbd_loglik_first_ (the engine never interprets mu), so the first stage is the same
 * arithmetic as the tbd module's. */
static void tbd_predict_(void *ctx, const pft_real_t *x, pft_real_t *mu)
{
    const pft_pf_tbd_model_t *m = (const pft_pf_tbd_model_t *)ctx;
    memcpy(mu, x, PFT_PF_TBD_DIM * sizeof(pft_real_t));
    if (x[PFT_PF_TBD_E] != PFT_C(0.0)) {
        to_int_(m, mu);
        mu[PFT_PF_TBD_X] = pft_add(mu[PFT_PF_TBD_X], pft_mul(m->cfg.T, x[PFT_PF_TBD_VX]));
        mu[PFT_PF_TBD_Y] = pft_add(mu[PFT_PF_TBD_Y], pft_mul(m->cfg.T, x[PFT_PF_TBD_VY]));
        mu[PFT_PF_TBD_E] = PFT_C(1.0);
    }
}

static pft_real_t tbd_loglik_first_(void *ctx, const pft_real_t *mu, const void *z)
{
    (void)z;
    return llr_int_((const pft_pf_tbd_model_t *)ctx, mu);
}

static void tbd_estimate_(void *ctx, const pft_real_t *x, const pft_weight_t *w, uint32_t n,
                          pft_real_t *est)
{
    pft_pf_tbd_model_t *m = (pft_pf_tbd_model_t *)ctx;
    pft_tbd_wsum_t a;
    pft_tbd_wsum_init_(&a);
    for (uint32_t i = 0; i < n; ++i) {
        const pft_real_t *xi = x + (size_t)i * PFT_PF_TBD_DIM;
        bool alive = xi[PFT_PF_TBD_E] != PFT_C(0.0);
        /* positions summed in the internal frame, so the mean is the tbd module's exactly */
        const pft_real_t v[5] = {
            alive ? pft_tbd_x_int_(xi[PFT_PF_TBD_X], m->m.dx) : PFT_C(0.0),
            alive ? pft_tbd_x_int_(xi[PFT_PF_TBD_Y], m->m.dy) : PFT_C(0.0), xi[PFT_PF_TBD_VX],
            xi[PFT_PF_TBD_VY], xi[PFT_PF_TBD_I]};
        pft_tbd_wsum_add_(&a, w[i], alive, v);
    }
    pft_real_t mean[5];
    if (pft_tbd_wsum_mean_(&a, mean)) {
        m->last[PFT_PF_TBD_X] = pft_tbd_x_pub_(mean[0], m->m.dx);
        m->last[PFT_PF_TBD_Y] = pft_tbd_x_pub_(mean[1], m->m.dy);
        m->last[PFT_PF_TBD_VX] = mean[2];
        m->last[PFT_PF_TBD_VY] = mean[3];
        m->last[PFT_PF_TBD_I] = mean[4];
    }
    memcpy(est, m->last, sizeof(m->last));
    est[PFT_PF_TBD_E] = pft_tbd_wsum_p_(&a);
}

pft_status_t pft_pf_tbd_model_init(pft_pf_tbd_model_t *m, const pft_tbd_config_t *cfg, void *work,
                                 size_t work_len, pft_pf_model_t *iface)
{
    if (m == NULL || cfg == NULL || work == NULL || iface == NULL) {
        return PFT_ERR_INVAL;
    }
    if (pft_tbd_config_check(cfg, NULL) != PFT_OK) {
        return PFT_ERR_CONFIG;
    }
    size_t npix = (size_t)cfg->width * cfg->height;
    size_t nimg = pft_tbd_img_len_(cfg->width, cfg->height);
    pft_ws_t ws;
    pft_ws_init(&ws, work, work_len);
    pft_real_t *img = (pft_real_t *)pft_ws_take(&ws, nimg * sizeof(pft_real_t));
    uint32_t *cand = (uint32_t *)pft_ws_take(&ws, npix * sizeof(uint32_t));
    pft_tbd_tab_t *tab = (pft_tbd_tab_t *)pft_ws_take(&ws, sizeof(pft_tbd_tab_t));
    if (pft_ws_status(&ws) != PFT_OK) {
        return PFT_ERR_NOMEM;
    }
    memset(m, 0, sizeof(*m));
    m->cfg = *cfg;
    pft_tbd_meas_setup_(&m->m, cfg);
    m->img = img;
    m->cand = cand;
    m->tab = tab;
    pft_tbd_tab_setup_(tab, cfg);
    m->gamma_w = pft_mul(cfg->gamma, m->m.inv_sn);
    memset(img, 0, nimg * sizeof(pft_real_t));
    memset(cand, 0, npix * sizeof(uint32_t));
    pft_tbd_dyn_setup_(&m->dyn, cfg);
    tbd_reset_(m);
    memset(iface, 0, sizeof(*iface));
    iface->dim = PFT_PF_TBD_DIM;
    iface->ctx = m;
    iface->begin = tbd_begin_;
    iface->sample_prior = tbd_prior_;
    iface->propagate = tbd_propagate_;
    iface->loglik = tbd_loglik_;
    iface->predict = tbd_predict_;
    iface->loglik_first = tbd_loglik_first_;
    iface->estimate = tbd_estimate_;
    iface->reset = tbd_reset_;
    iface->prepare = tbd_prepare_;
    return PFT_OK;
}

pft_status_t pft_pf_tbd_model_set_budget(pft_pf_tbd_model_t *m, uint32_t budget)
{
    if (m == NULL) {
        return PFT_ERR_INVAL;
    }
    m->budget = budget;
    m->plan_on = false;
    m->pend_x = NULL;
    return PFT_OK;
}
