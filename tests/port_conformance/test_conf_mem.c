/* The ring-buffer port (port/mem) passes the conformance check: finite (pulled by its fill
 * hook, closed after N frames) and endless, with its default and a smaller lend limit, padded
 * strides, and with dropped frames injected (gaps, not violations). */
#include <string.h>
#include "pft_test_support.h"
#include "pft_port_conformance.h"
#include "pft/pft_port_mem.h"

#define W 8u
#define H 6u
#define SLOTS 4u
#define STRIDE_MAX (W * 2u + 6u)

static uint8_t ring[SLOTS * STRIDE_MAX * H];
static pft_mem_source_t mem;

/* Producer: frames with seq-dependent pixels, pulled by acquire (fill) and pushed by tick
 * while there is room (never an overrun, so the count stays exact). */
typedef struct {
    uint32_t total;   /* frames to make; 0: endless */
    uint32_t made;
    bool starved;
    uint8_t px[W * 2u * H];
} gen_t;
static gen_t gen;

static pft_status_t push_one(pft_mem_source_t *m)
{
    if (gen.total != 0u && gen.made >= gen.total) {
        return PFT_ERR_EOF;
    }
    if (gen.starved || m->stats.lent + pft_mem_queued(m) >= m->cfg.slots) {
        return PFT_OK; /* nothing now */
    }
    uint32_t seq = m->next_seq;
    for (uint32_t i = 0; i < sizeof gen.px; ++i) {
        gen.px[i] = (uint8_t)(seq * 13u + i);
    }
    gen.made++;
    return pft_mem_push(m, gen.px, 0u, 40000u * (uint64_t)seq);
}

static pft_status_t gen_fill(void *ctx, pft_mem_source_t *m)
{
    (void)ctx;
    return push_one(m);
}

static void gen_tick(void *ctx)
{
    pft_mem_source_t *m = (pft_mem_source_t *)ctx;
    if (push_one(m) == PFT_ERR_EOF) {
        pft_mem_close(m);
    }
}

static void gen_starve(void *ctx, bool on)
{
    (void)ctx;
    gen.starved = on;
}

static uint32_t mem_bad(void *ctx) { return ((pft_mem_source_t *)ctx)->stats.bad_releases; }

static pft_frame_source_t setup(pft_pixfmt_t fmt, uint32_t stride, uint32_t max_lent,
                                uint32_t total, const pft_mem_faults_t *faults)
{
    memset(&gen, 0, sizeof gen);
    gen.total = total;
    pft_mem_config_t c;
    memset(&c, 0, sizeof c);
    c.buffer = ring;
    c.buffer_bytes = sizeof ring;
    c.slots = SLOTS;
    c.width = W;
    c.height = H;
    c.format = fmt;
    c.stride_bytes = stride;
    c.max_lent = max_lent;
    c.first_seq = 100u;
    c.fill = gen_fill;
    if (faults != NULL) {
        c.faults = *faults;
    }
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_mem_source_init(&mem, &c));
    return pft_mem_as_source(&mem);
}

static pft_conf_spec_t spec(pft_pixfmt_t fmt, uint32_t frames, uint32_t max_lent)
{
    pft_conf_spec_t s;
    pft_conf_spec_default(&s);
    s.width = W;
    s.height = H;
    s.fmt_mask = PFT_FMT_BIT(fmt);
    s.frames = frames;
    s.endless_frames = 60u;
    s.max_lent = max_lent;
    s.can_timeout = true; /* nothing queued: PFT_ERR_TIMEOUT at once */
    s.hook_ctx = &mem;
    s.tick = gen_tick;
    s.starve = gen_starve;
    s.bad_releases = mem_bad;
    return s;
}

static void expect_pass(const pft_frame_source_t *src, const pft_conf_spec_t *s,
                        pft_conf_report_t *r)
{
    bool ok = pft_conf_run(src, s, r);
    TEST_ASSERT_EQUAL_UINT32_MESSAGE(0u, r->total, r->first);
    TEST_ASSERT_TRUE(ok);
    /* the port's own books agree with what the check saw */
    TEST_ASSERT_EQUAL_UINT32(0u, mem.stats.lent);
    TEST_ASSERT_EQUAL_UINT32(mem.stats.acquired, mem.stats.released);
    TEST_ASSERT_EQUAL_UINT32(r->frames, mem.stats.acquired);
    TEST_ASSERT_EQUAL_UINT32(r->bad_releases, mem.stats.bad_releases);
    TEST_ASSERT_EQUAL_UINT32(r->refused, mem.stats.state_errors);
}

