/* Template port with a simulated camera DMA in both modes. One-shot: frames flow, nothing is
 * copied, a frame nobody took is replaced by the newer one, the camera pauses and resumes,
 * DMA errors are counted. Circular: the DMA swaps address registers by itself and the port
 * names the next target; frames with nowhere to go land in the sink (counted, callback, seq
 * gap); the DMA never writes into a lent buffer; the sensor's frame counter (narrow, wrapping,
 * skipping) gives seq; stop ends the stream with EOF and start resumes it. */
#include <string.h>
#include "pft_test_support.h"
#include "pft/pft_port_template.h"

#define W 4u
#define H 3u
#define NB 6u

static uint8_t bufs_mem[NB][W * H];
static uint8_t sink_mem[W * H];
static pft_tpl_port_t port;

/* Simulated hardware. One-shot: dma_start arms one transfer into `reg[0]`; a frame end
 * writes it and disarms. Circular: two address registers, `ct` the active one; a frame end
 * writes reg[ct], swaps ct and raises the interrupt; set_next writes the idle register.
 * The sensor counts every frame it produces (`counter`), captured or not. */
typedef struct {
    bool circular;
    bool armed;          /* one-shot transfer pending / circular DMA enabled */
    void *reg[2];
    uint32_t ct;
    uint32_t counter;    /* sensor frame counter of the next frame */
    uint32_t counter_step; /* sensor frames per produced frame (1: none skipped) */
    bool use_counter;    /* ISR passes the counter (else pft_tpl_on_frame_done) */
    bool no_time;        /* ISR passes no timestamp */
    uint64_t t;
    uint32_t pending;    /* frames that "arrive" while acquire waits */
    uint32_t starts, set_nexts, stops;
    uint32_t locks, unlocks, invalidates;
    uint32_t writes_into_lent; /* must stay 0 */
    uint32_t sink_writes;
} cam_t;
static cam_t cam;

/* Frames the test holds (data pointers), to catch a DMA write into a lent buffer. */
static const void *held[NB];

static void hold(const pft_frame_t *f)
{
    for (uint32_t i = 0; i < NB; ++i) {
        if (held[i] == NULL) {
            held[i] = f->data;
            return;
        }
    }
    TEST_FAIL_MESSAGE("test holds too many frames");
}

static void unhold(const pft_frame_t *f)
{
    for (uint32_t i = 0; i < NB; ++i) {
        if (held[i] == f->data) {
            held[i] = NULL;
            return;
        }
    }
}

static void dma_write(void *target)
{
    for (uint32_t i = 0; i < NB; ++i) {
        if (held[i] != NULL && held[i] == target) {
            cam.writes_into_lent++;
        }
    }
    if (target == sink_mem) {
        cam.sink_writes++;
    }
    memset(target, (int)(uint8_t)cam.counter, W * H);
}

static void cam_dma_start(void *drv, void *buf, uint32_t bytes)
{
    cam_t *c = (cam_t *)drv;
    TEST_ASSERT_EQUAL_UINT32(W * H, bytes);
    c->reg[c->circular ? c->ct : 0u] = buf;
    c->armed = true;
    c->starts++;
}

static void cam_set_next(void *drv, void *buf, uint32_t bytes)
{
    cam_t *c = (cam_t *)drv;
    TEST_ASSERT_EQUAL_UINT32(W * H, bytes);
    c->reg[c->ct ^ 1u] = buf;
    c->set_nexts++;
}

static void cam_stop(void *drv)
{
    cam_t *c = (cam_t *)drv;
    c->armed = false;
    c->ct = 0u;
    c->stops++;
}

static void isr(bool ok)
{
    uint32_t flags = ok ? 0u : PFT_TPL_FRAME_ERROR;
    if (cam.no_time) {
        flags |= PFT_TPL_FRAME_NO_TIME;
    }
    if (cam.use_counter) {
        pft_tpl_on_frame_counted(&port, cam.counter, cam.t, flags);
    } else {
        pft_tpl_on_frame_done(&port, cam.t, ok);
    }
}

