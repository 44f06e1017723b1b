/*
 * Template port: DMA double/triple buffering behind the pft_frame_source_t interface, with
 * the DMA restarted once per frame (one-shot) or running continuously (circular).
 * See pft_port_template.h for the buffer life cycle and docs/porting.md for the rules.
 *
 * To make it yours:
 *   1. Copy this file and pft_port_template.h, rename pft_tpl_ to pft_<board>_.
 *   2. Write the driver operations (pft_tpl_driver_t). A typical STM32-style camera
 *      interface (DCMI/CSI + DMA) in one-shot mode (snapshot capture) looks like this:
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
 *      In circular mode the same DMA runs in double-buffer mode (two address registers,
 *      the hardware swaps them at each frame end) and the camera in continuous capture:
 *
 *        static void my_set_next(void *drv, void *buf, uint32_t bytes)
 *        {   // the register the DMA is NOT using now (CT tells which one it is using)
 *            (void)bytes;
 *            if (DMA_Stream->CR & DMA_SxCR_CT) DMA_Stream->M0AR = (uint32_t)buf;
 *            else                              DMA_Stream->M1AR = (uint32_t)buf;
 *        }
 *        static void my_start_circular(void *drv, void *buf, uint32_t bytes)
 *        {   // set_next has just written M1AR (CT = 0 while stopped)
 *            DMA_Stream->M0AR = (uint32_t)buf;
 *            DMA_Stream->NDTR = bytes / 4u;
 *            DMA_Stream->CR |= DMA_SxCR_DBM | DMA_SxCR_TCIE | DMA_SxCR_EN;
 *            CAM->CR |= CAM_CR_CONTINUOUS | CAM_CR_CAPTURE;
 *        }
 *        static void my_stop(void *drv)
 *        {   CAM->CR &= ~CAM_CR_CAPTURE; DMA_Stream->CR &= ~DMA_SxCR_EN;
 *            while (DMA_Stream->CR & DMA_SxCR_EN) {} }   // bounded by the DMA's drain time
 *
 *        void DMA_Stream_IRQHandler(void)             // a frame ended, the DMA swapped
 *        {
 *            uint32_t flags = (DMA->ISR & DMA_TEIF) ? PFT_TPL_FRAME_ERROR : 0u;
 *            DMA->IFCR = DMA_ALL_FLAGS;
 *            pft_tpl_on_frame_counted(&g_port, sensor_frame_counter(), vsync_time_us(), flags);
 *            rtos_sem_give_from_isr(&g_frame_sem);
 *        }
 *
 *   3. Put the buffers where the DMA can write them (not DTCM on parts whose DMA cannot reach
 *      it), aligned to the cache line (32 bytes on Cortex-M7), each a multiple of 32 bytes,
 *      or in a non-cacheable MPU region and pass cache_invalidate = NULL.
 *   4. pft_tpl_config_default, fill in mode, buffers (and the sink) and geometry,
 *      pft_tpl_init, pft_tpl_start, then hand pft_tpl_as_source(&port) to pft_runner_run or
 *      call pft_source_acquire / pft_source_release from your tracking task.
 *
 * Without an RTOS, wait_frame can spin on a flag set by the ISR with __WFI() and give up after
 * timeout_ms of a millisecond tick.
 */
#include <string.h>

#include "pft/pft_port_template.h"

enum { BUF_FREE = 0, BUF_DMA = 1, BUF_READY = 2, BUF_LENT = 3 };
enum { RUN_IDLE = 0, RUN_ON = 1, RUN_STOPPED = 2 };

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

/* Memory of a target: a buffer index or PFT_TPL_SINK. */
static void *target_mem(const pft_tpl_port_t *p, int32_t t)
{
    return (t == PFT_TPL_SINK) ? p->cfg.sink : p->cfg.bufs[(uint32_t)t];
}

/* Locked or ISR: claims a FREE buffer for the DMA; -1 if there is none. */
static int32_t claim_free(pft_tpl_port_t *p)
{
    for (uint32_t i = 0; i < p->cfg.nbuf; ++i) {
        if (p->state[i] == BUF_FREE) {
            p->state[i] = BUF_DMA;
            return (int32_t)i;
        }
    }
    return -1;
}

/* Locked or ISR: a FREE buffer for the circular DMA, else the sink. */
static int32_t claim_target(pft_tpl_port_t *p)
{
    int32_t t = claim_free(p);
    return (t >= 0) ? t : PFT_TPL_SINK;
}

