/* Internals shared by the TBD sources and the pf engine's TBD model (private, not installed).
 *
 * The internal pixel frame. Inside the tbd module positions are kept as the paper writes them:
 * pixel (i, j), 1-based, has its centre at (i dx, j dy), i.e. x_int = x + dx for the public
 * 0-based x of docs/design.md ("Pixel coordinates"). Only the public boundary converts:
 * estimates, tracks and events on the way out, regions and the measurement-model calls on the
 * way in. In q16 the conversion is an exact integer addition, so the q16 arithmetic is the same
 * as before the public convention changed (golden vectors: a pure shift of the positions); in
 * float x - dx is exact for dx = 1 and any x_int >= 0.5 (every position inside the image), and
 * adding dx back restores x_int exactly. Regions (pft_tbd_region_t) are 0-based everywhere. */
#ifndef PFT_TBD_INT_H
#define PFT_TBD_INT_H

#include <string.h>

#include "pft/pft_tbd.h"
#include "pft/pft_resample.h"
#include "../core/acc_int.h"
#include "../core/kern_int.h"
#include "../core/rng_int.h"

/* Public 0-based position -> internal (x + d), and back (x - d). */
static inline pft_real_t pft_tbd_x_int_(pft_real_t x, pft_real_t d) { return pft_add(x, d); }
static inline pft_real_t pft_tbd_x_pub_(pft_real_t x, pft_real_t d) { return pft_sub(x, d); }

/* Images inside the module are whitened (z / sigma, clamped to +-32767) and carry a border of
 * one zero pixel: internal pixel (i, j) (1-based) is img[j * stride + i] with
 * stride = width + 2, so a 3 x 3 window around any pixel of the image reads only the buffer.
 * The border stays zero (only the interior is ever written). */
static inline uint32_t pft_tbd_stride_(uint32_t width) { return width + 2u; }
static inline size_t pft_tbd_img_len_(uint32_t width, uint32_t height)
{
    return (size_t)(width + 2u) * (height + 2u);
}

/* The exclusion (constraint) mask: one bit per pixel, bit col % 32 of word col / 32 of its
 * row, each row in pft_tbd_mask_words_(width) words (the bits past the width stay 0). */
static inline uint32_t pft_tbd_mask_words_(uint32_t width) { return (width + 31u) / 32u; }
static inline size_t pft_tbd_mask_len_(uint32_t width, uint32_t height)
{
    return (size_t)height * pft_tbd_mask_words_(width);
}
/* The bit of pixel (col, row), 0-based, in a mask of `words` words per row. */
static inline bool pft_tbd_masked_(const uint32_t *mask, uint32_t words, uint32_t col,
                                   uint32_t row)
{
    return ((mask[(size_t)row * words + (col >> 5u)] >> (col & 31u)) & 1u) != 0u;
}
/* Pixels of row `row` outside the mask. */
uint32_t pft_tbd_mask_row_free_(const uint32_t *mask, uint32_t width, uint32_t row);

/* What one frame offers a filter step: the converted image (or the RES16 frame read in place,
 * with the real-valued patches of the tracks' PSFs over it), the exclusion mask (NULL: none)
 * and the birth candidate list with its sizes. */
typedef struct {
    const pft_real_t *img; /* whitened, bordered (above); NULL: the RES16 frame r16 */
    /* cfg.frame_format PFT_PIX_RES16 (img NULL): the frame's pixels read in place, pixel
     * (col, row) 0-based at r16 + row r16_stride + 2 col, each res / 256 (a masked pixel 0),
     * 0 outside the image; where patch k (0 .. n_patch - 1) lies, its value instead (the
     * highest k that covers the pixel): the frame minus the tracks' PSFs, exactly as they were
     * subtracted from img (pft_tbd_psf_patch_). */
    const uint8_t *r16;
    size_t r16_stride;
    const int32_t *prect;   /* patch k: col_lo, col_hi, row_lo, row_hi at prect[4 k] (0-based,
                               inside the image; col_hi < col_lo: empty) */
    const pft_real_t *pval; /* patch k's values, row-major, at pval + k PFT_TBD_PSF_SAVE_REALS_ */
    const uint8_t *pflag;   /* per row: nonzero when a patch covers it or a row beside it */
    pft_real_t *rowbuf;     /* scratch: one row with its zero border (w + 2 reals), then the
                               window of the exact kernel (PFT_TBD_WIN_REALS_) */
    uint32_t n_patch;
    const uint32_t *mask;  /* bits (pft_tbd_masked_), or NULL */
    const uint32_t *cand;  /* 0-based row-major pixel indices; NULL: every allowed pixel, in
                              raster order, counted per row in row_pre */
    const uint32_t *row_pre; /* cand NULL: row_pre[r] allowed pixels in rows 0 .. r - 1
                                (height + 1 entries, row_pre[height] = n_allowed) */
    uint32_t width, height;
    uint32_t n_cand;    /* pixels proposed for births (B_k, or all allowed pixels) */
    uint32_t n_allowed; /* pixels outside the exclusion mask */
    bool cand_is_b;     /* cand holds B_k (z > gamma): the importance correction applies */
} pft_tbd_scene_t_;

/* Reals of the exact kernel's window scratch: (2 PFT_TBD_MAX_WINDOW + 1)^2. */
#define PFT_TBD_WIN_REALS_ ((2u * PFT_TBD_MAX_WINDOW + 1u) * (2u * PFT_TBD_MAX_WINDOW + 1u))

