/* Internals of the preprocessing stage (private, not installed): the per-frame accumulators,
 * the pixel classification, the histogram binning and the passes shared by the files of
 * lib/src/pre. Units (docs/algorithms.md 9.1): raw counts; R = counts * 2^rs (residual);
 * U = counts * 2^bf (temporal background); sigma in R units Q4. */
#ifndef PFT_PRE_INT_H
#define PFT_PRE_INT_H

#include <string.h>

#include "pft/pft_pre.h"

/* A valid pixel packed with its count: raw | 1 << 24 (0: masked). Sums of up to 225 packed
 * values keep the count in bits 24..31 and the sum of raw values below. */
#define PFT_PRE_ONE_ (1u << 24)
#define PFT_PRE_VAL_ 0x00FFFFFFu
/* Largest |residual| and |whitened| value (INT16_MIN is the mask). */
#define PFT_PRE_RMAX_ 32767
/* 1 / Phi^-1(3/4) in Q16: sigma = 1.4826 median |r| for Gaussian noise. */
#define PFT_PRE_MAD_K_ 97163u
/* Multiplier numerator: tmul = 2^28 / sigma(R Q4), whitened Q8.8 = r * tmul / 2^16. */
#define PFT_PRE_MUL_ONE_ (1u << 28)
/* Column sums are taken on every PFT_PRE_COL_ROWS_-th row (their recursion averages frames). */
#define PFT_PRE_COL_ROWS_ 4u
/* Half-width (columns) of the smoothing taken off the column offsets (a high-pass). */
#define PFT_PRE_COL_HP_ 8
/* Tile sigma entries flagged as not estimated in the current frame. */
#define PFT_PRE_TILE_STALE_ 0x80000000u

/* Per-frame accumulators. */
typedef struct {
    uint32_t n_sat, n_dead, n_bad; /* masked input pixels by cause */
    uint32_t n_masked;             /* residual pixels set to PFT_RES16_MASKED */
    uint32_t flags;
} pft_pre_acc_t;

/* Classification limits of a frame: valid iff raw - lo < span (unsigned) and not in the map. */
typedef struct {
    uint32_t lo, span;
    uint32_t mask;   /* 2^bits - 1 */
    bool u8;
    const uint8_t *map;
    uint32_t map_stride;
} pft_pre_cls_t;

static inline void pft_pre_cls_init_(const pft_pre_t *p, pft_pre_cls_t *c)
{
    c->lo = (uint32_t)p->cfg.dead_level + 1u;
    c->span = (uint32_t)p->cfg.sat_level - c->lo;
    c->mask = p->rawmask;
    c->u8 = p->cfg.format == PFT_PIX_U8;
    c->map = p->cfg.bad_map;
    c->map_stride = ((uint32_t)p->cfg.width + 7u) / 8u;
}

/* Raw value of pixel x of a frame row (low bit_depth bits). */
static inline uint32_t pft_pre_raw_(const uint8_t *row, uint32_t x, const pft_pre_cls_t *c)
{
    if (c->u8) {
        return row[x];
    }
    uint16_t v;
    memcpy(&v, row + 2u * x, 2u);
    return (uint32_t)v & c->mask;
}

/* Whether pixel (x, y) is set in the bad-pixel map (which must exist). */
static inline bool pft_pre_bad_(const pft_pre_cls_t *c, uint32_t x, uint32_t y)
{
    return (((uint32_t)c->map[y * c->map_stride + (x >> 3)] >> (x & 7u)) & 1u) != 0u;
}

/* Whether pixel x of row y with raw value v is unmasked. */
static inline bool pft_pre_valid_(const pft_pre_cls_t *c, uint32_t v, uint32_t x, uint32_t y)
{
    if (v - c->lo >= c->span) {
        return false;
    }
    return c->map == NULL || !pft_pre_bad_(c, x, y);
}

/* Counts a masked pixel of raw value v (a value in range: it is in the map). */
static inline void pft_pre_count_masked_(const pft_pre_cls_t *c, uint32_t v, pft_pre_acc_t *acc)
{
    if (v - c->lo < c->span) {
        acc->n_bad++;
    } else if (v < c->lo) {
        acc->n_dead++;
    } else {
        acc->n_sat++;
    }
}


/* n / d rounded half away from zero, d > 0 (per frame or per block, not per pixel: a 64-bit
 * division). */
static inline int64_t pft_pre_div_rnd_(int64_t n, int64_t d)
{
    return (n >= 0 ? n + d / 2 : n - d / 2) / d;
}

/* Floor of log2(v) for v >= 1. */
static inline uint32_t pft_pre_log2_(uint32_t v)
{
#if defined(__GNUC__)
    return 31u - (uint32_t)__builtin_clz(v);
#else
    uint32_t e = 0u;
    while (v > 1u) {
        v >>= 1;
        e++;
    }
    return e;
#endif
}

