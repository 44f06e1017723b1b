/* Frame pixels to reals: the one conversion every pixel-domain filter uses. The format is
 * decided once per row (one loop per format), so the per-pixel work is the arithmetic alone;
 * the values are those of one expression per format, as documented in pft_real.h. */
#include <string.h>

#include "pft/pft_real.h"

/* A RES16 value (Q8.8) as a real, exactly: res / 256 (float: a power of two; q16: res * 256). */
static pft_real_t res16_real_(int16_t res)
{
#ifdef PFT_NUMERIC_Q16
    return (pft_real_t)((int32_t)res * 256);
#else
    return (pft_real_t)res * 0.00390625f;
#endif
}

void pft_frame_row_to_real(const pft_frame_t *frame, uint32_t y, uint32_t n, pft_real_t gain,
                           pft_real_t offset, pft_real_t *out)
{
    const uint8_t *row = pft_frame_row(frame, y);
    const pft_real_t lo = PFT_C(-32767.0);
    const pft_real_t hi = PFT_C(32767.0);
    if (frame->format == PFT_PIX_U8) {
        for (uint32_t c = 0; c < n; ++c) {
            out[c] = pft_clamp(pft_add(pft_mul_i(gain, (int32_t)row[c]), offset), lo, hi);
        }
    } else if (frame->format == PFT_PIX_U16) {
        const uint32_t bd = frame->bit_depth == 0u ? 16u : frame->bit_depth;
        const uint32_t mask16 = bd >= 16u ? 0xFFFFu : ((1u << bd) - 1u);
        for (uint32_t c = 0; c < n; ++c) {
            uint16_t raw;
            memcpy(&raw, row + 2u * c, 2u);
            out[c] = pft_clamp(pft_add(pft_mul_i(gain, (int32_t)((uint32_t)raw & mask16)), offset),
                               lo, hi);
        }
    } else if (frame->format == PFT_PIX_RES16) {
        const pft_real_t masked = pft_clamp(offset, lo, hi);
        for (uint32_t c = 0; c < n; ++c) {
            int16_t res;
            memcpy(&res, row + 2u * c, 2u);
            /* Q8.8 sigma units; a masked pixel reads as a zero residual */
            out[c] = res == PFT_RES16_MASKED
                         ? masked
                         : pft_clamp(pft_add(pft_mul(gain, res16_real_(res)), offset), lo, hi);
        }
    } else {
        for (uint32_t c = 0; c < n; ++c) {
            float f;
            memcpy(&f, row + 4u * c, 4u);
            out[c] = pft_clamp(pft_from_f32(f), lo, hi);
        }
    }
}
