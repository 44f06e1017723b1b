/* Runner over the ring source with each injected fault: counts, every frame released once,
 * the source still usable after each error, timing hooks, stop conditions, NULL arguments. */
#include <string.h>
#include "pft_test_support.h"
#include "pft/pft_port_mem.h"

#define W 8u
#define H 6u
#define SLOTS 4u
#define PERIOD_US 40000u
#define MAX_SEQ 256u

static uint16_t ring[SLOTS * W * H];
static pft_mem_source_t mem;

/* Producer pulled by the ring: one frame per call, every pixel = seq, ts = seq * PERIOD. */
typedef struct {
    uint32_t total;
    uint32_t made;
} gen_t;
static gen_t gen;

static pft_status_t gen_fill(void *ctx, pft_mem_source_t *m)
{
    gen_t *g = (gen_t *)ctx;
    if (g->made >= g->total) {
        return PFT_ERR_EOF;
    }
    void *px = NULL;
    uint32_t seq = m->next_seq;
    pft_status_t st = pft_mem_write_begin(m, &px);
    if (st != PFT_OK) {
        return st;
    }
    uint16_t *p = (uint16_t *)px;
    for (uint32_t i = 0; i < W * H; ++i) {
        p[i] = (uint16_t)(seq + i);
    }
    g->made++;
    return pft_mem_write_commit(m, (uint64_t)seq * PERIOD_US);
}

/* A source wrapping another, counting lends and returns per seq. */
typedef struct {
    pft_frame_source_t inner;
    uint32_t acquires, releases;
    uint8_t lent[MAX_SEQ];
    uint8_t acq_by_seq[MAX_SEQ];
    uint8_t rel_by_seq[MAX_SEQ];
    uint32_t anomalies; /* release of something not lent, or acquire of a seq twice */
} counting_t;
static counting_t cnt;

static pft_status_t cnt_acquire(void *ctx, pft_frame_t *out, uint32_t timeout_ms)
{
    counting_t *c = (counting_t *)ctx;
    pft_status_t st = c->inner.acquire(c->inner.ctx, out, timeout_ms);
    if (st == PFT_OK) {
        uint32_t s = out->seq % MAX_SEQ;
        c->acquires++;
        c->acq_by_seq[s]++;
        if (c->lent[s] != 0u || c->acq_by_seq[s] > 1u) {
            c->anomalies++;
        }
        c->lent[s] = 1u;
    }
    return st;
}

static void cnt_release(void *ctx, const pft_frame_t *f)
{
    counting_t *c = (counting_t *)ctx;
    uint32_t s = f->seq % MAX_SEQ;
    c->releases++;
    c->rel_by_seq[s]++;
    if (c->lent[s] == 0u) {
        c->anomalies++;
    }
    c->lent[s] = 0u;
    c->inner.release(c->inner.ctx, f);
}

static pft_frame_source_t counted(void)
{
    memset(&cnt, 0, sizeof cnt);
    cnt.inner = pft_mem_as_source(&mem);
    pft_frame_source_t s = {&cnt, cnt_acquire, cnt_release};
    return s;
}

static void assert_all_released_once(void)
{
    TEST_ASSERT_EQUAL_UINT32(0u, cnt.anomalies);
    TEST_ASSERT_EQUAL_UINT32(cnt.acquires, cnt.releases);
    for (uint32_t s = 0; s < MAX_SEQ; ++s) {
        TEST_ASSERT_EQUAL_UINT8(cnt.acq_by_seq[s], cnt.rel_by_seq[s]);
        TEST_ASSERT_TRUE(cnt.acq_by_seq[s] <= 1u);
    }
    TEST_ASSERT_EQUAL_UINT32(0u, mem.stats.lent);
    TEST_ASSERT_EQUAL_UINT32(0u, mem.stats.bad_releases);
    TEST_ASSERT_EQUAL_UINT32(mem.stats.acquired, mem.stats.released);
}

/* Consumer: checks pixels against seq, records what it saw. */
typedef struct {
    uint32_t frames;
    uint32_t bad_pixels;
    uint32_t late_ts; /* frames whose timestamp is not seq * PERIOD */
    uint32_t stop_after; /* return EOF after this many (0: never) */
    pft_status_t ret;    /* status to return otherwise */
} sink_t;
static sink_t sink;

