/* The conformance check can fail: a fake port, correct by default, is broken one rule at a
 * time and the check must report that rule. The correct fake must pass (finite and endless),
 * gaps in seq must be counted without a violation, and a bad spec must be refused. */
#include <string.h>
#include "pft_test_support.h"
#include "pft_port_conformance.h"

#define FW 6u
#define FH 4u
#define FSLOTS 4u

typedef enum {
    BRK_NONE = 0,
    BRK_DESCRIPTOR,      /* frame 3 has a stride below a row */
    BRK_SIZE,            /* frame 4 is one row short */
    BRK_SEQ,             /* frame 4 repeats frame 3's seq */
    BRK_TS,              /* frame 5's timestamp goes back */
    BRK_EOF,             /* after EOF, the second acquire says TIMEOUT */
    BRK_RELEASE_UNCOUNTED, /* releases of frames not lent are silently taken */
    BRK_RELEASE_CORRUPT, /* a double release decrements the lent count */
    BRK_FOREIGN_CORRUPT, /* a foreign release frees a lent buffer (then overwritten) */
    BRK_LEND_LIMIT,      /* lends one frame beyond its documented limit */
    BRK_LEND_EARLY,      /* refuses with STATE below its documented limit */
    BRK_SAME_BUFFER,     /* lends the buffer of a frame already lent */
    BRK_TIMEOUT_STATUS,  /* starved: returns PFT_ERR_IO instead of a timeout */
    BRK_TIMEOUT_LEAK,    /* a timeout marks a buffer lent */
    BRK_SURPRISE_TIMEOUT, /* times out although documented as never timing out */
    BRK_DATA,            /* the producer writes into a lent buffer */
    BRK_COUNT,           /* ends one frame early */
    BRK_STATUS,          /* returns PFT_ERR_NOMEM once */
    BRK_ENDLESS_ENDS,    /* documented endless, ends after 30 frames */
    BRK_NEVER_ENDS,      /* documented finite, never ends */
    BRK_DROP             /* not a breakage: every 5th frame is dropped (a seq gap) */
} brk_t;

enum { S_FREE = 0, S_READY = 1, S_LENT = 2 };

typedef struct {
    brk_t brk;
    uint32_t limit;  /* documented lend limit */
    uint32_t total;  /* frames to make; 0: endless */
    uint8_t px[FSLOTS][FW * FH];
    uint8_t state[FSLOTS];
    uint32_t seq[FSLOTS];
    uint64_t ts[FSLOTS];
    int32_t lent;    /* signed: a broken release may drive it below zero */
    uint32_t made;   /* frames made (seq of the next one) */
    uint32_t given;  /* frames lent */
    uint32_t calls;  /* acquire calls */
    uint32_t eof_calls;
    bool starved, ended;
    uint32_t bad_releases;
} fake_t;

static fake_t fk;

static void fill(uint8_t *p, uint32_t seq)
{
    for (uint32_t i = 0; i < FW * FH; ++i) {
        p[i] = (uint8_t)(seq * 7u + i);
    }
}

/* Producer: one frame into the first FREE slot (a newer frame replaces nothing). */
static void produce(fake_t *f)
{
    if (f->starved || (f->total != 0u && f->made >= f->total)) {
        return;
    }
    for (uint32_t i = 0; i < FSLOTS; ++i) {
        if (f->state[i] == S_FREE) {
            uint32_t seq = f->made++;
            if (f->brk == BRK_DROP && seq % 5u == 4u) {
                seq = f->made++; /* the sensor lost one */
            }
            fill(f->px[i], seq);
            f->seq[i] = seq;
            f->ts[i] = 1000u * (uint64_t)seq;
            f->state[i] = S_READY;
            return;
        }
    }
}

