/*
 * Template port: DMA double/triple buffering behind the pft_frame_source_t interface.
 * See pft_port_template.h for the buffer life cycle and docs/porting.md for the rules.
 *
 * To make it yours:
 *   1. Copy this file and pft_port_template.h, rename pft_tpl_ to pft_<board>_.
 *   2. Write the driver operations (pft_tpl_driver_t). A typical STM32-style camera
 *      interface (DCMI/CSI + DMA) looks like this:
 *
 *        static void my_dma_start(void *drv, void *buf, uint32_t bytes)
 *        {
 *            my_cam_t *c = drv;
 *            DMA_Stream->CR &= ~DMA_SxCR_EN;          // stop, wait until EN reads 0
 *            DMA_Stream->M0AR = (uint32_t)buf;        // destination: our frame buffer
 *            DMA_Stream->NDTR = bytes / 4u;           // words
 *            DMA_Stream->CR |= DMA_SxCR_TCIE | DMA_SxCR_EN;
 *            CAM->CR |= CAM_CR_CAPTURE;               // snapshot mode: one frame
 *        }
 *
 *        void DMA_Stream_IRQHandler(void)             // frame complete
 *        {
 *            bool ok = (DMA->ISR & DMA_TEIF) == 0u;    // transfer error?
 *            DMA->IFCR = DMA_ALL_FLAGS;
 *            pft_tpl_on_frame_done(&g_port, board_time_us_latched_at_vsync(), ok);
 *            rtos_sem_give_from_isr(&g_frame_sem);      // wakes wait_frame
 *        }
 *
 *        static bool my_wait(void *drv, uint32_t ms) { return rtos_sem_take(&g_frame_sem, ms); }
 *        static void my_lock(void *drv)   { NVIC_DisableIRQ(DMA_Stream_IRQn); }
 *        static void my_unlock(void *drv) { NVIC_EnableIRQ(DMA_Stream_IRQn); }
 *        static void my_inval(void *drv, const void *b, uint32_t n)
 *        {   SCB_InvalidateDCache_by_Addr((void *)b, (int32_t)n); }  // 32-byte aligned buffers!
 *
 *   3. Put the buffers where the DMA can write them (not DTCM on parts whose DMA cannot reach
 *      it), aligned to the cache line (32 bytes on Cortex-M7), each a multiple of 32 bytes,
 *      or in a non-cacheable MPU region and pass cache_invalidate = NULL.
 *   4. pft_tpl_init, pft_tpl_start, then hand pft_tpl_as_source(&port) to pft_runner_run or
 *      call pft_source_acquire / pft_source_release from your tracking task.
 *
 * Without an RTOS, wait_frame can spin on a flag set by the ISR with __WFI() and give up after
 * timeout_ms of a millisecond tick.
 */
#include <string.h>

#include "pft/pft_port_template.h"

enum { BUF_FREE = 0, BUF_DMA = 1, BUF_READY = 2, BUF_LENT = 3 };

static void lock(pft_tpl_port_t *p)
{
    if (p->drv.irq_lock != NULL) {
        p->drv.irq_lock(p->drv.drv);
    }
}

static void unlock(pft_tpl_port_t *p)
{
    if (p->drv.irq_unlock != NULL) {
        p->drv.irq_unlock(p->drv.drv);
    }
}

/* With the interrupt masked (or in the ISR): start the DMA into a FREE buffer, if any. */
static void start_next_locked(pft_tpl_port_t *p)
{
    p->dma_buf = -1;
    for (uint32_t i = 0; i < p->nbuf; ++i) {
        if (p->state[i] == BUF_FREE) {
            p->state[i] = BUF_DMA;
            p->dma_buf = (int32_t)i;
            p->drv.dma_start(p->drv.drv, p->buf[i], p->bytes);
            return;
        }
    }
    /* every buffer READY or LENT: the camera pauses until a release */
}

pft_status_t pft_tpl_init(pft_tpl_port_t *p, const pft_tpl_driver_t *drv, void *const bufs[],
                          uint32_t nbuf, uint16_t width, uint16_t height, pft_pixfmt_t format,
                          uint8_t bit_depth, uint32_t stride)
{
    if (p == NULL || drv == NULL || bufs == NULL || drv->dma_start == NULL ||
        drv->wait_frame == NULL || nbuf < 2u || nbuf > PFT_TPL_MAX_BUFFERS) {
        return PFT_ERR_INVAL;
    }
    uint32_t row = (uint32_t)width * pft_pixfmt_bytes(format);
    uint32_t st = (stride == 0u) ? row : stride;
    if (row == 0u || height == 0u || st < row) {
        return PFT_ERR_INVAL;
    }
    memset(p, 0, sizeof *p);
    for (uint32_t i = 0; i < nbuf; ++i) {
        if (bufs[i] == NULL) {
            return PFT_ERR_INVAL;
        }
        p->buf[i] = (uint8_t *)bufs[i];
    }
    p->drv = *drv;
    p->nbuf = nbuf;
    p->width = width;
    p->height = height;
    p->stride = st;
    p->bytes = st * height;
    p->format = format;
    p->bit_depth = bit_depth;
    p->dma_buf = -1;
    return PFT_OK;
}

