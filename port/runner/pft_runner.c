/*
 * Frame source helpers and the runner: pull a frame, check it, push it to the consumer,
 * always release it, count what went wrong, keep going after recoverable faults.
 */
#include <string.h>

#include "pft/pft_port.h"

pft_status_t pft_source_acquire(const pft_frame_source_t *src, pft_frame_t *out,
                                uint32_t timeout_ms)
{
    if (out != NULL) {
        memset(out, 0, sizeof *out);
    }
    if (src == NULL || src->acquire == NULL || src->release == NULL || out == NULL) {
        return PFT_ERR_INVAL;
    }
    pft_status_t st = src->acquire(src->ctx, out, timeout_ms);
    if (st != PFT_OK) {
        memset(out, 0, sizeof *out);
    }
    return st;
}

pft_status_t pft_source_release(const pft_frame_source_t *src, const pft_frame_t *frame)
{
    if (src == NULL || src->release == NULL || frame == NULL || frame->data == NULL) {
        return PFT_ERR_INVAL;
    }
    src->release(src->ctx, frame);
    return PFT_OK;
}

/* Mask of every format pft_pixfmt_bytes knows. */
static uint32_t known_formats(void)
{
    return PFT_FMT_BIT(PFT_PIX_U8) | PFT_FMT_BIT(PFT_PIX_U16) | PFT_FMT_BIT(PFT_PIX_F32) |
           PFT_FMT_BIT(PFT_PIX_RGB888) | PFT_FMT_BIT(PFT_PIX_BGR888);
}

enum { VERDICT_OK = 0, VERDICT_SHORT = 1, VERDICT_CORRUPT = 2 };

/* Sorts a frame into good / short (smaller than expected) / corrupt (bad descriptor). */
static int classify(const pft_frame_t *f, uint16_t w, uint16_t h, uint32_t mask, bool finite)
{
    uint32_t bpp = pft_pixfmt_bytes(f->format);
    if (f->data == NULL || bpp == 0u || f->width == 0u || f->height == 0u ||
        (mask & PFT_FMT_BIT(f->format)) == 0u ||
        (f->format == PFT_PIX_U16 && f->bit_depth > 16u)) {
        return VERDICT_CORRUPT;
    }
    if (f->stride_bytes < (uint32_t)f->width * bpp) {
        return VERDICT_SHORT;
    }
    if ((w != 0u && f->width != w) || (h != 0u && f->height != h)) {
        bool smaller = (w == 0u || f->width <= w) && (h == 0u || f->height <= h);
        return smaller ? VERDICT_SHORT : VERDICT_CORRUPT;
    }
    /* the library's own check stays the authority */
    if (pft_frame_check(f, w, h, mask) != PFT_OK) {
        return VERDICT_CORRUPT;
    }
    if (finite && pft_frame_check_finite(f) != PFT_OK) {
        return VERDICT_CORRUPT;
    }
    return VERDICT_OK;
}

static void fault(const pft_runner_hooks_t *hooks, pft_status_t st, uint32_t seq)
{
    if (hooks != NULL && hooks->on_fault != NULL) {
        hooks->on_fault(hooks->ctx, st, seq);
    }
}

static uint64_t now(const pft_runner_hooks_t *hooks)
{
    return (hooks != NULL && hooks->now_us != NULL) ? hooks->now_us(hooks->ctx) : 0u;
}

