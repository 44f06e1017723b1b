/* Preprocessing stage: the per-frame driver (docs/algorithms.md 9): input check, pass 1 of
 * the configured background method, tile noise, column offsets, whitening and peaks. */
#include <string.h>

#include "pre_int.h"

#if defined(__aarch64__) && defined(__ARM_NEON)
/* AArch64 (the Cortex-A53 class): the tile histogram's bins 8 pixels at a time
 * (pft_pre_hist_rown_) */
#include <arm_neon.h>
#define PFT_PRE_UPD_NEON_ 1
#elif defined(__SSE2__)
/* x86-64 (SSE2): the same 8-pixel form of the tile histogram (pft_pre_hist_rown_) */
#include <emmintrin.h>
#define PFT_PRE_UPD_SSE2_ 1
#endif

uint32_t pft_pre_isqrt64_(uint64_t v)
{
    uint64_t r = 0u, bit = (uint64_t)1 << 62;
    while (bit > v) {
        bit >>= 2;
    }
    while (bit != 0u) {
        if (v >= r + bit) {
            v -= r + bit;
            r = (r >> 1) + bit;
        } else {
            r >>= 1;
        }
        bit >>= 2;
    }
    return r > 0xFFFFFFFFu ? 0xFFFFFFFFu : (uint32_t)r;
}

/* Constancy of the unmasked pixels: scans until a second value appears (at once in a real
 * frame); *valid is false when no pixel is unmasked. */
static bool frame_constant_(const pft_pre_cls_t *c, const pft_frame_t *f, bool *valid)
{
    bool have = false;
    uint32_t ref = 0u;
    for (uint32_t y = 0; y < f->height; ++y) {
        const uint8_t *row = pft_frame_row(f, y);
        for (uint32_t x = 0; x < f->width; ++x) {
            const uint32_t v = pft_pre_raw_(row, x, c);
            if (!pft_pre_valid_(c, v, x, y)) {
                continue;
            }
            if (!have) {
                have = true;
                ref = v;
            } else if (v != ref) {
                *valid = true;
                return false;
            } else {
                /* the same value as the reference: keep scanning */
            }
        }
    }
    *valid = have;
    return true;
}

/* Sigma (R units Q4) of one tile from its histogram of |r| over n pixels: 1.4826 times the
 * median, interpolated within its bin; bin k < 16 holds the integer k, so it stands for
 * [k - 1/2, k + 1/2) (k = 0: [0, 1/2)), and a bin of integers [lo, lo + 2^e3) for
 * [lo - 1/2, lo + 2^e3 - 1/2). 0 if n is 0. */
static uint32_t tile_sigma_(const uint16_t *h, uint32_t n)
{
    uint32_t cum = 0u;
    for (uint32_t k = 0; k < PFT_PRE_BINS; ++k) {
        const uint32_t c = h[k];
        if (c == 0u || 2u * (cum + c) < n) {
            cum += c;
            continue;
        }
        /* the median is in bin k: lo2, w2 its range in half units */
        uint32_t lo2, w2;
        if (k == 0u) {
            lo2 = 0u;
            w2 = 1u;
        } else if (k < 16u) {
            lo2 = 2u * k - 1u;
            w2 = 2u;
        } else {
            const uint32_t e3 = (k >> 3) - 1u; /* values [(8 + k % 8) 2^e3, + 2^e3) */
            const uint32_t lo = (8u + (k & 7u)) << e3;
            lo2 = 2u * lo - 1u;
            w2 = 2u << e3;
        }
        /* median (Q4) = 8 lo2 + 8 w2 (n/2 - cum) / c */
        const uint64_t med = (uint64_t)8u * lo2 + ((uint64_t)4u * w2 * (n - 2u * cum)) / c;
        return (uint32_t)((med * PFT_PRE_MAD_K_ + 32768u) >> 16);
    }
    return 0u;
}

/* Whether the sigmas of tile row j are estimated in this frame (sigma_every, docs/algorithms.md
 * 9.6): every frame until a sigma is known, then tile row j on the frames n with
 * (n + j) % sigma_every == 0 (the rows take turns, so that every frame costs the same). */
static bool tilerow_fresh_(const pft_pre_t *p, uint32_t j)
{
    const uint32_t k = p->cfg.sigma_every;
    return k <= 1u || !p->sig_known || (p->frames + j) % k == 0u;
}

/* sigma_bracket (docs/algorithms.md 9.6): once a sigma is known, each tile counts its |r|
 * below PFT_PRE_BRK_K_ thresholds around the median of its last sigma (m / 2 .. 2 m, ratio
 * sqrt 2) instead of a histogram; the tile's slots of p->hist hold the counts (0..K - 1),
 * the unmasked count (PFT_PRE_BRK_N_) and the thresholds (from PFT_PRE_BRK_T_; 0: not yet
 * set in this tile row). */
#define PFT_PRE_BRK_K_ 5u
#define PFT_PRE_BRK_N_ 5u
#define PFT_PRE_BRK_T_ 8u

static bool bracket_on_(const pft_pre_t *p)
{
    return p->cfg.sigma_bracket && p->sig_known;
}

/* The thresholds of tile (j, i) from its last sigma s (R units Q4): integers T_k, a count of
 * |r| < T_k placing the edge at T_k - 1/2, nearest to m 2^((k - 2) / 2), m = s / 1.4826 the
 * last median; T_0 >= 1 and increasing. */
static void bracket_set_(uint16_t *hist, uint32_t s)
{
    /* 2^((k - 2) / 2) / 1.4826 in Q16 */
    static const uint32_t ratio_[PFT_PRE_BRK_K_] = {22102u, 31257u, 44204u, 62514u, 88408u};
    uint32_t prev = 0u;
    for (uint32_t k = 0; k < PFT_PRE_BRK_K_; ++k) {
        /* edge (Q4) = s ratio; T = edge + 1/2 rounded: (edge + 8 + 8) >> 4 */
        const uint64_t e = ((uint64_t)s * ratio_[k] + 32768u) >> 16;
        uint32_t tk = (uint32_t)((e + 16u) >> 4);
        tk = tk <= prev ? prev + 1u : tk;
        tk = tk > (uint32_t)PFT_PRE_RMAX_ ? (uint32_t)PFT_PRE_RMAX_ : tk;
        hist[PFT_PRE_BRK_T_ + k] = (uint16_t)tk;
        prev = tk;
    }
}

/* Sigma (R units Q4) from the counts of n unmasked pixels: 1.4826 times the median, found
 * between the edges T_k - 1/2 around it and interpolated linearly; outside the edges by the
 * straight line from 0 through the nearest one: below the lowest (m / 2) the estimate falls
 * at most 4 times a frame, above the highest (2 m) a Gaussian's median is read within 7 %
 * low up to 5 times m (a straight line from 0 for the distribution of |r|), larger jumps
 * followed over the next frames. */
static uint32_t bracket_sigma_(const uint16_t *h, uint32_t n)
{
    uint64_t med; /* Q4 */
    const uint32_t kt = PFT_PRE_BRK_K_ - 1u;
    if (2u * (uint32_t)h[kt] <= n) {
        const uint64_t top = 16u * (uint64_t)h[PFT_PRE_BRK_T_ + kt] - 8u;
        const uint32_t c = h[kt] > 0u ? h[kt] : 1u;
        med = (top * n) / (2u * (uint64_t)c);
    } else {
        uint32_t k = 0u;
        while (2u * (uint32_t)h[k] <= n) { /* ends: 2 h[K - 1] > n */
            k++;
        }
        const uint32_t ca = k > 0u ? h[k - 1u] : 0u, cb = h[k];
        const uint64_t ea = k > 0u ? 16u * (uint64_t)h[PFT_PRE_BRK_T_ + k - 1u] - 8u : 0u;
        const uint64_t eb = 16u * (uint64_t)h[PFT_PRE_BRK_T_ + k] - 8u;
        /* ca <= n / 2 < cb */
        med = ea + ((eb - ea) * (n - 2u * ca)) / (2u * (uint64_t)(cb - ca));
    }
    const uint64_t s = (med * PFT_PRE_MAD_K_ + 32768u) >> 16;
    return s > 0x7FFFFFFFu ? 0x7FFFFFFFu : (uint32_t)s;
}

/* pft_pre_bin_(|v|) for |v| < PFT_PRE_BIN_LUT_ (most residuals) at index v + PFT_PRE_BIN_LUT_ - 1,
 * looked up instead of computed (on x86-64 about 3 instructions instead of 7 with |v|);
 * every entry equals the function's value (host_tools/scripts/pre_bin_table.py --check, the
 * host-q16 ctest pre_bin_table, compares all 2047; --print writes them). */
#define PFT_PRE_BIN_LUT_ 1024
#define PFT_PRE_BIN_N_ 2047u /* 2 PFT_PRE_BIN_LUT_ - 1 entries */

/* The column sums of one tile's span of a residual row, each value clipped to +-clip and a
 * masked pixel counted as 0 (every PFT_PRE_COL_ROWS_-th row; vectorisable: 16-bit min/max). */
static inline void colsum_add_(int32_t *cs, const int16_t *r, uint32_t x0, uint32_t x1,
                               int16_t clip)
{
    const int16_t nclip = (int16_t)-clip;
    for (uint32_t x = x0; x < x1; ++x) {
        const int16_t v = r[x];
        const int16_t c = v < nclip ? nclip : (v > clip ? clip : v);
        cs[x] += v == PFT_RES16_MASKED ? 0 : c;
    }
}


/* One residual into its tile histogram (hist_add_): its bin (hist_bin_) from the table for
 * |v| < PFT_PRE_BIN_LUT_, pft_pre_bin_ beyond (a masked pixel, |INT16_MIN| = 32768, lands in
 * the extra bin PFT_PRE_BINS). */