/* The sensor produces one frame; the DMA captures it if armed and interrupts. */
static void cam_frame(bool ok)
{
    cam.t += 1000u;
    if (cam.armed) {
        if (cam.circular) {
            dma_write(cam.reg[cam.ct]);
            cam.ct ^= 1u; /* the hardware moves on by itself */
        } else {
            dma_write(cam.reg[0]);
            cam.armed = false;
        }
        isr(ok);
    }
    cam.counter += (cam.counter_step != 0u) ? cam.counter_step : 1u;
}

static bool cam_wait(void *drv, uint32_t timeout_ms)
{
    cam_t *c = (cam_t *)drv;
    (void)timeout_ms;
    if (c->pending == 0u) {
        return false;
    }
    c->pending--;
    cam_frame(true);
    return true;
}
static void cam_lock(void *drv) { ((cam_t *)drv)->locks++; }
static void cam_unlock(void *drv) { ((cam_t *)drv)->unlocks++; }
static void cam_inval(void *drv, const void *b, uint32_t n)
{
    (void)b;
    (void)n;
    ((cam_t *)drv)->invalidates++;
}

static pft_tpl_driver_t driver(void)
{
    pft_tpl_driver_t d = {&cam,     cam_dma_start, cam_wait,     cam_lock,
                          cam_unlock, cam_inval,   cam_set_next, cam_stop};
    return d;
}

static pft_tpl_config_t config(pft_tpl_mode_t mode, uint32_t nbuf)
{
    pft_tpl_config_t c;
    pft_tpl_config_default(&c);
    c.mode = mode;
    for (uint32_t i = 0; i < nbuf; ++i) {
        c.bufs[i] = bufs_mem[i];
    }
    c.nbuf = nbuf;
    c.sink = sink_mem;
    c.width = W;
    c.height = H;
    c.format = PFT_PIX_U8;
    return c;
}

static void start_cfg(const pft_tpl_config_t *c)
{
    memset(&cam, 0, sizeof cam);
    memset(held, 0, sizeof held);
    cam.circular = (c->mode == PFT_TPL_CIRCULAR);
    pft_tpl_driver_t d = driver();
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tpl_init(&port, &d, c));
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tpl_start(&port));
    TEST_ASSERT_EQUAL_INT(PFT_ERR_STATE, pft_tpl_start(&port));
}

static void start(uint32_t nbuf)
{
    pft_tpl_config_t c = config(PFT_TPL_ONESHOT, nbuf);
    start_cfg(&c);
}

static pft_tpl_stats_t stats(void)
{
    pft_tpl_stats_t s;
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tpl_get_stats(&port, &s));
    return s;
}

static bool is_buf(const void *p)
{
    for (uint32_t i = 0; i < NB; ++i) {
        if (p == bufs_mem[i]) {
            return true;
        }
    }
    return false;
}

/* Acquire with the test's bookkeeping; the pixels hold the low byte of the sensor counter,
 * which is the low byte of seq unless the counter repeated (check_pixels false). */
static bool check_pixels = true;
static pft_status_t take(pft_frame_t *f)
{
    pft_status_t st = pft_tpl_acquire(&port, f, 5u);
    if (st == PFT_OK) {
        TEST_ASSERT_TRUE(is_buf(f->data)); /* the DMA buffer itself, never the sink */
        if (check_pixels) {
            TEST_ASSERT_EQUAL_UINT8((uint8_t)f->seq, pft_frame_row(f, H - 1u)[W - 1u]);
        }
        hold(f);
    }
    return st;
}

static void give(const pft_frame_t *f)
{
    unhold(f);
    pft_tpl_release(&port, f);
}

static uint32_t consumed;
static pft_status_t consume(void *ctx, const pft_frame_t *f)
{
    (void)ctx;
    TEST_ASSERT_TRUE(is_buf(f->data));
    TEST_ASSERT_EQUAL_UINT8((uint8_t)f->seq, pft_frame_row(f, H - 1u)[W - 1u]);
    consumed++;
    return PFT_OK;
}

void setUp(void)
{
    consumed = 0u;
    check_pixels = true;
}
void tearDown(void) {}

