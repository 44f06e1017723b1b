/* Refused calls of every port leave the port's state and the caller's buffers byte-identical
 * (memcmp against a snapshot taken just before), as the trackers' refused updates do. Where a
 * port documents a counter for a refused call (mem: state_errors, bad_releases; file and
 * template: bad_releases), the expected state is the snapshot with exactly that counter one
 * higher. Output parameters that a failed call documents as cleared (the frame of a failed
 * acquire, the pixels pointer of a failed write_begin) are checked to be cleared. */
#include <string.h>
#include "pft_test_support.h"
#include "pft/pft_port_file.h"
#include "pft/pft_port_mem.h"
#include "pft/pft_port_template.h"
#if defined(PFT_PORT_MPS2)
#include "pft/pft_port_mps2.h"
#endif

#define W 6u
#define H 4u

void setUp(void) {}
void tearDown(void) {}

/* Snapshot of an object (instance, or caller buffer) and the check that it did not move. */
static uint8_t g_snap[4096];
static uint8_t g_snap2[4096];
#define SNAP(obj)                                                                             \
    do {                                                                                      \
        TEST_ASSERT_TRUE(sizeof(obj) <= sizeof g_snap);                                       \
        memcpy(g_snap, &(obj), sizeof(obj));                                                  \
    } while (0)
#define SAME(obj) TEST_ASSERT_EQUAL_MEMORY(g_snap, &(obj), sizeof(obj))
#define SNAP2(obj)                                                                            \
    do {                                                                                      \
        TEST_ASSERT_TRUE(sizeof(obj) <= sizeof g_snap2);                                      \
        memcpy(g_snap2, &(obj), sizeof(obj));                                                 \
    } while (0)
#define SAME2(obj) TEST_ASSERT_EQUAL_MEMORY(g_snap2, &(obj), sizeof(obj))

static bool frame_is_zero(const pft_frame_t *f)
{
    static const pft_frame_t zero;
    return memcmp(f, &zero, sizeof zero) == 0;
}

static pft_frame_t garbage_frame(void)
{
    pft_frame_t f;
    memset(&f, 0x5A, sizeof f);
    return f;
}

/* ------------------------------------- file port ------------------------------------------ */
static uint8_t fbuf[2u * W * H * 3u];
static pft_file_source_t fs;

static pft_file_config_t fcfg(const char *path, pft_file_layout_t layout, pft_file_encoding_t enc)
{
    pft_file_config_t c;
    memset(&c, 0, sizeof c);
    c.path = path;
    c.layout = layout;
    c.encoding = enc;
    c.buffer = fbuf;
    c.buffer_bytes = sizeof fbuf;
    c.slots = 2u;
    return c;
}

static void write_pgm(const char *name, uint8_t v)
{
    static uint8_t px[W * H];
    memset(px, v, sizeof px);
    pft_frame_t f;
    memset(&f, 0, sizeof f);
    f.data = px;
    f.width = W;
    f.height = H;
    f.stride_bytes = W;
    f.format = PFT_PIX_U8;
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_pnm_write(name, &f));
}

static bool file_exists(const char *name)
{
    pft_frame_t f;
    pft_file_error_t e;
    static uint8_t tmp[16];
    return pft_pnm_read(name, tmp, sizeof tmp, &f, &e) != PFT_ERR_IO || e != PFT_FILE_E_OPEN;
}