static const uint8_t bin_lut_[PFT_PRE_BIN_N_] = {
    63, 63, 63, 63, 63, 63, 63, 63, 63, 63, 63, 63, 63, 63, 63, 63,
    63, 63, 63, 63, 63, 63, 63, 63, 63, 63, 63, 63, 63, 63, 63, 63,
    63, 63, 63, 63, 63, 63, 63, 63, 63, 63, 63, 63, 63, 63, 63, 63,
    63, 63, 63, 63, 63, 63, 63, 63, 63, 63, 63, 63, 63, 63, 63, 63,
    62, 62, 62, 62, 62, 62, 62, 62, 62, 62, 62, 62, 62, 62, 62, 62,
    62, 62, 62, 62, 62, 62, 62, 62, 62, 62, 62, 62, 62, 62, 62, 62,
    62, 62, 62, 62, 62, 62, 62, 62, 62, 62, 62, 62, 62, 62, 62, 62,
    62, 62, 62, 62, 62, 62, 62, 62, 62, 62, 62, 62, 62, 62, 62, 62,
    61, 61, 61, 61, 61, 61, 61, 61, 61, 61, 61, 61, 61, 61, 61, 61,
    61, 61, 61, 61, 61, 61, 61, 61, 61, 61, 61, 61, 61, 61, 61, 61,
    61, 61, 61, 61, 61, 61, 61, 61, 61, 61, 61, 61, 61, 61, 61, 61,
    61, 61, 61, 61, 61, 61, 61, 61, 61, 61, 61, 61, 61, 61, 61, 61,
    60, 60, 60, 60, 60, 60, 60, 60, 60, 60, 60, 60, 60, 60, 60, 60,
    60, 60, 60, 60, 60, 60, 60, 60, 60, 60, 60, 60, 60, 60, 60, 60,
    60, 60, 60, 60, 60, 60, 60, 60, 60, 60, 60, 60, 60, 60, 60, 60,
    60, 60, 60, 60, 60, 60, 60, 60, 60, 60, 60, 60, 60, 60, 60, 60,
    59, 59, 59, 59, 59, 59, 59, 59, 59, 59, 59, 59, 59, 59, 59, 59,
    59, 59, 59, 59, 59, 59, 59, 59, 59, 59, 59, 59, 59, 59, 59, 59,
    59, 59, 59, 59, 59, 59, 59, 59, 59, 59, 59, 59, 59, 59, 59, 59,
    59, 59, 59, 59, 59, 59, 59, 59, 59, 59, 59, 59, 59, 59, 59, 59,
    58, 58, 58, 58, 58, 58, 58, 58, 58, 58, 58, 58, 58, 58, 58, 58,
    58, 58, 58, 58, 58, 58, 58, 58, 58, 58, 58, 58, 58, 58, 58, 58,
    58, 58, 58, 58, 58, 58, 58, 58, 58, 58, 58, 58, 58, 58, 58, 58,
    58, 58, 58, 58, 58, 58, 58, 58, 58, 58, 58, 58, 58, 58, 58, 58,
    57, 57, 57, 57, 57, 57, 57, 57, 57, 57, 57, 57, 57, 57, 57, 57,
    57, 57, 57, 57, 57, 57, 57, 57, 57, 57, 57, 57, 57, 57, 57, 57,
    57, 57, 57, 57, 57, 57, 57, 57, 57, 57, 57, 57, 57, 57, 57, 57,
    57, 57, 57, 57, 57, 57, 57, 57, 57, 57, 57, 57, 57, 57, 57, 57,
    56, 56, 56, 56, 56, 56, 56, 56, 56, 56, 56, 56, 56, 56, 56, 56,
    56, 56, 56, 56, 56, 56, 56, 56, 56, 56, 56, 56, 56, 56, 56, 56,
    56, 56, 56, 56, 56, 56, 56, 56, 56, 56, 56, 56, 56, 56, 56, 56,
    56, 56, 56, 56, 56, 56, 56, 56, 56, 56, 56, 56, 56, 56, 56, 56,
    55, 55, 55, 55, 55, 55, 55, 55, 55, 55, 55, 55, 55, 55, 55, 55,
    55, 55, 55, 55, 55, 55, 55, 55, 55, 55, 55, 55, 55, 55, 55, 55,
    54, 54, 54, 54, 54, 54, 54, 54, 54, 54, 54, 54, 54, 54, 54, 54,
    54, 54, 54, 54, 54, 54, 54, 54, 54, 54, 54, 54, 54, 54, 54, 54,
    53, 53, 53, 53, 53, 53, 53, 53, 53, 53, 53, 53, 53, 53, 53, 53,
    53, 53, 53, 53, 53, 53, 53, 53, 53, 53, 53, 53, 53, 53, 53, 53,
    52, 52, 52, 52, 52, 52, 52, 52, 52, 52, 52, 52, 52, 52, 52, 52,
    52, 52, 52, 52, 52, 52, 52, 52, 52, 52, 52, 52, 52, 52, 52, 52,
    51, 51, 51, 51, 51, 51, 51, 51, 51, 51, 51, 51, 51, 51, 51, 51,
    51, 51, 51, 51, 51, 51, 51, 51, 51, 51, 51, 51, 51, 51, 51, 51,
    50, 50, 50, 50, 50, 50, 50, 50, 50, 50, 50, 50, 50, 50, 50, 50,
    50, 50, 50, 50, 50, 50, 50, 50, 50, 50, 50, 50, 50, 50, 50, 50,
    49, 49, 49, 49, 49, 49, 49, 49, 49, 49, 49, 49, 49, 49, 49, 49,
    49, 49, 49, 49, 49, 49, 49, 49, 49, 49, 49, 49, 49, 49, 49, 49,
    48, 48, 48, 48, 48, 48, 48, 48, 48, 48, 48, 48, 48, 48, 48, 48,
    48, 48, 48, 48, 48, 48, 48, 48, 48, 48, 48, 48, 48, 48, 48, 48,
    47, 47, 47, 47, 47, 47, 47, 47, 47, 47, 47, 47, 47, 47, 47, 47,
    46, 46, 46, 46, 46, 46, 46, 46, 46, 46, 46, 46, 46, 46, 46, 46,
    45, 45, 45, 45, 45, 45, 45, 45, 45, 45, 45, 45, 45, 45, 45, 45,
    44, 44, 44, 44, 44, 44, 44, 44, 44, 44, 44, 44, 44, 44, 44, 44,
    43, 43, 43, 43, 43, 43, 43, 43, 43, 43, 43, 43, 43, 43, 43, 43,
    42, 42, 42, 42, 42, 42, 42, 42, 42, 42, 42, 42, 42, 42, 42, 42,
    41, 41, 41, 41, 41, 41, 41, 41, 41, 41, 41, 41, 41, 41, 41, 41,
    40, 40, 40, 40, 40, 40, 40, 40, 40, 40, 40, 40, 40, 40, 40, 40,
    39, 39, 39, 39, 39, 39, 39, 39, 38, 38, 38, 38, 38, 38, 38, 38,
    37, 37, 37, 37, 37, 37, 37, 37, 36, 36, 36, 36, 36, 36, 36, 36,
    35, 35, 35, 35, 35, 35, 35, 35, 34, 34, 34, 34, 34, 34, 34, 34,
    33, 33, 33, 33, 33, 33, 33, 33, 32, 32, 32, 32, 32, 32, 32, 32,
    31, 31, 31, 31, 30, 30, 30, 30, 29, 29, 29, 29, 28, 28, 28, 28,
    27, 27, 27, 27, 26, 26, 26, 26, 25, 25, 25, 25, 24, 24, 24, 24,
    23, 23, 22, 22, 21, 21, 20, 20, 19, 19, 18, 18, 17, 17, 16, 16,
    15, 14, 13, 12, 11, 10, 9, 8, 7, 6, 5, 4, 3, 2, 1, 0,
    1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15, 16,
    16, 17, 17, 18, 18, 19, 19, 20, 20, 21, 21, 22, 22, 23, 23, 24,
    24, 24, 24, 25, 25, 25, 25, 26, 26, 26, 26, 27, 27, 27, 27, 28,
    28, 28, 28, 29, 29, 29, 29, 30, 30, 30, 30, 31, 31, 31, 31, 32,
    32, 32, 32, 32, 32, 32, 32, 33, 33, 33, 33, 33, 33, 33, 33, 34,
    34, 34, 34, 34, 34, 34, 34, 35, 35, 35, 35, 35, 35, 35, 35, 36,
    36, 36, 36, 36, 36, 36, 36, 37, 37, 37, 37, 37, 37, 37, 37, 38,
    38, 38, 38, 38, 38, 38, 38, 39, 39, 39, 39, 39, 39, 39, 39, 40,
    40, 40, 40, 40, 40, 40, 40, 40, 40, 40, 40, 40, 40, 40, 40, 41,
    41, 41, 41, 41, 41, 41, 41, 41, 41, 41, 41, 41, 41, 41, 41, 42,
    42, 42, 42, 42, 42, 42, 42, 42, 42, 42, 42, 42, 42, 42, 42, 43,
    43, 43, 43, 43, 43, 43, 43, 43, 43, 43, 43, 43, 43, 43, 43, 44,
    44, 44, 44, 44, 44, 44, 44, 44, 44, 44, 44, 44, 44, 44, 44, 45,
    45, 45, 45, 45, 45, 45, 45, 45, 45, 45, 45, 45, 45, 45, 45, 46,
    46, 46, 46, 46, 46, 46, 46, 46, 46, 46, 46, 46, 46, 46, 46, 47,
    47, 47, 47, 47, 47, 47, 47, 47, 47, 47, 47, 47, 47, 47, 47, 48,
    48, 48, 48, 48, 48, 48, 48, 48, 48, 48, 48, 48, 48, 48, 48, 48,
    48, 48, 48, 48, 48, 48, 48, 48, 48, 48, 48, 48, 48, 48, 48, 49,
    49, 49, 49, 49, 49, 49, 49, 49, 49, 49, 49, 49, 49, 49, 49, 49,
    49, 49, 49, 49, 49, 49, 49, 49, 49, 49, 49, 49, 49, 49, 49, 50,
    50, 50, 50, 50, 50, 50, 50, 50, 50, 50, 50, 50, 50, 50, 50, 50,
    50, 50, 50, 50, 50, 50, 50, 50, 50, 50, 50, 50, 50, 50, 50, 51,
    51, 51, 51, 51, 51, 51, 51, 51, 51, 51, 51, 51, 51, 51, 51, 51,
    51, 51, 51, 51, 51, 51, 51, 51, 51, 51, 51, 51, 51, 51, 51, 52,
    52, 52, 52, 52, 52, 52, 52, 52, 52, 52, 52, 52, 52, 52, 52, 52,
    52, 52, 52, 52, 52, 52, 52, 52, 52, 52, 52, 52, 52, 52, 52, 53,
    53, 53, 53, 53, 53, 53, 53, 53, 53, 53, 53, 53, 53, 53, 53, 53,
    53, 53, 53, 53, 53, 53, 53, 53, 53, 53, 53, 53, 53, 53, 53, 54,
    54, 54, 54, 54, 54, 54, 54, 54, 54, 54, 54, 54, 54, 54, 54, 54,
    54, 54, 54, 54, 54, 54, 54, 54, 54, 54, 54, 54, 54, 54, 54, 55,
    55, 55, 55, 55, 55, 55, 55, 55, 55, 55, 55, 55, 55, 55, 55, 55,
    55, 55, 55, 55, 55, 55, 55, 55, 55, 55, 55, 55, 55, 55, 55, 56,
    56, 56, 56, 56, 56, 56, 56, 56, 56, 56, 56, 56, 56, 56, 56, 56,
    56, 56, 56, 56, 56, 56, 56, 56, 56, 56, 56, 56, 56, 56, 56, 56,
    56, 56, 56, 56, 56, 56, 56, 56, 56, 56, 56, 56, 56, 56, 56, 56,
    56, 56, 56, 56, 56, 56, 56, 56, 56, 56, 56, 56, 56, 56, 56, 57,
    57, 57, 57, 57, 57, 57, 57, 57, 57, 57, 57, 57, 57, 57, 57, 57,
    57, 57, 57, 57, 57, 57, 57, 57, 57, 57, 57, 57, 57, 57, 57, 57,
    57, 57, 57, 57, 57, 57, 57, 57, 57, 57, 57, 57, 57, 57, 57, 57,
    57, 57, 57, 57, 57, 57, 57, 57, 57, 57, 57, 57, 57, 57, 57, 58,
    58, 58, 58, 58, 58, 58, 58, 58, 58, 58, 58, 58, 58, 58, 58, 58,
    58, 58, 58, 58, 58, 58, 58, 58, 58, 58, 58, 58, 58, 58, 58, 58,
    58, 58, 58, 58, 58, 58, 58, 58, 58, 58, 58, 58, 58, 58, 58, 58,
    58, 58, 58, 58, 58, 58, 58, 58, 58, 58, 58, 58, 58, 58, 58, 59,
    59, 59, 59, 59, 59, 59, 59, 59, 59, 59, 59, 59, 59, 59, 59, 59,
    59, 59, 59, 59, 59, 59, 59, 59, 59, 59, 59, 59, 59, 59, 59, 59,
    59, 59, 59, 59, 59, 59, 59, 59, 59, 59, 59, 59, 59, 59, 59, 59,
    59, 59, 59, 59, 59, 59, 59, 59, 59, 59, 59, 59, 59, 59, 59, 60,
    60, 60, 60, 60, 60, 60, 60, 60, 60, 60, 60, 60, 60, 60, 60, 60,
    60, 60, 60, 60, 60, 60, 60, 60, 60, 60, 60, 60, 60, 60, 60, 60,
    60, 60, 60, 60, 60, 60, 60, 60, 60, 60, 60, 60, 60, 60, 60, 60,
    60, 60, 60, 60, 60, 60, 60, 60, 60, 60, 60, 60, 60, 60, 60, 61,
    61, 61, 61, 61, 61, 61, 61, 61, 61, 61, 61, 61, 61, 61, 61, 61,
    61, 61, 61, 61, 61, 61, 61, 61, 61, 61, 61, 61, 61, 61, 61, 61,
    61, 61, 61, 61, 61, 61, 61, 61, 61, 61, 61, 61, 61, 61, 61, 61,
    61, 61, 61, 61, 61, 61, 61, 61, 61, 61, 61, 61, 61, 61, 61, 62,
    62, 62, 62, 62, 62, 62, 62, 62, 62, 62, 62, 62, 62, 62, 62, 62,
    62, 62, 62, 62, 62, 62, 62, 62, 62, 62, 62, 62, 62, 62, 62, 62,
    62, 62, 62, 62, 62, 62, 62, 62, 62, 62, 62, 62, 62, 62, 62, 62,
    62, 62, 62, 62, 62, 62, 62, 62, 62, 62, 62, 62, 62, 62, 62, 63,
    63, 63, 63, 63, 63, 63, 63, 63, 63, 63, 63, 63, 63, 63, 63, 63,
    63, 63, 63, 63, 63, 63, 63, 63, 63, 63, 63, 63, 63, 63, 63, 63,
    63, 63, 63, 63, 63, 63, 63, 63, 63, 63, 63, 63, 63, 63, 63, 63,
    63, 63, 63, 63, 63, 63, 63, 63, 63, 63, 63, 63, 63, 63, 63,
};
static inline uint32_t hist_bin_(int32_t v)
{
    const uint32_t k = (uint32_t)(v + (PFT_PRE_BIN_LUT_ - 1));
    return k < PFT_PRE_BIN_N_ ? bin_lut_[k] : pft_pre_bin_((uint32_t)(v < 0 ? -v : v));
}
static inline void hist_add_(uint16_t *hist, int32_t v) { hist[hist_bin_(v)]++; }
/* hist_bin_ of four residuals: when all four are in the table (the common case) one test and
 * the four table reads side by side. */
