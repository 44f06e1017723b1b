/* Bearings-only constant-velocity model (Gordon, Salmond & Smith 1993; docs/algorithms.md 3.1)
 * for the particle-filter engine. */
#include <string.h>

#include "pft/pft_pf_models.h"
#include "../core/config_int.h"

void pft_pf_bearings_config_default(pft_pf_bearings_config_t *cfg, int32_t scale)
{
    if (cfg == NULL) {
        return;
    }
    int32_t s = scale < 1 ? 1 : scale;
    memset(cfg, 0, sizeof(*cfg));
    cfg->T = PFT_C(1.0);
    /* exact integer ratios: value * scale = (k * scale) / 1000 */
    cfg->q_sd = pft_ratio(s, 1000);
    cfg->r_sd = PFT_C(0.005);
    cfg->prior_mean[PFT_PF_BRG_X] = PFT_C(0.0);
    cfg->prior_mean[PFT_PF_BRG_VX] = PFT_C(0.0);
    cfg->prior_mean[PFT_PF_BRG_Y] = pft_ratio(400 * s, 1000);
    cfg->prior_mean[PFT_PF_BRG_VY] = pft_ratio(-50 * s, 1000);
    cfg->prior_sd[PFT_PF_BRG_X] = pft_ratio(500 * s, 1000);
    cfg->prior_sd[PFT_PF_BRG_VX] = pft_ratio(5 * s, 1000);
    cfg->prior_sd[PFT_PF_BRG_Y] = pft_ratio(300 * s, 1000);
    cfg->prior_sd[PFT_PF_BRG_VY] = pft_ratio(10 * s, 1000);
    cfg->ll_clip = PFT_C(50.0);
    cfg->first_r_sd = PFT_C(0.0);
}

pft_real_t pft_pf_bearings_innovation(const pft_real_t *x, pft_real_t z)
{
    pft_real_t e = pft_sub(z, pft_atan2(x[PFT_PF_BRG_Y], x[PFT_PF_BRG_X]));
    /* both terms in [-pi, pi] (z may be any angle in (-pi, pi]): one correction suffices;
     * a second keeps a z slightly outside that interval in range too */
    for (int k = 0; k < 2; ++k) {
        if (e > PFT_PI) {
            e = pft_sub(e, PFT_TWO_PI);
        } else if (e <= pft_neg(PFT_PI)) {
            e = pft_add(e, PFT_TWO_PI);
        } else {
            /* e already in (-pi, pi] */
        }
    }
    return e;
}

/* -s^2/2 inside the clip, the tangent line beyond. s >= 0. */
static pft_real_t ll_of_s_(const pft_pf_bearings_model_t *m, pft_real_t s)
{
    if (s <= m->cfg.ll_clip) {
        return pft_neg(pft_mul(pft_sq(s), PFT_C(0.5)));
    }
    return pft_neg(pft_sub(pft_mul(m->cfg.ll_clip, s), m->half_clip2));
}

pft_real_t pft_pf_bearings_loglik(const pft_pf_bearings_model_t *m, const pft_real_t *x, pft_real_t z)
{
    pft_real_t s = pft_abs(pft_mul(pft_pf_bearings_innovation(x, z), m->inv_r));
    return ll_of_s_(m, s);
}

/* ---- interface callbacks ---- */

static void brg_prior_(void *ctx, pft_real_t *x, pft_rng_t *rng)
{
    const pft_pf_bearings_model_t *m = (const pft_pf_bearings_model_t *)ctx;
    for (int c = 0; c < PFT_PF_BRG_DIM; ++c) {
        x[c] = pft_add(m->cfg.prior_mean[c], pft_mul(m->cfg.prior_sd[c], pft_rng_gauss(rng)));
    }
}

static void brg_propagate_(void *ctx, pft_real_t *x, pft_rng_t *rng)
{
    const pft_pf_bearings_model_t *m = (const pft_pf_bearings_model_t *)ctx;
    pft_real_t T = m->cfg.T;
    pft_real_t wx = pft_rng_gauss(rng);
    pft_real_t wy = pft_rng_gauss(rng);
    x[PFT_PF_BRG_X] = pft_add(x[PFT_PF_BRG_X], pft_add(pft_mul(T, x[PFT_PF_BRG_VX]), pft_mul(m->pos_gain, wx)));
    x[PFT_PF_BRG_VX] = pft_add(x[PFT_PF_BRG_VX], pft_mul(m->vel_gain, wx));
    x[PFT_PF_BRG_Y] = pft_add(x[PFT_PF_BRG_Y], pft_add(pft_mul(T, x[PFT_PF_BRG_VY]), pft_mul(m->pos_gain, wy)));
    x[PFT_PF_BRG_VY] = pft_add(x[PFT_PF_BRG_VY], pft_mul(m->vel_gain, wy));
}