static pft_status_t consume(void *ctx, const pft_frame_t *f)
{
    sink_t *k = (sink_t *)ctx;
    k->frames++;
    for (uint32_t y = 0; y < f->height; ++y) {
        const uint16_t *row = (const uint16_t *)(const void *)pft_frame_row(f, y);
        for (uint32_t x = 0; x < f->width; ++x) {
            if (row[x] != (uint16_t)(f->seq + y * W + x)) {
                k->bad_pixels++;
            }
        }
    }
    if (f->timestamp_us != (uint64_t)f->seq * PERIOD_US) {
        k->late_ts++;
    }
    if (k->stop_after != 0u && k->frames >= k->stop_after) {
        return PFT_ERR_EOF;
    }
    return k->ret;
}

/* Fake clock: each reading advances 7 us; hooks count calls. */
typedef struct {
    uint64_t t;
    uint32_t begins, ends, faults;
    uint64_t elapsed_sum;
} clock_t_;
static clock_t_ clk;

static uint64_t fake_now(void *ctx)
{
    clock_t_ *c = (clock_t_ *)ctx;
    c->t += 7u;
    return c->t;
}
static void on_begin(void *ctx, const pft_frame_t *f)
{
    (void)f;
    ((clock_t_ *)ctx)->begins++;
}
static void on_end(void *ctx, const pft_frame_t *f, pft_status_t st, uint64_t us)
{
    (void)f;
    (void)st;
    ((clock_t_ *)ctx)->ends++;
    ((clock_t_ *)ctx)->elapsed_sum += us;
}
static void on_fault(void *ctx, pft_status_t st, uint32_t seq)
{
    (void)st;
    (void)seq;
    ((clock_t_ *)ctx)->faults++;
}
static const pft_runner_hooks_t hooks = {&clk, fake_now, on_begin, on_end, on_fault};

static void make_source(uint32_t total, const pft_mem_faults_t *faults)
{
    pft_mem_config_t c;
    memset(&c, 0, sizeof c);
    c.buffer = ring;
    c.buffer_bytes = sizeof ring;
    c.slots = SLOTS;
    c.width = W;
    c.height = H;
    c.format = PFT_PIX_U16;
    c.bit_depth = 14u;
    c.fill = gen_fill;
    c.fill_ctx = &gen;
    if (faults != NULL) {
        c.faults = *faults;
    }
    gen.total = total;
    gen.made = 0u;
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_mem_source_init(&mem, &c));
}

static pft_runner_stats_t st;

static pft_status_t run(pft_frame_source_t *src, const pft_runner_config_t *cfg)
{
    memset(&clk, 0, sizeof clk);
    return pft_runner_run(src, consume, &sink, &hooks, cfg, &st);
}

void setUp(void)
{
    memset(&sink, 0, sizeof sink);
    memset(&st, 0xFF, sizeof st); /* the runner must reset every field */
}
void tearDown(void) {}

static void test_clean_run_counts_and_times(void)
{
    make_source(20u, NULL);
    pft_frame_source_t s = counted();
    TEST_ASSERT_EQUAL_INT(PFT_OK, run(&s, NULL));
    TEST_ASSERT_EQUAL_INT(PFT_ERR_EOF, st.stop);
    TEST_ASSERT_EQUAL_UINT32(20u, st.frames);
    TEST_ASSERT_EQUAL_UINT32(20u, sink.frames);
    TEST_ASSERT_EQUAL_UINT32(0u, sink.bad_pixels);
    TEST_ASSERT_EQUAL_UINT32(20u, st.acquired);
    TEST_ASSERT_EQUAL_UINT32(20u, st.released);
    TEST_ASSERT_EQUAL_UINT32(21u, st.attempts); /* the 21st sees EOF */
    TEST_ASSERT_EQUAL_UINT32(0u, st.dropped + st.short_frames + st.corrupt + st.late +
                                     st.ts_backwards + st.timeouts + st.io_errors +
                                     st.format_errors + st.consumer_errors + st.seq_errors);
    /* consumer time is exactly one clock step */
    TEST_ASSERT_EQUAL_UINT64(7u, st.time_min_us);
    TEST_ASSERT_EQUAL_UINT64(7u, st.time_max_us);
    TEST_ASSERT_EQUAL_UINT64(140u, st.time_total_us);
    TEST_ASSERT_EQUAL_UINT32(20u, clk.begins);
    TEST_ASSERT_EQUAL_UINT32(20u, clk.ends);
    TEST_ASSERT_EQUAL_UINT64(140u, clk.elapsed_sum);
    TEST_ASSERT_EQUAL_UINT32(0u, clk.faults);
    TEST_ASSERT_EQUAL_UINT16(W, st.width); /* locked to the first frame */
    TEST_ASSERT_EQUAL_UINT16(H, st.height);
    assert_all_released_once();
}