static void test_file_source_init_refusals_leave_source_unchanged(void)
{
    write_pgm("pft_tpr_c.pgm", 7u);
    pft_file_config_t c = fcfg("pft_tpr_c.pgm", PFT_FILE_CONCAT, PFT_FILE_PNM);
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_file_source_init(&fs, &c)); /* a live, open source */
    pft_frame_t g;
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_file_acquire(&fs, &g, 0u)); /* one frame lent */
    SNAP(fs);
    SNAP2(fbuf);
    static char long_name[PFT_FILE_NAME_MAX + 8u];
    memset(long_name, 'a', sizeof long_name - 1u);
    long_name[sizeof long_name - 1u] = '\0';
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_file_source_init(&fs, NULL));
    pft_file_config_t b;
    b = c; b.path = NULL;
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_file_source_init(&fs, &b));
    b = c; b.buffer = NULL;
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_file_source_init(&fs, &b));
    b = c; b.slots = PFT_FILE_MAX_SLOTS + 1u;
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_file_source_init(&fs, &b));
    b = c; b.layout = (pft_file_layout_t)7;
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_file_source_init(&fs, &b));
    b = c; b.encoding = (pft_file_encoding_t)7;
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_file_source_init(&fs, &b));
    b = c; b.path = long_name;
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_file_source_init(&fs, &b));
    b = c; b.layout = PFT_FILE_PER_FRAME; b.path = "f%u%s.pgm";
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_file_source_init(&fs, &b));
    b = c; b.layout = PFT_FILE_PER_FRAME; b.path = long_name;
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_file_source_init(&fs, &b));
    b = c; b.encoding = PFT_FILE_RAW; /* no geometry */
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_file_source_init(&fs, &b));
    b.width = W; b.height = H; b.format = (pft_pixfmt_t)9;
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_file_source_init(&fs, &b));
    b.format = PFT_PIX_U16; b.bit_depth = 17u;
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_file_source_init(&fs, &b));
    b.bit_depth = 0u; b.width = 200u;
    TEST_ASSERT_EQUAL_INT(PFT_ERR_NOMEM, pft_file_source_init(&fs, &b));
    b = c; b.path = "pft_tpr_missing.raw";
    TEST_ASSERT_EQUAL_INT(PFT_ERR_IO, pft_file_source_init(&fs, &b));
    SAME(fs);
    SAME2(fbuf);
    /* and the source still works: the lent frame comes back, the stream ends */
    pft_file_release(&fs, &g);
    TEST_ASSERT_EQUAL_INT(PFT_ERR_EOF, pft_file_acquire(&fs, &g, 0u));
    pft_file_source_close(&fs);
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_file_remove("pft_tpr_c.pgm"));
}

static void test_file_acquire_release_refusals(void)
{
    write_pgm("pft_tpr_s0.pgm", 1u);
    write_pgm("pft_tpr_s1.pgm", 2u);
    write_pgm("pft_tpr_s2.pgm", 3u);
    pft_file_config_t c = fcfg("pft_tpr_s%u.pgm", PFT_FILE_PER_FRAME, PFT_FILE_PNM);
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_file_source_init(&fs, &c));
    pft_frame_t a, b2, g;
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_file_acquire(&fs, &a, 0u));
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_file_acquire(&fs, &b2, 0u)); /* both slots lent */
    SNAP(fs);
    SNAP2(fbuf);
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_file_acquire(NULL, &g, 0u));
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_file_acquire(&fs, NULL, 0u));
    g = garbage_frame();
    TEST_ASSERT_EQUAL_INT(PFT_ERR_STATE, pft_file_acquire(&fs, &g, 0u));
    TEST_ASSERT_TRUE(frame_is_zero(&g));
    SAME(fs);
    SAME2(fbuf);
    /* a release of something not lent: only bad_releases moves */
    pft_frame_t foreign = a;
    foreign.data = fbuf + 1;
    pft_file_release(&fs, &foreign);
    pft_file_release(&fs, NULL);
    pft_file_release(NULL, &a);
    ((pft_file_source_t *)(void *)g_snap)->stats.bad_releases += 2u;
    SAME(fs);
    SAME2(fbuf);
    /* the end is sticky and changes nothing */
    pft_file_release(&fs, &a);
    pft_file_release(&fs, &b2);
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_file_acquire(&fs, &a, 0u));
    pft_file_release(&fs, &a);
    TEST_ASSERT_EQUAL_INT(PFT_ERR_EOF, pft_file_acquire(&fs, &a, 0u));
    SNAP(fs);
    TEST_ASSERT_EQUAL_INT(PFT_ERR_EOF, pft_file_acquire(&fs, &a, 0u));
    SAME(fs);
    for (unsigned k = 0; k < 3u; ++k) {
        char name[32];
        (void)snprintf(name, sizeof name, "pft_tpr_s%u.pgm", k);
        TEST_ASSERT_EQUAL_INT(PFT_OK, pft_file_remove(name));
    }
}

