/*
 * NOT API. Layouts of the pte family's instances (PTE-TBD, DP-TBD, Kalman DBT), here only so
 * that a firmware can declare instances statically (sizeof) and the workspace macros of
 * pft_pte.h can be evaluated. Fields may change in any release: read results through the
 * calls of pft_pte.h. Included by pft_pte.h; including it alone includes pft_pte.h.
 */
#ifndef PFT_INTERNAL_PTE_TYPES_H
#define PFT_INTERNAL_PTE_TYPES_H

#include "pft/pft_pte.h"

#ifdef __cplusplus
extern "C" {
#endif

/** @cond internal */
#define PFT_PTE_CELLS_(nr, nd) ((size_t)(nr) * (size_t)(nd))
#define PFT_PTE_DPCORE_BYTES_(nr, nd, k)                                                        \
    (2u * PFT_WS_ROUND(PFT_PTE_CELLS_(nr, nd) * sizeof(pft_real_t)) +                           \
     2u * PFT_WS_ROUND((size_t)(k) * PFT_PTE_CELLS_(nr, nd)))
#define PFT_PTE_MAXU_(a, b) ((a) > (b) ? (a) : (b))
/** Frames in the ring: max_len + 1 (the frame leaving the operator window) or init_frames. */
#define PFT_PTE_RING_(mlen, ninit) ((size_t)PFT_PTE_MAXU_((size_t)(mlen) + 1u, (size_t)(ninit)))
#define PFT_PTE_NSCAN_(nd, steps, axis) ((axis) == 0 || (nd) > 1 ? 2u * (size_t)(steps) + 1u : 1u)
#define PFT_PTE_NDIR_(nd, l1) ((nd) > 1 ? (size_t)(l1) : 1u)
/** Largest number of scan positions per axis. */
#define PFT_PTE_MAX_SCAN_ (2u * PFT_PTE_MAX_SCAN_STEPS + 1u)
/** TABLE: slope entries per track (one per direction). */
#define PFT_PTE_NBANK_(l0) ((size_t)(l0))
/** TABLE: window lengths whose sums every slope entry slides (max_len and short_len). */
#define PFT_PTE_NWIN_ 2u
/** @endcond */

/* Ring of the last frames (normalised). */
typedef struct {
    pft_real_t *buf; /* len * cells */
    uint32_t cells;  /* n_range * n_doppler */
    uint16_t len;    /* capacity in frames */
    uint16_t count;  /* frames held (<= len) */
    uint16_t head;   /* slot of the newest frame */
} pft_pte_ring_t;

/* ------------------------------------------------------------------------------ PTE-TBD */

/* One PTE track. */
typedef struct {
    pft_real_t x[2][4];  /* per axis [r, 16 r', 256 r'', 0] (scaled, see pft_pte.h) */
    pft_real_t P[2][16]; /* per axis 4x4 covariance of the scaled state, row-major */
    pft_real_t amp, amp_var;
    pft_real_t score;    /* max_l T_l* of the last frame */
    uint32_t age;
    uint16_t id;
    uint8_t n_acc;       /* accumulation count (capped at max_len) */
    uint8_t misses;
    bool live;
    bool detected;
    uint8_t wait;        /* step_budget: frames since its last step (0 after a step) */
    uint8_t steady;      /* steady_dirs: the last step detected with the central direction the likeliest */
} pft_pte_track_t;

/* Result of one operator direction within a track step: the Kalman gain and state change of
 * its update per axis (effective state [r, SV r', SA r'']), amplitude, likelihood. */
typedef struct {
    pft_real_t dx[2][3]; /* per axis K nu */
    pft_real_t K[2][6];  /* per axis gain, 3 x 2 row-major */
    pft_real_t amp;      /* amplitude after the update with E/G */
    pft_real_t amp_var;
    pft_real_t logw;     /* log prior + the best scan position's log summand */
    pft_real_t ssum;     /* sum of the summands relative to the best (the likelihood is
                            exp(logw) ssum) */
    pft_real_t w;        /* its normalised weight in the fusion (kept here, not on the stack) */
} pft_pte_dir_t;

/* Per-axis operator parameters of one track at one frame. */
typedef struct {
    pft_real_t H[8];                   /* measurement matrix of [c*, SV theta*] (scaled state) */
    pft_real_t zc, zt;                 /* predicted measurement (end position, scaled slope) */
    pft_real_t sw2, sw, inv_sw, reach; /* sigma_w^2, sigma_w, 1/sigma_w, 3 sigma_w */
    pft_real_t dth;                    /* direction step, scaled (SV cells/frame) */
    pft_real_t prior_k;                /* dth^2 / (2 (S_tt + dth^2/12)): prior per k^2 */
    pft_real_t c0;                     /* first scan position */
    pft_real_t sc2;                    /* S_cc + sigma_r^2 */
    pft_real_t stt;                    /* S_tt: predicted variance of the scaled slope */
    pft_real_t pht[6];                 /* P H', 3 x 2 row-major (effective state) */
    pft_real_t s01;                    /* H P H' off-diagonal (the diagonal: sc2 - sigma_r^2, stt) */
    pft_real_t lck;                    /* 1 / (2 sc2): scan-position log prior per d^2 */
    pft_real_t r0c, r3c;               /* c_step^2 / 12 and dth^2 / 12: the constant terms of
                                          a direction's measurement noise R (per step) */
    pft_real_t sw12;                   /* 12 SV^2 sigma_w^2 (per step) */
    pft_real_t s00c;                   /* sc2 - sigma_r^2, the first diagonal of H P H' */
    int32_t ns;                        /* scan positions */
    int32_t L;                         /* directions */
    int32_t ncell;                     /* cells along the axis */
} pft_pte_axis_t;

/* TABLE operators: the sliding line sums of one operator slope of one track. Line j of the
 * entry passes, at frame k (numbered as frames_in), the response grid point
 * jlo + j + round(s U (k - k0) / 2^16), U the lattice step in 1/65536 grid points per frame.
 * Its sum E of the responses over the last m[w] frames lives in the bank sums of the track
 * (window w, line j); the sum G of their normalisers, for lines inside the profile, depends
 * only on (jlo + j) mod yq and is kept here per residue. */
typedef struct {
    pft_real_t gres[2][8]; /* G per window and residue */
    int32_t s;      /* slope, in lattice steps */
    int32_t jlo;    /* first line held */
    uint32_t k0;    /* anchor frame */
    uint32_t kl;    /* frame the sums are at */
    uint16_t n;     /* lines held */
    uint8_t m[2];   /* frames summed per window */
    uint8_t live;
    uint8_t used;   /* wanted at the current step */
} pft_pte_bank_t;

/* Scratch of one track step (one track at a time), in the workspace. */
typedef struct {
    pft_pte_axis_t ap[2];                        /* operator parameters per axis */
    pft_real_t lc[2][PFT_PTE_MAX_SCAN_];         /* log prior of each scan position per axis */
    pft_real_t gs[2][PFT_PTE_MAX_SCAN_];         /* sum of squared tap weights per position */
    int32_t bsel[PFT_PTE_MAX_DIRS];              /* TABLE: bank entry of each direction */
    int32_t bj0[PFT_PTE_MAX_DIRS];               /* TABLE: its first scan line in the entry */
    pft_real_t boff[PFT_PTE_MAX_DIRS];           /* TABLE: first scan position - predicted end */
    uint8_t bok[PFT_PTE_MAX_DIRS];               /* TABLE: its entry is complete (line_budget) */
    int32_t blo[PFT_PTE_MAX_SCAN_];              /* EXACT 2-D taps per phase: first cell, */
    int32_t bcnt[PFT_PTE_MAX_SCAN_];             /* count, */
    pft_real_t bg[PFT_PTE_MAX_SCAN_];            /* and sum of squared weights */
    uint32_t ti;                                 /* slot of the track being stepped */
} pft_pte_scratch_t;

/* The frame numbering of an instance (docs/design.md, "Time, sequence numbers and lost
 * frames"): the seq and timestamp of the last accepted frame, valid when set. */
typedef struct {
    uint64_t ts;
    uint32_t last;
    bool set;
} pft_pte_seq_t;

struct pft_pte_s {
    pft_pte_config_t cfg;
    pft_pte_ring_t ring;
    pft_real_t *row;
    pft_real_t *ma, *mb;
    uint8_t *psi, *mask;
    int16_t *path;               /* init_frames * 2 */
    pft_real_t *gtab;            /* PFT_PTE_GTAB_SIZE */
    pft_real_t *gw[2];           /* per-axis weight tables, PFT_PTE_GW_SIZE each (axis 1 only for range-Doppler) */
    pft_real_t *yring;           /* TABLE: matched responses, ring.len * ny */
    pft_real_t *gq;              /* TABLE: sum of g^2 of each response point minus gfull of its phase, ny */
    uint8_t *yflag;              /* TABLE: computed blocks of 8 cells, one bit each, ring.len * nyblk bytes */
    uint16_t nyblk;              /* TABLE: blocks per response row */
    pft_real_t ytap[8][PFT_PTE_MAX_TAPS]; /* TABLE: tap weights per grid phase */
    int16_t ytap_lo[8];          /* TABLE: first tap offset per phase (cells from floor(p)) */
    uint8_t ytap_n[8];           /* TABLE: taps per phase */
    pft_real_t ytap4_w[8][4];    /* TABLE: the taps padded to 4 from ytap4_lo (when ytap4) */
    int16_t ytap4_lo;
    uint8_t ytap4;               /* TABLE: every phase's taps fit in 4 from ytap4_lo */
    pft_real_t sigma_y;          /* TABLE: operator width */
    uint32_t ny;                 /* TABLE: response points (n_range + 2 PFT_PTE_YPAD) * yq */
    uint8_t yq;                  /* TABLE: grid points per cell (0: EXACT mode) */
    pft_pte_bank_t *bank;        /* TABLE: slope entries, max_tracks * nbank */
    pft_real_t *bsum;            /* TABLE: their E sums, max_tracks * nbank * NWIN * nline */
    pft_real_t gfull[16];        /* TABLE: normaliser of an interior grid point per phase, twice */
    int32_t yin_lo, yin_hi;      /* TABLE: interior grid points (gq = gfull) */
    int64_t lat_u;               /* TABLE: lattice step of the slopes, 1/65536 grid points per frame */
    int64_t lat_t;               /* TABLE: the same as a scaled slope (SV r'), 1/65536 */
    uint16_t nbank;              /* TABLE: entries per track */
    uint16_t nline;              /* TABLE: lines per entry (2 scan_steps + 1) */
    uint8_t short_len;           /* TABLE: frames of the short window (0: none) */
    uint8_t yblk_shift;          /* TABLE: log2 of the grid points per response block (0: not a power of 2) */
    pft_pte_track_t *tracks;
    pft_pte_report_t *rep;
    pft_real_t *sE, *sG, *sL;    /* scan accumulators (n_scan0 * n_scan1) */
    pft_real_t *tw[2];           /* tap weights per axis (n_scan * TAPS) */
    int16_t *tlo[2];             /* first tap cell, count, weight offset per axis (n_scan * 4) */
    pft_pte_dir_t *dir;          /* per-direction results (n_dir0 * n_dir1) */
    pft_pte_scratch_t *scr;      /* track-step scratch */
    pft_real_t kF[2][9];         /* per axis transition of the effective state [r, SV r', SA r''] */
    pft_real_t kQ[2][9];         /* per axis process noise of the effective state */
    uint32_t frames_in;
    pft_pte_seq_t seq;
    uint16_t next_id;
    uint16_t since_search;
    uint8_t init_run;            /* init_spread: a search is running */
    uint8_t init_stage;          /* init_spread: DP stages of the running search done */
    uint8_t init_todo;           /* init_spread: frames of the ring waiting for their stage */
    uint8_t n_steps;             /* track steps of the last update (step_budget bounds it) */
    uint32_t n_line_ops;         /* TABLE: line_budget units of the last update (line x frame sums, response blocks, edge rows and points; line_budget bounds them) */
    uint32_t line_used;          /* line_budget: units charged in this update (what was spent, and the edge reservations) */
    uint8_t n_rep;
    uint8_t naxes;
    uint8_t period;              /* 1/c_step when an integer <= 8 (tap reuse), else 0 */
    uint8_t miss[PFT_PTE_MAX_FRAMES + 1u]; /* per ring slot: 1 when it holds a lost frame */
#ifdef PFT_NUMERIC_Q16
    uint32_t f32t[256];          /* q16: multiplier of the one-product F32 input row per IEEE
                                    exponent (pft_pte_f32_table_) */
#endif
};

/* ------------------------------------------------------------------------------ DP-TBD */

struct pft_pte_dp_s {
    pft_pte_dp_config_t cfg;
    pft_pte_ring_t ring;
    pft_real_t *row;              /* input scratch (one range row) */
    pft_real_t *ma, *mb;          /* merit rows */
    uint8_t *psi;                 /* back-pointers, K * cells (neighbour index) */
    uint8_t *mask;                /* cancelled cells, K * cells */
    int16_t *paths;               /* max_targets * K * 2 cells */
    pft_pte_report_t *rep;        /* reports of the last frame */
    pft_pte_report_t *prev;       /* reports of the frame before (id association) */
    uint32_t frames_in;           /* accepted frames */
    pft_pte_seq_t seq;
    uint16_t next_id;
    uint8_t n_rep, n_prev;
    pft_real_t peak;              /* best merit of the last batch (first extraction) */
};

/* -------------------------------------------------------------------------------- DBT */

/* One DBT track. */
typedef struct {
    pft_real_t x[2][2];
    pft_real_t P[2][4];
    pft_real_t score;
    uint32_t age;
    uint16_t id;      /* 0 while tentative */
    uint8_t hist;     /* hit history, newest in bit 0 */
    uint8_t misses;
    bool live;
    bool confirmed;
    bool detected;
} pft_pte_dbt_track_t;

struct pft_pte_dbt_s {
    pft_pte_dbt_config_t cfg;
    pft_pte_ring_t ring;     /* one frame */
    pft_real_t *row;
    pft_pte_dbt_plot_t *plots;
    pft_pte_dbt_track_t *tracks;
    pft_pte_report_t *rep;
    pft_real_t *d2;          /* max_tracks * max_dets gating distances */
    uint32_t frames_in;
    pft_pte_seq_t seq;
    uint16_t n_plots;
    uint16_t next_id;
    uint8_t n_rep;
    uint8_t naxes;
};

#ifdef __cplusplus
}
#endif
#endif
