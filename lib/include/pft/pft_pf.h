/**
 * @file pft_pf.h
 * @brief Generic particle-filter engine: SIS, SIR and the auxiliary particle filter (APF)
 *        over one model interface (docs/algorithms.md 3; Gordon, Salmond & Smith 1993; Pitt &
 *        Shephard 1999; Wang 2010).
 *
 * A model is a struct of function pointers plus a context (pft_pf_model_t): propagate one
 * particle through the dynamics, log likelihood of a measurement, the predicted point used
 * by the APF's first stage, and optional hooks (prior draw, per-measurement preparation,
 * state-estimate reduction). The engine owns the particle set, the log-weights, the RNG and
 * the resampling; the model owns nothing of the particle set. pft_pf_models.h has three
 * models: the bearings-only constant-velocity benchmark, a linear-Gaussian model (tests,
 * Kalman comparisons) and the TBD pixel likelihood of pft_tbd.h.
 *
 * One update (pft_pf_update), with z the measurement of this step:
 *  0. model->begin(ctx, z) if set (may refuse z: then nothing at all has changed);
 *  1. a resampling decided at the end of the previous update is carried out now (SIR, and
 *     APF with a post-resampling policy): indices from the normalised weights with
 *     cfg.scheme, states copied, log-weights reset to -log N;
 *  2. model->prepare(ctx, x, N) if set; then
 *     SIS / SIR: every particle is propagated in place and its log-weight increased by
 *     loglik(x, z) (the bootstrap proposal).
 *     APF: first stage mu_i = predict(x_i), fl_i = loglik_first(mu_i, z) (loglik when
 *     NULL), first-stage weights lambda_i ~ w_i exp(fl_i); N indices j_m ~ lambda by
 *     cfg.scheme; x_m = propagate(copy of x_{j_m}); second stage
 *     log w_m = loglik(x_m, z) - fl_{j_m}. The previous weight w_{j_m} is NOT applied again
 *     (it is already in lambda): the second-stage weight is the likelihood ratio only.
 *  3. log-sum-exp normalisation; the log-weights are kept normalised (log sum exp = 0) and
 *     floored at PFT_PF_LW_FLOOR, far below anything that yields a non-zero weight;
 *  4. the estimate (model->estimate, or the weighted mean of each state component) from the
 *     weighted set, before any resampling;
 *  5. the ESS / N ratio, and the resampling decision for the next update:
 *     PFT_PF_RESAMPLE_ALWAYS (every step), _ESS (when ESS / N < cfg.ess_threshold), _NEVER.
 *     SIS never resamples whatever the policy.
 * Deferring the resampling (step 1) means that between updates the engine always holds the
 * weighted particle set of the last update, so pft_pf_mean_cov sees the lower-variance
 * pre-resampling weights; the sequence of operations is the textbook one.
 *
 * Log evidence: every update also returns log p^(z_k | z_1..k-1), the engine's estimate of
 * the measurement's predictive likelihood (SIS / SIR: log sum_i W_i exp(ll_i); APF:
 * log sum_i W_i exp(fl_i) + log mean_m exp(ll_m - fl_{j_m})), in the model's log-likelihood
 * units (constants the model drops are dropped here too).
 *
 * Number formats (q16 build): states and log-likelihoods are Q16.16 pft_real_t, weights
 * Q2.30 (pft_weight_t). Log-weights are normalised every step, so they stay <= 0; a model's
 * log-likelihood must stay within +-32768 (bearings and TBD models saturate by design, see
 * pft_pf_models.h). The weighted mean is accumulated in int64 (weight x state, < 2^61) and
 * rounded once; covariances square Q16.16 differences with pft_mul, so an entry saturates
 * at 32768 (state units squared): choose state units accordingly (pft_pf_models.h).
 *
 * Determinism: the engine owns one pft_rng_t, seeded from cfg.seed (pft_pf_reset reseeds);
 * the model draws from it through the rng argument. Float and q16 builds consume the same
 * integer stream as long as the model draws the same number of values.
 *
 * Memory: all buffers live in the caller workspace (PFT_PF_WORKSPACE_BYTES, equal to
 * pft_pf_workspace_size). No callback may keep pointers to the particle arrays.
 *
 * Calls, in the order of use (docs/design.md, "One API pattern for every tracker"):
 * pft_pf_config_default, set kind, n_particles and the model (cfg.model, e.g. from
 * pft_pf_bearings_model_init), pft_pf_config_check, pft_pf_workspace_size, pft_pf_init,
 * pft_pf_update per measurement, results copied out (pft_pf_estimate, pft_pf_mean_cov,
 * pft_pf_stats, pft_pf_states, pft_pf_weights), pft_pf_reset (or pft_pf_reseed) to start over.
 * pft_pf_set_states and pft_pf_set_logweights are the explicit write access (a known initial
 * set).
 */
