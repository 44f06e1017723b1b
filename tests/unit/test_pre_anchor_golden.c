/*
 * Cross-target determinism of the stage with bg_anchor: replays the calls behind
 * tests/vectors/pre_anchor_q16_vectors.h (a host q16 build's results, see
 * pre_anchor_vectors_spec.h) and compares every value bit for bit (the stage is integer
 * arithmetic only): residual and sigma hashes, statistics, peaks, the grid's hash and valid
 * ranges, the workspace size.
 */
#include "pft_test_support.h"
#include "pre_anchor_vectors_spec.h"
#include "pre_anchor_q16_vectors.h"

void setUp(void) {}
void tearDown(void) {}

static pre_agv_results_t got;

static void test_sequence_is_sane(void)
{
    TEST_ASSERT_TRUE(got.ws > 0);
    for (uint32_t k = 0; k < PRE_GV_FRAMES; ++k) {
        TEST_ASSERT_EQUAL_INT32(PFT_OK, got.frame[k][0]);
        TEST_ASSERT_EQUAL_INT32((int32_t)(100u + k), got.frame[k][20]);
        TEST_ASSERT_EQUAL_INT32((int32_t)(k + 1u), got.frame[k][21]);
        TEST_ASSERT_TRUE(got.grid[k][1] <= got.grid[k][2] && got.grid[k][3] <= got.grid[k][4]);
    }
    TEST_ASSERT_TRUE((got.frame[0][1] & PFT_PRE_FLAG_WARMUP) != 0);
    TEST_ASSERT_TRUE((got.frame[6][1] & PFT_PRE_FLAG_HELD) != 0);
}

static void test_frames_bit_exact(void)
{
    TEST_ASSERT_EQUAL_INT32_MESSAGE(pre_agv_ws[0], got.ws, "workspace");
    TEST_ASSERT_EQUAL_INT32_ARRAY_MESSAGE(pre_agv_frame, &got.frame[0][0], PRE_GV_FRAMES * PRE_GV_NF,
                                          "frame record");
    TEST_ASSERT_EQUAL_INT32_ARRAY_MESSAGE(pre_agv_peaks, &got.peaks[0][0],
                                          PRE_GV_FRAMES * PRE_GV_PEAKS * 3u, "peaks");
    TEST_ASSERT_EQUAL_INT32_ARRAY_MESSAGE(pre_agv_grid, &got.grid[0][0], PRE_GV_FRAMES * 5u,
                                          "grid");
}

int main(void)
{
    pre_agv_compute(&got);
    UNITY_BEGIN();
    RUN_TEST(test_sequence_is_sane);
    RUN_TEST(test_frames_bit_exact);
    return UNITY_END();
}
