/*
 * Port conformance check (see pft_port_conformance.h for the procedure and the rules).
 */
#include <stdarg.h>
#include <stdio.h>
#include <string.h>

#include "pft_port_conformance.h"

/* Acquire attempts per frame while a source answers TIMEOUT / IO / FORMAT (with a tick in
 * between), and acquires made while draining a starved source. */
#define RETRIES 16u
#define DRAIN_MAX (PFT_CONF_MAX_HELD + 8u)
/* Frames the lend probe holds for a source without a lend limit. */
#define NO_LIMIT_PROBE 4u
/* Extra acquires allowed after the end, beyond the attempt bound. */
#define AFTER_END_CALLS 4u
/* Rule argument of the lend probe meaning "do not report lend-rule failures". */
#define SILENT PFT_CONF_RULES

typedef struct {
    pft_frame_t f;
    uint32_t sum;
    bool readable;  /* descriptor valid: pixels may be read */
    bool reported;  /* a change of its pixels was already reported */
} lent_t;

typedef struct {
    const pft_frame_source_t *src;
    pft_conf_spec_t s;
    pft_conf_report_t *r;
    uint16_t w, h;          /* expected size (0: not locked yet) */
    uint32_t mask;
    bool have_seq, have_ts;
    uint32_t last_seq;
    uint64_t last_ts;
    uint32_t attempt_limit;
    bool exhausted;         /* attempt bound reached */
    bool stop;              /* a status the check cannot go on after */
    bool have_released;     /* `released` holds a copy of a frame given back */
    pft_frame_t released;
    lent_t held[PFT_CONF_MAX_HELD];
    uint32_t nheld;
    uint8_t foreign[16];    /* memory of no source: the foreign release's pixels */
} conf_t;

static const char *const rule_names[PFT_CONF_RULES] = {
    "spec", "descriptor", "seq", "timestamp", "eof", "release",
    "lend", "timeout", "data", "status", "count"};

const char *pft_conf_rule_name(pft_conf_rule_t rule)
{
    return ((uint32_t)rule < (uint32_t)PFT_CONF_RULES) ? rule_names[rule] : "?";
}

static void violate(conf_t *c, pft_conf_rule_t rule, const char *fmt, ...)
{
    if ((uint32_t)rule >= (uint32_t)PFT_CONF_RULES) {
        return; /* SILENT */
    }
    pft_conf_report_t *r = c->r;
    if (r->total == 0u) {
        r->first_rule = rule;
        int n = snprintf(r->first, sizeof r->first, "%s: ", rule_names[rule]);
        if (n > 0 && (size_t)n < sizeof r->first) {
            va_list ap;
            va_start(ap, fmt);
            (void)vsnprintf(r->first + n, sizeof r->first - (size_t)n, fmt, ap);
            va_end(ap);
        }
    }
    r->violations[rule]++;
    r->total++;
}

static uint32_t known_formats(void)
{
    return PFT_FMT_BIT(PFT_PIX_U8) | PFT_FMT_BIT(PFT_PIX_U16) | PFT_FMT_BIT(PFT_PIX_F32) |
           PFT_FMT_BIT(PFT_PIX_RGB888) | PFT_FMT_BIT(PFT_PIX_BGR888);
}

static void tick(conf_t *c)
{
    if (c->s.tick != NULL) {
        c->s.tick(c->s.hook_ctx);
    }
}

static uint32_t source_bad_releases(conf_t *c)
{
    return (c->s.bad_releases != NULL) ? c->s.bad_releases(c->s.hook_ctx) : 0u;
}

/* FNV-1a over the pixel bytes of every row (padding excluded). */
static uint32_t checksum(const pft_frame_t *f)
{
    uint32_t h = 2166136261u;
    uint32_t row = (uint32_t)f->width * pft_pixfmt_bytes(f->format);
    for (uint32_t y = 0; y < f->height; ++y) {
        const uint8_t *p = pft_frame_row(f, y);
        for (uint32_t x = 0; x < row; ++x) {
            h = (h ^ p[x]) * 16777619u;
        }
    }
    return h;
}

/* One acquire through the validated helper; false (nothing called) once the bound is hit. */
static bool acquire_once(conf_t *c, pft_frame_t *f, pft_status_t *st, uint32_t extra)
{
    if (c->r->attempts >= c->attempt_limit + extra) {
        c->exhausted = true;
        return false;
    }
    c->r->attempts++;
    *st = pft_source_acquire(c->src, f, c->s.timeout_ms);
    return true;
}

