/*
 * Ring-buffer frame source over caller memory, with fault injection (see pft_port_mem.h).
 * It never blocks: with nothing queued, acquire returns PFT_ERR_TIMEOUT at once (or
 * PFT_ERR_EOF once closed), whatever timeout_ms says.
 */
#include <string.h>

#include "pft/pft_port_mem.h"

enum { SLOT_FREE = 0, SLOT_WRITING = 1, SLOT_QUEUED = 2, SLOT_LENT = 3 };

#define PPM_ONE 1000000u

static uint32_t xorshift32(uint32_t *s)
{
    uint32_t x = *s;
    x ^= x << 13;
    x ^= x >> 17;
    x ^= x << 5;
    *s = x;
    return x;
}

pft_status_t pft_mem_source_init(pft_mem_source_t *m, const pft_mem_config_t *cfg)
{
    if (m == NULL || cfg == NULL || cfg->buffer == NULL) {
        return PFT_ERR_INVAL;
    }
    uint32_t bpp = pft_pixfmt_bytes(cfg->format);
    if (cfg->slots == 0u || cfg->slots > PFT_MEM_MAX_SLOTS || cfg->width == 0u ||
        cfg->height == 0u || bpp == 0u || cfg->max_lent > cfg->slots ||
        (cfg->format == PFT_PIX_U16 && cfg->bit_depth > 16u)) {
        return PFT_ERR_INVAL;
    }
    uint32_t row = (uint32_t)cfg->width * bpp;
    uint32_t stride = (cfg->stride_bytes == 0u) ? row : cfg->stride_bytes;
    if (stride < row) {
        return PFT_ERR_INVAL;
    }
    uint64_t ppm = 0u;
    for (uint32_t k = 1u; k < (uint32_t)PFT_FAULT_COUNT; ++k) {
        ppm += cfg->faults.prob_ppm[k];
    }
    if (ppm > PPM_ONE || (cfg->faults.at_count > 0u && cfg->faults.at == NULL)) {
        return PFT_ERR_INVAL;
    }
    uint64_t slot_bytes = (uint64_t)stride * cfg->height;
    if (slot_bytes > 0xFFFFFFFFu) {
        return PFT_ERR_INVAL;
    }
    if ((uint64_t)cfg->buffer_bytes < slot_bytes * cfg->slots) {
        return PFT_ERR_NOMEM;
    }
    memset(m, 0, sizeof *m);
    m->cfg = *cfg;
    m->cfg.stride_bytes = stride;
    if (m->cfg.max_lent == 0u) {
        m->cfg.max_lent = cfg->slots;
    }
    m->base = (uint8_t *)cfg->buffer;
    m->slot_bytes = (uint32_t)slot_bytes;
    m->next_seq = cfg->first_seq;
    m->rng = (cfg->faults.seed != 0u) ? cfg->faults.seed : 0x9E3779B9u;
    m->writing = -1;
    return PFT_OK;
}

pft_frame_source_t pft_mem_as_source(pft_mem_source_t *m)
{
    pft_frame_source_t s;
    s.ctx = m;
    s.acquire = pft_mem_acquire;
    s.release = pft_mem_release;
    return s;
}

pft_status_t pft_mem_write_begin(pft_mem_source_t *m, void **pixels)
{
    if (m == NULL || pixels == NULL) {
        return PFT_ERR_INVAL;
    }
    *pixels = NULL;
    if (m->writing >= 0 || m->closed) {
        return PFT_ERR_STATE;
    }
    for (uint32_t i = 0; i < m->cfg.slots; ++i) {
        if (m->state[i] == SLOT_FREE) {
            m->state[i] = SLOT_WRITING;
            m->writing = (int32_t)i;
            *pixels = m->base + (size_t)i * m->slot_bytes;
            return PFT_OK;
        }
    }
    /* ring full: the camera would drop this frame; its seq is gone */
    m->stats.overruns++;
    m->next_seq++;
    return PFT_ERR_NOMEM;
}

