/* Clutter map of the whitened residual (pft_pre.h, pft_pre_clutter_*; docs/algorithms.md
 * 9.9). Integer arithmetic only: the map m in sigma^2 Q6.10 (u16), the mean mu in sigma Q4.11
 * (u16, offset by 2^15), residuals in Q8.8 sigma; the warp's weights in Q8.
 * The gate's counter pc (frames Q8) needs its 16 bits: its values run from 0 to the cap 2 k
 * 256 = 512 k >= 512 (persist k >= 1; reached exactly by 2 k frames beyond excess without a
 * shift), and the warp's rounding makes intermediate integers (a capped counter next to a zero
 * one carried by f / 256 px gives 2 k (256 - f) and 2 k f: 257 distinct values for every k),
 * so no 8-bit code holds them with the same outputs (docs/algorithms.md 9.9). */
#include <string.h>

#include "pft/pft_pre.h"
#include "../core/config_int.h"
#include "pre_int.h"

#if defined(__SSE2__)
#include <emmintrin.h> /* CL_SSE2_ below */
#elif defined(__aarch64__) && defined(__ARM_NEON)
#include <arm_neon.h> /* CL_NEON_ below */
#endif

#define CL_ONE_ 1024u          /* 1 sigma^2 in Q6.10: the map's value where nothing is known */
#define CL_MMAX_ 65535u        /* largest map value (64 sigma^2 less one unit) */
#define CL_SQMAX_ 4194304u     /* 64 sigma^2 in Q16 (a squared Q8.8 value) */
#define CL_MUMAX_ 16384        /* 8 sigma in Q4.11 */
#define CL_MUOFF_ 32768u       /* offset of mu while warped (unsigned arithmetic) */
#define CL_FLOORMAX_ 2048u     /* largest mean_floor, Q8.8 sigma (8: the mean's clamp) */
#define CL_ONE8_ 64u           /* map8: the code of 1 sigma^2 (1024 Q6.10, exact) */
#define CL_HALF8_ 128u         /* map8: the rounding offset of the nearest code (half a step, in 1/256) */

void pft_pre_clutter_config_default(pft_pre_clutter_config_t *cfg)
{
    if (cfg == NULL) {
        return;
    }
    memset(cfg, 0, sizeof(*cfg));
    cfg->width = 384u;
    cfg->height = 288u;
    cfg->alpha = 6554u;
    cfg->blur = 1u;
    cfg->box = true;
    cfg->mean = false;
    cfg->thr = 2048u;
    cfg->veto = 0u;
    cfg->persist = 0u;
    cfg->excess = 384u;
    cfg->inplace = false;
    cfg->block = 0u;
    cfg->map8 = false;
    cfg->anchor = false;
    cfg->mean_floor = 0u;
    cfg->floor_age = 0u;
}

pft_status_t pft_pre_clutter_config_check(const pft_pre_clutter_config_t *cfg, const char **field)
{
    const char *bad = NULL;
    if (cfg == NULL) {
        return pft_config_verdict_(false, NULL, field);
    }
    if (cfg->width < 8u || cfg->width > PFT_CFG_MAX_IMAGE_SIDE) {
        bad = "width";
    } else if (cfg->height < 8u || cfg->height > PFT_CFG_MAX_IMAGE_SIDE) {
        bad = "height";
    } else if (cfg->alpha == 0u) {
        bad = "alpha";
    } else if (cfg->blur > PFT_PRE_CLUTTER_MAX_BLUR) {
        bad = "blur";
    } else if (cfg->thr < CL_ONE_) {
        bad = "thr";
    } else if (cfg->veto != 0u && cfg->veto < cfg->thr) {
        bad = "veto";
    } else if (cfg->persist > PFT_PRE_CLUTTER_MAX_PERSIST || (cfg->persist != 0u && !cfg->mean)) {
        bad = "persist";
    } else if (cfg->persist != 0u && (cfg->excess == 0u || cfg->excess > 32767u)) {
        bad = "excess";
    } else if (cfg->block != 0u && cfg->block != 2u && cfg->block != 4u) {
        bad = "block";
    } else if (cfg->map8 && cfg->block != 0u) {
        bad = "map8";
    } else if (cfg->anchor && cfg->block != 0u) {
        bad = "anchor"; /* the anchored grid is the pixels' (a block grid would need its own rounding) */
    } else if (cfg->mean_floor != 0u && (!cfg->mean || cfg->block != 0u || cfg->mean_floor > CL_FLOORMAX_)) {
        bad = "mean_floor";
    } else if (cfg->floor_age != 0u && cfg->mean_floor == 0u) {
        bad = "floor_age"; /* the age gates the floor: without one it would change nothing */
    } else {
        /* accepted */
    }
    return pft_config_verdict_(true, bad, field);
}

size_t pft_pre_clutter_workspace_size(const pft_pre_clutter_config_t *cfg)
{
    if (pft_pre_clutter_config_check(cfg, NULL) != PFT_OK) {
        return 0u;
    }
    const size_t ages = cfg->floor_age != 0u ? PFT_PRE_CLUTTER_WORKSPACE_BYTES_AGE(cfg->width, cfg->height) : 0u;
    if (cfg->map8) {
        return ages + PFT_PRE_CLUTTER_WORKSPACE_BYTES_MAP8(cfg->width, cfg->height, cfg->mean ? 1u : 0u,
                                                           cfg->blur, cfg->persist != 0u ? 1u : 0u,
                                                           cfg->inplace ? 1u : 0u);
    }
    return ages + PFT_PRE_CLUTTER_WORKSPACE_BYTES_BLOCK(cfg->width, cfg->height, cfg->mean ? 1u : 0u,
                                                        cfg->blur, cfg->persist != 0u ? 1u : 0u,
                                                        cfg->block, cfg->inplace ? 1u : 0u);
}

pft_status_t pft_pre_clutter_init(pft_pre_clutter_t *c, const pft_pre_clutter_config_t *cfg,
                                  void *work, size_t work_len)
{
    if (c == NULL || cfg == NULL || work == NULL) {
        return PFT_ERR_INVAL;
    }
    if (pft_pre_clutter_config_check(cfg, NULL) != PFT_OK) {
        return PFT_ERR_CONFIG;
    }
    const size_t w = cfg->width, h = cfg->height;
    /* the map's grid: pixels, or blocks of block x block pixels (the last ones cut) */
    uint32_t lb = 0u; /* per pixel */
    if (cfg->block == 4u) {
        lb = 2u;
    } else if (cfg->block == 2u) {
        lb = 1u;
    } else {
        /* block 0: the grid is the frame */
    }
    const size_t k = (size_t)1u << lb;
    const size_t gw = (w + k - 1u) / k, gh = (h + k - 1u) / k;
    pft_ws_t ws;
    pft_ws_init(&ws, work, work_len);
    /* map8 (per pixel): the map's codes, 2 blur + 1 decoded rows and the row being updated */
    uint16_t *m = cfg->map8 ? NULL : pft_ws_take(&ws, gw * gh * 2u);
    uint8_t *m8 = cfg->map8 ? pft_ws_take(&ws, gw * gh) : NULL;
    int16_t *out = cfg->inplace ? NULL : pft_ws_take(&ws, w * h * 2u);
    uint16_t *mu = cfg->mean ? pft_ws_take(&ws, gw * gh * 2u) : NULL;
    uint16_t *pc = cfg->persist != 0u ? pft_ws_take(&ws, gw * gh * 2u) : NULL;
    const size_t nring = cfg->map8 ? 2u * (size_t)cfg->blur + 1u : (size_t)cfg->blur + 1u;
    uint16_t *ring = pft_ws_take(&ws, nring * gw * 2u);
    uint16_t *row = cfg->map8 ? pft_ws_take(&ws, gw * 2u) : NULL;
    uint32_t *vs = pft_ws_take(&ws, gw * 4u);
    uint32_t *hs = pft_ws_take(&ws, gw * 4u);
    /* blocks: the per-block sums; map8: the fused warp's two horizontal passes (cl_fuse8_) */
    uint32_t *acc = lb != 0u || cfg->map8 ? pft_ws_take(&ws, gw * 8u) : NULL;
    int32_t *sacc = lb != 0u ? pft_ws_take(&ws, gw * 8u) : NULL;
    /* floor_age (block 0: the grid is the frame): the columns' ages, then the rows' */
    uint8_t *age = cfg->floor_age != 0u ? pft_ws_take(&ws, gw + gh) : NULL;
    if (pft_ws_status(&ws) != PFT_OK) {
        return PFT_ERR_NOMEM;
    }
    memset(c, 0, sizeof(*c));
    c->cfg = *cfg;
    c->gw = (uint32_t)gw;
    c->gh = (uint32_t)gh;
    c->lb = lb;
    c->acc = acc;
    c->sacc = sacc;
    c->age = age;
    c->m = m;
    c->m8 = m8;
    c->row = row;
    c->out = out;
    c->mu = mu;
    c->pc = pc;
    c->ring = ring;
    c->vs = vs;
    c->hs = hs;
    return pft_pre_clutter_reset(c);
}

/* An initialised map: its plane is the 16-bit m or, with map8, the 8-bit m8. */
static bool cl_ready_(const pft_pre_clutter_t *c)
{
    return c != NULL && (c->m != NULL || c->m8 != NULL);
}

pft_status_t pft_pre_clutter_reset(pft_pre_clutter_t *c)
{
    if (!cl_ready_(c)) {
        return PFT_ERR_INVAL;
    }
    const size_t npix = (size_t)c->cfg.width * (size_t)c->cfg.height;
    const size_t gw = c->gw, ng = gw * (size_t)c->gh; /* the map's grid */
    const size_t nring = c->m8 != NULL ? 2u * (size_t)c->cfg.blur + 1u : (size_t)c->cfg.blur + 1u;
    if (c->m8 != NULL) {
        memset(c->m8, (int)CL_ONE8_, ng);
        memset(c->row, 0, gw * 2u);
    } else {
        for (size_t i = 0u; i < ng; ++i) {
            c->m[i] = (uint16_t)CL_ONE_;
        }
    }
    if (c->cfg.inplace) {
        c->out = NULL; /* the caller's buffer of the next update */
    } else {
        memset(c->out, 0, npix * 2u);
    }
    for (size_t i = 0u; c->mu != NULL && i < ng; ++i) {
        c->mu[i] = (uint16_t)CL_MUOFF_;
    }
    if (c->pc != NULL) {
        memset(c->pc, 0, ng * 2u);
    }
    memset(c->ring, 0, nring * gw * 2u);
    memset(c->vs, 0, gw * 4u);
    memset(c->hs, 0, gw * 4u);
    if (c->acc != NULL) {
        memset(c->acc, 0, gw * 8u);
    }
    if (c->sacc != NULL) {
        memset(c->sacc, 0, gw * 8u);
    }
    if (c->age != NULL) {
        memset(c->age, 0, gw + (size_t)c->gh);
    }
    c->ax = 0;
    c->ay = 0;
    c->px = 0;
    c->py = 0;
    c->frames = 0u;
    c->updates = 0u;
    c->seq = 0u;
    c->timestamp_us = 0u;
    return PFT_OK;
}

/* a * d / 2^16 rounded half away from zero (|a| <= 2^16, |d| < 2^17). */
static int32_t cl_scale_(uint32_t a, int32_t d)
{
    const uint64_t mag = (uint64_t)a * (uint64_t)(d < 0 ? -(int64_t)d : (int64_t)d);
    const int32_t q = (int32_t)((mag + 32768u) >> 16);
    return d < 0 ? -q : q;
}

/* n / d rounded half away from zero (d > 0). */
static int32_t cl_div_(int32_t n, int32_t d)
{
    const int32_t mag = n < 0 ? -n : n;
    const int32_t q = (mag + d / 2) / d;
    return n < 0 ? -q : q;
}

/* Floor and Q8 fraction of a Q16.16 shift of s / 2^lb grid steps (lb 0: pixels), the fraction
 * rounded to 1/256 step. */
static void cl_split_(int32_t s, uint32_t lb, int32_t *ip, uint32_t *fp)
{
    const int64_t d = (int64_t)((uint64_t)256u << lb);
    const int64_t q8 = ((int64_t)s + d / 2) / d - (((int64_t)s + d / 2) % d < 0 ? 1 : 0);
    /* q8 = floor((s + d / 2) / d): the shift in Q8 steps, rounded (lb 0: floor((s + 128) / 256)) */
    const int64_t i = q8 / 256 - ((q8 % 256) < 0 ? 1 : 0);
    *ip = (int32_t)i;
    *fp = (uint32_t)(q8 - i * 256);
}

/* map8: the code of v (Q6.10, <= 65535) with the rounding offset dz / 256 of the code's step
 * (dz 0..255; CL_HALF8_: the nearest code; only dz's low 8 bits are read). With v clamped to 64512 (the largest code's value:
 * every v above it has code 255 either way) and e its octave (1 below 2^10, else 2..7 with
 * 2^(e + 8) <= v < 2^(e + 9)): c = 32 (e - 1) + floor((v + d) / 2^(e + 3)), d = floor(dz 2^(e +
 * 3) / 256) < 2^(e + 3), at most 192 + 63. A code's decoded value (a multiple of its step)
 * gives that code for every dz; a quotient of 64 is the next octave's first code (32 e + 32 =
 * 32 (e + 1) + 0, the same value 2^(e + 9)). With dz uniform the expected decoded value is v
 * within 1/256 step. In 16-bit lanes (the row functions below vectorise it): the octave from the
 * bits of v >> 10 smeared down (2^(e - 1) - 1) and their count e - 1, the step p2 = 2^(e + 3) and
 * 2^16 / p2 from them (selects a ^ (mask & (a ^ b)), no variable shift), the two shifts as high halves of 16 x 16-bit
 * products (v + d <= 64512 + 1023 < 2^16). */
static inline uint16_t cl_mask8_(uint16_t x01)
{
    return (uint16_t)(0u - (uint32_t)x01); /* 0 or 0xFFFF (x01 is 0 or 1) */
}