static void test_dropped_frames_show_as_seq_gaps(void)
{
    static const pft_fault_at_t at[] = {{3u, PFT_FAULT_DROP}, {7u, PFT_FAULT_DROP},
                                        {8u, PFT_FAULT_DROP}};
    pft_mem_faults_t f;
    memset(&f, 0, sizeof f);
    f.at = at;
    f.at_count = 3u;
    make_source(20u, &f);
    pft_frame_source_t s = counted();
    TEST_ASSERT_EQUAL_INT(PFT_OK, run(&s, NULL));
    TEST_ASSERT_EQUAL_UINT32(17u, st.frames);
    TEST_ASSERT_EQUAL_UINT32(3u, st.dropped);
    TEST_ASSERT_EQUAL_UINT32(3u, mem.stats.injected[PFT_FAULT_DROP]);
    TEST_ASSERT_EQUAL_UINT32(2u, clk.faults); /* one report per gap */
    TEST_ASSERT_EQUAL_UINT32(0u, sink.bad_pixels);
    TEST_ASSERT_EQUAL_UINT32(0u, cnt.acq_by_seq[3] + cnt.acq_by_seq[7] + cnt.acq_by_seq[8]);
    assert_all_released_once();
}

static void test_short_frames_rejected_and_released(void)
{
    static const pft_fault_at_t at[] = {{0u + 5u, PFT_FAULT_SHORT}, {6u, PFT_FAULT_SHORT}};
    pft_mem_faults_t f;
    memset(&f, 0, sizeof f);
    f.at = at;
    f.at_count = 2u;
    f.short_height = 4u;
    make_source(12u, &f);
    pft_frame_source_t s = counted();
    TEST_ASSERT_EQUAL_INT(PFT_OK, run(&s, NULL));
    TEST_ASSERT_EQUAL_UINT32(10u, st.frames);
    TEST_ASSERT_EQUAL_UINT32(2u, st.short_frames);
    TEST_ASSERT_EQUAL_UINT32(0u, st.corrupt);
    TEST_ASSERT_EQUAL_UINT32(12u, st.acquired);
    TEST_ASSERT_EQUAL_UINT32(12u, st.released);
    TEST_ASSERT_EQUAL_UINT32(1u, cnt.rel_by_seq[5]); /* released although never consumed */
    TEST_ASSERT_EQUAL_UINT32(2u, clk.faults);
    TEST_ASSERT_EQUAL_UINT32(0u, sink.bad_pixels);
    assert_all_released_once();
}

static void test_first_frame_short_against_configured_size(void)
{
    static const pft_fault_at_t at[] = {{0u, PFT_FAULT_SHORT}};
    pft_mem_faults_t f;
    memset(&f, 0, sizeof f);
    f.at = at;
    f.at_count = 1u;
    make_source(5u, &f);
    pft_frame_source_t s = counted();
    pft_runner_config_t cfg;
    memset(&cfg, 0, sizeof cfg);
    cfg.width = W; /* a configured geometry catches a short first frame */
    cfg.height = H;
    cfg.fmt_mask = PFT_FMT_BIT(PFT_PIX_U16);
    TEST_ASSERT_EQUAL_INT(PFT_OK, run(&s, &cfg));
    TEST_ASSERT_EQUAL_UINT32(1u, st.short_frames);
    TEST_ASSERT_EQUAL_UINT32(4u, st.frames);
    assert_all_released_once();
}

static void test_corrupt_headers_rejected(void)
{
    /* even seq: unknown format; odd seq: zero width */
    static const pft_fault_at_t at[] = {{4u, PFT_FAULT_CORRUPT}, {9u, PFT_FAULT_CORRUPT}};
    pft_mem_faults_t f;
    memset(&f, 0, sizeof f);
    f.at = at;
    f.at_count = 2u;
    make_source(12u, &f);
    pft_frame_source_t s = counted();
    TEST_ASSERT_EQUAL_INT(PFT_OK, run(&s, NULL));
    TEST_ASSERT_EQUAL_UINT32(10u, st.frames);
    TEST_ASSERT_EQUAL_UINT32(2u, st.corrupt);
    TEST_ASSERT_EQUAL_UINT32(0u, st.short_frames);
    TEST_ASSERT_EQUAL_UINT32(1u, cnt.rel_by_seq[4]);
    TEST_ASSERT_EQUAL_UINT32(1u, cnt.rel_by_seq[9]);
    assert_all_released_once();
}

