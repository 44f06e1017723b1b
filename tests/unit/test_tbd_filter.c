/*
 * TBD filter and manager: workspace formulas against init, refused input leaves every byte of
 * state untouched, determinism, noise-only behaviour, detection and accuracy on a bright
 * target (RBPF and PF), the exact Kalman variant's variance against a double reference, and
 * the manager's stable, never reused track ids with their events, and the joint (residual)
 * likelihood finding a target spawned beside a confirmed one (against a 5x5 constraint region).
 *
 * Images are 10x10 and particle counts a few hundred, so the file runs in seconds under QEMU.
 */
#include <math.h>
#include <string.h>

#include "pft_test_support.h"
#include "pft_tbd_sim.h"
#include "pft/pft_tbd.h"
#if defined(__aarch64__) || (defined(__x86_64__) && !defined(PFT_NUMERIC_Q16))
#include "../../lib/src/tbd/tbd_int.h" /* pft_tbd_move_bern_hook_ */
#endif

void setUp(void) {}
void tearDown(void) {}

#define IMG 10
#define NF 300u

static pft_real_t R(double v) { return pft_test_from_double(v); }
static double D(pft_real_t v) { return pft_test_to_double(v); }

/* "name=value" notes for the record (Unity's own printing, every target). */
static void note(const char *name, double v)
{
    UnityPrint(" ");
    UnityPrint(name);
    UnityPrint("=");
    UnityPrintFloat(v);
}

/* ----------------------------------- simulator -------------------------------------------- */
static uint16_t g_raw[IMG * IMG];

/* U16 frame, z = raw/256 - 64; t may be NULL (noise only). */
static void render(pft_rng_t *r, const pft_sim_truth_t *t, int k, double sigma, pft_frame_t *f)
{
    pft_sim_render_u16(r, t, t != NULL ? 1 : 0, k, sigma, IMG, IMG, g_raw, f);
}

static void small_cfg(pft_tbd_config_t *c, double sigma, uint64_t seed)
{
    pft_test_tbd_u16_config(c, IMG, sigma);
    c->n_search = 400u;
    c->n_track = 200u;
    c->max_targets = 2u;
    c->seed = seed;
}

/* A standalone filter of n particles of the given kind (cfg.n_search and cfg.kind). */
static pft_status_t finit(pft_tbd_filter_t *f, pft_tbd_config_t *c, uint32_t n,
                          pft_tbd_kind_t kind, void *buf, size_t len)
{
    c->n_search = n;
    c->kind = kind;
    return pft_tbd_filter_init(f, c, buf, len);
}

#define SIGMA_15DB 1.1552 /* 6.4961 * 10^(-15/20) */
#define SIGMA_6DB 3.256
#define SIGMA_10DB 2.0543 /* 6.4961 * 10^(-10/20) */

/* --------------------------------- workspace sizes ---------------------------------------- */
#define FWS_BYTES PFT_TBD_FILTER_WORKSPACE_BYTES(NF, PFT_TBD_RBPF, IMG, IMG)
#define MWS_BYTES PFT_TBD_WORKSPACE_BYTES(400u, 200u, 2u, PFT_TBD_RBPF, IMG, IMG)
static uint8_t g_fbuf[FWS_BYTES + 64];
static uint8_t g_mbuf[MWS_BYTES + 64];
static uint8_t g_snap[MWS_BYTES + 64];

/* Offset into buf so that buf + off is 1 mod 8: the start needs all PFT_WS_ALIGN - 1 pad bytes. */
static size_t misalign(const uint8_t *buf)
{
    size_t a = (size_t)((uintptr_t)buf % PFT_WS_ALIGN);
    return (1u + PFT_WS_ALIGN - a) % PFT_WS_ALIGN;
}

static void test_filter_workspace_size_is_exact(void)
{
    pft_tbd_config_t c;
    small_cfg(&c, SIGMA_6DB, 1u);
    static pft_tbd_filter_t f;
    for (int kind = 0; kind < 2; ++kind) {
        c.n_search = NF;
        c.kind = (pft_tbd_kind_t)kind;
        size_t need = pft_tbd_filter_workspace_size(&c);
        TEST_ASSERT_EQUAL_UINT(kind == 0 ? (unsigned)FWS_BYTES
                                         : (unsigned)PFT_TBD_FILTER_WORKSPACE_BYTES(NF, PFT_TBD_PF, IMG, IMG),
                               (unsigned)need);
        size_t off = misalign(g_fbuf);
        pft_test_guard_fill(g_fbuf, sizeof g_fbuf);
        TEST_ASSERT_EQUAL_INT(PFT_ERR_NOMEM, finit(&f, &c, NF, (pft_tbd_kind_t)kind,
                                                                g_fbuf + off, need - 1u));
        TEST_ASSERT_TRUE_MESSAGE(pft_test_guard_intact(g_fbuf, sizeof g_fbuf, 0, 0),
                                 "a refused init wrote into the workspace");
        TEST_ASSERT_EQUAL_INT(PFT_OK, finit(&f, &c, NF, (pft_tbd_kind_t)kind,
                                                         g_fbuf + off, need));
        TEST_ASSERT_TRUE(pft_test_guard_intact(g_fbuf, sizeof g_fbuf, off, off + need));
        /* a few updates stay inside too */
        pft_rng_t sim;
        pft_rng_seed(&sim, 3u);
        for (int k = 1; k <= 3; ++k) {
            pft_frame_t fr;
            render(&sim, NULL, k, SIGMA_6DB, &fr);
            TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tbd_filter_update(&f, &fr));
        }
        TEST_ASSERT_TRUE(pft_test_guard_intact(g_fbuf, sizeof g_fbuf, off, off + need));
    }
    /* refused configuration: PFT_ERR_CONFIG naming the field, workspace size 0 */
    TEST_ASSERT_EQUAL_INT(PFT_ERR_CONFIG, finit(&f, &c, 0u, PFT_TBD_RBPF, g_fbuf, sizeof g_fbuf));
    const char *field = NULL;
    TEST_ASSERT_EQUAL_INT(PFT_ERR_CONFIG, pft_tbd_config_check(&c, &field));
    TEST_ASSERT_EQUAL_STRING("n_search", field);
    TEST_ASSERT_EQUAL_UINT(0u, (unsigned)pft_tbd_filter_workspace_size(&c));
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_tbd_filter_init(&f, NULL, g_fbuf, sizeof g_fbuf));
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_tbd_filter_init(NULL, &c, g_fbuf, sizeof g_fbuf));
}

