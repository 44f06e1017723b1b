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
    pft_real_t inv_sn;       /* 1/sigma: frames are whitened, z/sigma */
    pft_real_t kc;           /* c0/sigma: the whitened amplitude of intensity I is I*kc */
    pft_real_t hi_x, hi_y;   /* width + 1/2, height + 1/2: a window centre u = x/dx is inside
                                the image for u in [1/2, hi_x) */
};

/* Rows of the PSF tap tables per pixel, and ages of the Kalman tables (pft_tbd_tab_t). */
#define PFT_TBD_TAP_STEPS 64u
#define PFT_TBD_KF_AGES 32u

/* Tables shared by every filter of a workspace (one copy per standalone filter, manager or pf
 * engine model): the separable PSF taps g((k - 1 - f) d) = exp(-((k - 1 - f) d)^2 / (2 S^2)),
 * k = 0..2, and their sum of squares (lane 3) at a window centre offset
 * f = -1/2 + n/PFT_TBD_TAP_STEPS, n = 0..STEPS - 1, followed by the differences of the four
 * lanes to row n + 1 (lanes 4-7), for x ([0], pitch dx) and y ([1], pitch dy); and the RBPF's
 * per-axis Kalman quantities as functions
 * of a particle's age (frames since birth; the covariance depends on nothing else): the
 * position spread sd = sqrt(T^2 P + q1 T^3/3) and the velocity gain times sd. Ages at or above
 * age_cap use entry age_cap (the recursion has converged there). */
typedef struct {
    pft_real_t taps[2][PFT_TBD_TAP_STEPS][8];
    pft_real_t kf_sd[2][PFT_TBD_KF_AGES];
    pft_real_t kf_gsd[2][PFT_TBD_KF_AGES];
    uint8_t age_cap;
    uint8_t r16_sum; /* nonzero: every tap lets the 3 x 3 kernel on a RES16 frame sum the
                        pixels' integers and scale once (always in q16; float: lib/src/core/kern_int.h) */
} pft_tbd_tab_t;

/* One particle's weight slot, used in turn for its log-weight, its weight and its replication
 * count within one update (only the member last written is read). */
typedef union {
    pft_real_t lw;
    pft_weight_t w;
    uint32_t n;
} pft_tbd_slot_t;

/* SoA particle arrays (both kinds). */
typedef struct {
    pft_real_t *x, *y, *in; /* position (internal frame) and intensity */
    pft_real_t *vx, *vy;    /* RBPF: Kalman velocity means; PF: sampled velocities */
    uint8_t *e;             /* 0: no target (E = 0); else 1 + age, age capped at tab->age_cap */
    pft_tbd_slot_t *w;      /* log-weight, weight, replication count */
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
    pft_tbd_particles_t cur;
    const pft_tbd_tab_t *tab; /* tables (workspace; shared by the manager's layers) */
    pft_real_t *img;         /* standalone only: converted frame (whitened, 1-pixel zero border) */
    uint32_t *mask;          /* standalone only: exclusion mask (bits, pft_tbd_masked_) */
    uint32_t *cand;          /* standalone only: birth candidate pixels */
    /* derived constants */
    pft_tbd_meas_t model;
    pft_real_t log_n;        /* log N */
    pft_real_t log_ratio;    /* log dis_ratio */
    pft_real_t gamma_w;      /* birth threshold on the whitened frame, gamma/sigma */
    pft_tbd_dyn_t dyn;       /* PF dynamics, births, existence probabilities */
    pft_real_t birth_lw;     /* birth log-weight correction of the current frame */
    pft_real_t bq;           /* cfg.birth_share > 0: the existence probability of the last frame */
    pft_rng_t rng;
    uint32_t frames;         /* accepted updates */
    pft_tbd_estimate_t est;
    /* disappearance statistic */
    pft_real_t lr_hist[PFT_TBD_MAX_DIS_R + 1u]; /* last log mean LRs (newest first) */
    pft_real_t win_hist[PFT_TBD_MAX_DIS_PREV];  /* previous window statistics (newest first) */
    uint32_t n_lr, n_win;
    bool gone;               /* disappearance declared at the last update */
    uint8_t resid_n;         /* manager, cfg.resid_split > 0: frames in a row with a residual peak beside the layer */
    pft_real_t resid_m;      /* ... the largest matched residual beside it at the last update (0: not tested) */
    pft_real_t resid_x, resid_y; /* ... and its pixel centre (internal frame) */
    bool seq_set;            /* standalone: last_seq holds the reference (cfg.seq_mode) */
    uint32_t last_seq;       /* standalone: seq of the last accepted frame */
};

