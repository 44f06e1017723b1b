/**
 * @file pft_pf_models.h
 * @brief Models for the particle-filter engine of pft_pf.h: the bearings-only
 *        constant-velocity benchmark (Gordon, Salmond & Smith 1993; docs/algorithms.md 3.1), a
 *        linear-Gaussian model (exact Kalman reference for tests) and the TBD pixel
 *        likelihood of pft_tbd.h (so the SIS / SIR / APF engines run as track-before-detect
 *        filters).
 *
 * Each model is an instance struct the caller declares; pft_xxx_model_init() checks the
 * configuration, precomputes constants and fills a pft_pf_model_t whose ctx points at the
 * instance (which must therefore outlive the engine and not move).
 */
#ifndef PFT_PF_MODELS_H
#define PFT_PF_MODELS_H

#include "pft/pft_pf.h"
#include "pft/pft_tbd.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Model instances: declared by the caller, layouts in pft/internal/pft_pf_models_types.h (not
 * API; included at the end of this header so that sizeof works). */
/** Instance of the bearings-only model (pft_pf_bearings_model_init). */
typedef struct pft_pf_bearings_model_s pft_pf_bearings_model_t;
/** Instance of the linear-Gaussian model (pft_pf_lg_model_init). */
typedef struct pft_pf_lg_model_s pft_pf_lg_model_t;
/** Instance of the TBD pixel-likelihood model (pft_pf_tbd_model_init). */
typedef struct pft_pf_tbd_model_s pft_pf_tbd_model_t;

/* ============================ bearings-only constant velocity ============================= */

/** State layout of the bearings model: [x, vx, y, vy]. */
enum { PFT_PF_BRG_X = 0, PFT_PF_BRG_VX = 1, PFT_PF_BRG_Y = 2, PFT_PF_BRG_VY = 3, PFT_PF_BRG_DIM = 4 };

/**
 * Bearings-only tracking with a constant-velocity target (docs/algorithms.md 3.1):
 *   x_k = Phi x_{k-1} + Gamma w,  w ~ N(0, q I2),  Phi, Gamma the CV matrices of period T,
 *   z_k = atan2(y_k, x_k) + v,     v ~ N(0, r).
 * Log-likelihood: with e = z - atan2(y, x) wrapped to (-pi, pi] and s = |e| / sqrt(r),
 *   ll = -s^2 / 2                     for s <= ll_clip,
 *   ll = -(ll_clip s - ll_clip^2 / 2)  beyond (the tangent continuation, so a particle far
 *                                      out still ranks by distance instead of saturating).
 * Beyond ll_clip standard deviations the Gaussian weight is below exp(-ll_clip^2/2)
 * (exp(-1250) for the default 50), so the continuation changes nothing unless every particle
 * is that far out. It keeps |ll| <= ll_clip * pi / sqrt(r) (31416 for the defaults), inside
 * the q16 range; the same likelihood is used in both builds. The scaled innovation s is
 * formed before squaring, so no intermediate exceeds the range either.
 *
 * Units and the q16 build. The benchmark's quantities are tiny (sqrt(q) = 0.001,
 * sqrt(r) = 0.005, velocities 0.001..0.05) against the Q16.16 resolution of 1.5e-5, so the
 * model works in scaled position units: pft_pf_bearings_config_default(cfg, scale) expresses all
 * positions and velocities in benchmark units times `scale` (e.g. 1000: "km -> m"). Bearings
 * are scale-invariant (atan2 of the scaled position is the same angle) and stay in radians. The
 * scale must keep every position within +-32768: for the benchmark's prior (sd 0.5) and 24
 * steps, scale <= 4000; 1000 is the documented choice (docs/results/apf.md measures the
 * q16-vs-float difference at scale 1 and 1000).
 */
typedef struct {
    pft_real_t T;             /**< period (default 1) */
    pft_real_t q_sd;          /**< sqrt(q), acceleration noise per step in state units (default 0.001 * scale) */
    pft_real_t r_sd;          /**< sqrt(r), bearing noise in radians (default 0.005) */
    pft_real_t prior_mean[4]; /**< prior mean [x, vx, y, vy] (default [0, 0, 0.4, -0.05] * scale) */
    pft_real_t prior_sd[4];   /**< prior standard deviations, diagonal (default [0.5, 0.005, 0.3, 0.01] * scale) */
    pft_real_t ll_clip;       /**< standardised innovation where the log-likelihood turns linear (default 50) */
    pft_real_t first_r_sd;    /**< APF first stage: bearing sd used at the predicted point
                                   (0, the default: r_sd, i.e. Pitt & Shephard's p(z | mu));
                                   a larger value widens the first-stage likelihood */
} pft_pf_bearings_config_t;