static void test_manager_workspace_size_is_exact(void)
{
    pft_tbd_config_t c;
    small_cfg(&c, SIGMA_6DB, 1u);
    static pft_tbd_t t;
    size_t need = pft_tbd_workspace_size(&c);
    TEST_ASSERT_EQUAL_UINT((unsigned)MWS_BYTES, (unsigned)need);
    size_t off = misalign(g_mbuf);
    pft_test_guard_fill(g_mbuf, sizeof g_mbuf);
    TEST_ASSERT_EQUAL_INT(PFT_ERR_NOMEM, pft_tbd_init(&t, &c, g_mbuf + off, need - 1u));
    TEST_ASSERT_TRUE_MESSAGE(pft_test_guard_intact(g_mbuf, sizeof g_mbuf, 0, 0),
                             "a refused init wrote into the workspace");
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tbd_init(&t, &c, g_mbuf + off, need));
    pft_rng_t sim;
    pft_rng_seed(&sim, 4u);
    const pft_sim_truth_t tr = {1, 20, 2.0, 2.0, 0.3, 0.2, 20.0};
    for (int k = 1; k <= 6; ++k) {
        pft_frame_t fr;
        render(&sim, &tr, k, SIGMA_15DB, &fr);
        TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tbd_update(&t, &fr));
    }
    TEST_ASSERT_TRUE(pft_test_guard_intact(g_mbuf, sizeof g_mbuf, off, off + need));
    c.n_search = 0u;
    TEST_ASSERT_EQUAL_INT(PFT_ERR_CONFIG, pft_tbd_init(&t, &c, g_mbuf, sizeof g_mbuf));
    TEST_ASSERT_EQUAL_UINT(0u, (unsigned)pft_tbd_workspace_size(&c));
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_tbd_init(NULL, &c, g_mbuf, sizeof g_mbuf));
}

/* ------------------------------- refused input -------------------------------------------- */
static float g_f32[IMG * IMG];

/* Every malformed frame; each call must fail with the given status. */
static void feed_bad_frames(pft_status_t (*upd)(void *, const pft_frame_t *), void *inst)
{
    pft_frame_t good;
    pft_rng_t sim;
    pft_rng_seed(&sim, 77u);
    render(&sim, NULL, 1, SIGMA_6DB, &good);
    pft_frame_t f;
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, upd(inst, NULL));
    f = good; f.data = NULL;
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, upd(inst, &f));
    f = good; f.width = IMG - 1;
    TEST_ASSERT_EQUAL_INT(PFT_ERR_FORMAT, upd(inst, &f));
    f = good; f.height = IMG + 1;
    TEST_ASSERT_EQUAL_INT(PFT_ERR_FORMAT, upd(inst, &f));
    f = good; f.format = PFT_PIX_RGB888; f.stride_bytes = 3u * IMG;
    TEST_ASSERT_EQUAL_INT(PFT_ERR_FORMAT, upd(inst, &f));
    f = good; f.stride_bytes = IMG; /* too small for U16 */
    TEST_ASSERT_EQUAL_INT(PFT_ERR_FORMAT, upd(inst, &f));
    f = good; f.bit_depth = 17;
    TEST_ASSERT_EQUAL_INT(PFT_ERR_FORMAT, upd(inst, &f));
    for (int k = 0; k < IMG * IMG; ++k) {
        g_f32[k] = 1.0f;
    }
    uint32_t bits = 0x7FC00000u; /* NaN in the last pixel: found only by a full scan */
    memcpy(&g_f32[IMG * IMG - 1], &bits, 4);
    f = good; f.data = g_f32; f.format = PFT_PIX_F32; f.stride_bytes = 4u * IMG;
    TEST_ASSERT_EQUAL_INT(PFT_ERR_FORMAT, upd(inst, &f));
    bits = 0xFF800000u; /* -Inf */
    memcpy(&g_f32[IMG * IMG - 1], &bits, 4);
    TEST_ASSERT_EQUAL_INT(PFT_ERR_FORMAT, upd(inst, &f));
}

