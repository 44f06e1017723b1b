/**
 * @file pft_port_template.h
 * @brief Template port: a camera whose DMA fills frame buffers in the background.
 *
 * Starting point for a real flight computer: copy port/template/pft_port_template.c and this
 * header, rename `pft_tpl_` to your port's prefix, and fill in the driver operations (they
 * are the only hardware-specific part). The code is complete and tested with a simulated DMA
 * (tests/unit/test_port_template.c, tests/port_conformance/test_conf_template.c), so what you
 * copy already keeps the lend-and-return rules.
 *
 * Two DMA modes, chosen in pft_tpl_config_t::mode:
 *
 * PFT_TPL_ONESHOT: the DMA captures one frame and stops; the port restarts it (`dma_start`)
 * for every frame. 2..PFT_TPL_MAX_BUFFERS buffers:
 *   FREE --dma_start--> DMA --ISR--> READY --acquire--> LENT --release--> FREE
 * - The ISR marks the filled buffer READY and restarts the DMA into a FREE buffer at once.
 * - If no buffer is FREE (the consumer holds the rest), the DMA stops; release restarts it.
 *   With 2 buffers the camera stalls while a frame is being processed and the next one is
 *   READY; 3 buffers keep it running. The consumer may hold nbuf - 1 frames.
 *
 * PFT_TPL_CIRCULAR: the DMA runs continuously and moves by itself, at the end of each frame,
 * to the address last given with `set_next` (double-buffer DMA with two address registers,
 * a camera interface with a "next frame buffer" register latched at frame start). From the
 * frame-done ISR the port gives, with `set_next`, the target of the frame *after* the one the
 * hardware has just begun: a FREE buffer, or the caller's `sink` when every buffer is READY
 * or LENT. A frame captured into the sink reaches nobody: it is counted (`sink_frames`),
 * reported to the optional `on_sink` callback, and shows as a seq gap. The lent buffers are
 * therefore never a DMA target, and the consumer may hold all nbuf frames at once.
 * - Targets change only in the ISR, right after the hardware switched, when a whole frame
 *   period is left to write the idle address register: no race with the hardware's switch.
 *   The price: at each frame end the port needs a FREE buffer besides the one just filled
 *   and the one being filled, so full rate takes nbuf >= 3 + (frames the consumer holds when
 *   a frame ends). Measured in tests/unit/test_port_template.c over 12 frames: a consumer
 *   that releases each frame before the next frame end gets 12 with 3 buffers, 8 with 2
 *   (every third frame to the sink); one that holds each frame until the next arrives gets
 *   12 with 4 buffers, 9 with 3, 6 with 2.
 * In both modes:
 * - "Latest frame wins": a READY frame nobody took is dropped when a newer frame completes
 *   (`overruns`, and a seq gap). A tracker wants the newest frame, not a backlog.
 * - Sequence numbers come from the sensor when the ISR passes its frame counter
 *   (pft_tpl_on_frame_counted; counters narrower than 32 bits are extended across wraps),
 *   else the port counts completed frames (pft_tpl_on_frame_done). Every completed frame
 *   takes a number, including those lost to transfer errors, overruns or the sink, so the
 *   consumer sees every loss as a gap.
 * - Frames are never copied: `data` points into a DMA buffer until released.
 *
 * Execution contexts (what may run in interrupt context, what takes the critical section):
 * - Interrupt context, the DMA/camera ISR only (one priority level): pft_tpl_on_frame_done
 *   and pft_tpl_on_frame_counted. Bounded work, never wait; they call `dma_start`
 *   (one-shot) or `set_next` and `on_sink` (circular), so those must be ISR-safe too.
 * - Thread context (the tracking task), never from the ISR: pft_tpl_start, pft_tpl_stop,
 *   pft_tpl_acquire, pft_tpl_release, pft_tpl_get_stats. Each wraps its access to buffer
 *   states, sequence and counters in `irq_lock` / `irq_unlock` (the port's critical
 *   section), so the ISR never sees a half-updated state.
 * - Thread context before the interrupt is enabled: pft_tpl_config_default, pft_tpl_init.
 * Every member the ISR writes is volatile. Read counters through pft_tpl_get_stats (a
 * consistent copy taken inside the critical section); 64-bit timestamps are never read
 * outside it. `wait_frame` and `cache_invalidate` are called outside the critical section.
 */
#ifndef PFT_PORT_TEMPLATE_H
#define PFT_PORT_TEMPLATE_H

#include "pft/pft_port.h"