static void test_runner_over_double_buffer(void)
{
    start(2u);
    cam.pending = 10u;
    pft_frame_source_t s = pft_tpl_as_source(&port);
    pft_runner_config_t cfg;
    memset(&cfg, 0, sizeof cfg);
    cfg.max_consecutive_errors = 1u; /* camera silent: stop */
    pft_runner_stats_t st;
    TEST_ASSERT_EQUAL_INT(PFT_ERR_TIMEOUT, pft_runner_run(&s, consume, NULL, NULL, &cfg, &st));
    TEST_ASSERT_EQUAL_UINT32(10u, st.frames);
    TEST_ASSERT_EQUAL_UINT32(10u, consumed);
    TEST_ASSERT_EQUAL_UINT32(0u, st.dropped);
    pft_tpl_stats_t ps = stats();
    TEST_ASSERT_EQUAL_UINT32(0u, ps.overruns);
    TEST_ASSERT_EQUAL_UINT32(0u, ps.bad_releases);
    TEST_ASSERT_EQUAL_UINT32(10u, ps.completed);
    TEST_ASSERT_EQUAL_UINT32(10u, cam.invalidates);
    TEST_ASSERT_EQUAL_UINT32(cam.locks, cam.unlocks);
    TEST_ASSERT_EQUAL_UINT32(11u, cam.starts); /* initial + one restart per frame */
    TEST_ASSERT_EQUAL_UINT32(0u, cam.set_nexts);
}

static void test_latest_frame_wins_and_pause(void)
{
    start(2u);
    cam_frame(true); /* seq 0 READY, DMA into the other buffer */
    cam_frame(true); /* seq 1 READY: seq 0 never taken, dropped */
    TEST_ASSERT_EQUAL_UINT32(1u, stats().overruns);
    pft_frame_t f;
    TEST_ASSERT_EQUAL_INT(PFT_OK, take(&f));
    TEST_ASSERT_EQUAL_UINT32(1u, f.seq);
    TEST_ASSERT_EQUAL_UINT64(2000u, f.timestamp_us);
    /* holding nbuf - 1 frames: one more is refused */
    pft_frame_t g;
    TEST_ASSERT_EQUAL_INT(PFT_ERR_STATE, pft_tpl_acquire(&port, &g, 0u));
    cam_frame(true); /* seq 2 READY; no FREE buffer: the camera pauses */
    TEST_ASSERT_FALSE(cam.armed);
    uint32_t starts = cam.starts;
    pft_tpl_on_frame_done(&port, 99u, true); /* spurious interrupt while paused: ignored */
    TEST_ASSERT_EQUAL_UINT32(3u, stats().completed);
    TEST_ASSERT_EQUAL_UINT8(1u, pft_frame_row(&f, 0u)[0]); /* lent pixels untouched */
    give(&f);
    TEST_ASSERT_EQUAL_UINT32(starts + 1u, cam.starts); /* release resumed the camera */
    TEST_ASSERT_EQUAL_INT(PFT_OK, take(&g));
    TEST_ASSERT_EQUAL_UINT32(2u, g.seq);
    give(&g);
    pft_tpl_release(&port, &g);
    TEST_ASSERT_EQUAL_UINT32(1u, stats().bad_releases);
    TEST_ASSERT_EQUAL_UINT32(0u, cam.writes_into_lent);
}

static void test_dma_error_and_timeout(void)
{
    start(3u);
    cam_frame(false); /* transfer error: seq 0 lost, same buffer again */
    TEST_ASSERT_EQUAL_UINT32(1u, stats().dma_errors);
    pft_frame_t f;
    TEST_ASSERT_EQUAL_INT(PFT_ERR_TIMEOUT, pft_tpl_acquire(&port, &f, 5u));
    TEST_ASSERT_NULL(f.data);
    cam.pending = 1u;
    TEST_ASSERT_EQUAL_INT(PFT_OK, take(&f));
    TEST_ASSERT_EQUAL_UINT32(1u, f.seq); /* the runner would count one dropped frame */
    pft_frame_t g;
    cam.pending = 1u;
    TEST_ASSERT_EQUAL_INT(PFT_OK, take(&g)); /* 3 buffers: hold 2 */
    TEST_ASSERT_TRUE(f.data != g.data);
    give(&f);
    give(&g);
    TEST_ASSERT_EQUAL_UINT32(0u, stats().bad_releases);
    TEST_ASSERT_EQUAL_UINT32(0u, stats().lent);
}

