/*
 * Cross-target determinism of the tbd family: replays the calls behind
 * tests/vectors/tbd_q16_vectors.h (standalone RBPF-TBD and PF-TBD filters, the manager with the
 * paper, recommended and a variant preset and with births from the multi-frame integration
 * (integ_alpha), measurement-model calls; tbd_vectors_spec.h) and
 * compares with the q16 results of a host build.
 *   q16 builds (host, Cortex-M3, Cortex-M7, AArch64): every value bit-identical.
 *   float builds: the trackers' random decisions diverge from q16 within a few frames, so the
 *   rows are not compared with q16; instead a second replay must give the same rows bit for
 *   bit (no state outside the instance and its workspace, no uninitialised memory).
 */
#include "pft_test_support.h"
#include "tbd_vectors_spec.h"
#include "tbd_q16_vectors.h"

void setUp(void) {}
void tearDown(void) {}

static pft_tv_results_t got, again;

static void check_rows(const char *name, const uint32_t *ref, const uint32_t *val, size_t rows,
                       size_t cols)
{
    pft_test_check_rows(name, "frame", ref, val, rows, cols);
}

#define REF PFT_GV_REF

static void test_filters(void)
{
    check_rows("filter rbpf", REF(&tv_filt_rbpf[0][0], &again.filt_rbpf[0][0]), &got.filt_rbpf[0][0],
               PFT_TV_FILTER_FRAMES, PFT_TV_FROW);
    check_rows("filter pf", REF(&tv_filt_pf[0][0], &again.filt_pf[0][0]), &got.filt_pf[0][0],
               PFT_TV_FILTER_FRAMES, PFT_TV_FROW);
}

static void test_manager(void)
{
    check_rows("manager paper", REF(&tv_mgr_paper[0][0], &again.mgr_paper[0][0]), &got.mgr_paper[0][0],
               PFT_TV_MGR_FRAMES, PFT_TV_MROW);
    check_rows("manager recommended", REF(&tv_mgr_rec[0][0], &again.mgr_rec[0][0]), &got.mgr_rec[0][0],
               PFT_TV_MGR_FRAMES, PFT_TV_MROW);
    check_rows("manager variant", REF(&tv_mgr_var[0][0], &again.mgr_var[0][0]), &got.mgr_var[0][0],
               PFT_TV_MGR_FRAMES, PFT_TV_MROW);
    check_rows("manager integration", REF(&tv_mgr_integ[0][0], &again.mgr_integ[0][0]),
               &got.mgr_integ[0][0], PFT_TV_MGR_FRAMES, PFT_TV_MROW);
}

/* The scene must exercise what the vectors are for: confirmations and endings in every
 * manager run (checked on the results of this build, q16 or float). */
static void test_scene_has_events(void)
{
    const uint32_t(*runs[4])[PFT_TV_MROW] = {got.mgr_paper, got.mgr_rec, got.mgr_var, got.mgr_integ};
    for (int m = 0; m < 4; ++m) {
        uint32_t most = 0, events = 0;
        for (int k = 0; k < PFT_TV_MGR_FRAMES; ++k) {
            most = runs[m][k][5] > most ? runs[m][k][5] : most;
            events += runs[m][k][6];
        }
        TEST_ASSERT_TRUE_MESSAGE(most >= 1u, "a track was confirmed");
        TEST_ASSERT_TRUE_MESSAGE(events >= 2u, "a confirmation and an ending");
    }
}

static void test_measurement_model(void)
{
#if PFT_GV_EXACT
    check_rows("measurement model", tv_meas[0], got.meas, 1, PFT_TV_MEAS);
#else
    check_rows("measurement model", again.meas, got.meas, 1, PFT_TV_MEAS);
#endif
}

int main(void)
{
    pft_tv_compute(&got);
#if !PFT_GV_EXACT
    pft_tv_compute(&again);
#endif
    UNITY_BEGIN();
    RUN_TEST(test_filters);
    RUN_TEST(test_manager);
    RUN_TEST(test_scene_has_events);
    RUN_TEST(test_measurement_model);
    return UNITY_END();
}