static inline uint8_t cl_enc8_(uint16_t v0, uint16_t dz)
{
    const uint16_t v = v0 > 64512u ? (uint16_t)64512u : v0;
    /* the bits of v >> 10 (< 64) smeared down: s = 2^j - 1, j = e - 1 the number of k = 10..15
     * with v >= 2^k; j = s's bit count (pairs, then the nibbles: s < 64) */
    uint16_t s = (uint16_t)(v >> 10);
    s = (uint16_t)(s | (uint16_t)(s >> 1));
    s = (uint16_t)(s | (uint16_t)(s >> 2));
    s = (uint16_t)(s | (uint16_t)(s >> 4));
    const uint16_t s2 = (uint16_t)(s - (uint16_t)((uint16_t)(s >> 1) & 0x15u));
    const uint16_t s4 = (uint16_t)((uint16_t)(s2 & 0x33u) + (uint16_t)((uint16_t)(s2 >> 2) & 0x33u));
    const uint16_t j = (uint16_t)((uint16_t)(s4 & 0x0Fu) + (uint16_t)(s4 >> 4));
    /* the step 2^(e + 3) = 16 (s + 1); 2^16 / step = 4096 >> j by j's three bits */
    const uint16_t p2 = (uint16_t)((uint16_t)(s + 1u) << 4);
    const uint16_t b0 = cl_mask8_((uint16_t)(j & 1u)), b1 = cl_mask8_((uint16_t)((j >> 1) & 1u));
    const uint16_t b2 = cl_mask8_((uint16_t)(j >> 2));
    const uint16_t i0 = (uint16_t)(4096u - (b0 & 2048u));
    const uint16_t i1 = (uint16_t)(i0 ^ (b1 & (uint16_t)(i0 ^ (uint16_t)(i0 >> 2))));
    const uint16_t inv = (uint16_t)(i1 ^ (b2 & (uint16_t)(i1 ^ (uint16_t)(i1 >> 4))));
    const uint16_t d = (uint16_t)(((uint32_t)(uint16_t)(dz << 8) * (uint32_t)p2) >> 16);
    const uint16_t q = (uint16_t)(((uint32_t)(uint16_t)(v + d) * (uint32_t)inv) >> 16);
    return (uint8_t)((uint16_t)(j << 5) + q);
}

/* map8: the Q6.10 value of code c: c 16 below 64, else (32 + c mod 32) 2^(c / 32 + 3) (the two
 * forms agree on 32..63), as the mantissa times the step, in 16-bit lanes; largest 64512. With
 * e = c / 32 and j = max(e - 1, 0) (0..6): the mantissa c - 32 j (c below 64, else 32 + c mod
 * 32) and the step 16 2^j, made from j's three bits (three selects, no variable shift). */
static inline uint16_t cl_dec8_(uint8_t c8)
{
    const uint16_t c = c8;
    const uint16_t e = (uint16_t)(c >> 5);
    const uint16_t j = (uint16_t)(e - (uint16_t)((uint16_t)(e + 7u) >> 3)); /* max(e - 1, 0) */
    const uint16_t mant = (uint16_t)(c - (uint16_t)(j << 5));
    const uint16_t b0 = cl_mask8_((uint16_t)(j & 1u)), b1 = cl_mask8_((uint16_t)((j >> 1) & 1u));
    const uint16_t b2 = cl_mask8_((uint16_t)(j >> 2));
    const uint16_t p0 = (uint16_t)(16u + (b0 & 16u));
    const uint16_t p1 = (uint16_t)(p0 ^ (b1 & (uint16_t)(p0 ^ (uint16_t)(p0 << 2))));
    const uint16_t p2 = (uint16_t)(p1 ^ (b2 & (uint16_t)(p1 ^ (uint16_t)(p1 << 4))));
    return (uint16_t)(mant * p2);
}

uint32_t pft_pre_clutter_enc8_(uint32_t v, uint32_t dz)
{
    return cl_enc8_((uint16_t)(v > 65535u ? 65535u : v), (uint16_t)(dz & 255u));
}

uint32_t pft_pre_clutter_dec8_(uint32_t c)
{
    return cl_dec8_((uint8_t)c);
}

/* map8: a row of codes decoded (w values). */
static void cl_dec8_row_(const uint8_t *src, uint16_t *dst, int32_t w)
{
    for (int32_t x = 0; x < w; ++x) {
        dst[x] = cl_dec8_(src[x]);
    }
}

/* The warp's horizontal value at an edge column x of a source row (cl_warp_h_):
 * v[x - ix] (256 - fx) + v[x - ix - 1] fx, a source outside the row counting b. */
static uint32_t cl_warp_edge_(const uint16_t *row, int32_t w, int32_t x, int32_t ix, uint32_t fx,
                              uint32_t b)
{
    const int32_t s1 = x - ix, s0 = s1 - 1;
    const uint32_t v1 = s1 >= 0 && s1 < w ? (uint32_t)row[s1] : b;
    const uint32_t v0 = s0 >= 0 && s0 < w ? (uint32_t)row[s0] : b;
    return v1 * (256u - fx) + v0 * fx;
}

/* The warp's horizontal pass over source row sy (the map's grid w x h): hr[x] =
 * v[sy][x - ix] (256 - fx) + v[sy][x - ix - 1] fx, a source outside the frame counting b (a row
 * outside: b 256 in every column, which the vertical pass turns back into b). Columns [xlo,
 * xhi) have both sources inside (cl_warp_). Each term <= 65535 * 256 < 2^24. */
static void cl_warp_h_(const uint16_t *v, uint32_t *hr, int32_t sy, int32_t w, int32_t h,
                       int32_t ix, uint32_t fx, uint32_t b, int32_t xlo, int32_t xhi)
{
    if (sy < 0 || sy >= h) {
        for (int32_t x = 0; x < w; ++x) {
            hr[x] = b * 256u;
        }
        return;
    }
    const uint16_t gx = (uint16_t)(256u - fx), f = (uint16_t)fx;
    const uint16_t *row = v + (size_t)sy * (size_t)w;
    if (xlo < xhi) {
        /* r[i] is column xlo - ix - 1 + i: x0 of x = xlo + i (>= 0) */
        const uint16_t *r = row + (size_t)(xlo - ix - 1);
        uint32_t *o = hr + xlo;
        const int32_t n = xhi - xlo;
        for (int32_t i = 0; i < n; ++i) {
            o[i] = (uint32_t)r[i + 1] * (uint32_t)gx + (uint32_t)r[i] * (uint32_t)f;
        }
    }
    /* the edge columns: sources beyond the frame count b */
    for (int32_t e = 0; e < xlo + (w - xhi); ++e) {
        const int32_t x = e < xlo ? e : xhi + (e - xlo);
        hr[x] = cl_warp_edge_(row, w, x, ix, fx, b);
    }
}

#if defined(__SSE2__)
/* The warp in one pass of 16 x 16-bit multiply-adds (pmaddwd) where the compiler has SSE2
 * (x86-64: no widening 16 x 16 -> 32-bit multiply-accumulate as AArch64's NEON has, which its
 * two-pass 32-bit form after the #else takes; a scalar core also takes that form). The same
 * values: out(x, y) = (S + 2^15) >> 16 with S = H1 (256 - fy) + H0 fy the two-pass sum and H1,
 * H0 the horizontal values of the two source rows, that is S = sum over the four sources v_ij
 * (row y - iy - j, column x - ix - i, i, j in 0..1) of v_ij w_ij with w_ij = wx_i wy_j (wx_0 =
 * 256 - fx, wx_1 = fx, wy_0 = 256 - fy, wy_1 = fy; the weights sum to 2^16, so S <= 65535 2^16
 * and S + 2^15 < 2^32), the integer sum in another order. */
/* One output value of cl_warp_ at column x from source rows r1 (y - iy) and r0 (y - iy - 1),
 * a source column outside the row counting b; wt: the weights of r1's columns x - ix and x -
 * ix - 1, then r0's (w_00, w_10, w_01, w_11). */
static uint16_t cl_warp_px_(const uint16_t *r1, const uint16_t *r0, int32_t w, int32_t x, int32_t ix,
                            const uint32_t *wt, uint32_t b)
{
    const int32_t s1 = x - ix, s0 = s1 - 1;
    const bool in1 = s1 >= 0 && s1 < w, in0 = s0 >= 0 && s0 < w;
    const uint32_t a1 = in1 ? (uint32_t)r1[s1] : b, b1 = in0 ? (uint32_t)r1[s0] : b;
    const uint32_t a0 = in1 ? (uint32_t)r0[s1] : b, b0 = in0 ? (uint32_t)r0[s0] : b;
    const uint32_t s = a1 * wt[0] + b1 * wt[1] + a0 * wt[2] + b0 * wt[3];
    return (uint16_t)((s + 32768u) >> 16);
}

/* cl_warp_'s constants in SSE2's lanes: the weights' high and low parts of the source rows r1
 * (k1h, k1l) and r0 (k0h, k0l) as 16-bit pairs (column x - ix - 1, column x - ix), the values'
 * offset 2^15 (16-bit lanes), the rounding 2^31 + 2^15 and the high halves' mask (32-bit). */
typedef struct {
    __m128i k1h, k1l, k0h, k0l, off, rnd, hmask;
} cl_warpk_t;

/* Columns x .. x + 7 of cl_warp_'s output row o from the source rows r1, r0 (a = x - ix - 1,
 * the first source column: a >= 0 and a + 8 < w), as cl_warp_'s comment below. */
static inline void cl_warp8_sse2_(const uint16_t *r1, const uint16_t *r0, uint16_t *o, int32_t x, int32_t a,
                                  const cl_warpk_t *k)
{
    const __m128i e1 = _mm_xor_si128(_mm_loadu_si128((const __m128i *)(const void *)(r1 + a)), k->off);
    const __m128i d1 = _mm_xor_si128(_mm_loadu_si128((const __m128i *)(const void *)(r1 + a + 1)), k->off);
    const __m128i e0 = _mm_xor_si128(_mm_loadu_si128((const __m128i *)(const void *)(r0 + a)), k->off);
    const __m128i d0 = _mm_xor_si128(_mm_loadu_si128((const __m128i *)(const void *)(r0 + a + 1)), k->off);
    /* the even columns' (e) and odd columns' (d) sums of the high and low products */
    const __m128i xhe = _mm_add_epi32(_mm_madd_epi16(e1, k->k1h), _mm_madd_epi16(e0, k->k0h));
    const __m128i xle = _mm_add_epi32(_mm_madd_epi16(e1, k->k1l), _mm_madd_epi16(e0, k->k0l));
    const __m128i xhd = _mm_add_epi32(_mm_madd_epi16(d1, k->k1h), _mm_madd_epi16(d0, k->k0h));
    const __m128i xld = _mm_add_epi32(_mm_madd_epi16(d1, k->k1l), _mm_madd_epi16(d0, k->k0l));
    const __m128i te = _mm_add_epi32(_mm_add_epi32(_mm_slli_epi32(xhe, 8), xle), k->rnd);
    const __m128i td = _mm_add_epi32(_mm_add_epi32(_mm_slli_epi32(xhd, 8), xld), k->rnd);
    _mm_storeu_si128((__m128i *)(void *)(o + x), _mm_or_si128(_mm_srli_epi32(te, 16), _mm_and_si128(td, k->hmask)));
}

/* Warps v (u16 values, w x h) in place by (ix + fx / 256, iy + fy / 256) px: out(p) =
 * v(p - shift), bilinear, b outside (the sum above). A source row outside the frame is tb
 * filled with b (its horizontal value b 256, as the two-pass form's); the rows are visited in
 * the two-pass form's order (descending where the sources lie at lower rows), so that every
 * source row but the output row itself (iy 0 descending, -1 ascending) is not yet
 * overwritten; that one is copied into ta first. Columns [xlo, xhi), whose two sources are
 * inside the row, 8 at a time: a row's 16-bit values loaded from column x - ix - 1 hold in
 * their 32-bit lanes the pairs (column x' - ix - 1, column x' - ix) of the even columns x' = x,
 * x + 2, .., loaded from one column further those of the odd ones, so that each pair times its
 * two weights is one pmaddwd: each weight w = 256 wh + wl (wh <= 256, wl <= 255: int16, >= 0,
 * no overflow), each value taken as v - 2^15 (int16: v xor 2^15), S = 256 Xh + Xl + 2^31 (Xh,
 * Xl the sums of the two rows' products with wh and wl; the offsets' sum 2^15 2^16) and T = S +
 * 2^15 < 2^32 in 32-bit lanes mod 2^32 (exact); out = T >> 16, the even columns' in the low
 * halves of their lanes (a logical shift), the odd ones' in the high halves (T with its low
 * half cleared), one OR (cl_warp8_sse2_); columns left over from the blocks of 8 as the last 8
 * columns again, the edge columns per pixel (cl_warp_px_). */