#ifndef PFT_PF_H
#define PFT_PF_H

#include "pft/pft_real.h"
#include "pft/pft_rng.h"
#include "pft/pft_resample.h"
#include "pft/pft_workspace.h"

#ifdef __cplusplus
extern "C" {
#endif

/** The engine instance: declared by the caller, layout in pft/internal/pft_pf_types.h (not
 *  API; included at the end of this header so that sizeof works). */
typedef struct pft_pf_s pft_pf_t;

/** Largest state dimension the engine accepts (bounds the per-particle scratch). */
#define PFT_PF_MAX_DIM 16u
/** Floor of the normalised log-weights (weights below exp(-21.5) are already 0 in q16 and
 *  below exp(-104) in float; the floor only keeps sums away from saturation). */
#define PFT_PF_LW_FLOOR PFT_C(-16384.0)

/**
 * The model interface. State vectors are dim consecutive pft_real_t. Every callback gets
 * ctx first. Required: propagate and loglik. predict is required by the APF only.
 */
typedef struct {
    uint16_t dim; /**< state dimension, 1..PFT_PF_MAX_DIM */
    void *ctx;    /**< the model's own data (configuration, precomputed constants, buffers) */
    /** Optional: called once per update, before anything else, with the measurement. May
     *  precompute measurement-dependent data in ctx, or refuse z (a negative status is
     *  returned by pft_pf_update; the particle set is then untouched). */
    pft_status_t (*begin)(void *ctx, const void *z);
    /** Optional: draws x from the prior (pft_pf_init / pft_pf_reset). NULL: all states 0. */
    void (*sample_prior)(void *ctx, pft_real_t *x, pft_rng_t *rng);
    /** Required: x <- a draw from p(x_k | x_{k-1} = x), in place. */
    void (*propagate)(void *ctx, pft_real_t *x, pft_rng_t *rng);
    /** Required: log p(z | x) up to a constant independent of x (<= 0 preferred; q16: within
     *  +-32768). */
    pft_real_t (*loglik)(void *ctx, const pft_real_t *x, const void *z);
    /** APF: the predicted point mu = E[x_k | x_{k-1} = x] (or another characteristic point;
     *  any choice gives a consistent filter since the second stage divides it out). */
    void (*predict)(void *ctx, const pft_real_t *x, pft_real_t *mu);
    /** Optional, APF: first-stage log-likelihood at mu (e.g. with a widened noise); NULL uses
     *  loglik. The same value is divided out in the second stage. */
    pft_real_t (*loglik_first)(void *ctx, const pft_real_t *mu, const void *z);
    /** Optional: reduces the weighted set (n particles at x[i*dim], normalised weights w)
     *  to an estimate of dim values in est. NULL: the weighted mean of each component. */
    void (*estimate)(void *ctx, const pft_real_t *x, const pft_weight_t *w, uint32_t n,
                     pft_real_t *est);
    /** Optional: called by pft_pf_init, pft_pf_reset and pft_pf_reseed before the prior is
     *  drawn: the model forgets what it kept from earlier measurements (e.g. the TBD model's
     *  frame count, so the next frame is a first frame again). */
    void (*reset)(void *ctx);
    /** Optional: called once per update just before the first propagate, with the n
     *  particles about to be propagated (SIS / SIR: the set after step 1's resampling; APF:
     *  the chosen parents copies x_{j_m}). Read only; the model may count them to plan the
     *  step's proposal (e.g. the TBD model's birth budget, pft_pf_tbd_model_set_budget). The
     *  engine then calls propagate(x_i) immediately followed by loglik(x_i) for i = 0..n-1. */
    void (*prepare)(void *ctx, const pft_real_t *x, uint32_t n);
} pft_pf_model_t;

/** Engine. */
typedef enum {
    PFT_PF_SIS = 0, /**< sequential importance sampling, no resampling ("basic PF") */
    PFT_PF_SIR = 1, /**< sampling importance resampling, bootstrap proposal ("resampling PF") */
    PFT_PF_APF = 2  /**< auxiliary particle filter (first stage at the predicted point) */
} pft_pf_kind_t;

/** When the set is resampled after an update (carried out at the start of the next). */
typedef enum {
    PFT_PF_RESAMPLE_ALWAYS = 0, /**< every update */
    PFT_PF_RESAMPLE_ESS = 1,    /**< when ESS / N < ess_threshold */
    PFT_PF_RESAMPLE_NEVER = 2,  /**< never (APF: the first-stage index sampling only) */
    PFT_PF_RESAMPLE_AUTO = 3    /**< the kind's own: SIR ALWAYS, APF ESS (docs/algorithms.md 3.2
                                     step 7), SIS NEVER */
} pft_pf_policy_t;

/** Engine configuration; pft_pf_config_default fills it. */
typedef struct {
    pft_pf_kind_t kind;            /**< engine (default PFT_PF_SIR) */
    uint32_t n_particles;          /**< N, 1..PFT_CFG_MAX_PARTICLES (default 1000) */
    pft_resample_scheme_t scheme;  /**< resampling and APF index sampling (default systematic) */
    pft_pf_policy_t policy;        /**< default PFT_PF_RESAMPLE_AUTO; SIS never resamples whatever
                                        the policy */
    pft_real_t ess_threshold;      /**< fraction of N for PFT_PF_RESAMPLE_ESS, in (0, 1] (default 0.5) */
    uint64_t seed;                 /**< RNG seed (default 1) */
    pft_pf_model_t model;          /**< the model (default: all zero, which config_check refuses:
                                        fill it, e.g. with pft_pf_bearings_model_init). Copied by
                                        init; model.ctx must outlive the engine. */
} pft_pf_config_t;

/** Statistics of the last update. */
typedef struct {
    uint32_t step;            /**< updates accepted so far */
    pft_real_t ess_ratio;     /**< ESS / N of the weights after the update, in [1/N, 1] */
    pft_real_t ess_first;     /**< APF: ESS / N of the first-stage weights lambda (the index
                                   sampling's diversity); SIS / SIR: equal to ess_ratio */
    pft_real_t log_evidence;  /**< log p^(z_k | z_1..k-1) (see the file comment) */
    bool resampled;           /**< a pending resampling was carried out at the start of it */
    bool resample_pending;    /**< the next update starts with a resampling */
} pft_pf_stats_t;

/** Workspace bytes for n particles of dimension dim (constant expression). */
#define PFT_PF_WORKSPACE_BYTES(n, dim)                                                          \
    ((size_t)(PFT_WS_ALIGN - 1u) +                                                              \
     2u * PFT_WS_ROUND((size_t)(n) * (size_t)(dim) * sizeof(pft_real_t)) +                      \
     2u * PFT_WS_ROUND((size_t)(n) * sizeof(pft_real_t)) +                                      \
     2u * PFT_WS_ROUND((size_t)(n) * sizeof(pft_weight_t)) +                                    \
     PFT_WS_ROUND((size_t)(n) * sizeof(uint32_t)))

/** Fills every field of cfg with its default (see pft_pf_config_t); set kind, n_particles
 *  and model after. */
void pft_pf_config_default(pft_pf_config_t *cfg);

/**
 * PFT_OK if cfg is usable; PFT_ERR_INVAL for NULL cfg; PFT_ERR_CONFIG otherwise, and then
 * *field (when field is not NULL) names the first refused field: "kind", "n_particles",
 * "scheme", "policy", "ess_threshold", "model.dim", "model.propagate", "model.loglik",
 * "model.predict" (required by the APF). *field is NULL on success.
 */
pft_status_t pft_pf_config_check(const pft_pf_config_t *cfg, const char **field);

/** Workspace bytes pft_pf_init needs, PFT_PF_WORKSPACE_BYTES(cfg->n_particles, cfg->model.dim);
 *  0 for a NULL or refused cfg. */
size_t pft_pf_workspace_size(const pft_pf_config_t *cfg);

/**
 * Initialises the engine: copies cfg (the model struct included), carves the workspace,
 * calls the model's reset hook, seeds the RNG with cfg.seed and draws the prior.
 * @return PFT_ERR_INVAL for NULL arguments, PFT_ERR_CONFIG for a refused cfg (nothing
 *         written), PFT_ERR_NOMEM for a short workspace (the instance is then zeroed).
 */
pft_status_t pft_pf_init(pft_pf_t *pf, const pft_pf_config_t *cfg, void *work, size_t work_len);

/** Back to the state right after pft_pf_init: the model's reset hook, the RNG reseeded with
 *  cfg.seed, every particle drawn from the prior (zeros without sample_prior), uniform
 *  weights, statistics cleared. PFT_ERR_INVAL for NULL or an uninitialised engine. */
pft_status_t pft_pf_reset(pft_pf_t *pf);

/** pft_pf_reset with another seed (kept as the engine's seed from then on): one engine for
 *  many Monte Carlo runs. */
pft_status_t pft_pf_reseed(pft_pf_t *pf, uint64_t seed);

/**
 * One step with measurement z (its type is the model's business; it is passed through to
 * begin, loglik and loglik_first). Returns the model's begin status when it refuses z (the
 * engine is then unchanged), PFT_ERR_INVAL for NULL pf.
 */
pft_status_t pft_pf_update(pft_pf_t *pf, const void *z);

/** Copies the estimate of the last update (dim values; the prior's weighted mean before the
 *  first update). */
pft_status_t pft_pf_estimate(const pft_pf_t *pf, pft_real_t *est);

/**
 * Weighted mean (dim values) and, when cov is not NULL, weighted covariance (dim * dim,
 * row-major, exactly symmetric) of the current particle set, sum_i w_i (x_i - m)(x_i - m)'.
 * q16: entries saturate at +-32768.
 */
pft_status_t pft_pf_mean_cov(const pft_pf_t *pf, pft_real_t *mean, pft_real_t *cov);

/** Statistics of the last update. */
pft_status_t pft_pf_stats(const pft_pf_t *pf, pft_pf_stats_t *out);

/** Copies the states of the first min(N, max) particles (dim values each, particle i at
 *  out[i * dim]) into out; returns N (out may be NULL with max 0 to ask it; 0 for NULL pf). */
size_t pft_pf_states(const pft_pf_t *pf, pft_real_t *out, size_t max);
/** Copies the normalised weights of the first min(N, max) particles; returns N. */
size_t pft_pf_weights(const pft_pf_t *pf, pft_weight_t *out, size_t max);

/**
 * Replaces the particle states by x[0 .. n * dim) (e.g. a known initial set; n must be the
 * engine's N) and recomputes the estimate; the weights are kept. PFT_ERR_INVAL for NULL
 * arguments or another n (nothing changed then).
 */
pft_status_t pft_pf_set_states(pft_pf_t *pf, const pft_real_t *x, size_t n);

/**
 * Replaces the weights by the normalisation of the log-weights lw[0..n) (e.g. a non-uniform
 * initial set) and cancels a pending resampling. PFT_ERR_INVAL for NULL arguments.
 */
pft_status_t pft_pf_set_logweights(pft_pf_t *pf, const pft_real_t *lw);

/** Weighted mean of each of the dim components of n states (x[i * dim + c]) with normalised
 *  weights w (sum PFT_W_ONE), into mean; the default estimate, usable by model reductions.
 *  q16: int64 accumulation, one rounding. */
void pft_pf_weighted_mean(const pft_real_t *x, const pft_weight_t *w, uint32_t n, uint16_t dim,
                          pft_real_t *mean);

#ifdef __cplusplus
}
#endif

#include "pft/internal/pft_pf_types.h"
#endif
