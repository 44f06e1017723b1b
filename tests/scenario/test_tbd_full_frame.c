/*
 * Scenario test of the TBD manager on a 64x64 frame with births from peaks (cfg.birth_peaks,
 * docs/algorithms.md 2.11), on every preset.
 *
 * One target at 8 dB (sigma 2.586, intensity 20) crosses the middle of a 64x64 frame of white
 * Gaussian noise: present in frames 4-19 from (28, 30) with velocity (0.45, 0.25), 22 frames;
 * U16 frames (z = raw/256 - 64) from the shared simulator. The manager runs the recommended
 * preset with Ns = 2000, Nt = 300, the birth importance correction on (birth_correction: the
 * existence probability stays calibrated, see docs/results/tbd.md "Full frames"; without it
 * peak births confirm about 16 false points per run here) and births from the 32 strongest
 * peaks (peak_gamma 1); SCN_RUNS seeds. A point is correct when a confirmed track is within 1 px
 * of the target; a false point is any other confirmed track (while the target is absent: after
 * 3 frames of grace). The same runs with births from B_k = {z > gamma} (the paper, birth_peaks
 * = 0, same correction) are printed beside them.
 * Measured when written (8 runs): peaks delay 5.13 / 5.38, correct 9.38 / 10.00, false 0.38 /
 * 0.25 per run (float / q16); B_k delay 6.00 / 4.75, correct 7.75 / 9.38, false 1.50 / 1.25.
 * (12 runs: peaks 4.58 / 5.00, 8.83 / 9.50, 0.75 / 0.25; B_k 7.50 / 6.33, 6.75 / 7.92, 1.25 /
 * 0.92; 12 runs took 87 s on the Cortex-M3 under a loaded QEMU, hence 8, and each run's
 * frames are rendered once for both births: 11.6 s there, as long as test_tbd_scenario.)
 * Asserted: with peaks delay < 6, correct > 7.5, false < 2 per run, and fewer false points than
 * B_k. At 100 runs and 6 dB the host tools measure peaks ahead of B_k on every measure
 * (docs/results/tbd.md "Full frames"); 8 runs cannot resolve the appearance difference (q16
 * has B_k ahead), so only the false points are compared. The 6 dB goals of issue #9 (delay
 * <= 3, >= 11 correct) are not reached: docs/results/tbd.md "Full frames" says why.
 */
#include <math.h>
#include <string.h>

#include "pft_test_support.h"
#include "pft_tbd_sim.h"
#include "pft/pft_tbd.h"

void setUp(void) {}
void tearDown(void) {}

#ifndef SCN_RUNS
#define SCN_RUNS 8
#endif

#define IMG 64
#define NS 2000u
#define NT 300u
#define MAXT 2u
#define KPEAKS 32u
#define NFRAMES 22
#define SIGMA 2.586 /* 8 dB */

static uint16_t g_raw[NFRAMES][IMG * IMG]; /* one run's frames, shared by both births */
static pft_frame_t g_fr[NFRAMES];
/* one workspace for both births: B_k's list holds one index per pixel, the peaks' K only */
#define WS_PEAKS PFT_TBD_WORKSPACE_BYTES_PEAKS(NS, NT, MAXT, PFT_TBD_RBPF, IMG, IMG, KPEAKS)
#define WS_BK PFT_TBD_WORKSPACE_BYTES(NS, NT, MAXT, PFT_TBD_RBPF, IMG, IMG)
static uint8_t g_ws[WS_PEAKS > WS_BK ? WS_PEAKS : WS_BK];
static const pft_sim_truth_t g_tr = {4, 19, 28.0, 30.0, 0.45, 0.25, 20.0};

static void note(const char *name, double v)
{
    UnityPrint(" ");
    UnityPrint(name);
    UnityPrint("=");
    UnityPrintFloat(v);
}

typedef struct {
    double delay, correct, false_pts;
} stats_t;