typedef struct {
    uint32_t calls;
    uint32_t seq[16];
} sink_log_t;
static sink_log_t sink_log;

static void on_sink(void *ctx, uint32_t seq, uint64_t ts)
{
    sink_log_t *l = (sink_log_t *)ctx;
    TEST_ASSERT_EQUAL_UINT64(1000u * (seq + 1u), ts);
    if (l->calls < 16u) {
        l->seq[l->calls] = seq;
    }
    l->calls++;
}

/* Circular mode over 12 frames with `nbuf` buffers and a consumer that either releases each
 * frame before the next frame end (hold = false) or holds it until the next one is acquired
 * (hold = true, a tracker running while the camera goes on). Frames with nowhere to go land
 * in the sink: counted, reported, seen as seq gaps; the DMA never writes a lent buffer and is
 * started once. `pattern`: 'd' delivered, 's' sink, per frame. */
static void check_circular_rate(uint32_t nbuf, bool hold_across, const char *pattern)
{
    memset(&sink_log, 0, sizeof sink_log);
    pft_tpl_config_t c = config(PFT_TPL_CIRCULAR, nbuf);
    c.on_sink = on_sink;
    c.on_sink_ctx = &sink_log;
    start_cfg(&c);
    TEST_ASSERT_EQUAL_UINT32(1u, cam.set_nexts); /* both registers set before the start */
    pft_frame_t prev;
    bool have_prev = false;
    uint32_t delivered = 0u, sunk = 0u, last_seq = 0u, gaps = 0u, sink_between = 0u;
    for (uint32_t k = 0u; k < 12u; ++k) {
        cam_frame(true);
        pft_frame_t f;
        pft_status_t st = take(&f);
        if (pattern[k] == 'd') {
            TEST_ASSERT_EQUAL_INT(PFT_OK, st);
            TEST_ASSERT_EQUAL_UINT32(k, f.seq);
            TEST_ASSERT_EQUAL_UINT64(1000u * (k + 1u), f.timestamp_us);
            if (delivered > 0u) {
                gaps += f.seq - last_seq - 1u;
                sink_between = sunk;
            }
            last_seq = f.seq;
            delivered++;
        } else {
            TEST_ASSERT_EQUAL_INT(PFT_ERR_TIMEOUT, st); /* woken, but the frame was sunk */
            TEST_ASSERT_EQUAL_UINT32(k, sink_log.seq[sunk]);
            sunk++;
        }
        if (!hold_across && st == PFT_OK) {
            give(&f);
        } else {
            if (have_prev) {
                give(&prev);
            }
            have_prev = (st == PFT_OK);
            prev = f;
        }
    }
    if (have_prev) {
        give(&prev);
    }
    pft_tpl_stats_t s = stats();
    TEST_ASSERT_EQUAL_UINT32(12u, s.completed);
    TEST_ASSERT_EQUAL_UINT32(sunk, s.sink_frames);
    TEST_ASSERT_EQUAL_UINT32(sunk, sink_log.calls);
    TEST_ASSERT_EQUAL_UINT32(sunk, cam.sink_writes);
    TEST_ASSERT_EQUAL_UINT32(sink_between, gaps); /* every loss is a gap in seq */
    TEST_ASSERT_EQUAL_UINT32(0u, s.overruns);
    TEST_ASSERT_EQUAL_UINT32(0u, s.bad_releases);
    TEST_ASSERT_EQUAL_UINT32(0u, s.lent);
    TEST_ASSERT_EQUAL_UINT32(0u, cam.writes_into_lent);
    TEST_ASSERT_EQUAL_UINT32(1u, cam.starts);     /* never restarted */
    TEST_ASSERT_EQUAL_UINT32(13u, cam.set_nexts); /* start + one per frame end */
    TEST_ASSERT_EQUAL_UINT32(cam.locks, cam.unlocks);
}

static void test_circular_rates(void)
{
    check_circular_rate(3u, false, "dddddddddddd");
    check_circular_rate(2u, false, "ddsddsddsdds");
    check_circular_rate(4u, true, "dddddddddddd");
    check_circular_rate(3u, true, "dddsdddsddds");
    check_circular_rate(2u, true, "ddssddssddss");
}