/* Checks a frame just lent: descriptor, seq, timestamp; takes its checksum. */
static void on_lent(conf_t *c, const pft_frame_t *f, lent_t *l)
{
    pft_conf_report_t *r = c->r;
    l->f = *f;
    l->reported = false;
    l->readable = false;
    l->sum = 0u;
    r->frames++;
    if (pft_frame_check(f, c->w, c->h, c->mask) != PFT_OK) {
        violate(c, PFT_CONF_DESCRIPTOR,
                "frame seq %lu: data %s, %ux%u, stride %lu, format %d (expected %ux%u)",
                (unsigned long)f->seq, f->data != NULL ? "set" : "NULL", (unsigned)f->width,
                (unsigned)f->height, (unsigned long)f->stride_bytes, (int)f->format,
                (unsigned)c->w, (unsigned)c->h);
    } else {
        if (c->w == 0u) {
            c->w = f->width;
            c->h = f->height;
        }
        l->readable = true;
        l->sum = checksum(f);
    }
    if (c->have_seq) {
        uint32_t d = f->seq - c->last_seq;
        if (d == 0u || d > 0x80000000u) {
            violate(c, PFT_CONF_SEQ, "seq %lu after %lu", (unsigned long)f->seq,
                    (unsigned long)c->last_seq);
        } else {
            r->gaps += d - 1u;
            c->last_seq = f->seq;
        }
    } else {
        c->have_seq = true;
        c->last_seq = f->seq;
        r->first_seq = f->seq;
    }
    r->last_seq = c->last_seq;
    if (c->have_ts && f->timestamp_us < c->last_ts) {
        violate(c, PFT_CONF_TIMESTAMP, "frame seq %lu: timestamp %lu us after %lu us",
                (unsigned long)f->seq, (unsigned long)f->timestamp_us,
                (unsigned long)c->last_ts);
    }
    c->have_ts = true;
    if (f->timestamp_us > c->last_ts) {
        c->last_ts = f->timestamp_us;
    }
}

/* Pixels of a lent frame unchanged? Reports `rule` once per frame. */
static void verify(conf_t *c, lent_t *l, pft_conf_rule_t rule, const char *when)
{
    if (l->readable && !l->reported && checksum(&l->f) != l->sum) {
        l->reported = true;
        violate(c, rule, "pixels of frame seq %lu changed while lent (%s)",
                (unsigned long)l->f.seq, when);
    }
}

/* Gives a lent frame back (checked at release), remembers a copy for the double release. */
static void give_back(conf_t *c, lent_t *l)
{
    verify(c, l, PFT_CONF_DATA, "seen at release");
    c->src->release(c->src->ctx, &l->f); /* also a NULL-data descriptor: it was lent */
    if (l->f.data != NULL) {
        c->released = l->f;
        c->have_released = true;
    }
}

/* Releases something that is not lent; it must be refused (counted) or be a no-op. */
static void bad_release(conf_t *c, const pft_frame_t *f, const char *what)
{
    uint32_t before = source_bad_releases(c);
    c->src->release(c->src->ctx, f);
    c->r->bad_releases++;
    uint32_t after = source_bad_releases(c);
    if (c->s.bad_releases != NULL && after != before + 1u) {
        violate(c, PFT_CONF_RELEASE, "release of %s not refused (bad_releases %lu -> %lu)",
                what, (unsigned long)before, (unsigned long)after);
    }
}

static pft_frame_t foreign_frame(conf_t *c)
{
    pft_frame_t f;
    memset(&f, 0, sizeof f);
    f.data = c->foreign;
    f.width = 1u;
    f.height = 1u;
    f.stride_bytes = 1u;
    f.format = PFT_PIX_U8;
    f.seq = c->last_seq;
    return f;
}

/* Acquire with retries over TIMEOUT (tick in between) and IO / FORMAT; other statuses are
 * returned to the caller. Counts and reports what the spec does not allow. */