static pft_status_t upd_filter(void *inst, const pft_frame_t *f)
{
    return pft_tbd_filter_update((pft_tbd_filter_t *)inst, f);
}
static pft_status_t upd_manager(void *inst, const pft_frame_t *f)
{
    return pft_tbd_update((pft_tbd_t *)inst, f);
}

static void test_filter_refused_input_leaves_state_untouched(void)
{
    pft_tbd_config_t c;
    small_cfg(&c, SIGMA_15DB, 9u);
    static pft_tbd_filter_t f, f_snap;
    c.n_search = NF;
    c.kind = PFT_TBD_RBPF;
    size_t need = pft_tbd_filter_workspace_size(&c);
    TEST_ASSERT_EQUAL_INT(PFT_OK, finit(&f, &c, NF, PFT_TBD_RBPF, g_fbuf, need));
    pft_rng_t sim;
    pft_rng_seed(&sim, 5u);
    const pft_sim_truth_t tr = {1, 20, 2.0, 2.0, 0.3, 0.2, 20.0};
    for (int k = 1; k <= 5; ++k) {
        pft_frame_t fr;
        render(&sim, &tr, k, SIGMA_15DB, &fr);
        TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tbd_filter_update(&f, &fr));
    }
    f_snap = f;
    memcpy(g_snap, g_fbuf, need);
    feed_bad_frames(upd_filter, &f);
    pft_tbd_region_t reg = {1, 2, 1, 2};
    pft_frame_t fr;
    render(&sim, &tr, 6, SIGMA_15DB, &fr);
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_tbd_filter_update_ex(&f, &fr, NULL, 1u));
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_tbd_filter_update_ex(NULL, &fr, &reg, 1u));
    TEST_ASSERT_EQUAL_MEMORY(&f_snap, &f, sizeof f);
    TEST_ASSERT_EQUAL_MEMORY(g_snap, g_fbuf, need);
    /* and the filter still works */
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tbd_filter_update(&f, &fr));
    TEST_ASSERT_TRUE(memcmp(g_snap, g_fbuf, need) != 0);
}

static void test_manager_refused_input_leaves_state_untouched(void)
{
    pft_tbd_config_t c;
    small_cfg(&c, SIGMA_15DB, 10u);
    static pft_tbd_t t, t_snap;
    size_t need = pft_tbd_workspace_size(&c);
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tbd_init(&t, &c, g_mbuf, need));
    pft_rng_t sim;
    pft_rng_seed(&sim, 6u);
    const pft_sim_truth_t tr = {1, 20, 2.0, 2.0, 0.3, 0.2, 20.0};
    for (int k = 1; k <= 8; ++k) {
        pft_frame_t fr;
        render(&sim, &tr, k, SIGMA_15DB, &fr);
        TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tbd_update(&t, &fr));
    }
    pft_tbd_track_t trk[2];
    TEST_ASSERT_EQUAL_UINT(1u, (unsigned)pft_tbd_tracks(&t, trk, 2)); /* a live track layer too */
    t_snap = t;
    memcpy(g_snap, g_mbuf, need);
    feed_bad_frames(upd_manager, &t);
    TEST_ASSERT_EQUAL_MEMORY(&t_snap, &t, sizeof t);
    TEST_ASSERT_EQUAL_MEMORY(g_snap, g_mbuf, need);
}

/* ------------------------------- determinism ---------------------------------------------- */
static uint8_t g_fbuf2[FWS_BYTES];

static void test_filter_is_deterministic(void)
{
    pft_tbd_config_t c;
    small_cfg(&c, SIGMA_6DB, 21u);
    static pft_tbd_filter_t a, b;
    TEST_ASSERT_EQUAL_INT(PFT_OK, finit(&a, &c, NF, PFT_TBD_RBPF, g_fbuf, FWS_BYTES));
    TEST_ASSERT_EQUAL_INT(PFT_OK, finit(&b, &c, NF, PFT_TBD_RBPF, g_fbuf2, FWS_BYTES));
    pft_rng_t sim;
    pft_rng_seed(&sim, 8u);
    const pft_sim_truth_t tr = {3, 20, 2.0, 2.0, 0.3, 0.2, 20.0};
    for (int k = 1; k <= 8; ++k) {
        pft_frame_t fr;
        render(&sim, &tr, k, SIGMA_6DB, &fr);
        TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tbd_filter_update(&a, &fr));
        TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tbd_filter_update(&b, &fr));
        TEST_ASSERT_EQUAL_MEMORY(&a.est, &b.est, sizeof a.est);
        TEST_ASSERT_EQUAL_MEMORY(a.cur.x, b.cur.x, NF * sizeof(pft_real_t));
        TEST_ASSERT_EQUAL_MEMORY(a.cur.e, b.cur.e, NF);
    }
}

/* reset: back to the state right after init (same seeds, ids from 1 again): a second pass
 * over the same frames gives the same estimates, tracks and events. */
#define RESET_FRAMES 10
static void run_pass(pft_tbd_filter_t *f, pft_tbd_t *t, pft_tbd_estimate_t *est, uint32_t *ids)
{
    pft_rng_t sim;
    pft_rng_seed(&sim, 15u);
    const pft_sim_truth_t tr = {2, 20, 2.0, 2.0, 0.3, 0.2, 20.0};
    for (int k = 1; k <= RESET_FRAMES; ++k) {
        pft_frame_t fr;
        render(&sim, &tr, k, SIGMA_15DB, &fr);
        if (f != NULL) {
            TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tbd_filter_update(f, &fr));
            TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tbd_filter_estimate(f, &est[k - 1]));
        } else {
            TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tbd_update(t, &fr));
            TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tbd_search_estimate(t, &est[k - 1]));
            pft_tbd_track_t trk[2];
            size_t n = pft_tbd_tracks(t, trk, 2);
            ids[k - 1] = n > 0u ? trk[0].id : 0u;
        }
    }
}