/* Circular: the application may hold every buffer; frames then go to the sink, and a
 * released buffer is a DMA target again from the second frame end after the release. */
static void test_circular_all_buffers_held(void)
{
    pft_tpl_config_t c = config(PFT_TPL_CIRCULAR, 2u);
    start_cfg(&c);
    pft_frame_t a, b, x;
    cam_frame(true);
    TEST_ASSERT_EQUAL_INT(PFT_OK, take(&a)); /* seq 0 */
    cam_frame(true);
    TEST_ASSERT_EQUAL_INT(PFT_OK, take(&b)); /* seq 1 */
    TEST_ASSERT_TRUE(a.data != b.data);
    TEST_ASSERT_EQUAL_INT(PFT_ERR_STATE, pft_tpl_acquire(&port, &x, 0u)); /* limit: nbuf */
    for (uint32_t k = 0; k < 5u; ++k) {
        cam_frame(true); /* seq 2..6: nowhere to go but the sink */
    }
    TEST_ASSERT_EQUAL_UINT32(5u, stats().sink_frames);
    TEST_ASSERT_EQUAL_UINT8(0u, pft_frame_row(&a, 0u)[0]); /* lent pixels untouched */
    TEST_ASSERT_EQUAL_UINT8(1u, pft_frame_row(&b, 0u)[0]);
    give(&a);
    cam_frame(true); /* seq 7 into the sink; a becomes the target after next */
    cam_frame(true); /* seq 8 into the sink; the DMA now fills a */
    TEST_ASSERT_EQUAL_UINT32(7u, stats().sink_frames);
    TEST_ASSERT_EQUAL_INT(PFT_ERR_TIMEOUT, pft_tpl_acquire(&port, &x, 0u));
    cam_frame(true); /* seq 9 into a */
    TEST_ASSERT_EQUAL_INT(PFT_OK, take(&x));
    TEST_ASSERT_EQUAL_UINT32(9u, x.seq);
    TEST_ASSERT_TRUE(x.data == a.data);
    give(&x);
    give(&b);
    TEST_ASSERT_EQUAL_UINT32(0u, cam.writes_into_lent);
    TEST_ASSERT_EQUAL_UINT32(0u, stats().lent);
}

/* Circular: a transfer error frees its buffer and costs one seq; the DMA keeps running. */
static void test_circular_dma_error(void)
{
    pft_tpl_config_t c = config(PFT_TPL_CIRCULAR, 3u);
    start_cfg(&c);
    cam_frame(false); /* seq 0 lost */
    pft_frame_t f;
    TEST_ASSERT_EQUAL_INT(PFT_ERR_TIMEOUT, pft_tpl_acquire(&port, &f, 0u));
    cam_frame(true);
    TEST_ASSERT_EQUAL_INT(PFT_OK, take(&f));
    TEST_ASSERT_EQUAL_UINT32(1u, f.seq);
    give(&f);
    for (uint32_t k = 0; k < 6u; ++k) { /* the failed buffer is used again */
        cam_frame(true);
        TEST_ASSERT_EQUAL_INT(PFT_OK, take(&f));
        TEST_ASSERT_EQUAL_UINT32(2u + k, f.seq);
        give(&f);
    }
    pft_tpl_stats_t s = stats();
    TEST_ASSERT_EQUAL_UINT32(1u, s.dma_errors);
    TEST_ASSERT_EQUAL_UINT32(0u, s.sink_frames);
    TEST_ASSERT_EQUAL_UINT32(1u, cam.starts);
}

/* The sensor's own counter gives seq: an 8-bit counter wraps (seq goes on past 255), frames
 * the sensor made but the DMA never saw are gaps, a counter that did not move is counted and
 * taken as +1, and frames without a timestamp get one from the frame period. */
