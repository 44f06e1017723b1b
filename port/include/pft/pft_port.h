/**
 * @file pft_port.h
 * @brief Hardware abstraction for frame input: the frame source interface and the runner.
 *
 * A frame source lends frames to its consumer and gets them back: `acquire` fills a
 * pft_frame_t whose `data` points into the source's own memory (a DMA buffer, a ring slot,
 * a file buffer), and that memory stays valid and unchanged until the same descriptor is
 * passed to `release`. Nothing is copied on the way. Every successful acquire must be
 * followed by exactly one release; a failed acquire lends nothing and must not be released.
 *
 * The runner pulls frames from a source, validates each with pft_frame_check, hands the good
 * ones to a consumer (typically a tracker step), always releases, times the consumer through
 * caller-supplied hooks, counts recoverable faults and keeps going.
 *
 * Port code (everything under port/) may use the C library (stdio in port/file); the
 * library core in lib/ never does. See docs/porting.md.
 */
#ifndef PFT_PORT_H
#define PFT_PORT_H

#include <stddef.h>
#include <stdint.h>
#include <stdbool.h>

#include "pft/pft_types.h"

#ifdef __cplusplus
extern "C" {
#endif

/**
 * A source of frames, lend-and-return.
 *
 * `acquire(ctx, out, timeout_ms)`: wait at most `timeout_ms` for the next frame and describe
 * it in `*out`. Returns PFT_OK (frame lent), PFT_ERR_TIMEOUT (none in time, nothing lent),
 * PFT_ERR_EOF (finite sequence ended; sticky), PFT_ERR_IO / PFT_ERR_FORMAT (this frame was
 * lost or unreadable; the next acquire may succeed), PFT_ERR_STATE (too many frames lent at
 * once: release one first), PFT_ERR_INVAL (bad arguments).
 *
 * `release(ctx, frame)`: give back a frame obtained from `acquire` (same descriptor or a copy
 * of it; sources identify a frame by its `data` pointer). Releasing something that is not lent
 * must be harmless (ignored; sources may count it).
 */
typedef struct {
    void *ctx;                                                                  /**< port state */
    pft_status_t (*acquire)(void *ctx, pft_frame_t *out, uint32_t timeout_ms); /**< lend a frame */
    void (*release)(void *ctx, const pft_frame_t *frame);                      /**< give it back */
} pft_frame_source_t;

/** Wait forever (for sources able to block). */
#define PFT_TIMEOUT_FOREVER 0xFFFFFFFFu

/**
 * Validated acquire: PFT_ERR_INVAL if `src`, its `acquire`/`release` or `out` is NULL.
 * Otherwise calls the source; `*out` is zeroed first, and zeroed again on any error, so a
 * failed acquire never leaves a dangling `data` pointer.
 */
pft_status_t pft_source_acquire(const pft_frame_source_t *src, pft_frame_t *out,
                                uint32_t timeout_ms);

/** Validated release: PFT_ERR_INVAL if `src`, its `release`, `frame` or `frame->data` is NULL. */
pft_status_t pft_source_release(const pft_frame_source_t *src, const pft_frame_t *frame);

/* ---------------------------------------------------------------------------------------- */
/* Runner                                                                                   */
/* ---------------------------------------------------------------------------------------- */

/**
 * Consumer of frames (e.g. one tracker step). The frame is valid only during the call.
 * Return PFT_OK to continue, PFT_ERR_EOF to stop the run cleanly, any other status to have it
 * counted in pft_runner_stats_t::consumer_errors (the run continues).
 */
typedef pft_status_t (*pft_consumer_fn)(void *ctx, const pft_frame_t *frame);

/** Platform hooks of the runner; every member may be NULL. */
typedef struct {
    void *ctx; /**< passed to every hook */
    /** Monotonic time in microseconds; NULL disables timing (times stay 0). */
    uint64_t (*now_us)(void *ctx);
    /** Just before the consumer is called (e.g. toggle a GPIO for a scope, start a cycle counter). */
    void (*on_frame_begin)(void *ctx, const pft_frame_t *frame);
    /** Just after the consumer returned, with its status and the consumer time in microseconds. */
    void (*on_frame_end)(void *ctx, const pft_frame_t *frame, pft_status_t status,
                         uint64_t elapsed_us);
    /** A recoverable fault was counted, for logging. `status`: the acquire error
     *  (TIMEOUT/IO/FORMAT); PFT_ERR_FORMAT for a frame rejected by the checks; PFT_ERR_RANGE
     *  for a seq gap or seq error; PFT_ERR_TIMEOUT for a late or backwards timestamp (the
     *  frame is still used);
     *  the consumer's status for a consumer error. `seq` is the frame's (0 if none lent). */
    void (*on_fault)(void *ctx, pft_status_t status, uint32_t seq);
} pft_runner_hooks_t;

/** What the runner accepts and when it stops. Zero-initialise, then set what you need. */
typedef struct {
    uint32_t timeout_ms;    /**< per acquire (0: poll) */
    uint32_t max_frames;    /**< stop after this many frames reached the consumer; 0: until EOF */
    uint32_t max_attempts;  /**< hard bound on acquire calls; 0: 16 * max_frames + 64, or no
                                 bound when max_frames is 0 */
    uint32_t max_consecutive_errors; /**< stop with the last error after this many failed
                                          iterations in a row; 0: no limit */
    uint16_t width;         /**< expected width; 0: lock to the first good frame */
    uint16_t height;        /**< expected height; 0: lock to the first good frame */
    uint32_t fmt_mask;      /**< accepted formats (PFT_FMT_BIT); 0: all known formats */
    uint64_t max_interval_us; /**< timestamp step above this counts as late; 0: not checked */
    bool check_finite;      /**< also reject F32 frames holding NaN/Inf */
} pft_runner_config_t;

/** Counters of one run. Every field is reset by pft_runner_run. */
typedef struct {
    uint32_t attempts;        /**< acquire calls */
    uint32_t acquired;        /**< acquires that lent a frame */
    uint32_t released;        /**< releases issued (always equals acquired at return) */
    uint32_t frames;          /**< frames that passed the checks and reached the consumer */
    uint32_t dropped;         /**< frames missing from the sequence (sum of seq gaps) */
    uint32_t seq_errors;      /**< seq not increasing (repeat or backwards) */
    uint32_t short_frames;    /**< rejected: smaller than expected (rows or stride) */
    uint32_t corrupt;         /**< rejected: bad descriptor (format, zero size, NULL data, NaN) */
    uint32_t late;            /**< delivered, but timestamp step > max_interval_us */
    uint32_t ts_backwards;    /**< delivered, but timestamp before the previous frame's */
    uint32_t timeouts;        /**< acquire returned PFT_ERR_TIMEOUT */
    uint32_t io_errors;       /**< acquire returned PFT_ERR_IO */
    uint32_t format_errors;   /**< acquire returned PFT_ERR_FORMAT (source found bad data) */
    uint32_t consumer_errors; /**< consumer returned an error other than PFT_ERR_EOF */
    uint64_t time_min_us;     /**< shortest consumer time (0 if no frame or no clock) */
    uint64_t time_max_us;     /**< longest consumer time */
    uint64_t time_total_us;   /**< sum of consumer times (mean = total / frames) */
    uint16_t width;           /**< geometry the run checked against (given or locked) */
    uint16_t height;          /**< rows of that geometry */
    pft_status_t stop;        /**< why the run ended: PFT_ERR_EOF (source or consumer), PFT_OK
                                   (max_frames or max_attempts reached), or the fatal error */
} pft_runner_stats_t;

/**
 * Runs `src` into `consumer` until the source ends (PFT_ERR_EOF), the consumer returns
 * PFT_ERR_EOF, `max_frames` frames were consumed, or `max_attempts` acquires were made.
 *
 * Recoverable (counted, run continues): acquire PFT_ERR_TIMEOUT / PFT_ERR_IO / PFT_ERR_FORMAT,
 * frames rejected by pft_frame_check (short or corrupt: released without reaching the
 * consumer), seq gaps (dropped frames), late timestamps, consumer errors.
 * Fatal (run stops, returned): acquire PFT_ERR_INVAL / PFT_ERR_STATE / PFT_ERR_NOMEM /
 * PFT_ERR_RANGE or any unknown status, and `max_consecutive_errors` reached (returns the last
 * recoverable error).
 *
 * @param src           the frame source (required).
 * @param consumer      called once per delivered frame (required).
 * @param consumer_ctx  passed to `consumer` unchanged.
 * @param hooks         may be NULL (no timing).
 * @param cfg           may be NULL (all defaults).
 * @param stats         required; filled even when an error is returned.
 * @return PFT_OK on a normal end (EOF, max_frames, max_attempts), PFT_ERR_INVAL for NULL
 *         `src`/`consumer`/`stats` or a source without acquire/release, else the fatal error.
 */
pft_status_t pft_runner_run(const pft_frame_source_t *src, pft_consumer_fn consumer,
                            void *consumer_ctx, const pft_runner_hooks_t *hooks,
                            const pft_runner_config_t *cfg, pft_runner_stats_t *stats);

#ifdef __cplusplus
}
#endif
#endif
