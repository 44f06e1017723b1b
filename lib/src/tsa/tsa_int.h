/* Internals shared by the tsa sources (private, not installed): integer square roots, reals as
 * Q16.16 integers, the channel layout of the accepted pixel formats, bounding boxes. */
#ifndef PFT_TSA_INT_H
#define PFT_TSA_INT_H

#include "pft/pft_tsa.h"

/* The pixel formats the appearance model reads. */
#define PFT_TSA_FMT_MASK_ \
    (PFT_FMT_BIT(PFT_PIX_U8) | PFT_FMT_BIT(PFT_PIX_RGB888) | PFT_FMT_BIT(PFT_PIX_BGR888))

/* floor(sqrt(v)), bit by bit (32 rounds). */
static inline uint32_t pft_tsa_isqrt64_(uint64_t v)
{
    uint64_t r = 0u;
    uint64_t bit = (uint64_t)1u << 62;
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
    return (uint32_t)r;
}

/* floor(sqrt(v)), bit by bit (16 rounds). */
static inline uint32_t pft_tsa_isqrt32_(uint32_t v)
{
    uint32_t r = 0u;
    uint32_t bit = (uint32_t)1u << 30;
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
    return r;
}

/* a in Q16.16 units as an integer, rounded to nearest with ties away from zero and saturated
 * to +-INT32_MAX: the identity in the q16 build, round(65536 a) in the float build. Built from
 * the integer part and two 8-bit steps of the fraction, so no intermediate leaves the Q16.16
 * range in either build. */
static inline int32_t pft_tsa_q16_(pft_real_t a)
{
    const pft_real_t m = pft_abs(a);
    /* the top of the Q16.16 range: PFT_REAL_MAX in q16 (so only PFT_REAL_MAX itself saturates,
     * to itself), 32768 in float */
    if (!(m < pft_ratio(INT32_MAX, 65536))) {
        return a < 0 ? -INT32_MAX : INT32_MAX;
    }
    const int32_t whole = pft_floor_int(m);
    const pft_real_t f256 = pft_mul_i(pft_sub(m, pft_from_int(whole)), 256); /* [0, 256) */
    const int32_t hi = pft_floor_int(f256);
    const int32_t lo = pft_round_int(pft_mul_i(pft_sub(f256, pft_from_int(hi)), 256));
    const int32_t r = whole * 65536 + hi * 256 + lo;
    return a < 0 ? -r : r;
}

/* Channel offsets (R, G, B) of a pixel of format fmt; bytes per pixel in *bpp. */
static inline void pft_tsa_channels_(pft_pixfmt_t fmt, uint32_t *o0, uint32_t *o1, uint32_t *o2,
                                     uint32_t *bpp)
{
    if (fmt == PFT_PIX_RGB888) {
        *o0 = 0u;
        *o1 = 1u;
        *o2 = 2u;
        *bpp = 3u;
    } else if (fmt == PFT_PIX_BGR888) {
        *o0 = 2u;
        *o1 = 1u;
        *o2 = 0u;
        *bpp = 3u;
    } else {
        *o0 = 0u;
        *o1 = 0u;
        *o2 = 0u;
        *bpp = 1u;
    }
}

/* Inclusive bounding box of integer points. */
typedef struct {
    int32_t x0, y0, x1, y1;
} pft_tsa_box_t_;

/* Bounding box of pts[0..n) (n >= 1). */
pft_tsa_box_t_ pft_tsa_bbox_(const pft_tsa_pt_t *pts, uint32_t n);

#endif