/* Histogram bin of |r| = v in 0..32767: v itself below 16, then 8 bins per octave
 * (bin 8 (e - 3) + (v >> (e - 3)) with e = floor(log2(v | 8)); 104 bins). */
static inline uint32_t pft_pre_bin_(uint32_t v)
{
    const uint32_t e3 = pft_pre_log2_(v | 8u) - 3u;
    return (e3 << 3) + (v >> e3);
}

/* Clamp of a residual to +-PFT_PRE_RMAX_. */
static inline int32_t pft_pre_rclamp_(int32_t r)
{
    return r > PFT_PRE_RMAX_ ? PFT_PRE_RMAX_ : (r < -PFT_PRE_RMAX_ ? -PFT_PRE_RMAX_ : r);
}

/* Clip (R units) of the column sums for tile (j, i): 3 sigma of the last frame, or no clip. */
static inline int32_t pft_pre_clip_(const pft_pre_t *p, uint32_t j, uint32_t i)
{
    const uint32_t s = p->tsig[j * p->ntx + i] & ~PFT_PRE_TILE_STALE_;
    if (s == 0u) {
        return PFT_PRE_RMAX_;
    }
    const uint32_t c = (3u * s + 8u) >> 4;
    return c > (uint32_t)PFT_PRE_RMAX_ ? PFT_PRE_RMAX_ : (int32_t)(c == 0u ? 1u : c);
}

/* Column sums and histograms of residual row y (written in p->res); returns its masked
 * pixels. */
uint32_t pft_pre_book_row_(pft_pre_t *p, uint32_t y);
/* Residual row y is complete (rows come in order, up or down): book-keeping, and when the
 * frame is whitened with the last frame's sigmas, whitening and the peaks of the row before.
 * Returns the row's masked pixels. */
uint32_t pft_pre_row_out_(pft_pre_t *p, uint32_t y);
/* Sigma of the tiles of tile row j from the histograms (then cleared). */
void pft_pre_tilerow_done_(pft_pre_t *p, uint32_t j);

/* Pass 1 of each method: residual (R units) into p->res, histograms, column sums. */
void pft_pre_local_pass_(pft_pre_t *p, const pft_frame_t *f, pft_pre_acc_t *acc);
/* TEMPORAL: registration of f against the background (sets p->st.shift*, flags in acc). */
void pft_pre_register_(pft_pre_t *p, const pft_frame_t *f, pft_pre_acc_t *acc);
void pft_pre_temporal_pass_(pft_pre_t *p, const pft_frame_t *f, pft_pre_acc_t *acc);
/* The anchored pass's residual of row pixels [x0, x1] (pre_temporal.c, exported for its unit
 * test): r[x] from the vertical blends v (U * 16; with split, held in the form of
 * pft_pre_vsplit_: 128 vh + vl, on AArch64 with NEON the values themselves), the read weights wr
 * and the frame row zl. */
int32_t pft_pre_vsplit_(int32_t v);
void pft_pre_ares_span_(const int32_t *v, const int32_t *zl, int16_t *r, int32_t x0, int32_t x1,
                        const int32_t wr[4], uint32_t k1, bool split);
/* The anchored update's clipped gate (bg_gate_shift 0) of cells [ja, jb] of grid row b (storage
 * entry j + 1) from ring rows q (pre_temporal.c, exported for its unit test), in the plain form
 * or (split, x86-64 and AArch64) the split form where it applies. */
void pft_pre_gate_clip_(const int32_t *const q[4], const int32_t w[4], const int32_t n[4], int32_t a15,
                        uint16_t *b, int32_t ja, int32_t jb, int32_t lim, bool split);
#if defined(__SSE2__)
/* bg_anchor on x86-64 (SSE2): one row of the registration's view of the anchored grid, its
 * vertical pass into int16 halves and its horizontal pass from them (pre_temporal.c). */
void pft_pre_view_vrow_(const uint16_t *t0, const uint16_t *t1, const uint16_t *t2,
                        const uint16_t *t3, const int32_t w[4], int16_t *vh, int16_t *vl,
                        int32_t n);
void pft_pre_view_hrow_(const int16_t *vh, const int16_t *vl, int32_t sw, int32_t k,
                        const int32_t w[4], uint16_t *o, int32_t n);
#elif defined(__aarch64__) && defined(__ARM_NEON)
/* bg_anchor on AArch64 (NEON): the registration's view's horizontal pass of the 32-bit form,
 * pixels 0 .. 8 (xe / 8) - 1 from the vertical blends v; returns 8 (xe / 8) (pre_temporal.c). */
int32_t pft_pre_view_h32_(const int32_t *v, const int32_t w[4], uint16_t *o, int32_t xe);
/* bg_stale_reinit with bg_anchor: the stale columns of nr (1 .. 4) age rows (hm) and the
 * residual row's pixels [ca, cb] they mask (stale_anchor_res_'s NEON form, pre_temporal.c). */