static inline void hist_bin4_(int32_t v0, int32_t v1, int32_t v2, int32_t v3, uint32_t *b0,
                              uint32_t *b1, uint32_t *b2, uint32_t *b3)
{
    const uint32_t k0 = (uint32_t)(v0 + (PFT_PRE_BIN_LUT_ - 1));
    const uint32_t k1 = (uint32_t)(v1 + (PFT_PRE_BIN_LUT_ - 1));
    const uint32_t k2 = (uint32_t)(v2 + (PFT_PRE_BIN_LUT_ - 1));
    const uint32_t k3 = (uint32_t)(v3 + (PFT_PRE_BIN_LUT_ - 1));
    if (k0 < PFT_PRE_BIN_N_ && k1 < PFT_PRE_BIN_N_ && k2 < PFT_PRE_BIN_N_ &&
        k3 < PFT_PRE_BIN_N_) {
        *b0 = bin_lut_[k0];
        *b1 = bin_lut_[k1];
        *b2 = bin_lut_[k2];
        *b3 = bin_lut_[k3];
    } else {
        *b0 = hist_bin_(v0);
        *b1 = hist_bin_(v1);
        *b2 = hist_bin_(v2);
        *b3 = hist_bin_(v3);
    }
}

#if defined(PFT_PRE_UPD_NEON_)
/* hist_bin_ of 8 residuals at a time: their table indices v + PFT_PRE_BIN_LUT_ - 1 in 16-bit
 * lanes (wrapping: below PFT_PRE_BIN_N_ exactly when the 32-bit index is), one test of the
 * largest, then the 8 table reads before the 8 counts (an in-order core overlaps the reads);
 * a block with a value beyond the table takes hist_add_. The same counts. */
uint32_t pft_pre_hist_rown_(uint16_t *hist, const int16_t *r, uint32_t n)
{
    const uint16x8_t off = vdupq_n_u16((uint16_t)(PFT_PRE_BIN_LUT_ - 1));
    const uint32_t ne = n / 8u * 8u;
    for (uint32_t x = 0; x < ne; x += 8u) {
        const uint16x8_t k = vaddq_u16(vreinterpretq_u16_s16(vld1q_s16(&r[x])), off);
        if (vmaxvq_u16(k) < (uint16_t)PFT_PRE_BIN_N_) {
            const uint32_t b0 = bin_lut_[vgetq_lane_u16(k, 0)];
            const uint32_t b1 = bin_lut_[vgetq_lane_u16(k, 1)];
            const uint32_t b2 = bin_lut_[vgetq_lane_u16(k, 2)];
            const uint32_t b3 = bin_lut_[vgetq_lane_u16(k, 3)];
            const uint32_t b4 = bin_lut_[vgetq_lane_u16(k, 4)];
            const uint32_t b5 = bin_lut_[vgetq_lane_u16(k, 5)];
            const uint32_t b6 = bin_lut_[vgetq_lane_u16(k, 6)];
            const uint32_t b7 = bin_lut_[vgetq_lane_u16(k, 7)];
            hist[b0]++;
            hist[b1]++;
            hist[b2]++;
            hist[b3]++;
            hist[b4]++;
            hist[b5]++;
            hist[b6]++;
            hist[b7]++;
        } else {
            for (uint32_t i = 0; i < 8u; ++i) {
                hist_add_(hist, r[x + i]);
            }
        }
    }
    return ne;
}
#elif defined(PFT_PRE_UPD_SSE2_)
/* SSE2's twin of the NEON form above: the table indices in 16-bit lanes (paddw, wrapping), all
 * 8 below PFT_PRE_BIN_N_ exactly when their unsigned saturating difference with
 * PFT_PRE_BIN_N_ - 1 is 0 in every lane (psubusw, pcmpeqw, pmovmskb: one test), then the 8 lanes
 * (pextrw) and their table reads before the 8 counts; a block with a value beyond the table
 * takes hist_add_. The same counts. */
