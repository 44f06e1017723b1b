/**
 * @file pft_dbt.h
 * @brief Kalman detect-before-track baseline of the multi-frame TBD comparison
 *        (ALGORITHMS.md 5.5): per-frame threshold, centroid plots, CV Kalman filters,
 *        nearest-neighbour gating, M-of-N confirmation, deletion after missed frames.
 *
 * Frames and the input stage are those of pft_mftbd.h (range-time profiles or range-Doppler
 * maps, normalised to zeta = z/sigma with a fixed sigma or a CA-CFAR estimate); tracks are
 * reported with pft_mftbd_report_t. Per frame:
 *  1. plots: cells with zeta > threshold (default Q^-1(1e-2) = 2.326). Range-time: each run
 *     of adjacent cells above the threshold is one plot at its zeta-weighted centroid.
 *     Range-Doppler [A]: each local maximum (8-neighbourhood) above the threshold is one plot
 *     at the centroid of the cells above the threshold in its 3x3 block. At most max_dets
 *     plots are kept (the strongest).
 *  2. predict every track (CV per axis, T = 1 frame, noise q: Q = q [[1/3, 1/2], [1/2, 1]]);
 *  3. gate: d^2 = sum over axes of nu^2 / S <= gate (chi-square, default 6.63 for one axis,
 *     9.21 for two); global nearest neighbour, greedy by d^2, confirmed tracks first;
 *  4. update (R = sigma_r^2 per axis) or count a miss;
 *  5. a tentative track is confirmed with confirm_m hits in its first confirm_n frames
 *     (default 2 of 3), else deleted; a confirmed track is deleted after max_misses
 *     consecutive misses (default 3);
 *  6. every plot left over starts a tentative track at the plot with velocity 0 and
 *     covariance diag(sigma_r^2, vel_var0) while slots are free.
 * Reports are the confirmed tracks (ids given at confirmation); `detected` says whether the
 * track was updated with a plot at this frame, `score` is that plot's peak zeta.
 *
 * Memory in a caller workspace (PFT_DBT_WORKSPACE_BYTES); bad input is refused before any
 * state changes. Per-frame work: one pass over the cells plus max_tracks * max_dets gating
 * tests and at most min(max_tracks, max_dets) greedy selection rounds over them.
 */
#ifndef PFT_DBT_H
#define PFT_DBT_H

#include "pft/pft_mftbd.h"

#ifdef __cplusplus
extern "C" {
#endif

/** Largest number of plots kept per frame. */
#define PFT_DBT_MAX_DETS 256u
/** Largest number of tracks (tentative and confirmed). */
#define PFT_DBT_MAX_TRACKS 64u

/** Configuration of the Kalman DBT baseline. */
typedef struct {
    pft_mftbd_input_t in;    /**< input stage (pft_mftbd.h) */
    pft_real_t threshold;    /**< plot threshold on zeta (default 2.3263, P_fa = 1e-2 per cell) */
    pft_real_t sigma_r[2];   /**< measurement standard deviation per axis, cells (default 0.5) */
    pft_real_t q[2];         /**< CV process noise intensity per axis (default 2e-4) */
    pft_real_t vel_var0[2];  /**< initial velocity variance per axis (default 0.04) */
    pft_real_t gate;         /**< chi-square gate (default 6.63; 9.21 for range-Doppler) */
    uint8_t confirm_m;       /**< hits needed ... (default 2) */
    uint8_t confirm_n;       /**< ... within the first n frames, 1..8 (default 3) */
    uint8_t max_misses;      /**< consecutive misses deleting a confirmed track, >= 1 (default 3) */
    uint8_t max_tracks;      /**< track slots, 1..PFT_DBT_MAX_TRACKS (default 32) */
    uint16_t max_dets;       /**< plots kept per frame, 1..PFT_DBT_MAX_DETS (default 64) */
} pft_dbt_config_t;

/** Defaults for n_range x n_doppler frames. */
void pft_dbt_config_default(pft_dbt_config_t *cfg, uint16_t n_range, uint16_t n_doppler);
/** PFT_OK if cfg is usable, PFT_ERR_INVAL otherwise. */
pft_status_t pft_dbt_config_check(const pft_dbt_config_t *cfg);

/** One plot of the current frame. */
typedef struct {
    pft_real_t pos[2]; /**< centroid (range, Doppler) */
    pft_real_t peak;   /**< largest zeta of the plot */
} pft_dbt_plot_t;

/** One DBT track (internal). */
typedef struct {
    pft_real_t x[2][2];
    pft_real_t P[2][4];
    pft_real_t score;
    uint32_t age;
    uint16_t id;      /**< 0 while tentative */
    uint8_t hist;     /**< hit history, newest in bit 0 */
    uint8_t misses;
    bool live;
    bool confirmed;
    bool detected;
} pft_dbt_track_t;

/** DBT instance (fields private). */
typedef struct {
    pft_dbt_config_t cfg;
    pft_mftbd_ring_t ring;   /**< one frame */
    pft_real_t *row;
    pft_dbt_plot_t *plots;
    pft_dbt_track_t *tracks;
    pft_mftbd_report_t *rep;
    pft_real_t *d2;          /**< max_tracks * max_dets gating distances */
    uint32_t frames_in;
    uint16_t n_plots;
    uint16_t next_id;
    uint8_t n_rep;
    uint8_t naxes;
} pft_dbt_t;

/** Workspace bytes (n_range, n_doppler, max_tracks, max_dets). */
#define PFT_DBT_WORKSPACE_BYTES(nr, nd, tmax, dmax)                                             \
    ((size_t)(PFT_WS_ALIGN - 1u) +                                                              \
     PFT_WS_ROUND((size_t)(nr) * (size_t)(nd) * sizeof(pft_real_t)) +                           \
     PFT_WS_ROUND((size_t)(nr) * sizeof(pft_real_t)) +                                          \
     PFT_WS_ROUND((size_t)(dmax) * sizeof(pft_dbt_plot_t)) +                                    \
     PFT_WS_ROUND((size_t)(tmax) * sizeof(pft_dbt_track_t)) +                                   \
     PFT_WS_ROUND((size_t)(tmax) * sizeof(pft_mftbd_report_t)) +                                \
     PFT_WS_ROUND((size_t)(tmax) * (size_t)(dmax) * sizeof(pft_real_t)))

/** Exact workspace bytes for cfg (0 if cfg is invalid). */
size_t pft_dbt_workspace_size(const pft_dbt_config_t *cfg);
/** Initialises dbt in work[0..len): PFT_ERR_INVAL (bad cfg), PFT_ERR_NOMEM (short work). */
pft_status_t pft_dbt_init(pft_dbt_t *dbt, const pft_dbt_config_t *cfg, void *work, size_t len);
/** Forgets all tracks (configuration kept; ids restart at 1). */
void pft_dbt_reset(pft_dbt_t *dbt);
/** Processes one frame (steps 1-6 above). */
pft_status_t pft_dbt_update(pft_dbt_t *dbt, const pft_frame_t *frame);
/** Same with a frame given as n_range * n_doppler values in input units. */
pft_status_t pft_dbt_update_real(pft_dbt_t *dbt, const pft_real_t *z);
/** Confirmed tracks after the last update; returns their count. */
uint32_t pft_dbt_reports(const pft_dbt_t *dbt, const pft_mftbd_report_t **out);
/** Plots of the last frame; returns their count. */
uint32_t pft_dbt_plots(const pft_dbt_t *dbt, const pft_dbt_plot_t **out);

#ifdef __cplusplus
}
#endif
#endif
