/* Frame descriptor validation and status strings. */
#include <string.h>
#include "pft_test_support.h"

void setUp(void) {}
void tearDown(void) {}

static uint8_t pix[4 * 6 * 4];

static pft_frame_t make(pft_pixfmt_t fmt, uint16_t w, uint16_t h)
{
    pft_frame_t f;
    memset(&f, 0, sizeof f);
    f.data = pix;
    f.width = w;
    f.height = h;
    f.format = fmt;
    f.stride_bytes = (uint32_t)w * pft_pixfmt_bytes(fmt);
    return f;
}

static void test_good_frame_passes(void)
{
    pft_frame_t f = make(PFT_PIX_U16, 4, 6);
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_frame_check(&f, 4, 6, PFT_FMT_BIT(PFT_PIX_U16)));
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_frame_check(&f, 0, 0, PFT_FMT_BIT(PFT_PIX_U16)));
}

static void test_bad_frames_refused(void)
{
    pft_frame_t f = make(PFT_PIX_U16, 4, 6);
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_frame_check(NULL, 4, 6, PFT_FMT_BIT(PFT_PIX_U16)));
    TEST_ASSERT_EQUAL_INT(PFT_ERR_FORMAT, pft_frame_check(&f, 4, 6, PFT_FMT_BIT(PFT_PIX_U8)));
    TEST_ASSERT_EQUAL_INT(PFT_ERR_FORMAT, pft_frame_check(&f, 5, 6, PFT_FMT_BIT(PFT_PIX_U16)));
    f.stride_bytes = 7;
    TEST_ASSERT_EQUAL_INT(PFT_ERR_FORMAT, pft_frame_check(&f, 4, 6, PFT_FMT_BIT(PFT_PIX_U16)));
    f = make((pft_pixfmt_t)77, 4, 6);
    TEST_ASSERT_EQUAL_INT(PFT_ERR_FORMAT, pft_frame_check(&f, 4, 6, 0xFFFFFFFFu));
    f = make(PFT_PIX_U8, 4, 6);
    f.data = NULL;
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_frame_check(&f, 4, 6, PFT_FMT_BIT(PFT_PIX_U8)));
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_frame_check_finite(&f));
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_frame_check_finite(NULL));
    /* empty geometry, a geometry that differs in height only, a 16-bit container with more
     * than 16 significant bits */
    f = make(PFT_PIX_U16, 4, 6);
    f.width = 0;
    TEST_ASSERT_EQUAL_INT(PFT_ERR_FORMAT, pft_frame_check(&f, 0, 0, PFT_FMT_BIT(PFT_PIX_U16)));
    f = make(PFT_PIX_U16, 4, 6);
    f.height = 0;
    TEST_ASSERT_EQUAL_INT(PFT_ERR_FORMAT, pft_frame_check(&f, 0, 0, PFT_FMT_BIT(PFT_PIX_U16)));
    f = make(PFT_PIX_U16, 4, 6);
    TEST_ASSERT_EQUAL_INT(PFT_ERR_FORMAT, pft_frame_check(&f, 4, 7, PFT_FMT_BIT(PFT_PIX_U16)));
    f.bit_depth = 17;
    TEST_ASSERT_EQUAL_INT(PFT_ERR_FORMAT, pft_frame_check(&f, 4, 6, PFT_FMT_BIT(PFT_PIX_U16)));
    f.bit_depth = 14;
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_frame_check(&f, 4, 6, PFT_FMT_BIT(PFT_PIX_U16)));
}

static void test_nonfinite_f32_refused(void)
{
    float px[6] = {1.0f, 2.0f, 3.0f, 4.0f, 5.0f, 6.0f};
    pft_frame_t f = make(PFT_PIX_F32, 3, 2);
    f.data = px;
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_frame_check_finite(&f));
    uint32_t nan_bits = 0x7FC00000u, inf_bits = 0xFF800000u;
    memcpy(&px[4], &nan_bits, 4);
    TEST_ASSERT_EQUAL_INT(PFT_ERR_FORMAT, pft_frame_check_finite(&f));
    px[4] = 0.0f;
    memcpy(&px[0], &inf_bits, 4);
    TEST_ASSERT_EQUAL_INT(PFT_ERR_FORMAT, pft_frame_check_finite(&f));
}

static void test_status_strings(void)
{
    TEST_ASSERT_EQUAL_STRING("ok", pft_status_str(PFT_OK));
    TEST_ASSERT_EQUAL_STRING("workspace too short", pft_status_str(PFT_ERR_NOMEM));
    TEST_ASSERT_EQUAL_STRING("unknown status", pft_status_str((pft_status_t)-99));
    TEST_ASSERT_EQUAL_STRING("unknown status", pft_status_str((pft_status_t)-14)); /* one past */
    /* every status has its own name (a log line tells them apart) */
    for (int a = 0; a >= -13; --a) {
        const char *sa = pft_status_str((pft_status_t)a);
        TEST_ASSERT_NOT_NULL(sa);
        TEST_ASSERT_TRUE(strlen(sa) > 0u);
        TEST_ASSERT_TRUE_MESSAGE(strcmp(sa, "unknown status") != 0, "a status without a name");
        for (int b = a - 1; b >= -13; --b) {
            TEST_ASSERT_TRUE_MESSAGE(strcmp(sa, pft_status_str((pft_status_t)b)) != 0,
                                     "two statuses share a name");
        }
    }
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_good_frame_passes);
    RUN_TEST(test_bad_frames_refused);
    RUN_TEST(test_nonfinite_f32_refused);
    RUN_TEST(test_status_strings);
    return UNITY_END();
}
