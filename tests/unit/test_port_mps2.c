/* MPS2 port (bare metal under QEMU only): semihosting console and clock, and the file source
 * adapter reading a PGM over semihosting. Elsewhere the tests are ignored. */
#include <string.h>
#include "pft_test_support.h"
#include "pft/pft_port_file.h"
#if defined(PFT_PORT_MPS2)
#include "pft/pft_port_mps2.h"
#endif

void setUp(void) {}
void tearDown(void) {}

#if defined(PFT_PORT_MPS2)
static void test_console_and_clock(void)
{
    pft_mps2_console_write("pft_mps2 console: ");
    pft_mps2_console_write_u32(4294967295u);
    pft_mps2_console_write(" ");
    pft_mps2_console_write_u32(0u);
    pft_mps2_console_write("\n");
    pft_mps2_console_write(NULL);
    uint64_t t0 = pft_mps2_now_us(NULL);
    volatile uint32_t spin = 0u;
    for (uint32_t i = 0; i < 200000u; ++i) {
        spin += i;
    }
    uint64_t t1 = pft_mps2_now_us(NULL);
    pft_mps2_console_write("pft_mps2 clock: spin took ");
    pft_mps2_console_write_u32((uint32_t)(t1 - t0));
    pft_mps2_console_write(" us\n");
    TEST_ASSERT_TRUE(t1 > t0); /* QEMU's SYS_ELAPSED counts host nanoseconds */
    TEST_ASSERT_TRUE(t1 - t0 < 60000000u); /* sane: well under a minute */
    pft_runner_hooks_t h;
    memset(&h, 0xFF, sizeof h);
    pft_mps2_runner_hooks(&h);
    TEST_ASSERT_TRUE(h.now_us == pft_mps2_now_us);
    TEST_ASSERT_NULL(h.on_frame_begin);
    TEST_ASSERT_NULL(h.on_fault);
}

static uint8_t px[6 * 4];
static uint8_t buf[6 * 4];

static void test_file_source_over_semihosting(void)
{
    for (uint32_t i = 0; i < sizeof px; ++i) {
        px[i] = (uint8_t)(i * 11u);
    }
    pft_frame_t f;
    memset(&f, 0, sizeof f);
    f.data = px;
    f.width = 6u;
    f.height = 4u;
    f.stride_bytes = 6u;
    f.format = PFT_PIX_U8;
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_pnm_write("pft_tpm_0.pgm", &f));
    (void)pft_file_remove("pft_tpm_1.pgm");
    (void)pft_file_remove("pft_tpm_2.pgm");
    pft_file_config_t c;
    memset(&c, 0, sizeof c);
    c.path = "pft_tpm_%u.pgm";
    c.buffer = buf;
    c.buffer_bytes = sizeof buf;
    pft_file_source_t fs;
    pft_frame_source_t src;
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_mps2_file_source_init(&fs, &c, NULL));
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_mps2_file_source_init(&fs, &c, &src));
    pft_frame_t g;
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_source_acquire(&src, &g, 0u));
    TEST_ASSERT_EQUAL_UINT8_ARRAY(px, g.data, sizeof px);
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_source_release(&src, &g));
    TEST_ASSERT_EQUAL_INT(PFT_ERR_EOF, pft_source_acquire(&src, &g, 0u));
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_file_remove("pft_tpm_0.pgm"));
}
#else
static void test_console_and_clock(void)
{
    TEST_IGNORE_MESSAGE("MPS2 port not in this build");
}
static void test_file_source_over_semihosting(void)
{
    TEST_IGNORE_MESSAGE("MPS2 port not in this build");
}
#endif

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_console_and_clock);
    RUN_TEST(test_file_source_over_semihosting);
    return UNITY_END();
}