static void test_late_timestamp_counted_frame_still_used(void)
{
    static const pft_fault_at_t at[] = {{6u, PFT_FAULT_LATE}};
    pft_mem_faults_t f;
    memset(&f, 0, sizeof f);
    f.at = at;
    f.at_count = 1u;
    f.late_us = 500000u;
    make_source(12u, &f);
    pft_frame_source_t s = counted();
    pft_runner_config_t cfg;
    memset(&cfg, 0, sizeof cfg);
    cfg.max_interval_us = 2u * PERIOD_US;
    TEST_ASSERT_EQUAL_INT(PFT_OK, run(&s, &cfg));
    TEST_ASSERT_EQUAL_UINT32(12u, st.frames);
    TEST_ASSERT_EQUAL_UINT32(1u, st.late);
    TEST_ASSERT_EQUAL_UINT32(1u, st.ts_backwards); /* seq 7 comes back to its own time */
    TEST_ASSERT_EQUAL_UINT32(1u, sink.late_ts);
    assert_all_released_once();
}

static void test_timeout_then_frame_arrives(void)
{
    static const pft_fault_at_t at[] = {{2u, PFT_FAULT_TIMEOUT}, {10u, PFT_FAULT_TIMEOUT}};
    pft_mem_faults_t f;
    memset(&f, 0, sizeof f);
    f.at = at;
    f.at_count = 2u;
    make_source(12u, &f);
    pft_frame_source_t s = counted();
    TEST_ASSERT_EQUAL_INT(PFT_OK, run(&s, NULL));
    TEST_ASSERT_EQUAL_UINT32(12u, st.frames); /* nothing lost: the frames came late */
    TEST_ASSERT_EQUAL_UINT32(2u, st.timeouts);
    TEST_ASSERT_EQUAL_UINT32(0u, st.dropped);
    TEST_ASSERT_EQUAL_UINT32(15u, st.attempts); /* 12 frames + 2 timeouts + EOF */
    assert_all_released_once();
}

static void test_random_faults_consistent(void)
{
    pft_mem_faults_t f;
    memset(&f, 0, sizeof f);
    f.seed = 12345u;
    f.prob_ppm[PFT_FAULT_DROP] = 50000u;
    f.prob_ppm[PFT_FAULT_SHORT] = 50000u;
    f.prob_ppm[PFT_FAULT_CORRUPT] = 50000u;
    f.prob_ppm[PFT_FAULT_LATE] = 50000u;
    f.prob_ppm[PFT_FAULT_TIMEOUT] = 50000u;
    make_source(200u, &f);
    pft_frame_source_t s = counted();
    pft_runner_config_t cfg;
    memset(&cfg, 0, sizeof cfg);
    cfg.width = W;
    cfg.height = H;
    cfg.max_interval_us = 500000u;
    TEST_ASSERT_EQUAL_INT(PFT_OK, run(&s, &cfg));
    const uint32_t *inj = mem.stats.injected;
    /* with 25% faults over 200 frames, every kind occurs (deterministic for this seed) */
    for (uint32_t k = 1u; k < (uint32_t)PFT_FAULT_COUNT; ++k) {
        TEST_ASSERT_TRUE(inj[k] > 0u);
    }
    TEST_ASSERT_EQUAL_UINT32(200u, mem.stats.pushed);
    TEST_ASSERT_EQUAL_UINT32(inj[PFT_FAULT_DROP], st.dropped);
    TEST_ASSERT_EQUAL_UINT32(inj[PFT_FAULT_SHORT], st.short_frames);
    TEST_ASSERT_EQUAL_UINT32(inj[PFT_FAULT_CORRUPT], st.corrupt);
    TEST_ASSERT_EQUAL_UINT32(inj[PFT_FAULT_TIMEOUT], st.timeouts);
    TEST_ASSERT_EQUAL_UINT32(inj[PFT_FAULT_LATE], sink.late_ts);
    TEST_ASSERT_TRUE(st.late >= 1u && st.late <= inj[PFT_FAULT_LATE]);
    TEST_ASSERT_EQUAL_UINT32(200u - inj[PFT_FAULT_DROP], st.acquired);
    TEST_ASSERT_EQUAL_UINT32(st.acquired - st.short_frames - st.corrupt, st.frames);
    TEST_ASSERT_EQUAL_UINT32(0u, sink.bad_pixels);
    assert_all_released_once();
}

