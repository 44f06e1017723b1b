/* Internals of the pte family (private, not installed): the input stage and ring, the DP core
 * shared by DP-TBD and the PTE-TBD initiation, the configuration-check and copy-out helpers of
 * the three trackers, and what the PTE-TBD files share (track step, TABLE operators). */
#ifndef PFT_PTE_INT_H
#define PFT_PTE_INT_H

#include <string.h>

#include "pft/pft_pte.h"

/* Merit of a cancelled cell (paths avoid it; sums saturate harmlessly in q16). */
#define PFT_PTE_NEG_ PFT_C(-1000.0)

/* ---------------------------------------------------------------- checks and copy-out */

/* Finishes a config_check: bad is the first refused field (NULL: none). */
static inline pft_status_t pft_pte_check_done_(const char *bad, const char **field)
{
    if (field != NULL) {
        *field = bad;
    }
    return bad == NULL ? PFT_OK : PFT_ERR_CONFIG;
}

/* First refused field of an input stage as written in a tracker config ("in.n_range"), or
 * NULL when it is usable. */
const char *pft_pte_input_bad_(const pft_pte_input_t *in);

/* Copies min(n, max) elements of `size` bytes from src to out (nothing when out is NULL);
 * returns n. */
static inline size_t pft_pte_copy_out_(const void *src, size_t n, size_t size, void *out,
                                       size_t max)
{
    if (out != NULL && max > 0u && n > 0u) {
        memcpy(out, src, (n < max ? n : max) * size);
    }
    return n;
}

/* Returns the next track id and advances it (1, 2, ..., 65535, 1, ...). */
static inline uint16_t pft_pte_new_id_(uint16_t *next)
{
    uint16_t id = *next;
    *next = (uint16_t)(*next == 0xFFFFu ? 1u : *next + 1u);
    return id;
}

/* ------------------------------------------------------------------ input stage and ring */
/* Checks a frame against the input stage (size, format, finiteness). */
pft_status_t pft_pte_frame_check_(const pft_pte_input_t *in, const pft_frame_t *frame);
/* The seq rule (docs/design.md, "Time, sequence numbers and lost frames") before an update
 * touches anything: the frame check, then *k as pft_seq_gap_ (1 for frame NULL, the
 * *_update_real calls). */
pft_status_t pft_pte_seq_check_(const pft_pte_input_t *in, const pft_pte_seq_t *s,
                                const pft_frame_t *frame, uint32_t *k);
/* After an accepted update: the frame becomes the reference (frame NULL: seq + 1) and the
 * n_rep reports get its seq and timestamp. */
void pft_pte_seq_take_(const pft_pte_input_t *in, pft_pte_seq_t *s, const pft_frame_t *frame,
                       pft_pte_report_t *rep, uint32_t n_rep);
/* Converts row d of a checked frame to input units. */
void pft_pte_frame_row_(const pft_pte_input_t *in, const pft_frame_t *frame, uint32_t d,
                        pft_real_t *z);
/* Normalises one range row z (n_range values) into out (distinct buffers). */
void pft_pte_norm_row_(const pft_pte_input_t *in, const pft_real_t *z, pft_real_t *out);

void pft_pte_ring_setup_(pft_pte_ring_t *r, pft_real_t *buf, uint16_t len, uint32_t cells);
/* Slot for the next frame (not yet counted). */
pft_real_t *pft_pte_ring_next_(const pft_pte_ring_t *r);
/* Counts the slot returned by ring_next_ as the newest frame. */
void pft_pte_ring_commit_(pft_pte_ring_t *r);
/* Frame back frames ago (0 = newest); back < count. */
const pft_real_t *pft_pte_ring_get_(const pft_pte_ring_t *r, uint32_t back);

/* Pushes a frame that passed pft_pte_seq_check_ (not checked again) or values (checked). */
pft_status_t pft_pte_push_(const pft_pte_input_t *in, pft_pte_ring_t *ring, pft_real_t *row,
                           const pft_frame_t *frame, const pft_real_t *z);
#ifdef PFT_NUMERIC_Q16
/* pft_pte_push_ for PTE-TBD (q16): fixed-noise F32 rows with one product per pixel through
 * f32t, the table of pft_pte_f32_table_, instead of fixed_row_'s decoding. */
pft_status_t pft_pte_push_f32t_(const pft_pte_input_t *in, pft_pte_ring_t *ring,
                                pft_real_t *row, const pft_frame_t *frame, const pft_real_t *z,
                                const uint32_t *f32t);
/* q16: the multipliers of the one-product F32 row for the input stage in (fixed noise), one per
 * IEEE exponent (docs/fixed_point.md, "PTE-TBD F32 input row by one product"). */
void pft_pte_f32_table_(const pft_pte_input_t *in, uint32_t tab[256]);
#endif

/* ------------------------------------------------------------------------------ DP core */
typedef struct {
    const pft_pte_ring_t *ring;
    uint16_t nr, nd;
    uint8_t k;          /* batch length */
    uint8_t g0, g1;     /* gates */
    pft_real_t amp;     /* known amplitude or 0 */
    pft_real_t *ma, *mb;
    uint8_t *psi;       /* k * cells */
    uint8_t *mask;      /* k * cells, frame index 0 = oldest; NULL: none */
} pft_pte_core_t_;