static void test_pnm_read_refusals_leave_buffers_unchanged(void)
{
    static uint8_t px[W * H];
    memset(px, 0x33, sizeof px);
    pft_frame_t out = garbage_frame();
    pft_file_error_t e = PFT_FILE_E_TRUNCATED;
    SNAP(px);
    SNAP2(out);
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_pnm_read(NULL, px, sizeof px, &out, &e));
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_pnm_read("x.pgm", NULL, sizeof px, &out, &e));
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_pnm_read("x.pgm", px, sizeof px, NULL, &e));
    TEST_ASSERT_EQUAL_INT(PFT_FILE_E_NONE, e);
    SAME(px);
    SAME2(out);
    /* headers refused before any pixel is read: the pixel buffer is untouched, out cleared */
    static const char *const bad[] = {"P2\n6 4\n255\n", "P5\n6 4\n0\n", "P6\n6 4\n65535\n",
                                      "P5\n600 400\n255\n", "P5\n6 x\n255\n"};
    static const pft_file_error_t why[] = {PFT_FILE_E_MAGIC, PFT_FILE_E_HEADER,
                                           PFT_FILE_E_UNSUPPORTED, PFT_FILE_E_TOO_BIG,
                                           PFT_FILE_E_HEADER};
    for (uint32_t i = 0; i < 5u; ++i) {
        pft_frame_t f;
        memset(&f, 0, sizeof f);
        f.data = bad[i];
        f.width = (uint16_t)strlen(bad[i]);
        f.height = 1u;
        f.stride_bytes = f.width;
        f.format = PFT_PIX_U8;
        TEST_ASSERT_EQUAL_INT(PFT_OK, pft_raw_write("pft_tpr_bad.pgm", &f, false));
        out = garbage_frame();
        TEST_ASSERT_EQUAL_INT(PFT_ERR_FORMAT, pft_pnm_read("pft_tpr_bad.pgm", px, sizeof px, &out, &e));
        TEST_ASSERT_EQUAL_INT(why[i], e);
        TEST_ASSERT_TRUE(frame_is_zero(&out));
        SAME(px);
    }
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_file_remove("pft_tpr_bad.pgm"));
}

static void test_writers_refusals_create_no_file(void)
{
    static float fpx[4];
    pft_frame_t f;
    memset(&f, 0, sizeof f);
    f.data = fpx;
    f.width = 2u;
    f.height = 2u;
    f.stride_bytes = 8u;
    f.format = PFT_PIX_F32;
    (void)pft_file_remove("pft_tpr_w.pgm");
    TEST_ASSERT_EQUAL_INT(PFT_ERR_FORMAT, pft_pnm_write("pft_tpr_w.pgm", &f)); /* F32 */
    f.format = PFT_PIX_U8;
    f.stride_bytes = 1u;
    TEST_ASSERT_EQUAL_INT(PFT_ERR_FORMAT, pft_pnm_write("pft_tpr_w.pgm", &f)); /* stride */
    TEST_ASSERT_EQUAL_INT(PFT_ERR_FORMAT, pft_raw_write("pft_tpr_w.pgm", &f, false));
    f.stride_bytes = 2u;
    f.data = NULL;
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_pnm_write("pft_tpr_w.pgm", &f));
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_raw_write("pft_tpr_w.pgm", &f, true));
    TEST_ASSERT_FALSE(file_exists("pft_tpr_w.pgm"));
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_file_remove(NULL));
    TEST_ASSERT_EQUAL_INT(PFT_ERR_IO, pft_file_remove("pft_tpr_w.pgm"));
}

/* -------------------------------------- mem port ------------------------------------------ */
static uint8_t ring[3u * W * H];
static pft_mem_source_t ms;

static pft_mem_config_t mcfg(void)
{
    pft_mem_config_t c;
    memset(&c, 0, sizeof c);
    c.buffer = ring;
    c.buffer_bytes = sizeof ring;
    c.slots = 3u;
    c.width = W;
    c.height = H;
    c.format = PFT_PIX_U8;
    c.max_lent = 1u;
    return c;
}