static void cl_warp_(uint16_t *v, uint32_t *ta, uint32_t *tb, int32_t w, int32_t h, int32_t ix,
                     uint32_t fx, int32_t iy, uint32_t fy, uint32_t b)
{
    const bool ydown = iy >= 0;
    /* columns whose two sources are inside: x - ix - 1 >= 0 and x - ix < w */
    const int32_t xlo = ix + 1 < 0 ? 0 : (ix + 1 > w ? w : ix + 1);
    const int32_t xhi = ix > 0 ? w : (w + ix < xlo ? xlo : w + ix);
    uint16_t *cp = (uint16_t *)(void *)ta, *brow = (uint16_t *)(void *)tb;
    for (int32_t x = 0; x < w; ++x) {
        brow[x] = (uint16_t)b;
    }
    const uint32_t g = 256u - fx, gy = 256u - fy;
    /* w_00 (r1, column x - ix), w_10 (r1, x - ix - 1), w_01 (r0, x - ix), w_11 (r0, x - ix - 1) */
    const uint32_t wt[4] = {g * gy, fx * gy, g * fy, fx * fy};
    /* the lanes' pairs: column x - ix - 1 (low half), x - ix (high half) */
    cl_warpk_t kw;
    kw.k1h = _mm_set1_epi32((int32_t)(((wt[0] >> 8) << 16) | (wt[1] >> 8)));
    kw.k1l = _mm_set1_epi32((int32_t)(((wt[0] & 255u) << 16) | (wt[1] & 255u)));
    kw.k0h = _mm_set1_epi32((int32_t)(((wt[2] >> 8) << 16) | (wt[3] >> 8)));
    kw.k0l = _mm_set1_epi32((int32_t)(((wt[2] & 255u) << 16) | (wt[3] & 255u)));
    kw.off = _mm_set1_epi16((int16_t)-32768);
    kw.rnd = _mm_set1_epi32((int32_t)-2147450880); /* 2^31 + 2^15 mod 2^32 */
    kw.hmask = _mm_set1_epi32((int32_t)-65536);    /* 0xFFFF0000 */
    int32_t y = ydown ? h - 1 : 0;
    for (int32_t k = 0; k < h; ++k) {
        const int32_t s1 = y - iy, s0 = s1 - 1; /* weights 256 - fy, fy */
        const uint16_t *r1 = s1 < 0 || s1 >= h ? brow : v + (size_t)s1 * (size_t)w;
        const uint16_t *r0 = s0 < 0 || s0 >= h ? brow : v + (size_t)s0 * (size_t)w;
        uint16_t *o = v + (size_t)y * (size_t)w;
        if (s1 == y || s0 == y) {
            memcpy(cp, o, sizeof(uint16_t) * (size_t)w);
            r1 = s1 == y ? cp : r1;
            r0 = s0 == y ? cp : r0;
        }
        if (xhi - xlo >= 8) {
            /* whole blocks of 8, then the last 8 columns again where some are left over (the
             * sources are not the output row: the same values written twice) */
            const int32_t xe = xlo + ((xhi - xlo) & ~7);
            for (int32_t x = xlo; x < xe; x += 8) {
                cl_warp8_sse2_(r1, r0, o, x, x - ix - 1, &kw);
            }
            if (xe < xhi) {
                cl_warp8_sse2_(r1, r0, o, xhi - 8, xhi - 8 - ix - 1, &kw);
            }
        } else {
            for (int32_t x = xlo; x < xhi; ++x) {
                o[x] = cl_warp_px_(r1, r0, w, x, ix, wt, b);
            }
        }
        /* the edge columns: sources beyond the frame count b */
        for (int32_t e = 0; e < xlo + (w - xhi); ++e) {
            const int32_t xc = e < xlo ? e : xhi + (e - xlo);
            o[xc] = cl_warp_px_(r1, r0, w, xc, ix, wt, b);
        }
        y = ydown ? y - 1 : y + 1;
    }
}
#else
/* Warps v (u16 values, w x h) in place by (ix + fx / 256, iy + fy / 256) px: out(p) =
 * v(p - shift), bilinear, b outside:
 *   out(x, y) = (H(y - iy)[x] (256 - fy) + H(y - iy - 1)[x] fy + 2^15) >> 16
 * with H the horizontal pass (cl_warp_h_, < 2^24 in 32 bits), made once per source row in the
 * order of the SSE2 form above (descending where the sources lie at lower rows), one row's
 * second source row the next row's first, kept in ta or tb (w 32-bit words each). The sum is
 * at most (2^24 - 256) 256 + 2^15 < 2^32: a 32-bit product and multiply-add per pixel; fy = 0:
 * out = (H1 2^8 + 2^15) >> 16 = (H1 + 128) >> 8. The same values as the SSE2 form (the same
 * integer sum in another order) and as cl_fuse8_row_'s (H1 2^8 + (H0 - H1) fy + 2^15) >> 16
 * (the same sum mod 2^32). */
static void cl_warp_(uint16_t *v, uint32_t *ta, uint32_t *tb, int32_t w, int32_t h, int32_t ix,
                     uint32_t fx, int32_t iy, uint32_t fy, uint32_t b)
{
    const bool ydown = iy >= 0;
    /* columns whose two sources are inside: x - ix - 1 >= 0 and x - ix < w */
    const int32_t xlo = ix + 1 < 0 ? 0 : (ix + 1 > w ? w : ix + 1);
    const int32_t xhi = ix > 0 ? w : (w + ix < xlo ? xlo : w + ix);
    uint32_t *hc = ta, *hn = tb; /* hc: the source row shared with the row before */
    int32_t y = ydown ? h - 1 : 0;
    const uint32_t gy = 256u - fy;
    /* descending, row y's first source y - iy; ascending, its second y - iy - 1 */
    cl_warp_h_(v, hc, ydown ? y - iy : y - iy - 1, w, h, ix, fx, b, xlo, xhi);
    for (int32_t k = 0; k < h; ++k) {
        /* the other source row: not yet overwritten (below y descending, above ascending) */
        cl_warp_h_(v, hn, ydown ? y - iy - 1 : y - iy, w, h, ix, fx, b, xlo, xhi);
        const uint32_t *h1 = ydown ? hc : hn, *h0 = ydown ? hn : hc; /* weights 256 - fy, fy */
        uint16_t *o = v + (size_t)y * (size_t)w;
        if (fy == 0u) {
            for (int32_t x = 0; x < w; ++x) {
                o[x] = (uint16_t)((h1[x] + 128u) >> 8);
            }
        } else {
            for (int32_t x = 0; x < w; ++x) {
                o[x] = (uint16_t)((h1[x] * gy + h0[x] * fy + 32768u) >> 16);
            }
        }
        uint32_t *t = hc;
        hc = hn;
        hn = t;
        y = ydown ? y - 1 : y + 1;
    }
}
#endif

/* map8: the value of v's nearest code, pft_pre_clutter_dec8_(pft_pre_clutter_enc8_(v,
 * CL_HALF8_)) for every v (test_pre_clutter_map8 compares the two for every v): with v clamped
 * to 64512 and its step p2 = 2^(e + 3) as in cl_enc8_ (the bits of v >> 10 smeared down, s =
 * 2^(e - 1) - 1, p2 = 16 (s + 1)), the code's quotient is floor((v + p2 / 2) / p2) and its
 * value that quotient times p2 (a quotient of 64 is the next octave's first code, the same
 * value): (v + p2 / 2) with the bits below p2 cleared (v + p2 / 2 <= 64512 + 512 < 2^16). */
static inline uint16_t cl_round8_(uint16_t v0)
{
    const uint16_t v = v0 > 64512u ? (uint16_t)64512u : v0;
    uint16_t s = (uint16_t)(v >> 10);
    s = (uint16_t)(s | (uint16_t)(s >> 1));
    s = (uint16_t)(s | (uint16_t)(s >> 2));
    s = (uint16_t)(s | (uint16_t)(s >> 4));
    const uint16_t p2 = (uint16_t)((uint16_t)(s + 1u) << 4);
    return (uint16_t)((uint16_t)(v + (uint16_t)(p2 >> 1)) & (uint16_t)(0u - (uint32_t)p2));
}

/* map8 with a shift: the warp (cl_warp_'s formulas on the decoded map, each value rounded to
 * its nearest code's, cl_round8_) fused with the update. The update of row y reads only the
 * ring of the rows y - blur .. y + blur as they are before this frame's update (after the warp)
 * and writes row y only, so the rows can be updated in the warp's order: descending when iy >=
 * 0 (warped row y reads source rows y - iy and y - iy - 1, both <= y), ascending otherwise
 * (sources > y). The warp puts each warped row straight into its ring slot; row y is updated
 * and stored as codes once the rows up to y - blur (descending) or y + blur (ascending) are
 * warped, and every row warped after that reads source rows beyond them (< y, or > y), so no
 * source row is read after its codes are replaced. One decode (of the warp's source row) and
 * one encode (the update's, with the dither) per pixel and frame, the same values as the warp
 * over the whole plane stored as nearest codes and decoded again by the update. The
 * horizontal passes of a warped row's two source rows live in c->acc (hc, hn: w values each),
 * since c->vs and c->hs serve the update between two warped rows. */
typedef struct {
    uint32_t *hc;  /* the horizontal pass of the source row shared with the row warped before */
    uint32_t *hn;  /* the other source row's */
    int32_t ix;    /* the shift: whole grid steps and Q8 fractions, as cl_warp_ */
    int32_t iy;
    uint32_t fx;
    uint32_t fy;
    int32_t xlo;   /* columns [xlo, xhi) have both sources inside */
    int32_t xhi;
    int32_t next;  /* the next row to warp */
    bool on;       /* this frame's update warps (map8 with a shift) */
    bool down;     /* rows in descending order (on and iy >= 0) */
} cl_fuse8_t;

/* cl_fuse8_t for a map8 update with the shift (ix + fx / 256, iy + fy / 256). */
static void cl_fuse8_init_(const pft_pre_clutter_t *c, cl_fuse8_t *fz, int32_t ix, uint32_t fx,
                           int32_t iy, uint32_t fy)
{
    const int32_t w = (int32_t)c->gw, h = (int32_t)c->gh;
    fz->hc = c->acc;
    fz->hn = c->acc + c->gw;
    fz->ix = ix;
    fz->iy = iy;
    fz->fx = fx;
    fz->fy = fy;
    /* columns whose two sources are inside: x - ix - 1 >= 0 and x - ix < w */
    fz->xlo = ix + 1 < 0 ? 0 : (ix + 1 > w ? w : ix + 1);
    fz->xhi = ix > 0 ? w : (w + ix < fz->xlo ? fz->xlo : w + ix);
    fz->down = iy >= 0;
    fz->next = fz->down ? h - 1 : 0;
    fz->on = true;
}

/* The horizontal pass of source row sy (decoded into c->row first) into hr; a row outside the
 * frame gives b = 1 sigma^2 in every column. */
static void cl_fuse8_h_(pft_pre_clutter_t *c, const cl_fuse8_t *fz, uint32_t *hr, int32_t sy)
{
    const int32_t w = (int32_t)c->gw, h = (int32_t)c->gh;
    if (sy >= 0 && sy < h) {
        cl_dec8_row_(c->m8 + (size_t)sy * (size_t)w, c->row, w);
        cl_warp_h_(c->row, hr, 0, w, 1, fz->ix, fz->fx, CL_ONE_, fz->xlo, fz->xhi);
    } else {
        cl_warp_h_(c->row, hr, -1, w, 1, fz->ix, fz->fx, CL_ONE_, fz->xlo, fz->xhi);
    }
}

/* Warps row fz->next into its ring slot (cl_warp_'s order and sums: the first row's shared
 * source row first, then per row the other one) and moves fz->next on. */
static void cl_fuse8_row_(pft_pre_clutter_t *c, cl_fuse8_t *fz)
{
    const int32_t w = (int32_t)c->gw, h = (int32_t)c->gh;
    const int32_t y = fz->next, iy = fz->iy;
    const bool down = fz->down;
    if (y == (down ? h - 1 : 0)) {
        /* descending, row y's first source y - iy; ascending, its second y - iy - 1 */
        cl_fuse8_h_(c, fz, fz->hc, down ? y - iy : y - iy - 1);
    }
    cl_fuse8_h_(c, fz, fz->hn, down ? y - iy - 1 : y - iy);
    const uint32_t *h1 = down ? fz->hc : fz->hn, *h0 = down ? fz->hn : fz->hc; /* weights 256 - fy, fy */
    const uint32_t fy = fz->fy;
    uint16_t *o = c->ring + (size_t)((uint32_t)y % (2u * (uint32_t)c->cfg.blur + 1u)) * (size_t)w;
    for (int32_t x = 0; x < w; ++x) {
        /* the interpolated value <= 64512 (a mix of code values) */
        o[x] = cl_round8_((uint16_t)(((h1[x] << 8) + (h0[x] - h1[x]) * fy + 32768u) >> 16));
    }
    uint32_t *t = fz->hc;
    fz->hc = fz->hn;
    fz->hn = t;
    fz->next = down ? y - 1 : y + 1;
}

/* The map's former row r (0..h-1) while row y is updated: rows above y come from the ring
 * (map8: every row, decoded). */
static const uint16_t *cl_row_(const pft_pre_clutter_t *c, int32_t r, int32_t y)
{
    const int32_t h = (int32_t)c->gh;
    const int32_t rr = r < 0 ? 0 : (r >= h ? h - 1 : r);
    if (c->m8 != NULL) {
        return c->ring + (size_t)((uint32_t)rr % (2u * (uint32_t)c->cfg.blur + 1u)) * c->gw;
    }
    if (rr <= y) {
        return c->ring + (size_t)((uint32_t)rr % ((uint32_t)c->cfg.blur + 1u)) * c->gw;
    }
    return c->m + (size_t)rr * c->gw;
}

/* Read value of the map at every pixel of row y (before its update): the sum over the square
 * (box) or its largest value, Q6.10, into c->hs (c->vs: the vertical pass). The box's sums in
 * plain (vectorisable) passes of up to three terms each: the same integer sums in another
 * order (every sum <= 81 * 65535 < 2^32). */
static void cl_read_row_(pft_pre_clutter_t *c, int32_t y)
{
    const int32_t b = (int32_t)c->cfg.blur, w = (int32_t)c->gw;
    uint32_t *vs = c->vs;
    const uint16_t *r0 = cl_row_(c, y - b, y);
    if (c->cfg.box) {
        /* rows y - b .. y + b: the first three (or the one of blur 0) in one pass, then two
         * per pass */
        if (b == 0) {
            for (int32_t x = 0; x < w; ++x) {
                vs[x] = r0[x];
            }
        } else {
            const uint16_t *r1 = cl_row_(c, y - b + 1, y), *r2 = cl_row_(c, y - b + 2, y);
            for (int32_t x = 0; x < w; ++x) {
                vs[x] = (uint32_t)r0[x] + (uint32_t)r1[x] + (uint32_t)r2[x];
            }
        }
        for (int32_t k = -b + 3; k <= b; k += 2) {
            const uint16_t *ra = cl_row_(c, y + k, y);
            if (k + 1 <= b) {
                const uint16_t *rb = cl_row_(c, y + k + 1, y);
                for (int32_t x = 0; x < w; ++x) {
                    vs[x] += (uint32_t)ra[x] + (uint32_t)rb[x];
                }
            } else {
                for (int32_t x = 0; x < w; ++x) {
                    vs[x] += ra[x];
                }
            }
        }
    } else {
        for (int32_t x = 0; x < w; ++x) {
            vs[x] = r0[x];
        }
        for (int32_t k = -b + 1; k <= b; ++k) {
            const uint16_t *r = cl_row_(c, y + k, y);
            for (int32_t x = 0; x < w; ++x) {
                vs[x] = r[x] > vs[x] ? r[x] : vs[x];
            }
        }
    }
    /* horizontal: sum (box) or largest value over 2 b + 1 columns, edges replicated */
    uint32_t *hs = c->hs;
    if (c->cfg.box) {
        /* interior columns b .. w - b - 1: the 2 b + 1 terms summed directly, three in the
         * first pass (blur 0: the one), two per further pass; the same sums as the running
         * box of the edges */
        const int32_t xi0 = b, xi1 = w - b > b ? w - b : b;
        if (b == 0) {
            for (int32_t x = xi0; x < xi1; ++x) {
                hs[x] = vs[x];
            }
        } else {
            for (int32_t x = xi0; x < xi1; ++x) {
                hs[x] = vs[x - b] + vs[x - b + 1] + vs[x - b + 2];
            }
        }
        for (int32_t k = -b + 3; k <= b; k += 2) {
            if (k + 1 <= b) {
                for (int32_t x = xi0; x < xi1; ++x) {
                    hs[x] += vs[x + k] + vs[x + k + 1];
                }
            } else {
                for (int32_t x = xi0; x < xi1; ++x) {
                    hs[x] += vs[x + k];
                }
            }
        }
        /* the edge columns: the same sum with the columns beyond the edge replicated */
        for (int32_t e = 0; e < 2 * b; ++e) {
            const int32_t x = e < b ? e : xi1 + (e - b); /* columns 0 .. b - 1, w - b .. w - 1 */
            uint32_t acc = 0u;
            for (int32_t k = -b; k <= b; ++k) {
                acc += vs[x + k < 0 ? 0 : (x + k >= w ? w - 1 : x + k)];
            }
            hs[x] = acc;
        }
    } else {
        for (int32_t x = 0; x < w; ++x) {
            uint32_t acc = vs[x];
            for (int32_t k = -b; k <= b; ++k) {
                const int32_t xx = x + k < 0 ? 0 : (x + k >= w ? w - 1 : x + k);
                acc = vs[xx] > acc ? vs[xx] : acc;
            }
            hs[x] = acc;
        }
    }
}

