/* Ring source rules: lend-and-return bookkeeping, limits, producer overrun, close, faults on
 * odd geometries, argument checks. */
#include <string.h>
#include "pft_test_support.h"
#include "pft/pft_port_mem.h"

#define W 5u
#define H 3u

static uint8_t ring[4u * 8u * H]; /* room for 4 slots of stride 8 */
static pft_mem_source_t m;

static pft_mem_config_t base_cfg(uint32_t slots)
{
    pft_mem_config_t c;
    memset(&c, 0, sizeof c);
    c.buffer = ring;
    c.buffer_bytes = sizeof ring;
    c.slots = slots;
    c.width = W;
    c.height = H;
    c.format = PFT_PIX_U8;
    c.first_seq = 100u;
    return c;
}

static void push_value(uint8_t v, uint64_t ts)
{
    uint8_t px[W * H];
    memset(px, v, sizeof px);
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_mem_push(&m, px, 0u, ts));
}

void setUp(void)
{
    memset(ring, 0, sizeof ring);
}
void tearDown(void) {}

static void test_fifo_order_and_content(void)
{
    pft_mem_config_t c = base_cfg(3u);
    c.stride_bytes = 8u;
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_mem_source_init(&m, &c));
    push_value(1u, 10u);
    push_value(2u, 20u);
    TEST_ASSERT_EQUAL_UINT32(2u, pft_mem_queued(&m));
    pft_frame_t f;
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_mem_acquire(&m, &f, 0u));
    TEST_ASSERT_EQUAL_UINT32(100u, f.seq);
    TEST_ASSERT_EQUAL_UINT64(10u, f.timestamp_us);
    TEST_ASSERT_EQUAL_UINT32(8u, f.stride_bytes);
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_frame_check(&f, W, H, PFT_FMT_BIT(PFT_PIX_U8)));
    for (uint32_t y = 0; y < H; ++y) {
        for (uint32_t x = 0; x < W; ++x) {
            TEST_ASSERT_EQUAL_UINT8(1u, pft_frame_row(&f, y)[x]);
        }
    }
    /* a slot freed out of order is reused, order still by seq */
    push_value(3u, 30u);
    pft_mem_release(&m, &f);
    push_value(4u, 40u);
    uint32_t want = 101u;
    for (uint32_t i = 0; i < 3u; ++i) {
        TEST_ASSERT_EQUAL_INT(PFT_OK, pft_mem_acquire(&m, &f, 0u));
        TEST_ASSERT_EQUAL_UINT32(want + i, f.seq);
        TEST_ASSERT_EQUAL_UINT8((uint8_t)(2u + i), pft_frame_row(&f, H - 1u)[W - 1u]);
        pft_mem_release(&m, &f);
    }
    TEST_ASSERT_EQUAL_INT(PFT_ERR_TIMEOUT, pft_mem_acquire(&m, &f, 100u));
    TEST_ASSERT_NULL(f.data);
    pft_mem_close(&m);
    TEST_ASSERT_EQUAL_INT(PFT_ERR_EOF, pft_mem_acquire(&m, &f, 0u));
    TEST_ASSERT_EQUAL_INT(PFT_ERR_EOF, pft_mem_acquire(&m, &f, 0u));
    TEST_ASSERT_EQUAL_UINT32(4u, m.stats.acquired);
    TEST_ASSERT_EQUAL_UINT32(4u, m.stats.released);
    TEST_ASSERT_EQUAL_UINT32(0u, m.stats.bad_releases);
}

static void test_lend_limit_gives_state(void)
{
    pft_mem_config_t c = base_cfg(3u);
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_mem_source_init(&m, &c));
    pft_frame_t f[4];
    push_value(1u, 0u);
    push_value(2u, 0u);
    push_value(3u, 0u);
    for (uint32_t i = 0; i < 3u; ++i) {
        TEST_ASSERT_EQUAL_INT(PFT_OK, pft_mem_acquire(&m, &f[i], 0u));
    }
    /* every slot lent: one more is beyond the slot count */
    TEST_ASSERT_EQUAL_INT(PFT_ERR_STATE, pft_mem_acquire(&m, &f[3], 0u));
    TEST_ASSERT_EQUAL_UINT32(1u, m.stats.state_errors);
    /* and the producer has nowhere to write: overrun, seq consumed */
    uint8_t px[W * H] = {0};
    TEST_ASSERT_EQUAL_INT(PFT_ERR_NOMEM, pft_mem_push(&m, px, 0u, 0u));
    TEST_ASSERT_EQUAL_UINT32(1u, m.stats.overruns);
    pft_mem_release(&m, &f[1]);
    push_value(9u, 0u);
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_mem_acquire(&m, &f[3], 0u));
    TEST_ASSERT_EQUAL_UINT32(104u, f[3].seq); /* 103 was lost in the overrun */
    TEST_ASSERT_EQUAL_UINT32(3u, m.stats.lent_max);

    /* max_lent below the slot count */
    c.max_lent = 1u;
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_mem_source_init(&m, &c));
    push_value(1u, 0u);
    push_value(2u, 0u);
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_mem_acquire(&m, &f[0], 0u));
    TEST_ASSERT_EQUAL_INT(PFT_ERR_STATE, pft_mem_acquire(&m, &f[1], 0u));
    pft_mem_release(&m, &f[0]);
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_mem_acquire(&m, &f[1], 0u));
    TEST_ASSERT_EQUAL_UINT32(101u, f[1].seq);
}

