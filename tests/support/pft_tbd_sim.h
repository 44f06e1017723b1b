/* Deterministic dim-target frame simulator shared by the TBD tests (64-bit floating point,
 * noise from the library's own RNG so every target draws the same frames). */
#ifndef PFT_TBD_SIM_H
#define PFT_TBD_SIM_H
#include "pft/pft.h"

/** A deterministic straight-line target present in frames first..last (1-based, inclusive). */
typedef struct {
    int first, last;       /* frames of presence */
    double x0, y0, vx, vy; /* position at `first`, velocity per frame */
    double I;              /* intensity */
} pft_sim_truth_t;

int pft_sim_alive(const pft_sim_truth_t *t, int k);
double pft_sim_x(const pft_sim_truth_t *t, int k);
double pft_sim_y(const pft_sim_truth_t *t, int k);
/** Standard normal draw (Box-Muller on two 32-bit draws). */
double pft_sim_gauss(pft_rng_t *r);

/**
 * Renders frame k as U16 into buf (w*h pixels): z = sigma * noise + the PSF (Sigma^2 = 0.49,
 * unit pixels, the pixel in column c, row r centred at (c, r): 0-based, docs/design.md) of every
 * live target of t[0..nt), stored as
 * raw = round((z + 64) * 256) clamped to 0..65535 (so pixel_gain 1/256, pixel_offset -64).
 * f describes buf, seq = k.
 */
void pft_sim_render_u16(pft_rng_t *r, const pft_sim_truth_t *t, int nt, int k, double sigma,
                        int w, int h, uint16_t *buf, pft_frame_t *f);
#endif