/* floor(sqrt(x)), x = mm 2^10 < 2^26: for mm >= 2^10 (every scored pixel of a map with thr >=
 * 1 sigma^2 has its mean M >= thr) Newton's integer iteration s <- (s + x / s) / 2 from s0 =
 * cl_sqrt_top_[mm >> 10] >= floor(sqrt(x)) (x < (k + 1) 2^20): while s > floor(sqrt(x)) the
 * next s is smaller and >= floor(sqrt(x)) (AM-GM), and at s = floor(sqrt(x)) it is not
 * smaller, so the first step that does not decrease s ends at floor(sqrt(x)); 3 to 5 steps
 * (s0 within 42 % above). Below 2^10, pft_pre_isqrt64_. test_pre_sqrt compares it with
 * pft_pre_isqrt64_ for every mm in 0..65535. */
uint32_t pft_pre_sqrt_q10_(uint32_t mm)
{
    /* the iteration's starting points: floor(sqrt((k + 1) 2^20)) for mm in
     * [k 2^10, (k + 1) 2^10), k = 0..63 (k 0 unused). */
    static const uint16_t cl_sqrt_top_[64] = {
        1024u, 1448u, 1773u, 2048u, 2289u, 2508u, 2709u, 2896u, 3072u, 3238u, 3396u, 3547u, 3692u,
        3831u, 3965u, 4096u, 4222u, 4344u, 4463u, 4579u, 4692u, 4802u, 4910u, 5016u, 5120u, 5221u,
        5320u, 5418u, 5514u, 5608u, 5701u, 5792u, 5882u, 5970u, 6058u, 6144u, 6228u, 6312u, 6394u,
        6476u, 6556u, 6636u, 6714u, 6792u, 6869u, 6945u, 7020u, 7094u, 7168u, 7240u, 7312u, 7384u,
        7454u, 7524u, 7594u, 7662u, 7731u, 7798u, 7865u, 7931u, 7997u, 8062u, 8127u, 8192u};
    if (mm < 1024u || mm > 65535u) {
        return pft_pre_isqrt64_((uint64_t)mm << 10);
    }
    const uint32_t x = mm << 10;
    uint32_t s = cl_sqrt_top_[mm >> 10];
    for (uint32_t i = 0u; i < 16u; ++i) { /* at most 5 steps are taken; 16 bounds the loop */
        const uint32_t n = (s + x / s) >> 1;
        if (n >= s) {
            break;
        }
        s = n;
    }
    return s;
}

/* The chunked scoring's test for the columns x0..x1 - 1 of a row's reads hs (x1 - x0 <= 32):
 * negative when some read may exceed thr (a full chunk: the OR of thr - hs, all < 2^23, so
 * negative exactly when some hs > thr; a shorter last chunk: always, it is scored per pixel). */
static inline int32_t cl_chunk_any_(const uint32_t *hs, int32_t sthr, int32_t x0, int32_t x1)
{
    int32_t any = -1;
    if (x1 - x0 == 32) {
        const uint32_t *hc = hs + x0;
        any = 0;
        for (int32_t i = 0; i < 32; ++i) {
            any |= sthr - (int32_t)hc[i];
        }
    }
    return any;
}

/* (d a + 2^15) >> 16 for d, a < 2^16: the high half of the product d a plus bit 15 of its low
 * half, each half computed on its own (a form the compiler maps to 16-bit multiplies, high and
 * low). */
static inline uint16_t cl_round_scale16_(uint16_t d, uint16_t a)
{
    const uint16_t hi = (uint16_t)(((uint32_t)d * (uint32_t)a) >> 16);
    const uint16_t lo = (uint16_t)((uint32_t)d * (uint32_t)a);
    return (uint16_t)(hi + (uint16_t)(lo >> 15));
}

/* Row y without the running mean (the default): the per-pixel formulas of pft_pre.h
 * (docs/algorithms.md 9.9) in plain passes: the map's update (it reads r), then the output
 * (which may be r itself, inplace). The output is the residual itself except
 * where the square's read exceeds thr (a masked pixel stays PFT_RES16_MASKED, any other
 * value is within +-PFT_PRE_RMAX_ already), and 0 where it exceeds veto; the map's update runs on every pixel and is kept
 * where the pixel is not masked. Its ranges: t and m in 0..65535, so |t - m| <= 65535, and
 * a <= 65535 but on the first frame (a = 2^16, where the update gives m = t): the update in
 * 16-bit lanes with a 16 x 16 -> 32-bit product (a |t - m| + 32768 < 2^32). The output in
 * chunks of 32 columns: a chunk whose reads are all <= thr (hs and thr < 2^23, so compared as
 * signed) is the residual itself. */
static void cl_row_plain_(const int16_t *r, int16_t *o, uint16_t *mrow, const uint32_t *hs,
                          int32_t w, uint32_t a, uint32_t thr, uint32_t veto, uint32_t area)
{
    /* the map's update first: it reads the residual, which o may be (inplace) */
    if (a > 65535u) {
        for (int32_t x = 0; x < w; ++x) {
            const int32_t v = r[x];
            const uint32_t ac = (uint32_t)(v < 0 ? -v : v);
            const uint32_t t0 = (ac * ac + 32u) >> 6;
            mrow[x] = v == PFT_RES16_MASKED ? mrow[x] : (uint16_t)(t0 > CL_MMAX_ ? CL_MMAX_ : t0);
        }
    } else {
        const uint16_t a16 = (uint16_t)a;
        for (int32_t x = 0; x < w; ++x) {
            const int16_t v = r[x];
            /* |v| <= 2^15 (2^15: the mask, whose update is not kept), and ac^2 = v^2 <= 2^30,
             * formed from v itself (a signed 16 x 16 -> 32-bit product: no absolute value on
             * the chain). t = min((ac^2 + 32) >> 6, 65535) in 16-bit halves of ac^2 = hi 2^16
             * + lo: (ac^2 + 32) >> 6 = hi 2^10 + (lo >> 6) + bit 5 of lo (<= 65473 for ac <=
             * 2047); ac >= 2048 gives ac^2 >= 2^22, the clamp: all ones ORed in, tested on v
             * itself (v + 2047 as uint16 exceeds 4094 exactly when v >= 2048 or v <= -2048) */
            const uint32_t sq = (uint32_t)((int32_t)v * (int32_t)v);
            const uint16_t hi = (uint16_t)(sq >> 16);
            const uint16_t lo = (uint16_t)sq;
            const uint16_t tl = (uint16_t)((uint16_t)(hi << 10) + (uint16_t)(lo >> 6) + (uint16_t)((lo >> 5) & 1u));
            const uint16_t big = (uint16_t)(0u - (uint16_t)((uint16_t)((int32_t)v + 2047) > 4094u ? 1u : 0u));
            const uint16_t t = (uint16_t)(tl | big);
            const uint16_t m = mrow[x];
            const uint16_t neg = (uint16_t)(t >= m ? 0u : 0xFFFFu);       /* t < m */
            const uint16_t d = (uint16_t)((uint16_t)((uint16_t)(t - m) ^ neg) - neg); /* |t - m| */
            /* q = (d a + 2^15) >> 16: the product's high half plus bit 15 of its low half */
            const uint16_t q = cl_round_scale16_(d, a16);
            const uint16_t nm = (uint16_t)(m + (uint16_t)((uint16_t)(q ^ neg) - neg)); /* m +- q */
            mrow[x] = v == PFT_RES16_MASKED ? m : nm;
        }
    }
    if (o != r) {
        memcpy(o, r, (size_t)w * 2u);
    }
    const int32_t sthr = (int32_t)thr;
    for (int32_t x0 = 0; x0 < w; x0 += 32) {
        const int32_t x1 = w - x0 >= 32 ? x0 + 32 : w;
        const int32_t any = cl_chunk_any_(hs, sthr, x0, x1);
        for (int32_t x = x0; any < 0 && x < x1; ++x) {
            const int32_t v = o[x]; /* r[x]: o is its copy, or r itself */
            if (hs[x] > thr && v != PFT_RES16_MASKED) {
                const uint32_t mm = (hs[x] + area / 2u) / area; /* the square's mean, Q6.10 */
                const uint32_t s = pft_pre_sqrt_q10_(mm);         /* sqrt(M) in Q10 */
                o[x] = hs[x] > veto ? (int16_t)0 : (int16_t)pft_pre_rclamp_(cl_div_(v * 1024, (int32_t)s));
            }
        }
    }
}

/* (d a + 2^15) >> 16 for d <= 65535 and a <= 2^16 (a16 = min(a, 65535), full: a = 2^16,
 * where it is d): with a < 2^16 the product's high half plus bit 15 of its low half, in 16-bit
 * halves (a form the compiler maps to 16-bit multiplies). */
static inline uint16_t cl_round_scale_(uint16_t d, uint16_t a16, uint16_t full)
{
    const uint16_t q = cl_round_scale16_(d, a16);
    return full != 0u ? d : q;
}

#if defined(__SSE2__)
/* Where the compiler has SSE2 (x86-64), the gated mean's pixel (cl_mean_px_, cl_gate_px_)
 * takes its compares and clamps in the forms SSE2 has (signed 16-bit compares and min; no
 * unsigned 16-bit compare or min, which the compiler emulates with several instructions) and
 * cl_mean_span_ runs a loop per value of full, so that cl_round_scale_'s per-pixel choice
 * leaves the loops (the same values; fewer register spills). Other targets keep the forms
 * below the #else (their object code as before: a scalar core pays no more for an unsigned
 * compare, and at -Os a second loop would call the pixel functions out of line). */
#define CL_SSE2_ 1
#endif

#if !defined(CL_SSE2_) && defined(__aarch64__) && defined(__ARM_NEON) && defined(__BYTE_ORDER__) && \
    (__BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__)
/* Where the compiler has AArch64's Advanced SIMD (NEON; little-endian), cl_mean_span_ takes 8
 * pixels at a time in NEON's forms (cl_mean8_neon_): saturating and rounding narrowing shifts
 * (t = min((c^2 + 32) >> 6, 65535) and (d a + 2^15) >> 16 each a widening product and one
 * narrowing shift), absolute differences, unsigned saturating steps of the counter; the same
 * values as the plain pixel functions, which take the columns left over. */
#define CL_NEON_ 1
#endif

/* One pixel of cl_row_mean_'s pass 1: m and mu (mu where learn) from the residual v = *ov, c
 * + 2^16 into *cs (0 where v is masked: nothing changes there) and the output before scoring,
 * the masked value or clamp(c), over v in *ov. Every value in 16-bit lanes, so that the loop
 * takes 8 pixels per 16-byte vector: mv = mu - 2^15 in [-2^14, 2^14] and the signed shift
 * sdm = +-dm (|dm| <= 2^11) fit int16, and c = v - sdm (|c| <= 2^15 + 2^11, 17 bits) is
 * kept as its low 16 bits c16 and its sign (c < 0 exactly when v < sdm, a 16-bit compare):
 * |c| = c16 or -c16 (mod 2^16, exact: |c| < 2^16), clamp(c) = +-min(|c|, 2^15 - 1) and c +
 * 2^16 = c16 (c < 0) or c16 + 2^16. t = min((c^2 + 32) >> 6, 65535) from the 16-bit halves of
 * |c|^2 as in cl_row_plain_ (|c| >= 2048: the clamp), |t - m| <= 65535; the mean's target
 * clamp(8 v, +-2^14) as 8 clamp(v, +-2^11), e = tv - mv with |e| <= 2^15 and its sign from a
 * 16-bit compare; the signs applied by two's complement in 16 bits (m + -q and mv + -qe stay
 * in range). The same values as the 32-bit form it replaced (branch ircost15). */
