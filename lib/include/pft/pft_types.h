/**
 * @file pft_types.h
 * @brief Status codes, pixel formats and the frame descriptor shared by every pftrack module.
 */
#ifndef PFT_TYPES_H
#define PFT_TYPES_H

#include <stddef.h>
#include <stdint.h>
#include <stdbool.h>

#include "pft/pft_config.h"

#ifdef __cplusplus
extern "C" {
#endif

/** Result of every fallible call. PFT_OK is zero, errors are negative. */
typedef enum {
    PFT_OK = 0,
    PFT_ERR_INVAL = -1,   /**< NULL pointer or argument out of its documented domain */
    PFT_ERR_NOMEM = -2,   /**< caller workspace too short */
    PFT_ERR_FORMAT = -3,  /**< frame of the wrong pixel format, size, or with NaN/Inf pixels */
    PFT_ERR_TIMEOUT = -4, /**< no frame within the timeout */
    PFT_ERR_IO = -5,      /**< device, file or transport error */
    PFT_ERR_STATE = -6,   /**< call not valid in the current state (e.g. frame not released) */
    PFT_ERR_RANGE = -7,   /**< a number outside what the arithmetic can represent (e.g. Q16.16 overflow) */
    PFT_ERR_EOF = -8,     /**< end of a finite sequence */
    PFT_ERR_CONFIG = -9,  /**< configuration refused by its config_check (which names the field) */
    PFT_ERR_SINGULAR = -10,  /**< matrix singular or not positive definite */
    PFT_ERR_DEGENERATE = -11, /**< nothing to work on: all weights zero, empty set, box or polygon too small */
    PFT_ERR_SEQ = -12,    /**< frame sequence number repeated or going backwards */
    PFT_ERR_LOST = -13    /**< the tracker has no hypothesis that passes its gate (target lost) */
} pft_status_t;

/** Human-readable name of a status code (static string, never NULL). */
const char *pft_status_str(pft_status_t s);

/** Pixel formats a frame can carry. */
typedef enum {
    PFT_PIX_U8 = 1,     /**< 8-bit grey */
    PFT_PIX_U16 = 2,    /**< 16-bit container, significant bits in frame.bit_depth (e.g. 14-bit IR) */
    PFT_PIX_F32 = 3,    /**< IEEE single, intensity units (host or FPU targets) */
    PFT_PIX_RGB888 = 4, /**< packed R,G,B bytes */
    PFT_PIX_BGR888 = 5, /**< packed B,G,R bytes (OpenCV order) */
    PFT_PIX_RES16 = 6   /**< whitened residual (pft_pre.h): int16 per pixel, Q8.8 in units of
                             the local noise sigma (value / 256), saturating at +-32767 (127.996
                             sigma); PFT_RES16_MASKED marks a pixel without a valid value */
} pft_pixfmt_t;

/**
 * The reserved PFT_PIX_RES16 value of a masked pixel (dead, saturated, listed as bad, or without
 * a background estimate yet). pft_frame_row_to_real gives such a pixel the value of a zero
 * residual; a tracker that can skip pixels should test for this value instead.
 */
#define PFT_RES16_MASKED INT16_MIN

/** Bytes per pixel of a format, 0 for an unknown format. */
uint32_t pft_pixfmt_bytes(pft_pixfmt_t f);

/**
 * A frame lent by a source to a consumer. The library never owns or copies the pixels:
 * `data` stays valid until the frame is released to its source.
 */
typedef struct {
    const void *data;      /**< first pixel of the first row */
    uint16_t width;        /**< pixels per row */
    uint16_t height;       /**< rows */
    uint32_t stride_bytes; /**< bytes from one row to the next (>= width * bytes per pixel) */
    pft_pixfmt_t format;   /**< pixel format */
    uint8_t bit_depth;     /**< significant bits for U16 (1..16); 0 means 16 */
    uint64_t timestamp_us; /**< capture time */
    uint32_t seq;          /**< sequence number from the source */
} pft_frame_t;

/**
 * How a tracker reads pft_frame_t.seq (docs/design.md, "Time, sequence numbers and lost frames").
 * With PFT_SEQ_USE the first frame after init, reset or start sets the reference; each later
 * frame is k = seq - previous accepted seq frame periods on (uint32 arithmetic, so the count
 * wraps from 2^32 - 1 to 0 without a jump): k = 0 (a duplicate) and k >= 2^31 (a frame from the
 * past) are refused with PFT_ERR_SEQ and change nothing; 1 < k <= max_gap predicts over k
 * periods; k > max_gap restarts the tracker on that frame (its tracks end). Timestamps are
 * recorded, not interpreted: the frame period stays the configured T.
 */
typedef enum {
    PFT_SEQ_IGNORE = 0, /**< every frame is one period after the previous one, whatever its seq
                             (default: sources that do not number their frames; old behaviour) */
    PFT_SEQ_USE = 1     /**< gaps in seq are lost frames, as above */
} pft_seq_mode_t;

/** Largest max_gap a tracker config accepts (it bounds the work of one update). */
#define PFT_SEQ_MAX_GAP 64u
/** Default max_gap of every tracker config. */
#define PFT_SEQ_DEFAULT_GAP 8u

/**
 * Checks a frame descriptor: non-NULL data, known format, stride large enough,
 * and, when width/height are non-zero, the exact expected size.
 * @param frame the descriptor to check.
 * @param width expected width in pixels, 0 for any.
 * @param height expected height in rows, 0 for any.
 * @param fmt_mask bit (1u << format) set for every accepted format (PFT_FMT_BIT).
 * Returns PFT_ERR_INVAL for a NULL frame or data, PFT_ERR_FORMAT otherwise.
 * Does not look at pixel values (see pft_frame_check_finite for F32 frames).
 */
pft_status_t pft_frame_check(const pft_frame_t *frame, uint16_t width, uint16_t height,
                             uint32_t fmt_mask);

/** PFT_ERR_FORMAT if an F32 frame holds a NaN or infinity (other formats always pass). */
pft_status_t pft_frame_check_finite(const pft_frame_t *frame);

/** Pointer to row y of a frame (no checks). */
static inline const uint8_t *pft_frame_row(const pft_frame_t *f, uint32_t y)
{
    return (const uint8_t *)f->data + (size_t)y * f->stride_bytes;
}

/** Bit of pixel format f in a format mask (pft_frame_check's fmt_mask). */
#define PFT_FMT_BIT(f) (1u << (unsigned)(f))

#ifdef __cplusplus
}
#endif
#endif