static pft_status_t acquire_retry(conf_t *c, pft_frame_t *f)
{
    pft_status_t st = PFT_ERR_TIMEOUT;
    for (uint32_t k = 0; k < RETRIES; ++k) {
        if (!acquire_once(c, f, &st, 0u)) {
            return PFT_ERR_TIMEOUT;
        }
        if (st == PFT_ERR_TIMEOUT) {
            c->r->timeouts++;
            if (!c->s.can_timeout) {
                violate(c, PFT_CONF_TIMEOUT, "PFT_ERR_TIMEOUT from a source that cannot time out");
            }
            tick(c);
        } else if (st == PFT_ERR_IO || st == PFT_ERR_FORMAT) {
            c->r->lost++;
            if (!c->s.may_lose) {
                violate(c, PFT_CONF_STATUS, "%s from a source that cannot lose frames",
                        pft_status_str(st));
            }
        } else {
            if (st == PFT_ERR_EOF) {
                c->r->ended = true;
            }
            return st;
        }
    }
    return st;
}

/* Memory of a readable lent frame, [lo, hi). */
static void span(const pft_frame_t *f, uintptr_t *lo, uintptr_t *hi)
{
    *lo = (uintptr_t)f->data;
    *hi = *lo + (uintptr_t)(f->height - 1u) * f->stride_bytes +
          (uintptr_t)f->width * pft_pixfmt_bytes(f->format);
}

/* Lends up to the limit and holds; one more must be PFT_ERR_STATE; the held pixels must not
 * change while time passes (and, with `foreign`, after a foreign release); gives all back.
 * Lend-rule failures are reported under `rule` (SILENT: not reported). */
static void lend_probe(conf_t *c, pft_conf_rule_t rule, bool foreign)
{
    bool limited = (c->s.max_lent != PFT_CONF_NO_LIMIT);
    uint32_t n = limited ? c->s.max_lent : NO_LIMIT_PROBE;
    c->nheld = 0u;
    while (c->nheld < n && !c->stop && !c->r->ended) {
        pft_frame_t f;
        pft_status_t st = acquire_retry(c, &f);
        if (st == PFT_OK) {
            lent_t *l = &c->held[c->nheld];
            on_lent(c, &f, l);
            for (uint32_t j = 0; l->readable && j < c->nheld; ++j) {
                uintptr_t a0, a1, b0, b1;
                span(&l->f, &a0, &a1);
                span(&c->held[j].f, &b0, &b1);
                if (c->held[j].readable && a0 < b1 && b0 < a1) {
                    violate(c, rule, "frames seq %lu and %lu lent at once share memory",
                            (unsigned long)c->held[j].f.seq, (unsigned long)l->f.seq);
                }
            }
            c->nheld++;
        } else if (st == PFT_ERR_STATE) {
            c->r->refused++;
            violate(c, rule, "acquire %lu refused with PFT_ERR_STATE, limit is %lu",
                    (unsigned long)(c->nheld + 1u), (unsigned long)n);
            break;
        } else if (st != PFT_ERR_EOF) {
            if (st != PFT_ERR_TIMEOUT) {
                violate(c, PFT_CONF_STATUS, "acquire returned %s", pft_status_str(st));
                c->stop = true;
            }
            break; /* no frame in RETRIES tries: not a lend-rule matter */
        }
    }
    if (limited && c->nheld == n && !c->stop && !c->r->ended) {
        tick(c); /* a frame may be waiting: only the limit can refuse now */
        pft_frame_t g;
        pft_status_t st = PFT_ERR_STATE;
        if (acquire_once(c, &g, &st, 0u)) {
            if (st == PFT_OK) {
                lent_t extra;
                on_lent(c, &g, &extra);
                violate(c, rule, "acquire %lu lent a frame, limit is %lu",
                        (unsigned long)(n + 1u), (unsigned long)n);
                give_back(c, &extra);
            } else if (st == PFT_ERR_STATE) {
                c->r->refused++;
            } else if (st == PFT_ERR_EOF) {
                c->r->ended = true;
            } else {
                violate(c, rule, "acquire %lu returned %s, expected PFT_ERR_STATE",
                        (unsigned long)(n + 1u), pft_status_str(st));
            }
        }
    }
    for (uint32_t t = 0; t < 2u; ++t) {
        tick(c);
        for (uint32_t j = 0; j < c->nheld; ++j) {
            verify(c, &c->held[j], PFT_CONF_DATA, "while held with others");
        }
    }
    if (foreign && c->nheld > 0u) {
        pft_frame_t ff = foreign_frame(c);
        bad_release(c, &ff, "a foreign frame while frames are lent");
        for (uint32_t t = 0; t < 2u; ++t) {
            tick(c);
            for (uint32_t j = 0; j < c->nheld; ++j) {
                verify(c, &c->held[j], PFT_CONF_RELEASE, "after a foreign release");
            }
        }
    }
    for (uint32_t j = 0; j < c->nheld; ++j) {
        give_back(c, &c->held[j]);
    }
    c->nheld = 0u;
}