uint32_t pft_pre_hist_rown_(uint16_t *hist, const int16_t *r, uint32_t n)
{
    const __m128i off = _mm_set1_epi16((int16_t)(PFT_PRE_BIN_LUT_ - 1));
    const __m128i top = _mm_set1_epi16((int16_t)(PFT_PRE_BIN_N_ - 1u));
    const __m128i zero = _mm_setzero_si128();
    const uint32_t ne = n / 8u * 8u;
    for (uint32_t x = 0; x < ne; x += 8u) {
        const __m128i k = _mm_add_epi16(_mm_loadu_si128((const __m128i *)(const void *)&r[x]), off);
        if (_mm_movemask_epi8(_mm_cmpeq_epi16(_mm_subs_epu16(k, top), zero)) == 0xFFFF) {
            const uint32_t b0 = bin_lut_[_mm_extract_epi16(k, 0)];
            const uint32_t b1 = bin_lut_[_mm_extract_epi16(k, 1)];
            const uint32_t b2 = bin_lut_[_mm_extract_epi16(k, 2)];
            const uint32_t b3 = bin_lut_[_mm_extract_epi16(k, 3)];
            const uint32_t b4 = bin_lut_[_mm_extract_epi16(k, 4)];
            const uint32_t b5 = bin_lut_[_mm_extract_epi16(k, 5)];
            const uint32_t b6 = bin_lut_[_mm_extract_epi16(k, 6)];
            const uint32_t b7 = bin_lut_[_mm_extract_epi16(k, 7)];
            hist[b0]++;
            hist[b1]++;
            hist[b2]++;
            hist[b3]++;
            hist[b4]++;
            hist[b5]++;
            hist[b6]++;
            hist[b7]++;
        } else {
            for (uint32_t i = 0; i < 8u; ++i) {
                hist_add_(hist, r[x + i]);
            }
        }
    }
    return ne;
}
#endif

/* sigma_bracket: the counts of one tile's span below the tile's five thresholds, and of its
 * unmasked pixels, added to the tile's record; returns the masked pixels of the span. */
static inline uint32_t bracket_add_(uint16_t *hist, const int16_t *r, uint32_t x0, uint32_t x1)
{
    const uint16_t t0 = hist[PFT_PRE_BRK_T_], t1 = hist[PFT_PRE_BRK_T_ + 1u];
    const uint16_t t2 = hist[PFT_PRE_BRK_T_ + 2u], t3 = hist[PFT_PRE_BRK_T_ + 3u];
    const uint16_t t4 = hist[PFT_PRE_BRK_T_ + 4u];
    uint16_t c0 = 0u, c1 = 0u, c2 = 0u, c3 = 0u, c4 = 0u, cn = 0u;
    for (uint32_t x = x0; x < x1; ++x) { /* vectorisable: 16-bit compares */
        const int32_t v = r[x];
        const uint16_t a = (uint16_t)(v < 0 ? -v : v); /* masked: 32768 */
        c0 = (uint16_t)(c0 + (a < t0 ? 1u : 0u));
        c1 = (uint16_t)(c1 + (a < t1 ? 1u : 0u));
        c2 = (uint16_t)(c2 + (a < t2 ? 1u : 0u));
        c3 = (uint16_t)(c3 + (a < t3 ? 1u : 0u));
        c4 = (uint16_t)(c4 + (a < t4 ? 1u : 0u));
        cn = (uint16_t)(cn + (a < 32768u ? 1u : 0u));
    }
    hist[0] = (uint16_t)(hist[0] + c0);
    hist[1] = (uint16_t)(hist[1] + c1);
    hist[2] = (uint16_t)(hist[2] + c2);
    hist[3] = (uint16_t)(hist[3] + c3);
    hist[4] = (uint16_t)(hist[4] + c4);
    hist[PFT_PRE_BRK_N_] = (uint16_t)(hist[PFT_PRE_BRK_N_] + cn);
    return (x1 - x0) - cn;
}

/* sigma_level (docs/algorithms.md 9.6 [E]): one tile's span into its histogram as |r - c|, c the
 * tile's level (R units, from the last frame that estimated the tile); on the rows of the
 * column sums also the residual clipped at the column sums' clip (3 sigma) and its count into
 * the tile column's sums, for the next level. A masked pixel lands in the extra bin as without
 * the option and enters no sum; returns the masked pixels of the span. */
static uint32_t level_add_(pft_pre_t *p, uint16_t *hist, const int16_t *r, uint32_t x0,
                           uint32_t x1, uint32_t j, uint32_t i, bool colrow)
{
    const int32_t c = p->tlev[j * p->ntx + i];
    uint32_t nm = 0u;
    for (uint32_t x = x0; x < x1; ++x) {
        const int32_t v = r[x];
        const bool masked = v == PFT_RES16_MASKED;
        hist[masked ? PFT_PRE_BINS : hist_bin_(pft_pre_rclamp_(v - c))]++;
        nm += masked ? 1u : 0u;
    }
    if (colrow) {
        const int32_t clip = pft_pre_clip_(p, j, i);
        int32_t sum = 0; /* at most 64 rows of 255 pixels of 32767: within 31 bits */
        for (uint32_t x = x0; x < x1; ++x) {
            const int32_t v = r[x];
            const int32_t cv = v < -clip ? -clip : (v > clip ? clip : v);
            sum += v == PFT_RES16_MASKED ? 0 : cv;
        }
        p->lsum[2u * i] += sum;
        p->lsum[2u * i + 1u] += (int32_t)((x1 - x0) - nm);
    }
    return nm;
}

uint32_t pft_pre_book_row_(pft_pre_t *p, uint32_t y)
{
    const uint32_t w = p->cfg.width, t = p->cfg.tile, j = y / t;
    const int16_t *r = p->res + (size_t)y * w;
    int32_t *cs = p->csum;
    const bool colrow = y % PFT_PRE_COL_ROWS_ == 0u; /* column sums: every 4th row */
    const uint32_t ss = p->cfg.sigma_step > 1u ? p->cfg.sigma_step : 1u;
    uint32_t nm = 0u;
    const bool fresh = tilerow_fresh_(p, j);
    if (bracket_on_(p)) {
        /* sigma_bracket: counts below the tile's thresholds (16-bit compares, vectorisable) */
        for (uint32_t i = 0; i < p->ntx; ++i) {
            const uint32_t x0 = i * t, x1 = x0 + t > w ? w : x0 + t;
            if (colrow) {
                colsum_add_(cs, r, x0, x1, (int16_t)pft_pre_clip_(p, j, i));
            }
            uint16_t *hist = p->hist + (size_t)i * (PFT_PRE_BINS + 1u);
            if (hist[PFT_PRE_BRK_T_] == 0u) {
                bracket_set_(hist, p->tsig[j * p->ntx + i] & ~PFT_PRE_TILE_STALE_);
            }
            nm += bracket_add_(hist, r, x0, x1);
        }
        return nm;
    }
    if (ss > 1u || !fresh) {
        /* sigma_step: the histograms take the sampled pixels of the sampled rows; sigma_every:
         * only in the frames that estimate this tile row; the masked pixels and the column sums
         * every pixel */
        for (uint32_t x = 0; x < w; ++x) { /* vectorisable: a 16-bit compare */
            nm += r[x] == PFT_RES16_MASKED ? 1u : 0u;
        }
        const bool hrow = fresh && y % ss == 0u;
        for (uint32_t i = 0; i < p->ntx; ++i) {
            const uint32_t x0 = i * t, x1 = x0 + t > w ? w : x0 + t;
            if (colrow) {
                colsum_add_(cs, r, x0, x1, (int16_t)pft_pre_clip_(p, j, i));
            }
            uint16_t *hist = p->hist + (size_t)i * (PFT_PRE_BINS + 1u);
            for (uint32_t x = (x0 + ss - 1u) / ss * ss; hrow && x < x1; x += ss) {
                hist_add_(hist, r[x]);
            }
        }
        return nm;
    }
    for (uint32_t i = 0; i < p->ntx; ++i) {
        const uint32_t x0 = i * t, x1 = x0 + t > w ? w : x0 + t;
        if (colrow) {
            colsum_add_(cs, r, x0, x1, (int16_t)pft_pre_clip_(p, j, i));
        }
        /* a masked pixel (|INT16_MIN| = 32768) lands in the extra bin PFT_PRE_BINS */
        uint16_t *hist = p->hist + (size_t)i * (PFT_PRE_BINS + 1u);
        if (p->tlev != NULL) {
            nm += level_add_(p, hist, r, x0, x1, j, i, colrow);
            continue;
        }
        const uint16_t before = hist[PFT_PRE_BINS];
        uint32_t x = x0;
#if defined(PFT_PRE_UPD_NEON_) || defined(PFT_PRE_UPD_SSE2_)
        x += pft_pre_hist_rown_(hist, &r[x0], x1 - x0);
#endif
        for (; x + 3u < x1; x += 4u) { /* four pixels per iteration: a quarter of the loop's own work */
            /* the four bins first, then the four counts: the pixels' loads and table reads do
             * not wait behind a count's load, add and store (a count may alias a pixel for the
             * compiler), so an in-order core overlaps them; the same counts */
            const int32_t v0 = r[x];
            const int32_t v1 = r[x + 1u];
            const int32_t v2 = r[x + 2u];
            const int32_t v3 = r[x + 3u];
            uint32_t b0, b1, b2, b3;
            hist_bin4_(v0, v1, v2, v3, &b0, &b1, &b2, &b3);
            hist[b0]++;
            hist[b1]++;
            hist[b2]++;
            hist[b3]++;
        }
        for (; x < x1; ++x) {
            hist_add_(hist, r[x]);
        }
        nm += (uint16_t)(hist[PFT_PRE_BINS] - before);
    }
    return nm;
}