static int32_t oldest_ready(const fake_t *f)
{
    int32_t best = -1;
    for (uint32_t i = 0; i < FSLOTS; ++i) {
        if (f->state[i] == S_READY && (best < 0 || f->seq[i] < f->seq[(uint32_t)best])) {
            best = (int32_t)i;
        }
    }
    return best;
}

static int32_t first_in(const fake_t *f, uint8_t state)
{
    for (uint32_t i = 0; i < FSLOTS; ++i) {
        if (f->state[i] == state) {
            return (int32_t)i;
        }
    }
    return -1;
}

static pft_status_t fake_acquire(void *ctx, pft_frame_t *out, uint32_t timeout_ms)
{
    fake_t *f = (fake_t *)ctx;
    (void)timeout_ms;
    f->calls++;
    if (f->ended) {
        f->eof_calls++;
        return (f->brk == BRK_EOF && f->eof_calls == 2u) ? PFT_ERR_TIMEOUT : PFT_ERR_EOF;
    }
    if (f->brk == BRK_SURPRISE_TIMEOUT && f->calls == 9u) {
        return PFT_ERR_TIMEOUT;
    }
    if (f->brk == BRK_STATUS && f->calls == 20u) { /* in the stream phase */
        return PFT_ERR_NOMEM;
    }
    if (f->brk == BRK_ENDLESS_ENDS && f->given >= 30u) {
        f->ended = true;
        return PFT_ERR_EOF;
    }
    int32_t limit = (int32_t)f->limit + (f->brk == BRK_LEND_LIMIT ? 1 : 0) -
                    (f->brk == BRK_LEND_EARLY ? 1 : 0);
    if (f->lent >= limit) {
        return PFT_ERR_STATE;
    }
    int32_t s = oldest_ready(f);
    if (s < 0) {
        produce(f);
        s = oldest_ready(f);
    }
    if (s < 0) {
        uint32_t total = f->total;
        if (f->brk == BRK_COUNT) {
            total--;
        }
        bool over = (f->total != 0u && f->made >= total);
        if (over && f->brk != BRK_NEVER_ENDS) {
            f->ended = true;
            return PFT_ERR_EOF;
        }
        if (f->starved && f->brk == BRK_TIMEOUT_STATUS) {
            return PFT_ERR_IO;
        }
        int32_t fr = first_in(f, S_FREE);
        if (f->brk == BRK_TIMEOUT_LEAK && fr >= 0) {
            f->state[(uint32_t)fr] = S_LENT;
            f->lent++;
        }
        return PFT_ERR_TIMEOUT;
    }
    if (f->brk == BRK_COUNT && f->given + 1u >= f->total) {
        f->ended = true;
        return PFT_ERR_EOF;
    }
    uint32_t i = (uint32_t)s;
    int32_t other = first_in(f, S_LENT);
    f->state[i] = S_LENT;
    f->lent++;
    f->given++;
    out->data = f->px[i];
    if (f->brk == BRK_SAME_BUFFER && other >= 0) {
        out->data = f->px[(uint32_t)other];
    }
    out->width = FW;
    out->height = FH;
    out->stride_bytes = FW;
    out->format = PFT_PIX_U8;
    out->seq = f->seq[i];
    out->timestamp_us = f->ts[i];
    if (f->brk == BRK_DESCRIPTOR && f->given == 3u) {
        out->stride_bytes = FW - 1u;
    }
    if (f->brk == BRK_SIZE && f->given == 4u) {
        out->height = FH - 1u;
    }
    if (f->brk == BRK_SEQ && f->given == 4u) {
        out->seq = out->seq - 1u;
    }
    if (f->brk == BRK_TS && f->given == 5u) {
        out->timestamp_us = 0u;
    }
    return PFT_OK;
}