/* Phase 2: releases of frames that are not lent, then the lend probe again. */
static void release_probe(conf_t *c, bool lend_ok)
{
    if (c->have_released) {
        pft_frame_t twice = c->released;
        bad_release(c, &twice, "a frame already released");
    }
    pft_frame_t ff = foreign_frame(c);
    bad_release(c, &ff, "a foreign frame");
    lend_probe(c, lend_ok ? PFT_CONF_RELEASE : SILENT, true);
}

/* Phase 3: no frame coming; acquire must time out (after lending what was waiting). */
static void timeout_probe(conf_t *c, bool lend_ok)
{
    c->s.starve(c->s.hook_ctx, true);
    bool timed_out = false;
    for (uint32_t k = 0; k < DRAIN_MAX && !c->stop; ++k) {
        pft_frame_t f;
        pft_status_t st = PFT_ERR_TIMEOUT;
        if (!acquire_once(c, &f, &st, 0u)) {
            break;
        }
        if (st == PFT_OK) {
            lent_t l;
            on_lent(c, &f, &l);
            give_back(c, &l);
        } else if (st == PFT_ERR_TIMEOUT) {
            c->r->timeouts++;
            timed_out = true;
            break;
        } else if (st == PFT_ERR_EOF) {
            c->r->ended = true; /* a finite source may end here */
            break;
        } else {
            violate(c, PFT_CONF_TIMEOUT, "starved source returned %s, expected PFT_ERR_TIMEOUT",
                    pft_status_str(st));
            break;
        }
    }
    if (!timed_out && !c->r->ended && !c->exhausted && c->r->violations[PFT_CONF_TIMEOUT] == 0u) {
        violate(c, PFT_CONF_TIMEOUT, "starved source never returned PFT_ERR_TIMEOUT");
    }
    c->s.starve(c->s.hook_ctx, false);
    lend_probe(c, lend_ok ? PFT_CONF_TIMEOUT : SILENT, false); /* a timeout lent nothing */
}

/* Phase 4: the stream. */
static void stream(conf_t *c)
{
    bool endless = (c->s.frames == PFT_CONF_ENDLESS);
    uint32_t n = 0u;
    while (!c->stop && !c->r->ended && !(endless && n >= c->s.endless_frames)) {
        pft_frame_t f;
        pft_status_t st = PFT_OK;
        if (!acquire_once(c, &f, &st, 0u)) {
            break;
        }
        if (st == PFT_OK) {
            lent_t l;
            on_lent(c, &f, &l);
            for (uint32_t t = 0; t < c->s.ticks_while_lent; ++t) {
                tick(c);
                verify(c, &l, PFT_CONF_DATA, "while the source ran");
            }
            give_back(c, &l);
            n++;
        } else if (st == PFT_ERR_TIMEOUT) {
            c->r->timeouts++;
            if (!c->s.can_timeout) {
                violate(c, PFT_CONF_TIMEOUT, "PFT_ERR_TIMEOUT from a source that cannot time out");
            }
            tick(c);
        } else if (st == PFT_ERR_IO || st == PFT_ERR_FORMAT) {
            c->r->lost++;
            if (!c->s.may_lose) {
                violate(c, PFT_CONF_STATUS, "%s from a source that cannot lose frames",
                        pft_status_str(st));
            }
        } else if (st == PFT_ERR_EOF) {
            c->r->ended = true;
        } else if (st == PFT_ERR_STATE) {
            violate(c, PFT_CONF_LEND, "PFT_ERR_STATE with no frame lent");
            c->stop = true;
        } else {
            violate(c, PFT_CONF_STATUS, "acquire returned %s", pft_status_str(st));
            c->stop = true;
        }
    }
    if (endless && c->r->ended) {
        violate(c, PFT_CONF_EOF, "endless source ended after %lu frames",
                (unsigned long)c->r->frames);
    } else if (endless && n < c->s.endless_frames && !c->stop) {
        violate(c, PFT_CONF_STATUS, "%lu of %lu frames in %lu acquires", (unsigned long)n,
                (unsigned long)c->s.endless_frames, (unsigned long)c->r->attempts);
    } else if (!endless && !c->r->ended && !c->stop) {
        violate(c, PFT_CONF_EOF, "no PFT_ERR_EOF within %lu acquires",
                (unsigned long)c->r->attempts);
    }
}

