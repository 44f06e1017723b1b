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

/* A run of kernel pixels in one row (the fast histogram path): offsets of the first pixel and
 * the count. */
typedef struct {
    int16_t dy, dx0;
    uint16_t n;
} pft_tsa_span_t;

/* Most spans a kernel of a max_w x max_h box from an n_pts-point contour has: per row at most
 * n_pts / 2 (two crossings each) and at most (max_w + 1) / 2 (separated by gaps). */
#define PFT_TSA_SPAN_CAP(max_w, max_h, n_pts)                                                  \
    ((size_t)(max_h) * (((size_t)(n_pts) / 2u) < (((size_t)(max_w) + 1u) / 2u)                \
                            ? ((size_t)(n_pts) / 2u)                                            \
                            : (((size_t)(max_w) + 1u) / 2u)))

/* Templates under the camera gains (256 + 13 (i - 3)) / 256, i = 0..6 (cfg.gain_select). */
#define PFT_TSA_GAINS_ 7u

/* The square-root form of a histogram (Bhattacharyya coefficient): s_u / root = sqrt(bin_u /
 * total) to 2^-15. */

typedef struct {
    uint32_t s[PFT_TSA_BINS];
    uint32_t root;
    uint8_t nz[PFT_TSA_BINS]; /* the bins u with s_u != 0, ascending */
    uint32_t n_nz;            /* how many */
} pft_tsa_hroot_t;

/* Loss handling (cfg.loss_search): tracking, searching around the last good position, or
 * confirming a candidate found by the search. */
typedef enum { PFT_TSA_MODE_TRACK = 0, PFT_TSA_MODE_SEARCH = 1, PFT_TSA_MODE_CONFIRM = 2 } pft_tsa_mode_t;

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
    pft_tsa_span_t *spans, *spans_alt;    /* the kernels' row spans */
    uint32_t n_spans, n_spans_alt, span_cap;
    uint16_t *kw, *kw_alt;            /* the kernels' weights in span order */
    uint8_t *map;                     /* per-frame code map, 2 map_cap bytes (NULL: no map) */
    size_t map_cap;
    uint32_t *memo_key;               /* per-frame similarity cache by kernel position */
    pft_real_t *memo_rho;
    uint32_t memo_cap;
    int32_t *cross;
    pft_tsa_pt_t *contour;            /* offsets from the kernel origin */
    pft_tsa_pt_t *cwork;              /* frame coordinates, snake work */
    uint8_t *bflags;
    void *snake_ws;
    size_t snake_ws_len;
    pft_tsa_hist_t q;                 /* template */
    pft_tsa_hist_t q0;                /* first template (drift anchor) */
    pft_tsa_hist_t h;                 /* scratch */
    uint32_t jb[110];                 /* scratch of the joint-bin histogram (tsa_appear.c) */
    pft_tsa_hroot_t q_root;           /* square-root form of the template */
    pft_tsa_hroot_t q0_root;          /* square-root form of the first template */
    pft_tsa_hist_t qg[PFT_TSA_GAINS_]; /* the template under the gains of tsa_tracker.c */
    pft_tsa_hroot_t qg_root[PFT_TSA_GAINS_];
    pft_real_t qg_scale[PFT_TSA_GAINS_]; /* bg_ring: 1 / rho(target, weighted template) per gain */
    pft_tsa_hist_t qp;                /* bg_ring: the unweighted template at gain 1 (acquire_on 1) */
    pft_tsa_hroot_t qp_root;
    uint32_t gsel;                    /* the gain of this frame: an index into qg */
    pft_real_t ref_x[PFT_TSA_MOTION_MAX_K]; /* reference points of the fit, oldest first */
    pft_real_t ref_y[PFT_TSA_MOTION_MAX_K];
    pft_real_t ref_w[PFT_TSA_MOTION_MAX_K];
    uint32_t ref_n;
    pft_real_t beta;
    int64_t area2;                    /* twice the contour area */
    uint32_t n_state;                 /* particles in the state arrays: N, or N + 1 (pioneer) */
    uint32_t weak_run;                /* frames since the last frame with a particle kept */
    pft_tsa_mode_t mode;
    pft_real_t good_x, good_y;        /* last estimate of a frame with a particle kept */
    pft_real_t cand_x, cand_y;        /* candidate of the search (CONFIRM) */
    pft_real_t prior_x, prior_y;      /* mean of the propagated particles (this frame) */
    pft_real_t res_x, res_y;          /* last innovation: estimate - prior mean */
    pft_tsa_estimate_t est;
    bool started;
} pft_tsa_t;

#endif
