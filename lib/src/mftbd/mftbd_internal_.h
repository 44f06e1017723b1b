/* Internals shared by the multi-frame TBD files (input stage, ring, DP core) and the DBT. */
#ifndef PFT_MFTBD_INTERNAL_H_
#define PFT_MFTBD_INTERNAL_H_

#include "pft/pft_mftbd.h"

/* Merit of a cancelled cell (paths avoid it; sums saturate harmlessly in q16). */
#define PFT_MFTBD_NEG_ PFT_C(-1000.0)

/* ------------------------------------------------------------------ input stage and ring */
/* Checks a frame against the input stage (size, format, finiteness). */
pft_status_t pft_mftbd_frame_check_(const pft_mftbd_input_t *in, const pft_frame_t *frame);
/* Converts row d of a checked frame to input units. */
void pft_mftbd_frame_row_(const pft_mftbd_input_t *in, const pft_frame_t *frame, uint32_t d,
                          pft_real_t *z);
/* Normalises one range row z (n_range values) into out (distinct buffers). */
void pft_mftbd_norm_row_(const pft_mftbd_input_t *in, const pft_real_t *z, pft_real_t *out);

void pft_mftbd_ring_setup_(pft_mftbd_ring_t *r, pft_real_t *buf, uint16_t len, uint32_t cells);
/* Slot for the next frame (not yet counted). */
pft_real_t *pft_mftbd_ring_next_(const pft_mftbd_ring_t *r);
/* Counts the slot returned by ring_next_ as the newest frame. */
void pft_mftbd_ring_commit_(pft_mftbd_ring_t *r);
/* Frame back frames ago (0 = newest); back < count. */
const pft_real_t *pft_mftbd_ring_get_(const pft_mftbd_ring_t *r, uint32_t back);

/* Pushes a frame (pft_frame_t or values in input units; exactly one non-NULL). Checks first. */
pft_status_t pft_mftbd_push_(const pft_mftbd_input_t *in, pft_mftbd_ring_t *ring,
                             pft_real_t *row, const pft_frame_t *frame, const pft_real_t *z);

/* ------------------------------------------------------------------------------ DP core */
typedef struct {
    const pft_mftbd_ring_t *ring;
    uint16_t nr, nd;
    uint8_t k;          /* batch length */
    uint8_t g0, g1;     /* gates */
    pft_real_t amp;     /* known amplitude or 0 */
    pft_real_t *ma, *mb;
    uint8_t *psi;       /* k * cells */
    uint8_t *mask;      /* k * cells, frame index 0 = oldest; NULL: none */
} pft_mftbd_dpcore_t_;

/* Runs the DP over the last k frames of the ring (ring->count >= k). Returns the best final
 * merit and its cell in *cell (-1 and PFT_REAL_MIN if every final cell is cancelled). */
pft_real_t pft_mftbd_dp_run_(const pft_mftbd_dpcore_t_ *c, int32_t *cell);
/* Backtracks from final cell into path[2*j + axis], j = 0 oldest .. k-1. */
void pft_mftbd_dp_backtrack_(const pft_mftbd_dpcore_t_ *c, int32_t cell, int16_t *path);
/* Marks cells within +-h0 (range) / +-h1 (Doppler) of path in every frame of the mask. */
void pft_mftbd_dp_cancel_(const pft_mftbd_dpcore_t_ *c, const int16_t *path, int32_t h0,
                          int32_t h1);
/* Sub-cell refinement of path frame j along axis a (3-point parabola on zeta), in cells. */
pft_real_t pft_mftbd_refine_(const pft_mftbd_dpcore_t_ *c, const int16_t *path, uint32_t j,
                             uint32_t axis);
/* Least-squares line through the refined path along axis a: position at the newest frame,
 * velocity (cells/frame). */
void pft_mftbd_path_fit_(const pft_mftbd_dpcore_t_ *c, const int16_t *path, uint32_t axis,
                         pft_real_t *pos, pft_real_t *vel);
/* Mean zeta along the path. */
pft_real_t pft_mftbd_path_amp_(const pft_mftbd_dpcore_t_ *c, const int16_t *path);
/* Noise-only Monte Carlo threshold with the core's geometry (ring is overwritten). */
pft_status_t pft_mftbd_dp_mc_(const pft_mftbd_input_t *in, pft_mftbd_dpcore_t_ *c,
                              pft_mftbd_ring_t *ring, pft_real_t *row, pft_real_t pfa,
                              uint32_t runs, uint64_t seed, pft_real_t *vt);

/* Returns the next track id and advances it (1, 2, ..., 65535, 1, ...). */
static inline uint16_t pft_mftbd_new_id_(uint16_t *next)
{
    uint16_t id = *next;
    *next = (uint16_t)(*next == 0xFFFFu ? 1u : *next + 1u);
    return id;
}

/* 3-point parabola vertex offset in (-0.5, 0.5) for values ym, y0, yp with y0 the largest;
 * 0 when the curvature is not negative. */
pft_real_t pft_mftbd_parabola_(pft_real_t ym, pft_real_t y0, pft_real_t yp);

#endif