/** Fills cfg with the benchmark's values in units of 1/scale of the benchmark's (scale >= 1;
 *  each value is an exact integer ratio, so e.g. scale 1000 gives q_sd = 1 exactly). */
void pft_pf_bearings_config_default(pft_pf_bearings_config_t *cfg, int32_t scale);

/** Checks cfg (T, q_sd, r_sd, ll_clip at least 2^-16, sds non-negative, first_r_sd 0 or at least
 *  2^-16, every real within +-32767: the configuration domain of both builds), fills m and
 *  the interface iface, e.g. &engine_cfg.model (measurement: const pft_real_t *, one bearing in
 *  radians). PFT_ERR_INVAL on NULL, PFT_ERR_CONFIG for a refused cfg. */
pft_status_t pft_pf_bearings_model_init(pft_pf_bearings_model_t *m, const pft_pf_bearings_config_t *cfg,
                                     pft_pf_model_t *iface);

/** Bearing innovation z - atan2(y, x) of a state, wrapped to (-pi, pi]. */
pft_real_t pft_pf_bearings_innovation(const pft_real_t *x, pft_real_t z);

/** Log-likelihood of bearing z for state x (the model's loglik, for tests and tools). */
pft_real_t pft_pf_bearings_loglik(const pft_pf_bearings_model_t *m, const pft_real_t *x, pft_real_t z);

/* ===================================== linear Gaussian ==================================== */

/** Largest state dimension of the linear-Gaussian model. */
#define PFT_PF_LG_MAX_DIM 4u
/** Largest measurement dimension of the linear-Gaussian model. */
#define PFT_PF_LG_MAX_MEAS 2u

/**
 * Linear-Gaussian model x_k = F x_{k-1} + Lq g (g ~ N(0, I)), z_k = H x_k + v with
 * v ~ N(0, diag(r_sd^2)); prior x_0 = m0 + L0 g. Matrices row-major with row length dim
 * (H: meas rows of dim). Log-likelihood -sum_k ((z_k - (H x)_k) / r_sd_k)^2 / 2 (the
 * Gaussian's constant -sum_k log(sqrt(2 pi) r_sd_k) is dropped). The exact posterior is the
 * Kalman filter's, which makes it the reference model of the engine's unit tests.
 * Measurement: const pft_real_t * of meas values.
 */
typedef struct {
    uint16_t dim;                                     /**< 1..PFT_PF_LG_MAX_DIM */
    uint16_t meas;                                    /**< 1..PFT_PF_LG_MAX_MEAS */
    pft_real_t F[PFT_PF_LG_MAX_DIM * PFT_PF_LG_MAX_DIM];    /**< transition, dim x dim */
    pft_real_t Lq[PFT_PF_LG_MAX_DIM * PFT_PF_LG_MAX_DIM];   /**< process-noise factor, dim x dim */
    pft_real_t H[PFT_PF_LG_MAX_MEAS * PFT_PF_LG_MAX_DIM];   /**< measurement matrix, meas x dim */
    pft_real_t r_sd[PFT_PF_LG_MAX_MEAS];                 /**< measurement noise sds (> 0) */
    pft_real_t m0[PFT_PF_LG_MAX_DIM];                    /**< prior mean */
    pft_real_t L0[PFT_PF_LG_MAX_DIM * PFT_PF_LG_MAX_DIM];   /**< prior factor, dim x dim */
} pft_pf_lg_config_t;

/** Checks cfg, fills m and iface. PFT_ERR_INVAL on NULL, PFT_ERR_CONFIG for bad dimensions,
 *  r_sd below 2^-16, or a real of the used part of the matrices or the prior outside
 *  +-32767 (the configuration domain of both builds). */
pft_status_t pft_pf_lg_model_init(pft_pf_lg_model_t *m, const pft_pf_lg_config_t *cfg,
                               pft_pf_model_t *iface);

/* ================================ TBD pixel likelihood ==================================== */

/** State layout of the TBD model: [x, vx, y, vy, I, E], positions in the 0-based pixel
 *  coordinates of pft_tbd.h. E is 0 (no target), 1 (target) or 2 (born at this step: a target
 *  whose log-likelihood also gets the birth correction). */
enum {
    PFT_PF_TBD_X = 0, PFT_PF_TBD_VX = 1, PFT_PF_TBD_Y = 2, PFT_PF_TBD_VY = 3, PFT_PF_TBD_I = 4,
    PFT_PF_TBD_E = 5, PFT_PF_TBD_DIM = 6
};

