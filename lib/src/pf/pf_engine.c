/* SIS, SIR and auxiliary particle filter engine over the pft_pf_model_t interface
 * (docs/algorithms.md 3.2; see pft_pf.h for the exact sequence of one update). */
#include <string.h>

#include "pft/pft_pf.h"
#include "../core/acc_int.h"
#include "../core/config_int.h"

/* ---------------------------------- helpers ----------------------------------------------- */

static pft_real_t floor_lw_(pft_real_t v) { return pft_max(v, PFT_PF_LW_FLOOR); }

void pft_pf_weighted_mean(const pft_real_t *x, const pft_weight_t *w, uint32_t n, uint16_t dim,
                          pft_real_t *mean)
{
    pft_acc_t_ acc[PFT_PF_MAX_DIM];
    pft_wacc_t wt = 0;
    uint16_t d = dim > PFT_PF_MAX_DIM ? (uint16_t)PFT_PF_MAX_DIM : dim;
    for (uint16_t c = 0; c < d; ++c) {
        acc[c] = PFT_ACC_ZERO_;
    }
    for (uint32_t i = 0; i < n; ++i) {
        const pft_real_t *xi = x + (size_t)i * dim;
        wt += w[i];
        if (w[i] == 0) {
            continue;
        }
        for (uint16_t c = 0; c < d; ++c) {
            acc[c] += pft_acc_wx_(w[i], xi[c]);
        }
    }
    for (uint16_t c = 0; c < d; ++c) {
        mean[c] = pft_acc_div_(acc[c], wt);
    }
}

static void estimate_(pft_pf_t *pf)
{
    if (pf->cfg.model.estimate != NULL) {
        pf->cfg.model.estimate(pf->cfg.model.ctx, pf->x, pf->w, pf->n, pf->est);
    } else {
        pft_pf_weighted_mean(pf->x, pf->w, pf->n, pf->dim, pf->est);
    }
}

static void uniform_weights_(pft_pf_t *pf)
{
    pft_real_t lu = pft_neg(pf->log_n);
    for (uint32_t i = 0; i < pf->n; ++i) {
        pf->lw[i] = lu;
    }
    (void)pft_lognormalize(pf->lw, pf->w, pf->n);
}

static void swap_sets_(pft_pf_t *pf)
{
    pft_real_t *t = pf->x;
    pf->x = pf->x_alt;
    pf->x_alt = t;
}

/* Normalises lw into w, keeps lw normalised (log sum exp = 0); returns the log of the
 * unnormalised total. */
static pft_real_t normalise_(pft_pf_t *pf)
{
    pft_real_t lse = pft_lognormalize(pf->lw, pf->w, pf->n);
    for (uint32_t i = 0; i < pf->n; ++i) {
        pf->lw[i] = floor_lw_(pft_sub(pf->lw[i], lse));
    }
    return lse;
}

static pft_status_t draw_indices_(pft_pf_t *pf)
{
    return pft_resample(pf->cfg.scheme, pf->w, pf->n, pf->idx, pf->n, &pf->rng, pf->scratch,
                        (size_t)pf->n * sizeof(pft_weight_t));
}

/* The pending resampling (step 1): x <- x[idx], uniform weights. */
static void resample_(pft_pf_t *pf)
{
    if (draw_indices_(pf) != PFT_OK) {
        return; /* cannot happen: normalised weights have a positive maximum */
    }
    size_t row = (size_t)pf->dim * sizeof(pft_real_t);
    for (uint32_t m = 0; m < pf->n; ++m) {
        memcpy(pf->x_alt + (size_t)m * pf->dim, pf->x + (size_t)pf->idx[m] * pf->dim, row);
    }
    swap_sets_(pf);
    uniform_weights_(pf);
}

/* ---------------------------------- steps ------------------------------------------------- */

/* SIS / SIR: bootstrap proposal, weights times the likelihood. */
static pft_real_t step_bootstrap_(pft_pf_t *pf, const void *z)
{
    const pft_pf_model_t *md = &pf->cfg.model;
    if (md->prepare != NULL) {
        md->prepare(md->ctx, pf->x, pf->n);
    }
    for (uint32_t i = 0; i < pf->n; ++i) {
        pft_real_t *xi = pf->x + (size_t)i * pf->dim;
        md->propagate(md->ctx, xi, &pf->rng);
        pf->lw[i] = floor_lw_(pft_add(pf->lw[i], md->loglik(md->ctx, xi, z)));
    }
    return normalise_(pf);
}

/* APF (Pitt & Shephard): first stage at the predicted point, index sampling, propagation,
 * second-stage correction by the first-stage likelihood of the parent only. */