/* The fault of the frame with sequence number seq: schedule first, else the dice. The dice
 * are thrown for every frame, so the random plan does not depend on the schedule. */
static pft_fault_kind_t decide_fault(pft_mem_source_t *m, uint32_t seq)
{
    const pft_mem_faults_t *f = &m->cfg.faults;
    uint32_t r = xorshift32(&m->rng) % PPM_ONE;
    for (uint32_t i = 0; i < f->at_count; ++i) {
        if (f->at[i].seq == seq) {
            return f->at[i].kind;
        }
    }
    uint32_t acc = 0u;
    for (uint32_t k = 1u; k < (uint32_t)PFT_FAULT_COUNT; ++k) {
        acc += f->prob_ppm[k];
        if (r < acc) {
            return (pft_fault_kind_t)k;
        }
    }
    return PFT_FAULT_NONE;
}

pft_status_t pft_mem_write_commit(pft_mem_source_t *m, uint64_t timestamp_us)
{
    if (m == NULL) {
        return PFT_ERR_INVAL;
    }
    if (m->writing < 0) {
        return PFT_ERR_STATE;
    }
    uint32_t i = (uint32_t)m->writing;
    m->writing = -1;
    uint32_t seq = m->next_seq;
    m->next_seq++;
    m->stats.pushed++;
    pft_fault_kind_t k = decide_fault(m, seq);
    if ((uint32_t)k >= (uint32_t)PFT_FAULT_COUNT) {
        k = PFT_FAULT_NONE;
    }
    if (k != PFT_FAULT_NONE) {
        m->stats.injected[k]++;
    }
    if (k == PFT_FAULT_DROP) {
        m->state[i] = SLOT_FREE;
        return PFT_OK;
    }
    m->state[i] = SLOT_QUEUED;
    m->seq[i] = seq;
    m->ts[i] = timestamp_us;
    m->fault[i] = (uint8_t)k;
    m->fault_served[i] = 0u;
    return PFT_OK;
}

pft_status_t pft_mem_write_abort(pft_mem_source_t *m)
{
    if (m == NULL) {
        return PFT_ERR_INVAL;
    }
    if (m->writing < 0) {
        return PFT_ERR_STATE;
    }
    m->state[(uint32_t)m->writing] = SLOT_FREE;
    m->writing = -1;
    return PFT_OK;
}

pft_status_t pft_mem_push(pft_mem_source_t *m, const void *pixels, uint32_t src_stride,
                          uint64_t timestamp_us)
{
    if (m == NULL || pixels == NULL) {
        return PFT_ERR_INVAL;
    }
    uint32_t row = (uint32_t)m->cfg.width * pft_pixfmt_bytes(m->cfg.format);
    uint32_t in_stride = (src_stride == 0u) ? row : src_stride;
    if (in_stride < row) {
        return PFT_ERR_INVAL;
    }
    void *dst = NULL;
    pft_status_t st = pft_mem_write_begin(m, &dst);
    if (st != PFT_OK) {
        return st;
    }
    const uint8_t *s = (const uint8_t *)pixels;
    uint8_t *d = (uint8_t *)dst;
    for (uint32_t y = 0; y < m->cfg.height; ++y) {
        memcpy(d + (size_t)y * m->cfg.stride_bytes, s + (size_t)y * in_stride, row);
    }
    return pft_mem_write_commit(m, timestamp_us);
}

void pft_mem_close(pft_mem_source_t *m)
{
    if (m != NULL) {
        m->closed = true;
    }
}

uint32_t pft_mem_queued(const pft_mem_source_t *m)
{
    uint32_t n = 0u;
    if (m != NULL) {
        for (uint32_t i = 0; i < m->cfg.slots; ++i) {
            n += (m->state[i] == SLOT_QUEUED) ? 1u : 0u;
        }
    }
    return n;
}