static inline void cl_mean_px_(int16_t *ov, uint16_t learn, uint16_t a16, uint16_t full, uint16_t mfl,
                               uint16_t *m, uint16_t *mu, uint32_t *cs)
{
    const int16_t v = *ov;
    const uint16_t msk = (uint16_t)(v == PFT_RES16_MASKED ? 0xFFFFu : 0u);
    const uint16_t mu0 = *mu;
    const int16_t mv = (int16_t)(uint16_t)(mu0 ^ CL_MUOFF_);
    const uint16_t mvn = (uint16_t)(mv < 0 ? 0xFFFFu : 0u);
    const uint16_t amv = (uint16_t)((uint16_t)((uint16_t)mv ^ mvn) - mvn);
    const uint16_t dr = (uint16_t)((uint16_t)(amv + 4u) >> 3); /* cl_div_(mv, 8) in magnitude */
#ifdef CL_SSE2_
    /* mean_floor (0: dm = dr); dr, mfl <= 2048: a signed compare */
    const uint16_t dm = (int16_t)dr > (int16_t)mfl ? dr : 0u;
#else
    const uint16_t dm = dr > mfl ? dr : 0u;                     /* mean_floor (0: dm = dr) */
#endif
    const int16_t sdm = (int16_t)(uint16_t)((uint16_t)(dm ^ mvn) - mvn); /* mv < 0: -dm */
    const uint16_t cn = (uint16_t)(v < sdm ? 0xFFFFu : 0u);  /* c < 0 */
    const uint16_t c16 = (uint16_t)((uint16_t)v - (uint16_t)sdm); /* c mod 2^16 */
    const uint16_t ac = (uint16_t)((uint16_t)(c16 ^ cn) - cn); /* |c| */
    const uint16_t hi = (uint16_t)(((uint32_t)ac * (uint32_t)ac) >> 16);
    const uint16_t lo = (uint16_t)((uint32_t)ac * (uint32_t)ac);
    const uint16_t tl = (uint16_t)((uint16_t)(hi << 10) + (uint16_t)(lo >> 6) + (uint16_t)((lo >> 5) & 1u));
#ifdef CL_SSE2_
    const uint16_t t = (uint16_t)(ac >> 11) != 0u ? (uint16_t)CL_MMAX_ : tl; /* ac >= 2048: the clamp */
#else
    const uint16_t t = ac >= 2048u ? (uint16_t)CL_MMAX_ : tl;
#endif
    const uint16_t m0 = *m;
    const uint16_t neg = (uint16_t)(t >= m0 ? 0u : 0xFFFFu); /* t < m */
    const uint16_t d = (uint16_t)((uint16_t)((uint16_t)(t - m0) ^ neg) - neg); /* |t - m| */
    const uint16_t q = cl_round_scale_(d, a16, full);
    const uint16_t nm = (uint16_t)(m0 + (uint16_t)((uint16_t)(q ^ neg) - neg));
    *m = (uint16_t)((m0 & msk) | (nm & (uint16_t)~msk));
    const int16_t vc = v > 2048 ? (int16_t)2048 : (v < -2048 ? (int16_t)-2048 : v);
    const int16_t tv = (int16_t)(uint16_t)((uint16_t)vc << 3); /* clamp(8 v, +-CL_MUMAX_) */
    const uint16_t ne = (uint16_t)(tv < mv ? 0xFFFFu : 0u);   /* e < 0 */
    const uint16_t ae = (uint16_t)((uint16_t)((uint16_t)((uint16_t)tv - (uint16_t)mv) ^ ne) - ne);
    const uint16_t qe = cl_round_scale_(ae, a16, full);
    const uint16_t nmu = (uint16_t)(mu0 + (uint16_t)((uint16_t)(qe ^ ne) - ne));
    const uint16_t keep = (uint16_t)(msk | (uint16_t)(learn - 1u)); /* masked or not learnt */
    *mu = (uint16_t)((mu0 & keep) | (nmu & (uint16_t)~keep));
#ifdef CL_SSE2_
    /* min(ac, 32767) as ac less its saturated excess (SSE2 has no unsigned 16-bit min) */
    const uint16_t acl = (uint16_t)(ac - (ac > (uint16_t)PFT_PRE_RMAX_ ? (uint16_t)(ac - (uint16_t)PFT_PRE_RMAX_) : 0u));
#else
    const uint16_t acl = ac > (uint16_t)PFT_PRE_RMAX_ ? (uint16_t)PFT_PRE_RMAX_ : ac;
#endif
    const uint16_t oc = (uint16_t)((uint16_t)(acl ^ cn) - cn); /* clamp(c) */
    *cs = msk != 0u ? 0u : (uint32_t)c16 + (cn != 0u ? 0u : 65536u);
    *ov = (int16_t)(uint16_t)((oc & (uint16_t)~msk) | ((uint16_t)PFT_RES16_MASKED & msk));
}

#ifdef CL_SSE2_
/* One pixel of cl_row_mean_'s gate (persist): the counter *p from the stage's residual v (o[x]
 * before the mean pass writes it) and whether the mean takes this residual (*learn, 1 or 0).
 * In 16-bit lanes with signed compares (SSE2 has no unsigned 16-bit compare or min): exc <=
 * 32767, pk <= 2^13, pcap = 2 pk <= 2^14 and the counter p <= pcap (every writer caps it there,
 * the warp interpolates, a move or reset fills 0), so p + 256 <= 2^14 + 256, p1 and pk fit
 * int16 and min(p + 256, pcap) is a signed min; |v| of a pixel that is not masked fits int16,
 * and the mask's |v| = 2^15 (-2^15 as int16: ex = 0) changes only *learn, which the mean pass
 * does not read at a masked pixel (it keeps m and mu there), and not *p (kept). */
static inline void cl_gate_px_(int16_t v, uint16_t *p, uint16_t exc, uint16_t pk, uint16_t pcap,
                               uint16_t *learn)
{
    const uint16_t vn = (uint16_t)(v < 0 ? 0xFFFFu : 0u);
    const uint16_t av = (uint16_t)((uint16_t)((uint16_t)v ^ vn) - vn); /* |v|, 2^15 for the mask */
    const uint16_t p0 = *p;
    const int16_t pp = (int16_t)(uint16_t)(p0 + 256u);
    const uint16_t pu = pp < (int16_t)pcap ? (uint16_t)pp : pcap;
    const uint16_t pd = p0 > 128u ? (uint16_t)(p0 - 128u) : 0u;
    const uint16_t ex = (uint16_t)((int16_t)av > (int16_t)exc ? 1u : 0u);
    const uint16_t p1 = ex != 0u ? pu : pd;
    *p = v == PFT_RES16_MASKED ? p0 : p1;
    *learn = (uint16_t)((ex ^ 1u) | ((int16_t)p1 >= (int16_t)pk ? 1u : 0u));
}
#else
/* One pixel of cl_row_mean_'s gate (persist): the counter *p from the stage's residual v (o[x]
 * before the mean pass writes it) and whether the mean takes this residual (*learn, 1 or 0).
 * In 16-bit lanes: exc <= 32767, pk <= 2^13, pcap = 2 pk, so p + 256 is tested against pcap
 * without forming it (plim = pcap - 256 >= 256). */
static inline void cl_gate_px_(int16_t v, uint16_t *p, uint16_t exc, uint16_t pk, uint16_t pcap,
                               uint16_t plim, uint16_t *learn)
{
    const uint16_t vn = (uint16_t)(v < 0 ? 0xFFFFu : 0u);
    const uint16_t av = (uint16_t)((uint16_t)((uint16_t)v ^ vn) - vn); /* |v|, 2^15 for the mask */
    const uint16_t p0 = *p;
    const uint16_t pu = p0 > plim ? pcap : (uint16_t)(p0 + 256u);
    const uint16_t pd = p0 > 128u ? (uint16_t)(p0 - 128u) : 0u;
    const uint16_t ex = (uint16_t)(av > exc ? 1u : 0u);
    const uint16_t p1 = ex != 0u ? pu : pd;
    *p = v == PFT_RES16_MASKED ? p0 : p1;
    *learn = (uint16_t)((ex ^ 1u) | (p1 >= pk ? 1u : 0u));
}
#endif

#ifdef CL_SSE2_
/* The constants of cl_mean8_sse2_'s lanes (each a 16-bit value in all 8 lanes). */
typedef struct {
    __m128i a, mfl, exc, nexc, pk, pcap; /* a16, mean_floor, excess and -excess, pk, pcap */
    __m128i zero, one, four, h8, rmax, nrmax, lim, nlim, p256, p128;
} cl_sse2k_t;

/* (d a + 2^15) >> 16 per lane (d, a < 2^16): the product's high half (pmulhuw) plus bit 15 of
 * its low half (pmullw), cl_round_scale16_'s form; d where full (a = 2^16). */
static inline __m128i cl_scale8_sse2_(__m128i d, __m128i a, bool full)
{
    return full ? d : _mm_add_epi16(_mm_mulhi_epu16(d, a), _mm_srli_epi16(_mm_mullo_epi16(d, a), 15));
}

/* Columns x .. x + 7 of cl_mean_span_ (x86-64 with SSE2): cl_gate_px_ (gate: pc != NULL) and
 * cl_mean_px_ of their SSE2 forms above in 8 lanes, the same values for any input. |mv|, |c|
 * and |e| as (u ^ s) - s with s the lane's sign from a signed 16-bit compare or shift (SSE2 has
 * no pabsw); the signed compares and mins of the pixel forms as pcmpgtw, pminsw and pmaxsw;
 * max(p - 128, 0) as an unsigned saturating subtraction; t >= m where m - t saturates to 0, |t
 * - m| the OR of the two saturating differences (one of them 0); the products' high and low
 * halves as pmulhuw and pmullw. A masked pixel keeps m, mu and p: its steps are zeroed before
 * they are applied (a zero step, either sign, leaves the value), its counter selected. The gate's
 * |v| > exc as v > exc or v < -exc: the same for every v but the mask (-2^15, whose |v| is 2^15,
 * -2^15 as int16: not over exc in the pixel form), where it changes only learn, which the mean
 * does not read there (masked: kept). The output clamp(c) = max(min(c, 32767), -32767) with the
 * signed saturating v - sdm (c's range is +-(2^15 + 2^11)), then min'ed with -2^15 where masked
 * (32767 ^ msk: 32767, or -2^15); c + 2^16 (0 where masked) as the 16-bit halves c16 and [c >=
 * 0] interleaved. */
static inline void cl_mean8_sse2_(int16_t *o, uint16_t *mrow, uint16_t *mu, uint16_t *pc, uint32_t *cs,
                                  int32_t x, const cl_sse2k_t *k, bool gate, bool full)
{
    const __m128i v = _mm_loadu_si128((const __m128i *)(const void *)(o + x));
    const __m128i msk = _mm_cmpeq_epi16(v, k->h8);
    __m128i keep = msk; /* mu kept: masked, or not learnt */
    if (gate) {
        const __m128i p0 = _mm_loadu_si128((const __m128i *)(const void *)(pc + x));
        const __m128i pu = _mm_min_epi16(_mm_add_epi16(p0, k->p256), k->pcap);
        const __m128i pd = _mm_subs_epu16(p0, k->p128);
        const __m128i ex = _mm_or_si128(_mm_cmpgt_epi16(v, k->exc), _mm_cmpgt_epi16(k->nexc, v));
        const __m128i p1 = _mm_or_si128(_mm_and_si128(ex, pu), _mm_andnot_si128(ex, pd));
        _mm_storeu_si128((__m128i *)(void *)(pc + x),
                         _mm_or_si128(_mm_and_si128(msk, p0), _mm_andnot_si128(msk, p1)));
        /* not learnt: ex and p1 < pk */
        keep = _mm_or_si128(msk, _mm_and_si128(ex, _mm_cmpgt_epi16(k->pk, p1)));
    }
    const __m128i mu0 = _mm_loadu_si128((const __m128i *)(const void *)(mu + x));
    const __m128i mv = _mm_xor_si128(mu0, k->h8); /* mu - 2^15 */
    const __m128i mvn = _mm_srai_epi16(mv, 15);
    const __m128i amv = _mm_sub_epi16(_mm_xor_si128(mv, mvn), mvn);
    const __m128i dr = _mm_srli_epi16(_mm_add_epi16(amv, k->four), 3);
    const __m128i dm = _mm_and_si128(dr, _mm_cmpgt_epi16(dr, k->mfl));
    const __m128i sdm = _mm_sub_epi16(_mm_xor_si128(dm, mvn), mvn);
    const __m128i cn = _mm_cmpgt_epi16(sdm, v); /* c < 0 */
    const __m128i c16 = _mm_sub_epi16(v, sdm);
    const __m128i ac = _mm_sub_epi16(_mm_xor_si128(c16, cn), cn);
    const __m128i hi = _mm_mulhi_epu16(ac, ac), lo = _mm_mullo_epi16(ac, ac);
    const __m128i tl = _mm_add_epi16(_mm_add_epi16(_mm_slli_epi16(hi, 10), _mm_srli_epi16(lo, 6)),
                                     _mm_and_si128(_mm_srli_epi16(lo, 5), k->one));
    const __m128i big = _mm_cmpgt_epi16(_mm_srli_epi16(ac, 11), k->zero); /* ac >= 2048 */
    const __m128i t = _mm_or_si128(tl, big);
    const __m128i m0 = _mm_loadu_si128((const __m128i *)(const void *)(mrow + x));
    const __m128i dmt = _mm_subs_epu16(m0, t);
    const __m128i nn = _mm_cmpeq_epi16(dmt, k->zero); /* t >= m */
    const __m128i d = _mm_andnot_si128(msk, _mm_or_si128(dmt, _mm_subs_epu16(t, m0)));
    const __m128i q = cl_scale8_sse2_(d, k->a, full);
    _mm_storeu_si128((__m128i *)(void *)(mrow + x),
                     _mm_sub_epi16(_mm_add_epi16(m0, _mm_and_si128(nn, q)), _mm_andnot_si128(nn, q)));
    const __m128i tv = _mm_slli_epi16(_mm_max_epi16(_mm_min_epi16(v, k->lim), k->nlim), 3);
    const __m128i ne = _mm_cmpgt_epi16(mv, tv); /* e < 0 */
    const __m128i e = _mm_sub_epi16(tv, mv);
    const __m128i ae = _mm_andnot_si128(keep, _mm_sub_epi16(_mm_xor_si128(e, ne), ne));
    const __m128i qe = cl_scale8_sse2_(ae, k->a, full);
    _mm_storeu_si128((__m128i *)(void *)(mu + x), _mm_add_epi16(mu0, _mm_sub_epi16(_mm_xor_si128(qe, ne), ne)));
    const __m128i oc = _mm_max_epi16(_mm_subs_epi16(v, sdm), k->nrmax);
    _mm_storeu_si128((__m128i *)(void *)(o + x), _mm_min_epi16(oc, _mm_xor_si128(msk, k->rmax)));
    const __m128i cl = _mm_andnot_si128(msk, c16);
    const __m128i ch = _mm_andnot_si128(_mm_or_si128(msk, cn), k->one);
    _mm_storeu_si128((__m128i *)(void *)(cs + x), _mm_unpacklo_epi16(cl, ch));
    _mm_storeu_si128((__m128i *)(void *)(cs + x + 4), _mm_unpackhi_epi16(cl, ch));
}

/* Columns x0..x1-1 of cl_row_mean_'s gate (pc, persist) and mean pass with one floor mfl for
 * all of them: whole blocks of 8 columns in SSE2's lanes (cl_mean8_sse2_, full a constant in
 * each loop), the columns left over in the per-pixel loops below, with one floor (a constant)
 * and full a constant in each loop, so that cl_round_scale_'s choice leaves the loops (the
 * same values). */