static pft_real_t brg_loglik_(void *ctx, const pft_real_t *x, const void *z)
{
    const pft_pf_bearings_model_t *m = (const pft_pf_bearings_model_t *)ctx;
    return pft_pf_bearings_loglik(m, x, *(const pft_real_t *)z);
}

static pft_real_t brg_loglik_first_(void *ctx, const pft_real_t *mu, const void *z)
{
    const pft_pf_bearings_model_t *m = (const pft_pf_bearings_model_t *)ctx;
    pft_real_t e = pft_pf_bearings_innovation(mu, *(const pft_real_t *)z);
    return ll_of_s_(m, pft_abs(pft_mul(e, m->inv_r_first)));
}

static void brg_predict_(void *ctx, const pft_real_t *x, pft_real_t *mu)
{
    const pft_pf_bearings_model_t *m = (const pft_pf_bearings_model_t *)ctx;
    pft_real_t T = m->cfg.T;
    mu[PFT_PF_BRG_X] = pft_add(x[PFT_PF_BRG_X], pft_mul(T, x[PFT_PF_BRG_VX]));
    mu[PFT_PF_BRG_VX] = x[PFT_PF_BRG_VX];
    mu[PFT_PF_BRG_Y] = pft_add(x[PFT_PF_BRG_Y], pft_mul(T, x[PFT_PF_BRG_VY]));
    mu[PFT_PF_BRG_VY] = x[PFT_PF_BRG_VY];
}

pft_status_t pft_pf_bearings_model_init(pft_pf_bearings_model_t *m, const pft_pf_bearings_config_t *cfg,
                                     pft_pf_model_t *iface)
{
    if (m == NULL || cfg == NULL || iface == NULL) {
        return PFT_ERR_INVAL;
    }
    /* every real in the configuration domain (core/config_int.h): a finite, huge prior sd or a
     * subnormal noise sd would give infinite draws or reciprocals in the float build */
    bool ok = pft_cfg_real_pos_(cfg->T) && pft_cfg_real_pos_(cfg->q_sd) &&
              pft_cfg_real_pos_(cfg->r_sd) && pft_cfg_real_pos_(cfg->ll_clip) &&
              (cfg->first_r_sd == PFT_C(0.0) || pft_cfg_real_pos_(cfg->first_r_sd));
    for (int c = 0; c < PFT_PF_BRG_DIM; ++c) {
        ok = ok && cfg->prior_sd[c] >= PFT_C(0.0) && pft_cfg_real_ok_(cfg->prior_sd[c]) &&
             pft_cfg_real_ok_(cfg->prior_mean[c]);
    }
    if (!ok) {
        return PFT_ERR_CONFIG;
    }
    memset(m, 0, sizeof(*m));
    m->cfg = *cfg;
    m->inv_r = pft_recip(cfg->r_sd);
    m->inv_r_first = cfg->first_r_sd > PFT_C(0.0) ? pft_recip(cfg->first_r_sd) : m->inv_r;
    m->half_clip2 = pft_mul(pft_sq(cfg->ll_clip), PFT_C(0.5));
    m->pos_gain = pft_mul(pft_mul(pft_sq(cfg->T), PFT_C(0.5)), cfg->q_sd);
    m->vel_gain = pft_mul(cfg->T, cfg->q_sd);
    memset(iface, 0, sizeof(*iface));
    iface->dim = PFT_PF_BRG_DIM;
    iface->ctx = m;
    iface->sample_prior = brg_prior_;
    iface->propagate = brg_propagate_;
    iface->loglik = brg_loglik_;
    iface->predict = brg_predict_;
    iface->loglik_first = cfg->first_r_sd > PFT_C(0.0) ? brg_loglik_first_ : NULL;
    return PFT_OK;
}