static void test_reset_reproduces_the_first_run(void)
{
    static pft_tbd_filter_t f;
    static pft_tbd_t t;
    static pft_tbd_estimate_t a[RESET_FRAMES], b[RESET_FRAMES];
    uint32_t ia[RESET_FRAMES], ib[RESET_FRAMES];
    pft_tbd_config_t c;
    small_cfg(&c, SIGMA_15DB, 17u);
    TEST_ASSERT_EQUAL_INT(PFT_OK, finit(&f, &c, NF, PFT_TBD_RBPF, g_fbuf, FWS_BYTES));
    run_pass(&f, NULL, a, NULL);
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tbd_filter_reset(&f));
    run_pass(&f, NULL, b, NULL);
    TEST_ASSERT_EQUAL_MEMORY(a, b, sizeof a);
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_tbd_filter_reset(NULL));
    small_cfg(&c, SIGMA_15DB, 18u);
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tbd_init(&t, &c, g_mbuf, MWS_BYTES));
    run_pass(NULL, &t, a, ia);
    TEST_ASSERT_TRUE(ia[RESET_FRAMES - 1] >= 1u); /* a track is held at the last frame */
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tbd_reset(&t));
    TEST_ASSERT_EQUAL_UINT32(0u, pft_tbd_frame(&t));
    TEST_ASSERT_EQUAL_UINT(0u, (unsigned)pft_tbd_tracks(&t, NULL, 0));
    run_pass(NULL, &t, b, ib);
    TEST_ASSERT_EQUAL_MEMORY(a, b, sizeof a);
    TEST_ASSERT_EQUAL_MEMORY(ia, ib, sizeof ia);
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_tbd_reset(NULL));
    TEST_ASSERT_EQUAL_UINT32(0u, pft_tbd_frame(NULL));
    /* a layer of the manager is not a standalone filter */
    TEST_ASSERT_EQUAL_INT(PFT_ERR_STATE, pft_tbd_filter_reset(&t.tracks[0]));
}

/* ------------------------------- behaviour ------------------------------------------------ */
static void test_noise_only_keeps_existence_low(void)
{
    static pft_tbd_filter_t f;
    int high = 0;
    double sum = 0.0;
    int n = 0;
    for (uint64_t seed = 1; seed <= 3; ++seed) {
        pft_tbd_config_t c;
        small_cfg(&c, SIGMA_6DB, seed);
        TEST_ASSERT_EQUAL_INT(PFT_OK, finit(&f, &c, NF, PFT_TBD_RBPF, g_fbuf, FWS_BYTES));
        pft_rng_t sim;
        pft_rng_seed(&sim, 100u + seed);
        for (int k = 1; k <= 20; ++k) {
            pft_frame_t fr;
            render(&sim, NULL, k, SIGMA_6DB, &fr);
            TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tbd_filter_update(&f, &fr));
            pft_tbd_estimate_t e;
            pft_tbd_filter_estimate(&f, &e);
            double p = D(e.p_exist);
            TEST_ASSERT_TRUE(p >= 0.0 && p <= 1.0 + 1e-4);
            high += p > 0.6;
            sum += p;
            ++n;
        }
    }
    UnityPrint("noise only:");
    note("mean_P", sum / n);
    note("frames_above_0.6", high);
    note("of", n);
    UNITY_PRINT_EOL();
    TEST_ASSERT_TRUE_MESSAGE(high <= 6, "false declarations on noise (at most 10 % of frames)");
    TEST_ASSERT_TRUE_MESSAGE(sum / n < 0.3, "mean existence on noise");
}

/* 15 dB target born at frame 3, three seeds. RBPF (N = 300): detected within a frame, and
 * from frame 9 on (six frames to learn the velocity from the birth prior) every estimate is
 * within 0.5 px. The bootstrap PF at the same N is much weaker (its position noise is only
 * sqrt(q1/3) = 0.04 px, so wrong birth velocities carry particles off; the paper needs 10x the
 * particles): it must detect, and be correct (P > 0.6, error < 1 px) in 60 % of the frames. */