static void fake_release(void *ctx, const pft_frame_t *frame)
{
    fake_t *f = (fake_t *)ctx;
    for (uint32_t i = 0; i < FSLOTS; ++i) {
        if (frame->data == (const void *)f->px[i]) {
            if (f->state[i] == S_LENT) {
                f->state[i] = S_FREE;
                f->lent--;
                return;
            }
            if (f->brk == BRK_RELEASE_CORRUPT) {
                f->lent--; /* the counter goes wrong... */
                f->bad_releases++; /* ...though the release was "refused" */
                return;
            }
            break;
        }
    }
    if (f->brk == BRK_RELEASE_UNCOUNTED) {
        return;
    }
    if (f->brk == BRK_FOREIGN_CORRUPT) {
        int32_t l = first_in(f, S_LENT);
        if (l >= 0) { /* frees someone else's frame */
            f->state[(uint32_t)l] = S_FREE;
            f->lent--;
        }
    }
    f->bad_releases++;
}

static void fake_tick(void *ctx)
{
    fake_t *f = (fake_t *)ctx;
    if (f->brk == BRK_DATA) {
        int32_t l = first_in(f, S_LENT);
        if (l >= 0) {
            f->px[(uint32_t)l][0] ^= 0x5Au; /* a DMA writing where it must not */
        }
    }
    /* the lowest FREE slot first: a buffer freed by mistake is overwritten at once */
    produce(f);
}

static void fake_starve(void *ctx, bool on) { ((fake_t *)ctx)->starved = on; }
static uint32_t fake_bad(void *ctx) { return ((fake_t *)ctx)->bad_releases; }

static pft_frame_source_t fake_source(brk_t brk, uint32_t total)
{
    memset(&fk, 0, sizeof fk);
    fk.brk = brk;
    fk.limit = 2u;
    fk.total = total;
    pft_frame_source_t s = {&fk, fake_acquire, fake_release};
    return s;
}

static pft_conf_spec_t fake_spec(uint32_t frames)
{
    pft_conf_spec_t sp;
    pft_conf_spec_default(&sp);
    sp.width = FW;
    sp.height = FH;
    sp.fmt_mask = PFT_FMT_BIT(PFT_PIX_U8);
    sp.frames = frames;
    sp.endless_frames = 40u;
    sp.max_lent = 2u;
    sp.can_timeout = true;
    sp.hook_ctx = &fk;
    sp.tick = fake_tick;
    sp.starve = fake_starve;
    sp.bad_releases = fake_bad;
    return sp;
}

void setUp(void) {}
void tearDown(void) {}

static void show(const char *what, const pft_conf_report_t *r)
{
    char line[200];
    (void)snprintf(line, sizeof line, "  %s: %lu violations, first: %s", what,
                   (unsigned long)r->total, r->first);
    UnityPrint(line);
    UNITY_PRINT_EOL();
}

static void test_correct_fake_passes(void)
{
    pft_conf_report_t r;
    pft_frame_source_t s = fake_source(BRK_NONE, 24u);
    pft_conf_spec_t sp = fake_spec(24u);
    bool ok = pft_conf_run(&s, &sp, &r);
    show("finite", &r);
    TEST_ASSERT_TRUE(ok);
    TEST_ASSERT_EQUAL_UINT32(0u, r.total);
    TEST_ASSERT_EQUAL_UINT32(24u, r.frames);
    TEST_ASSERT_EQUAL_UINT32(0u, r.gaps);
    TEST_ASSERT_TRUE(r.ended);
    TEST_ASSERT_EQUAL_UINT32(3u, r.refused);      /* three lend probes hit the limit */
    TEST_ASSERT_TRUE(r.timeouts >= 1u);           /* the starve probe timed out */
    TEST_ASSERT_EQUAL_UINT32(r.bad_releases, fk.bad_releases); /* all refused */
    TEST_ASSERT_TRUE(r.bad_releases >= 4u);
    TEST_ASSERT_EQUAL_INT32(0, fk.lent);

    s = fake_source(BRK_NONE, 0u);
    sp = fake_spec(PFT_CONF_ENDLESS);
    ok = pft_conf_run(&s, &sp, &r);
    show("endless", &r);
    TEST_ASSERT_TRUE(ok);
    TEST_ASSERT_FALSE(r.ended);
    TEST_ASSERT_TRUE(r.frames >= 40u);
    TEST_ASSERT_EQUAL_INT32(0, fk.lent);
}

