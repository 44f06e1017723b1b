/* Template port with a simulated camera DMA: frames flow, nothing is copied, a frame nobody
 * took is replaced by the newer one, the camera pauses and resumes, DMA errors are counted. */
#include <string.h>
#include "pft_test_support.h"
#include "pft/pft_port_template.h"

#define W 4u
#define H 3u

static uint8_t bufs_mem[3][W * H];
static void *const bufs[3] = {bufs_mem[0], bufs_mem[1], bufs_mem[2]};
static pft_tpl_port_t port;

/* Simulated camera: dma_start remembers the target; a "frame" writes value v into it and
 * raises the ISR. wait_frame delivers one pending frame, as if it arrived while waiting. */
typedef struct {
    void *target;
    uint32_t starts;
    uint32_t pending;
    uint8_t value;
    uint64_t t;
    uint32_t locks, unlocks, invalidates;
} cam_t;
static cam_t cam;

static void cam_dma_start(void *drv, void *buf, uint32_t bytes)
{
    cam_t *c = (cam_t *)drv;
    TEST_ASSERT_EQUAL_UINT32(W * H, bytes);
    c->target = buf;
    c->starts++;
}

static void cam_frame(bool ok)
{
    if (cam.target != NULL && port.dma_buf >= 0) {
        memset(cam.target, cam.value, W * H);
    }
    cam.value++;
    cam.t += 1000u;
    pft_tpl_on_frame_done(&port, cam.t, ok);
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

static void start(uint32_t nbuf)
{
    memset(&cam, 0, sizeof cam);
    pft_tpl_driver_t d = {&cam, cam_dma_start, cam_wait, cam_lock, cam_unlock, cam_inval};
    TEST_ASSERT_EQUAL_INT(PFT_OK,
                          pft_tpl_init(&port, &d, bufs, nbuf, W, H, PFT_PIX_U8, 0u, 0u));
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tpl_start(&port));
    TEST_ASSERT_EQUAL_INT(PFT_ERR_STATE, pft_tpl_start(&port));
}

static uint32_t consumed;
static pft_status_t consume(void *ctx, const pft_frame_t *f)
{
    (void)ctx;
    /* the pixels are the DMA buffer itself and hold the frame's value */
    TEST_ASSERT_TRUE(f->data == bufs[0] || f->data == bufs[1] || f->data == bufs[2]);
    TEST_ASSERT_EQUAL_UINT8((uint8_t)f->seq, pft_frame_row(f, H - 1u)[W - 1u]);
    consumed++;
    return PFT_OK;
}

void setUp(void) { consumed = 0u; }
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
    TEST_ASSERT_EQUAL_UINT32(0u, port.overruns);
    TEST_ASSERT_EQUAL_UINT32(0u, port.bad_releases);
    TEST_ASSERT_EQUAL_UINT32(10u, cam.invalidates);
    TEST_ASSERT_EQUAL_UINT32(cam.locks, cam.unlocks);
    TEST_ASSERT_EQUAL_UINT32(11u, cam.starts); /* initial + one restart per frame */
}

static void test_latest_frame_wins_and_pause(void)
{
    start(2u);
    cam_frame(true); /* seq 0 READY, DMA into the other buffer */
    cam_frame(true); /* seq 1 READY: seq 0 never taken, dropped */
    TEST_ASSERT_EQUAL_UINT32(1u, port.overruns);
    pft_frame_t f;
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tpl_acquire(&port, &f, 0u));
    TEST_ASSERT_EQUAL_UINT32(1u, f.seq);
    TEST_ASSERT_EQUAL_UINT64(2000u, f.timestamp_us);
    /* holding nbuf - 1 frames: one more is refused */
    pft_frame_t g;
    TEST_ASSERT_EQUAL_INT(PFT_ERR_STATE, pft_tpl_acquire(&port, &g, 0u));
    cam_frame(true); /* seq 2 READY; no FREE buffer: the camera pauses */
    TEST_ASSERT_TRUE(port.dma_buf < 0);
    uint32_t starts = cam.starts;
    cam_frame(true); /* spurious interrupt while paused: ignored */
    TEST_ASSERT_EQUAL_UINT8(1u, pft_frame_row(&f, 0u)[0]); /* lent pixels untouched */
    pft_tpl_release(&port, &f);
    TEST_ASSERT_EQUAL_UINT32(starts + 1u, cam.starts); /* release resumed the camera */
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tpl_acquire(&port, &g, 0u));
    TEST_ASSERT_EQUAL_UINT32(2u, g.seq);
    pft_tpl_release(&port, &g);
    pft_tpl_release(&port, &g);
    TEST_ASSERT_EQUAL_UINT32(1u, port.bad_releases);
}

static void test_dma_error_and_timeout(void)
{
    start(3u);
    cam_frame(false); /* transfer error: seq 0 lost, same buffer again */
    TEST_ASSERT_EQUAL_UINT32(1u, port.dma_errors);
    pft_frame_t f;
    TEST_ASSERT_EQUAL_INT(PFT_ERR_TIMEOUT, pft_tpl_acquire(&port, &f, 5u));
    TEST_ASSERT_NULL(f.data);
    cam.pending = 1u;
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tpl_acquire(&port, &f, 5u));
    TEST_ASSERT_EQUAL_UINT32(1u, f.seq); /* the runner would count one dropped frame */
    pft_frame_t g;
    cam.pending = 1u;
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tpl_acquire(&port, &g, 5u)); /* 3 buffers: hold 2 */
    TEST_ASSERT_TRUE(f.data != g.data);
    pft_tpl_release(&port, &f);
    pft_tpl_release(&port, &g);
    TEST_ASSERT_EQUAL_UINT32(0u, port.bad_releases);
}

static void test_arguments(void)
{
    pft_tpl_driver_t d = {&cam, cam_dma_start, cam_wait, NULL, NULL, NULL};
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_tpl_init(NULL, &d, bufs, 2u, W, H, PFT_PIX_U8, 0u, 0u));
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_tpl_init(&port, NULL, bufs, 2u, W, H, PFT_PIX_U8, 0u, 0u));
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_tpl_init(&port, &d, NULL, 2u, W, H, PFT_PIX_U8, 0u, 0u));
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_tpl_init(&port, &d, bufs, 1u, W, H, PFT_PIX_U8, 0u, 0u));
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_tpl_init(&port, &d, bufs, 4u, W, H, PFT_PIX_U8, 0u, 0u));
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_tpl_init(&port, &d, bufs, 2u, W, H, (pft_pixfmt_t)0, 0u, 0u));
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_tpl_init(&port, &d, bufs, 2u, W, H, PFT_PIX_U8, 0u, 3u));
    d.wait_frame = NULL;
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_tpl_init(&port, &d, bufs, 2u, W, H, PFT_PIX_U8, 0u, 0u));
    pft_frame_t f;
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_tpl_acquire(NULL, &f, 0u));
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_tpl_start(NULL));
    pft_tpl_release(NULL, &f);
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_runner_over_double_buffer);
    RUN_TEST(test_latest_frame_wins_and_pause);
    RUN_TEST(test_dma_error_and_timeout);
    RUN_TEST(test_arguments);
    return UNITY_END();
}