static void test_mem_refusals_leave_source_unchanged(void)
{
    static uint8_t px[W * H];
    memset(px, 9, sizeof px);
    pft_mem_config_t c = mcfg();
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_mem_source_init(&ms, &c));
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_mem_push(&ms, px, 0u, 10u));
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_mem_push(&ms, px, 0u, 20u));
    pft_frame_t lent;
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_mem_acquire(&ms, &lent, 0u));
    SNAP(ms);
    SNAP2(ring);
    /* init */
    static const pft_fault_at_t at[1] = {{1u, PFT_FAULT_DROP}};
    pft_mem_config_t b;
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_mem_source_init(&ms, NULL));
    b = c; b.buffer = NULL;
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_mem_source_init(&ms, &b));
    b = c; b.slots = 0u;
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_mem_source_init(&ms, &b));
    b = c; b.slots = PFT_MEM_MAX_SLOTS + 1u;
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_mem_source_init(&ms, &b));
    b = c; b.width = 0u;
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_mem_source_init(&ms, &b));
    b = c; b.format = (pft_pixfmt_t)0;
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_mem_source_init(&ms, &b));
    b = c; b.max_lent = 4u;
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_mem_source_init(&ms, &b));
    b = c; b.format = PFT_PIX_U16; b.bit_depth = 17u;
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_mem_source_init(&ms, &b));
    b = c; b.stride_bytes = W - 1u;
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_mem_source_init(&ms, &b));
    b = c; b.faults.prob_ppm[1] = 600000u; b.faults.prob_ppm[2] = 400001u;
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_mem_source_init(&ms, &b));
    b = c; b.faults.at_count = 1u;
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_mem_source_init(&ms, &b));
    b = c; b.faults.at = at; b.faults.at_count = 1u; b.buffer_bytes = sizeof ring - 1u;
    TEST_ASSERT_EQUAL_INT(PFT_ERR_NOMEM, pft_mem_source_init(&ms, &b));
    b = c; b.width = 0xFFFFu; b.height = 0xFFFFu; b.format = PFT_PIX_F32;
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_mem_source_init(&ms, &b)); /* slot above 4 GiB */
    SAME(ms);
    SAME2(ring);
    /* producer */
    void *pix = &pix;
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_mem_write_begin(NULL, &pix));
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_mem_write_begin(&ms, NULL));
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_mem_write_commit(NULL, 0u));
    TEST_ASSERT_EQUAL_INT(PFT_ERR_STATE, pft_mem_write_commit(&ms, 0u)); /* no write open */
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_mem_write_abort(NULL));
    TEST_ASSERT_EQUAL_INT(PFT_ERR_STATE, pft_mem_write_abort(&ms));
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_mem_push(NULL, px, 0u, 0u));
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_mem_push(&ms, NULL, 0u, 0u));
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_mem_push(&ms, px, W - 1u, 0u)); /* stride < row */
    SAME(ms);
    SAME2(ring);
    /* consumer: acquire above max_lent counts state_errors only, and clears out */
    pft_frame_t g = garbage_frame();
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_mem_acquire(NULL, &g, 0u));
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_mem_acquire(&ms, NULL, 0u));
    SAME(ms);
    TEST_ASSERT_EQUAL_INT(PFT_ERR_STATE, pft_mem_acquire(&ms, &g, 0u));
    TEST_ASSERT_TRUE(frame_is_zero(&g));
    ((pft_mem_source_t *)(void *)g_snap)->stats.state_errors++;
    SAME(ms);
    /* releases of what is not lent count bad_releases only */
    pft_frame_t foreign = lent;
    foreign.data = ring + 1;
    pft_mem_release(&ms, &foreign);
    pft_mem_release(&ms, NULL);
    pft_mem_release(NULL, &lent);
    ((pft_mem_source_t *)(void *)g_snap)->stats.bad_releases += 2u;
    SAME(ms);
    SAME2(ring);
    /* a write open: a second write_begin or a push is refused, nothing else moves */
    pft_mem_release(&ms, &lent);
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_mem_write_begin(&ms, &pix));
    SNAP(ms);
    void *pix2 = &pix2;
    TEST_ASSERT_EQUAL_INT(PFT_ERR_STATE, pft_mem_write_begin(&ms, &pix2));
    TEST_ASSERT_NULL(pix2);
    TEST_ASSERT_EQUAL_INT(PFT_ERR_STATE, pft_mem_push(&ms, px, 0u, 0u));
    SAME(ms);
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_mem_write_abort(&ms));
    /* closed: write_begin refused */
    pft_mem_close(&ms);
    SNAP(ms);
    TEST_ASSERT_EQUAL_INT(PFT_ERR_STATE, pft_mem_write_begin(&ms, &pix2));
    TEST_ASSERT_EQUAL_INT(PFT_ERR_STATE, pft_mem_push(&ms, px, 0u, 0u));
    SAME(ms);
}

/* ----------------------------------- template port ---------------------------------------- */
static uint8_t tbufs[3][W * H];
static uint8_t tsink[W * H];
static pft_tpl_port_t tp;
static uint32_t dma_calls;