void pft_pre_tilerow_done_(pft_pre_t *p, uint32_t j)
{
    const uint32_t t = p->cfg.tile, w = p->cfg.width, h = p->cfg.height;
    const uint32_t y0 = j * t, ny = (y0 + t > h ? h : y0 + t) - y0;
    if (!tilerow_fresh_(p, j)) {
        return; /* sigma_every: the row's sigmas are kept (its histograms are empty) */
    }
    const bool brk = bracket_on_(p);
    for (uint32_t i = 0; i < p->ntx; ++i) {
        uint16_t *hist = p->hist + (size_t)i * (PFT_PRE_BINS + 1u);
        const uint32_t x0 = i * t, nx = (x0 + t > w ? w : x0 + t) - x0;
        uint32_t n = 0u;
        for (uint32_t k = 0; !brk && k < PFT_PRE_BINS; ++k) {
            n += hist[k];
        }
        n = brk ? hist[PFT_PRE_BRK_N_] : n;
        /* at least 1/16 of the tile's pixels (of its sampled ones with sigma_step), and 16 */
        const uint32_t ss = p->cfg.sigma_step > 1u ? p->cfg.sigma_step : 1u;
        const uint32_t nxs = (x0 + nx + ss - 1u) / ss - (x0 + ss - 1u) / ss;
        const uint32_t nys = (y0 + ny + ss - 1u) / ss - (y0 + ss - 1u) / ss;
        const uint32_t need = (nxs * nys) / 16u > 16u ? (nxs * nys) / 16u : 16u;
        uint32_t *ts = &p->tsig[j * p->ntx + i];
        if (n >= need) {
            *ts = brk ? bracket_sigma_(hist, n) : tile_sigma_(hist, n);
        } else {
            *ts = (*ts & ~PFT_PRE_TILE_STALE_) | PFT_PRE_TILE_STALE_;
        }
        memset(hist, 0, (PFT_PRE_BINS + 1u) * 2u);
        if (p->tlev != NULL) {
            /* sigma_level: the tile's next level, the mean of its clipped residual (rounded
             * half away from zero; kept when fewer than 16 pixels entered) */
            const int32_t ls = p->lsum[2u * i], ln = p->lsum[2u * i + 1u];
            if (ln >= 16) {
                const int32_t a = ls < 0 ? -ls : ls;
                const int32_t q = (a + ln / 2) / ln;
                p->tlev[j * p->ntx + i] = ls < 0 ? -q : q;
            }
            p->lsum[2u * i] = 0;
            p->lsum[2u * i + 1u] = 0;
        }
    }
}

/* Tiles without enough pixels take the mean of the estimated ones (or keep their last value
 * when none was estimated); every sigma is floored; multipliers and statistics. */
static void tiles_finish_(pft_pre_t *p, pft_pre_acc_t *acc)
{
    const uint32_t nt = p->ntx * p->nty;
    const uint32_t floor_q4 = (uint32_t)p->cfg.sigma_floor << p->rs;
    uint64_t sum = 0u;
    uint32_t nvalid = 0u;
    for (uint32_t k = 0; k < nt; ++k) {
        if ((p->tsig[k] & PFT_PRE_TILE_STALE_) == 0u) {
            sum += p->tsig[k];
            nvalid++;
        }
    }
    const uint32_t fill = nvalid > 0u ? (uint32_t)(sum / nvalid) : 0u;
    if (nvalid > 0u) {
        p->sig_known = true;
    }
    uint32_t smin = 0xFFFFFFFFu, smax = 0u;
    uint64_t ssum = 0u;
    for (uint32_t k = 0; k < nt; ++k) {
        uint32_t s = p->tsig[k];
        if ((s & PFT_PRE_TILE_STALE_) != 0u) {
            s = nvalid > 0u ? fill : (s & ~PFT_PRE_TILE_STALE_);
        }
        if (s < floor_q4) {
            s = floor_q4;
            acc->flags |= PFT_PRE_FLAG_SIGMA_FLOOR;
        }
        p->tsig[k] = s;
        p->tmul[k] = (PFT_PRE_MUL_ONE_ + s / 2u) / s;
        smin = s < smin ? s : smin;
        smax = s > smax ? s : smax;
        ssum += s;
    }
    const uint32_t sh = 12u - p->rs; /* R Q4 -> counts Q16.16 */
    const uint64_t lim = 0xFFFFFFFFu;
    p->st.sigma_min = (uint64_t)smin << sh > lim ? 0xFFFFFFFFu : smin << sh;
    p->st.sigma_max = (uint64_t)smax << sh > lim ? 0xFFFFFFFFu : smax << sh;
    const uint64_t mean = (ssum / nt) << sh;
    p->st.sigma_mean = mean > lim ? 0xFFFFFFFFu : (uint32_t)mean;
}

/* Column offsets: c += col_alpha * HP(m), m the column mean of the clipped r over the rows
 * summed, HP taking off the mean of m over the columns within PFT_PRE_COL_HP_ (clipped at the
 * border). A smooth column profile is the background's to follow (it moves with the scene,
 * which tells it apart from the sensor only slowly), so c learns the column-to-column
 * pattern only and the split between the two cannot wander. A masked pixel adds 0: it slows
 * the convergence of its column, not where it converges to (r's mean goes to 0). The csum
 * buffer holds m in place. */
static void columns_update_(pft_pre_t *p)
{
    const int32_t w = p->cfg.width, hp = PFT_PRE_COL_HP_;
    const int64_t a = p->cfg.col_alpha;
    const int64_t n = (p->cfg.height + PFT_PRE_COL_ROWS_ - 1u) / PFT_PRE_COL_ROWS_;
    const int64_t lim = (int64_t)PFT_PRE_RMAX_ * 256;
    int32_t *m = p->csum;
    for (int32_t x = 0; x < w; ++x) { /* column means, R units Q8 (|m| <= 32767 * 256) */
        const int64_t m0 = (int64_t)m[x] * 256;
        m[x] = (int32_t)((m0 >= 0 ? m0 + n / 2 : m0 - n / 2) / n);
    }
    /* c += a (m - mean of m over [x - hp, x + hp]), a sliding sum; m[x - hp - 1] is read
     * before it is needed no more, so the means go to colq directly */
    int64_t sum = 0;
    int32_t cnt = 0;
    for (int32_t x = 0; x < hp && x < w; ++x) {
        sum += m[x];
        cnt++;
    }
    for (int32_t x = 0; x < w; ++x) {
        if (x + hp < w) {
            sum += m[x + hp];
            cnt++;
        }
        if (x - hp - 1 >= 0) {
            sum -= m[x - hp - 1];
            cnt--;
        }
        const int64_t mean = (sum >= 0 ? sum + cnt / 2 : sum - cnt / 2) / cnt;
        int64_t q = (int64_t)p->colq[x] + ((((int64_t)m[x] - mean) * a + 32768) >> 16);
        q = q > lim ? lim : (q < -lim ? -lim : q);
        p->colq[x] = (int32_t)q;
    }
}

/* ------------------------------------------------------------------------------ peaks */

/* a ranks below b: smaller value, or the same value later in raster order. */
static bool peak_below_(const pft_pre_peak_t *a, const pft_pre_peak_t *b, uint32_t w)
{
    if (a->value != b->value) {
        return a->value < b->value;
    }
    return (uint32_t)a->y * w + a->x > (uint32_t)b->y * w + b->x;
}

/* Restores the min-heap (root: the lowest-ranked peak) below slot i of n. */
static void heap_down_(pft_pre_peak_t *hp, uint32_t n, uint32_t i, uint32_t w)
{
    for (;;) {
        const uint32_t l = 2u * i + 1u, r = l + 1u;
        uint32_t m = i;
        if (l < n && peak_below_(&hp[l], &hp[m], w)) {
            m = l;
        }
        if (r < n && peak_below_(&hp[r], &hp[m], w)) {
            m = r;
        }
        if (m == i) {
            return;
        }
        const pft_pre_peak_t t = hp[i];
        hp[i] = hp[m];
        hp[m] = t;
        i = m;
    }
}

static void peak_add_(pft_pre_t *p, uint32_t x, uint32_t y, int16_t v)
{
    const uint32_t w = p->cfg.width, k = p->cfg.peak_max;
    pft_pre_peak_t pk;
    pk.x = (uint16_t)x;
    pk.y = (uint16_t)y;
    pk.value = v;
    p->st.n_candidates++;
    if (p->n_peaks < k) {
        uint32_t i = p->n_peaks++;
        p->peaks[i] = pk;
        while (i > 0u) { /* sift up */
            const uint32_t up = (i - 1u) / 2u;
            if (!peak_below_(&p->peaks[i], &p->peaks[up], w)) {
                break;
            }
            const pft_pre_peak_t t = p->peaks[i];
            p->peaks[i] = p->peaks[up];
            p->peaks[up] = t;
            i = up;
        }
    } else if (peak_below_(&p->peaks[0], &pk, w)) {
        p->peaks[0] = pk;
        heap_down_(p->peaks, k, 0u, w);
    } else {
        /* not above the heap's lowest: dropped */
    }
}

