/* Status names, pixel-format sizes and frame validation. */
#include <string.h>

#include "pft/pft_types.h"

const char *pft_status_str(pft_status_t s)
{
    switch (s) {
    case PFT_OK: return "ok";
    case PFT_ERR_INVAL: return "invalid argument";
    case PFT_ERR_NOMEM: return "workspace too short";
    case PFT_ERR_FORMAT: return "bad frame format";
    case PFT_ERR_TIMEOUT: return "timeout";
    case PFT_ERR_IO: return "i/o error";
    case PFT_ERR_STATE: return "invalid state";
    case PFT_ERR_RANGE: return "out of range";
    case PFT_ERR_EOF: return "end of sequence";
    case PFT_ERR_CONFIG: return "bad configuration";
    case PFT_ERR_SINGULAR: return "singular matrix";
    case PFT_ERR_DEGENERATE: return "degenerate input";
    case PFT_ERR_SEQ: return "frame out of sequence";
    case PFT_ERR_LOST: return "target lost";
    default: return "unknown status";
    }
}

uint32_t pft_pixfmt_bytes(pft_pixfmt_t f)
{
    switch (f) {
    case PFT_PIX_U8: return 1u;
    case PFT_PIX_U16:
    case PFT_PIX_RES16: return 2u;
    case PFT_PIX_F32: return 4u;
    case PFT_PIX_RGB888:
    case PFT_PIX_BGR888: return 3u;
    default: return 0u;
    }
}

pft_status_t pft_frame_check(const pft_frame_t *frame, uint16_t width, uint16_t height,
                             uint32_t fmt_mask)
{
    if (frame == NULL || frame->data == NULL) {
        return PFT_ERR_INVAL;
    }
    uint32_t bpp = pft_pixfmt_bytes(frame->format);
    if (bpp == 0u || (fmt_mask & PFT_FMT_BIT(frame->format)) == 0u) {
        return PFT_ERR_FORMAT;
    }
    if (frame->width == 0u || frame->height == 0u ||
        frame->stride_bytes < (uint32_t)frame->width * bpp) {
        return PFT_ERR_FORMAT;
    }
    if (frame->format == PFT_PIX_U16 && frame->bit_depth > 16u) {
        return PFT_ERR_FORMAT;
    }
    if ((width != 0u && frame->width != width) || (height != 0u && frame->height != height)) {
        return PFT_ERR_FORMAT;
    }
    return PFT_OK;
}

pft_status_t pft_frame_check_finite(const pft_frame_t *frame)
{
    if (frame == NULL || frame->data == NULL) {
        return PFT_ERR_INVAL;
    }
    if (frame->format != PFT_PIX_F32) {
        return PFT_OK;
    }
    for (uint32_t y = 0; y < frame->height; ++y) {
        const uint8_t *row = pft_frame_row(frame, y);
        for (uint32_t x = 0; x < frame->width; ++x) {
            uint32_t bits;
            memcpy(&bits, row + 4u * x, 4u); /* integer test: no float ops (q16 builds) */
            if ((bits & 0x7F800000u) == 0x7F800000u) {
                return PFT_ERR_FORMAT;
            }
        }
    }
    return PFT_OK;
}
