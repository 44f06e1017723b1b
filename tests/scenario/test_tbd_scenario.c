/*
 * Monte Carlo scenario test of RBPF-TBD (docs/algorithms.md 2.10, metrics of section 6).
 *
 * A deterministic simulator (own generator on pft_rng's integer stream, Box-Muller in double)
 * renders the paper's targets on a 20x20 image with Gaussian noise and hands the filters U16
 * frames (z = raw/256 - 64), the integer path every build shares.
 *   1. Single target, 8 dB, standalone RBPF (Exp. 1): present in frames 7-22 from (5, 6) with
 *      velocity (0.45, 0.25); 30 frames.
 *   2. Two targets, case 1, 6 dB, the manager: target 1 frames 7-22 from (1, 1) at
 *      (0.70, 0.35); target 2 frames 17-32 from (2, 3) at (0.55, 0.55); 35 frames.
 *   Positions are 0-based pixels (docs/design.md): the paper's (6, 7), (2, 2), (3, 4).
 * Small particle counts (N = Ns = 2000, Nt = 300), 24 seeds, pft_tbd_config_recommended()
 * (the paper's values with robust track ending, the joint likelihood instead of constraint
 * regions and the hand-over gate, see pft_tbd.h; the two-target values below were measured
 * with the earlier preset, which used 5x5 constraint regions. With the current one, the first
 * seed set gives delay 2.9/4.2, correct 10.3/9.4, RMSE 0.48 and 5.4 false points per run,
 * the same within this test's noise. At 200 runs with the same particle counts, the host
 * tools measure correct 10.30 against 9.16 over the three cases.)
 * A point is correct when it is declared (existence > theta1 / a confirmed track) and within
 * 1 px of the truth. Bounds: mean appearance delay, mean correct frames (of 16), RMSE over
 * correct points within 1.35x (single) / 1.38x (two targets) the 16-frame deterministic-line
 * floor of docs/algorithms.md 7.2 (0.309 at 8 dB, 0.386 at 6 dB), few false declarations. The measured values are printed.
 *
 * Over four seed sets of 24 runs (float build) the measured values were: single target delay
 * 1.4-1.8, correct 13.4-13.7, RMSE 0.36-0.38, false 0.6-1.2 per run; two targets delay
 * 2.8-4.6, correct 9.2-11.2 per target, RMSE 0.45-0.50, false points 5.3-8.7 per run.
 * The bounds were checked to fail with the likelihood sign flipped, births disabled,
 * resampling removed, the velocity left out of the position prediction, and the Kalman
 * update removed (velocity frozen at the birth prior: single RMSE 0.445, two-target RMSE
 * 0.55-0.59, mean correct 8.1, false points 13-15 per run) -- the last is why the RMSE bound
 * is at most 1.38x the floor.
 */
#include <math.h>
#include <string.h>

#include "pft_test_support.h"
#include "pft_tbd_sim.h"
#include "pft/pft_tbd.h"

void setUp(void) {}
void tearDown(void) {}

#ifndef SCN_RUNS
#define SCN_RUNS 24
#endif

#define IMG 20
#define NS 2000u
#define NT 300u
#define MAXT 3u
#define GAIN_INV 256.0
#define OFFSET 64.0

/* ------------------------------- simulator ------------------------------------------------ */
static uint16_t g_raw[IMG * IMG];

static void render(pft_rng_t *r, const pft_sim_truth_t *t, int nt, int k, double sigma, pft_frame_t *f)
{
    pft_sim_render_u16(r, t, nt, k, sigma, IMG, IMG, g_raw, f);
}

#ifndef SCN_SEED_BASE
#define SCN_SEED_BASE 0u
#endif

static void scenario_cfg(pft_tbd_config_t *c, double sigma, uint64_t seed)
{
    pft_tbd_config_recommended(c);
    c->noise_sigma = pft_test_from_double(sigma);
    c->pixel_gain = pft_test_from_double(1.0 / GAIN_INV);
    c->pixel_offset = pft_test_from_double(-OFFSET);
    c->n_search = NS;
    c->n_track = NT;
    c->max_targets = MAXT;
    c->seed = seed + SCN_SEED_BASE;
}

static void note(const char *name, double v)
{
    UnityPrint(" ");
    UnityPrint(name);
    UnityPrint("=");
    UnityPrintFloat(v);
}

/* ------------------------------- 1. single target ----------------------------------------- */
static uint8_t g_fws[PFT_TBD_FILTER_WORKSPACE_BYTES(NS, PFT_TBD_RBPF, IMG, IMG)];