/* Oldest queued slot (seq order, wrap-safe), or -1. */
static int32_t oldest_queued(const pft_mem_source_t *m)
{
    int32_t best = -1;
    for (uint32_t i = 0; i < m->cfg.slots; ++i) {
        if (m->state[i] != SLOT_QUEUED) {
            continue;
        }
        if (best < 0 || (int32_t)(m->seq[i] - m->seq[(uint32_t)best]) < 0) {
            best = (int32_t)i;
        }
    }
    return best;
}

pft_status_t pft_mem_acquire(void *ctx, pft_frame_t *out, uint32_t timeout_ms)
{
    pft_mem_source_t *m = (pft_mem_source_t *)ctx;
    (void)timeout_ms;
    if (m == NULL || out == NULL) {
        return PFT_ERR_INVAL;
    }
    memset(out, 0, sizeof *out);
    if (m->stats.lent >= m->cfg.max_lent) {
        m->stats.state_errors++;
        return PFT_ERR_STATE;
    }
    int32_t s = oldest_queued(m);
    /* pull the producer until a frame is queued (a dropped frame leaves the queue empty) */
    for (uint32_t n = 0; s < 0 && !m->closed && m->cfg.fill != NULL && n < PFT_MEM_FILL_CALLS;
         ++n) {
        pft_status_t st = m->cfg.fill(m->cfg.fill_ctx, m);
        if (st == PFT_ERR_EOF) {
            m->closed = true;
        } else if (st != PFT_OK) {
            return st;
        } else {
            /* the producer may have queued a frame: look again */
        }
        s = oldest_queued(m);
    }
    if (s < 0) {
        return m->closed ? PFT_ERR_EOF : PFT_ERR_TIMEOUT;
    }
    uint32_t i = (uint32_t)s;
    pft_fault_kind_t k = (pft_fault_kind_t)m->fault[i];
    if (k == PFT_FAULT_TIMEOUT && m->fault_served[i] == 0u) {
        m->fault_served[i] = 1u; /* this time nothing arrives; next time it does */
        return PFT_ERR_TIMEOUT;
    }
    out->data = m->base + (size_t)i * m->slot_bytes;
    out->width = m->cfg.width;
    out->height = m->cfg.height;
    out->stride_bytes = m->cfg.stride_bytes;
    out->format = m->cfg.format;
    out->bit_depth = m->cfg.bit_depth;
    out->timestamp_us = m->ts[i];
    out->seq = m->seq[i];
    switch (k) {
    case PFT_FAULT_SHORT:
        if (m->cfg.height >= 2u) {
            uint16_t h = m->cfg.faults.short_height;
            out->height = (h != 0u && h < m->cfg.height) ? h : (uint16_t)(m->cfg.height / 2u);
        } else {
            out->stride_bytes = (uint32_t)m->cfg.width * pft_pixfmt_bytes(m->cfg.format) - 1u;
        }
        break;
    case PFT_FAULT_CORRUPT:
        if ((m->seq[i] & 1u) == 0u) {
            out->format = (pft_pixfmt_t)0;
        } else {
            out->width = 0u;
        }
        break;
    case PFT_FAULT_LATE:
        out->timestamp_us += (m->cfg.faults.late_us != 0u) ? m->cfg.faults.late_us : 1000000u;
        break;
    default:
        break;
    }
    m->state[i] = SLOT_LENT;
    m->stats.acquired++;
    m->stats.lent++;
    if (m->stats.lent > m->stats.lent_max) {
        m->stats.lent_max = m->stats.lent;
    }
    return PFT_OK;
}

void pft_mem_release(void *ctx, const pft_frame_t *frame)
{
    pft_mem_source_t *m = (pft_mem_source_t *)ctx;
    if (m == NULL) {
        return;
    }
    if (frame != NULL && frame->data != NULL) {
        for (uint32_t i = 0; i < m->cfg.slots; ++i) {
            if (frame->data == (const void *)(m->base + (size_t)i * m->slot_bytes)) {
                if (m->state[i] == SLOT_LENT) {
                    m->state[i] = SLOT_FREE;
                    m->stats.released++;
                    m->stats.lent--;
                    return;
                }
                break;
            }
        }
    }
    m->stats.bad_releases++;
}