/* One-shot, locked or ISR: start the DMA into a FREE buffer, if any. */
static void start_next_locked(pft_tpl_port_t *p)
{
    p->dma_buf = claim_free(p);
    if (p->dma_buf >= 0) {
        p->drv.dma_start(p->drv.drv, p->cfg.bufs[(uint32_t)p->dma_buf], p->bytes);
    }
    /* else every buffer READY or LENT: the camera pauses until a release */
}

void pft_tpl_config_default(pft_tpl_config_t *cfg)
{
    if (cfg != NULL) {
        memset(cfg, 0, sizeof *cfg);
        cfg->mode = PFT_TPL_ONESHOT;
        cfg->counter_bits = 32u;
    }
}

pft_status_t pft_tpl_init(pft_tpl_port_t *p, const pft_tpl_driver_t *drv,
                          const pft_tpl_config_t *cfg)
{
    if (p == NULL || drv == NULL || cfg == NULL || drv->dma_start == NULL ||
        drv->wait_frame == NULL || cfg->nbuf < 2u || cfg->nbuf > PFT_TPL_MAX_BUFFERS ||
        cfg->counter_bits > 32u) {
        return PFT_ERR_INVAL;
    }
    if (cfg->mode == PFT_TPL_CIRCULAR) {
        if (drv->set_next == NULL || drv->dma_stop == NULL || cfg->sink == NULL) {
            return PFT_ERR_INVAL;
        }
    } else if (cfg->mode != PFT_TPL_ONESHOT) {
        return PFT_ERR_INVAL;
    } else {
        /* one-shot: nothing more is required */
    }
    uint32_t row = (uint32_t)cfg->width * pft_pixfmt_bytes(cfg->format);
    uint32_t st = (cfg->stride == 0u) ? row : cfg->stride;
    if (row == 0u || cfg->height == 0u || st < row ||
        (uint64_t)st * cfg->height > 0xFFFFFFFFu ||
        (cfg->format == PFT_PIX_U16 && cfg->bit_depth > 16u)) {
        return PFT_ERR_INVAL;
    }
    for (uint32_t i = 0; i < cfg->nbuf; ++i) {
        if (cfg->bufs[i] == NULL) {
            return PFT_ERR_INVAL;
        }
    }
    memset(p, 0, sizeof *p);
    p->drv = *drv;
    p->cfg = *cfg;
    for (uint32_t i = cfg->nbuf; i < PFT_TPL_MAX_BUFFERS; ++i) {
        p->cfg.bufs[i] = NULL;
    }
    p->cfg.stride = st;
    if (p->cfg.counter_bits == 0u) {
        p->cfg.counter_bits = 32u;
    }
    p->bytes = st * cfg->height;
    p->run = RUN_IDLE;
    p->dma_buf = -1;
    p->next_buf = -1;
    return PFT_OK;
}

pft_status_t pft_tpl_start(pft_tpl_port_t *p)
{
    if (p == NULL) {
        return PFT_ERR_INVAL;
    }
    lock(p);
    pft_status_t st = PFT_ERR_STATE;
    if (p->run != RUN_ON) {
        p->run = RUN_ON;
        if (p->cfg.mode == PFT_TPL_CIRCULAR) {
            /* both address registers first, then enable: capture never lacks a target */
            p->dma_buf = claim_target(p);
            p->next_buf = claim_target(p);
            p->drv.set_next(p->drv.drv, target_mem(p, p->next_buf), p->bytes);
            p->drv.dma_start(p->drv.drv, target_mem(p, p->dma_buf), p->bytes);
        } else {
            start_next_locked(p); /* may stay paused: a buffer is freed by release */
        }
        st = PFT_OK;
    }
    unlock(p);
    return st;
}

pft_status_t pft_tpl_stop(pft_tpl_port_t *p)
{
    if (p == NULL || p->drv.dma_stop == NULL) {
        return PFT_ERR_INVAL;
    }
    lock(p);
    pft_status_t st = PFT_ERR_STATE;
    if (p->run == RUN_ON) {
        p->drv.dma_stop(p->drv.drv);
        for (uint32_t i = 0; i < p->cfg.nbuf; ++i) {
            if (p->state[i] == BUF_DMA) {
                p->state[i] = BUF_FREE;
            }
        }
        p->dma_buf = -1;
        p->next_buf = -1;
        p->run = RUN_STOPPED;
        st = PFT_OK;
    }
    unlock(p);
    return st;
}

