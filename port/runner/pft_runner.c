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

/* State of one run, shared by its steps. */
typedef struct {
    const pft_frame_source_t *src;
    pft_consumer_fn consumer;
    void *consumer_ctx;
    const pft_runner_hooks_t *hooks;
    pft_runner_config_t c;
    pft_runner_stats_t *stats;
    uint32_t mask;          /* accepted formats */
    uint32_t attempt_limit; /* 0: none */
    uint16_t exp_w, exp_h;  /* expected geometry (0: not locked yet) */
    bool have_seq, have_ts;
    uint32_t last_seq;
    uint64_t last_ts;
    uint32_t consecutive;   /* failed iterations in a row */
    pft_status_t ret;       /* returned by pft_runner_run */
    pft_status_t stop;      /* stats->stop */
} run_t;

/* What the loop does after a step. */
typedef enum { STEP_GO_ON = 0, STEP_NEXT = 1, STEP_STOP = 2 } step_t;

/* Copies the configuration and derives the format mask and the acquire bound. */
static void run_setup(run_t *r, const pft_runner_config_t *cfg)
{
    if (cfg != NULL) {
        r->c = *cfg;
    } else {
        memset(&r->c, 0, sizeof r->c);
    }
    r->mask = (r->c.fmt_mask != 0u) ? r->c.fmt_mask : known_formats();
    r->attempt_limit = r->c.max_attempts;
    if (r->attempt_limit == 0u && r->c.max_frames != 0u) {
        uint64_t lim = 16u * (uint64_t)r->c.max_frames + 64u;
        r->attempt_limit = (lim > 0xFFFFFFFFu) ? 0xFFFFFFFFu : (uint32_t)lim;
    }
    r->exp_w = r->c.width;
    r->exp_h = r->c.height;
    r->ret = PFT_OK;
    r->stop = PFT_OK;
}

/* max_frames, max_attempts or the counter bound reached: a normal end. */
static bool run_limit_reached(const run_t *r)
{
    const pft_runner_stats_t *s = r->stats;
    if (r->c.max_frames != 0u && s->frames >= r->c.max_frames) {
        return true;
    }
    if (r->attempt_limit != 0u && s->attempts >= r->attempt_limit) {
        return true;
    }
    return s->attempts == 0xFFFFFFFFu; /* counters would wrap: the loop is bounded */
}

/* One more failed iteration; stops the run with `st` when max_consecutive_errors is reached. */
static step_t run_count_failure(run_t *r, pft_status_t st)
{
    r->consecutive++;
    if (r->c.max_consecutive_errors != 0u && r->consecutive >= r->c.max_consecutive_errors) {
        r->stop = st;
        r->ret = st;
        return STEP_STOP;
    }
    return STEP_NEXT;
}

/* Acquires one frame. EOF ends the run; TIMEOUT/IO/FORMAT are counted (next iteration);
 * anything else is fatal. */
static step_t run_acquire(run_t *r, pft_frame_t *f)
{
    r->stats->attempts++;
    pft_status_t st = pft_source_acquire(r->src, f, r->c.timeout_ms);
    if (st == PFT_OK) {
        r->stats->acquired++;
        return STEP_GO_ON;
    }
    if (st == PFT_ERR_EOF) {
        r->stop = PFT_ERR_EOF;
        return STEP_STOP;
    }
    if (st == PFT_ERR_TIMEOUT) {
        r->stats->timeouts++;
    } else if (st == PFT_ERR_IO) {
        r->stats->io_errors++;
    } else if (st == PFT_ERR_FORMAT) {
        r->stats->format_errors++;
    } else {
        r->stop = st; /* INVAL, STATE, NOMEM, RANGE, unknown: the port is misused */
        r->ret = st;
        return STEP_STOP;
    }
    fault(r->hooks, st, 0u);
    return run_count_failure(r, st);
}

/* Sequence check: gaps are dropped frames, repeats and steps back are seq errors (an unsigned
 * difference handles wrap-around). */
static void run_check_seq(run_t *r, const pft_frame_t *f)
{
    if (!r->have_seq) {
        r->have_seq = true;
        r->last_seq = f->seq;
        return;
    }
    uint32_t d = f->seq - r->last_seq;
    if (d == 0u || d > 0x80000000u) {
        r->stats->seq_errors++;
        fault(r->hooks, PFT_ERR_RANGE, f->seq);
        return;
    }
    if (d > 1u) {
        r->stats->dropped += d - 1u;
        fault(r->hooks, PFT_ERR_RANGE, f->seq);
    }
    r->last_seq = f->seq;
}