void setUp(void) {}
void tearDown(void) {}

static void test_mem_finite_u16(void)
{
    pft_frame_source_t src = setup(PFT_PIX_U16, 0u, 0u, 30u, NULL);
    pft_conf_spec_t s = spec(PFT_PIX_U16, 30u, SLOTS);
    pft_conf_report_t r;
    expect_pass(&src, &s, &r);
    TEST_ASSERT_TRUE(r.ended);
    TEST_ASSERT_EQUAL_UINT32(30u, r.frames);
    TEST_ASSERT_EQUAL_UINT32(0u, r.gaps);
    TEST_ASSERT_EQUAL_UINT32(100u, r.first_seq);
    TEST_ASSERT_EQUAL_UINT32(129u, r.last_seq);
    TEST_ASSERT_TRUE(r.timeouts >= 1u); /* the starve probe */
    TEST_ASSERT_EQUAL_UINT32(SLOTS, mem.stats.lent_max);
}

static void test_mem_endless_limited_padded(void)
{
    pft_frame_source_t src = setup(PFT_PIX_U8, STRIDE_MAX, 2u, 0u, NULL);
    pft_conf_spec_t s = spec(PFT_PIX_U8, PFT_CONF_ENDLESS, 2u);
    pft_conf_report_t r;
    expect_pass(&src, &s, &r);
    TEST_ASSERT_FALSE(r.ended);
    TEST_ASSERT_TRUE(r.frames >= 60u);
    TEST_ASSERT_EQUAL_UINT32(2u, mem.stats.lent_max);
}

/* Dropped frames are seq gaps, not violations, and the check counts exactly the drops. */
static void test_mem_drops_are_gaps(void)
{
    static const pft_fault_at_t at[] = {{105u, PFT_FAULT_DROP}, {110u, PFT_FAULT_DROP},
                                        {111u, PFT_FAULT_DROP}, {120u, PFT_FAULT_DROP}};
    pft_mem_faults_t f;
    memset(&f, 0, sizeof f);
    f.at = at;
    f.at_count = 4u;
    pft_frame_source_t src = setup(PFT_PIX_U8, 0u, 0u, 30u, &f);
    pft_conf_spec_t s = spec(PFT_PIX_U8, 26u, SLOTS);
    pft_conf_report_t r;
    expect_pass(&src, &s, &r);
    TEST_ASSERT_EQUAL_UINT32(4u, mem.stats.injected[PFT_FAULT_DROP]);
    TEST_ASSERT_EQUAL_UINT32(4u, r.gaps);
    TEST_ASSERT_EQUAL_UINT32(26u, r.frames);
}

/* The same port described wrongly fails: the check is not vacuous on a real port. */
static void test_mem_wrong_description_fails(void)
{
    pft_frame_source_t src = setup(PFT_PIX_U8, 0u, 0u, 30u, NULL);
    pft_conf_spec_t s = spec(PFT_PIX_U8, 30u, SLOTS - 1u); /* the limit is SLOTS */
    pft_conf_report_t r;
    TEST_ASSERT_FALSE(pft_conf_run(&src, &s, &r));
    TEST_ASSERT_TRUE(r.violations[PFT_CONF_LEND] > 0u);
    src = setup(PFT_PIX_U8, 0u, 0u, 30u, NULL);
    s = spec(PFT_PIX_U8, 30u, SLOTS);
    s.can_timeout = false; /* it does time out when nothing is queued: */
    s.starve = NULL;
    gen.starved = true;    /* a producer that is late */
    TEST_ASSERT_FALSE(pft_conf_run(&src, &s, &r));
    TEST_ASSERT_TRUE(r.violations[PFT_CONF_TIMEOUT] > 0u);
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_mem_finite_u16);
    RUN_TEST(test_mem_endless_limited_padded);
    RUN_TEST(test_mem_drops_are_gaps);
    RUN_TEST(test_mem_wrong_description_fails);
    return UNITY_END();
}