/* A RES16 pixel as the converted frame holds it: res / 256, a masked pixel 0. */
static inline pft_real_t pft_tbd_r16_(const uint8_t *p)
{
    int16_t v;
    memcpy(&v, p, 2u);
    return v != PFT_RES16_MASKED ? pft_kres16_(v) : PFT_C(0.0);
}
/* The pixels (col0 + a, row0 + b), a < nx, b < ny, of a RES16 scene (sc->img NULL) into z
 * (row-major, nx per row) as the bordered real-valued frame would hold them: 0 outside the
 * image, the patches over the frame. */
void pft_tbd_fetch_(const pft_tbd_scene_t_ *sc, int32_t col0, int32_t row0, uint32_t nx,
                    uint32_t ny, pft_real_t *z);
/* The patches' values over the window z of pft_tbd_fetch_ (the frame's values already in z). */
void pft_tbd_patch_over_(const pft_tbd_scene_t_ *sc, int32_t col0, int32_t row0, uint32_t nx,
                         uint32_t ny, pft_real_t *z);
#if defined(__aarch64__) || (defined(__x86_64__) && !defined(PFT_NUMERIC_Q16))
/* The Bernoulli search layer's move pass (tbd_filter.c, move_bern_) on f's particles for the
 * scene sc (births from its candidates), in its split form (split) or the general form: *nb
 * births, *np survivors (for the unit tests; AArch64 and x86-64 float builds only). */
void pft_tbd_move_bern_hook_(pft_tbd_filter_t *f, const pft_tbd_scene_t_ *sc, uint32_t p16_share,
                             bool split, uint32_t *nb, uint32_t *np);
#endif
/* Whether a patch of sc may cover a pixel of the 3 x 3 window at columns col0 .. col0 + 2,
 * rows row0 .. row0 + 2 (0-based): false when every patch's rectangle lies apart from it. */
bool pft_tbd_patch_in_win_(const pft_tbd_scene_t_ *sc, int32_t col0, int32_t row0);
#if defined(__SSE2__) || (defined(PFT_NUMERIC_Q16) && defined(__aarch64__) && defined(__ARM_NEON))
/* The scene scan's horizontal sums of a RES16 row of w pixels (src: the row's bytes, int16
 * pixels) with the taps t0, t1 prepared by pft_kr16_tap_: hs[c] = t1 z(c) + t0 (z(c - 1) +
 * z(c + 1)), z a pixel / 256, a masked one or one outside the row 0 (tbd_meas.c,
 * peak_hrow_r16_; for the unit tests, x86-64 builds and AArch64 q16 only). */
void pft_tbd_hrow_r16_(const uint8_t *src, uint32_t w, pft_real_t t0, pft_real_t t1,
                       pft_real_t *hs);
#endif
#if defined(__SSE2__) && defined(PFT_NUMERIC_Q16)
/* The scene scan's vertical sums mf[c] = u1 mid[c] + u0 (up[c] + dn[c]) (tbd_meas.c,
 * peak_vrow_; up and dn may be NULL, zero rows; for the unit tests, q16 x86-64 builds only). */
void pft_tbd_vrow_(const pft_real_t *up, const pft_real_t *mid, const pft_real_t *dn, uint32_t w,
                   pft_real_t u0, pft_real_t u1, pft_real_t *mf);
#endif
/* Row r (0-based) of the scene with its zero border: element 0 is the border, 1 .. w the
 * pixels, w + 1 the border (img's own row, or the scene's row buffer filled). */
const pft_real_t *pft_tbd_row_(const pft_tbd_scene_t_ *sc, uint32_t r);
/* Patch `slot` (= sc->n_patch: the patches below it already in sc) of the PSF that
 * pft_tbd_psf_add_(m, img, .., x, y, coef, half) adds: its rectangle into rect (4 int32) and
 * the pixels' values plus the PSF into val, the same arithmetic as on the real-valued frame. */
void pft_tbd_psf_patch_(const pft_tbd_meas_t *m, const pft_tbd_scene_t_ *sc, int32_t *rect,
                        pft_real_t *val, pft_real_t x, pft_real_t y, pft_real_t coef,
                        uint8_t half);

/* pft_tbd_meas_init without the checks (cfg already passed pft_tbd_config_check). */
void pft_tbd_meas_setup_(pft_tbd_meas_t *m, const pft_tbd_config_t *cfg);
/* The measurement model in the internal frame: pixel (i, j) 1-based, positions x_int. */
pft_real_t pft_tbd_meas_h_int_(const pft_tbd_meas_t *m, int32_t i, int32_t j, pft_real_t x,
                              pft_real_t y, pft_real_t intensity);
pft_real_t pft_tbd_meas_llr_int_(const pft_tbd_meas_t *m, const pft_real_t *img, pft_real_t x,
                                pft_real_t y, pft_real_t intensity);
/* img += coef gx gy over the (2 half + 1)^2 pixels around (x, y) (internal frame), clipped to
 * the image; internal pixel (i, j) is img[origin + (j - 1) stride + i - 1] (origin 0 and
 * stride width for a plain row-major image, stride + 1 and width + 2 for a bordered one).
 * coef = I c0 adds h; I kc adds h / sigma (whitened); a negative coef subtracts. */