/* Heap sort: highest first. */
static void peaks_sort_(pft_pre_t *p)
{
    const uint32_t w = p->cfg.width;
    for (uint32_t n = p->n_peaks; n > 1u; --n) {
        const pft_pre_peak_t t = p->peaks[0];
        p->peaks[0] = p->peaks[n - 1u];
        p->peaks[n - 1u] = t;
        heap_down_(p->peaks, n - 1u, 0u, w);
    }
}

/* Peaks of row y (mid) given the rows above and below (NULL at the image border): a value at
 * or above the threshold, not below a later neighbour and above an earlier one. */
static void peaks_row_(pft_pre_t *p, uint32_t y, const int16_t *up, const int16_t *mid,
                       const int16_t *dn)
{
    const uint32_t w = p->cfg.width;
    const int16_t thr = p->cfg.peak_threshold;
    for (uint32_t xb = 0; xb < w; xb += 16u) {
        const uint32_t xe = xb + 16u < w ? xb + 16u : w;
        int16_t bmax = INT16_MIN;
        for (uint32_t x = xb; x < xe; ++x) { /* vectorisable block maximum */
            bmax = mid[x] > bmax ? mid[x] : bmax;
        }
        if (bmax < thr) {
            continue;
        }
        for (uint32_t x = xb; x < xe; ++x) {
            const int16_t v = mid[x];
            if (v < thr) {
                continue;
            }
            const uint32_t xl = x > 0u ? x - 1u : x, xr = x + 1u < w ? x + 1u : x;
            bool ok = true;
            for (uint32_t xx = xl; ok && xx <= xr; ++xx) {
                if (up != NULL && !(v > up[xx])) {
                    ok = false;
                }
                if (dn != NULL && v < dn[xx]) {
                    ok = false;
                }
            }
            if (ok && x > 0u && !(v > mid[x - 1u])) {
                ok = false;
            }
            if (ok && x + 1u < w && v < mid[x + 1u]) {
                ok = false;
            }
            if (ok) {
                peak_add_(p, x, y, v);
            }
        }
    }
}

/* ------------------------------------------------------------------------------ whitening */

/* Twice the centre of tile i along a side of n pixels: first + last pixel. */
static uint32_t centre2_(uint32_t i, uint32_t t, uint32_t n)
{
    const uint32_t a = i * t, b = (a + t > n ? n : a + t) - 1u;
    return a + b;
}

/* Multipliers of row y at the tile columns: tile row values interpolated vertically. */
static void row_multipliers_(pft_pre_t *p, uint32_t y)
{
    const uint32_t t = p->cfg.tile, h = p->cfg.height, ntx = p->ntx, nty = p->nty;
    const uint32_t y2 = 2u * y;
    uint32_t j = y / t; /* tile row of y; interpolate towards the neighbour on y's side */
    uint32_t ja = j, jb = j;
    const uint32_t cj = centre2_(j, t, h);
    if (y2 < cj && j > 0u) {
        ja = j - 1u;
    } else if (y2 > cj && j + 1u < nty) {
        jb = j + 1u;
    } else {
        /* y on its tile's centre: no neighbour */
    }
    const uint32_t *ma = p->tmul + (size_t)ja * ntx, *mb = p->tmul + (size_t)jb * ntx;
    if (ja == jb || !p->cfg.sigma_interp) {
        memcpy(p->rowm, p->tmul + (size_t)j * ntx, ntx * 4u);
        return;
    }
    const int64_t ca = centre2_(ja, t, h), d = (int64_t)centre2_(jb, t, h) - ca;
    const int64_t num = (int64_t)y2 - ca;
    for (uint32_t i = 0; i < ntx; ++i) {
        const int64_t a = ma[i], diff = (int64_t)mb[i] - a;
        const int64_t q = diff * num;
        p->rowm[i] = (uint32_t)(a + (q >= 0 ? q + d / 2 : q - d / 2) / d);
    }
}

#if defined(PFT_PRE_UPD_SSE2_)
/* x86-64 (SSE2): mline_span_'s running sum 8 pixels at a time: m[i] = the upper half of
 * s + i st (modulo 2^32) read as a signed 16-bit number (psrad 16, then packssdw, exact: the
 * shifted lanes are within int16), i < 8 (n / 8); returns 8 (n / 8). gcc's loop of the plain
 * form takes the halves apart with 7 shuffles per 8 pixels. */
uint32_t pft_pre_mline_n_(int16_t *m, uint32_t n, uint32_t s, uint32_t st)
{
    __m128i sa = _mm_add_epi32(_mm_set1_epi32((int32_t)s),
                               _mm_set_epi32((int32_t)(3u * st), (int32_t)(2u * st), (int32_t)st, 0));
    __m128i sb = _mm_add_epi32(sa, _mm_set1_epi32((int32_t)(4u * st)));
    const __m128i st8 = _mm_set1_epi32((int32_t)(8u * st));
    const uint32_t ne = n / 8u * 8u;
    for (uint32_t x = 0; x < ne; x += 8u) {
        _mm_storeu_si128((__m128i *)(void *)&m[x],
                         _mm_packs_epi32(_mm_srai_epi32(sa, 16), _mm_srai_epi32(sb, 16)));
        sa = _mm_add_epi32(sa, st8);
        sb = _mm_add_epi32(sb, st8);
    }
    return ne;
}

/* x86-64 (SSE2): whiten_row_'s loop without the clamp 8 pixels at a time: r[x] =
 * (r[x] m[x] + 2^(sh - 1)) >> sh (1 <= sh <= 16), a masked pixel left as it is, x < 8 (n / 8);
 * returns 8 (n / 8). For a row where every unmasked pixel's value lies in int16 (whiten_row_'s
 * test): the 32-bit products from pmullw and pmulhw, the shift psrad, the narrowing packssdw
 * (exact within int16) and the masked pixels by a min with INT16_MIN there (32767 elsewhere),
 * the same values as the plain loop (whose SSE2 form narrows with 7 shuffles). */
uint32_t pft_pre_whiten_rown_(int16_t *r, const int16_t *m, uint32_t n, uint32_t sh)
{
    const __m128i rnd = _mm_set1_epi32((int32_t)(1u << (sh - 1u)));
    const __m128i cnt = _mm_cvtsi32_si128((int32_t)sh);
    const __m128i o7f = _mm_set1_epi16(32767);
    const __m128i msk = _mm_set1_epi16(PFT_RES16_MASKED);
    const uint32_t ne = n / 8u * 8u;
    for (uint32_t x = 0; x < ne; x += 8u) {
        const __m128i v = _mm_loadu_si128((const __m128i *)(const void *)&r[x]);
        const __m128i mm = _mm_loadu_si128((const __m128i *)(const void *)&m[x]);
        const __m128i lo = _mm_mullo_epi16(v, mm), hi = _mm_mulhi_epi16(v, mm);
        const __m128i qa = _mm_sra_epi32(_mm_add_epi32(_mm_unpacklo_epi16(lo, hi), rnd), cnt);
        const __m128i qb = _mm_sra_epi32(_mm_add_epi32(_mm_unpackhi_epi16(lo, hi), rnd), cnt);
        const __m128i ms = _mm_cmpeq_epi16(v, msk);
        _mm_storeu_si128((__m128i *)(void *)&r[x],
                         _mm_min_epi16(_mm_packs_epi32(qa, qb), _mm_xor_si128(ms, o7f)));
    }
    return ne;
}
#endif

/* Multipliers of pixels [x0, x1) (scaled, below 2^15) into m: from ma at doubled coordinate
 * x2a linearly to mb at x2b (ma alone when x2a == x2b). */
static void mline_span_(int16_t *m, uint32_t x0, uint32_t x1, int32_t ma, int32_t mb,
                        int32_t x2a, int32_t x2b)
{
    if (x2b <= x2a || ma == mb) {
        for (uint32_t x = x0; x < x1; ++x) {
            m[x] = (int16_t)ma;
        }
        return;
    }
    /* m(x) = ma + (mb - ma) (2x - x2a) / d, in Q16: base at x0 plus 2 step per pixel */
    const int64_t d = x2b - x2a, dm = (int64_t)(mb - ma) * 65536;
    const int64_t b0 = (int64_t)ma * 65536 + (dm * (2 * (int64_t)x0 - x2a)) / d;
    const int32_t base = (int32_t)b0, step2 = (int32_t)((2 * dm) / d);
    /* s = base + (x - x0) step2 + 32768 as a running sum modulo 2^32 (unsigned: no overflow,
     * also past the last pixel), so that the vectorised loop adds a step per vector; m[x] is
     * its upper half read as a signed 16-bit number, floor(s / 2^16): the int32 sum's
     * arithmetic shift, the same value */
    uint32_t s = (uint32_t)base + 32768u;
    const uint32_t st = (uint32_t)step2;
    uint32_t xs = x0;
#if defined(PFT_PRE_UPD_SSE2_)
    xs += pft_pre_mline_n_(&m[x0], x1 - x0, s, st);
    s += (xs - x0) * st;
#endif
    for (uint32_t x = xs; x < x1; ++x) {
        const int32_t hi = (int32_t)(s >> 16) - (int32_t)((s >> 15) & 0x10000u);
        m[x] = (int16_t)hi;
        s += st;
    }
}

/* Whitening of row y with the edge term: the row's multipliers m (scaled by 2^-e) and the
 * background rows around y (p->bg, U units; clamped at the image border). |grad b| is taken
 * as max + min / 2 of the central differences' magnitudes (within 12 % of the Euclidean
 * norm), the edge spread s = edge_k |grad b| in R units, its ratio to the pixel's sigma
 * u = s m 2^e / 2^24 in Q4, and w = (r m / 2^sh) edge_f_[u] / 2^15. */