static inline void cl_mean_span_(int16_t *o, uint16_t *mrow, uint16_t *mu, uint16_t *pc, uint32_t *cs,
                                 int32_t x0, int32_t x1, uint16_t a16, uint16_t full, uint32_t exc,
                                 uint32_t pk, uint32_t pcap, int32_t mfl)
{
    const uint16_t f16 = (uint16_t)mfl; /* 0..CL_FLOORMAX_ */
    /* exc 1..32767, pk = persist * 256 in 256..PFT_PRE_CLUTTER_MAX_PERSIST * 256 = 2^13
     * (the config check), pcap = 2 pk <= 2^14 (without persist pk = pcap = 0, not read) */
    const uint16_t e16 = (uint16_t)exc, k16 = (uint16_t)pk, c16 = (uint16_t)pcap;
    const int32_t xs = x0 + ((x1 - x0) & ~7);
    if (xs > x0) {
        cl_sse2k_t k;
        k.a = _mm_set1_epi16((int16_t)a16);
        k.mfl = _mm_set1_epi16((int16_t)f16);
        k.exc = _mm_set1_epi16((int16_t)e16);
        k.nexc = _mm_set1_epi16((int16_t)(-(int32_t)e16));
        k.pk = _mm_set1_epi16((int16_t)k16);
        k.pcap = _mm_set1_epi16((int16_t)c16);
        k.zero = _mm_setzero_si128();
        k.one = _mm_set1_epi16(1);
        k.four = _mm_set1_epi16(4);
        k.h8 = _mm_set1_epi16((int16_t)PFT_RES16_MASKED); /* also mu's offset 2^15 */
        k.rmax = _mm_set1_epi16((int16_t)PFT_PRE_RMAX_);
        k.nrmax = _mm_set1_epi16((int16_t)-PFT_PRE_RMAX_);
        k.lim = _mm_set1_epi16(2048);
        k.nlim = _mm_set1_epi16(-2048);
        k.p256 = _mm_set1_epi16(256);
        k.p128 = _mm_set1_epi16(128);
        /* the gate and full constants in each loop (the first frame: full) */
        if (pc != NULL && full == 0u) {
            for (int32_t x = x0; x < xs; x += 8) {
                cl_mean8_sse2_(o, mrow, mu, pc, cs, x, &k, true, false);
            }
        } else if (pc != NULL) {
            for (int32_t x = x0; x < xs; x += 8) {
                cl_mean8_sse2_(o, mrow, mu, pc, cs, x, &k, true, true);
            }
        } else if (full == 0u) {
            for (int32_t x = x0; x < xs; x += 8) {
                cl_mean8_sse2_(o, mrow, mu, pc, cs, x, &k, false, false);
            }
        } else {
            for (int32_t x = x0; x < xs; x += 8) {
                cl_mean8_sse2_(o, mrow, mu, pc, cs, x, &k, false, true);
            }
        }
    }
    if (pc != NULL) {
        if (full != 0u) {
            for (int32_t x = xs; x < x1; ++x) {
                uint16_t learn;
                cl_gate_px_(o[x], &pc[x], e16, k16, c16, &learn);
                cl_mean_px_(&o[x], learn, a16, 1u, f16, &mrow[x], &mu[x], &cs[x]);
            }
        } else {
            for (int32_t x = xs; x < x1; ++x) {
                uint16_t learn;
                cl_gate_px_(o[x], &pc[x], e16, k16, c16, &learn);
                cl_mean_px_(&o[x], learn, a16, 0u, f16, &mrow[x], &mu[x], &cs[x]);
            }
        }
    } else if (full != 0u) {
        for (int32_t x = xs; x < x1; ++x) {
            cl_mean_px_(&o[x], 1u, a16, 1u, f16, &mrow[x], &mu[x], &cs[x]);
        }
    } else {
        for (int32_t x = xs; x < x1; ++x) {
            cl_mean_px_(&o[x], 1u, a16, 0u, f16, &mrow[x], &mu[x], &cs[x]);
        }
    }
}
#else
#ifdef CL_NEON_
/* (d a + 2^15) >> 16 per lane (d, a < 2^16: the product < 2^32, the rounding taken in the
 * narrowing shift, exact), or d where full (a = 2^16). */
static inline uint16x8_t cl_scale8_neon_(uint16x8_t d, uint16x8_t a, bool full)
{
    if (full) {
        return d;
    }
    const uint32x4_t lo = vmull_u16(vget_low_u16(d), vget_low_u16(a));
    const uint32x4_t hi = vmull_high_u16(d, a);
    return vrshrn_high_n_u32(vrshrn_n_u32(lo, 16), hi, 16);
}

/* Columns x0 .. x0 + 8 n - 1 of cl_mean_span_ (n blocks of 8): cl_gate_px_ (pc != NULL) and
 * cl_mean_px_ per lane, the same values for any input: |v| and |mv| as vabsq_s16 (-2^15 stays
 * 2^15 as uint16, the plain form's two's complement), the counter's min(p + 256, pcap) with a
 * saturating add (p > pcap - 256 exactly when p + 256 > pcap, also where the add saturates) and
 * max(p - 128, 0) as a saturating subtraction; t = min((|c|^2 + 32) >> 6, 65535) as a
 * saturating rounding narrowing shift of the 32-bit square (|c| < 2^16: no overflow; below 2048
 * the plain form's hi 2^10 + (lo >> 6) + bit 5 of lo, above it its clamp); |t - m| and
 * |tv - mv| (mod 2^16) as absolute differences; c + 2^16 (0 at a masked pixel) as the two
 * 16-bit halves c16 and [c >= 0] stored interleaved (little-endian). */
static void cl_mean8_neon_(int16_t *o, uint16_t *mrow, uint16_t *mu, uint16_t *pc, uint32_t *cs,
                           int32_t x0, int32_t n, uint16_t a16, bool full, uint16_t exc, uint16_t pk,
                           uint16_t pcap, uint16_t mfl)
{
    const uint16x8_t va = vdupq_n_u16(a16), vmfl = vdupq_n_u16(mfl);
    const uint16x8_t vexc = vdupq_n_u16(exc), vpk = vdupq_n_u16(pk), vpcap = vdupq_n_u16(pcap);
    const uint16x8_t one = vdupq_n_u16(1u), rmax = vdupq_n_u16((uint16_t)PFT_PRE_RMAX_);
    const int16x8_t vmask = vdupq_n_s16((int16_t)PFT_RES16_MASKED);
    const int16x8_t lim = vdupq_n_s16(2048), nlim = vdupq_n_s16(-2048);
    for (int32_t i = 0; i < n; ++i) {
        const int32_t x = x0 + 8 * i;
        const int16x8_t v = vld1q_s16(o + x);
        const uint16x8_t msk = vceqq_s16(v, vmask);
        uint16x8_t learn = vdupq_n_u16(0xFFFFu);
        if (pc != NULL) {
            const uint16x8_t av = vreinterpretq_u16_s16(vabsq_s16(v));
            const uint16x8_t p0 = vld1q_u16(pc + x);
            const uint16x8_t pu = vminq_u16(vqaddq_u16(p0, vdupq_n_u16(256u)), vpcap);
            const uint16x8_t pd = vqsubq_u16(p0, vdupq_n_u16(128u));
            const uint16x8_t ex = vcgtq_u16(av, vexc);
            const uint16x8_t p1 = vbslq_u16(ex, pu, pd);
            vst1q_u16(pc + x, vbslq_u16(msk, p0, p1));
            learn = vorrq_u16(vmvnq_u16(ex), vcgeq_u16(p1, vpk));
        }
        const uint16x8_t mu0 = vld1q_u16(mu + x);
        const int16x8_t mv = vreinterpretq_s16_u16(veorq_u16(mu0, vdupq_n_u16((uint16_t)CL_MUOFF_)));
        const uint16x8_t mvn = vcltzq_s16(mv);
        const uint16x8_t amv = vreinterpretq_u16_s16(vabsq_s16(mv));
        const uint16x8_t dr = vshrq_n_u16(vaddq_u16(amv, vdupq_n_u16(4u)), 3);
        const uint16x8_t dm = vandq_u16(dr, vcgtq_u16(dr, vmfl));
        const int16x8_t sdm = vreinterpretq_s16_u16(vsubq_u16(veorq_u16(dm, mvn), mvn));
        const uint16x8_t cn = vcltq_s16(v, sdm);
        const uint16x8_t c16 = vreinterpretq_u16_s16(vsubq_s16(v, sdm));
        const uint16x8_t ac = vsubq_u16(veorq_u16(c16, cn), cn);
        const uint32x4_t sqlo = vmull_u16(vget_low_u16(ac), vget_low_u16(ac));
        const uint32x4_t sqhi = vmull_high_u16(ac, ac);
        const uint16x8_t t = vqrshrn_high_n_u32(vqrshrn_n_u32(sqlo, 6), sqhi, 6);
        const uint16x8_t m0 = vld1q_u16(mrow + x);
        const uint16x8_t neg = vcltq_u16(t, m0);
        const uint16x8_t q = cl_scale8_neon_(vabdq_u16(t, m0), va, full);
        const uint16x8_t nm = vaddq_u16(m0, vsubq_u16(veorq_u16(q, neg), neg));
        vst1q_u16(mrow + x, vbslq_u16(msk, m0, nm));
        const int16x8_t tv = vshlq_n_s16(vmaxq_s16(vminq_s16(v, lim), nlim), 3);
        const uint16x8_t ne = vcltq_s16(tv, mv);
        const uint16x8_t qe = cl_scale8_neon_(vreinterpretq_u16_s16(vabdq_s16(tv, mv)), va, full);
        const uint16x8_t nmu = vaddq_u16(mu0, vsubq_u16(veorq_u16(qe, ne), ne));
        vst1q_u16(mu + x, vbslq_u16(vornq_u16(msk, learn), mu0, nmu));
        const uint16x8_t acl = vminq_u16(ac, rmax);
        const uint16x8_t oc = vsubq_u16(veorq_u16(acl, cn), cn);
        vst1q_s16(o + x, vreinterpretq_s16_u16(vbslq_u16(msk, vreinterpretq_u16_s16(vmask), oc)));
        uint16x8x2_t cw;
        cw.val[0] = vbicq_u16(c16, msk);
        cw.val[1] = vbicq_u16(vaddq_u16(cn, one), msk);
        vst2q_u16((uint16_t *)(void *)(cs + x), cw);
    }
}
#endif

/* Columns x0..x1-1 of cl_row_mean_'s gate (pc, persist) and mean pass with one floor mfl for
 * all of them (a constant, so that the loops vectorise). */
static inline void cl_mean_span_(int16_t *o, uint16_t *mrow, uint16_t *mu, uint16_t *pc, uint32_t *cs,
                                 int32_t x0, int32_t x1, uint16_t a16, uint16_t full, uint32_t exc,
                                 uint32_t pk, uint32_t pcap, int32_t mfl)
{
    const uint16_t f16 = (uint16_t)mfl; /* 0..CL_FLOORMAX_ */
#ifdef CL_NEON_
    /* whole blocks of 8 columns in NEON's forms, the columns left over below */
    const int32_t n8 = (x1 - x0) / 8;
    cl_mean8_neon_(o, mrow, mu, pc, cs, x0, n8, a16, full != 0u, (uint16_t)exc, (uint16_t)pk,
                   (uint16_t)pcap, f16);
    const int32_t xs = x0 + 8 * n8;
#else
    const int32_t xs = x0;
#endif
    /* exc 1..32767, pk = persist * 256 in 256..PFT_PRE_CLUTTER_MAX_PERSIST * 256 = 2^13
     * (the config check), pcap = 2 pk <= 2^14 (without persist pk = pcap = 0, not read) */
    const uint16_t e16 = (uint16_t)exc, k16 = (uint16_t)pk, c16 = (uint16_t)pcap;
    const uint16_t plim = (uint16_t)(c16 - 256u);
    /* one loop, the gate per pixel where pc is set: one call of each pixel function, so that a
     * compiler inlines it also where it optimises for size (the Cortex-M presets' -Os) */
    for (int32_t x = xs; x < x1; ++x) {
        uint16_t learn = 1u;
        if (pc != NULL) {
            cl_gate_px_(o[x], &pc[x], e16, k16, c16, plim, &learn);
        }
        cl_mean_px_(&o[x], learn, a16, full, f16, &mrow[x], &mu[x], &cs[x]);
    }
}
#endif

/* floor_age: the end of the run of columns from x0 on whose ages ca lie on the same side of ka
 * (>= ka: old) as ca[x0]. An old run is passed 4 columns at a time while none of the 4 ages is
 * below ka, tested on the 4 bytes as one 32-bit word: (q - 0x01010101 ka) & ~q & 0x80808080 is
 * nonzero exactly when some byte of q is below ka, for 1 <= ka <= 128 (a byte below ka borrows
 * into its own top bit, not set in q; the lowest such byte is exact, a borrow can only mark
 * bytes above it); the rest per column. The same run ends as the per-column scan. */
static int32_t cl_age_run_end_(const uint8_t *ca, int32_t x0, int32_t w, uint8_t ka, bool old)
{
    int32_t x1 = x0 + 1;
    if (old && ka <= 128u) {
        const uint32_t kk = 0x01010101u * (uint32_t)ka;
        while (x1 <= w - 4) {
            uint32_t q;
            memcpy(&q, ca + x1, 4u);
            if (((q - kk) & ~q & 0x80808080u) != 0u) {
                break; /* some age of the 4 is below ka */
            }
            x1 += 4;
        }
    }
    while (x1 < w && (ca[x1] >= ka) == old) {
        ++x1;
    }
    return x1;
}

/* Row y with the running mean (mean; the gate with persist): the per-pixel formulas of
 * pft_pre.h (docs/algorithms.md 9.9) in plain passes over the output row o, a copy of the
 * residual (or r's own buffer, inplace; each pass reads and writes o at the same column
 * only). With persist, a first pass updates the counter and keeps the learn flags in cs. The
 * mean pass reads the residual, updates the map and the mean, keeps c = r - mu (before mu's
 * update) in cs as c + 2^16 (0: a masked pixel) and writes the output before scoring (the
 * mask, or c clamped) over the residual; the last pass scores, in chunks of 32 columns, the
 * pixels whose read exceeds thr. Ranges: mu - 2^15 in [-2^14, 2^14] (a mean of values clamped
 * there), so |c| <= 2^15 + 2^11 and c^2 < 2^31; t and m in 0..65535 and a <= 2^16, so
 * a |t - m| + 2^15 < 2^32 and m + -q lies between m and t (q <= |t - m|), likewise the mean's
 * step (|tv - mv| <= 2^15); the cl_scale_ and cl_div_ roundings written out. */