/**
 * The single-target TBD model of docs/algorithms.md 1 and 2.9 (the bootstrap PF-TBD's) as an
 * engine model: existence Markov chain (pb, pd; eta on the first frame), births proposed
 * uniformly from the pixels above gamma (all pixels when none is) with uniform sub-pixel
 * position, intensity ~ U[i_min, i_max], velocity ~ N(vel_mean, vel_var); survivors move with
 * the full CV process noise chol(V) and the intensity random walk; a target whose window
 * centre leaves the image gets E = 0 (it left the surveillance region). The log-likelihood is
 * the windowed pixel log likelihood ratio of pft_tbd.h, evaluated by the tbd filters' kernel
 * (the tabulated 3 x 3 window for p = 1, on the whitened frame), for E != 0 and 0 for E = 0
 * (plus log(|B_k| / A_allow) for births when cfg.birth_correction). The APF's
 * predicted point moves the kinematic part by Phi (it is kept in the tbd module's internal
 * frame and scored by the model's loglik_first). The estimate is
 * [mean of x, vx, y, vy, I over the E != 0 particles, P(E != 0)] (the kinematic part keeps
 * its last value while no particle has E != 0).
 *
 * With the SIR engine (systematic resampling every step) this is the bootstrap PF-TBD of the
 * tbd module: the same draws per particle from the same state (the engine normalises and
 * resamples its own way, so the two runs agree on the first frame and in distribution after);
 * with the APF engine it is the APF-TBD. Measurement: const pft_frame_t * (formats and conversion as pft_tbd.h); a frame
 * of the wrong size or format is refused by begin (the engine then changes nothing).
 * Fields of cfg that belong to the tbd manager (theta1, disappearance, sizes, kind) are
 * ignored.
 */
/** Workspace bytes of the TBD model for a w x h image (constant expression). */
#define PFT_PF_TBD_WORKSPACE_BYTES(w, h)                                                          \
    ((size_t)(PFT_WS_ALIGN - 1u) +                                                              \
     PFT_WS_ROUND(((size_t)(w) + 2u) * ((size_t)(h) + 2u) * sizeof(pft_real_t)) +                 \
     PFT_WS_ROUND((size_t)(w) * (size_t)(h) * sizeof(uint32_t)) + PFT_WS_ROUND(sizeof(pft_tbd_tab_t)))

/** Workspace bytes pft_pf_tbd_model_init needs for cfg (0 for NULL or a refused cfg). */
size_t pft_pf_tbd_model_workspace_size(const pft_tbd_config_t *cfg);

/** Checks cfg (pft_tbd_config_check), carves the image buffers, fills m and iface (whose reset
 *  hook starts a new sequence: pft_pf_reset makes the next frame a first frame again, births
 *  with probability eta). PFT_ERR_INVAL for NULL, PFT_ERR_CONFIG for a refused cfg,
 *  PFT_ERR_NOMEM for a short workspace. */
pft_status_t pft_pf_tbd_model_init(pft_pf_tbd_model_t *m, const pft_tbd_config_t *cfg, void *work,
                                 size_t work_len, pft_pf_model_t *iface);

/**
 * Birth budget of the TBD model (docs/algorithms.md 3.4; default 0: off, the model as above).
 * With budget K > 0 the births of a step are proposed in a fixed number instead of by one
 * Bernoulli(pb) draw per E = 0 particle, so that about K particles are weighed on the pixels
 * at every step whatever the existence probability: with n1 particles of E != 0 and n0 of
 * E = 0 before the step (counted by the interface's prepare hook), exactly
 * b = min(max(K - n1, ceil(pb n0), 1), n0 - 1) E = 0 particles, chosen uniformly without
 * replacement, propose a birth (q = b / n0 each) and the others stay at E = 0; the weights are
 * corrected by the proposal ratio, pb / q for a birth and (1 - pb) / (1 - q) for one that
 * stays (pb: eta on a first frame, quantised to 1/65536 as the draw it replaces), so the
 * weighted set targets the same posterior as without the budget (importance sampling of the
 * existence transition). Survivors are unchanged. A step with fewer than 2 E = 0 particles,
 * no birth candidate or pb of 0 or 1 runs without the budget. The work per step is then
 * about max(K, n1 + b) weighed particles (at most N, as without the budget). PFT_ERR_INVAL
 * for NULL. Call after pft_pf_tbd_model_init (which sets 0), before the engine runs.
 */
pft_status_t pft_pf_tbd_model_set_budget(pft_pf_tbd_model_t *m, uint32_t budget);

#ifdef __cplusplus
}
#endif

#include "pft/internal/pft_pf_models_types.h"
#endif