static void whiten_edge_row_(pft_pre_t *p, uint32_t y, const int16_t *m, uint32_t e, uint32_t sh)
{
    /* docs/algorithms.md 9.6: 32768 / sqrt(1 + (i / 16)^2), rounded, the factor that takes a
     * residual whitened by the tile sigma to one whitened by sqrt(sigma^2 + s^2), for
     * s / sigma = i / 16 (i = 0..255; larger ratios use the last). */
    static const uint16_t edge_f_[256] = {
        32768u, 32704u, 32515u, 32207u, 31790u, 31276u, 30682u, 30021u, 29309u, 28560u,
        27787u, 27002u, 26214u, 25432u, 24660u, 23905u, 23170u, 22458u, 21770u, 21107u,
        20470u, 19859u, 19273u, 18713u, 18176u, 17664u, 17174u, 16705u, 16257u, 15829u,
        15420u, 15029u, 14654u, 14296u, 13953u, 13624u, 13308u, 13006u, 12716u, 12437u,
        12170u, 11913u, 11665u, 11427u, 11198u, 10978u, 10765u, 10560u, 10362u, 10171u,
        9987u, 9809u, 9637u, 9470u, 9309u, 9153u, 9002u, 8856u, 8714u, 8576u,
        8443u, 8314u, 8188u, 8066u, 7947u, 7832u, 7720u, 7611u, 7505u, 7402u,
        7302u, 7204u, 7108u, 7015u, 6925u, 6837u, 6751u, 6667u, 6585u, 6504u,
        6426u, 6350u, 6275u, 6203u, 6131u, 6062u, 5994u, 5927u, 5862u, 5798u,
        5735u, 5674u, 5615u, 5556u, 5498u, 5442u, 5387u, 5333u, 5280u, 5228u,
        5177u, 5127u, 5078u, 5030u, 4983u, 4936u, 4891u, 4846u, 4802u, 4759u,
        4717u, 4675u, 4634u, 4594u, 4554u, 4516u, 4477u, 4440u, 4403u, 4366u,
        4331u, 4296u, 4261u, 4227u, 4193u, 4160u, 4128u, 4096u, 4064u, 4033u,
        4003u, 3973u, 3943u, 3914u, 3885u, 3857u, 3829u, 3801u, 3774u, 3747u,
        3721u, 3695u, 3669u, 3644u, 3619u, 3594u, 3570u, 3546u, 3522u, 3499u,
        3476u, 3453u, 3430u, 3408u, 3386u, 3365u, 3343u, 3322u, 3301u, 3281u,
        3261u, 3240u, 3221u, 3201u, 3182u, 3163u, 3144u, 3125u, 3107u, 3088u,
        3070u, 3053u, 3035u, 3018u, 3000u, 2983u, 2967u, 2950u, 2934u, 2917u,
        2901u, 2885u, 2870u, 2854u, 2839u, 2823u, 2808u, 2793u, 2779u, 2764u,
        2750u, 2735u, 2721u, 2707u, 2693u, 2680u, 2666u, 2653u, 2639u, 2626u,
        2613u, 2600u, 2587u, 2575u, 2562u, 2550u, 2537u, 2525u, 2513u, 2501u,
        2489u, 2478u, 2466u, 2455u, 2443u, 2432u, 2421u, 2410u, 2399u, 2388u,
        2377u, 2366u, 2356u, 2345u, 2335u, 2324u, 2314u, 2304u, 2294u, 2284u,
        2274u, 2264u, 2255u, 2245u, 2235u, 2226u, 2216u, 2207u, 2198u, 2189u,
        2180u, 2171u, 2162u, 2153u, 2144u, 2135u, 2127u, 2118u, 2110u, 2101u,
        2093u, 2085u, 2076u, 2068u, 2060u, 2052u,
    };
    const uint32_t w = p->cfg.width, h = p->cfg.height;
    const uint16_t *bc = p->bg + (size_t)y * w;
    const uint16_t *bu = y > 0u ? bc - w : bc, *bd = y + 1u < h ? bc + w : bc;
    int16_t *r = p->res + (size_t)y * w;
    const uint32_t k = p->cfg.edge_k, ks = 13u + (uint32_t)(p->bf - p->rs), us = 20u - e;
    const uint32_t uh = 1u << (us - 1u);
    const int32_t rnd = (int32_t)(1u << (sh - 1u));
    for (uint32_t x = 0; x < w; ++x) {
        const int16_t v = r[x];
        const uint32_t xl = x > 0u ? x - 1u : x, xr = x + 1u < w ? x + 1u : x;
        const int32_t gx = (int32_t)bc[xr] - (int32_t)bc[xl], gy = (int32_t)bd[x] - (int32_t)bu[x];
        const uint32_t ax = (uint32_t)(gx < 0 ? -gx : gx), ay = (uint32_t)(gy < 0 ? -gy : gy);
        const uint32_t g2 = ax > ay ? ax + (ay >> 1) : ay + (ax >> 1); /* 2 |grad b|, U units */
        const uint32_t s = (k * g2) >> ks;                               /* R units, < 2^17 */
        const uint32_t u = (s * (uint32_t)(uint16_t)m[x] + uh) >> us;
        int32_t q = ((int32_t)v * (int32_t)m[x] + rnd) >> sh;
        q = q > 65535 ? 65535 : (q < -65535 ? -65535 : q);
        q = (q * (int32_t)edge_f_[u > 255u ? 255u : u] + 16384) >> 15;
        int16_t q16 = (int16_t)(q > INT16_MAX ? INT16_MAX : (q < -PFT_PRE_RMAX_ ? -PFT_PRE_RMAX_ : q));
        r[x] = v == PFT_RES16_MASKED ? (int16_t)PFT_RES16_MASKED : q16;
    }
}

/* Whitens row y in place: w = r m / 2^16 with m = 2^28 / sigma(R Q4) interpolated; the
 * row's multipliers share one exponent e so that m >> e < 2^15 and the products fit 32 bits
 * (a multiplier 2^k times smaller than the row's largest keeps 15 - k bits). */
static void whiten_row_(pft_pre_t *p, uint32_t y)
{
    const uint32_t t = p->cfg.tile, w = p->cfg.width, ntx = p->ntx;
    int16_t *r = p->res + (size_t)y * w;
    int16_t *m = (int16_t *)p->line; /* w int16 in the row buffer */
    row_multipliers_(p, y);
    uint32_t mx = 1u;
    for (uint32_t i = 0; i < ntx; ++i) {
        mx = p->rowm[i] > mx ? p->rowm[i] : mx;
    }
    const uint32_t e = pft_pre_log2_(mx) >= 15u ? pft_pre_log2_(mx) - 14u : 0u;
    const uint32_t half = 1u << e >> 1;
#define MS_(i) ((int32_t)((p->rowm[i] + half) >> e) > 32767 ? 32767 : (int32_t)((p->rowm[i] + half) >> e))
    if (!p->cfg.sigma_interp || ntx == 1u) {
        for (uint32_t i = 0; i < ntx; ++i) {
            const uint32_t x0 = i * t, x1 = x0 + t > w ? w : x0 + t;
            mline_span_(m, x0, x1, MS_(i), MS_(i), 0, 0);
        }
    } else {
        /* before the first centre and after the last: held; between centres: linear */
        uint32_t x = (centre2_(0u, t, w) + 1u) / 2u; /* first x with 2x >= the first centre */
        mline_span_(m, 0u, x, MS_(0u), MS_(0u), 0, 0);
        for (uint32_t i = 0; i + 1u < ntx; ++i) {
            const uint32_t cb = centre2_(i + 1u, t, w), xb = (cb + 1u) / 2u;
            mline_span_(m, x, xb, MS_(i), MS_(i + 1u), (int32_t)centre2_(i, t, w), (int32_t)cb);
            x = xb;
        }
        mline_span_(m, x, w, MS_(ntx - 1u), MS_(ntx - 1u), 0, 0);
    }
#undef MS_
    const uint32_t sh = 16u - e;
    if (p->cfg.edge_k != 0u) {
        whiten_edge_row_(p, y, m, e, sh);
        return;
    }
    const int32_t rnd = (int32_t)(1u << (sh - 1u));
    /* The clamp to +-PFT_PRE_RMAX_ changes no pixel of the row when a m + rnd < 2^(15 + sh)
     * for a = max |v| over its unmasked pixels and m = max m[x] (then every q of an unmasked
     * pixel lies in [-PFT_PRE_RMAX_, PFT_PRE_RMAX_]): the row goes through the loop without
     * it, the same values (on x86-64 SSE2, whose 32-bit lanes have no min/max, about 6
     * instructions per pixel less; such a row is the rule: the clamp is at 128 sigma) */
    int16_t vlo = 0, vhi = 0, mhi = 0;
    {
        /* vectorisable: 16-bit min/max; the row in two halves with their own extremes (two
         * independent chains for an in-order core), then joined: the same extremes */
        const uint32_t hw = w / 2u;
        int16_t vlo2 = 0, vhi2 = 0, mhi2 = 0;
        for (uint32_t x = 0; x < hw; ++x) {
            const int16_t v = r[x] == PFT_RES16_MASKED ? (int16_t)0 : r[x];
            const int16_t v2 = r[x + hw] == PFT_RES16_MASKED ? (int16_t)0 : r[x + hw];
            vlo = v < vlo ? v : vlo;
            vhi = v > vhi ? v : vhi;
            mhi = m[x] > mhi ? m[x] : mhi;
            vlo2 = v2 < vlo2 ? v2 : vlo2;
            vhi2 = v2 > vhi2 ? v2 : vhi2;
            mhi2 = m[x + hw] > mhi2 ? m[x + hw] : mhi2;
        }
        for (uint32_t x = 2u * hw; x < w; ++x) {
            const int16_t v = r[x] == PFT_RES16_MASKED ? (int16_t)0 : r[x];
            vlo = v < vlo ? v : vlo;
            vhi = v > vhi ? v : vhi;
            mhi = m[x] > mhi ? m[x] : mhi;
        }
        vlo = vlo2 < vlo ? vlo2 : vlo;
        vhi = vhi2 > vhi ? vhi2 : vhi;
        mhi = mhi2 > mhi ? mhi2 : mhi;
    }
    const int32_t amax = -(int32_t)vlo > (int32_t)vhi ? -(int32_t)vlo : (int32_t)vhi;
    if ((int64_t)amax * mhi + rnd < ((int64_t)1 << (15u + sh))) {
#if defined(PFT_PRE_UPD_SSE2_)
        /* x86-64: 8 pixels at a time (pft_pre_whiten_rown_), the rest as the loop below */
        for (uint32_t x = pft_pre_whiten_rown_(r, m, w, sh); x < w; ++x) {
            const int16_t v = r[x];
            const int32_t q = ((int32_t)v * (int32_t)m[x] + rnd) >> sh;
            r[x] = v == PFT_RES16_MASKED ? (int16_t)PFT_RES16_MASKED : (int16_t)q;
        }
        return;
#else
        /* vectorisable: 16 x 16 bit products; the row in two halves, a pixel of each per
         * iteration, so that the vector loop has two independent chains for an in-order core
         * to overlap (the same value per pixel) */
        const uint32_t hw = w / 2u;
        for (uint32_t x = 0; x < hw; ++x) {
            const int16_t v = r[x];
            const int16_t v2 = r[x + hw];
            const int32_t q = ((int32_t)v * (int32_t)m[x] + rnd) >> sh;
            const int32_t q2 = ((int32_t)v2 * (int32_t)m[x + hw] + rnd) >> sh;
            r[x] = v == PFT_RES16_MASKED ? (int16_t)PFT_RES16_MASKED : (int16_t)q;
            r[x + hw] = v2 == PFT_RES16_MASKED ? (int16_t)PFT_RES16_MASKED : (int16_t)q2;
        }
        for (uint32_t x = 2u * hw; x < w; ++x) {
            const int16_t v = r[x];
            const int32_t q = ((int32_t)v * (int32_t)m[x] + rnd) >> sh;
            r[x] = v == PFT_RES16_MASKED ? (int16_t)PFT_RES16_MASKED : (int16_t)q;
        }
        return;
#endif
    }
    for (uint32_t x = 0; x < w; ++x) { /* vectorisable: 16 x 16 bit products, saturation */
        const int16_t v = r[x];
        const int32_t q = ((int32_t)v * (int32_t)m[x] + rnd) >> sh;
        int16_t q16 = (int16_t)(q > INT16_MAX ? INT16_MAX : (q < INT16_MIN ? INT16_MIN : q));
        q16 = q16 < -PFT_PRE_RMAX_ ? (int16_t)-PFT_PRE_RMAX_ : q16;
        r[x] = v == PFT_RES16_MASKED ? (int16_t)PFT_RES16_MASKED : q16;
    }
}

