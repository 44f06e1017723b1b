/* The TBD pixel likelihood (pft_tbd.h, ALGORITHMS.md 1 and 2.9) as a model of the
 * particle-filter engine: with SIR it is the bootstrap PF-TBD, with the APF the APF-TBD.
 * The measurement model, frame conversion and birth-candidate scan are the tbd module's
 * (pft_tbd_meas_llr and its internal frame helpers); only the engine differs. */
#include <string.h>

#include "pft/pft_pf_models.h"
#include "../core/acc_int.h"
#include "../core/num_int.h"
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
    pft_tbd_frame_convert_(&m->cfg, frame, m->img);
    pft_tbd_scene_t_ sc;
    pft_tbd_scene_build_(&m->cfg, m->img, NULL, m->cand, &sc);
    m->n_cand = sc.n_cand;
    m->birth_lw = PFT_C(0.0);
    if (m->cfg.birth_correction && sc.cand_is_b && sc.n_allowed > 0u) {
        m->birth_lw = pft_log(pft_ratio((int32_t)sc.n_cand, (int32_t)sc.n_allowed));
    }
    if (m->frames < UINT32_MAX) {
        ++m->frames;
    }
    return PFT_OK;
}

static void tbd_prior_(void *ctx, pft_real_t *x, pft_rng_t *rng)
{
    (void)ctx;
    (void)rng;
    memset(x, 0, PFT_PF_TBD_DIM * sizeof(pft_real_t)); /* E = 0: no target before frame 1 */
}

static void axis_(const pft_pf_tbd_model_t *m, pft_real_t *pos, pft_real_t *v, pft_real_t g1,
                  pft_real_t g2)
{
    *pos = pft_add(*pos, pft_add(pft_mul(m->cfg.T, *v), pft_mul(m->ch_pos, g1)));
    *v = pft_add(*v, pft_add(pft_mul(m->ch_cross, g1), pft_mul(m->ch_vel, g2)));
}

static void birth_(const pft_pf_tbd_model_t *m, pft_real_t *x, pft_rng_t *rng)
{
    const pft_tbd_config_t *c = &m->cfg;
    uint32_t k = m->cand[pft_rng_below(rng, m->n_cand)];
    uint32_t col = k % c->width;
    uint32_t row = k / c->width;
    pft_real_t ux = pft_rng_uniform(rng);
    pft_real_t uy = pft_rng_uniform(rng);
    /* pixel i = col + 1 covers [(i - 0.5) dx, (i + 0.5) dx) */
    x[PFT_PF_TBD_X] = pft_mul(pft_add(pft_add(pft_from_int((int32_t)col), PFT_C(0.5)), ux), c->dx);
    x[PFT_PF_TBD_Y] = pft_mul(pft_add(pft_add(pft_from_int((int32_t)row), PFT_C(0.5)), uy), c->dy);
    x[PFT_PF_TBD_I] = pft_rng_uniform_range(rng, c->i_min, c->i_max);
    x[PFT_PF_TBD_VX] = pft_add(c->vel_mean[0], pft_mul(m->vel_sd[0], pft_rng_gauss(rng)));
    x[PFT_PF_TBD_VY] = pft_add(c->vel_mean[1], pft_mul(m->vel_sd[1], pft_rng_gauss(rng)));
    x[PFT_PF_TBD_E] = PFT_C(2.0);
}

/* A target whose window centre leaves the image leaves the surveillance region: E = 0 (the
 * tbd module's rule). */
static void leave_image_(const pft_pf_tbd_model_t *m, pft_real_t *x)
{
    int32_t i0 = pft_tbd_pix_(x[PFT_PF_TBD_X], m->m.inv_dx);
    int32_t j0 = pft_tbd_pix_(x[PFT_PF_TBD_Y], m->m.inv_dy);
    if (i0 < 1 || j0 < 1 || i0 > (int32_t)m->cfg.width || j0 > (int32_t)m->cfg.height) {
        x[PFT_PF_TBD_E] = PFT_C(0.0);
    }
}

static void tbd_propagate_(void *ctx, pft_real_t *x, pft_rng_t *rng)
{
    const pft_pf_tbd_model_t *m = (const pft_pf_tbd_model_t *)ctx;
    /* existence: one draw per particle, decided on its top 16 bits (same as the tbd module) */
    uint32_t u = pft_rng_u32(rng) >> 16;
    if (x[PFT_PF_TBD_E] != PFT_C(0.0)) {
        if (u < m->p16_d) {
            x[PFT_PF_TBD_E] = PFT_C(0.0);
            return;
        }
        pft_real_t g1 = pft_rng_gauss(rng);
        pft_real_t g2 = pft_rng_gauss(rng);
        pft_real_t g3 = pft_rng_gauss(rng);
        pft_real_t g4 = pft_rng_gauss(rng);
        pft_real_t g5 = pft_rng_gauss(rng);
        axis_(m, &x[PFT_PF_TBD_X], &x[PFT_PF_TBD_VX], g1, g2);
        axis_(m, &x[PFT_PF_TBD_Y], &x[PFT_PF_TBD_VY], g3, g4);
        x[PFT_PF_TBD_I] = pft_add(x[PFT_PF_TBD_I], pft_mul(m->ch_int, g5));
        x[PFT_PF_TBD_E] = PFT_C(1.0);
        leave_image_(m, x);
        return;
    }
    uint32_t p_birth = m->frames <= 1u ? m->p16_eta : m->p16_b;
    if (m->n_cand > 0u && u < p_birth) {
        birth_(m, x, rng);
        leave_image_(m, x);
    }
}