static void test_gaps_are_counted_not_violations(void)
{
    pft_conf_report_t r;
    pft_frame_source_t s = fake_source(BRK_DROP, 30u);
    pft_conf_spec_t sp = fake_spec(PFT_CONF_FINITE);
    TEST_ASSERT_TRUE(pft_conf_run(&s, &sp, &r));
    /* 30 frames made, seq 0..30 with every fifth skipped (4, 9, ..., 29): 25 lent, 6 gaps */
    TEST_ASSERT_EQUAL_UINT32(25u, r.frames);
    TEST_ASSERT_EQUAL_UINT32(6u, r.gaps);
    TEST_ASSERT_EQUAL_UINT32(0u, r.first_seq);
    TEST_ASSERT_EQUAL_UINT32(30u, r.last_seq);
}

typedef struct {
    brk_t brk;
    pft_conf_rule_t rule;
    const char *name;
} broken_t;

static void test_each_broken_rule_is_reported(void)
{
    static const broken_t cases[] = {
        {BRK_DESCRIPTOR, PFT_CONF_DESCRIPTOR, "stride below a row"},
        {BRK_SIZE, PFT_CONF_DESCRIPTOR, "short frame"},
        {BRK_SEQ, PFT_CONF_SEQ, "seq repeated"},
        {BRK_TS, PFT_CONF_TIMESTAMP, "timestamp back"},
        {BRK_EOF, PFT_CONF_EOF, "EOF not sticky"},
        {BRK_RELEASE_UNCOUNTED, PFT_CONF_RELEASE, "bad release not refused"},
        {BRK_RELEASE_CORRUPT, PFT_CONF_RELEASE, "double release corrupts the lend count"},
        {BRK_FOREIGN_CORRUPT, PFT_CONF_RELEASE, "foreign release frees a lent buffer"},
        {BRK_LEND_LIMIT, PFT_CONF_LEND, "lends beyond its limit"},
        {BRK_LEND_EARLY, PFT_CONF_LEND, "refuses below its limit"},
        {BRK_SAME_BUFFER, PFT_CONF_LEND, "lends one buffer twice"},
        {BRK_TIMEOUT_STATUS, PFT_CONF_TIMEOUT, "starved source says IO"},
        {BRK_TIMEOUT_LEAK, PFT_CONF_TIMEOUT, "timeout leaks a lend"},
        {BRK_DATA, PFT_CONF_DATA, "writes into a lent frame"},
        {BRK_COUNT, PFT_CONF_COUNT, "one frame short"},
        {BRK_STATUS, PFT_CONF_STATUS, "PFT_ERR_NOMEM"},
        {BRK_NEVER_ENDS, PFT_CONF_EOF, "finite source never ends"},
    };
    for (uint32_t k = 0; k < sizeof cases / sizeof cases[0]; ++k) {
        pft_conf_report_t r;
        pft_frame_source_t s = fake_source(cases[k].brk, 24u);
        pft_conf_spec_t sp = fake_spec(24u);
        sp.max_attempts = 2000u; /* BRK_NEVER_ENDS: bounded */
        TEST_ASSERT_FALSE_MESSAGE(pft_conf_run(&s, &sp, &r), cases[k].name);
        show(cases[k].name, &r);
        TEST_ASSERT_TRUE_MESSAGE(r.violations[cases[k].rule] > 0u, cases[k].name);
        TEST_ASSERT_EQUAL_UINT32_MESSAGE(0u, r.violations[PFT_CONF_SPEC], cases[k].name);
    }
}

/* Rules that depend on the spec: a timeout from a source documented as never timing out,
 * and an endless source that ends. */