static void test_sensor_counter_gives_seq(void)
{
    pft_tpl_config_t c = config(PFT_TPL_CIRCULAR, 3u);
    c.counter_bits = 8u;
    c.frame_period_us = 20000u;
    start_cfg(&c);
    cam.use_counter = true;
    cam.no_time = true;
    cam.counter = 250u;
    uint32_t expect[] = {250u, 251u, 252u, 253u, 254u, 255u, 256u, 257u};
    pft_frame_t f;
    for (uint32_t k = 0; k < 8u; ++k) {
        cam_frame(true);
        TEST_ASSERT_EQUAL_INT(PFT_OK, take(&f));
        TEST_ASSERT_EQUAL_UINT32(expect[k], f.seq);
        TEST_ASSERT_EQUAL_UINT64(20000u * k, f.timestamp_us);
        give(&f);
    }
    cam.counter += 3u; /* the sensor made 3 frames the interface lost */
    cam_frame(true);
    TEST_ASSERT_EQUAL_INT(PFT_OK, take(&f));
    TEST_ASSERT_EQUAL_UINT32(261u, f.seq);
    TEST_ASSERT_EQUAL_UINT64(20000u * 11u, f.timestamp_us);
    give(&f);
    cam.counter -= 1u; /* the counter repeats */
    cam_frame(true);
    check_pixels = false; /* from here seq runs one ahead of the counter */
    TEST_ASSERT_EQUAL_INT(PFT_OK, take(&f));
    TEST_ASSERT_EQUAL_UINT32(262u, f.seq);
    TEST_ASSERT_EQUAL_UINT8(261u & 0xFFu, pft_frame_row(&f, 0u)[0]);
    give(&f);
    TEST_ASSERT_EQUAL_UINT32(1u, stats().counter_repeats);
    /* with timestamps from the ISR, those are used as they are */
    cam.no_time = false;
    cam_frame(true);
    TEST_ASSERT_EQUAL_INT(PFT_OK, take(&f));
    TEST_ASSERT_EQUAL_UINT32(263u, f.seq);
    TEST_ASSERT_EQUAL_UINT64(cam.t, f.timestamp_us);
    give(&f);
}

/* A 32-bit counter is seq itself, in one-shot mode too. */
static void test_counter_oneshot_32bit(void)
{
    start(2u);
    cam.use_counter = true;
    cam.counter = 0xFFFFFFFEu;
    pft_frame_t f;
    cam_frame(true);
    TEST_ASSERT_EQUAL_INT(PFT_OK, take(&f));
    TEST_ASSERT_EQUAL_UINT32(0xFFFFFFFEu, f.seq);
    give(&f);
    cam.counter_step = 2u;
    cam_frame(true); /* counter 0xFFFFFFFF */
    cam_frame(true); /* counter 1 (the sensor skipped 0): 0xFFFFFFFF overrun, never taken */
    TEST_ASSERT_EQUAL_INT(PFT_OK, take(&f));
    TEST_ASSERT_EQUAL_UINT32(1u, f.seq);
    give(&f);
    TEST_ASSERT_EQUAL_UINT32(1u, stats().overruns);
}

/* Stop: the READY frame is still lent, then EOF on every call; interrupts after stop are
 * ignored; start resumes. Before the first start acquire is PFT_ERR_STATE. */
static void test_stop_eof_restart(void)
{
    for (uint32_t mode = 0; mode < 2u; ++mode) {
        pft_tpl_config_t c = config(mode == 0u ? PFT_TPL_ONESHOT : PFT_TPL_CIRCULAR, 3u);
        memset(&cam, 0, sizeof cam);
        memset(held, 0, sizeof held);
        cam.circular = (mode != 0u);
        pft_tpl_driver_t d = driver();
        TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tpl_init(&port, &d, &c));
        pft_frame_t f;
        TEST_ASSERT_EQUAL_INT(PFT_ERR_STATE, pft_tpl_acquire(&port, &f, 0u));
        TEST_ASSERT_EQUAL_INT(PFT_ERR_STATE, pft_tpl_stop(&port));
        TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tpl_start(&port));
        cam_frame(true);
        cam_frame(true);
        TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tpl_stop(&port));
        TEST_ASSERT_EQUAL_UINT32(1u, cam.stops);
        TEST_ASSERT_EQUAL_INT(PFT_ERR_STATE, pft_tpl_stop(&port));
        pft_tpl_on_frame_done(&port, 0u, true); /* late interrupt: ignored */
        TEST_ASSERT_EQUAL_INT(PFT_OK, take(&f));
        TEST_ASSERT_EQUAL_UINT32(1u, f.seq);
        for (uint32_t k = 0; k < 3u; ++k) {
            pft_frame_t g;
            TEST_ASSERT_EQUAL_INT(PFT_ERR_EOF, pft_tpl_acquire(&port, &g, 0u));
        }
        give(&f);
        TEST_ASSERT_EQUAL_UINT32(2u, stats().completed);
        TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tpl_start(&port));
        cam_frame(true);
        TEST_ASSERT_EQUAL_INT(PFT_OK, take(&f));
        TEST_ASSERT_EQUAL_UINT32(2u, f.seq);
        give(&f);
        TEST_ASSERT_EQUAL_UINT32(0u, cam.writes_into_lent);
        TEST_ASSERT_EQUAL_UINT32(cam.locks, cam.unlocks);
    }
}