void pft_tbd_psf_add_(const pft_tbd_meas_t *m, pft_real_t *img, size_t origin, uint32_t stride,
                      pft_real_t x, pft_real_t y, pft_real_t coef, uint8_t half);
/* The (2p+1)^2 window around an internal position, as a 0-based region. */
pft_tbd_region_t pft_tbd_window_int_(const pft_tbd_config_t *cfg, pft_real_t x, pft_real_t y);
/* Frame validation against cfg (size, format, finiteness): touches nothing. */
pft_status_t pft_tbd_frame_check_(const pft_tbd_config_t *cfg, const pft_frame_t *frame);
/* Converts a validated frame into the interior of the bordered whitened image img. */
void pft_tbd_frame_convert_(const pft_tbd_config_t *cfg, const pft_tbd_meas_t *m,
                            const pft_frame_t *frame, pft_real_t *img);
/* mask |= region (0-based, clipped to the image). */
void pft_tbd_mask_add_(const pft_tbd_config_t *cfg, uint32_t *mask, const pft_tbd_region_t *r);
/* Fills cand and the counts of sc from the bordered whitened img (birth threshold gamma_w =
 * gamma / sigma) and mask (may be NULL). img NULL: from the RES16 source the caller set in sc
 * (r16 .. n_patch); else sc's source becomes img. */
void pft_tbd_scene_build_(const pft_tbd_config_t *cfg, pft_real_t gamma_w, const pft_real_t *img,
                          const uint32_t *mask, uint32_t *cand, pft_tbd_scene_t_ *sc);

/* The same with births from peaks (cfg.birth_peaks = K >= 1, docs/algorithms.md 2.11): cand
 * (min(K, w h) slots) gets the K strongest 3 x 3 local maxima above peak_gamma of img
 * correlated with the f = 0 PSF taps of tab, outside the mask; when there is none the scene
 * proposes every allowed pixel without a list (sc->cand NULL, the per-row counts in lines).
 * rows holds six image rows of scratch, val K reals (the peaks' values), lines w + h + 1
 * counts (the allowed pixels per row, and the tile quota's counts of the current tile row).
 * img NULL: the RES16 source of sc, as above. */
/* The multi-frame integration of the peak scan (cfg.integ_alpha > 0, docs/algorithms.md 2.13):
 * prev the last frame's sums, cur this frame's (bw x bh bins of 2 x 2 pixels, row-major, each
 * (S << 2) | i, S in 1/64 noise sigmas, i the bin's largest pixel: row 2 (i / 2), column i % 2);
 * (sx, sy) the platform's shift to this frame in whole bins; a_q = integ_alpha in 1/256. */
typedef struct {
    const uint16_t *prev;
    uint16_t *cur;
    uint32_t bw, bh;
    int32_t sx, sy;
    uint32_t a_q;
} pft_tbd_integ_t_;
void pft_tbd_scene_peaks_(const pft_tbd_config_t *cfg, const pft_tbd_tab_t *tab,
                          const pft_real_t *img, const uint32_t *mask, pft_real_t *rows,
                          pft_real_t *val, uint32_t *cand, uint32_t *lines, pft_tbd_scene_t_ *sc);
/* The same with the peaks of the integration instead (ig->cur written, ig->prev read). */
void pft_tbd_scene_integ_(const pft_tbd_config_t *cfg, const pft_tbd_tab_t *tab,
                          const pft_real_t *img, const uint32_t *mask, pft_real_t *rows,
                          pft_real_t *val, uint32_t *cand, uint32_t *lines, pft_tbd_scene_t_ *sc,
                          const pft_tbd_integ_t_ *ig);
#if defined(__SSE2__) || (defined(__aarch64__) && defined(__ARM_NEON))
/* One bin row br of the integration (tbd_meas.c, integ_row_) from the PSF-matched rows r0, r1
 * (r1 NULL past the last row) into ig->cur with ig->prev's sums, vm bw + 2 words of scratch,
 * the row's sums and squares added to sum[0], sum[1]; general: every bin by the general code
 * (integ_bin_) instead of the inner bins' loops (for the unit tests, x86-64 and AArch64
 * builds only). */
void pft_tbd_integ_row_(const pft_tbd_integ_t_ *ig, uint32_t br, const pft_real_t *r0,
                        const pft_real_t *r1, uint32_t w, uint32_t *vm, uint64_t *sum,
                        bool general);
#endif
#if defined(__SSE2__) || (defined(__aarch64__) && defined(__ARM_NEON))
/* The first bin from bc on (bc .. bw - 1) of a row of the integration's words above bound, or
 * bw: the peak scan's skip (tbd_meas.c, integ_scan_: eight words per step, then one at a time;
 * for the unit tests, x86-64 and AArch64 builds only). */
uint32_t pft_tbd_integ_skip_(const uint16_t *row, uint32_t bc, uint32_t bw, int32_t bound);
#endif
/* The n-th (0-based, n < sc->n_allowed) allowed pixel of a scene in raster order (sc->cand
 * NULL): a binary search of row_pre, then the row's mask. */
uint32_t pft_tbd_scene_pick_(const pft_tbd_scene_t_ *sc, uint32_t n);

/* The tables of cfg (PSF taps, Kalman quantities by age), and the taps alone (tbd_meas.c). */
void pft_tbd_tab_setup_(pft_tbd_tab_t *t, const pft_tbd_config_t *cfg);
void pft_tbd_taps_setup_(pft_tbd_tab_t *t, const pft_tbd_meas_t *m);

