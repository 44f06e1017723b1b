/* Frame pixels to reals: the one conversion every pixel-domain filter uses. */
#include <string.h>

#include "pft/pft_real.h"

void pft_frame_row_to_real(const pft_frame_t *frame, uint32_t y, uint32_t n, pft_real_t gain,
                           pft_real_t offset, pft_real_t *out)
{
    const uint8_t *row = pft_frame_row(frame, y);
    uint32_t bd = frame->bit_depth == 0u ? 16u : frame->bit_depth;
    uint32_t mask16 = bd >= 16u ? 0xFFFFu : ((1u << bd) - 1u);
    for (uint32_t c = 0; c < n; ++c) {
        pft_real_t v;
        if (frame->format == PFT_PIX_U8) {
            v = pft_add(pft_mul_i(gain, (int32_t)row[c]), offset);
        } else if (frame->format == PFT_PIX_U16) {
            uint16_t raw;
            memcpy(&raw, row + 2u * c, 2u);
            v = pft_add(pft_mul_i(gain, (int32_t)((uint32_t)raw & mask16)), offset);
        } else if (frame->format == PFT_PIX_RES16) {
            int16_t res;
            memcpy(&res, row + 2u * c, 2u);
            /* Q8.8 sigma units; a masked pixel reads as a zero residual */
            v = res == PFT_RES16_MASKED
                    ? offset
                    : pft_add(pft_mul(gain, pft_ratio((int32_t)res, 256)), offset);
        } else {
            float f;
            memcpy(&f, row + 4u * c, 4u);
            v = pft_from_f32(f);
        }
        out[c] = pft_clamp(v, PFT_C(-32767.0), PFT_C(32767.0));
    }
}