static pft_real_t step_apf_(pft_pf_t *pf, const void *z)
{
    const pft_pf_model_t *md = &pf->cfg.model;
    pft_real_t mu[PFT_PF_MAX_DIM];
    size_t row = (size_t)pf->dim * sizeof(pft_real_t);
    /* 1-2. first stage: lambda_i ~ w_i p(z | mu_i); lw is reused for log lambda */
    for (uint32_t i = 0; i < pf->n; ++i) {
        md->predict(md->ctx, pf->x + (size_t)i * pf->dim, mu);
        pft_real_t f = md->loglik_first != NULL ? md->loglik_first(md->ctx, mu, z)
                                                : md->loglik(md->ctx, mu, z);
        pf->fl[i] = f;
        pf->lw[i] = floor_lw_(pft_add(pf->lw[i], f));
    }
    pft_real_t lse1 = pft_lognormalize(pf->lw, pf->w, pf->n);
    pf->stats.ess_first = pft_ess_ratio(pf->w, pf->n);
    /* 3. indices j_m ~ lambda */
    if (draw_indices_(pf) != PFT_OK) {
        for (uint32_t m = 0; m < pf->n; ++m) {
            pf->idx[m] = m; /* cannot happen (positive maximum); keep the set */
        }
    }
    /* 4-5. propagate the chosen parents; second-stage weight p(z | x_m) / p(z | mu_{j_m}) */
    for (uint32_t m = 0; m < pf->n; ++m) {
        memcpy(pf->x_alt + (size_t)m * pf->dim, pf->x + (size_t)pf->idx[m] * pf->dim, row);
    }
    if (md->prepare != NULL) {
        md->prepare(md->ctx, pf->x_alt, pf->n);
    }
    for (uint32_t m = 0; m < pf->n; ++m) {
        uint32_t j = pf->idx[m];
        pft_real_t *xm = pf->x_alt + (size_t)m * pf->dim;
        md->propagate(md->ctx, xm, &pf->rng);
        pf->lw[m] = floor_lw_(pft_sub(md->loglik(md->ctx, xm, z), pf->fl[j]));
    }
    swap_sets_(pf);
    pft_real_t lse2 = normalise_(pf);
    /* log p^(z) = log sum_i W_i p(z|mu_i) + log mean_m (p(z|x_m) / p(z|mu_{j_m})) */
    return pft_add(lse1, pft_sub(lse2, pf->log_n));
}

/* ---------------------------------- public API -------------------------------------------- */

void pft_pf_config_default(pft_pf_config_t *cfg)
{
    if (cfg == NULL) {
        return;
    }
    memset(cfg, 0, sizeof(*cfg));
    cfg->kind = PFT_PF_SIR;
    cfg->n_particles = 1000u;
    cfg->scheme = PFT_RESAMPLE_SYSTEMATIC;
    cfg->policy = PFT_PF_RESAMPLE_AUTO;
    cfg->ess_threshold = PFT_C(0.5);
    cfg->seed = 1u;
}

/* The policy in force: AUTO resolved by kind, SIS never. */
static pft_pf_policy_t policy_(const pft_pf_config_t *c)
{
    if (c->kind == PFT_PF_SIS) {
        return PFT_PF_RESAMPLE_NEVER;
    }
    if (c->policy == PFT_PF_RESAMPLE_AUTO) {
        return c->kind == PFT_PF_APF ? PFT_PF_RESAMPLE_ESS : PFT_PF_RESAMPLE_ALWAYS;
    }
    return c->policy;
}

/* The first refused field of c, NULL if none. */
static const char *refused_field_(const pft_pf_config_t *c)
{
    const pft_pf_model_t *m = &c->model;
    if (c->kind != PFT_PF_SIS && c->kind != PFT_PF_SIR && c->kind != PFT_PF_APF) {
        return "kind";
    }
    if (c->n_particles < 1u || c->n_particles > PFT_CFG_MAX_PARTICLES) {
        return "n_particles";
    }
    if ((unsigned)c->scheme > (unsigned)PFT_RESAMPLE_MULTINOMIAL) {
        return "scheme";
    }
    if (c->policy != PFT_PF_RESAMPLE_ALWAYS && c->policy != PFT_PF_RESAMPLE_ESS &&
        c->policy != PFT_PF_RESAMPLE_NEVER && c->policy != PFT_PF_RESAMPLE_AUTO) {
        return "policy";
    }
    if (policy_(c) == PFT_PF_RESAMPLE_ESS &&
        !(c->ess_threshold > PFT_C(0.0) && c->ess_threshold <= PFT_C(1.0))) {
        return "ess_threshold";
    }
    if (m->dim < 1u || m->dim > PFT_PF_MAX_DIM) {
        return "model.dim";
    }
    if (m->propagate == NULL) {
        return "model.propagate";
    }
    if (m->loglik == NULL) {
        return "model.loglik";
    }
    if (c->kind == PFT_PF_APF && m->predict == NULL) {
        return "model.predict";
    }
    return NULL;
}