/* Bytes of one filter's particle buffers, and carving them. */
size_t pft_tbd_particle_bytes_(uint32_t n, pft_tbd_kind_t kind);
/* Carves the particle buffers of f (n, kind set) from ws; pointers NULL when short. */
void pft_tbd_particles_carve_(pft_tbd_filter_t *f, pft_ws_t *ws);
/* Sets every field of f except the buffers and the tables: cfg copy, constants, RNG,
 * statistics. */
void pft_tbd_filter_setup_(pft_tbd_filter_t *f, const pft_tbd_config_t *cfg, uint32_t n,
                           pft_tbd_kind_t kind, bool births, bool constrain, uint64_t seed);
/* All particles E = 0 (buffers carved). */
void pft_tbd_filter_clear_(pft_tbd_filter_t *f);
/* Resets the statistics (estimate history, disappearance windows). */
void pft_tbd_filter_reset_stats_(pft_tbd_filter_t *f);
/* One iteration on a prepared scene (docs/algorithms.md 2.5). */
void pft_tbd_filter_step_(pft_tbd_filter_t *f, const pft_tbd_scene_t_ *sc);
/* periods frame periods without a frame (a seq gap, docs/design.md "Time, sequence numbers and
 * lost frames"): the existence chain and the dynamics of every particle, no births, no weights;
 * the Bernoulli form's existence probability is predicted as many times. */
void pft_tbd_filter_coast_(pft_tbd_filter_t *f, uint32_t periods);
/* Hand-over: fills dst with dst->n particles by systematic resampling (equal weights) of the
 * E = 1 particles of src (only those whose window centre pixel lies in the 0-based region
 * gate, when gate is not NULL) with dst's RNG, ages kept, and sets dst->est from the
 * handed-over set (p_exist and log_mean_lr: src's). Returns false (dst untouched) if no
 * particle qualifies. src's weight slots (free between updates) are the scratch of the
 * qualification test. */
#define PFT_TBD_NO_PIX_ 0xFFFFFFFFu
bool pft_tbd_filter_handover_(pft_tbd_filter_t *dst, pft_tbd_filter_t *src,
                              const pft_tbd_region_t *gate);

/* The split test of a track layer (cfg.split_px, docs/algorithms.md 2.7 [E]): true when its
 * live particles part into two groups as cfg.split_px and split_share ask; the groups are then
 * left in f's weight slots (1 the larger, 2 the smaller) and (*sx, *sy) is the smaller's
 * centroid. Reads f only (the weight slots apart: free between updates). */
bool pft_tbd_filter_parts_(pft_tbd_filter_t *f, pft_real_t min_sep, pft_real_t min_share,
                           pft_real_t *sx, pft_real_t *sy);
/* After pft_tbd_filter_parts_ returned true: d (a track layer of as many particles) takes f's
 * particles with the larger group's slots refilled from the smaller group, f keeps the larger
 * group with the smaller's slots refilled from it (systematic resampling, each with its own
 * generator); both estimates from their live particles, existence and frame log likelihood
 * ratio f's. */
void pft_tbd_filter_split_(pft_tbd_filter_t *f, pft_tbd_filter_t *d);
/* A new track layer d beside layer f (cfg.resid_split, docs/algorithms.md 2.7 [E]): f's
 * particles copied, each live one moved by (ox, oy) and born anew (state byte 1: age 0; the
 * velocity at cfg.vel_mean, sampled about it with vel_var's sd in the PF kind, d's generator);
 * d's estimate from its live particles, existence probability and frame log likelihood ratio
 * f's. */
void pft_tbd_filter_seed_at_(const pft_tbd_filter_t *f, pft_tbd_filter_t *d, pft_real_t ox,
                             pft_real_t oy);

/* The public copy of an estimate: positions in the 0-based frame when valid (an estimate that
 * was never valid stays all zero). */
void pft_tbd_est_pub_(const pft_tbd_meas_t *m, const pft_tbd_estimate_t *in,
                      pft_tbd_estimate_t *out);
/* Integer pixel index round(v * inv_d), with v clamped so the conversion is defined. */
int32_t pft_tbd_pix_(pft_real_t v, pft_real_t inv_d);

/* ---- the per-particle kernel (the filters' hot loop and the pf engine's TBD model) ---- */

/* The window centre of a position: internal pixel (i, j) and the offsets f = u - i of
 * u = x / dx (and of y) from its centre, in [-1/2, 1/2), in the tap tables' terms
 * (kern_int.h; pft_kfrac_off_ gives f). */
typedef struct {
    int32_t i, j;
    pft_kfrac_t fx, fy;
} pft_tbd_cell_t;

/* False when the window centre pixel is outside the image (the target left the surveillance
 * region). One rounding rule for the leave-image test, the constraint mask and the window. */
static inline bool pft_tbd_cell_(const pft_tbd_meas_t *m, pft_real_t x, pft_real_t y,
                                 pft_tbd_cell_t *c)
{
    const pft_real_t u = m->dx == PFT_REAL_ONE ? x : pft_mul(x, m->inv_dx);
    const pft_real_t v = m->dy == PFT_REAL_ONE ? y : pft_mul(y, m->inv_dy);
    return pft_kcell_(u, m->hi_x, (int32_t)m->width, &c->i, &c->fx) &&
           pft_kcell_(v, m->hi_y, (int32_t)m->height, &c->j, &c->fy);
}

