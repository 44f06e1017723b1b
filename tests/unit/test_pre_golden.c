/*
 * Cross-target determinism of the preprocessing stage: replays the calls behind
 * tests/vectors/pre_q16_vectors.h (the results of a host q16 build, see pre_vectors_spec.h)
 * and compares every value bit for bit: the stage is integer arithmetic only, so float and q16
 * builds, on x86-64, Cortex-M and AArch64, give the same residual frames, statistics and
 * peaks. The workspace sizes are compared too (the same on every target with 8-byte rounding;
 * pointer-size independent).
 */
#include "pft_test_support.h"
#include "pre_vectors_spec.h"
#include "pre_q16_vectors.h"

void setUp(void) {}
void tearDown(void) {}

static pre_gv_results_t got;

static void test_sequence_is_sane(void)
{
    /* the generator ran every frame: status OK, frame counters and the warm-up */
    for (uint32_t c = 0; c < PRE_GV_CASES; ++c) {
        TEST_ASSERT_TRUE(got.ws[c] > 0);
        for (uint32_t k = 0; k < PRE_GV_FRAMES; ++k) {
            TEST_ASSERT_EQUAL_INT32(PFT_OK, got.frame[c][k][0]);
            TEST_ASSERT_EQUAL_INT32((int32_t)(100u + k), got.frame[c][k][20]);
            TEST_ASSERT_EQUAL_INT32((int32_t)(k + 1u), got.frame[c][k][21]);
        }
    }
    TEST_ASSERT_TRUE((got.frame[0][0][1] & PFT_PRE_FLAG_WARMUP) != 0);
    TEST_ASSERT_TRUE((got.frame[0][6][1] & PFT_PRE_FLAG_CONSTANT) != 0);
    for (uint32_t j = 0; j < PRE_GV_CLUT; ++j) {
        for (uint32_t k = 0; k < PRE_GV_FRAMES; ++k) {
            TEST_ASSERT_EQUAL_INT32(PFT_OK, got.clut[j][k][0]);
            TEST_ASSERT_EQUAL_INT32((int32_t)(100u + k), got.clut[j][k][4]);
        }
    }
}

static void test_frames_bit_exact(void)
{
    TEST_ASSERT_EQUAL_INT32_ARRAY_MESSAGE(pre_gv_ws, got.ws, PRE_GV_CASES, "workspace");
    TEST_ASSERT_EQUAL_INT32_ARRAY_MESSAGE(pre_gv_clut, &got.clut[0][0][0],
                                          PRE_GV_CLUT * PRE_GV_FRAMES * PRE_GV_CF, "clutter map");
    for (uint32_t c = 0; c < PRE_GV_CASES; ++c) {
        for (uint32_t k = 0; k < PRE_GV_FRAMES; ++k) {
            TEST_ASSERT_EQUAL_INT32_ARRAY_MESSAGE(&pre_gv_frame[(c * PRE_GV_FRAMES + k) * PRE_GV_NF],
                                                  got.frame[c][k], PRE_GV_NF, "frame record");
            TEST_ASSERT_EQUAL_INT32_ARRAY_MESSAGE(
                &pre_gv_peaks[(c * PRE_GV_FRAMES + k) * PRE_GV_PEAKS * 3u], got.peaks[c][k],
                PRE_GV_PEAKS * 3u, "peaks");
        }
    }
}

int main(void)
{
    pre_gv_compute(&got);
    UNITY_BEGIN();
    RUN_TEST(test_sequence_is_sane);
    RUN_TEST(test_frames_bit_exact);
    return UNITY_END();
}