/* Runs the DP over the last k frames of the ring (ring->count >= k). Returns the best final
 * merit and its cell in *cell (-1 and PFT_REAL_MIN if every final cell is cancelled). */
pft_real_t pft_pte_core_run_(const pft_pte_core_t_ *c, int32_t *cell);
/* Stage j (0 = oldest frame of the batch) of the DP on frame zf (mask row j and psi row j
 * used): writes the merits into ma (j even) or mb (j odd) from the other one and returns
 * them. pft_pte_core_run_ is stages 0..k-1 on the last k frames of the ring. */
pft_real_t *pft_pte_core_stage_(const pft_pte_core_t_ *c, uint32_t j, const pft_real_t *zf);
/* Best final merit (merits of stage k-1) outside the cancelled cells of the last frame and
 * its cell in *cell (-1 and PFT_REAL_MIN if every final cell is cancelled). */
pft_real_t pft_pte_core_best_(const pft_pte_core_t_ *c, const pft_real_t *merit, int32_t *cell);
/* true when the path crosses no cancelled cell of the mask (always without a mask). */
bool pft_pte_core_clear_(const pft_pte_core_t_ *c, const int16_t *path);
/* Backtracks from final cell into path[2*j + axis], j = 0 oldest .. k-1. */
void pft_pte_core_backtrack_(const pft_pte_core_t_ *c, int32_t cell, int16_t *path);
/* Marks cells within +-h0 (range) / +-h1 (Doppler) of path in every frame of the mask. */
void pft_pte_core_cancel_(const pft_pte_core_t_ *c, const int16_t *path, int32_t h0,
                          int32_t h1);
/* Sub-cell refinement of path frame j along axis a (3-point parabola on zeta), in cells. */
pft_real_t pft_pte_core_refine_(const pft_pte_core_t_ *c, const int16_t *path, uint32_t j,
                                uint32_t axis);
/* Least-squares line through the refined path along axis a: position at the newest frame,
 * velocity (cells/frame). */
void pft_pte_core_fit_(const pft_pte_core_t_ *c, const int16_t *path, uint32_t axis,
                       pft_real_t *pos, pft_real_t *vel);
/* Mean zeta along the path. */
pft_real_t pft_pte_core_amp_(const pft_pte_core_t_ *c, const int16_t *path);
/* Noise-only Monte Carlo threshold with the core's geometry (ring is overwritten). */
pft_status_t pft_pte_core_mc_(const pft_pte_input_t *in, pft_pte_core_t_ *c,
                              pft_pte_ring_t *ring, pft_real_t *row, pft_real_t pfa,
                              uint32_t runs, uint64_t seed, pft_real_t *vt);

/* 3-point parabola vertex offset in (-0.5, 0.5) for values ym, y0, yp with y0 the largest;
 * 0 when the curvature is not negative. */
pft_real_t pft_pte_parabola_(pft_real_t ym, pft_real_t y0, pft_real_t yp);

/* ------------------------------------------------------- PTE-TBD (pte_tbd.c, pte_track.c) */

/* The state per axis is [r, SV r', SA r'', 0] with SV = 16, SA = 256 (exact in q16), so the
 * small velocity and acceleration variances are far above one LSB. */
#define PFT_PTE_SV_ 16
#define PFT_PTE_SA_ 256

/* Displacement theta*tau' - r''*tau'^2/2 of a path tau' frames back (scaled theta and acc). */
pft_real_t pft_pte_shift_(pft_real_t th, pft_real_t acc, int32_t tau);
/* TABLE operators: tap weights of each grid phase and the normaliser of every response point
 * (at init, after gtab and the TABLE buffers are set). */
void pft_pte_ytable_setup_(pft_pte_t *p);
/* Transition and process noise of every axis into the instance (at init, after cfg). */
void pft_pte_model_setup_(pft_pte_t *p);
/* Step 3 for one live track at the newest frame of the ring (the frame is pushed). False
 * when line_budget left its slope entries incomplete: the track predicted over the frame. */
bool pft_pte_track_step_(pft_pte_t *p, pft_pte_track_t *t);
/* line_budget, after a frame a track predicted over without stepping: it ends when it left
 * the image (as in step 7) or has waited max_len frames (a whole template predicted). */
void pft_pte_track_waited_(const pft_pte_t *p, pft_pte_track_t *t);
/* One lost frame for one live track: the prediction of step 1 over one period, the template
 * one frame longer (the lost frame is a missing stage of its window), no miss counted. */
void pft_pte_track_coast_(pft_pte_t *p, pft_pte_track_t *t);
/* 1 when the frame `back` frames ago (back < ring.count) is a lost frame. */
static inline uint8_t pft_pte_missing_(const pft_pte_t *p, uint32_t back)
{
    int32_t slot = (int32_t)p->ring.head - (int32_t)back;
    return p->miss[slot < 0 ? slot + (int32_t)p->ring.len : slot];
}

#endif
