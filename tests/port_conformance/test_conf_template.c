/* The template port (port/template) passes the conformance check in both DMA modes, driven by
 * a simulated camera whose "ISR" runs while the check holds frames (tick) and while acquire
 * waits: one-shot with 2 and 3 buffers, circular with 2, 3 and 4 buffers (frames going to
 * the sink while the consumer holds buffers), the sensor's 8-bit frame counter wrapping, a
 * finite run ended by pft_tpl_stop and an endless one. Every frame the port lost (overrun,
 * sink) is a gap in seq, and the DMA never wrote a lent buffer. */
#include <string.h>
#include "pft_test_support.h"
#include "pft_port_conformance.h"
#include "pft/pft_port_template.h"

#define W 10u
#define H 4u
#define NB PFT_TPL_MAX_BUFFERS

static uint16_t bufs_mem[NB][W * H];
static uint16_t sink_mem[W * H];
static pft_tpl_port_t port;

/* Simulated hardware (as in tests/unit/test_port_template.c): one-shot arms one transfer;
 * circular has two address registers swapped by the hardware at each frame end. */
typedef struct {
    bool circular;
    bool armed;
    void *reg[2];
    uint32_t ct;
    uint32_t counter;    /* sensor frame counter */
    bool use_counter;
    uint32_t stop_after; /* stop the port after this many sensor frames; 0: never */
    bool silent;         /* starved: the camera delivers nothing */
    uint64_t t;
    uint32_t lent_mask;  /* buffers lent, kept by the port wrapper below */
    uint32_t writes_into_lent;
} cam_t;
static cam_t cam;

static uint32_t index_of(const void *p)
{
    for (uint32_t i = 0; i < NB; ++i) {
        if (p == (const void *)bufs_mem[i]) {
            return i;
        }
    }
    return NB;
}

static void dma_write(void *target)
{
    uint32_t i = index_of(target);
    if (i < NB && (cam.lent_mask & (1u << i)) != 0u) {
        cam.writes_into_lent++;
    }
    uint16_t *p = (uint16_t *)target;
    for (uint32_t k = 0; k < W * H; ++k) {
        p[k] = (uint16_t)(cam.counter * 31u + k);
    }
}

static void cam_dma_start(void *drv, void *buf, uint32_t bytes)
{
    cam_t *c = (cam_t *)drv;
    (void)bytes;
    c->reg[c->circular ? c->ct : 0u] = buf;
    c->armed = true;
}

static void cam_set_next(void *drv, void *buf, uint32_t bytes)
{
    cam_t *c = (cam_t *)drv;
    (void)bytes;
    c->reg[c->ct ^ 1u] = buf;
}

static void cam_stop(void *drv)
{
    cam_t *c = (cam_t *)drv;
    c->armed = false;
    c->ct = 0u;
}

/* One sensor frame: DMA write, hardware swap, ISR; the port is stopped after stop_after. */
static void cam_frame(void)
{
    if (cam.silent) {
        return;
    }
    cam.t += 33333u;
    if (cam.armed) {
        if (cam.circular) {
            dma_write(cam.reg[cam.ct]);
            cam.ct ^= 1u;
        } else {
            dma_write(cam.reg[0]);
            cam.armed = false;
        }
        if (cam.use_counter) {
            pft_tpl_on_frame_counted(&port, cam.counter, cam.t, 0u);
        } else {
            pft_tpl_on_frame_done(&port, cam.t, true);
        }
    }
    cam.counter++;
    if (cam.stop_after != 0u && cam.counter == cam.stop_after) {
        TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tpl_stop(&port));
    }
}

/* A frame arrives while acquire waits, unless the camera is silent or stopped. */
static bool cam_wait(void *drv, uint32_t timeout_ms)
{
    (void)drv;
    (void)timeout_ms;
    if (cam.silent || !cam.armed) {
        return false;
    }
    cam_frame();
    return true;
}

static void tick(void *ctx)
{
    (void)ctx;
    cam_frame();
}

static void starve(void *ctx, bool on)
{
    (void)ctx;
    cam.silent = on;
}

static uint32_t bad_releases(void *ctx)
{
    pft_tpl_stats_t s;
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tpl_get_stats((pft_tpl_port_t *)ctx, &s));
    return s.bad_releases;
}