static void t_dma_start(void *drv, void *buf, uint32_t bytes)
{
    (void)drv;
    (void)buf;
    (void)bytes;
    dma_calls++;
}
static bool t_wait(void *drv, uint32_t ms)
{
    (void)drv;
    (void)ms;
    return false;
}
static void t_set_next(void *drv, void *buf, uint32_t bytes)
{
    (void)drv;
    (void)buf;
    (void)bytes;
}
static void t_stop(void *drv)
{
    (void)drv;
}

static void tpl_setup(pft_tpl_driver_t *d, pft_tpl_config_t *c)
{
    memset(d, 0, sizeof *d);
    d->dma_start = t_dma_start;
    d->wait_frame = t_wait;
    d->set_next = t_set_next;
    d->dma_stop = t_stop;
    pft_tpl_config_default(c);
    c->bufs[0] = tbufs[0];
    c->bufs[1] = tbufs[1];
    c->bufs[2] = tbufs[2];
    c->nbuf = 3u;
    c->sink = tsink;
    c->width = W;
    c->height = H;
    c->format = PFT_PIX_U8;
}

static void test_template_refusals_leave_port_unchanged(void)
{
    pft_tpl_driver_t d;
    pft_tpl_config_t c;
    tpl_setup(&d, &c);
    /* not started: acquire refused */
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tpl_init(&tp, &d, &c));
    SNAP(tp);
    pft_frame_t g = garbage_frame();
    TEST_ASSERT_EQUAL_INT(PFT_ERR_STATE, pft_tpl_acquire(&tp, &g, 0u));
    TEST_ASSERT_TRUE(frame_is_zero(&g));
    TEST_ASSERT_EQUAL_INT(PFT_ERR_STATE, pft_tpl_stop(&tp));
    SAME(tp);
    /* running, one frame lent */
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tpl_start(&tp));
    pft_tpl_on_frame_done(&tp, 100u, true);
    pft_frame_t lent;
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tpl_acquire(&tp, &lent, 0u));
    pft_tpl_on_frame_done(&tp, 200u, true);
    pft_frame_t lent2;
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tpl_acquire(&tp, &lent2, 0u)); /* limit nbuf - 1 = 2 */
    SNAP(tp);
    SNAP2(tbufs);
    uint32_t calls = dma_calls;
    pft_tpl_driver_t bd;
    pft_tpl_config_t bc;
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_tpl_init(&tp, NULL, &c));
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_tpl_init(&tp, &d, NULL));
    bd = d; bd.dma_start = NULL;
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_tpl_init(&tp, &bd, &c));
    bd = d; bd.wait_frame = NULL;
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_tpl_init(&tp, &bd, &c));
    bc = c; bc.nbuf = 1u;
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_tpl_init(&tp, &d, &bc));
    bc = c; bc.nbuf = PFT_TPL_MAX_BUFFERS + 1u;
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_tpl_init(&tp, &d, &bc));
    bc = c; bc.bufs[1] = NULL;
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_tpl_init(&tp, &d, &bc));
    bc = c; bc.format = (pft_pixfmt_t)0;
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_tpl_init(&tp, &d, &bc));
    bc = c; bc.height = 0u;
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_tpl_init(&tp, &d, &bc));
    bc = c; bc.stride = W - 1u;
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_tpl_init(&tp, &d, &bc));
    bc = c; bc.counter_bits = 33u;
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_tpl_init(&tp, &d, &bc));
    bc = c; bc.format = PFT_PIX_U16; bc.bit_depth = 17u;
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_tpl_init(&tp, &d, &bc));
    bc = c; bc.mode = (pft_tpl_mode_t)5;
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_tpl_init(&tp, &d, &bc));
    bc = c; bc.mode = PFT_TPL_CIRCULAR; bc.sink = NULL;
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_tpl_init(&tp, &d, &bc));
    bc = c; bc.mode = PFT_TPL_CIRCULAR; bd = d; bd.set_next = NULL;
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_tpl_init(&tp, &bd, &bc));
    bc = c; bc.width = 0xFFFFu; bc.height = 0xFFFFu; bc.format = PFT_PIX_F32;
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_tpl_init(&tp, &d, &bc)); /* buffer above 4 GiB */
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_tpl_start(NULL));
    TEST_ASSERT_EQUAL_INT(PFT_ERR_STATE, pft_tpl_start(&tp)); /* already running */
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_tpl_stop(NULL));
    g = garbage_frame();
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_tpl_acquire(NULL, &g, 0u));
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_tpl_acquire(&tp, NULL, 0u));
    TEST_ASSERT_EQUAL_INT(PFT_ERR_STATE, pft_tpl_acquire(&tp, &g, 0u)); /* holds its limit */
    TEST_ASSERT_TRUE(frame_is_zero(&g));
    pft_tpl_stats_t st;
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_tpl_get_stats(NULL, &st));
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_tpl_get_stats(&tp, NULL));
    SAME(tp);
    SAME2(tbufs);
    TEST_ASSERT_EQUAL_UINT32(calls, dma_calls);
    /* releases of what is not lent count bad_releases only */
    pft_frame_t foreign = lent;
    foreign.data = tsink;
    pft_tpl_release(&tp, &foreign);
    pft_tpl_release(&tp, NULL);
    pft_tpl_release(NULL, &lent);
    ((pft_tpl_port_t *)(void *)g_snap)->bad_releases += 2u;
    SAME(tp);
    /* stop without a dma_stop is refused on a one-shot port */
    pft_tpl_driver_t nd = d;
    nd.dma_stop = NULL;
    static pft_tpl_port_t tp2;
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tpl_init(&tp2, &nd, &c));
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tpl_start(&tp2));
    SNAP(tp2);
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_tpl_stop(&tp2));
    SAME(tp2);
}