static void test_bad_releases_ignored_and_counted(void)
{
    pft_mem_config_t c = base_cfg(2u);
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_mem_source_init(&m, &c));
    push_value(1u, 0u);
    pft_frame_t f;
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_mem_acquire(&m, &f, 0u));
    pft_mem_release(&m, &f);
    pft_mem_release(&m, &f); /* double */
    pft_frame_t foreign = f;
    static uint8_t elsewhere[4];
    foreign.data = elsewhere;
    pft_mem_release(&m, &foreign);
    pft_mem_release(&m, NULL);
    pft_mem_release(NULL, &f); /* no crash */
    TEST_ASSERT_EQUAL_UINT32(3u, m.stats.bad_releases);
    TEST_ASSERT_EQUAL_UINT32(1u, m.stats.released);
    TEST_ASSERT_EQUAL_UINT32(0u, m.stats.lent);
    /* a queued (not lent) slot cannot be released by guessing its pointer */
    push_value(2u, 0u);
    pft_frame_t guess = f;
    guess.data = ring;
    pft_mem_release(&m, &guess);
    guess.data = ring + W * H;
    pft_mem_release(&m, &guess);
    TEST_ASSERT_EQUAL_UINT32(5u, m.stats.bad_releases);
    TEST_ASSERT_EQUAL_UINT32(1u, pft_mem_queued(&m));
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_mem_acquire(&m, &f, 0u));
    TEST_ASSERT_EQUAL_UINT8(2u, pft_frame_row(&f, 0u)[0]);
}

static void test_producer_zero_copy(void)
{
    pft_mem_config_t c = base_cfg(2u);
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_mem_source_init(&m, &c));
    void *px = NULL;
    TEST_ASSERT_EQUAL_INT(PFT_ERR_STATE, pft_mem_write_commit(&m, 0u));
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_mem_write_begin(&m, &px));
    TEST_ASSERT_NOT_NULL(px);
    void *px2 = NULL;
    TEST_ASSERT_EQUAL_INT(PFT_ERR_STATE, pft_mem_write_begin(&m, &px2));
    memset(px, 7, W * H);
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_mem_write_abort(&m));
    TEST_ASSERT_EQUAL_UINT32(0u, pft_mem_queued(&m));
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_mem_write_begin(&m, &px));
    memset(px, 8, W * H);
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_mem_write_commit(&m, 55u));
    pft_frame_t f;
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_mem_acquire(&m, &f, 0u));
    TEST_ASSERT_EQUAL_PTR(px, f.data); /* lent in place, no copy */
    TEST_ASSERT_EQUAL_UINT32(100u, f.seq); /* the abort consumed no seq */
    TEST_ASSERT_EQUAL_UINT8(8u, pft_frame_row(&f, 2u)[4]);
    pft_mem_close(&m);
    TEST_ASSERT_EQUAL_INT(PFT_ERR_STATE, pft_mem_write_begin(&m, &px));
    pft_mem_release(&m, &f);
    TEST_ASSERT_EQUAL_INT(PFT_ERR_EOF, pft_mem_acquire(&m, &f, 0u));
}