static void test_single_target_8db(void)
{
    const double sigma = 2.586; /* 8 dB */
    const pft_sim_truth_t tr = {7, 22, 5.0, 6.0, 0.45, 0.25, 20.0};
    double sum_delay = 0.0, sum_correct = 0.0, se = 0.0, n_pts = 0.0, false_decl = 0.0;
    for (int run = 0; run < SCN_RUNS; ++run) {
        pft_tbd_config_t c;
        scenario_cfg(&c, sigma, 1000u + (uint64_t)run);
        pft_tbd_filter_t f;
        TEST_ASSERT_EQUAL_INT(PFT_OK,
                              pft_tbd_filter_init(&f, &c, g_fws, sizeof g_fws));
        pft_rng_t sim;
        pft_rng_seed(&sim, 5000u + SCN_SEED_BASE + (uint64_t)run);
        int appear = -1, correct = 0;
        for (int k = 1; k <= 30; ++k) {
            pft_frame_t fr;
            render(&sim, &tr, 1, k, sigma, &fr);
            TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tbd_filter_update(&f, &fr));
            pft_tbd_estimate_t e;
            pft_tbd_filter_estimate(&f, &e);
            int decl = pft_test_to_double(e.p_exist) > 0.6;
            if (!decl) {
                continue;
            }
            if (pft_sim_alive(&tr, k)) {
                double dx = pft_test_to_double(e.x) - pft_sim_x(&tr, k);
                double dy = pft_test_to_double(e.y) - pft_sim_y(&tr, k);
                double d2 = dx * dx + dy * dy;
                if (d2 <= 1.0) {
                    ++correct;
                    se += d2;
                    n_pts += 1.0;
                    if (appear < 0) {
                        appear = k;
                    }
                } else {
                    false_decl += 1.0;
                }
            } else if (k < tr.first || k > tr.last + 3) {
                false_decl += 1.0; /* declared while absent (3 frames of grace after death) */
            }
        }
        sum_delay += appear < 0 ? 16.0 : (double)(appear - tr.first);
        sum_correct += correct;
    }
    double delay = sum_delay / SCN_RUNS, corr = sum_correct / SCN_RUNS;
    double rmse = n_pts > 0 ? sqrt(se / n_pts) : 99.0, fd = false_decl / SCN_RUNS;
    UnityPrint("single 8 dB RBPF N=2000:");
    note("appear_delay", delay);
    note("correct_of_16", corr);
    note("rmse", rmse);
    note("floor", 0.309);
    note("false_per_run", fd);
    UNITY_PRINT_EOL();
    TEST_ASSERT_TRUE_MESSAGE(delay < 3.0, "appearance delay");
    TEST_ASSERT_TRUE_MESSAGE(corr > 12.0, "correct frames");
    TEST_ASSERT_TRUE_MESSAGE(rmse < 1.35 * 0.309, "RMSE within 1.35x floor");
    TEST_ASSERT_TRUE_MESSAGE(fd < 2.0, "false declarations");
}

/* ------------------------------- 2. two targets, manager ---------------------------------- */
static uint8_t g_mws[PFT_TBD_WORKSPACE_BYTES(NS, NT, MAXT, PFT_TBD_RBPF, IMG, IMG)];

#define C1_FRAMES 35
#define C1_SIGMA 3.256 /* 6 dB */
static const pft_sim_truth_t g_c1[2] = {{7, 22, 1.0, 1.0, 0.70, 0.35, 20.0},
                                        {17, 32, 2.0, 3.0, 0.55, 0.55, 20.0}};

/* Sums over the runs. */
typedef struct {
    double delay[2], dis[2], correct[2];
    double se, n_pts, false_pts, n_ids;
} case1_stats_t;

/* One run's bookkeeping per target: first associated frame, correct frames, the id that
 * followed it last, the frame its ending was reported. */
typedef struct {
    int appear[2], correct[2], ended[2];
    uint32_t last_id[2], max_id;
} case1_run_t;

/* Associates the tracks of frame k with the live targets (nearest within 1 px, one track per
 * target) and counts correct and false points. */
static void score_frame(int k, const pft_tbd_track_t *trk, size_t n, case1_run_t *r, case1_stats_t *st)
{
    int used[MAXT] = {0};
    for (int q = 0; q < 2; ++q) {
        if (!pft_sim_alive(&g_c1[q], k)) {
            continue;
        }
        int best = -1;
        double bd = 1.0;
        for (size_t a = 0; a < n; ++a) {
            double dx = pft_test_to_double(trk[a].x) - pft_sim_x(&g_c1[q], k);
            double dy = pft_test_to_double(trk[a].y) - pft_sim_y(&g_c1[q], k);
            if (!used[a] && dx * dx + dy * dy <= bd) {
                bd = dx * dx + dy * dy;
                best = (int)a;
            }
        }
        if (best >= 0) {
            used[best] = 1;
            ++r->correct[q];
            st->se += bd;
            st->n_pts += 1.0;
            if (r->appear[q] < 0) {
                r->appear[q] = k;
            }
            if (k == g_c1[q].last || r->last_id[q] == 0 || k > g_c1[q].last - 3) {
                r->last_id[q] = trk[best].id;
            }
        }
    }
    for (size_t a = 0; a < n; ++a) {
        st->false_pts += used[a] ? 0.0 : 1.0;
        r->max_id = trk[a].id > r->max_id ? trk[a].id : r->max_id;
    }
}