static void test_spec_dependent_rules(void)
{
    pft_conf_report_t r;
    pft_frame_source_t s = fake_source(BRK_SURPRISE_TIMEOUT, 24u);
    pft_conf_spec_t sp = fake_spec(24u);
    sp.can_timeout = false;
    sp.starve = NULL;
    TEST_ASSERT_FALSE(pft_conf_run(&s, &sp, &r));
    show("surprise timeout", &r);
    TEST_ASSERT_TRUE(r.violations[PFT_CONF_TIMEOUT] > 0u);

    s = fake_source(BRK_ENDLESS_ENDS, 0u);
    sp = fake_spec(PFT_CONF_ENDLESS);
    TEST_ASSERT_FALSE(pft_conf_run(&s, &sp, &r));
    show("endless ends", &r);
    TEST_ASSERT_TRUE(r.violations[PFT_CONF_EOF] > 0u);

    /* the same correct source checked against a wrong description fails too */
    s = fake_source(BRK_NONE, 24u);
    sp = fake_spec(24u);
    sp.width = FW + 1u;
    TEST_ASSERT_FALSE(pft_conf_run(&s, &sp, &r));
    TEST_ASSERT_TRUE(r.violations[PFT_CONF_DESCRIPTOR] > 0u);
    s = fake_source(BRK_NONE, 24u);
    sp = fake_spec(25u);
    TEST_ASSERT_FALSE(pft_conf_run(&s, &sp, &r));
    TEST_ASSERT_TRUE(r.violations[PFT_CONF_COUNT] > 0u);
}

static void test_bad_spec_refused(void)
{
    pft_conf_report_t r;
    pft_frame_source_t s = fake_source(BRK_NONE, 24u);
    pft_conf_spec_t sp = fake_spec(24u);
    TEST_ASSERT_FALSE(pft_conf_run(NULL, &sp, &r));
    TEST_ASSERT_EQUAL_UINT32(1u, r.violations[PFT_CONF_SPEC]);
    TEST_ASSERT_FALSE(pft_conf_run(&s, NULL, &r));
    TEST_ASSERT_FALSE(pft_conf_run(&s, &sp, NULL));
    pft_frame_source_t no_release = {&fk, fake_acquire, NULL};
    TEST_ASSERT_FALSE(pft_conf_run(&no_release, &sp, &r));
    sp.max_lent = 0u;
    TEST_ASSERT_FALSE(pft_conf_run(&s, &sp, &r));
    sp = fake_spec(24u);
    sp.max_lent = PFT_CONF_MAX_HELD + 1u;
    TEST_ASSERT_FALSE(pft_conf_run(&s, &sp, &r));
    sp = fake_spec(24u);
    sp.can_timeout = false; /* starve given: the source must be able to time out */
    TEST_ASSERT_FALSE(pft_conf_run(&s, &sp, &r));
    sp = fake_spec(24u);
    sp.height = 0u; /* half a size */
    TEST_ASSERT_FALSE(pft_conf_run(&s, &sp, &r));
    TEST_ASSERT_EQUAL_UINT32(1u, r.total);
    TEST_ASSERT_EQUAL_INT(PFT_CONF_SPEC, r.first_rule);
    TEST_ASSERT_EQUAL_UINT32(0u, fk.calls); /* nothing was run */
    TEST_ASSERT_EQUAL_STRING("release", pft_conf_rule_name(PFT_CONF_RELEASE));
    TEST_ASSERT_EQUAL_STRING("?", pft_conf_rule_name(PFT_CONF_RULES));
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_correct_fake_passes);
    RUN_TEST(test_gaps_are_counted_not_violations);
    RUN_TEST(test_each_broken_rule_is_reported);
    RUN_TEST(test_spec_dependent_rules);
    RUN_TEST(test_bad_spec_refused);
    return UNITY_END();
}