/* The windowed LLR (docs/algorithms.md 1) of intensity I at cell c on a bordered whitened
 * image, for any window: the exact PSF taps (2 (2p + 1) exponentials), the window clipped to
 * the image. */
pft_real_t pft_tbd_llr_exact_(const pft_tbd_meas_t *m, const pft_real_t *img,
                              const pft_tbd_cell_t *c, pft_real_t intensity);

/* Taps at an image edge: the tap outside set to 0 and its square taken out of lane 3. */
static inline void pft_tbd_clip_(pft_real_t t[4], int32_t i, int32_t n)
{
    if (i == 1) {
        t[3] = pft_sub(t[3], pft_kmulq_(t[0], t[0]));
        t[0] = PFT_C(0.0);
    }
    if (i == n) {
        t[3] = pft_sub(t[3], pft_kmulq_(t[2], t[2]));
        t[2] = PFT_C(0.0);
    }
}

/* The same for p = 1 with tabulated taps (pft_tbd_tab_t, linear interpolation): three taps
 * and their sum of squares per axis, a tap outside the image set to 0 (the window clipped),
 * the 3 x 3 sum factored, the pixel index computed once. */
static inline pft_real_t pft_tbd_llr3_(const pft_tbd_meas_t *m, const pft_tbd_tab_t *tab,
                                       const pft_real_t *img, const pft_tbd_cell_t *c,
                                       pft_real_t intensity)
{
    pft_real_t tx[4], ty[4];
    const size_t stride = (size_t)m->width + 2u;
    pft_ktaps_(tab->taps[0], c->fx, tx);
    pft_ktaps_(tab->taps[1], c->fy, ty);
    /* i = 1 or i = n (i in [1, n]): one unsigned comparison, i - 2 wraps for i = 1 */
    if ((uint32_t)(c->i - 2) >= (uint32_t)m->width - 2u) {
        pft_tbd_clip_(tx, c->i, (int32_t)m->width);
    }
    if ((uint32_t)(c->j - 2) >= (uint32_t)m->height - 2u) {
        pft_tbd_clip_(ty, c->j, (int32_t)m->height);
    }
    return pft_kspot3_(img + (size_t)(c->j - 1) * stride + (size_t)(c->i - 1), stride, tx, ty,
                       pft_kmulq_(intensity, m->kc));
}

/* The rest of pft_tbd_llr3_r16_ when the window cannot be summed from the frame's integers
 * (tbd_meas.c): at an image edge (the taps clipped, the window fetched, 0 outside), on a row a
 * patch may cover (the pixels read, the patches over them), or with taps that pft_kspot3_r16_
 * cannot take (tab->r16_sum 0): the taps of cell (i, j, fx, fy), the values of the bordered
 * real-valued frame, then pft_kspot3_. Everything by value, so that the inline kernel's taps
 * never go through memory on the common path (and the caller's cell never has its address
 * taken). */
pft_real_t pft_tbd_llr3_r16_out_(const pft_tbd_meas_t *m, const pft_tbd_tab_t *tab,
                                 const pft_tbd_scene_t_ *sc, int32_t i, int32_t j, pft_kfrac_t fx,
                                 pft_kfrac_t fy, pft_real_t amp);

/* What pft_tbd_llr3_r16_ reads of the scene, the table and the model for every window: a
 * particle loop reads them once (pft_tbd_llr3_r16_inv_) instead of through the pointers per
 * particle. The window is summed in place when (uint32_t)(i - 2) < wi and (uint32_t)(j - 2) <
 * hj: wi and hj are width - 2 and height - 2 (the inner pixels' test) when the table's taps
 * allow it (tab->r16_sum), else 0, which no unsigned value is below; the same test as
 * !(i - 2 >= width - 2 || j - 2 >= height - 2) && r16_sum, with the subtractions and the
 * flag's test once per pass instead of per window. */
typedef struct {
    const uint8_t *r16;
    const uint8_t *pflag; /* NULL when no patch lies on the frame */
    size_t st;
    uint32_t wi, hj;
} pft_tbd_r16_inv_t;

static inline pft_tbd_r16_inv_t pft_tbd_llr3_r16_inv_(const pft_tbd_meas_t *m,
                                                      const pft_tbd_tab_t *tab,
                                                      const pft_tbd_scene_t_ *sc)
{
    pft_tbd_r16_inv_t v;
    const bool sum = tab->r16_sum != 0u;
    v.r16 = sc->r16;
    v.pflag = sc->n_patch > 0u ? sc->pflag : NULL;
    v.st = sc->r16_stride;
    v.wi = sum ? (uint32_t)m->width - 2u : 0u;
    v.hj = sum ? (uint32_t)m->height - 2u : 0u;
    return v;
}

