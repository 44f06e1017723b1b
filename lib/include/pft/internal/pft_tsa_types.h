/*
 * NOT API. The layout of the TSA-AK tracker instance pft_tsa_t, published only so that a
 * firmware can declare instances statically (sizeof). The fields may change in any release:
 * read results through the calls of pft/pft_tsa.h, which includes this file.
 */
#ifndef PFT_INTERNAL_PFT_TSA_TYPES_H
#define PFT_INTERNAL_PFT_TSA_TYPES_H

#ifndef PFT_TSA_H
#error "include pft/pft_tsa.h (this layout is not API)"
#endif

typedef struct {
    pft_tsa_config_t cfg;
    pft_rng_t rng;
    pft_real_t *px, *py, *pvx, *pvy;  /* N + 1 (index N: pioneer); px is the aligned start of
                                         the workspace */
    pft_real_t *tx, *ty, *tvx, *tvy;  /* resampling copies, N */
    pft_real_t *rho;                  /* N + 1 */
    pft_weight_t *w;                  /* N + 1 */
    uint32_t *idx;                    /* N */
    pft_tsa_kernel_t kern, kern_alt;
    int32_t *cross;
    pft_tsa_pt_t *contour;            /* offsets from the kernel origin */
    pft_tsa_pt_t *cwork;              /* frame coordinates, snake work */
    uint8_t *bflags;
    void *snake_ws;
    size_t snake_ws_len;
    pft_tsa_hist_t q;                 /* template */
    pft_tsa_hist_t q0;                /* first template (drift anchor) */
    pft_tsa_hist_t h;                 /* scratch */
    pft_real_t ref_x[PFT_TSA_MOTION_MAX_K]; /* reference points of the fit, oldest first */
    pft_real_t ref_y[PFT_TSA_MOTION_MAX_K];
    pft_real_t ref_w[PFT_TSA_MOTION_MAX_K];
    uint32_t ref_n;
    pft_real_t beta;
    int64_t area2;                    /* twice the contour area */
    uint32_t n_state;                 /* particles in the state arrays: N, or N + 1 (pioneer) */
    uint32_t weak_run;
    pft_tsa_estimate_t est;
    bool started;
} pft_tsa_t;

#endif