static void test_same_seed_same_faults(void)
{
    pft_mem_faults_t f;
    memset(&f, 0, sizeof f);
    f.seed = 777u;
    f.prob_ppm[PFT_FAULT_DROP] = 100000u;
    f.prob_ppm[PFT_FAULT_CORRUPT] = 100000u;
    make_source(100u, &f);
    pft_frame_source_t s = counted();
    TEST_ASSERT_EQUAL_INT(PFT_OK, run(&s, NULL));
    pft_runner_stats_t first = st;
    make_source(100u, &f);
    s = counted();
    TEST_ASSERT_EQUAL_INT(PFT_OK, run(&s, NULL));
    TEST_ASSERT_EQUAL_UINT32(first.dropped, st.dropped);
    TEST_ASSERT_EQUAL_UINT32(first.corrupt, st.corrupt);
    TEST_ASSERT_EQUAL_UINT32(first.frames, st.frames);
    f.seed = 778u;
    make_source(100u, &f);
    s = counted();
    TEST_ASSERT_EQUAL_INT(PFT_OK, run(&s, NULL));
    TEST_ASSERT_TRUE(first.dropped != st.dropped || first.corrupt != st.corrupt);
}

static void test_stop_conditions(void)
{
    /* max_frames */
    make_source(50u, NULL);
    pft_frame_source_t s = counted();
    pft_runner_config_t cfg;
    memset(&cfg, 0, sizeof cfg);
    cfg.max_frames = 5u;
    TEST_ASSERT_EQUAL_INT(PFT_OK, run(&s, &cfg));
    TEST_ASSERT_EQUAL_INT(PFT_OK, st.stop);
    TEST_ASSERT_EQUAL_UINT32(5u, st.frames);
    assert_all_released_once();
    /* the same source goes on where it stopped */
    sink.frames = 0u;
    TEST_ASSERT_EQUAL_INT(PFT_OK, run(&s, &cfg));
    TEST_ASSERT_EQUAL_UINT32(5u, st.frames);
    TEST_ASSERT_EQUAL_UINT32(1u, cnt.acq_by_seq[9]);

    /* consumer asks to stop */
    make_source(50u, NULL);
    s = counted();
    memset(&sink, 0, sizeof sink);
    sink.stop_after = 3u;
    TEST_ASSERT_EQUAL_INT(PFT_OK, run(&s, NULL));
    TEST_ASSERT_EQUAL_INT(PFT_ERR_EOF, st.stop);
    TEST_ASSERT_EQUAL_UINT32(3u, st.frames);
    assert_all_released_once();

    /* consumer errors are counted, the run continues */
    make_source(6u, NULL);
    s = counted();
    memset(&sink, 0, sizeof sink);
    sink.ret = PFT_ERR_RANGE;
    TEST_ASSERT_EQUAL_INT(PFT_OK, run(&s, NULL));
    TEST_ASSERT_EQUAL_UINT32(6u, st.frames);
    TEST_ASSERT_EQUAL_UINT32(6u, st.consumer_errors);
}

static void test_starved_source_bounded(void)
{
    /* open ring, nothing produced, no fill: every acquire times out */
    make_source(0u, NULL);
    mem.cfg.fill = NULL;
    pft_frame_source_t s = counted();
    pft_runner_config_t cfg;
    memset(&cfg, 0, sizeof cfg);
    cfg.max_consecutive_errors = 10u;
    TEST_ASSERT_EQUAL_INT(PFT_ERR_TIMEOUT, run(&s, &cfg));
    TEST_ASSERT_EQUAL_INT(PFT_ERR_TIMEOUT, st.stop);
    TEST_ASSERT_EQUAL_UINT32(10u, st.timeouts);
    memset(&cfg, 0, sizeof cfg);
    cfg.max_attempts = 25u;
    TEST_ASSERT_EQUAL_INT(PFT_OK, run(&s, &cfg));
    TEST_ASSERT_EQUAL_UINT32(25u, st.attempts);
    TEST_ASSERT_EQUAL_UINT32(25u, st.timeouts);
    /* and it still works once frames come */
    uint16_t px[W * H];
    for (uint32_t i = 0; i < W * H; ++i) {
        px[i] = (uint16_t)(mem.next_seq + i);
    }
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_mem_push(&mem, px, 0u, (uint64_t)mem.next_seq * PERIOD_US));
    pft_mem_close(&mem);
    TEST_ASSERT_EQUAL_INT(PFT_OK, run(&s, NULL));
    TEST_ASSERT_EQUAL_UINT32(1u, st.frames);
    TEST_ASSERT_EQUAL_UINT32(0u, sink.bad_pixels);
}

