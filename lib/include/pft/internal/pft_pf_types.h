/*
 * NOT API. The layout of the particle-filter engine instance, here only so that a firmware can
 * declare instances statically (sizeof). Fields may change in any release: read results with
 * the calls of pft/pft_pf.h. Included by pft/pft_pf.h; do not include it directly.
 */
#ifndef PFT_INTERNAL_PF_TYPES_H
#define PFT_INTERNAL_PF_TYPES_H

#ifndef PFT_PF_H
#error "pft/internal/pft_pf_types.h is included by pft/pft_pf.h; include that instead"
#endif

#ifdef __cplusplus
extern "C" {
#endif

/* The engine instance (private fields). */
struct pft_pf_s {
    pft_pf_config_t cfg;   /* copy of the configuration, the model included */
    uint32_t n;
    uint16_t dim;
    pft_real_t *x;         /* n * dim states (current set) */
    pft_real_t *x_alt;     /* n * dim states (next set) */
    pft_real_t *lw;        /* normalised log-weights */
    pft_real_t *fl;        /* APF first-stage log-likelihoods */
    pft_weight_t *w;       /* normalised weights */
    pft_weight_t *scratch; /* resampling scratch (residual) */
    uint32_t *idx;         /* resampling indices */
    pft_real_t log_n;      /* log N */
    pft_rng_t rng;
    pft_pf_stats_t stats;
    pft_real_t est[PFT_PF_MAX_DIM];
};

#ifdef __cplusplus
}
#endif
#endif