static void bright_target(pft_tbd_kind_t kind)
{
    static pft_tbd_filter_t f;
    int correct = 0, frames = 0, late_bad = 0, worst_detect = 0;
    double se = 0.0, worst_late = 0.0, vmax = 0.0;
    int npts = 0;
    for (uint64_t seed = 0; seed < 3; ++seed) {
        pft_tbd_config_t c;
        small_cfg(&c, SIGMA_15DB, 31u + seed);
        TEST_ASSERT_EQUAL_INT(PFT_OK, finit(&f, &c, NF, kind, g_fbuf, FWS_BYTES));
        pft_rng_t sim;
        pft_rng_seed(&sim, 12u + seed);
        const pft_sim_truth_t tr = {3, 40, 2.0, 2.5, 0.3, 0.2, 20.0};
        int detected = -1;
        for (int k = 1; k <= 16; ++k) {
            pft_frame_t fr;
            render(&sim, &tr, k, SIGMA_15DB, &fr);
            TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tbd_filter_update(&f, &fr));
            pft_tbd_estimate_t e;
            pft_tbd_filter_estimate(&f, &e);
            if (k < tr.first) {
                TEST_ASSERT_TRUE(D(e.p_exist) < 0.6);
                continue;
            }
            int decl = D(e.p_exist) > 0.6;
            if (detected < 0 && decl) {
                detected = k;
            }
            double dx = D(e.x) - pft_sim_x(&tr, k), dy = D(e.y) - pft_sim_y(&tr, k);
            double err = sqrt(dx * dx + dy * dy);
            ++frames;
            if (decl && err < 1.0) {
                ++correct;
                se += err * err;
                ++npts;
            }
            if (k >= tr.first + 6) {
                late_bad += !decl || err >= 0.5;
                worst_late = err > worst_late ? err : worst_late;
                TEST_ASSERT_TRUE(D(e.pos_cov[0]) >= 0.0 && D(e.pos_cov[2]) >= 0.0);
            }
            if (k == 16) {
                double v = fmax(fabs(D(e.vx) - tr.vx), fabs(D(e.vy) - tr.vy));
                vmax = v > vmax ? v : vmax;
            }
        }
        int delay = detected < 0 ? 99 : detected - tr.first;
        worst_detect = delay > worst_detect ? delay : worst_detect;
    }
    UnityPrint(kind == PFT_TBD_RBPF ? "RBPF 15 dB N=300:" : "PF 15 dB N=300:");
    note("worst_detection_delay", worst_detect);
    note("correct_frames", correct);
    note("of", frames);
    note("rmse", npts ? sqrt(se / npts) : 99.0);
    note("worst_err_from_birth+6", worst_late);
    note("worst_final_velocity_err", vmax);
    UNITY_PRINT_EOL();
    TEST_ASSERT_TRUE_MESSAGE(worst_detect <= 1, "detection delay");
    if (kind == PFT_TBD_RBPF) {
        TEST_ASSERT_EQUAL_INT_MESSAGE(0, late_bad, "RBPF: declared and within 0.5 px once converged");
        TEST_ASSERT_TRUE_MESSAGE(sqrt(se / npts) < 0.35, "RBPF rmse");
        TEST_ASSERT_TRUE_MESSAGE(vmax < 0.15, "RBPF velocity estimate");
    } else {
        TEST_ASSERT_TRUE_MESSAGE(correct * 10 >= frames * 6, "PF correct frames");
    }
}

static void test_bright_target_rbpf(void) { bright_target(PFT_TBD_RBPF); }
static void test_bright_target_pf(void) { bright_target(PFT_TBD_PF); }

/* The velocity variance of the exact variant follows the Riccati recursion of docs/algorithms.md
 * 2.3 (data independent), so the filter keeps it as a function of a particle's age: after ten
 * frames it is the fixed point, ~1.44e-3 (the calibrated value of the Monte Carlo check there),
 * read back from the tabulated position spread sd = sqrt(P + q1/3) (T = 1) of the ages the
 * live particles have. */
static void test_kf_exact_variance_matches_reference(void)
{
    double q1 = 0.005, p = 1.0 / 3.0;
    double ref[PFT_TBD_KF_AGES];
    for (int k = 0; k < 40; ++k) {
        if (k < (int)PFT_TBD_KF_AGES) {
            ref[k] = p;
        }
        double n = p + q1 / 3.0;
        double kk = p / n;
        double pp = p - kk * kk * n;
        p = 0.25 * pp + q1 / 4.0;
    }
    TEST_ASSERT_DOUBLE_WITHIN(0.02e-3, 1.44e-3, p);
    static pft_tbd_filter_t f;
    pft_tbd_config_t c;
    small_cfg(&c, SIGMA_15DB, 41u);
    TEST_ASSERT_EQUAL_INT(PFT_OK, finit(&f, &c, NF, PFT_TBD_RBPF, g_fbuf, FWS_BYTES));
    /* the table against the double recursion, every age (P from sd^2 - q1/3) */
    for (uint32_t a = 0; a < PFT_TBD_KF_AGES; ++a) {
        for (int ax = 0; ax < 2; ++ax) {
            double sd = D(f.tab->kf_sd[ax][a]);
            double pa = sd * sd - q1 / 3.0;
            double tol = 0.01 * ref[a] + 4.0 * sd * pft_test_lsb(sd);
            TEST_ASSERT_DOUBLE_WITHIN(tol, ref[a], pa);
        }
    }
    pft_rng_t sim;
    pft_rng_seed(&sim, 13u);
    const pft_sim_truth_t tr = {1, 40, 2.0, 2.0, 0.3, 0.2, 20.0};
    for (int k = 1; k <= 16; ++k) {
        pft_frame_t fr;
        render(&sim, &tr, k, SIGMA_15DB, &fr);
        TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tbd_filter_update(&f, &fr));
    }
    uint32_t alive_n = 0, at_fix = 0;
    double tol = 0.02 * p + 3.0 * pft_test_lsb(p);
    for (uint32_t s = 0; s < NF; ++s) {
        if (f.cur.e[s]) {
            uint32_t age = f.cur.e[s] - 1u;
            double sx = D(f.tab->kf_sd[0][age]), sy = D(f.tab->kf_sd[1][age]);
            ++alive_n;
            at_fix += fabs(sx * sx - q1 / 3.0 - p) < tol && fabs(sy * sy - q1 / 3.0 - p) < tol;
        }
    }
    UnityPrint("exact KF:");
    note("fixed_point", p);
    note("live_at_it", at_fix);
    note("live", alive_n);
    UNITY_PRINT_EOL();
    TEST_ASSERT_TRUE(alive_n > NF / 2u);
    TEST_ASSERT_TRUE_MESSAGE(at_fix * 2u > alive_n, "Riccati fixed point");
}