/* The source handed to the check: the port itself, with the test noting which buffers are
 * lent so the simulated DMA can tell a write into one. */
static pft_status_t wrap_acquire(void *ctx, pft_frame_t *out, uint32_t timeout_ms)
{
    pft_status_t st = pft_tpl_acquire(ctx, out, timeout_ms);
    if (st == PFT_OK) {
        uint32_t i = index_of(out->data);
        TEST_ASSERT_TRUE(i < NB);
        cam.lent_mask |= 1u << i;
    }
    return st;
}

static void wrap_release(void *ctx, const pft_frame_t *f)
{
    uint32_t i = index_of(f->data);
    pft_tpl_stats_t before, after;
    (void)pft_tpl_get_stats(&port, &before);
    pft_tpl_release(ctx, f);
    (void)pft_tpl_get_stats(&port, &after);
    if (i < NB && after.bad_releases == before.bad_releases) {
        cam.lent_mask &= ~(1u << i); /* really given back */
    }
}

typedef struct {
    pft_tpl_mode_t mode;
    uint32_t nbuf;
    bool use_counter;
    uint32_t stop_after; /* 0: endless */
    uint32_t first_counter;
} run_t;

static pft_conf_report_t rep;
static pft_tpl_stats_t stats;

static void run(const run_t *rc)
{
    memset(&cam, 0, sizeof cam);
    cam.circular = (rc->mode == PFT_TPL_CIRCULAR);
    cam.use_counter = rc->use_counter;
    cam.counter = rc->first_counter;
    cam.stop_after = (rc->stop_after != 0u) ? rc->first_counter + rc->stop_after : 0u;
    pft_tpl_driver_t d = {&cam, cam_dma_start, cam_wait, NULL, NULL, NULL, cam_set_next, cam_stop};
    pft_tpl_config_t c;
    pft_tpl_config_default(&c);
    c.mode = rc->mode;
    for (uint32_t i = 0; i < rc->nbuf; ++i) {
        c.bufs[i] = bufs_mem[i];
    }
    c.nbuf = rc->nbuf;
    c.sink = sink_mem;
    c.width = W;
    c.height = H;
    c.format = PFT_PIX_U16;
    c.bit_depth = 14u;
    c.counter_bits = rc->use_counter ? 8u : 32u;
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tpl_init(&port, &d, &c));
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tpl_start(&port));

    pft_frame_source_t src = {&port, wrap_acquire, wrap_release};
    pft_conf_spec_t s;
    pft_conf_spec_default(&s);
    s.width = W;
    s.height = H;
    s.fmt_mask = PFT_FMT_BIT(PFT_PIX_U16);
    s.frames = (rc->stop_after != 0u) ? PFT_CONF_FINITE : PFT_CONF_ENDLESS;
    s.endless_frames = 80u;
    s.max_lent = (rc->mode == PFT_TPL_CIRCULAR) ? rc->nbuf : rc->nbuf - 1u;
    s.can_timeout = true;
    s.timeout_ms = 10u;
    s.hook_ctx = &port;
    s.tick = tick;
    s.starve = starve;
    s.bad_releases = bad_releases;
    bool ok = pft_conf_run(&src, &s, &rep);
    TEST_ASSERT_EQUAL_UINT32_MESSAGE(0u, rep.total, rep.first);
    TEST_ASSERT_TRUE(ok);
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tpl_get_stats(&port, &stats));
    TEST_ASSERT_EQUAL_UINT32(0u, stats.lent);
    TEST_ASSERT_EQUAL_UINT32(0u, cam.writes_into_lent);
    TEST_ASSERT_EQUAL_UINT32(rep.bad_releases, stats.bad_releases);
    TEST_ASSERT_EQUAL_UINT32(0u, stats.dma_errors);
}

/* Port-counted seq (0, 1, 2, ...): every completed frame was lent or lost, and every loss
 * between the first and the last lent frame is exactly one gap. */
static void check_losses_are_gaps(void)
{
    uint32_t losses = stats.overruns + stats.sink_frames + stats.dma_errors;
    TEST_ASSERT_EQUAL_UINT32(stats.completed, rep.frames + losses);
    uint32_t outside = rep.first_seq + (stats.completed - 1u - rep.last_seq);
    TEST_ASSERT_EQUAL_UINT32(losses - outside, rep.gaps);
}