void pft_pre_stale_res_n_(const uint8_t *const a[4], int32_t nr, int32_t sw, uint32_t n, uint8_t *hm,
                          int32_t k1, int32_t xlo, int32_t xhi, int32_t ca, int32_t cb, int16_t *r);
#endif
#if defined(__SSE2__) || (defined(__aarch64__) && defined(__ARM_NEON))
/* sigma_mad's tile histogram (pft_pre_book_row_'s NEON and SSE2 forms): the bins of residuals
 * r[0 .. 8 (n / 8) - 1] added to hist (PFT_PRE_BINS + 1 counts, a masked pixel in the last);
 * returns the pixels done (pre_update.c). */
uint32_t pft_pre_hist_rown_(uint16_t *hist, const int16_t *r, uint32_t n);
/* The masked pixels of a U16 row without a bad-pixel map by cause (count_row_'s NEON and SSE2
 * forms), pixels 0 .. 8 (w / 8) - 1 where the form takes them (the SSE2 form only for lo below
 * 2^16 and span in 1 .. 2^32 - 2^16, else none): cnt[0] dead, cnt[1] saturated added to;
 * returns the pixels done (pre_temporal.c). */
uint32_t pft_pre_count_rowv_(const uint8_t *row, uint32_t w, uint32_t mask, uint32_t lo, uint32_t span,
                             uint32_t cnt[2]);
/* bg registration (NEON and SSE2 forms): the Lucas-Kanade sums of a row's samples 0, st, 2 st,
 * ... (st 2 or 4) in whole blocks of four (U16 frame, no bad-pixel map); returns the first sample
 * left to the plain loop (pre_temporal.c). */
int32_t pft_pre_lk_rowv_(const uint8_t *rz, const int32_t *cz, const uint16_t *bm, int32_t bs,
                         const uint32_t par[6], int32_t st, int32_t n, int64_t sums[6], uint32_t *cnt);
#endif
#if defined(__SSE2__)
/* whiten_row_ on x86-64 (SSE2), pre_update.c: the multipliers m[0 .. 8 (n / 8) - 1] as the
 * signed upper halves of s + i st (mline_span_'s running sum), and the whitening without the
 * clamp r[x] = (r[x] m[x] + 2^(sh - 1)) >> sh of pixels 0 .. 8 (n / 8) - 1 (a masked pixel
 * kept; every unmasked result within int16); both return 8 (n / 8). */
uint32_t pft_pre_mline_n_(int16_t *m, uint32_t n, uint32_t s, uint32_t st);
uint32_t pft_pre_whiten_rown_(int16_t *r, const int16_t *m, uint32_t n, uint32_t sh);
#endif
#if defined(__SSE2__)
/* bg_anchor's update pass on x86-64 (SSE2), pre_temporal.c: anchor_hrow_'s blend of cells
 * ja .. jb in blocks of 8 (frame row zl, its biased int16 copy zs, tap offset ub, weights w,
 * tested taps ulo .. uhi) into hz, and the residual's vertical blends in the split form
 * (pft_pre_vsplit_ of each) of columns i0 .. c1 in blocks of 8; both return the first cell or
 * column left to the plain loop. */
int32_t pft_pre_hrow8_(const int32_t *zl, const int16_t *zs, int32_t ub, const int32_t w[4], int32_t ulo,
                       int32_t uhi, int32_t *hz, int32_t ja, int32_t jb);
int32_t pft_pre_vsplit8_(const uint16_t *const t[4], const int32_t w[4], int32_t *vb, int32_t i0, int32_t c1);
/* zspan_'s conversion of a U16 row (mask, lo, span, bf, column offsets cn) on x86-64 (SSE2):
 * pixels x0 .. x1 - 1 in blocks of 8 into zl (U units clamped to [0, 65535], -1 masked), the
 * masked ones added to *ninv; returns the first pixel left to the loop (pre_temporal.c). */
uint32_t pft_pre_zspan8_(const uint8_t *row, uint32_t mask, uint32_t lo, uint32_t span, uint32_t bf,
                         const int32_t *cn, int32_t *zl, uint32_t x0, uint32_t x1, uint32_t *ninv);
#endif

/* Integer square root of a 64-bit value (floor). */
uint32_t pft_pre_isqrt64_(uint64_t v);
/* floor(sqrt(mm 2^10)) for mm <= 65535 (the clutter map's sqrt(M) in Q10): the value of
 * pft_pre_isqrt64_((uint64_t)mm << 10) in fewer instructions (pre_clutter.c). */
uint32_t pft_pre_sqrt_q10_(uint32_t mm);
/* The clutter map's 8-bit code (map8, pre_clutter.c): the code of a Q6.10 value v <= 65535
 * with the rounding offset dz / 256 of a step (128: the nearest code), and a code's value. */
uint32_t pft_pre_clutter_enc8_(uint32_t v, uint32_t dz);
uint32_t pft_pre_clutter_dec8_(uint32_t c);

#endif