/* pft_tbd_llr3_r16_ (below) with those values read (v) */
static inline pft_real_t pft_tbd_llr3_r16_v_(const pft_tbd_meas_t *m, const pft_tbd_tab_t *tab,
                                             const pft_tbd_scene_t_ *sc,
                                             const pft_tbd_r16_inv_t *v, const pft_tbd_cell_t *c,
                                             pft_real_t intensity)
{
    /* i = 1 or i = n (i in [1, n]): one unsigned comparison, i - 2 wraps for i = 1 */
    const bool in = (uint32_t)(c->i - 2) < v->wi && (uint32_t)(c->j - 2) < v->hj;
    const pft_real_t amp = pft_kmulq_(intensity, m->kc);
    /* a row that pflag names may hold a patch: the window read in place unless one covers
     * a pixel of it (pft_tbd_llr3_r16_out_ then reads the frame's values as they are) */
    if (in && !(v->pflag != NULL && v->pflag[c->j - 1] != 0u &&
          pft_tbd_patch_in_win_(sc, c->i - 2, c->j - 2))) {
#ifdef PFT_KSPOT3_R16T_LANES_
        /* float with SSE2 or AArch64 NEON: the taps and the window in vector lanes (the same
         * bits) */
        return pft_kspot3_r16t_(v->r16 + (size_t)(c->j - 2) * v->st + 2u * (size_t)(c->i - 2),
                                v->st, tab->taps[0], c->fx, tab->taps[1], c->fy, amp);
#else
        pft_real_t tx[4], ty[4];
        pft_ktaps_(tab->taps[0], c->fx, tx);
        pft_ktaps_(tab->taps[1], c->fy, ty);
        return pft_kspot3_r16_(v->r16 + (size_t)(c->j - 2) * v->st + 2u * (size_t)(c->i - 2),
                               v->st, tx, ty, amp);
#endif
    }
    return pft_tbd_llr3_r16_out_(m, tab, sc, c->i, c->j, c->fx, c->fy, amp);
}

/* pft_tbd_llr3_ on a scene's RES16 frame read in place (sc->img NULL): the same 3 x 3 values,
 * the same arithmetic. Inside the image away from the patches (the common case) the window
 * is summed from the frame's integers with one base index (pft_kspot3_r16_, the same bits);
 * else pft_tbd_llr3_r16_out_. */
static inline pft_real_t pft_tbd_llr3_r16_(const pft_tbd_meas_t *m, const pft_tbd_tab_t *tab,
                                           const pft_tbd_scene_t_ *sc, const pft_tbd_cell_t *c,
                                           pft_real_t intensity)
{
    const pft_tbd_r16_inv_t v = pft_tbd_llr3_r16_inv_(m, tab, sc);
    return pft_tbd_llr3_r16_v_(m, tab, sc, &v, c, intensity);
}

/* pft_tbd_llr3_r16_ called (tbd_meas.c): the inline kernel has one call site in the filters'
 * hot loops (tbd_filter.c, weigh_r16_); the other cases call this. */
pft_real_t pft_tbd_llr3_r16_call_(const pft_tbd_meas_t *m, const pft_tbd_tab_t *tab,
                                  const pft_tbd_scene_t_ *sc, const pft_tbd_cell_t *c,
                                  pft_real_t intensity);

/* pft_tbd_llr_exact_ on a scene's RES16 frame (the window fetched into sc->rowbuf's window
 * scratch). */
pft_real_t pft_tbd_llr_exact_r16_(const pft_tbd_meas_t *m, const pft_tbd_scene_t_ *sc,
                                  const pft_tbd_cell_t *c, pft_real_t intensity);

/* The filters' likelihood: the tabulated 3 x 3 kernel for p = 1, the exact one otherwise (on a
 * copy of the cell, so that the caller's never has its address taken by a call). */
static inline pft_real_t pft_tbd_llr_(const pft_tbd_meas_t *m, const pft_tbd_tab_t *tab,
                                      const pft_real_t *img, const pft_tbd_cell_t *c,
                                      pft_real_t intensity)
{
    if (m->p == 1u) {
        return pft_tbd_llr3_(m, tab, img, c, intensity);
    }
    {
        const pft_tbd_cell_t cc = *c;
        return pft_tbd_llr_exact_(m, img, &cc, intensity);
    }
}

/* The same on a scene: its real-valued frame, or its RES16 frame read in place. */
static inline pft_real_t pft_tbd_llr_sc_(const pft_tbd_meas_t *m, const pft_tbd_tab_t *tab,
                                         const pft_tbd_scene_t_ *sc, const pft_tbd_cell_t *c,
                                         pft_real_t intensity)
{
    if (sc->img != NULL) {
        return pft_tbd_llr_(m, tab, sc->img, c, intensity);
    }
    {
        const pft_tbd_cell_t cc = *c;
        if (m->p == 1u) {
            return pft_tbd_llr3_r16_call_(m, tab, sc, &cc, intensity);
        }
        return pft_tbd_llr_exact_r16_(m, sc, &cc, intensity);
    }
}

/* ---- PF-TBD pieces shared with the pf engine's TBD model (tbd_dyn.c) ---- */

/* Pointers to one particle's kinematic state (the filter's SoA arrays or the engine's state
 * vector). */
typedef struct {
    pft_real_t *x, *y, *vx, *vy, *in;
} pft_tbd_kin_t;

/* Fills the PF-TBD constants of cfg: chol(V), sqrt(q2 T), sqrt(P0), quantised probabilities. */
void pft_tbd_dyn_setup_(pft_tbd_dyn_t *d, const pft_tbd_config_t *cfg);
/* The existence draw of one particle: 16 bits, compared with the quantised probabilities. */
static inline uint32_t pft_tbd_exist_draw_(pft_rng_t *rng) { return pft_rng_next_(rng) >> 16; }
/* Birth probability of a frame (eta on the first frame, pb after). */
static inline uint32_t pft_tbd_p_birth_(const pft_tbd_dyn_t *d, bool first_frame)
{
    return first_frame ? d->p16_eta : d->p16_b;
}
/* The birth log-weight correction log(|B_k| / A_allow) of a scene (0 unless
 * cfg.birth_correction and the candidates are B_k). */