/* Peaks of row yq once both its neighbours are whitened. */
static void peaks_of_(pft_pre_t *p, int32_t yq)
{
    const uint32_t w = p->cfg.width, h = p->cfg.height;
    const int16_t *mid = p->res + (size_t)yq * w;
    peaks_row_(p, (uint32_t)yq, yq >= 1 ? mid - w : NULL, mid, (uint32_t)yq + 1u < h ? mid + w : NULL);
}

/* The second pass (sigma of the frame itself): whitens every row, then its peaks. */
static void whiten_(pft_pre_t *p)
{
    const uint32_t h = p->cfg.height;
    for (uint32_t y = 0; y < h; ++y) {
        whiten_row_(p, y);
        if (p->cfg.peak_max > 0u && y >= 1u) {
            peaks_of_(p, (int32_t)y - 1);
        }
    }
    if (p->cfg.peak_max > 0u) {
        peaks_of_(p, (int32_t)h - 1);
    }
}

uint32_t pft_pre_row_out_(pft_pre_t *p, uint32_t y)
{
    const uint32_t nm = pft_pre_book_row_(p, y);
    if (p->fused) {
        whiten_row_(p, y);
        /* rows come in order (up or down): the row before has both neighbours now */
        if (p->cfg.peak_max > 0u && p->last_row >= 0) {
            peaks_of_(p, p->last_row);
        }
        p->last_row = (int32_t)y;
    }
    return nm;
}

/* ------------------------------------------------------------------------------ update */

static pft_status_t check_frame_(const pft_pre_t *p, const pft_frame_t *f)
{
    const pft_status_t s =
        pft_frame_check(f, p->cfg.width, p->cfg.height, PFT_FMT_BIT(p->cfg.format));
    if (s != PFT_OK) {
        return s;
    }
    if (f->format == PFT_PIX_U16 && (f->bit_depth == 0u ? 16u : f->bit_depth) != p->cfg.bit_depth) {
        return PFT_ERR_FORMAT;
    }
    return PFT_OK;
}

/* One accepted frame (checked): the residual goes to p->res. */
static void update_(pft_pre_t *p, const pft_frame_t *f)
{
    pft_pre_acc_t acc;
    memset(&acc, 0, sizeof acc);
    pft_pre_cls_t cls;
    pft_pre_cls_init_(p, &cls);
    bool any_valid = false;
    if (frame_constant_(&cls, f, &any_valid)) {
        acc.flags |= PFT_PRE_FLAG_CONSTANT;
    }
    if (!any_valid) {
        acc.flags |= PFT_PRE_FLAG_ALL_MASKED;
    }
    const uint32_t w = p->cfg.width;
    const bool temporal = p->cfg.method == PFT_PRE_BG_TEMPORAL;
    /* this frame's column offsets in working units (TEMPORAL: U, LOCAL: R) */
    const uint32_t k = temporal ? (uint32_t)(p->bf - p->rs) : 0u;
    for (uint32_t x = 0; x < w; ++x) {
        p->colnow[x] = (int32_t)(((int64_t)p->colq[x] * (1 << k) + 128) >> 8);
    }
    memset(p->csum, 0, (size_t)w * 4u);
    /* whiten row by row with the last frame's tile sigmas, or in a second pass with this
     * frame's (configured so, or no sigma estimated yet) */
    p->fused = !p->cfg.sigma_current && p->sig_known;
    p->last_row = -1;
    p->n_peaks = 0u;
    p->st.n_candidates = 0u;
    if (temporal) {
        if ((acc.flags & PFT_PRE_FLAG_CONSTANT) != 0u && p->bg_frames > 0u) {
            acc.flags |= PFT_PRE_FLAG_HELD; /* no scene to learn or register */
        }
        pft_pre_register_(p, f, &acc);
        pft_pre_temporal_pass_(p, f, &acc);
    } else {
        pft_pre_local_pass_(p, f, &acc);
    }
    const uint32_t npix = (uint32_t)w * p->cfg.height;
    if (acc.n_sat == npix) {
        acc.flags |= PFT_PRE_FLAG_ALL_SATURATED;
    }
    if (acc.n_dead == npix) {
        acc.flags |= PFT_PRE_FLAG_ALL_DEAD;
    }
    tiles_finish_(p, &acc);
    if (p->cfg.col_alpha > 0u && (acc.flags & (PFT_PRE_FLAG_HELD | PFT_PRE_FLAG_ALL_MASKED)) == 0u) {
        columns_update_(p);
    }
    if (!p->fused) {
        whiten_(p);
    } else if (p->cfg.peak_max > 0u && p->last_row >= 0) {
        peaks_of_(p, p->last_row);
    } else {
        /* fused without peaks: the residual is complete */
    }
    peaks_sort_(p);
    p->st.n_peaks = p->n_peaks;
    p->frames++;
    p->last_seq = f->seq;
    p->st.seq = f->seq;
    p->st.timestamp_us = f->timestamp_us;
    p->st.frames = p->frames;
    p->st.flags = acc.flags;
    p->st.n_masked = acc.n_masked;
    p->st.n_saturated = acc.n_sat;
    p->st.n_dead = acc.n_dead;
    p->st.n_bad = acc.n_bad;
}

pft_status_t pft_pre_update(pft_pre_t *p, const pft_frame_t *f)
{
    if (p == NULL || p->line == NULL) {
        return PFT_ERR_INVAL;
    }
    if (p->cfg.inplace) {
        return PFT_ERR_STATE; /* pft_pre_update_inplace: the residual has no buffer here */
    }
    const pft_status_t s = check_frame_(p, f);
    if (s != PFT_OK) {
        return s;
    }
    update_(p, f);
    return PFT_OK;
}

pft_status_t pft_pre_update_inplace(pft_pre_t *p, const pft_frame_t *f, uint16_t *pixels)
{
    if (p == NULL || p->line == NULL || f == NULL || pixels == NULL) {
        return PFT_ERR_INVAL;
    }
    if (!p->cfg.inplace) {
        return PFT_ERR_STATE;
    }
    if (f->data != (const void *)pixels) {
        return PFT_ERR_INVAL;
    }
    const pft_status_t s = check_frame_(p, f);
    if (s != PFT_OK) {
        return s;
    }
    if (f->stride_bytes != 2u * (uint32_t)f->width) {
        return PFT_ERR_FORMAT; /* the residual's rows are packed */
    }
    /* every check is above: from here the frame buffer becomes the residual, row by row, each
     * row once its raw values are no longer read (pft_pre.h, "Memory") */
    p->res = (int16_t *)(void *)pixels;
    update_(p, f);
    return PFT_OK;
}
