/* Internals shared by the TBD sources and the pf engine's TBD model (private, not installed). */
#ifndef PFT_TBD_INT_H
#define PFT_TBD_INT_H

#include "pft/pft_tbd.h"
#include "pft/pft_resample.h"

/* What one frame offers a filter step: the converted image, the exclusion mask (NULL: none)
 * and the birth candidate list with its sizes. */
typedef struct {
    const pft_real_t *img;
    const uint8_t *mask;
    const uint32_t *cand;
    uint32_t n_cand;    /* pixels proposed for births (B_k, or all allowed pixels) */
    uint32_t n_allowed; /* pixels outside the exclusion mask */
    bool cand_is_b;     /* cand holds B_k (z > gamma): the importance correction applies */
} pft_tbd_scene_t_;

/* pft_tbd_meas_init without the checks (cfg already passed pft_tbd_config_check). */
void pft_tbd_meas_setup_(pft_tbd_meas_t *m, const pft_tbd_config_t *cfg);
/* Frame validation against cfg (size, format, finiteness): touches nothing. */
pft_status_t pft_tbd_frame_check_(const pft_tbd_config_t *cfg, const pft_frame_t *frame);
/* Converts a validated frame into img (width*height reals, row-major). */
void pft_tbd_frame_convert_(const pft_tbd_config_t *cfg, const pft_frame_t *frame,
                            pft_real_t *img);
/* mask |= region (clipped). */
void pft_tbd_mask_add_(const pft_tbd_config_t *cfg, uint8_t *mask, const pft_tbd_region_t *r);
/* Fills cand and the counts of sc from img and mask (mask may be NULL). */
void pft_tbd_scene_build_(const pft_tbd_config_t *cfg, const pft_real_t *img,
                          const uint8_t *mask, uint32_t *cand, pft_tbd_scene_t_ *sc);

/* Bytes of one filter's particle buffers, and carving them. */
size_t pft_tbd_particle_bytes_(uint32_t n, pft_tbd_kind_t kind);
/* Carves the particle buffers of f (n, kind set) from ws; pointers NULL when short. */
void pft_tbd_particles_carve_(pft_tbd_filter_t *f, pft_ws_t *ws);
/* Sets every field of f except the buffers: cfg copy, constants, RNG, statistics. */
void pft_tbd_filter_setup_(pft_tbd_filter_t *f, const pft_tbd_config_t *cfg, uint32_t n,
                           pft_tbd_kind_t kind, bool births, bool constrain, uint64_t seed);
/* All particles E = 0 (buffers carved). */
void pft_tbd_filter_clear_(pft_tbd_filter_t *f);
/* Resets the statistics (estimate history, disappearance windows). */
void pft_tbd_filter_reset_stats_(pft_tbd_filter_t *f);
/* One iteration on a prepared scene (ALGORITHMS.md 2.5). */
void pft_tbd_filter_step_(pft_tbd_filter_t *f, const pft_tbd_scene_t_ *sc);
/* Hand-over: fills dst (E = 1 everywhere) by systematic resampling of the E = 1 particles of
 * src (only those whose window centre pixel is set in gate, when gate is not NULL) with dst's
 * RNG, and sets dst->est from the handed-over set (p_exist and log_mean_lr: src's). Returns
 * false (dst untouched) if no particle qualifies. */
bool pft_tbd_filter_handover_(pft_tbd_filter_t *dst, pft_tbd_filter_t *src, const uint8_t *gate);

/* Integer pixel index round(v * inv_d), with v clamped so the conversion is defined. */
int32_t pft_tbd_pix_(pft_real_t v, pft_real_t inv_d);

#endif
