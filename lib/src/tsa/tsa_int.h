/* Internals shared by the vision sources: integer square roots and Q16 conversions. */
#ifndef PFT_TSA_INT_H_
#define PFT_TSA_INT_H_

#include "pft/pft_tsa.h"

/* floor(sqrt(v)), bit by bit (32 rounds). */
static inline uint32_t tsa_isqrt64_(uint64_t v)
{
    uint64_t r = 0u, bit = (uint64_t)1u << 62;
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

static inline uint32_t tsa_isqrt32_(uint32_t v)
{
    uint32_t r = 0u, bit = (uint32_t)1u << 30;
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

/* pft_real_t <-> Q16.16 integer (identity in the q16 build). */
#ifdef PFT_NUMERIC_Q16
static inline int32_t tsa_to_q16_(pft_real_t a) { return a; }
static inline pft_real_t tsa_from_q16_(int32_t a) { return a; }
#else
static inline int32_t tsa_to_q16_(pft_real_t a)
{
    float s = a * 65536.0f;
    if (s >= 2147483520.0f) {
        return INT32_MAX;
    }
    if (s <= -2147483520.0f) {
        return -INT32_MAX;
    }
    return (int32_t)(s >= 0.0f ? s + 0.5f : s - 0.5f);
}
static inline pft_real_t tsa_from_q16_(int32_t a) { return (float)a * (1.0f / 65536.0f); }
#endif

/* Channel offsets (R, G, B) of a pixel of format fmt; bytes per pixel in *bpp. */
static inline void tsa_channels_(pft_pixfmt_t fmt, uint32_t *o0, uint32_t *o1, uint32_t *o2,
                                 uint32_t *bpp)
{
    if (fmt == PFT_PIX_RGB888) {
        *o0 = 0u; *o1 = 1u; *o2 = 2u; *bpp = 3u;
    } else if (fmt == PFT_PIX_BGR888) {
        *o0 = 2u; *o1 = 1u; *o2 = 0u; *bpp = 3u;
    } else {
        *o0 = 0u; *o1 = 0u; *o2 = 0u; *bpp = 1u;
    }
}

#define TSA_FMT_MASK_ (PFT_FMT_BIT(PFT_PIX_U8) | PFT_FMT_BIT(PFT_PIX_RGB888) | PFT_FMT_BIT(PFT_PIX_BGR888))

#endif