static void test_arguments(void)
{
    pft_tpl_driver_t d = driver();
    pft_tpl_config_t c = config(PFT_TPL_ONESHOT, 2u);
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_tpl_init(NULL, &d, &c));
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_tpl_init(&port, NULL, &c));
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_tpl_init(&port, &d, NULL));
    c.nbuf = 1u;
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_tpl_init(&port, &d, &c));
    c.nbuf = PFT_TPL_MAX_BUFFERS + 1u;
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_tpl_init(&port, &d, &c));
    c = config(PFT_TPL_ONESHOT, 3u);
    c.bufs[2] = NULL;
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_tpl_init(&port, &d, &c));
    c = config(PFT_TPL_ONESHOT, 2u);
    c.format = (pft_pixfmt_t)0;
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_tpl_init(&port, &d, &c));
    c = config(PFT_TPL_ONESHOT, 2u);
    c.stride = 3u;
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_tpl_init(&port, &d, &c));
    c = config(PFT_TPL_ONESHOT, 2u);
    c.counter_bits = 33u;
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_tpl_init(&port, &d, &c));
    c = config(PFT_TPL_ONESHOT, 2u);
    c.mode = (pft_tpl_mode_t)7;
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_tpl_init(&port, &d, &c));
    c = config(PFT_TPL_ONESHOT, 2u);
    c.sink = NULL; /* not needed one-shot */
    d.set_next = NULL;
    d.dma_stop = NULL;
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tpl_init(&port, &d, &c));
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_tpl_stop(&port)); /* no dma_stop */
    c.mode = PFT_TPL_CIRCULAR;
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_tpl_init(&port, &d, &c)); /* no set_next... */
    d.set_next = cam_set_next;
    d.dma_stop = cam_stop;
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_tpl_init(&port, &d, &c)); /* ...no sink */
    c.sink = sink_mem;
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tpl_init(&port, &d, &c));
    d.wait_frame = NULL;
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_tpl_init(&port, &d, &c));
    d = driver();
    d.dma_start = NULL;
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_tpl_init(&port, &d, &c));
    pft_frame_t f;
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_tpl_acquire(NULL, &f, 0u));
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_tpl_acquire(&port, NULL, 0u));
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_tpl_start(NULL));
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_tpl_stop(NULL));
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_tpl_get_stats(NULL, NULL));
    pft_tpl_release(NULL, &f);
    pft_tpl_on_frame_done(NULL, 0u, true);
    pft_tpl_config_default(NULL);
    pft_tpl_config_default(&c);
    TEST_ASSERT_EQUAL_INT(PFT_TPL_ONESHOT, c.mode);
    TEST_ASSERT_EQUAL_UINT8(32u, c.counter_bits);
    TEST_ASSERT_EQUAL_UINT32(0u, c.nbuf);
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_runner_over_double_buffer);
    RUN_TEST(test_latest_frame_wins_and_pause);
    RUN_TEST(test_dma_error_and_timeout);
    RUN_TEST(test_circular_rates);
    RUN_TEST(test_circular_all_buffers_held);
    RUN_TEST(test_circular_dma_error);
    RUN_TEST(test_sensor_counter_gives_seq);
    RUN_TEST(test_counter_oneshot_32bit);
    RUN_TEST(test_stop_eof_restart);
    RUN_TEST(test_arguments);
    return UNITY_END();
}