/* -------------------------------------- runner -------------------------------------------- */
static pft_status_t consume_nothing(void *ctx, const pft_frame_t *f)
{
    (void)ctx;
    (void)f;
    return PFT_OK;
}

static void test_runner_refusals_leave_source_unchanged(void)
{
    static uint8_t px[W * H];
    pft_mem_config_t c = mcfg();
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_mem_source_init(&ms, &c));
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_mem_push(&ms, px, 0u, 10u));
    pft_frame_source_t src = pft_mem_as_source(&ms);
    SNAP(ms);
    pft_frame_t g = garbage_frame();
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_source_acquire(NULL, &g, 0u));
    TEST_ASSERT_TRUE(frame_is_zero(&g));
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_source_acquire(&src, NULL, 0u));
    pft_frame_source_t bad = src;
    bad.acquire = NULL;
    g = garbage_frame();
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_source_acquire(&bad, &g, 0u));
    TEST_ASSERT_TRUE(frame_is_zero(&g));
    bad = src;
    bad.release = NULL;
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_source_acquire(&bad, &g, 0u));
    pft_frame_t f;
    memset(&f, 0, sizeof f);
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_source_release(NULL, &f));
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_source_release(&src, NULL));
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_source_release(&src, &f)); /* NULL data */
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_source_release(&bad, &f));
    /* the run refuses before pulling anything; stats are cleared with stop = INVAL */
    pft_runner_stats_t st;
    memset(&st, 0x77, sizeof st);
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_runner_run(NULL, consume_nothing, NULL, NULL, NULL, &st));
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, st.stop);
    TEST_ASSERT_EQUAL_UINT32(0u, st.attempts);
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_runner_run(&src, NULL, NULL, NULL, NULL, &st));
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_runner_run(&bad, consume_nothing, NULL, NULL, NULL, &st));
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_runner_run(&src, consume_nothing, NULL, NULL, NULL, NULL));
    SAME(ms);
}

#if defined(PFT_PORT_MPS2)
static void test_mps2_file_source_refusals(void)
{
    pft_file_config_t c = fcfg("pft_tpr_m%u.pgm", PFT_FILE_PER_FRAME, PFT_FILE_PNM);
    pft_frame_source_t src;
    memset(&src, 0x5A, sizeof src);
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_file_source_init(&fs, &c));
    SNAP(fs);
    SNAP2(src);
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_mps2_file_source_init(&fs, &c, NULL));
    c.path = "pft_tpr_m%s.pgm";
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_mps2_file_source_init(&fs, &c, &src));
    SAME(fs);
    SAME2(src);
}
#endif

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_file_source_init_refusals_leave_source_unchanged);
    RUN_TEST(test_file_acquire_release_refusals);
    RUN_TEST(test_pnm_read_refusals_leave_buffers_unchanged);
    RUN_TEST(test_writers_refusals_create_no_file);
    RUN_TEST(test_mem_refusals_leave_source_unchanged);
    RUN_TEST(test_template_refusals_leave_port_unchanged);
    RUN_TEST(test_runner_refusals_leave_source_unchanged);
#if defined(PFT_PORT_MPS2)
    RUN_TEST(test_mps2_file_source_refusals);
#endif
    return UNITY_END();
}