pft_status_t pft_pf_config_check(const pft_pf_config_t *cfg, const char **field)
{
    return pft_config_verdict_(cfg != NULL, cfg != NULL ? refused_field_(cfg) : NULL, field);
}

size_t pft_pf_workspace_size(const pft_pf_config_t *cfg)
{
    if (pft_pf_config_check(cfg, NULL) != PFT_OK) {
        return 0u;
    }
    return PFT_PF_WORKSPACE_BYTES(cfg->n_particles, cfg->model.dim);
}

pft_status_t pft_pf_init(pft_pf_t *pf, const pft_pf_config_t *cfg, void *work, size_t work_len)
{
    if (pf == NULL || cfg == NULL || work == NULL) {
        return PFT_ERR_INVAL;
    }
    if (pft_pf_config_check(cfg, NULL) != PFT_OK) {
        return PFT_ERR_CONFIG;
    }
    memset(pf, 0, sizeof(*pf));
    pf->cfg = *cfg;
    pf->n = cfg->n_particles;
    pf->dim = cfg->model.dim;
    size_t sb = (size_t)pf->n * pf->dim * sizeof(pft_real_t);
    size_t rb = (size_t)pf->n * sizeof(pft_real_t);
    size_t wb = (size_t)pf->n * sizeof(pft_weight_t);
    pft_ws_t ws;
    pft_ws_init(&ws, work, work_len);
    pf->x = (pft_real_t *)pft_ws_take(&ws, sb);
    pf->x_alt = (pft_real_t *)pft_ws_take(&ws, sb);
    pf->lw = (pft_real_t *)pft_ws_take(&ws, rb);
    pf->fl = (pft_real_t *)pft_ws_take(&ws, rb);
    pf->w = (pft_weight_t *)pft_ws_take(&ws, wb);
    pf->scratch = (pft_weight_t *)pft_ws_take(&ws, wb);
    pf->idx = (uint32_t *)pft_ws_take(&ws, (size_t)pf->n * sizeof(uint32_t));
    if (pft_ws_status(&ws) != PFT_OK) {
        memset(pf, 0, sizeof(*pf));
        return PFT_ERR_NOMEM;
    }
    pf->log_n = pft_log_count_(pf->n);
    memset(pf->x_alt, 0, sb);
    memset(pf->fl, 0, rb);
    memset(pf->scratch, 0, wb);
    memset(pf->idx, 0, (size_t)pf->n * sizeof(uint32_t));
    return pft_pf_reset(pf);
}

pft_status_t pft_pf_reset(pft_pf_t *pf)
{
    if (pf == NULL || pf->x == NULL) {
        return PFT_ERR_INVAL;
    }
    const pft_pf_model_t *md = &pf->cfg.model;
    if (md->reset != NULL) {
        md->reset(md->ctx);
    }
    pft_rng_seed(&pf->rng, pf->cfg.seed);
    for (uint32_t i = 0; i < pf->n; ++i) {
        pft_real_t *xi = pf->x + (size_t)i * pf->dim;
        if (md->sample_prior != NULL) {
            md->sample_prior(md->ctx, xi, &pf->rng);
        } else {
            memset(xi, 0, (size_t)pf->dim * sizeof(pft_real_t));
        }
    }
    uniform_weights_(pf);
    memset(&pf->stats, 0, sizeof(pf->stats));
    pf->stats.ess_ratio = PFT_C(1.0);
    pf->stats.ess_first = PFT_C(1.0);
    estimate_(pf);
    return PFT_OK;
}

pft_status_t pft_pf_reseed(pft_pf_t *pf, uint64_t seed)
{
    if (pf == NULL || pf->x == NULL) {
        return PFT_ERR_INVAL;
    }
    pf->cfg.seed = seed;
    return pft_pf_reset(pf);
}

/* The resampling decision for the next update (step 5). */
static bool resample_next_(const pft_pf_t *pf)
{
    switch (policy_(&pf->cfg)) {
    case PFT_PF_RESAMPLE_ALWAYS:
        return true;
    case PFT_PF_RESAMPLE_ESS:
        return pf->stats.ess_ratio < pf->cfg.ess_threshold;
    default:
        return false;
    }
}

