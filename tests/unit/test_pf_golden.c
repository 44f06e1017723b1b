/*
 * Cross-target determinism of the pf family: replays the calls behind
 * tests/vectors/pf_q16_vectors.h (the engine's SIS / SIR / APF on the bearings, linear-Gaussian
 * and TBD pixel models; pf_vectors_spec.h) and compares with the q16 results of a host build.
 *   q16 builds (host, Cortex-M3, Cortex-M7, AArch64): every value bit-identical.
 *   float builds: a second replay must give the same rows bit for bit (float results are not
 *   comparable with q16 row by row once resampling decisions differ).
 */
#include "pft_test_support.h"
#include "pf_vectors_spec.h"
#include "pf_q16_vectors.h"

void setUp(void) {}
void tearDown(void) {}

static pft_pv_results_t got, again;

static void check_rows(const char *name, const uint32_t *ref, const uint32_t *val, size_t rows,
                       size_t cols)
{
    pft_test_check_rows(name, "step", ref, val, rows, cols);
}

#define REF PFT_GV_REF

static void test_bearings(void)
{
    static const uint32_t(*const ref[4])[PFT_PV_ROW] = {pv_brg_sis, pv_brg_sir, pv_brg_apf, pv_brg_apf_known};
    static const char *const name[4] = {"bearings SIS", "bearings SIR", "bearings APF", "bearings APF known set"};
    for (int i = 0; i < 4; ++i) {
        check_rows(name[i], REF(&ref[i][0][0], &again.brg[i][0][0]), &got.brg[i][0][0],
                   PFT_PV_BRG_STEPS, PFT_PV_ROW);
    }
}

static void test_linear_gaussian(void)
{
    static const uint32_t(*const ref[4])[PFT_PV_ROW] = {pv_lg_sis, pv_lg_sir, pv_lg_apf, pv_lg_sir_known};
    static const char *const name[4] = {"lg SIS", "lg SIR", "lg APF", "lg SIR known set"};
    for (int i = 0; i < 4; ++i) {
        check_rows(name[i], REF(&ref[i][0][0], &again.lg[i][0][0]), &got.lg[i][0][0],
                   PFT_PV_LG_STEPS, PFT_PV_ROW);
    }
}

static void test_tbd_model(void)
{
    check_rows("tbd SIR", REF(&pv_tbd_sir[0][0], &again.tbd[0][0][0]), &got.tbd[0][0][0],
               PFT_PV_TBD_STEPS, PFT_PV_ROW);
    check_rows("tbd APF", REF(&pv_tbd_apf[0][0], &again.tbd[1][0][0]), &got.tbd[1][0][0],
               PFT_PV_TBD_STEPS, PFT_PV_ROW);
}

/* Every run took all its steps (the step counter of the statistics, low bits of column 9). */
static void test_every_step_ran(void)
{
    for (int i = 0; i < 4; ++i) {
        TEST_ASSERT_EQUAL_UINT32(PFT_PV_BRG_STEPS, got.brg[i][PFT_PV_BRG_STEPS - 1][9] & 0xFFFFu);
        TEST_ASSERT_EQUAL_UINT32(PFT_PV_LG_STEPS, got.lg[i][PFT_PV_LG_STEPS - 1][9] & 0xFFFFu);
    }
    for (int i = 0; i < 2; ++i) {
        TEST_ASSERT_EQUAL_UINT32(PFT_PV_TBD_STEPS, got.tbd[i][PFT_PV_TBD_STEPS - 1][9] & 0xFFFFu);
    }
}

int main(void)
{
    pft_pv_compute(&got);
#if !PFT_GV_EXACT
    pft_pv_compute(&again);
#endif
    UNITY_BEGIN();
    RUN_TEST(test_bearings);
    RUN_TEST(test_linear_gaussian);
    RUN_TEST(test_tbd_model);
    RUN_TEST(test_every_step_ran);
    return UNITY_END();
}