static void cl_row_mean_(const int16_t *r, int16_t *o, uint16_t *mrow, uint16_t *mu, uint16_t *pc,
                         uint32_t *cs, const uint32_t *hs, int32_t w, uint32_t a, uint32_t thr,
                         uint32_t veto, uint32_t area, uint32_t exc, uint32_t pk, uint32_t pcap, int32_t mfl,
                         const uint8_t *ca, uint8_t ka)
{
    const uint16_t a16 = (uint16_t)(a > 65535u ? 65535u : a), full = (uint16_t)(a > 65535u ? 1u : 0u);
    /* the passes read and write o at the same column only (o may be r, inplace) */
    if (o != r) {
        memcpy(o, r, (size_t)w * 2u);
    }
    if (ca == NULL) {
        cl_mean_span_(o, mrow, mu, pc, cs, 0, w, a16, full, exc, pk, pcap, mfl);
    } else {
        /* floor_age: runs of columns on the same side of ka, each with its floor constant */
        int32_t x0 = 0;
        while (x0 < w) {
            const bool old = ca[x0] >= ka;
            const int32_t x1 = cl_age_run_end_(ca, x0, w, ka, old);
            cl_mean_span_(o, mrow, mu, pc, cs, x0, x1, a16, full, exc, pk, pcap, old ? mfl : 0);
            x0 = x1;
        }
    }
    const int32_t sthr = (int32_t)thr;
    for (int32_t x0 = 0; x0 < w; x0 += 32) {
        const int32_t x1 = w - x0 >= 32 ? x0 + 32 : w;
        const int32_t any = cl_chunk_any_(hs, sthr, x0, x1);
        for (int32_t x = x0; any < 0 && x < x1; ++x) {
            if (hs[x] > thr && cs[x] != 0u) {
                const int32_t cv = (int32_t)cs[x] - 65536;
                const uint32_t mm = (hs[x] + area / 2u) / area; /* the square's mean, Q6.10 */
                const uint32_t s = pft_pre_sqrt_q10_(mm);         /* sqrt(M) in Q10 */
                o[x] = hs[x] > veto ? (int16_t)0 : (int16_t)pft_pre_rclamp_(cl_div_(cv * 1024, (int32_t)s));
            }
        }
    }
}

/* The map on blocks (cfg.block): block row j (rows j B .. j B + B - 1 of the frame, B =
 * 2^lb) is read once over the block grid (cl_read_row_), every pixel of it is scored with its
 * block's read, then each block of the row is updated with the means over its unmasked pixels
 * of this frame's terms (t = min(c^2, 64), the mean's clamp(r, -8, 8), the gate's r): the
 * formulas of the per-pixel map with the pixel's terms replaced by their block means. A block
 * without an unmasked pixel keeps its values. Each residual row is read before its output row
 * is written (inplace). */
static void cl_update_blocks_(pft_pre_clutter_t *c, const pft_frame_t *res, uint32_t a,
                              uint32_t thr, uint32_t veto, uint32_t area)
{
    const int32_t w = (int32_t)c->cfg.width, h = (int32_t)c->cfg.height;
    const int32_t gw = (int32_t)c->gw, gh = (int32_t)c->gh;
    const uint32_t lb = c->lb, nring = (uint32_t)c->cfg.blur + 1u;
    const uint32_t rs = res->stride_bytes / 2u;
    const uint32_t pk = (uint32_t)c->cfg.persist * 256u, pcap = 2u * pk;
    const uint32_t exc = c->cfg.excess;
    uint32_t *st = c->acc, *sn = c->acc + gw;       /* sum of t (<= 16 * 65535), count */
    int32_t *smu = c->sacc, *sv = c->sacc + gw;     /* sum of clamp(8 r) (Q4.11), sum of r (Q8.8) */
    uint32_t *sc = c->vs;                           /* per block: 0 plain, UINT32_MAX veto, else sqrt(M) Q10 */
    for (int32_t j = 0; j < gh; ++j) {
        uint16_t *mrow = c->m + (size_t)j * (size_t)gw;
        memcpy(c->ring + (size_t)((uint32_t)j % nring) * (size_t)gw, mrow, (size_t)gw * 2u);
        cl_read_row_(c, j);
        for (int32_t i = 0; i < gw; ++i) {
            const uint32_t mb = c->hs[i];
            if (mb > thr) {
                const uint32_t mm = (mb + area / 2u) / area; /* the square's mean, Q6.10 */
                sc[i] = mb > veto ? UINT32_MAX : pft_pre_sqrt_q10_(mm);
            } else {
                sc[i] = 0u;
            }
        }
        memset(st, 0, (size_t)gw * 8u);
        memset(smu, 0, (size_t)gw * 8u);
        uint16_t *mu = c->mu != NULL ? c->mu + (size_t)j * (size_t)gw : NULL;
        uint16_t *pc = c->pc != NULL ? c->pc + (size_t)j * (size_t)gw : NULL;
        const uint32_t y0 = (uint32_t)j << lb;
        uint32_t y1 = y0 + (1u << lb) < (uint32_t)h ? y0 + (1u << lb) : (uint32_t)h;
        if (mu == NULL) {
            /* without the mean (c = r): plain passes per row, the same values: the block sums
             * of t first (they read r), then the output (r itself where the block's read is
             * not above thr, which may be r's own buffer, inplace) */
            uint32_t any = 0u;
            for (int32_t i = 0; i < gw; ++i) {
                any |= sc[i];
            }
            for (uint32_t y = y0; y < y1; ++y) {
                const int16_t *r = (const int16_t *)res->data + (size_t)y * rs;
                int16_t *o = c->out + (size_t)y * (size_t)w;
                for (int32_t x = 0; x < w; ++x) {
                    const int32_t v = r[x];
                    const uint32_t ac = (uint32_t)(v < 0 ? -v : v); /* <= 2^15 */
                    const uint32_t t0 = (ac * ac + 32u) >> 6;       /* >= 65536 where sq >= CL_SQMAX_ */
                    uint32_t in = 1u; /* whether the pixel enters its block's sums */
                    if (v == PFT_RES16_MASKED) {
                        in = 0u;
                    }
                    const uint32_t i = (uint32_t)x >> lb;
                    st[i] += in * (t0 > CL_MMAX_ ? CL_MMAX_ : t0);
                    sn[i] += in;
                }
                if (o != r) {
                    memcpy(o, r, (size_t)w * 2u);
                }
                for (int32_t x = 0; any != 0u && x < w; ++x) {
                    const int32_t v = o[x]; /* r[x] */
                    const uint32_t sv_ = sc[(uint32_t)x >> lb];
                    if (sv_ != 0u && v != PFT_RES16_MASKED) {
                        o[x] = sv_ == UINT32_MAX ? (int16_t)0 : (int16_t)pft_pre_rclamp_(cl_div_(v * 1024, (int32_t)sv_));
                    }
                }
            }
            y1 = y0; /* the rows are done */
        }
        for (uint32_t y = y0; y < y1; ++y) {
            const int16_t *r = (const int16_t *)res->data + (size_t)y * rs;
            int16_t *o = c->out + (size_t)y * (size_t)w;
            for (int32_t x = 0; x < w; ++x) {
                const int32_t v = r[x];
                if (v == PFT_RES16_MASKED) {
                    o[x] = PFT_RES16_MASKED;
                    continue;
                }
                const uint32_t i = (uint32_t)x >> lb;
                const int32_t cv = mu != NULL ? v - cl_div_((int32_t)mu[i] - (int32_t)CL_MUOFF_, 8) : v;
                const uint32_t s = sc[i];
                const int32_t wv = s == 0u ? cv : (s == UINT32_MAX ? 0 : cl_div_(cv * 1024, (int32_t)s));
                o[x] = (int16_t)pft_pre_rclamp_(wv);
                const uint32_t ac = (uint32_t)(cv < 0 ? -cv : cv);
                const uint64_t sq = (uint64_t)ac * ac;
                st[i] += sq >= CL_SQMAX_ ? CL_MMAX_ : (uint32_t)((sq + 32u) >> 6);
                sn[i] += 1u;
                if (mu != NULL) {
                    smu[i] += v * 8 > CL_MUMAX_ ? CL_MUMAX_ : (v * 8 < -CL_MUMAX_ ? -CL_MUMAX_ : v * 8);
                    sv[i] += v;
                }
            }
        }
        for (int32_t i = 0; i < gw; ++i) {
            const uint32_t n = sn[i];
            if (n == 0u) {
                continue; /* every pixel of the block masked: its values kept */
            }
            const uint32_t t = (st[i] + n / 2u) / n;
            const int32_t nm = (int32_t)mrow[i] + cl_scale_(a, (int32_t)t - (int32_t)mrow[i]);
            mrow[i] = (uint16_t)(nm < 0 ? 0 : (nm > (int32_t)CL_MMAX_ ? (int32_t)CL_MMAX_ : nm));
            if (mu == NULL) {
                continue;
            }
            bool learn = true;
            if (pc != NULL) {
                const int32_t rb = cl_div_(sv[i], (int32_t)n); /* the block's mean r, Q8.8 */
                const uint32_t av = (uint32_t)(rb < 0 ? -rb : rb);
                const uint32_t p0 = pc[i];
                const uint32_t p1 = av > exc ? (p0 + 256u > pcap ? pcap : p0 + 256u)
                                             : (p0 > 128u ? p0 - 128u : 0u);
                pc[i] = (uint16_t)p1;
                learn = av <= exc || p1 >= pk;
            }
            if (learn) {
                const int32_t tv = cl_div_(smu[i], (int32_t)n);
                const int32_t mv = (int32_t)mu[i] - (int32_t)CL_MUOFF_;
                mu[i] = (uint16_t)(mv + cl_scale_(a, tv - mv) + (int32_t)CL_MUOFF_);
            }
        }
    }
}

/* PFT_OK or PFT_ERR_FORMAT: whether res is a residual frame of the configured size. */
static pft_status_t cl_check_frame_(const pft_pre_clutter_t *c, const pft_frame_t *res)
{
    if (res->format != PFT_PIX_RES16 || res->width != c->cfg.width ||
        res->height != c->cfg.height || res->stride_bytes < 2u * (uint32_t)c->cfg.width ||
        (res->stride_bytes & 1u) != 0u) {
        return PFT_ERR_FORMAT;
    }
    return PFT_OK;
}

/* map8, before row y's update: the ring made to hold the rows y - blur .. y + blur as they are
 * before this frame's update (cl_row_): without a shift (rows ascending) row y + blur decoded
 * into it (rows 0 .. blur - 1 as well before row 0); with a shift (fz->on) the rows warped
 * into it up to y - blur (descending) or y + blur (ascending), clamped to the frame (the rows
 * beyond it read the edge row, cl_row_). Row y's copied into c->row, where the 16-bit row
 * functions update it. */
static uint16_t *cl_row8_begin_(pft_pre_clutter_t *c, cl_fuse8_t *fz, int32_t y)
{
    const int32_t w = (int32_t)c->gw, h = (int32_t)c->gh, b = (int32_t)c->cfg.blur;
    const uint32_t nring = 2u * (uint32_t)b + 1u;
    if (fz->on) {
        const int32_t last = fz->down ? (y - b < 0 ? 0 : y - b) : (y + b >= h ? h - 1 : y + b);
        /* each row is warped once: at most h rows over the frame */
        for (int32_t k = 0; k < h && (fz->down ? fz->next >= last : fz->next <= last); ++k) {
            cl_fuse8_row_(c, fz);
        }
    } else {
        for (int32_t r = y == 0 ? 0 : y + b; r <= y + b && r < h; ++r) {
            cl_dec8_row_(c->m8 + (size_t)r * (size_t)w, c->ring + (size_t)((uint32_t)r % nring) * (size_t)w, w);
        }
    }
    memcpy(c->row, c->ring + (size_t)((uint32_t)y % nring) * (size_t)w, (size_t)w * 2u);
    return c->row;
}

/* map8, after row y's update: c->row stored as codes with the dither: the rounding offset of
 * column x is (o + 167 x) mod 256 (167 odd: a permutation of 0..255 over 256 columns), o a
 * hash of the row and the frame count, so a pixel's offset is drawn anew every frame. A masked
 * pixel's value is its code's own, which every offset gives back. */
static void cl_row8_end_(pft_pre_clutter_t *c, int32_t y)
{
    const int32_t w = (int32_t)c->gw;
    uint32_t z = ((uint32_t)y * 0x85EBCA77u) ^ (c->frames * 0xC2B2AE3Du);
    z ^= z >> 15;
    z *= 0x2C1B3C6Du;
    z ^= z >> 13;
    const uint32_t o = z >> 24;
    const uint16_t *v = c->row;
    uint8_t *m8 = c->m8 + (size_t)y * (size_t)w;
    /* the offset as a 16-bit running sum: cl_enc8_ reads dz's low 8 bits only, which are
     * (o + 167 x) mod 256 */
    uint16_t dz = (uint16_t)o;
    for (int32_t x = 0; x < w; ++x) {
        m8[x] = cl_enc8_(v[x], dz);
        dz = (uint16_t)(dz + 167u);
    }
}

/* anchor: a Q16.16 position rounded to the nearest integer, halves upwards (floor((a + 2^15) /
 * 2^16); |a| < 2^62: the sum of fewer than 2^31 shifts of int32). */
static int64_t cl_round16_(int64_t a)
{
    const int64_t t = a + 32768;
    return t / 65536 - (t % 65536 < 0 ? 1 : 0);
}

/* anchor: the w x h array of es-byte values (es 1 or 2) at base moved by (dx, dy) whole
 * pixels, out(x, y) = v(x - dx, y - dy), fill where the source is outside (|dx| <= w, |dy| <=
 * h). Rows are visited in the order that reads every source row before it is overwritten
 * (descending for dy > 0); a row's values are moved by one memmove, the entering columns and
 * rows filled. */