pft_status_t pft_tpl_start(pft_tpl_port_t *p)
{
    if (p == NULL) {
        return PFT_ERR_INVAL;
    }
    lock(p);
    pft_status_t st = PFT_ERR_STATE;
    if (p->dma_buf < 0) {
        start_next_locked(p);
        st = (p->dma_buf >= 0) ? PFT_OK : PFT_ERR_STATE;
    }
    unlock(p);
    return st;
}

void pft_tpl_on_frame_done(pft_tpl_port_t *p, uint64_t timestamp_us, bool ok)
{
    /* interrupt context: no waiting, no printing, bounded work */
    int32_t b = p->dma_buf;
    if (b < 0) {
        return; /* spurious */
    }
    uint32_t i = (uint32_t)b;
    uint32_t seq = p->next_seq++;
    if (!ok) {
        p->dma_errors++;
        p->drv.dma_start(p->drv.drv, p->buf[i], p->bytes); /* same buffer again */
        return;
    }
    for (uint32_t k = 0; k < p->nbuf; ++k) {
        if (p->state[k] == BUF_READY) { /* nobody took it: the newer frame wins */
            p->state[k] = BUF_FREE;
            p->overruns++;
        }
    }
    p->seq[i] = seq;
    p->ts[i] = timestamp_us;
    p->state[i] = BUF_READY;
    start_next_locked(p);
}

/* The READY buffer, marked LENT, or -1. */
static int32_t take_ready(pft_tpl_port_t *p)
{
    int32_t got = -1;
    lock(p);
    for (uint32_t i = 0; i < p->nbuf; ++i) {
        if (p->state[i] == BUF_READY) {
            p->state[i] = BUF_LENT;
            got = (int32_t)i;
            break;
        }
    }
    unlock(p);
    return got;
}

pft_status_t pft_tpl_acquire(void *ctx, pft_frame_t *out, uint32_t timeout_ms)
{
    pft_tpl_port_t *p = (pft_tpl_port_t *)ctx;
    if (p == NULL || out == NULL) {
        return PFT_ERR_INVAL;
    }
    memset(out, 0, sizeof *out);
    uint32_t lent = 0u;
    for (uint32_t i = 0; i < p->nbuf; ++i) {
        lent += (p->state[i] == BUF_LENT) ? 1u : 0u;
    }
    if (lent + 1u >= p->nbuf) {
        /* one buffer always stays with the camera, so capture goes on while the consumer
         * holds frames: holding more than nbuf - 1 is a consumer bug (release first) */
        return PFT_ERR_STATE;
    }
    int32_t b = take_ready(p);
    if (b < 0) {
        if (!p->drv.wait_frame(p->drv.drv, timeout_ms)) {
            return PFT_ERR_TIMEOUT;
        }
        b = take_ready(p);
        if (b < 0) {
            return PFT_ERR_TIMEOUT; /* woken, but the frame was an error */
        }
    }
    uint32_t i = (uint32_t)b;
    if (p->drv.cache_invalidate != NULL) {
        p->drv.cache_invalidate(p->drv.drv, p->buf[i], p->bytes);
    }
    out->data = p->buf[i];
    out->width = p->width;
    out->height = p->height;
    out->stride_bytes = p->stride;
    out->format = p->format;
    out->bit_depth = p->bit_depth;
    lock(p);
    out->seq = p->seq[i];
    out->timestamp_us = p->ts[i];
    unlock(p);
    return PFT_OK;
}

void pft_tpl_release(void *ctx, const pft_frame_t *frame)
{
    pft_tpl_port_t *p = (pft_tpl_port_t *)ctx;
    if (p == NULL) {
        return;
    }
    lock(p);
    bool found = false;
    for (uint32_t i = 0; frame != NULL && i < p->nbuf; ++i) {
        if (frame->data == (const void *)p->buf[i] && p->state[i] == BUF_LENT) {
            p->state[i] = BUF_FREE;
            found = true;
            if (p->dma_buf < 0) {
                start_next_locked(p); /* the camera was paused for want of a buffer */
            }
            break;
        }
    }
    if (!found) {
        p->bad_releases++;
    }
    unlock(p);
}

pft_frame_source_t pft_tpl_as_source(pft_tpl_port_t *p)
{
    pft_frame_source_t s;
    s.ctx = p;
    s.acquire = pft_tpl_acquire;
    s.release = pft_tpl_release;
    return s;
}