pft_status_t pft_pf_update(pft_pf_t *pf, const void *z)
{
    if (pf == NULL || pf->x == NULL) {
        return PFT_ERR_INVAL;
    }
    const pft_pf_model_t *md = &pf->cfg.model;
    if (md->begin != NULL) {
        pft_status_t st = md->begin(md->ctx, z);
        if (st != PFT_OK) {
            return st;
        }
    }
    bool resampled = false;
    if (pf->stats.resample_pending && pf->cfg.kind != PFT_PF_SIS) {
        resample_(pf);
        resampled = true;
    }
    pft_real_t lev = pf->cfg.kind == PFT_PF_APF ? step_apf_(pf, z) : step_bootstrap_(pf, z);
    estimate_(pf);
    pft_pf_stats_t *s = &pf->stats;
    if (s->step < UINT32_MAX) {
        ++s->step;
    }
    s->ess_ratio = pft_ess_ratio(pf->w, pf->n);
    if (pf->cfg.kind != PFT_PF_APF) {
        s->ess_first = s->ess_ratio;
    }
    s->log_evidence = lev;
    s->resampled = resampled;
    s->resample_pending = resample_next_(pf);
    return PFT_OK;
}

pft_status_t pft_pf_estimate(const pft_pf_t *pf, pft_real_t *est)
{
    if (pf == NULL || est == NULL || pf->x == NULL) {
        return PFT_ERR_INVAL;
    }
    memcpy(est, pf->est, (size_t)pf->dim * sizeof(pft_real_t));
    return PFT_OK;
}

pft_status_t pft_pf_mean_cov(const pft_pf_t *pf, pft_real_t *mean, pft_real_t *cov)
{
    if (pf == NULL || mean == NULL || pf->x == NULL) {
        return PFT_ERR_INVAL;
    }
    uint16_t d = pf->dim;
    pft_pf_weighted_mean(pf->x, pf->w, pf->n, d, mean);
    if (cov == NULL) {
        return PFT_OK;
    }
    /* one row of the upper triangle at a time: PFT_PF_MAX_DIM accumulators on the stack instead
     * of the whole triangle (1088 bytes of int64 in q16), the same sums in the same order */
    pft_acc_t_ acc[PFT_PF_MAX_DIM];
    pft_wacc_t wt = 0;
    for (uint32_t i = 0; i < pf->n; ++i) {
        wt += pf->w[i];
    }
    for (uint16_t a = 0; a < d; ++a) {
        for (uint16_t b = a; b < d; ++b) {
            acc[b] = PFT_ACC_ZERO_;
        }
        for (uint32_t i = 0; i < pf->n; ++i) {
            pft_weight_t wi = pf->w[i];
            if (wi == 0) {
                continue;
            }
            const pft_real_t *xi = pf->x + (size_t)i * d;
            pft_real_t da = pft_sub(xi[a], mean[a]);
            for (uint16_t b = a; b < d; ++b) {
                acc[b] += pft_acc_wx_(wi, pft_mul(da, pft_sub(xi[b], mean[b])));
            }
        }
        for (uint16_t b = a; b < d; ++b) {
            pft_real_t v = pft_acc_div_(acc[b], wt);
            cov[(size_t)a * d + b] = v;
            cov[(size_t)b * d + a] = v;
        }
    }
    return PFT_OK;
}

pft_status_t pft_pf_stats(const pft_pf_t *pf, pft_pf_stats_t *out)
{
    if (pf == NULL || out == NULL) {
        return PFT_ERR_INVAL;
    }
    *out = pf->stats;
    return PFT_OK;
}

size_t pft_pf_states(const pft_pf_t *pf, pft_real_t *out, size_t max)
{
    if (pf == NULL || pf->x == NULL) {
        return 0u;
    }
    size_t k = max < pf->n ? max : pf->n;
    if (out != NULL && k > 0u) {
        memcpy(out, pf->x, k * pf->dim * sizeof(pft_real_t));
    }
    return pf->n;
}

size_t pft_pf_weights(const pft_pf_t *pf, pft_weight_t *out, size_t max)
{
    if (pf == NULL || pf->x == NULL) {
        return 0u;
    }
    size_t k = max < pf->n ? max : pf->n;
    if (out != NULL && k > 0u) {
        memcpy(out, pf->w, k * sizeof(pft_weight_t));
    }
    return pf->n;
}

pft_status_t pft_pf_set_states(pft_pf_t *pf, const pft_real_t *x, size_t n)
{
    if (pf == NULL || x == NULL || pf->x == NULL || n != pf->n) {
        return PFT_ERR_INVAL;
    }
    memcpy(pf->x, x, n * pf->dim * sizeof(pft_real_t));
    estimate_(pf);
    return PFT_OK;
}

pft_status_t pft_pf_set_logweights(pft_pf_t *pf, const pft_real_t *lw)
{
    if (pf == NULL || lw == NULL || pf->x == NULL) {
        return PFT_ERR_INVAL;
    }
    memcpy(pf->lw, lw, (size_t)pf->n * sizeof(pft_real_t));
    (void)normalise_(pf);
    pf->stats.resample_pending = false;
    pf->stats.ess_ratio = pft_ess_ratio(pf->w, pf->n);
    estimate_(pf);
    return PFT_OK;
}