static pft_real_t tbd_loglik_(void *ctx, const pft_real_t *x, const void *z)
{
    const pft_pf_tbd_model_t *m = (const pft_pf_tbd_model_t *)ctx;
    (void)z; /* the converted frame of begin() */
    if (x[PFT_PF_TBD_E] == PFT_C(0.0)) {
        return PFT_C(0.0);
    }
    pft_real_t ll = pft_tbd_meas_llr(&m->m, m->img, x[PFT_PF_TBD_X], x[PFT_PF_TBD_Y], x[PFT_PF_TBD_I]);
    if (x[PFT_PF_TBD_E] > PFT_C(1.0)) {
        ll = pft_add(ll, m->birth_lw);
    }
    return ll;
}

static void tbd_predict_(void *ctx, const pft_real_t *x, pft_real_t *mu)
{
    const pft_pf_tbd_model_t *m = (const pft_pf_tbd_model_t *)ctx;
    memcpy(mu, x, PFT_PF_TBD_DIM * sizeof(pft_real_t));
    if (x[PFT_PF_TBD_E] != PFT_C(0.0)) {
        mu[PFT_PF_TBD_X] = pft_add(x[PFT_PF_TBD_X], pft_mul(m->cfg.T, x[PFT_PF_TBD_VX]));
        mu[PFT_PF_TBD_Y] = pft_add(x[PFT_PF_TBD_Y], pft_mul(m->cfg.T, x[PFT_PF_TBD_VY]));
        mu[PFT_PF_TBD_E] = PFT_C(1.0);
    }
}

static void tbd_estimate_(void *ctx, const pft_real_t *x, const pft_weight_t *w, uint32_t n,
                           pft_real_t *est)
{
    pft_pf_tbd_model_t *m = (pft_pf_tbd_model_t *)ctx;
    pft_acc_t_ acc[5];
    pft_wacc_t wt = 0;
    pft_wacc_t we = 0;
    for (int c = 0; c < 5; ++c) {
        acc[c] = PFT_ACC_ZERO_;
    }
    for (uint32_t i = 0; i < n; ++i) {
        const pft_real_t *xi = x + (size_t)i * PFT_PF_TBD_DIM;
        wt += w[i];
        if (xi[PFT_PF_TBD_E] != PFT_C(0.0)) {
            we += w[i];
            for (int c = 0; c < 5; ++c) {
                acc[c] += pft_acc_wx_(w[i], xi[c]);
            }
        }
    }
    if (we > 0) {
        for (int c = 0; c < 5; ++c) {
            m->last[c] = pft_acc_div_(acc[c], we);
        }
    }
    memcpy(est, m->last, sizeof(m->last));
    est[PFT_PF_TBD_E] = pft_wratio_(we, wt);
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
    pft_ws_t ws;
    pft_ws_init(&ws, work, work_len);
    pft_real_t *img = (pft_real_t *)pft_ws_take(&ws, npix * sizeof(pft_real_t));
    uint32_t *cand = (uint32_t *)pft_ws_take(&ws, npix * sizeof(uint32_t));
    if (pft_ws_status(&ws) != PFT_OK) {
        return PFT_ERR_NOMEM;
    }
    memset(m, 0, sizeof(*m));
    m->cfg = *cfg;
    pft_tbd_meas_setup_(&m->m, cfg);
    m->img = img;
    m->cand = cand;
    memset(img, 0, npix * sizeof(pft_real_t));
    memset(cand, 0, npix * sizeof(uint32_t));
    pft_real_t T = cfg->T;
    pft_real_t q1T = pft_mul(cfg->q1, T);
    /* chol of q1 [[T^3/3, T^2/2], [T^2/2, T]]: L11 = sqrt(q1 T^3/3), L21 = q1 T^2/2 / L11,
     * L22 = sqrt(q1 T/4) (same constants as the tbd module's PF-TBD) */
    m->ch_pos = pft_sqrt(pft_div(pft_mul(cfg->q1, pft_mul(pft_sq(T), T)), PFT_C(3.0)));
    m->ch_cross = m->ch_pos > PFT_C(0.0)
                      ? pft_div(pft_mul(pft_mul(cfg->q1, pft_sq(T)), PFT_C(0.5)), m->ch_pos)
                      : PFT_C(0.0);
    m->ch_vel = pft_sqrt(pft_mul(q1T, PFT_C(0.25)));
    m->ch_int = pft_sqrt(pft_mul(cfg->q2, T));
    m->vel_sd[0] = pft_sqrt(cfg->vel_var[0]);
    m->vel_sd[1] = pft_sqrt(cfg->vel_var[1]);
    m->p16_b = pft_p16_(cfg->pb);
    m->p16_d = pft_p16_(cfg->pd);
    m->p16_eta = pft_p16_(cfg->eta);
    tbd_reset_(m);
    memset(iface, 0, sizeof(*iface));
    iface->dim = PFT_PF_TBD_DIM;
    iface->ctx = m;
    iface->begin = tbd_begin_;
    iface->sample_prior = tbd_prior_;
    iface->propagate = tbd_propagate_;
    iface->loglik = tbd_loglik_;
    iface->predict = tbd_predict_;
    iface->estimate = tbd_estimate_;
    iface->reset = tbd_reset_;
    return PFT_OK;
}