static pft_status_t bad_acquire(void *ctx, pft_frame_t *out, uint32_t timeout_ms)
{
    (void)out;
    (void)timeout_ms;
    return *(const pft_status_t *)ctx;
}
static void noop_release(void *ctx, const pft_frame_t *f)
{
    (void)ctx;
    (void)f;
}

static void test_fatal_source_errors_stop(void)
{
    static const pft_status_t fatal[] = {PFT_ERR_STATE, PFT_ERR_INVAL, PFT_ERR_NOMEM,
                                         PFT_ERR_RANGE};
    for (uint32_t i = 0; i < 4u; ++i) {
        pft_status_t code = fatal[i];
        pft_frame_source_t s = {&code, bad_acquire, noop_release};
        TEST_ASSERT_EQUAL_INT(code, run(&s, NULL));
        TEST_ASSERT_EQUAL_INT(code, st.stop);
        TEST_ASSERT_EQUAL_UINT32(1u, st.attempts);
    }
    pft_status_t io = PFT_ERR_IO;
    pft_frame_source_t s = {&io, bad_acquire, noop_release};
    pft_runner_config_t cfg;
    memset(&cfg, 0, sizeof cfg);
    cfg.max_consecutive_errors = 3u;
    TEST_ASSERT_EQUAL_INT(PFT_ERR_IO, run(&s, &cfg));
    TEST_ASSERT_EQUAL_UINT32(3u, st.io_errors);
}

static void test_null_arguments(void)
{
    make_source(3u, NULL);
    pft_frame_source_t s = pft_mem_as_source(&mem);
    pft_frame_source_t no_rel = {&mem, pft_mem_acquire, NULL};
    pft_frame_source_t no_acq = {&mem, NULL, pft_mem_release};
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_runner_run(NULL, consume, &sink, NULL, NULL, &st));
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_runner_run(&s, NULL, &sink, NULL, NULL, &st));
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_runner_run(&s, consume, &sink, NULL, NULL, NULL));
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_runner_run(&no_rel, consume, &sink, NULL, NULL, &st));
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_runner_run(&no_acq, consume, &sink, NULL, NULL, &st));
    TEST_ASSERT_EQUAL_UINT32(0u, st.attempts);

    pft_frame_t f;
    memset(&f, 0xAB, sizeof f);
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_source_acquire(NULL, &f, 0u));
    TEST_ASSERT_NULL(f.data); /* zeroed even on error */
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_source_acquire(&s, NULL, 0u));
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_source_acquire(&no_rel, &f, 0u));
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_source_release(NULL, &f));
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_source_release(&s, NULL));
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_source_release(&s, &f)); /* data NULL */
    TEST_ASSERT_EQUAL_UINT32(0u, mem.stats.acquired);
    /* the real thing still works through the helpers */
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_source_acquire(&s, &f, 0u));
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_source_release(&s, &f));
    TEST_ASSERT_EQUAL_UINT32(1u, mem.stats.released);
    /* hooks and config may be NULL */
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_runner_run(&s, consume, &sink, NULL, NULL, &st));
    TEST_ASSERT_EQUAL_UINT32(2u, st.frames);
    TEST_ASSERT_EQUAL_UINT64(0u, st.time_total_us);
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_clean_run_counts_and_times);
    RUN_TEST(test_dropped_frames_show_as_seq_gaps);
    RUN_TEST(test_short_frames_rejected_and_released);
    RUN_TEST(test_first_frame_short_against_configured_size);
    RUN_TEST(test_corrupt_headers_rejected);
    RUN_TEST(test_late_timestamp_counted_frame_still_used);
    RUN_TEST(test_timeout_then_frame_arrives);
    RUN_TEST(test_random_faults_consistent);
    RUN_TEST(test_same_seed_same_faults);
    RUN_TEST(test_stop_conditions);
    RUN_TEST(test_starved_source_bounded);
    RUN_TEST(test_fatal_source_errors_stop);
    RUN_TEST(test_null_arguments);
    return UNITY_END();
}
