/**
 * @file pft_port_template.h
 * @brief Template port: a camera whose DMA fills frame buffers in the background.
 *
 * Starting point for a real flight computer: copy port/template/pft_port_template.c and this
 * header, rename `pft_tpl_` to your port's prefix, and fill in the driver operations (they
 * are the only hardware-specific part). The code is complete and tested with a simulated DMA
 * (tests/unit/test_port_template.c), so what you copy already keeps the lend-and-return rules.
 *
 * Scheme (2 or 3 buffers in RAM the DMA can reach):
 *   FREE --dma_start--> DMA --ISR: pft_tpl_on_frame_done--> READY --acquire--> LENT
 *     ^                                                                          |
 *     +--------------------------------- release ---------------------------------+
 * - The ISR marks the filled buffer READY and restarts the DMA into a FREE buffer at once.
 * - If an older READY frame was never taken, it is dropped ("latest frame wins"): its buffer
 *   is reused and the consumer sees a seq gap. A tracker wants the newest frame, not a backlog.
 * - If no buffer is FREE (consumer holds the rest), the DMA stops; release restarts it.
 *   With 2 buffers the camera stalls while a frame is being processed and the next one is
 *   READY; 3 buffers keep it running.
 * - Frames are never copied: `data` points into the DMA buffer until released.
 */
#ifndef PFT_PORT_TEMPLATE_H
#define PFT_PORT_TEMPLATE_H

#include "pft/pft_port.h"

#ifdef __cplusplus
extern "C" {
#endif

#define PFT_TPL_MAX_BUFFERS 3u

/** Hardware operations: the part of the port you write for your board. */
typedef struct {
    void *drv; /**< your driver state, passed to every operation */
    /** Program the DMA to write the next frame into `buf` (`bytes` long) and enable its
     *  completion interrupt. Called from thread context and from the ISR. Required. */
    void (*dma_start)(void *drv, void *buf, uint32_t bytes);
    /** Sleep until the ISR has signalled a frame or `timeout_ms` passed (an RTOS semaphore,
     *  or a WFI loop on a tick counter). Return true if woken by a frame. Required. */
    bool (*wait_frame)(void *drv, uint32_t timeout_ms);
    /** Mask / unmask the DMA interrupt around shared state. NULL on single-context tests. */
    void (*irq_lock)(void *drv);
    void (*irq_unlock)(void *drv);
    /** Invalidate the data cache over a buffer the DMA wrote, before the CPU reads it
     *  (Cortex-M7 with D-cache; NULL when buffers are in non-cacheable memory or no cache). */
    void (*cache_invalidate)(void *drv, const void *buf, uint32_t bytes);
} pft_tpl_driver_t;

/** Port state. Members written by the ISR are volatile. */
typedef struct {
    pft_tpl_driver_t drv;
    uint8_t *buf[PFT_TPL_MAX_BUFFERS];
    uint32_t nbuf;
    uint32_t bytes;               /**< stride * height */
    uint16_t width, height;
    uint32_t stride;
    pft_pixfmt_t format;
    uint8_t bit_depth;
    volatile uint8_t state[PFT_TPL_MAX_BUFFERS];
    volatile uint32_t seq[PFT_TPL_MAX_BUFFERS];
    volatile uint64_t ts[PFT_TPL_MAX_BUFFERS];
    volatile int32_t dma_buf;     /**< buffer the DMA is filling, -1 if stopped */
    volatile uint32_t next_seq;   /**< seq of the frame being captured */
    volatile uint32_t overruns;   /**< READY frames replaced by a newer one */
    volatile uint32_t dma_errors; /**< frames the ISR reported as failed */
    uint32_t bad_releases;
} pft_tpl_port_t;

/**
 * Initialises the port over `nbuf` (2..3) caller buffers of stride * height bytes each
 * (stride 0: packed). PFT_ERR_INVAL on NULL or bad geometry. The DMA is not started.
 */
pft_status_t pft_tpl_init(pft_tpl_port_t *p, const pft_tpl_driver_t *drv, void *const bufs[],
                          uint32_t nbuf, uint16_t width, uint16_t height, pft_pixfmt_t format,
                          uint8_t bit_depth, uint32_t stride);

/** Starts capturing into the first buffer. PFT_ERR_STATE if already running. */
pft_status_t pft_tpl_start(pft_tpl_port_t *p);

/**
 * Call from the DMA-complete interrupt (or the camera driver's frame-done callback):
 * `timestamp_us` is the capture time (latch it at frame start if the sensor allows),
 * `ok` false for a DMA/transfer error (the frame is discarded, its seq consumed).
 */
void pft_tpl_on_frame_done(pft_tpl_port_t *p, uint64_t timestamp_us, bool ok);

/** Source interface (ctx = p). The consumer may hold at most nbuf - 1 frames at once; one
 *  more gives PFT_ERR_STATE. */
pft_status_t pft_tpl_acquire(void *ctx, pft_frame_t *out, uint32_t timeout_ms);
void pft_tpl_release(void *ctx, const pft_frame_t *frame);
pft_frame_source_t pft_tpl_as_source(pft_tpl_port_t *p);

#ifdef __cplusplus
}
#endif
#endif