/* A target that appears, vanishes and reappears gets two different ids; events report both.
 * The tracks follow their targets (15 dB): every point of age >= 2 within 1 px and the RMSE of
 * those points below 0.45 px. Over 2000 seeds of this scene the per-run RMSE has median 0.22
 * and 90th percentile 0.41 (the same before and after the ziggurat and table kernels), and
 * about 6 % of single points lie beyond 0.5 px, which is why a per-point 0.5 px bound is not
 * asserted. */
static void test_manager_ids_and_events(void)
{
    double se2 = 0.0;
    int npos = 0;
    static pft_tbd_t t;
    pft_tbd_config_t c;
    small_cfg(&c, SIGMA_15DB, 51u);
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tbd_init(&t, &c, g_mbuf, MWS_BYTES));
    pft_rng_t sim;
    pft_rng_seed(&sim, 14u);
    const pft_sim_truth_t tr1 = {2, 9, 2.0, 2.0, 0.3, 0.2, 20.0};
    const pft_sim_truth_t tr2 = {16, 40, 6.0, 5.0, -0.2, 0.1, 20.0};
    uint32_t confirmed[4] = {0}, ended[4] = {0};
    int nc = 0, ne = 0;
    for (int k = 1; k <= 24; ++k) {
        pft_frame_t fr;
        render(&sim, pft_sim_alive(&tr1, k) ? &tr1 : &tr2, k, SIGMA_15DB, &fr);
        TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tbd_update(&t, &fr));
        TEST_ASSERT_EQUAL_UINT32((uint32_t)k, pft_tbd_frame(&t));
        pft_tbd_event_t ev[3];
        size_t n = pft_tbd_events(&t, ev, 3);
        for (size_t a = 0; a < n; ++a) {
            TEST_ASSERT_EQUAL_UINT32((uint32_t)k, ev[a].frame);
            if (ev[a].kind == PFT_TBD_EV_CONFIRMED && nc < 4) {
                confirmed[nc++] = ev[a].id;
            } else if (ev[a].kind == PFT_TBD_EV_ENDED && ne < 4) {
                ended[ne++] = ev[a].id;
            }
        }
        pft_tbd_track_t trk[2];
        size_t nt = pft_tbd_tracks(&t, trk, 2);
        TEST_ASSERT_TRUE(nt <= 1u);
        if (nt == 1u) {
            TEST_ASSERT_EQUAL_UINT32((uint32_t)k - trk[0].first_frame, trk[0].age);
            const pft_sim_truth_t *tt = pft_sim_alive(&tr1, k) ? &tr1 : &tr2;
            if (pft_sim_alive(tt, k) && trk[0].age >= 2u) {
                double dx = D(trk[0].x) - pft_sim_x(tt, k), dy = D(trk[0].y) - pft_sim_y(tt, k);
                TEST_ASSERT_TRUE_MESSAGE(dx * dx + dy * dy < 1.0, "track position within 1 px");
                se2 += dx * dx + dy * dy;
                ++npos;
            }
        }
        if (k == 8) {
            TEST_ASSERT_EQUAL_UINT(1u, (unsigned)nt);
        }
        if (k == 14) {
            TEST_ASSERT_EQUAL_UINT_MESSAGE(0u, (unsigned)nt, "track 1 ended");
        }
        if (k == 24) {
            TEST_ASSERT_EQUAL_UINT(1u, (unsigned)nt);
        }
    }
    UnityPrint("manager tracks:");
    note("points", npos);
    note("rmse", sqrt(se2 / npos));
    UNITY_PRINT_EOL();
    TEST_ASSERT_TRUE(npos >= 10);
    TEST_ASSERT_TRUE_MESSAGE(se2 < 0.45 * 0.45 * npos, "track RMSE");
    TEST_ASSERT_EQUAL_INT(2, nc);
    TEST_ASSERT_EQUAL_INT(1, ne);
    TEST_ASSERT_EQUAL_UINT32(1u, confirmed[0]);
    TEST_ASSERT_EQUAL_UINT32(2u, confirmed[1]);
    TEST_ASSERT_EQUAL_UINT32(1u, ended[0]);
    pft_tbd_estimate_t se;
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tbd_search_estimate(&t, &se));
    TEST_ASSERT_TRUE(D(se.p_exist) < 0.6);
}

/* Renders up to two targets (either may be NULL) into one U16 frame. */
static void render2(pft_rng_t *r, const pft_sim_truth_t *a, const pft_sim_truth_t *b, int k, double sigma,
                    pft_frame_t *f)
{
    pft_sim_truth_t ts[2];
    int n = 0;
    if (a != NULL) {
        ts[n++] = *a;
    }
    if (b != NULL) {
        ts[n++] = *b;
    }
    pft_sim_render_u16(r, ts, n, k, sigma, IMG, IMG, g_raw, f);
}