static void cl_move_(uint8_t *base, size_t es, int32_t w, int32_t h, int32_t dx, int32_t dy,
                     uint16_t fill)
{
    const size_t rb = (size_t)w * es;
    const int32_t adx = dx < 0 ? -dx : dx;
    uint8_t fb[2];
    memcpy(fb, &fill, sizeof fb); /* the fill's bytes in memory order (es 1: its low byte) */
    if (es == 1u) {
        fb[0] = (uint8_t)fill;
    }
    for (int32_t k = 0; k < h; ++k) {
        const int32_t y = dy > 0 ? h - 1 - k : k;
        const int32_t sy = y - dy;
        uint8_t *dst = base + (size_t)y * rb;
        int32_t f0 = 0, f1 = w; /* the columns to fill: [f0, f1) */
        if (sy >= 0 && sy < h) {
            const uint8_t *src = base + (size_t)sy * rb;
            if (adx < w) {
                memmove(dst + (size_t)(dx > 0 ? dx : 0) * es, src + (size_t)(dx < 0 ? -dx : 0) * es,
                        (size_t)(w - adx) * es);
            }
            /* a move of the whole width or more fills the row (clamped: never outside it) */
            f0 = dx > 0 ? 0 : (adx < w ? w - adx : 0);
            f1 = dx > 0 ? (adx < w ? dx : w) : w;
        }
        if (es == 1u && f1 > f0) {
            memset(dst + f0, (int)fb[0], (size_t)(f1 - f0));
        } else {
            for (int32_t x = f0; x < f1; ++x) {
                memcpy(dst + (size_t)x * es, fb, es);
            }
        }
    }
}

/* floor_age, the bilinear carry of one axis's n ages by i + f / 256 px (cl_warp_'s sources):
 * out(x) = the younger of a(x - i) and, with f > 0, a(x - i - 1), a source outside 0 (it
 * enters). In place: descending for i >= 0 (both sources at or below x), else ascending (both
 * at or above x). */
static void cl_age_carry_(uint8_t *a, int32_t n, int32_t i, uint32_t f)
{
    for (int32_t k = 0; k < n; ++k) {
        const int32_t x = i >= 0 ? n - 1 - k : k;
        const int32_t s1 = x - i, s0 = s1 - 1;
        const uint8_t a1 = s1 >= 0 && s1 < n ? a[s1] : 0u;
        const uint8_t a0 = f == 0u ? a1 : (s0 >= 0 && s0 < n ? a[s0] : 0u);
        a[x] = a0 < a1 ? a0 : a1;
    }
}

/* floor_age, after an update with evidence: every column and row one frame older (capped). */
static void cl_age_step_(uint8_t *a, size_t n, uint8_t cap)
{
    for (size_t x = 0u; x < n; ++x) {
        a[x] = a[x] < cap ? (uint8_t)(a[x] + 1u) : cap;
    }
}

/* anchor, at an update with evidence: the arrays moved to the rounded position of the summed
 * shifts (set without a move at the first frame, when every cell holds the reset's values). */
static void cl_anchor_(pft_pre_clutter_t *c)
{
    const int64_t nx = cl_round16_(c->ax), ny = cl_round16_(c->ay);
    const int32_t w = (int32_t)c->gw, h = (int32_t)c->gh;
    if (c->frames > 0u && (nx != c->px || ny != c->py)) {
        const int64_t ex = nx - c->px, ey = ny - c->py;
        /* beyond the frame, every cell enters */
        const int32_t dx = (int32_t)(ex > w ? w : (ex < -w ? -w : ex));
        const int32_t dy = (int32_t)(ey > h ? h : (ey < -h ? -h : ey));
        if (c->m8 != NULL) {
            cl_move_(c->m8, 1u, w, h, dx, dy, (uint16_t)CL_ONE8_);
        } else {
            cl_move_((uint8_t *)c->m, 2u, w, h, dx, dy, (uint16_t)CL_ONE_);
        }
        if (c->mu != NULL) {
            cl_move_((uint8_t *)c->mu, 2u, w, h, dx, dy, (uint16_t)CL_MUOFF_);
        }
        if (c->pc != NULL) {
            cl_move_((uint8_t *)c->pc, 2u, w, h, dx, dy, 0u);
        }
        if (c->age != NULL) {
            /* the columns' ages as one row moved by dx, the rows' by dy; those that enter at 0 */
            cl_move_(c->age, 1u, w, 1, dx, 0, 0u);
            cl_move_(c->age + w, 1u, h, 1, dy, 0, 0u);
        }
    }
    c->px = nx;
    c->py = ny;
}

/* One accepted frame; the output goes to c->out (packed rows), which is the residual's own
 * buffer with inplace: each residual row is read before its output row is written, and not
 * after. */
static void cl_update_(pft_pre_clutter_t *c, const pft_frame_t *res, int32_t shift_x,
                       int32_t shift_y, bool evidence)
{
    const int32_t w = (int32_t)c->cfg.width, h = (int32_t)c->cfg.height;
    const size_t npix = (size_t)w * (size_t)h;
    c->updates++;
    c->seq = res->seq;
    c->timestamp_us = res->timestamp_us;
    if (c->cfg.anchor) {
        c->ax += shift_x; /* the scene's position moves with or without evidence */
        c->ay += shift_y;
    }
    if (!evidence) {
        for (size_t i = 0u; i < npix; ++i) {
            c->out[i] = PFT_RES16_MASKED;
        }
        return;
    }
    cl_fuse8_t fz; /* map8 with a shift: the warp runs within the row loop below */
    memset(&fz, 0, sizeof(fz));
    if (c->cfg.anchor) {
        cl_anchor_(c); /* whole pixels only: no carry warp */
    } else if (c->frames > 0u) {
        int32_t ix, iy;
        uint32_t fx, fy;
        const int32_t gw = (int32_t)c->gw, gh = (int32_t)c->gh;
        cl_split_(shift_x, c->lb, &ix, &fx);
        cl_split_(shift_y, c->lb, &iy, &fy);
        if (ix != 0 || iy != 0 || fx != 0u || fy != 0u) {
            /* beyond the frame, every pixel enters: the warp's indices stay in range */
            ix = ix > gw ? gw : (ix < -gw ? -gw : ix);
            iy = iy > gh ? gh : (iy < -gh ? -gh : iy);
            if (c->m8 != NULL) {
                cl_fuse8_init_(c, &fz, ix, fx, iy, fy);
            } else {
                cl_warp_(c->m, c->vs, c->hs, gw, gh, ix, fx, iy, fy, CL_ONE_);
            }
            if (c->mu != NULL) {
                cl_warp_(c->mu, c->vs, c->hs, gw, gh, ix, fx, iy, fy, CL_MUOFF_);
            }
            if (c->pc != NULL) {
                cl_warp_(c->pc, c->vs, c->hs, gw, gh, ix, fx, iy, fy, 0u);
            }
            if (c->age != NULL) {
                cl_age_carry_(c->age, gw, ix, fx);
                cl_age_carry_(c->age + gw, gh, iy, fy);
            }
        }
    } else {
        /* the first frame with evidence: nothing to carry */
    }
    c->frames++;
    const uint32_t a1 = (65536u + c->frames / 2u) / c->frames;
    const uint32_t a = a1 > c->cfg.alpha ? a1 : c->cfg.alpha;
    const uint32_t rs = res->stride_bytes / 2u;
    const uint32_t nring = (uint32_t)c->cfg.blur + 1u;
    const uint32_t area = c->cfg.box ? (2u * nring - 1u) * (2u * nring - 1u) : 1u;
    const uint32_t thr = (uint32_t)c->cfg.thr * area; /* on the square's sum (box) */
    const uint32_t veto = c->cfg.veto != 0u ? (uint32_t)c->cfg.veto * area : UINT32_MAX;
    /* persistence gate: the counter in frames Q8, its cap 2 k and its opening level k */
    const uint32_t pk = (uint32_t)c->cfg.persist * 256u, pcap = 2u * pk;
    const uint32_t exc = c->cfg.excess;
    if (c->lb != 0u) {
        cl_update_blocks_(c, res, a, thr, veto, area);
        return;
    }
    for (int32_t k = 0; k < h; ++k) {
        /* rows ascending, but in the warp's order with map8 and a shift (descending when iy >= 0) */
        const int32_t y = fz.down ? h - 1 - k : k;
        /* map8: the decoded row, stored back after the update (cl_row8_begin_, cl_row8_end_) */
        uint16_t *mrow = c->m8 != NULL ? cl_row8_begin_(c, &fz, y) : c->m + (size_t)y * (size_t)w;
        if (c->m8 == NULL) {
            memcpy(c->ring + (size_t)((uint32_t)y % nring) * (size_t)w, mrow, (size_t)w * 2u);
        }
        cl_read_row_(c, y);
        const int16_t *r = (const int16_t *)res->data + (size_t)y * rs;
        int16_t *o = c->out + (size_t)y * (size_t)w;
        uint16_t *mu = c->mu != NULL ? c->mu + (size_t)y * (size_t)w : NULL;
        uint16_t *pc = c->pc != NULL ? c->pc + (size_t)y * (size_t)w : NULL;
        if (mu == NULL) {
            /* without the mean there is no counter (persist needs mean) */
            cl_row_plain_(r, o, mrow, c->hs, w, a, thr, veto, area);
        } else {
            /* the vertical sums c->vs are spent: they keep c */
            /* floor_age: a young row takes no floor; an old one reads its columns' ages */
            const uint8_t ka = c->cfg.floor_age;
            const bool rold = c->age == NULL || c->age[(size_t)w + (size_t)y] >= ka;
            cl_row_mean_(r, o, mrow, mu, pc, c->vs, c->hs, w, a, thr, veto, area, exc, pk, pcap,
                         rold ? (int32_t)c->cfg.mean_floor : 0, rold ? c->age : NULL, ka);
        }
        if (c->m8 != NULL) {
            cl_row8_end_(c, y);
        }
    }
    if (c->age != NULL) {
        cl_age_step_(c->age, (size_t)w + (size_t)h, c->cfg.floor_age);
    }
}

pft_status_t pft_pre_clutter_update(pft_pre_clutter_t *c, const pft_frame_t *res,
                                    int32_t shift_x, int32_t shift_y, bool evidence)
{
    if (!cl_ready_(c) || res == NULL || res->data == NULL) {
        return PFT_ERR_INVAL;
    }
    if (c->cfg.inplace) {
        return PFT_ERR_STATE; /* pft_pre_clutter_update_inplace: the output has no buffer here */
    }
    const pft_status_t s = cl_check_frame_(c, res);
    if (s != PFT_OK) {
        return s;
    }
    cl_update_(c, res, shift_x, shift_y, evidence);
    return PFT_OK;
}

pft_status_t pft_pre_clutter_update_inplace(pft_pre_clutter_t *c, const pft_frame_t *res,
                                            int16_t *pixels, int32_t shift_x, int32_t shift_y,
                                            bool evidence)
{
    if (!cl_ready_(c) || res == NULL || pixels == NULL) {
        return PFT_ERR_INVAL;
    }
    if (!c->cfg.inplace) {
        return PFT_ERR_STATE;
    }
    if (res->data != (const void *)pixels) {
        return PFT_ERR_INVAL;
    }
    const pft_status_t s = cl_check_frame_(c, res);
    if (s != PFT_OK) {
        return s;
    }
    if (res->stride_bytes != 2u * (uint32_t)res->width) {
        return PFT_ERR_FORMAT; /* the output's rows are packed */
    }
    /* every check is above: from here the residual becomes the output, row by row */
    c->out = pixels;
    cl_update_(c, res, shift_x, shift_y, evidence);
    return PFT_OK;
}

pft_status_t pft_pre_clutter_frame(const pft_pre_clutter_t *c, pft_frame_t *out)
{
    if (c == NULL || out == NULL) {
        return PFT_ERR_INVAL;
    }
    if (c->updates == 0u) {
        return PFT_ERR_STATE;
    }
    memset(out, 0, sizeof(*out));
    out->data = c->out;
    out->width = c->cfg.width;
    out->height = c->cfg.height;
    out->stride_bytes = 2u * (uint32_t)c->cfg.width;
    out->format = PFT_PIX_RES16;
    out->bit_depth = 16u;
    out->timestamp_us = c->timestamp_us;
    out->seq = c->seq;
    return PFT_OK;
}

pft_status_t pft_pre_clutter_raise(pft_pre_clutter_t *c, uint32_t x, uint32_t y, uint16_t level)
{
    if (!cl_ready_(c) || x >= c->cfg.width || y >= c->cfg.height) {
        return PFT_ERR_INVAL;
    }
    const uint32_t w = c->cfg.width, h = c->cfg.height, lb = c->lb;
    const uint32_t y0 = y > 0u ? y - 1u : 0u, y1 = y + 1u < h ? y + 1u : h - 1u;
    const uint32_t x0 = x > 0u ? x - 1u : 0u, x1 = x + 1u < w ? x + 1u : w - 1u;
    if (c->m8 != NULL) {
        /* per pixel: the smallest code at or above level (the largest, 63 sigma^2, above it) */
        uint32_t lc = pft_pre_clutter_enc8_(level, CL_HALF8_);
        lc = pft_pre_clutter_dec8_(lc) < (uint32_t)level && lc < 255u ? lc + 1u : lc;
        for (uint32_t yy = y0; yy <= y1; ++yy) {
            for (uint32_t xx = x0; xx <= x1; ++xx) {
                uint8_t *m8 = &c->m8[(size_t)yy * w + xx];
                *m8 = *m8 < lc ? (uint8_t)lc : *m8;
            }
        }
        return PFT_OK;
    }
    /* the entries of the map that hold those pixels (blocks: each once) */
    for (uint32_t yy = y0 >> lb; yy <= y1 >> lb; ++yy) {
        for (uint32_t xx = x0 >> lb; xx <= x1 >> lb; ++xx) {
            uint16_t *m = &c->m[(size_t)yy * c->gw + xx];
            *m = *m < level ? level : *m;
        }
    }
    return PFT_OK;
}

uint32_t pft_pre_clutter_at(const pft_pre_clutter_t *c, uint32_t x, uint32_t y)
{
    if (!cl_ready_(c) || x >= c->cfg.width || y >= c->cfg.height) {
        return 0u;
    }
    if (c->m8 != NULL) {
        return pft_pre_clutter_dec8_(c->m8[(size_t)y * c->gw + x]);
    }
    return c->m[(size_t)(y >> c->lb) * c->gw + (x >> c->lb)];
}
