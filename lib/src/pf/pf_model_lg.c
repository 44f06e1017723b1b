/* Linear-Gaussian model for the particle-filter engine (the Kalman filter is its exact
 * posterior: the reference of the engine tests). */
#include <string.h>

#include "pft/pft_pf_models.h"
#include "../core/config_int.h"

static void matvec_(const pft_real_t *A, const pft_real_t *v, uint16_t rows, uint16_t cols,
                    pft_real_t *out)
{
    for (uint16_t r = 0; r < rows; ++r) {
        pft_real_t acc = PFT_C(0.0);
        for (uint16_t c = 0; c < cols; ++c) {
            acc = pft_add(acc, pft_mul(A[(size_t)r * cols + c], v[c]));
        }
        out[r] = acc;
    }
}

static void lg_prior_(void *ctx, pft_real_t *x, pft_rng_t *rng)
{
    const pft_pf_lg_model_t *m = (const pft_pf_lg_model_t *)ctx;
    uint16_t d = m->cfg.dim;
    pft_real_t g[PFT_PF_LG_MAX_DIM] = {0};
    pft_real_t t[PFT_PF_LG_MAX_DIM] = {0};
    for (uint16_t c = 0; c < d; ++c) {
        g[c] = pft_rng_gauss(rng);
    }
    matvec_(m->cfg.L0, g, d, d, t);
    for (uint16_t c = 0; c < d; ++c) {
        x[c] = pft_add(m->cfg.m0[c], t[c]);
    }
}

static void lg_predict_(void *ctx, const pft_real_t *x, pft_real_t *mu)
{
    const pft_pf_lg_model_t *m = (const pft_pf_lg_model_t *)ctx;
    matvec_(m->cfg.F, x, m->cfg.dim, m->cfg.dim, mu);
}

static void lg_propagate_(void *ctx, pft_real_t *x, pft_rng_t *rng)
{
    const pft_pf_lg_model_t *m = (const pft_pf_lg_model_t *)ctx;
    uint16_t d = m->cfg.dim;
    pft_real_t g[PFT_PF_LG_MAX_DIM] = {0};
    pft_real_t fx[PFT_PF_LG_MAX_DIM] = {0};
    pft_real_t t[PFT_PF_LG_MAX_DIM] = {0};
    for (uint16_t c = 0; c < d; ++c) {
        g[c] = pft_rng_gauss(rng);
    }
    matvec_(m->cfg.F, x, d, d, fx);
    matvec_(m->cfg.Lq, g, d, d, t);
    for (uint16_t c = 0; c < d; ++c) {
        x[c] = pft_add(fx[c], t[c]);
    }
}

static pft_real_t lg_loglik_(void *ctx, const pft_real_t *x, const void *z)
{
    const pft_pf_lg_model_t *m = (const pft_pf_lg_model_t *)ctx;
    const pft_real_t *zz = (const pft_real_t *)z;
    pft_real_t hx[PFT_PF_LG_MAX_MEAS] = {0};
    pft_real_t ll = PFT_C(0.0);
    matvec_(m->cfg.H, x, m->cfg.meas, m->cfg.dim, hx);
    for (uint16_t k = 0; k < m->cfg.meas; ++k) {
        pft_real_t s = pft_mul(pft_sub(zz[k], hx[k]), m->inv_r[k]);
        ll = pft_sub(ll, pft_mul(pft_sq(s), PFT_C(0.5)));
    }
    return ll;
}

pft_status_t pft_pf_lg_model_init(pft_pf_lg_model_t *m, const pft_pf_lg_config_t *cfg,
                               pft_pf_model_t *iface)
{
    if (m == NULL || cfg == NULL || iface == NULL) {
        return PFT_ERR_INVAL;
    }
    if (cfg->dim < 1u || cfg->dim > PFT_PF_LG_MAX_DIM || cfg->meas < 1u ||
        cfg->meas > PFT_PF_LG_MAX_MEAS) {
        return PFT_ERR_CONFIG;
    }
    for (uint16_t k = 0; k < cfg->meas; ++k) {
        if (!pft_cfg_real_pos_(cfg->r_sd[k])) {
            return PFT_ERR_CONFIG;
        }
    }
    /* every matrix and the prior in the configuration domain (core/config_int.h) */
    const size_t dd = (size_t)cfg->dim * cfg->dim; /* matrices are packed rows of dim */
    if (!pft_cfg_reals_ok_(cfg->F, dd) || !pft_cfg_reals_ok_(cfg->Lq, dd) ||
        !pft_cfg_reals_ok_(cfg->H, (size_t)cfg->meas * cfg->dim) ||
        !pft_cfg_reals_ok_(cfg->m0, cfg->dim) || !pft_cfg_reals_ok_(cfg->L0, dd)) {
        return PFT_ERR_CONFIG;
    }
    memset(m, 0, sizeof(*m));
    m->cfg = *cfg;
    for (uint16_t k = 0; k < cfg->meas; ++k) {
        m->inv_r[k] = pft_recip(cfg->r_sd[k]);
    }
    memset(iface, 0, sizeof(*iface));
    iface->dim = cfg->dim;
    iface->ctx = m;
    iface->sample_prior = lg_prior_;
    iface->propagate = lg_propagate_;
    iface->loglik = lg_loglik_;
    iface->predict = lg_predict_;
    return PFT_OK;
}