/* One run of the manager over case 1; adds its measures to st. */
static void run_case1(int run, case1_stats_t *st)
{
    pft_tbd_config_t c;
    scenario_cfg(&c, C1_SIGMA, 2000u + (uint64_t)run * 17u);
    static pft_tbd_t t;
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tbd_init(&t, &c, g_mws, sizeof g_mws));
    TEST_ASSERT_EQUAL_UINT((unsigned)sizeof g_mws, (unsigned)pft_tbd_workspace_size(&c));
    pft_rng_t sim;
    pft_rng_seed(&sim, 7000u + SCN_SEED_BASE + (uint64_t)run);
    case1_run_t r = {{-1, -1}, {0, 0}, {-1, -1}, {0, 0}, 0};
    for (int k = 1; k <= C1_FRAMES; ++k) {
        pft_frame_t fr;
        render(&sim, g_c1, 2, k, C1_SIGMA, &fr);
        TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tbd_update(&t, &fr));
        pft_tbd_track_t trk[MAXT];
        size_t n = pft_tbd_tracks(&t, trk, MAXT);
        TEST_ASSERT_TRUE(n <= MAXT);
        score_frame(k, trk, n, &r, st);
        pft_tbd_event_t ev[MAXT + 1];
        size_t ne = pft_tbd_events(&t, ev, MAXT + 1);
        for (size_t a = 0; a < ne; ++a) {
            for (int q = 0; q < 2; ++q) {
                if (ev[a].kind == PFT_TBD_EV_ENDED && ev[a].id == r.last_id[q] && k > g_c1[q].last &&
                    r.ended[q] < 0) {
                    r.ended[q] = k;
                }
            }
        }
    }
    for (int q = 0; q < 2; ++q) {
        st->delay[q] += r.appear[q] < 0 ? 16.0 : (double)(r.appear[q] - g_c1[q].first);
        st->correct[q] += r.correct[q];
        st->dis[q] += r.ended[q] < 0 ? (double)(C1_FRAMES - g_c1[q].last)
                                     : (double)(r.ended[q] - g_c1[q].last);
    }
    st->n_ids += r.max_id;
}

static void test_two_targets_case1_6db(void)
{
    case1_stats_t st;
    memset(&st, 0, sizeof st);
    for (int run = 0; run < SCN_RUNS; ++run) {
        run_case1(run, &st);
    }
    double rmse = st.n_pts > 0 ? sqrt(st.se / st.n_pts) : 99.0;
    for (int q = 0; q < 2; ++q) {
        UnityPrint(q == 0 ? "case1 6 dB target 1:" : "case1 6 dB target 2:");
        note("appear_delay", st.delay[q] / SCN_RUNS);
        note("disappear_delay", st.dis[q] / SCN_RUNS);
        note("correct_of_16", st.correct[q] / SCN_RUNS);
        UNITY_PRINT_EOL();
    }
    UnityPrint("case1 6 dB:");
    note("rmse", rmse);
    note("floor", 0.386);
    note("false_pts_per_run", st.false_pts / SCN_RUNS);
    note("ids_per_run", st.n_ids / SCN_RUNS);
    UNITY_PRINT_EOL();
    for (int q = 0; q < 2; ++q) {
        TEST_ASSERT_TRUE_MESSAGE(st.delay[q] / SCN_RUNS < 6.0, "appearance delay");
        TEST_ASSERT_TRUE_MESSAGE(st.correct[q] / SCN_RUNS > 7.5, "correct frames per target");
    }
    TEST_ASSERT_TRUE_MESSAGE((st.correct[0] + st.correct[1]) / (2.0 * SCN_RUNS) > 9.0,
                             "mean correct frames");
    TEST_ASSERT_TRUE_MESSAGE(rmse < 1.38 * 0.386, "RMSE within 1.38x floor");
    TEST_ASSERT_TRUE_MESSAGE(st.false_pts / SCN_RUNS < 11.0, "false track points");
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_single_target_8db);
    RUN_TEST(test_two_targets_case1_6db);
    return UNITY_END();
}