pft_real_t pft_tbd_birth_lw_(const pft_tbd_config_t *cfg, const pft_tbd_scene_t_ *sc);
/* A birth: a candidate pixel, a uniform position inside it, intensity U[i_min, i_max]; the
 * velocity drawn from N(vel_mean, vel_var) when sample_vel (PF), else vel_mean (RBPF, whose
 * Kalman variance is that of age 0). n_cand >= 1. */
void pft_tbd_birth_(const pft_tbd_config_t *c, const pft_tbd_dyn_t *d, const uint32_t *cand,
                    uint32_t n_cand, bool sample_vel, pft_rng_t *rng, pft_tbd_kin_t *k);
/* The same in pixel p drawn by the caller (its draw pft_rng_below(rng, n_cand) first, as
 * above): everything after the pixel's draw. A scene's pixel is its candidate list's entry or,
 * without a list, its n-th allowed pixel (pft_tbd_scene_pick_). */
void pft_tbd_birth_pix_(const pft_tbd_config_t *c, const pft_tbd_dyn_t *d, uint32_t p,
                        bool sample_vel, pft_rng_t *rng, pft_tbd_kin_t *k);
/* A birth's coordinate in pixel c (0-based) at the uniform offset u in [0, 1) for the pitch d:
 * (c + 1/2 + u) d with pft_add's and pft_mul's bits, without their saturation. The config
 * check gives n d < 16384 for n = width, height (pft_span_ok_) and n <= 8192; a birth's pixel
 * p is one of the frame's, p < width height (every caller's candidate list, or the n-th allowed
 * pixel), so c < n: the sum is below n + 1/2, exact, and the product below n d + d / 2 <
 * 16384 + 8192 (d < 16384 as n >= 1), positive: in q16 the 64-bit product stays below
 * 1.5 2^46, so pft_mul's rounded value fits 31 bits (docs/fixed_point.md, "Particle
 * kernels"). */
static inline pft_real_t pft_tbd_birth_coord_(uint32_t c, pft_real_t u, pft_real_t d)
{
    return pft_kmula_(pft_kaddr_(pft_kaddr_(pft_from_int((int32_t)c), PFT_C(0.5)), u), d);
}

/* A birth's configuration and the intensity draw's range tests in a local
 * (pft_tbd_birth_inv_): the search layer's move pass reads them once per pass instead of
 * through the config pointer per birth (the stores of a birth to the particle arrays, floats or
 * int32_t in q16 and the state bytes, may alias the config's fields, so a read through the
 * pointer is repeated at each birth); pft_tbd_birth_pix_ builds it per call. The draws and
 * values are those of the per-call form with pft_rng_uniform_range_ (test_tbd_kern_r16). */
typedef struct {
    pft_real_t dx, dy;
    pft_real_t vel_mean[2], vel_sd[2];
    pft_real_t i_lo, i_hi;
#ifdef PFT_NUMERIC_Q16
    int64_t i_span; /* i_max - i_min when i_min < i_max, else 0 (the draw is then i_min) */
#else
    pft_real_t i_span; /* i_max - i_min (i_fast only) */
    bool i_fast;       /* i_min < i_max and i_max - i_min finite */
#endif
    uint32_t width;
} pft_tbd_birth_inv_t;

static inline pft_tbd_birth_inv_t pft_tbd_birth_inv_(const pft_tbd_config_t *c,
                                                     const pft_tbd_dyn_t *d)
{
    pft_tbd_birth_inv_t b;
    b.dx = c->dx;
    b.dy = c->dy;
    b.vel_mean[0] = c->vel_mean[0];
    b.vel_mean[1] = c->vel_mean[1];
    b.vel_sd[0] = d->vel_sd[0];
    b.vel_sd[1] = d->vel_sd[1];
    b.i_lo = c->i_min;
    b.i_hi = c->i_max;
#ifdef PFT_NUMERIC_Q16
    b.i_span = b.i_lo < b.i_hi ? (int64_t)b.i_hi - (int64_t)b.i_lo : 0;
#else
    b.i_span = pft_sub(b.i_hi, b.i_lo);
    b.i_fast = b.i_lo < b.i_hi && b.i_span <= PFT_REAL_MAX;
#endif
    b.width = c->width;
    return b;
}

/* pft_rng_uniform_range_(rng, i_min, i_max) with its range tests decided once per pass. q16:
 * with a span of 0 when i_min >= i_max the sum is i_min, what the test there returns; the
 * same product and shift otherwise. float, i_min < i_max with a finite span (i_fast): the same
 * sum lo + span f, and its test against lo dropped: span > 0 and f >= 0 make span f >= 0, and
 * round-to-nearest is monotone, so lo + span f >= lo (with lo = -0 the sum is +0, and +0 < -0
 * is false too); the other cases take pft_rng_uniform_range_'s code after the same draw. */
