/*
 * NOT API. The layouts of the TBD instances (measurement model constants, filter, manager),
 * here only so that a firmware can declare them statically (sizeof). Fields may change in any
 * release: read results with the calls of pft/pft_tbd.h. Included by pft/pft_tbd.h; do not
 * include it directly.
 */
#ifndef PFT_INTERNAL_TBD_TYPES_H
#define PFT_INTERNAL_TBD_TYPES_H

#ifndef PFT_TBD_H
#error "pft/internal/pft_tbd_types.h is included by pft/pft_tbd.h; include that instead"
#endif

#ifdef __cplusplus
extern "C" {
#endif

/* Derived constants of the measurement model (pft_tbd_meas_init). */
struct pft_tbd_meas_s {
    uint16_t width, height;
    uint8_t p;               /* window half-size */
    pft_real_t dx, dy;
    pft_real_t inv_dx, inv_dy;
    pft_real_t c0;           /* dx*dy/(2 pi S^2): h = I*c0*gx*gy */
    pft_real_t inv_2s2;      /* 1/(2 S^2) */
    pft_real_t inv_s2n;      /* 1/sigma^2 */
};

/* SoA particle arrays (RBPF uses all, PF leaves px/py NULL). */
typedef struct {
    pft_real_t *x, *y, *in; /* position and intensity */
    pft_real_t *mx, *my;    /* RBPF: Kalman velocity means; PF: sampled velocities */
    pft_real_t *px, *py;    /* RBPF: Kalman velocity variances (P stays diagonal) */
    uint8_t *e;             /* existence E */
} pft_tbd_particles_t;

/* Constants of the PF-TBD dynamics, births and existence chain (shared by the filters and the
 * pf engine's TBD model). */
typedef struct {
    pft_real_t ch_pos, ch_cross, ch_vel, ch_int; /* chol(V) per axis, sqrt(q2 T) */
    pft_real_t vel_sd[2];                        /* sqrt(P0) */
    uint32_t p16_b, p16_d, p16_eta;              /* probabilities in 1/65536 steps (0..65536) */
} pft_tbd_dyn_t;

/* One TBD filter (a single target with existence): standalone, or a layer of the manager. */
struct pft_tbd_filter_s {
    pft_tbd_config_t cfg;
    pft_tbd_kind_t kind;
    uint32_t n;              /* particles */
    bool births;             /* births from E = 0 allowed (false in track layers) */
    bool constrain;          /* force E = 0 inside the exclusion mask (search layer) */
    pft_tbd_particles_t cur, nxt;
    pft_real_t *lw;
    pft_weight_t *w;
    uint32_t *idx;
    pft_real_t *img;         /* standalone only: converted frame */
    uint8_t *mask;           /* standalone only: exclusion mask */
    uint32_t *cand;          /* standalone only: birth candidate pixels */
    /* derived constants */
    pft_tbd_meas_t model;
    pft_real_t log_n;        /* log N */
    pft_real_t log_ratio;    /* log dis_ratio */
    pft_real_t kf_qpos;      /* q1 T^3 / 3 */
    pft_real_t kf_qvel;      /* q1 T (paper) or q1 T / 4 (exact) */
    pft_tbd_dyn_t dyn;       /* PF dynamics, births, existence probabilities */
    pft_real_t birth_lw;     /* birth log-weight correction of the current frame */
    pft_rng_t rng;
    uint32_t frames;         /* accepted updates */
    pft_tbd_estimate_t est;
    /* disappearance statistic */
    pft_real_t lr_hist[PFT_TBD_MAX_DIS_R + 1u]; /* last log mean LRs (newest first) */
    pft_real_t win_hist[PFT_TBD_MAX_DIS_PREV];  /* previous window statistics (newest first) */
    uint32_t n_lr, n_win;
    bool gone;               /* disappearance declared at the last update */
};

/* The multi-target manager (docs/algorithms.md 2.7). */
struct pft_tbd_s {
    pft_tbd_config_t cfg;
    pft_tbd_filter_t search;
    pft_tbd_filter_t *tracks;    /* max_targets slots (workspace) */
    pft_tbd_track_t *records;    /* max_targets slots (workspace); id 0 marks a free slot */
    pft_tbd_event_t *events;     /* max_targets + 1 (workspace) */
    uint32_t n_events;
    pft_real_t *img;
    uint8_t *mask;
    uint32_t *cand;
    pft_real_t *res;             /* residual frame (joint likelihood, cfg.residual_*) */
    uint32_t frame;              /* frames accepted so far (the last frame number) */
    uint32_t next_id;
    uint16_t n_tracks;           /* active tracks */
};

#ifdef __cplusplus
}
#endif
#endif