/* Descriptor check. A rejected frame is counted and released here (next iteration); a good
 * one locks the geometry if it was not given. */
static step_t run_check_frame(run_t *r, pft_frame_t *f)
{
    int verdict = classify(f, r->exp_w, r->exp_h, r->mask, r->c.check_finite);
    if (verdict != VERDICT_OK) {
        if (verdict == VERDICT_SHORT) {
            r->stats->short_frames++;
        } else {
            r->stats->corrupt++;
        }
        uint32_t seq = f->seq;
        r->src->release(r->src->ctx, f); /* always, even for a NULL-data descriptor */
        r->stats->released++;
        fault(r->hooks, PFT_ERR_FORMAT, seq);
        return run_count_failure(r, PFT_ERR_FORMAT);
    }
    if (r->exp_w == 0u) {
        r->exp_w = f->width;
    }
    if (r->exp_h == 0u) {
        r->exp_h = f->height;
    }
    r->consecutive = 0u;
    return STEP_GO_ON;
}

/* Timestamp check: a step above max_interval_us is late; a step back is counted apart, and
 * either way the clock follows the newest frame, so one odd timestamp costs one count. */
static void run_check_time(run_t *r, const pft_frame_t *f)
{
    if (r->have_ts) {
        if (f->timestamp_us < r->last_ts) {
            r->stats->ts_backwards++;
            fault(r->hooks, PFT_ERR_TIMEOUT, f->seq);
        } else if (r->c.max_interval_us != 0u &&
                   f->timestamp_us - r->last_ts > r->c.max_interval_us) {
            r->stats->late++;
            fault(r->hooks, PFT_ERR_TIMEOUT, f->seq);
        } else {
            /* on time */
        }
    }
    r->last_ts = f->timestamp_us;
    r->have_ts = true;
}

/* Hands the frame to the consumer between the hooks, times it, releases it and counts it.
 * The consumer's PFT_ERR_EOF ends the run; its other errors are counted. */
static step_t run_consume(run_t *r, pft_frame_t *f)
{
    const pft_runner_hooks_t *hooks = r->hooks;
    pft_runner_stats_t *s = r->stats;
    if (hooks != NULL && hooks->on_frame_begin != NULL) {
        hooks->on_frame_begin(hooks->ctx, f);
    }
    uint64_t t0 = now(hooks);
    pft_status_t cs = r->consumer(r->consumer_ctx, f);
    uint64_t t1 = now(hooks);
    uint64_t dt = (t1 >= t0) ? t1 - t0 : 0u;
    if (hooks != NULL && hooks->on_frame_end != NULL) {
        hooks->on_frame_end(hooks->ctx, f, cs, dt);
    }
    uint32_t seq = f->seq;
    r->src->release(r->src->ctx, f); /* always, even for a NULL-data descriptor */
    s->released++;

    if (s->frames == 0u || dt < s->time_min_us) {
        s->time_min_us = dt;
    }
    if (dt > s->time_max_us) {
        s->time_max_us = dt;
    }
    s->time_total_us += dt;
    s->frames++;

    if (cs == PFT_ERR_EOF) {
        r->stop = PFT_ERR_EOF;
        return STEP_STOP;
    }
    if (cs != PFT_OK) {
        s->consumer_errors++;
        fault(hooks, cs, seq);
    }
    return STEP_GO_ON;
}

/* One iteration: acquire -> sequence -> descriptor -> timestamp -> consumer + release. */
static step_t run_iteration(run_t *r)
{
    pft_frame_t f;
    step_t k = run_acquire(r, &f);
    if (k != STEP_GO_ON) {
        return k;
    }
    run_check_seq(r, &f);
    k = run_check_frame(r, &f);
    if (k != STEP_GO_ON) {
        return k;
    }
    run_check_time(r, &f);
    return run_consume(r, &f);
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
    run_t r;
    memset(&r, 0, sizeof r);
    r.src = src;
    r.consumer = consumer;
    r.consumer_ctx = consumer_ctx;
    r.hooks = hooks;
    r.stats = stats;
    run_setup(&r, cfg);
    /* bounded: every iteration makes one acquire, and run_limit_reached stops at the attempt
     * limit (or at the counter's maximum when there is none) */
    while (!run_limit_reached(&r)) {
        if (run_iteration(&r) == STEP_STOP) {
            break;
        }
    }
    stats->width = r.exp_w;
    stats->height = r.exp_h;
    stats->stop = r.stop;
    return r.ret;
}