static inline pft_real_t pft_tbd_birth_in_draw_(const pft_tbd_birth_inv_t *b, pft_rng_t *rng)
{
    const uint32_t u = pft_rng_next_(rng);
#ifdef PFT_NUMERIC_Q16
    return (pft_real_t)((int64_t)b->i_lo + ((b->i_span * (int64_t)(u >> 16)) >> 16));
#else
    if (b->i_fast) {
        const pft_real_t r = pft_add(b->i_lo, pft_mul(b->i_span, pft_from_u32_frac(u)));
        return r < b->i_hi ? r : nextafterf(b->i_hi, b->i_lo); /* rounded up to i_max: rare */
    } else {
        const pft_real_t lo = b->i_lo;
        const pft_real_t hi = b->i_hi;
        if (!(lo < hi)) {
            return lo;
        }
        {
            const pft_real_t f = pft_from_u32_frac(u);
            const pft_real_t r = pft_add(pft_mul(lo, pft_sub(PFT_REAL_ONE, f)), pft_mul(hi, f));
            return r < hi ? (r < lo ? lo : r) : nextafterf(hi, lo);
        }
    }
#endif
}

/* A birth in pixel p from the locals b: its position uniform in the pixel, its intensity
 * uniform in [i_min, i_max), its velocity drawn around vel_mean (sample_vel: PF births) or
 * vel_mean itself; inline, so that the search layer's generator, a local of the move pass,
 * stays in registers. */
static inline void pft_tbd_birth_pix_v_(const pft_tbd_birth_inv_t *b, uint32_t p, bool sample_vel,
                                        pft_rng_t *rng, const pft_tbd_kin_t *k)
{
    const uint32_t col = p % b->width;
    const uint32_t row = p / b->width;
    const pft_real_t ux = pft_from_u32_frac(pft_rng_next_(rng));
    const pft_real_t uy = pft_from_u32_frac(pft_rng_next_(rng));
    *k->x = pft_tbd_birth_coord_(col, ux, b->dx);
    *k->y = pft_tbd_birth_coord_(row, uy, b->dy);
    *k->in = pft_tbd_birth_in_draw_(b, rng);
    if (sample_vel) {
        *k->vx = pft_kmad1_(b->vel_mean[0], b->vel_sd[0], pft_rng_zig_(rng));
        *k->vy = pft_kmad1_(b->vel_mean[1], b->vel_sd[1], pft_rng_zig_(rng));
    } else {
        *k->vx = b->vel_mean[0];
        *k->vy = b->vel_mean[1];
    }
}
/* A survivor's PF move: X = F X + chol(V) n on the full state (five ziggurat draws: x axis,
 * y axis, intensity), each component rounded once. */
static inline void pft_tbd_pf_move_(const pft_tbd_dyn_t *d, pft_real_t T, pft_rng_t *rng,
                                    const pft_tbd_kin_t *k)
{
    /* each axis as soon as its two draws are made (fewer draws live at once; the draws in the
     * same order) */
    const pft_real_t g1 = pft_rng_zig_(rng);
    const pft_real_t g2 = pft_rng_zig_(rng);
    const pft_real_t vx = *k->vx;
    *k->x = pft_kmad2_(*k->x, T, vx, d->ch_pos, g1);
    *k->vx = pft_kmad2_(vx, d->ch_cross, g1, d->ch_vel, g2);
    {
        const pft_real_t g3 = pft_rng_zig_(rng);
        const pft_real_t g4 = pft_rng_zig_(rng);
        const pft_real_t vy = *k->vy;
        *k->y = pft_kmad2_(*k->y, T, vy, d->ch_pos, g3);
        *k->vy = pft_kmad2_(vy, d->ch_cross, g3, d->ch_vel, g4);
    }
    *k->in = pft_kmad1_(*k->in, d->ch_int, pft_rng_zig_(rng));
}
/* True when the window centre pixel of (x, y) is inside the image (else the target left the
 * surveillance region); *pix is then its 0-based row-major index. */
static inline bool pft_tbd_centre_(const pft_tbd_meas_t *m, pft_real_t x, pft_real_t y,
                                   size_t *pix)
{
    pft_tbd_cell_t c;
    if (!pft_tbd_cell_(m, x, y, &c)) {
        return false;
    }
    *pix = (size_t)(c.j - 1) * m->width + (size_t)(c.i - 1);
    return true;
}

/* Estimate sums: total weight, weight of the E != 0 particles and their weighted x, y, vx,
 * vy, I. */
typedef struct {
    pft_wacc_t wt, we;
    pft_acc_t_ s[5];
} pft_tbd_wsum_t;
static inline void pft_tbd_wsum_init_(pft_tbd_wsum_t *a)
{
    a->wt = 0;
    a->we = 0;
    for (int c = 0; c < 5; ++c) {
        a->s[c] = PFT_ACC_ZERO_;
    }
}
/* Adds one particle (v: x, y, vx, vy, I). */
static inline void pft_tbd_wsum_add_(pft_tbd_wsum_t *a, pft_weight_t w, bool alive,
                                     const pft_real_t v[5])
{
    a->wt += w;
    if (alive) {
        a->we += w;
        for (int c = 0; c < 5; ++c) {
            a->s[c] += pft_acc_wx_(w, v[c]);
        }
    }
}
/* P(E != 0) of the sums. */
static inline pft_real_t pft_tbd_wsum_p_(const pft_tbd_wsum_t *a) { return pft_wratio_(a->we, a->wt); }
/* Weighted means x, y, vx, vy, I of the E != 0 particles; false (mean untouched) when they
 * have no weight. */
bool pft_tbd_wsum_mean_(const pft_tbd_wsum_t *a, pft_real_t mean[5]);

#endif