pft_status_t pft_runner_run(const pft_frame_source_t *src, pft_consumer_fn consumer,
                            void *consumer_ctx, const pft_runner_hooks_t *hooks,
                            const pft_runner_config_t *cfg, pft_runner_stats_t *stats)
{
    if (stats == NULL) {
        return PFT_ERR_INVAL;
    }
    memset(stats, 0, sizeof *stats);
    if (src == NULL || src->acquire == NULL || src->release == NULL || consumer == NULL) {
        stats->stop = PFT_ERR_INVAL;
        return PFT_ERR_INVAL;
    }
    pft_runner_config_t c;
    if (cfg != NULL) {
        c = *cfg;
    } else {
        memset(&c, 0, sizeof c);
    }
    uint32_t mask = (c.fmt_mask != 0u) ? c.fmt_mask : known_formats();
    uint32_t attempt_limit = c.max_attempts;
    if (attempt_limit == 0u && c.max_frames != 0u) {
        uint64_t lim = 16u * (uint64_t)c.max_frames + 64u;
        attempt_limit = (lim > 0xFFFFFFFFu) ? 0xFFFFFFFFu : (uint32_t)lim;
    }
    uint16_t exp_w = c.width;
    uint16_t exp_h = c.height;
    bool have_seq = false;
    bool have_ts = false;
    uint32_t last_seq = 0u;
    uint64_t last_ts = 0u;
    uint32_t consecutive = 0u;
    pft_status_t ret = PFT_OK;
    pft_status_t stop = PFT_OK;

    for (;;) {
        if (c.max_frames != 0u && stats->frames >= c.max_frames) {
            stop = PFT_OK;
            break;
        }
        if (attempt_limit != 0u && stats->attempts >= attempt_limit) {
            stop = PFT_OK;
            break;
        }
        if (stats->attempts == 0xFFFFFFFFu) { /* counters would wrap: the loop is bounded */
            stop = PFT_OK;
            break;
        }
        stats->attempts++;

        pft_frame_t f;
        pft_status_t st = pft_source_acquire(src, &f, c.timeout_ms);
        if (st == PFT_ERR_EOF) {
            stop = PFT_ERR_EOF;
            break;
        }
        if (st != PFT_OK) {
            if (st == PFT_ERR_TIMEOUT) {
                stats->timeouts++;
            } else if (st == PFT_ERR_IO) {
                stats->io_errors++;
            } else if (st == PFT_ERR_FORMAT) {
                stats->format_errors++;
            } else {
                stop = st; /* INVAL, STATE, NOMEM, RANGE, unknown: the port is misused */
                ret = st;
                break;
            }
            fault(hooks, st, 0u);
            consecutive++;
            if (c.max_consecutive_errors != 0u && consecutive >= c.max_consecutive_errors) {
                stop = st;
                ret = st;
                break;
            }
            continue;
        }
        stats->acquired++;

        /* sequence: unsigned difference handles wrap-around */
        if (have_seq) {
            uint32_t d = f.seq - last_seq;
            if (d == 0u || d > 0x80000000u) {
                stats->seq_errors++;
                fault(hooks, PFT_ERR_RANGE, f.seq);
            } else {
                if (d > 1u) {
                    stats->dropped += d - 1u;
                    fault(hooks, PFT_ERR_RANGE, f.seq);
                }
                last_seq = f.seq;
            }
        } else {
            have_seq = true;
            last_seq = f.seq;
        }

        int verdict = classify(&f, exp_w, exp_h, mask, c.check_finite);
        if (verdict != VERDICT_OK) {
            if (verdict == VERDICT_SHORT) {
                stats->short_frames++;
            } else {
                stats->corrupt++;
            }
            uint32_t seq = f.seq;
            src->release(src->ctx, &f); /* always, even for a NULL-data descriptor */
            stats->released++;
            fault(hooks, PFT_ERR_FORMAT, seq);
            consecutive++;
            if (c.max_consecutive_errors != 0u && consecutive >= c.max_consecutive_errors) {
                stop = PFT_ERR_FORMAT;
                ret = PFT_ERR_FORMAT;
                break;
            }
            continue;
        }
        if (exp_w == 0u) {
            exp_w = f.width;
        }
        if (exp_h == 0u) {
            exp_h = f.height;
        }
        consecutive = 0u;

        /* a step above max_interval_us is late; a step back is counted apart, and either way
         * the clock follows the newest frame, so one odd timestamp costs one count */
        if (have_ts) {
            if (f.timestamp_us < last_ts) {
                stats->ts_backwards++;
                fault(hooks, PFT_ERR_TIMEOUT, f.seq);
            } else if (c.max_interval_us != 0u && f.timestamp_us - last_ts > c.max_interval_us) {
                stats->late++;
                fault(hooks, PFT_ERR_TIMEOUT, f.seq);
            }
        }
        last_ts = f.timestamp_us;
        have_ts = true;

        if (hooks != NULL && hooks->on_frame_begin != NULL) {
            hooks->on_frame_begin(hooks->ctx, &f);
        }
        uint64_t t0 = now(hooks);
        pft_status_t cs = consumer(consumer_ctx, &f);
        uint64_t t1 = now(hooks);
        uint64_t dt = (t1 >= t0) ? t1 - t0 : 0u;
        if (hooks != NULL && hooks->on_frame_end != NULL) {
            hooks->on_frame_end(hooks->ctx, &f, cs, dt);
        }
        uint32_t seq = f.seq;
        src->release(src->ctx, &f); /* always, even for a NULL-data descriptor */
        stats->released++;

        if (stats->frames == 0u || dt < stats->time_min_us) {
            stats->time_min_us = dt;
        }
        if (dt > stats->time_max_us) {
            stats->time_max_us = dt;
        }
        stats->time_total_us += dt;
        stats->frames++;

        if (cs == PFT_ERR_EOF) {
            stop = PFT_ERR_EOF;
            break;
        }
        if (cs != PFT_OK) {
            stats->consumer_errors++;
            fault(hooks, cs, seq);
        }
    }
    stats->width = exp_w;
    stats->height = exp_h;
    stats->stop = stop;
    return ret;
}