/* The multi-target manager (docs/algorithms.md 2.7). */
struct pft_tbd_s {
    pft_tbd_config_t cfg;
    pft_tbd_filter_t search;
    pft_tbd_filter_t *tracks;    /* max_targets slots (workspace) */
    pft_tbd_track_t *records;    /* max_targets slots (workspace); id 0 marks a free slot */
    pft_tbd_event_t *events;     /* max_targets + 1 (workspace) */
    uint32_t n_events;
    void *base;                  /* the workspace's first (aligned) byte: its first buffer */
    pft_real_t *img;             /* converted frame (whitened, 1-pixel zero border); NULL with cfg.frame_format PFT_PIX_RES16 (the frame read in place) */
    int32_t *prect;              /* cfg.frame_format PFT_PIX_RES16: max_targets patch rectangles (4 each), the values in res */
    uint8_t *pflag;              /* cfg.frame_format PFT_PIX_RES16: per row, a patch on it or beside it */
    pft_real_t *rowbuf;          /* cfg.frame_format PFT_PIX_RES16: one row with its border, then the exact kernel's window */
    uint32_t *mask;              /* constraint mask: one bit per pixel, rows in whole 32-bit words */
    uint32_t *cand;              /* birth candidates: w h slots (B_k), or min(birth_peaks, w h) */
    uint32_t *lines;             /* w + h + 1 per-line counts: the allowed pixels per row of the peak scan's uniform proposal and its tile quota, or the hand-over gate's row lists and column counts */
    pft_tbd_tab_t *tab;          /* tables shared by every layer */
    pft_real_t *res;             /* img's pixels under the tracks' PSFs while they are subtracted in place (cfg.residual_*), or with PFT_PIX_RES16 the patches' values: max_targets slots of PFT_TBD_PSF_SAVE_REALS_ */
    pft_real_t *peak_rows;       /* cfg.birth_peaks > 0: six rolling image rows of the peak scan */
    pft_real_t *peak_val;        /* cfg.birth_peaks > 0: the peaks' values (heap) */
    uint32_t frame;              /* frames accepted so far (the last frame number) */
    uint32_t next_id;
    uint32_t n_cand;             /* birth candidates of the last update (0 after a hand-over) */
    bool cand_listed;            /* they are in cand (else every allowed pixel of mask) */
    uint16_t n_tracks;           /* active tracks */
    uint8_t above;               /* consecutive frames with the search layer's P > theta1 */
    bool seq_set;                /* last_seq holds the reference (cfg.seq_mode) */
    uint32_t last_seq;           /* seq of the last accepted frame */
    uint64_t last_ts;            /* its timestamp_us */
    uint32_t gap;                /* frame periods of the current update (1 without a gap) */
    uint16_t *integ[2];          /* cfg.integ_alpha > 0: the integrated sums S of the last frame and of this one, per 2 x 2 bin ((S << 2) | the bin's best pixel) */
    uint8_t integ_i;             /* which of integ[] holds the last frame's sums */
    pft_real_t shift_next[2];    /* pft_tbd_set_shift's shift to the next frame (pixels) */
    pft_real_t shift_acc[2];     /* the shift not yet applied in whole bins (pixels) */
    pft_tbd_filter_t *search_x;  /* cfg.search_layers = H >= 2: search layers 1 .. H - 1 (workspace; their particles are slices of search's) */
    uint32_t *cand_x;            /* cfg.search_layers >= 2: the birth candidates one layer may draw from */
    uint8_t above_x[PFT_TBD_MAX_SEARCH - 1u]; /* consecutive frames with layer h's P > theta1 (h >= 1) */
};

#ifdef __cplusplus
}
#endif
#endif