/* Runs the manager on T1 (frames 1-20, at rest at (3, 4)) and T2 spawned 2.06 px beside it at
 * frame 6 (at rest at (5, 4.5), inside the 5x5 region D around T1), 10 dB. Returns the first
 * frame at which both targets hold a track within 1 px (0: never); *held counts the frames
 * after it in which both still do, *ids the largest track id. */
static int spawned_beside(const pft_tbd_config_t *c, int *held, uint32_t *ids)
{
    static pft_tbd_t t;
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tbd_init(&t, c, g_mbuf, MWS_BYTES));
    pft_rng_t sim;
    pft_rng_seed(&sim, 23u + c->seed);
    const pft_sim_truth_t t1 = {1, 20, 3.0, 4.0, 0.0, 0.0, 20.0};
    const pft_sim_truth_t t2 = {6, 20, 5.0, 4.5, 0.0, 0.0, 20.0};
    int both = 0;
    *held = 0;
    for (int k = 1; k <= 20; ++k) {
        pft_frame_t fr;
        render2(&sim, &t1, &t2, k, SIGMA_10DB, &fr);
        TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tbd_update(&t, &fr));
        pft_tbd_track_t trk[2];
        size_t n = pft_tbd_tracks(&t, trk, 2);
        int on[2] = {0, 0};
        for (size_t a = 0; a < n && a < 2u; ++a) {
            const pft_sim_truth_t *ts[2] = {&t1, &t2};
            for (int q = 0; q < 2; ++q) {
                double dx = D(trk[a].x) - pft_sim_x(ts[q], k), dy = D(trk[a].y) - pft_sim_y(ts[q], k);
                on[q] |= pft_sim_alive(ts[q], k) && dx * dx + dy * dy <= 1.0;
            }
            *ids = trk[a].id > *ids ? trk[a].id : *ids;
        }
        if (both > 0 && on[0] && on[1]) {
            ++*held;
        }
        if (on[0] && on[1] && both == 0) {
            both = k;
        }
    }
    return both;
}

/* Over 8 seeds: mean frames from T2's spawn until both targets are tracked (never: 14), the
 * fraction of the later frames in which both stay tracked, and the mean largest track id. */
static void spawned_stats(bool residual, double *delay, double *held_frac, double *ids_mean)
{
    double sd = 0.0, sh = 0.0, sn = 0.0, si = 0.0;
    for (uint64_t q = 0; q < 8u; ++q) {
        pft_tbd_config_t c;
        small_cfg(&c, SIGMA_10DB, 61u + q);
        if (!residual) {
            /* the previous recommended preset: D = 5x5 around the current estimate */
            c.residual_search = false;
            c.residual_tracks = false;
            c.d_region = PFT_TBD_D_WINDOW;
            c.handover_gate = 0u;
        }
        int held = 0;
        uint32_t ids = 0;
        int both = spawned_beside(&c, &held, &ids);
        sd += both > 0 ? (double)(both - 6) : 14.0;
        sh += held;
        sn += both > 0 ? (double)(20 - both) : 0.0;
        si += ids;
    }
    *delay = sd / 8.0;
    *held_frac = sn > 0.0 ? sh / sn : 0.0;
    *ids_mean = si / 8.0;
}

/* The joint (residual) likelihood lets the search layer find a target spawned beside a
 * confirmed one, and both track layers keep their targets (each sees the other's PSF
 * removed); without it, the 5x5 D of the previous recommended preset blocks the spawned
 * target's births for as long as the targets stay this close.
 * Measured (float): residual delay 1.75 frames, both held in 0.94 of the later frames, largest
 * id 2.9; D 5x5: delay 5.1, held 0.44, largest id 2.6. */
static void test_manager_residual_finds_spawned_target(void)
{
    double d1, h1, i1, d0, h0, i0;
    spawned_stats(true, &d1, &h1, &i1);
    spawned_stats(false, &d0, &h0, &i0);
    UnityPrint("spawned 2 px beside a track, 10 dB, 8 seeds: residual");
    note("delay", d1);
    note("held", h1);
    note("ids", i1);
    UnityPrint(" | D 5x5");
    note("delay", d0);
    note("held", h0);
    note("ids", i0);
    UNITY_PRINT_EOL();
    TEST_ASSERT_TRUE_MESSAGE(d1 <= 3.0, "spawned target tracked within 3 frames on average");
    TEST_ASSERT_TRUE_MESSAGE(h1 >= 0.85, "both stay tracked");
    TEST_ASSERT_TRUE_MESSAGE(i1 <= 3.5, "few duplicate or re-acquired tracks");
    TEST_ASSERT_TRUE_MESSAGE(d0 >= d1 + 2.0, "the constraint region delays it");
    TEST_ASSERT_TRUE_MESSAGE(h1 >= h0 + 0.2, "and holds both less often");
}