#ifdef __cplusplus
extern "C" {
#endif

/** Most frame buffers of one port (the circular mode's sink is extra). */
#define PFT_TPL_MAX_BUFFERS 6u

/** How the DMA moves from one frame to the next. */
typedef enum {
    PFT_TPL_ONESHOT = 0, /**< one transfer per frame, restarted by the port (`dma_start`) */
    PFT_TPL_CIRCULAR = 1 /**< continuous; the port names the next target (`set_next`) */
} pft_tpl_mode_t;

/** Hardware operations: the part of the port you write for your board. */
typedef struct {
    void *drv; /**< your driver state, passed to every operation */
    /** One-shot: program the DMA to write the next frame into `buf` (`bytes` long) and enable
     *  its completion interrupt (thread context in start/release, and the ISR). Circular:
     *  start continuous capture into `buf`; the address for the frame after it was given by
     *  the `set_next` call just before (thread context, in pft_tpl_start). Required. */
    void (*dma_start)(void *drv, void *buf, uint32_t bytes);
    /** Sleep until the ISR has signalled a frame or `timeout_ms` passed (an RTOS binary
     *  semaphore / event flag, or a WFI loop on a tick counter). Return true if woken by a
     *  frame. Thread context, outside the critical section. Required. */
    bool (*wait_frame)(void *drv, uint32_t timeout_ms);
    /** Mask / unmask the DMA interrupt around shared state (the critical section). NULL only
     *  where nothing runs concurrently (single-context tests). */
    void (*irq_lock)(void *drv);
    /** Unmask the DMA interrupt (the end of the critical section); NULL with `irq_lock`. */
    void (*irq_unlock)(void *drv);
    /** Invalidate the data cache over a buffer the DMA wrote, before the CPU reads it
     *  (Cortex-M7 with D-cache; NULL when buffers are in non-cacheable memory or no cache). */
    void (*cache_invalidate)(void *drv, const void *buf, uint32_t bytes);
    /** Circular mode: write the idle address register, the target of the frame after the one
     *  being captured (`buf` is a frame buffer or the sink). Called from the ISR, and once
     *  from pft_tpl_start before `dma_start`. Required in circular mode, unused in one-shot. */
    void (*set_next)(void *drv, void *buf, uint32_t bytes);
    /** Stop capture; return only when the DMA no longer writes to memory. Thread context,
     *  inside the critical section (pft_tpl_stop). Required in circular mode; in one-shot
     *  mode pft_tpl_stop needs it. */
    void (*dma_stop)(void *drv);
} pft_tpl_driver_t;

/** Circular mode: a frame went to the sink (interrupt context: bounded, no waiting). */
typedef void (*pft_tpl_sink_fn)(void *ctx, uint32_t seq, uint64_t timestamp_us);

/** Port configuration. pft_tpl_config_default, then set buffers and geometry. */
typedef struct {
    pft_tpl_mode_t mode;                 /**< default PFT_TPL_ONESHOT */
    void *bufs[PFT_TPL_MAX_BUFFERS];     /**< frame buffers, stride * height bytes each */
    uint32_t nbuf;                       /**< 2..PFT_TPL_MAX_BUFFERS */
    void *sink;                          /**< circular: required, stride * height bytes the
                                              DMA may write and nobody reads; one-shot: unused */
    uint16_t width;                      /**< pixels per row */
    uint16_t height;                     /**< rows */
    pft_pixfmt_t format;                 /**< pixel format the DMA writes */
    uint8_t bit_depth;                   /**< U16 significant bits (0: 16) */
    uint32_t stride;                     /**< bytes per row; 0: packed */
    uint8_t counter_bits;                /**< width of the sensor's frame counter, 1..32
                                              (default 32); see pft_tpl_on_frame_counted */
    uint64_t frame_period_us;            /**< nominal frame period: timestamps of frames the
                                              ISR reports without one (0: repeat the last) */
    pft_tpl_sink_fn on_sink;             /**< optional, called from the ISR per sink frame */
    void *on_sink_ctx;                   /**< passed to `on_sink` */
} pft_tpl_config_t;

/** Counters (read them with pft_tpl_get_stats). */
typedef struct {
    uint32_t completed;       /**< frame-done events taken (every outcome) */
    uint32_t overruns;        /**< READY frames replaced by a newer one */
    uint32_t sink_frames;     /**< circular: frames captured into the sink */
    uint32_t dma_errors;      /**< frames the ISR reported as failed */
    uint32_t counter_repeats; /**< sensor counter did not advance (taken as +1) */
    uint32_t bad_releases;    /**< releases of frames that were not lent (ignored) */
    uint32_t lent;            /**< frames lent right now */
} pft_tpl_stats_t;

/** Port state (allocate it statically; members are private to the port). */
typedef struct {
    pft_tpl_driver_t drv;         /**< copy of the driver callbacks */
    pft_tpl_config_t cfg;         /**< copy; stride resolved, counter_bits 32 for 0 */
    uint32_t bytes;               /**< stride * height */
    volatile uint8_t state[PFT_TPL_MAX_BUFFERS]; /**< free / DMA / ready / lent, per buffer */
    volatile uint32_t seq[PFT_TPL_MAX_BUFFERS];  /**< sequence number of the buffer's frame */
    volatile uint64_t ts[PFT_TPL_MAX_BUFFERS];   /**< timestamp of the buffer's frame, us */
    volatile uint8_t run;         /**< never started / running / stopped */
    volatile int32_t dma_buf;     /**< target being filled: buffer index, PFT_TPL_SINK, or -1
                                       (one-shot paused for want of a buffer, or not running) */
    volatile int32_t next_buf;    /**< circular: target given by the last set_next */
    volatile bool have_seq;       /**< a frame has been numbered */
    volatile uint32_t last_seq;   /**< seq of the last completed frame */
    volatile uint32_t last_counter; /**< sensor counter of the last completed frame */
    volatile uint64_t last_ts;    /**< timestamp of the last completed frame */
    volatile uint32_t completed;  /**< counters: see pft_tpl_stats_t */
    volatile uint32_t overruns;   /**< see pft_tpl_stats_t */
    volatile uint32_t sink_frames; /**< see pft_tpl_stats_t */
    volatile uint32_t dma_errors; /**< see pft_tpl_stats_t */
    volatile uint32_t counter_repeats; /**< see pft_tpl_stats_t */
    uint32_t bad_releases;        /**< see pft_tpl_stats_t */
} pft_tpl_port_t;

/** dma_buf / next_buf value of the sink. */
#define PFT_TPL_SINK ((int32_t)PFT_TPL_MAX_BUFFERS)

/** Flags of pft_tpl_on_frame_counted. */
#define PFT_TPL_FRAME_ERROR 0x1u   /**< transfer error: the frame is discarded, its seq used */
#define PFT_TPL_FRAME_NO_TIME 0x2u /**< no timestamp: previous one + frames * frame_period_us */

/** Defaults: one-shot, no buffers, 32-bit counter, everything else zero. */
void pft_tpl_config_default(pft_tpl_config_t *cfg);

/**
 * Initialises the port (the DMA is not started). PFT_ERR_INVAL: NULL, `dma_start` or
 * `wait_frame` missing, nbuf outside 2..PFT_TPL_MAX_BUFFERS, a NULL buffer, unknown format,
 * zero size, stride below a row, counter_bits above 32, unknown mode; circular mode also
 * without `set_next`, `dma_stop` or `sink`. Both structs are copied.
 */
pft_status_t pft_tpl_init(pft_tpl_port_t *p, const pft_tpl_driver_t *drv,
                          const pft_tpl_config_t *cfg);

/** Starts (or restarts after pft_tpl_stop) capturing. PFT_ERR_STATE if already running. */
pft_status_t pft_tpl_start(pft_tpl_port_t *p);

/**
 * Stops capturing (`dma_stop`); buffers the DMA owned become FREE. Frames already READY can
 * still be acquired, then acquire returns PFT_ERR_EOF until pft_tpl_start. PFT_ERR_STATE if
 * not running, PFT_ERR_INVAL for NULL or a driver without `dma_stop`.
 */
pft_status_t pft_tpl_stop(pft_tpl_port_t *p);

/**
 * Frame-done hook for a sensor that numbers its frames: call it from the DMA-complete /
 * frame-end interrupt with the sensor's frame counter (e.g. from the frame-start packet or
 * the embedded data line) and the capture time. seq follows the counter: the first frame
 * gets the counter itself, later ones advance by the counter's difference modulo
 * 2^counter_bits (so frames the sensor produced but the port never saw are gaps; a jump of
 * 2^counter_bits frames or more cannot be seen). A counter that did not move is counted in
 * `counter_repeats` and taken as +1 so seq still increases. `flags`: PFT_TPL_FRAME_ERROR,
 * PFT_TPL_FRAME_NO_TIME. Interrupt context; ignored unless running.
 */
void pft_tpl_on_frame_counted(pft_tpl_port_t *p, uint32_t sensor_counter,
                              uint64_t timestamp_us, uint32_t flags);

/**
 * Frame-done hook for a sensor without a frame counter: the port numbers completed frames
 * itself (0, 1, 2...). `ok` false for a DMA/transfer error. Interrupt context.
 */
void pft_tpl_on_frame_done(pft_tpl_port_t *p, uint64_t timestamp_us, bool ok);

/**
 * Source interface (ctx = p). PFT_ERR_STATE before the first start or when the consumer
 * already holds its limit (one-shot: nbuf - 1 frames, circular: nbuf); PFT_ERR_EOF after
 * pft_tpl_stop once no READY frame is left; PFT_ERR_TIMEOUT when `wait_frame` gave up, and
 * also, early, when the frame that woke it was lost (transfer error, sink, overrun).
 * Releasing a frame that is not lent is ignored and counted (`bad_releases`).
 */
pft_status_t pft_tpl_acquire(void *ctx, pft_frame_t *out, uint32_t timeout_ms);
/** release of the source interface: the buffer goes back to the DMA's pool. */
void pft_tpl_release(void *ctx, const pft_frame_t *frame);
/** The pft_frame_source_t view of `p` (ctx = p). */
pft_frame_source_t pft_tpl_as_source(pft_tpl_port_t *p);

/** Copies the counters inside the critical section. PFT_ERR_INVAL for NULL. */
pft_status_t pft_tpl_get_stats(pft_tpl_port_t *p, pft_tpl_stats_t *out);

#ifdef __cplusplus
}
#endif
#endif