/* ISR: seq of the completed frame from the sensor counter (or the port's own count). */
static uint32_t number_frame(pft_tpl_port_t *p, uint32_t counter, bool counted)
{
    uint32_t bits = p->cfg.counter_bits;
    uint32_t mask = (bits >= 32u) ? 0xFFFFFFFFu : ((1u << bits) - 1u);
    uint32_t c = counter & mask;
    uint32_t seq;
    if (!p->have_seq) {
        seq = counted ? c : 0u;
    } else if (!counted) {
        seq = p->last_seq + 1u;
    } else {
        uint32_t d = (c - p->last_counter) & mask;
        if (d == 0u) {
            p->counter_repeats++;
            d = 1u;
        }
        seq = p->last_seq + d;
    }
    p->last_counter = counted ? c : seq;
    return seq;
}

/* ISR: timestamp of frame `seq`, given or derived from the frame period. */
static uint64_t time_frame(pft_tpl_port_t *p, uint32_t seq, uint64_t ts, bool given)
{
    if (given) {
        return ts;
    }
    if (!p->have_seq) {
        return 0u;
    }
    return p->last_ts + (uint64_t)(seq - p->last_seq) * p->cfg.frame_period_us;
}

/* ISR: a good frame completed into buffer i: it becomes the one READY frame. */
static void publish(pft_tpl_port_t *p, uint32_t i, uint32_t seq, uint64_t ts)
{
    for (uint32_t k = 0; k < p->cfg.nbuf; ++k) {
        if (p->state[k] == BUF_READY) { /* nobody took it: the newer frame wins */
            p->state[k] = BUF_FREE;
            p->overruns++;
        }
    }
    p->seq[i] = seq;
    p->ts[i] = ts;
    p->state[i] = BUF_READY;
}

/* ISR, one-shot: the DMA stopped after filling dma_buf. */
static void done_oneshot(pft_tpl_port_t *p, uint32_t seq, uint64_t ts, bool ok)
{
    uint32_t i = (uint32_t)p->dma_buf;
    if (!ok) {
        p->dma_errors++;
        p->drv.dma_start(p->drv.drv, p->cfg.bufs[i], p->bytes); /* same buffer again */
        return;
    }
    publish(p, i, seq, ts);
    start_next_locked(p);
}

/* ISR, circular: the hardware finished dma_buf and already moved on to next_buf. */
static void done_circular(pft_tpl_port_t *p, uint32_t seq, uint64_t ts, bool ok)
{
    int32_t done = p->dma_buf;
    p->dma_buf = p->next_buf;
    if (done == PFT_TPL_SINK) {
        if (!ok) {
            p->dma_errors++;
        } else {
            p->sink_frames++;
            if (p->cfg.on_sink != NULL) {
                p->cfg.on_sink(p->cfg.on_sink_ctx, seq, ts);
            }
        }
    } else if (!ok) {
        p->dma_errors++;
        p->state[(uint32_t)done] = BUF_FREE;
    } else {
        publish(p, (uint32_t)done, seq, ts);
    }
    /* the idle register gets the frame after next: a FREE buffer, else the sink */
    p->next_buf = claim_target(p);
    p->drv.set_next(p->drv.drv, target_mem(p, p->next_buf), p->bytes);
}

/* ISR: every frame-done event, numbered and timed, then handed to the mode. */
static void frame_done(pft_tpl_port_t *p, uint32_t counter, bool counted, uint64_t ts,
                       uint32_t flags)
{
    /* interrupt context: no waiting, no printing, bounded work */
    if (p == NULL || p->run != RUN_ON || p->dma_buf < 0) {
        return; /* spurious: not running, or a one-shot DMA with no target */
    }
    uint32_t seq = number_frame(p, counter, counted);
    uint64_t t = time_frame(p, seq, ts, (flags & PFT_TPL_FRAME_NO_TIME) == 0u);
    p->have_seq = true;
    p->last_seq = seq;
    p->last_ts = t;
    p->completed++;
    bool ok = (flags & PFT_TPL_FRAME_ERROR) == 0u;
    if (p->cfg.mode == PFT_TPL_CIRCULAR) {
        done_circular(p, seq, t, ok);
    } else {
        done_oneshot(p, seq, t, ok);
    }
}