static void test_fault_shapes(void)
{
    static const pft_fault_at_t at[] = {{100u, PFT_FAULT_SHORT}, {101u, PFT_FAULT_CORRUPT},
                                        {102u, PFT_FAULT_CORRUPT}, {103u, PFT_FAULT_LATE}};
    pft_mem_config_t c = base_cfg(4u);
    c.faults.at = at;
    c.faults.at_count = 4u;
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_mem_source_init(&m, &c));
    for (uint8_t i = 0; i < 4u; ++i) {
        push_value(i, 1000u * i);
    }
    pft_frame_t f[4];
    for (uint32_t i = 0; i < 4u; ++i) {
        TEST_ASSERT_EQUAL_INT(PFT_OK, pft_mem_acquire(&m, &f[i], 0u));
    }
    TEST_ASSERT_EQUAL_UINT16(1u, f[0].height); /* H / 2 */
    TEST_ASSERT_EQUAL_UINT16(0u, f[1].width);  /* odd seq: zero width */
    TEST_ASSERT_EQUAL_INT(0, (int)f[2].format); /* even seq: unknown format */
    TEST_ASSERT_EQUAL_UINT64(3000u + 1000000u, f[3].timestamp_us);
    TEST_ASSERT_EQUAL_INT(PFT_ERR_FORMAT, pft_frame_check(&f[0], W, H, 0xFFFFFFFEu));
    TEST_ASSERT_EQUAL_INT(PFT_ERR_FORMAT, pft_frame_check(&f[1], 0u, 0u, 0xFFFFFFFEu));
    TEST_ASSERT_EQUAL_INT(PFT_ERR_FORMAT, pft_frame_check(&f[2], 0u, 0u, 0xFFFFFFFEu));
    for (uint32_t i = 0; i < 4u; ++i) {
        pft_mem_release(&m, &f[i]); /* corrupt headers still release by data pointer */
    }
    TEST_ASSERT_EQUAL_UINT32(4u, m.stats.released);
    TEST_ASSERT_EQUAL_UINT32(0u, m.stats.bad_releases);

    /* one-row frames get a short stride instead of fewer rows */
    static const pft_fault_at_t at1[] = {{100u, PFT_FAULT_SHORT}};
    c = base_cfg(1u);
    c.height = 1u;
    c.faults.at = at1;
    c.faults.at_count = 1u;
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_mem_source_init(&m, &c));
    uint8_t px[W] = {0};
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_mem_push(&m, px, 0u, 0u));
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_mem_acquire(&m, &f[0], 0u));
    TEST_ASSERT_EQUAL_UINT16(1u, f[0].height);
    TEST_ASSERT_TRUE(f[0].stride_bytes < W);
    pft_mem_release(&m, &f[0]);
    TEST_ASSERT_EQUAL_UINT32(1u, m.stats.released);
}

static void test_init_checks(void)
{
    pft_mem_config_t c = base_cfg(2u);
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_mem_source_init(NULL, &c));
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_mem_source_init(&m, NULL));
    c.buffer = NULL;
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_mem_source_init(&m, &c));
    c = base_cfg(0u);
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_mem_source_init(&m, &c));
    c = base_cfg(PFT_MEM_MAX_SLOTS + 1u);
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_mem_source_init(&m, &c));
    c = base_cfg(2u);
    c.format = (pft_pixfmt_t)9;
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_mem_source_init(&m, &c));
    c = base_cfg(2u);
    c.stride_bytes = W - 1u;
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_mem_source_init(&m, &c));
    c = base_cfg(2u);
    c.max_lent = 3u;
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_mem_source_init(&m, &c));
    c = base_cfg(2u);
    c.faults.prob_ppm[PFT_FAULT_DROP] = 600000u;
    c.faults.prob_ppm[PFT_FAULT_LATE] = 600000u;
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_mem_source_init(&m, &c));
    c = base_cfg(2u);
    c.faults.at_count = 1u;
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_mem_source_init(&m, &c));
    c = base_cfg(4u);
    c.buffer_bytes = 4u * W * H - 1u;
    TEST_ASSERT_EQUAL_INT(PFT_ERR_NOMEM, pft_mem_source_init(&m, &c));
    c.buffer_bytes = 4u * W * H;
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_mem_source_init(&m, &c));

    pft_frame_t f;
    void *px;
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_mem_acquire(NULL, &f, 0u));
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_mem_acquire(&m, NULL, 0u));
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_mem_push(NULL, ring, 0u, 0u));
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_mem_push(&m, NULL, 0u, 0u));
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_mem_push(&m, ring, W - 1u, 0u));
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_mem_write_begin(NULL, &px));
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_mem_write_begin(&m, NULL));
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_mem_write_commit(NULL, 0u));
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_mem_write_abort(NULL));
    TEST_ASSERT_EQUAL_UINT32(0u, pft_mem_queued(NULL));
    pft_mem_close(NULL);
    /* after all that the source still works */
    push_value(5u, 0u);
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_mem_acquire(&m, &f, 0u));
    TEST_ASSERT_EQUAL_UINT8(5u, pft_frame_row(&f, 0u)[0]);
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_fifo_order_and_content);
    RUN_TEST(test_lend_limit_gives_state);
    RUN_TEST(test_bad_releases_ignored_and_counted);
    RUN_TEST(test_producer_zero_copy);
    RUN_TEST(test_fault_shapes);
    RUN_TEST(test_init_checks);
    return UNITY_END();
}