/* One run of the manager with births from `peaks` peaks (0: B_k) over the frames in g_fr. */
static void run_one(int run, uint16_t peaks, stats_t *st)
{
    static pft_tbd_t t;
    pft_tbd_config_t c;
    pft_tbd_config_recommended(&c);
    c.width = IMG;
    c.height = IMG;
    c.noise_sigma = pft_test_from_double(SIGMA);
    c.pixel_gain = pft_test_from_double(1.0 / 256.0);
    c.pixel_offset = pft_test_from_double(-64.0);
    c.n_search = NS;
    c.n_track = NT;
    c.max_targets = MAXT;
    c.birth_peaks = peaks;
    c.birth_correction = true;
    c.seed = 300u + (uint64_t)run;
    TEST_ASSERT_TRUE(pft_tbd_workspace_size(&c) <= sizeof g_ws);
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tbd_init(&t, &c, g_ws, sizeof g_ws));
    int appear = -1;
    for (int k = 1; k <= NFRAMES; ++k) {
        TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tbd_update(&t, &g_fr[k - 1]));
        pft_tbd_track_t trk[MAXT];
        size_t n = pft_tbd_tracks(&t, trk, MAXT);
        TEST_ASSERT_TRUE(n <= MAXT);
        bool hit = false;
        for (size_t a = 0; a < n; ++a) {
            const bool alive = pft_sim_alive(&g_tr, k) != 0;
            double d2 = 1e9;
            if (alive) {
                double dx = pft_test_to_double(trk[a].x) - pft_sim_x(&g_tr, k);
                double dy = pft_test_to_double(trk[a].y) - pft_sim_y(&g_tr, k);
                d2 = dx * dx + dy * dy;
            }
            if (alive && d2 <= 1.0 && !hit) {
                hit = true;
            } else if (alive || k < g_tr.first || k > g_tr.last + 3) {
                st->false_pts += 1.0; /* 3 frames of grace after the target's end */
            }
        }
        if (hit) {
            st->correct += 1.0;
            if (appear < 0) {
                appear = k;
            }
        }
    }
    st->delay += appear < 0 ? 16.0 : (double)(appear - g_tr.first);
}

/* Every run: its frames rendered once, then both births on them. */
static void run_all(stats_t *pk, stats_t *bk)
{
    memset(pk, 0, sizeof(*pk));
    memset(bk, 0, sizeof(*bk));
    for (int run = 0; run < SCN_RUNS; ++run) {
        pft_rng_t sim;
        pft_rng_seed(&sim, 9100u + (uint64_t)run);
        for (int k = 1; k <= NFRAMES; ++k) {
            pft_sim_render_u16(&sim, &g_tr, 1, k, SIGMA, IMG, IMG, g_raw[k - 1], &g_fr[k - 1]);
        }
        run_one(run, (uint16_t)KPEAKS, pk);
        run_one(run, 0u, bk);
    }
    pk->delay /= SCN_RUNS;
    pk->correct /= SCN_RUNS;
    pk->false_pts /= SCN_RUNS;
    bk->delay /= SCN_RUNS;
    bk->correct /= SCN_RUNS;
    bk->false_pts /= SCN_RUNS;
}

static void test_full_frame_64_peaks(void)
{
    stats_t pk, bk;
    run_all(&pk, &bk);
    UnityPrint("64x64 8 dB, births from 32 peaks:");
    note("appear_delay", pk.delay);
    note("correct_of_16", pk.correct);
    note("false_per_run", pk.false_pts);
    UNITY_PRINT_EOL();
    UnityPrint("64x64 8 dB, births from B_k:");
    note("appear_delay", bk.delay);
    note("correct_of_16", bk.correct);
    note("false_per_run", bk.false_pts);
    UNITY_PRINT_EOL();
    TEST_ASSERT_TRUE_MESSAGE(pk.delay < 6.0, "appearance delay with peak births");
    TEST_ASSERT_TRUE_MESSAGE(pk.correct > 7.5, "correct frames with peak births");
    TEST_ASSERT_TRUE_MESSAGE(pk.false_pts < 2.0, "false points with peak births");
    TEST_ASSERT_TRUE_MESSAGE(pk.false_pts < bk.false_pts, "peak births confirm fewer false points");
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_full_frame_64_peaks);
    return UNITY_END();
}