/* ------------------------- the search layer's move pass in its split form ------------------ */
/* tbd_filter.c's move_bern_ on AArch64 and x86-64 float (MOVE_SPLIT_): the inner loop takes only
 * the ziggurat's fast words and stops at a word that needs the slow path (about 1.2 % of the
 * words) and, in float, at a birth intensity that rounds up to i_max; the outer loop finishes
 * that particle. Against the general loop on a copy: 2 x 6 passes over 3000 RBPF particles
 * (share 1/4, births from five candidate pixels, one pass without candidates), the default
 * intensity range and one of two ulps (float: most births stop there; q16: two LSBs), every
 * particle array, the generator and the counts equal after every pass. Known answers: the
 * births, survivors and the generator's last word, integers that only the words drawn decide,
 * the same in both builds and on both targets (the general loop's). The inner loop stopped
 * about 1 750 times at a survivor's slow word (each of the three draws some 550-650 times;
 * counted once with a temporary counter) and, in float, about 1 700 times at a birth's i_max. */
#define MB_N 3000u
#define MB_BYTES PFT_TBD_FILTER_WORKSPACE_BYTES(MB_N, PFT_TBD_RBPF, IMG, IMG)
static uint8_t g_mb[2][MB_BYTES + 64];

static void test_move_bern_split_is_its_general_form(void)
{
#if defined(__aarch64__) || (defined(__x86_64__) && !defined(PFT_NUMERIC_Q16))
    static const uint32_t cand[5] = {0u, 11u, 45u, 67u, 99u};
    uint32_t tot[2][3] = {{0u, 0u, 0u}, {0u, 0u, 0u}};
    for (int narrow = 0; narrow < 2; ++narrow) {
        pft_tbd_config_t c;
        pft_tbd_filter_t f[2];
        pft_tbd_scene_t_ sc;
        small_cfg(&c, SIGMA_10DB, 7u + (uint64_t)narrow);
        if (narrow != 0) {
#ifdef PFT_NUMERIC_Q16
            c.i_max = c.i_min + 2;
#else
            c.i_max = nextafterf(nextafterf(c.i_min, 1e9f), 1e9f);
#endif
        }
        for (int k = 0; k < 2; ++k) {
            TEST_ASSERT_EQUAL_INT(PFT_OK,
                                  finit(&f[k], &c, MB_N, PFT_TBD_RBPF, g_mb[k], sizeof g_mb[k]));
        }
        memset(&sc, 0, sizeof sc);
        sc.width = IMG;
        sc.height = IMG;
        for (int pass = 0; pass < 6; ++pass) {
            uint32_t nb[2];
            uint32_t np[2];
            sc.cand = pass == 3 ? NULL : cand;
            sc.n_cand = pass == 3 ? 0u : 5u;
            for (int k = 0; k < 2; ++k) {
                pft_tbd_move_bern_hook_(&f[k], &sc, 0x4000u, k == 0, &nb[k], &np[k]);
            }
            TEST_ASSERT_EQUAL_UINT32(nb[1], nb[0]);
            TEST_ASSERT_EQUAL_UINT32(np[1], np[0]);
            TEST_ASSERT_EQUAL_MEMORY(f[1].rng.s, f[0].rng.s, sizeof f[0].rng.s);
            TEST_ASSERT_EQUAL_MEMORY(f[1].cur.e, f[0].cur.e, MB_N);
            TEST_ASSERT_EQUAL_MEMORY(f[1].cur.x, f[0].cur.x, MB_N * sizeof(pft_real_t));
            TEST_ASSERT_EQUAL_MEMORY(f[1].cur.y, f[0].cur.y, MB_N * sizeof(pft_real_t));
            TEST_ASSERT_EQUAL_MEMORY(f[1].cur.vx, f[0].cur.vx, MB_N * sizeof(pft_real_t));
            TEST_ASSERT_EQUAL_MEMORY(f[1].cur.vy, f[0].cur.vy, MB_N * sizeof(pft_real_t));
            TEST_ASSERT_EQUAL_MEMORY(f[1].cur.in, f[0].cur.in, MB_N * sizeof(pft_real_t));
            tot[narrow][0] += nb[0];
            tot[narrow][1] += np[0];
        }
        tot[narrow][2] = f[0].rng.s[3];
    }
    TEST_ASSERT_EQUAL_UINT32(6531u, tot[0][0]);
    TEST_ASSERT_EQUAL_UINT32(10723u, tot[0][1]);
    TEST_ASSERT_EQUAL_UINT32(803233196u, tot[0][2]);
    TEST_ASSERT_EQUAL_UINT32(6592u, tot[1][0]);
    TEST_ASSERT_EQUAL_UINT32(10675u, tot[1][1]);
    TEST_ASSERT_EQUAL_UINT32(578712873u, tot[1][2]);
#else
    TEST_IGNORE_MESSAGE("the split move pass exists on AArch64 and x86-64 float only");
#endif
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_filter_workspace_size_is_exact);
    RUN_TEST(test_manager_workspace_size_is_exact);
    RUN_TEST(test_filter_refused_input_leaves_state_untouched);
    RUN_TEST(test_manager_refused_input_leaves_state_untouched);
    RUN_TEST(test_filter_is_deterministic);
    RUN_TEST(test_reset_reproduces_the_first_run);
    RUN_TEST(test_noise_only_keeps_existence_low);
    RUN_TEST(test_bright_target_rbpf);
    RUN_TEST(test_bright_target_pf);
    RUN_TEST(test_kf_exact_variance_matches_reference);
    RUN_TEST(test_manager_ids_and_events);
    RUN_TEST(test_manager_residual_finds_spawned_target);
    RUN_TEST(test_move_bern_split_is_its_general_form);
    return UNITY_END();
}