void pft_tpl_on_frame_counted(pft_tpl_port_t *p, uint32_t sensor_counter,
                              uint64_t timestamp_us, uint32_t flags)
{
    frame_done(p, sensor_counter, true, timestamp_us, flags);
}

void pft_tpl_on_frame_done(pft_tpl_port_t *p, uint64_t timestamp_us, bool ok)
{
    frame_done(p, 0u, false, timestamp_us, ok ? 0u : PFT_TPL_FRAME_ERROR);
}

/* Locked: frames lent now. */
static uint32_t count_lent(const pft_tpl_port_t *p)
{
    uint32_t lent = 0u;
    for (uint32_t i = 0; i < p->cfg.nbuf; ++i) {
        lent += (p->state[i] == BUF_LENT) ? 1u : 0u;
    }
    return lent;
}

/* The READY buffer, marked LENT, with its seq and time; -1 if none. */
static int32_t take_ready(pft_tpl_port_t *p, uint32_t *seq, uint64_t *ts)
{
    int32_t got = -1;
    lock(p);
    for (uint32_t i = 0; i < p->cfg.nbuf; ++i) {
        if (p->state[i] == BUF_READY) {
            p->state[i] = BUF_LENT;
            *seq = p->seq[i];
            *ts = p->ts[i];
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
    lock(p);
    uint8_t run = p->run;
    uint32_t lent = count_lent(p);
    unlock(p);
    /* one-shot: one buffer always stays with the camera, so capture goes on while the
     * consumer holds frames; circular: the sink takes frames when every buffer is held */
    uint32_t limit = (p->cfg.mode == PFT_TPL_CIRCULAR) ? p->cfg.nbuf : p->cfg.nbuf - 1u;
    if (run == RUN_IDLE || lent >= limit) {
        return PFT_ERR_STATE; /* not started, or a consumer bug: release first */
    }
    uint32_t seq = 0u;
    uint64_t ts = 0u;
    int32_t b = take_ready(p, &seq, &ts);
    if (b < 0) {
        if (run == RUN_STOPPED) {
            return PFT_ERR_EOF;
        }
        /* woken or not, look again: a frame that arrived just as the wait gave up is taken */
        (void)p->drv.wait_frame(p->drv.drv, timeout_ms);
        b = take_ready(p, &seq, &ts);
        if (b < 0) {
            /* stopped while waiting: the end; else no frame in time, or the one that woke
             * us was lost (transfer error, sink, overrun) */
            return (p->run == RUN_STOPPED) ? PFT_ERR_EOF : PFT_ERR_TIMEOUT;
        }
    }
    uint32_t i = (uint32_t)b;
    if (p->drv.cache_invalidate != NULL) {
        p->drv.cache_invalidate(p->drv.drv, p->cfg.bufs[i], p->bytes);
    }
    out->data = p->cfg.bufs[i];
    out->width = p->cfg.width;
    out->height = p->cfg.height;
    out->stride_bytes = p->cfg.stride;
    out->format = p->cfg.format;
    out->bit_depth = p->cfg.bit_depth;
    out->seq = seq;
    out->timestamp_us = ts;
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
    for (uint32_t i = 0; frame != NULL && i < p->cfg.nbuf; ++i) {
        if (frame->data == (const void *)p->cfg.bufs[i] && p->state[i] == BUF_LENT) {
            p->state[i] = BUF_FREE;
            found = true;
            /* one-shot camera paused for want of a buffer: resume it (circular: the ISR
             * gives this buffer to the DMA at the next frame end) */
            if (p->cfg.mode == PFT_TPL_ONESHOT && p->run == RUN_ON && p->dma_buf < 0) {
                start_next_locked(p);
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

pft_status_t pft_tpl_get_stats(pft_tpl_port_t *p, pft_tpl_stats_t *out)
{
    if (p == NULL || out == NULL) {
        return PFT_ERR_INVAL;
    }
    lock(p);
    out->completed = p->completed;
    out->overruns = p->overruns;
    out->sink_frames = p->sink_frames;
    out->dma_errors = p->dma_errors;
    out->counter_repeats = p->counter_repeats;
    out->bad_releases = p->bad_releases;
    out->lent = count_lent(p);
    unlock(p);
    return PFT_OK;
}
