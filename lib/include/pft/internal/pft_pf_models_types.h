/*
 * NOT API. The layouts of the particle-filter engine's model instances, here only so that a
 * firmware can declare them statically (sizeof). Fields may change in any release. Included by
 * pft/pft_pf_models.h; do not include it directly.
 */
#ifndef PFT_INTERNAL_PF_MODELS_TYPES_H
#define PFT_INTERNAL_PF_MODELS_TYPES_H

#ifndef PFT_PF_MODELS_H
#error "pft/internal/pft_pf_models_types.h is included by pft/pft_pf_models.h; include that instead"
#endif

#ifdef __cplusplus
extern "C" {
#endif

/* Bearings-only model. */
struct pft_pf_bearings_model_s {
    pft_pf_bearings_config_t cfg;
    pft_real_t inv_r;       /* 1 / r_sd */
    pft_real_t inv_r_first; /* 1 / first-stage sd */
    pft_real_t half_clip2;  /* ll_clip^2 / 2 */
    pft_real_t pos_gain;    /* T^2/2 * q_sd */
    pft_real_t vel_gain;    /* T * q_sd */
};

/* Linear-Gaussian model. */
struct pft_pf_lg_model_s {
    pft_pf_lg_config_t cfg;
    pft_real_t inv_r[PFT_PF_LG_MAX_MEAS];
};

/* TBD pixel model. */
struct pft_pf_tbd_model_s {
    pft_tbd_config_t cfg;
    pft_tbd_meas_t m;
    pft_real_t *img;       /* converted frame, whitened with a zero border (workspace) */
    uint32_t *cand;        /* birth candidate pixels (workspace) */
    pft_tbd_tab_t *tab;    /* PSF tap tables (workspace) */
    pft_real_t gamma_w;    /* birth threshold on the whitened frame */
    uint32_t n_cand;
    uint32_t frames;       /* frames accepted since init / reset */
    pft_real_t birth_lw;   /* birth correction of the current frame */
    pft_tbd_dyn_t dyn;     /* the tbd module's PF-TBD constants */
    pft_real_t last[5];    /* last kinematic estimate [x, vx, y, vy, I] */
    /* birth budget (pft_pf_tbd_model_set_budget; 0: off) and the plan of the current step */
    uint32_t budget;
    bool plan_on;          /* this step draws a fixed number of births */
    uint32_t n0, nb;       /* E = 0 particles before the step, births to draw among them */
    uint32_t seen0, sel0;  /* E = 0 particles propagated so far, births drawn so far */
    pft_real_t lc_born, lc_stay; /* log weight corrections of a birth / an E = 0 that stays */
    const pft_real_t *pend_x;    /* the particle last propagated, its correction pending */
    pft_real_t pend_c;
};

#ifdef __cplusplus
}
#endif
#endif