void setUp(void) {}
void tearDown(void) {}

static void test_oneshot_finite(void)
{
    /* 3 buffers: while the check holds a frame the camera runs on; frames nobody took are
     * replaced by newer ones (overruns), each a gap */
    run_t r3 = {PFT_TPL_ONESHOT, 3u, false, 60u, 0u};
    run(&r3);
    TEST_ASSERT_TRUE(rep.ended);
    TEST_ASSERT_TRUE(stats.overruns > 0u);
    check_losses_are_gaps();
    /* 2 buffers: the camera pauses instead (no overrun). Frames the sensor made during a
     * pause never reach the port; numbered by the port they leave no gap... */
    run_t r2 = {PFT_TPL_ONESHOT, 2u, false, 60u, 0u};
    run(&r2);
    TEST_ASSERT_TRUE(rep.ended);
    TEST_ASSERT_EQUAL_UINT32(0u, stats.overruns);
    TEST_ASSERT_TRUE(stats.completed < 60u);
    TEST_ASSERT_EQUAL_UINT32(0u, rep.gaps);
    check_losses_are_gaps();
    /* ...numbered by the sensor's counter, each of them is a gap */
    run_t c2 = {PFT_TPL_ONESHOT, 2u, true, 60u, 0u};
    run(&c2);
    TEST_ASSERT_TRUE(rep.ended);
    TEST_ASSERT_EQUAL_UINT32(0u, stats.overruns);
    TEST_ASSERT_EQUAL_UINT32(60u - stats.completed - rep.first_seq - (59u - rep.last_seq),
                             rep.gaps);
    TEST_ASSERT_TRUE(rep.gaps > 0u);
}

static void test_circular_finite_with_sink(void)
{
    static const uint32_t nbufs[] = {2u, 3u, 4u};
    uint32_t sunk[3];
    for (uint32_t k = 0; k < 3u; ++k) {
        run_t rc = {PFT_TPL_CIRCULAR, nbufs[k], false, 60u, 0u};
        run(&rc);
        TEST_ASSERT_TRUE(rep.ended);
        TEST_ASSERT_TRUE(rep.gaps > 0u);
        check_losses_are_gaps();
        sunk[k] = stats.sink_frames;
    }
    /* the check holds up to nbuf frames at once, so every size sinks some frames; fewer
     * buffers sink more */
    TEST_ASSERT_TRUE(sunk[0] > 0u);
    TEST_ASSERT_TRUE(sunk[0] > sunk[2]);
}

static void test_endless_both_modes(void)
{
    run_t a = {PFT_TPL_ONESHOT, 3u, false, 0u, 0u};
    run(&a);
    TEST_ASSERT_FALSE(rep.ended);
    TEST_ASSERT_TRUE(rep.frames >= 80u);
    run_t b = {PFT_TPL_CIRCULAR, 2u, false, 0u, 0u};
    run(&b);
    TEST_ASSERT_FALSE(rep.ended);
    TEST_ASSERT_TRUE(rep.frames >= 80u);
    TEST_ASSERT_TRUE(stats.sink_frames > 0u);
}

/* seq from the sensor's 8-bit counter, starting near its wrap: 300 sensor frames, so the
 * counter wraps more than once and seq keeps increasing past 255 (the check would report
 * a seq going back). */
static void test_sensor_counter_wraps(void)
{
    run_t rc = {PFT_TPL_CIRCULAR, 3u, true, 300u, 250u};
    run(&rc);
    TEST_ASSERT_TRUE(rep.ended);
    TEST_ASSERT_EQUAL_UINT32(250u, rep.first_seq);
    TEST_ASSERT_TRUE(rep.last_seq > 500u);
    TEST_ASSERT_TRUE(rep.last_seq <= 549u);
    TEST_ASSERT_EQUAL_UINT32(0u, stats.counter_repeats);
    uint32_t losses = stats.overruns + stats.sink_frames;
    TEST_ASSERT_EQUAL_UINT32(stats.completed, rep.frames + losses);
    TEST_ASSERT_EQUAL_UINT32(losses - (549u - rep.last_seq), rep.gaps);
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_oneshot_finite);
    RUN_TEST(test_circular_finite_with_sink);
    RUN_TEST(test_endless_both_modes);
    RUN_TEST(test_sensor_counter_wraps);
    return UNITY_END();
}