/* Phase 5: EOF is sticky, also after a stray release; the count. */
static void after_end(conf_t *c)
{
    for (uint32_t k = 0; k < AFTER_END_CALLS; ++k) {
        if (k == AFTER_END_CALLS - 1u) {
            pft_frame_t ff = foreign_frame(c);
            bad_release(c, &ff, "a foreign frame after the end");
        }
        pft_frame_t f;
        pft_status_t st = PFT_ERR_EOF;
        if (!acquire_once(c, &f, &st, AFTER_END_CALLS)) {
            break;
        }
        if (st != PFT_ERR_EOF) {
            violate(c, PFT_CONF_EOF, "acquire %lu after PFT_ERR_EOF returned %s",
                    (unsigned long)(k + 1u), pft_status_str(st));
            if (st == PFT_OK) {
                lent_t l;
                on_lent(c, &f, &l);
                give_back(c, &l);
            }
        }
    }
    if (c->s.frames != PFT_CONF_FINITE && c->r->frames != c->s.frames) {
        violate(c, PFT_CONF_COUNT, "lent %lu frames, expected %lu", (unsigned long)c->r->frames,
                (unsigned long)c->s.frames);
    }
}

void pft_conf_spec_default(pft_conf_spec_t *spec)
{
    if (spec != NULL) {
        memset(spec, 0, sizeof *spec);
        spec->frames = PFT_CONF_ENDLESS;
        spec->endless_frames = 48u;
        spec->max_lent = 1u;
        spec->ticks_while_lent = 2u;
    }
}

static bool spec_ok(const pft_frame_source_t *src, const pft_conf_spec_t *s)
{
    return src != NULL && s != NULL && src->acquire != NULL && src->release != NULL &&
           s->max_lent != 0u && (s->max_lent <= PFT_CONF_MAX_HELD || s->max_lent == PFT_CONF_NO_LIMIT) &&
           (s->starve == NULL || s->can_timeout) &&
           (s->frames != PFT_CONF_ENDLESS || s->endless_frames != 0u) &&
           ((s->width == 0u) == (s->height == 0u));
}

bool pft_conf_run(const pft_frame_source_t *src, const pft_conf_spec_t *spec,
                  pft_conf_report_t *report)
{
    if (report == NULL) {
        return false;
    }
    memset(report, 0, sizeof *report);
    static conf_t c; /* a check is not reentrant; keeps ~1 KiB off small stacks */
    memset(&c, 0, sizeof c);
    c.r = report;
    if (!spec_ok(src, spec)) {
        violate(&c, PFT_CONF_SPEC, "NULL source or callbacks, or an inconsistent spec");
        return false;
    }
    c.src = src;
    c.s = *spec;
    c.w = spec->width;
    c.h = spec->height;
    c.mask = (spec->fmt_mask != 0u) ? spec->fmt_mask : known_formats();
    uint64_t base = (spec->frames == PFT_CONF_ENDLESS) ? spec->endless_frames
                    : (spec->frames == PFT_CONF_FINITE) ? 8192u : spec->frames;
    uint64_t lim = (spec->max_attempts != 0u) ? spec->max_attempts : 8u * base + 256u;
    c.attempt_limit = (lim > 0x7FFFFFFFu) ? 0x7FFFFFFFu : (uint32_t)lim;

    lend_probe(&c, PFT_CONF_LEND, false);
    bool lend_ok = c.r->violations[PFT_CONF_LEND] == 0u;
    if (!c.stop && !c.r->ended) {
        release_probe(&c, lend_ok);
    }
    if (spec->starve != NULL && !c.stop && !c.r->ended) {
        timeout_probe(&c, lend_ok);
    }
    stream(&c);
    if (spec->frames != PFT_CONF_ENDLESS && c.r->ended) {
        after_end(&c);
    }
    return report->total == 0u;
}
