/*
 * Refusals leave every byte as it was (issue #12): for each public function that can refuse,
 * and that no other test file already covers (docs/reliability.md "Refusals" lists every
 * refusing function with the test that covers it), a valid instance and workspace are set up
 * and run for a few frames so their state is not trivial, instance and workspace (and caller
 * output buffers the contract leaves untouched) are snapshotted, the refused call must return
 * its documented status, and a memcmp against the snapshot must find no changed byte. After the
 * refusals a valid call must still work (so the snapshot was of a live state).
 *
 * Sizes are small (images of a few hundred pixels, a few hundred particles): the file runs in
 * seconds under QEMU; the big buffers are static.
 */
#include <math.h>
#include <string.h>

#include "pft_test_support.h"
#include "pft_tbd_sim.h"
#include "pft/pft_pf.h"
#include "pft/pft_pf_models.h"
#include "pft/pft_pre.h"
#include "pft/pft_pte.h"
#include "pft/pft_resample.h"
#include "pft/pft_tbd.h"
#include "pft/pft_tsa.h"

void setUp(void) {}
void tearDown(void) {}

static pft_real_t R(double v) { return pft_test_from_double(v); }

/* ------------------------------------ snapshots ------------------------------------------- */
/* Up to four regions (instance, workspace, caller outputs) copied into one static buffer;
 * snap_check compares every region with its copy. */
#define SNAP_BYTES (320u * 1024u)
#define SNAP_MAX 4u
static uint8_t g_snap[SNAP_BYTES];
static const void *g_reg[SNAP_MAX];
static size_t g_len[SNAP_MAX];
static size_t g_nreg;
static size_t g_used;

static void snap_begin(void)
{
    g_nreg = 0u;
    g_used = 0u;
}

#if defined(__GNUC__)
__attribute__((noinline)) /* keeps GCC from guessing overreads of the inlined memcpy */
#endif
static void snap_add(const void *p, size_t n)
{
    TEST_ASSERT_TRUE_MESSAGE(g_nreg < SNAP_MAX, "too many snapshot regions");
    TEST_ASSERT_TRUE_MESSAGE(n <= SNAP_BYTES - g_used, "snapshot buffer too small");
    memcpy(g_snap + g_used, p, n);
    g_reg[g_nreg] = p;
    g_len[g_nreg] = n;
    g_nreg++;
    g_used += n;
}

static void snap_check(const char *what)
{
    size_t off = 0u;
    for (size_t i = 0; i < g_nreg; ++i) {
        TEST_ASSERT_EQUAL_MEMORY_MESSAGE(g_snap + off, g_reg[i], g_len[i], what);
        off += g_len[i];
    }
}

/* The refused call returns `code` and every snapshotted byte is as it was. */
#define REFUSED(code, call)                                                                   \
    do {                                                                                      \
        TEST_ASSERT_EQUAL_INT_MESSAGE((int)(code), (int)(call), #call);                       \
        snap_check(#call);                                                                    \
    } while (0)

/* One byte below what an 8-byte aligned workspace needs (the sizes count PFT_WS_ALIGN - 1
 * bytes of alignment padding that an aligned start does not use). */
#define SHORT(need) ((need) - (size_t)PFT_WS_ALIGN)

/* Shared workspace for every test (one at a time), 8-byte aligned. */
static uint64_t g_work[(256u * 1024u) / 8u];
static uint64_t g_work2[(64u * 1024u) / 8u]; /* a second instance's workspace */

/* ------------------------------------- core ----------------------------------------------- */

/* pft_resample: a refusal leaves the indices AND the caller's RNG untouched (the RNG is state
 * the caller carries from frame to frame); test_resample.c covers the indices alone. */
static void test_resample_refusals_leave_idx_and_rng(void)
{
    static pft_weight_t w[4];
    static const pft_weight_t zero[4];
    static uint32_t idx[6];
    static uint8_t scratch[64];
    const uint32_t u[6] = {1u, 2u, 3u, 4u, 5u, 6u};
    pft_rng_t rng;
    pft_rng_seed(&rng, 9u);
    (void)pft_rng_u32(&rng); /* not the freshly seeded state */
    for (int i = 0; i < 4; ++i) {
        w[i] = PFT_W_ONE / 4;
    }
    memset(idx, 0xEE, sizeof idx);
    snap_begin();
    snap_add(idx, sizeof idx);
    snap_add(&rng, sizeof rng);
    snap_add(scratch, sizeof scratch);
    REFUSED(PFT_ERR_INVAL, pft_resample(PFT_RESAMPLE_SYSTEMATIC, NULL, 4, idx, 6, &rng, NULL, 0));
    REFUSED(PFT_ERR_INVAL, pft_resample(PFT_RESAMPLE_SYSTEMATIC, w, 4, NULL, 6, &rng, NULL, 0));
    REFUSED(PFT_ERR_INVAL, pft_resample((pft_resample_scheme_t)77, w, 4, idx, 6, &rng, NULL, 0));
    REFUSED(PFT_ERR_INVAL, pft_resample(PFT_RESAMPLE_SYSTEMATIC, w, PFT_CFG_MAX_PARTICLES + 1u,
                                        idx, 6, &rng, NULL, 0));
    REFUSED(PFT_ERR_INVAL, pft_resample(PFT_RESAMPLE_SYSTEMATIC, w, 4, idx,
                                        PFT_CFG_MAX_PARTICLES + 1u, &rng, NULL, 0));
    REFUSED(PFT_ERR_NOMEM, pft_resample(PFT_RESAMPLE_RESIDUAL, w, 4, idx, 6, &rng, NULL, 0));
    REFUSED(PFT_ERR_NOMEM, pft_resample(PFT_RESAMPLE_RESIDUAL, w, 4, idx, 6, &rng, scratch, 1u));
    for (int s = 0; s < 4; ++s) {
        const pft_resample_scheme_t sc = s == 0   ? PFT_RESAMPLE_SYSTEMATIC
                                         : s == 1 ? PFT_RESAMPLE_STRATIFIED
                                         : s == 2 ? PFT_RESAMPLE_MULTINOMIAL
                                                  : PFT_RESAMPLE_RESIDUAL;
        REFUSED(PFT_ERR_DEGENERATE, pft_resample(sc, zero, 4, idx, 6, &rng, scratch, sizeof scratch));
    }
    REFUSED(PFT_ERR_INVAL, pft_resample_systematic_u(NULL, 4, idx, 6, 7u));
    REFUSED(PFT_ERR_INVAL, pft_resample_stratified_u(w, 4, idx, 6, NULL));
    REFUSED(PFT_ERR_INVAL, pft_resample_multinomial_u(w, 4, idx, 6, NULL));
    REFUSED(PFT_ERR_DEGENERATE, pft_resample_stratified_u(zero, 4, idx, 6, u));
    REFUSED(PFT_ERR_DEGENERATE, pft_resample_multinomial_u(zero, 4, idx, 6, u));
    /* and a valid call moves both */
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_resample(PFT_RESAMPLE_MULTINOMIAL, w, 4, idx, 6, &rng,
                                               scratch, sizeof scratch));
    TEST_ASSERT_TRUE(memcmp(g_snap, idx, sizeof idx) != 0);
    TEST_ASSERT_TRUE(memcmp(g_snap + sizeof idx, &rng, sizeof rng) != 0);
}

/* ------------------------------------ pf engine ------------------------------------------- */
#define PF_N 64u
static pft_pf_t g_pf;
static pft_pf_bearings_model_t g_brg;

static void pf_live(pft_pf_config_t *c)
{
    pft_pf_bearings_config_t bc;
    pft_pf_bearings_config_default(&bc, 1000);
    pft_pf_config_default(c);
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_pf_bearings_model_init(&g_brg, &bc, &c->model));
    c->kind = PFT_PF_SIR;
    c->n_particles = PF_N;
    c->seed = 3u;
    TEST_ASSERT_TRUE(pft_pf_workspace_size(c) <= sizeof g_work);
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_pf_init(&g_pf, c, g_work, sizeof g_work));
    for (int k = 0; k < 3; ++k) {
        const pft_real_t z = R(1.2 - 0.01 * k);
        TEST_ASSERT_EQUAL_INT(PFT_OK, pft_pf_update(&g_pf, &z));
    }
}

static void test_pf_engine_refusals(void)
{
    pft_pf_config_t c;
    pf_live(&c);
    const size_t need = pft_pf_workspace_size(&c);
    static pft_real_t out[PF_N * 4u], cov[16];
    static pft_pf_stats_t st;
    memset(out, 0x5A, sizeof out);
    memset(cov, 0x5A, sizeof cov);
    memset(&st, 0x5A, sizeof st);
    snap_begin();
    snap_add(&g_pf, sizeof g_pf);
    snap_add(g_work, need);
    snap_add(out, sizeof out);
    snap_add(&st, sizeof st);
    /* init on a live engine: a refused cfg, NULL pieces */
    pft_pf_config_t bad = c;
    bad.n_particles = 0u;
    REFUSED(PFT_ERR_CONFIG, pft_pf_init(&g_pf, &bad, g_work, sizeof g_work));
    bad = c;
    bad.model.loglik = NULL;
    REFUSED(PFT_ERR_CONFIG, pft_pf_init(&g_pf, &bad, g_work, sizeof g_work));
    REFUSED(PFT_ERR_INVAL, pft_pf_init(&g_pf, NULL, g_work, sizeof g_work));
    REFUSED(PFT_ERR_INVAL, pft_pf_init(&g_pf, &c, NULL, sizeof g_work));
    /* steps and results */
    const pft_real_t z = R(1.1);
    REFUSED(PFT_ERR_INVAL, pft_pf_update(NULL, &z));
    REFUSED(PFT_ERR_INVAL, pft_pf_reset(NULL));
    REFUSED(PFT_ERR_INVAL, pft_pf_reseed(NULL, 5u));
    REFUSED(PFT_ERR_INVAL, pft_pf_estimate(&g_pf, NULL));
    REFUSED(PFT_ERR_INVAL, pft_pf_estimate(NULL, out));
    REFUSED(PFT_ERR_INVAL, pft_pf_mean_cov(&g_pf, NULL, cov));
    REFUSED(PFT_ERR_INVAL, pft_pf_mean_cov(NULL, out, NULL));
    REFUSED(PFT_ERR_INVAL, pft_pf_stats(&g_pf, NULL));
    REFUSED(PFT_ERR_INVAL, pft_pf_stats(NULL, &st));
    /* replacing the particle set: another N, NULL */
    for (uint32_t i = 0; i < PF_N * 4u; ++i) {
        out[i] = R(0.25);
    }
    snap_begin();
    snap_add(&g_pf, sizeof g_pf);
    snap_add(g_work, need);
    snap_add(out, sizeof out);
    REFUSED(PFT_ERR_INVAL, pft_pf_set_states(&g_pf, out, PF_N - 1u));
    REFUSED(PFT_ERR_INVAL, pft_pf_set_states(&g_pf, out, PF_N + 1u));
    REFUSED(PFT_ERR_INVAL, pft_pf_set_states(&g_pf, NULL, PF_N));
    REFUSED(PFT_ERR_INVAL, pft_pf_set_states(NULL, out, PF_N));
    REFUSED(PFT_ERR_INVAL, pft_pf_set_logweights(&g_pf, NULL));
    REFUSED(PFT_ERR_INVAL, pft_pf_set_logweights(NULL, out));
    /* still live: a valid update moves the workspace */
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_pf_update(&g_pf, &z));
    TEST_ASSERT_TRUE(memcmp(g_snap + sizeof g_pf, g_work, need) != 0);
}

/* A short workspace on a live engine: documented as zeroing the instance (pft_pf.h), the
 * workspace itself is not written. */
static void test_pf_init_short_workspace_zeroes_instance_only(void)
{
    pft_pf_config_t c;
    pf_live(&c);
    const size_t need = pft_pf_workspace_size(&c);
    snap_begin();
    snap_add(g_work, need);
    TEST_ASSERT_EQUAL_INT(PFT_ERR_NOMEM, pft_pf_init(&g_pf, &c, g_work, SHORT(need)));
    snap_check("pft_pf_init short workspace");
    static const pft_pf_t zero;
    TEST_ASSERT_EQUAL_MEMORY(&zero, &g_pf, sizeof g_pf);
    /* and a zeroed (never initialised) engine refuses reset, changing nothing */
    snap_begin();
    snap_add(&g_pf, sizeof g_pf);
    REFUSED(PFT_ERR_INVAL, pft_pf_reset(&g_pf));
    REFUSED(PFT_ERR_INVAL, pft_pf_reseed(&g_pf, 3u));
}

/* The models' init on a live model (one an engine is using): refused, model and interface as
 * they were. */
static void test_pf_model_init_refusals(void)
{
    pft_pf_config_t c;
    pf_live(&c);
    pft_pf_model_t iface = c.model;
    pft_pf_bearings_config_t bc;
    pft_pf_bearings_config_default(&bc, 1000);
    snap_begin();
    snap_add(&g_brg, sizeof g_brg);
    snap_add(&iface, sizeof iface);
    pft_pf_bearings_config_t bb = bc;
    bb.r_sd = PFT_C(0.0);
    REFUSED(PFT_ERR_CONFIG, pft_pf_bearings_model_init(&g_brg, &bb, &iface));
    bb = bc;
    bb.prior_sd[1] = PFT_C(-1.0);
    REFUSED(PFT_ERR_CONFIG, pft_pf_bearings_model_init(&g_brg, &bb, &iface));
    REFUSED(PFT_ERR_INVAL, pft_pf_bearings_model_init(&g_brg, NULL, &iface));
    REFUSED(PFT_ERR_INVAL, pft_pf_bearings_model_init(&g_brg, &bc, NULL));

    /* linear Gaussian */
    static pft_pf_lg_model_t lm;
    pft_pf_lg_config_t lc;
    memset(&lc, 0, sizeof lc);
    lc.dim = 2u;
    lc.meas = 1u;
    lc.F[0] = R(1.0);
    lc.F[1] = R(1.0);
    lc.F[3] = R(1.0);
    lc.Lq[0] = R(0.1);
    lc.Lq[3] = R(0.1);
    lc.H[0] = R(1.0);
    lc.r_sd[0] = R(0.5);
    lc.L0[0] = R(1.0);
    lc.L0[3] = R(1.0);
    pft_pf_model_t li;
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_pf_lg_model_init(&lm, &lc, &li));
    snap_begin();
    snap_add(&lm, sizeof lm);
    snap_add(&li, sizeof li);
    pft_pf_lg_config_t lb = lc;
    lb.dim = 0u;
    REFUSED(PFT_ERR_CONFIG, pft_pf_lg_model_init(&lm, &lb, &li));
    lb = lc;
    lb.meas = PFT_PF_LG_MAX_MEAS + 1u;
    REFUSED(PFT_ERR_CONFIG, pft_pf_lg_model_init(&lm, &lb, &li));
    lb = lc;
    lb.r_sd[0] = PFT_C(0.0);
    REFUSED(PFT_ERR_CONFIG, pft_pf_lg_model_init(&lm, &lb, &li));
    REFUSED(PFT_ERR_INVAL, pft_pf_lg_model_init(NULL, &lc, &li));
    REFUSED(PFT_ERR_INVAL, pft_pf_lg_model_init(&lm, NULL, &li));

    /* TBD pixel model: a live model and its workspace */
    static pft_pf_tbd_model_t tm;
    pft_tbd_config_t tc;
    pft_tbd_config_default(&tc);
    tc.width = 12u;
    tc.height = 10u;
    tc.noise_sigma = R(2.0);
    pft_pf_model_t ti;
    const size_t need = pft_pf_tbd_model_workspace_size(&tc);
    TEST_ASSERT_TRUE(need > 0u && need <= sizeof g_work2);
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_pf_tbd_model_init(&tm, &tc, g_work2, need, &ti));
    snap_begin();
    snap_add(&tm, sizeof tm);
    snap_add(&ti, sizeof ti);
    snap_add(g_work2, need);
    pft_tbd_config_t tb = tc;
    tb.width = 0u;
    REFUSED(PFT_ERR_CONFIG, pft_pf_tbd_model_init(&tm, &tb, g_work2, need, &ti));
    REFUSED(PFT_ERR_NOMEM, pft_pf_tbd_model_init(&tm, &tc, g_work2, SHORT(need), &ti));
    REFUSED(PFT_ERR_INVAL, pft_pf_tbd_model_init(&tm, &tc, NULL, need, &ti));
    REFUSED(PFT_ERR_INVAL, pft_pf_tbd_model_init(&tm, NULL, g_work2, need, &ti));
    REFUSED(PFT_ERR_INVAL, pft_pf_tbd_model_init(&tm, &tc, g_work2, need, NULL));
}

/* --------------------------------------- tbd ---------------------------------------------- */
#define TIMG 10
static uint16_t g_raw[TIMG * TIMG];

static void tbd_cfg(pft_tbd_config_t *c)
{
    pft_test_tbd_u16_config(c, TIMG, 1.1552);
    c->n_search = 300u;
    c->n_track = 150u;
    c->max_targets = 2u;
    c->seed = 11u;
}

static void tbd_frame(pft_rng_t *sim, int k, pft_frame_t *f)
{
    const pft_sim_truth_t tr = {1, 40, 2.0, 2.0, 0.3, 0.2, 20.0};
    pft_sim_render_u16(sim, &tr, 1, k, 1.1552, TIMG, TIMG, g_raw, f);
}

static void test_tbd_manager_init_and_results_refusals(void)
{
    static pft_tbd_t t;
    pft_tbd_config_t c;
    tbd_cfg(&c);
    const size_t need = pft_tbd_workspace_size(&c);
    TEST_ASSERT_TRUE(need > 0u && need <= sizeof g_work);
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tbd_init(&t, &c, g_work, need));
    pft_rng_t sim;
    pft_rng_seed(&sim, 6u);
    pft_frame_t fr;
    for (int k = 1; k <= 8; ++k) {
        tbd_frame(&sim, k, &fr);
        TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tbd_update(&t, &fr));
    }
    TEST_ASSERT_EQUAL_UINT(1u, (unsigned)pft_tbd_tracks(&t, NULL, 0)); /* a live track layer */
    static pft_tbd_estimate_t e;
    memset(&e, 0x5A, sizeof e);
    snap_begin();
    snap_add(&t, sizeof t);
    snap_add(g_work, need);
    snap_add(&e, sizeof e);
    pft_tbd_config_t bad = c;
    bad.n_search = 0u;
    REFUSED(PFT_ERR_CONFIG, pft_tbd_init(&t, &bad, g_work, need));
    bad = c;
    bad.vel_var[1] = PFT_C(-1.0);
    REFUSED(PFT_ERR_CONFIG, pft_tbd_init(&t, &bad, g_work, need));
    REFUSED(PFT_ERR_NOMEM, pft_tbd_init(&t, &c, g_work, SHORT(need)));
    REFUSED(PFT_ERR_INVAL, pft_tbd_init(&t, &c, NULL, need));
    REFUSED(PFT_ERR_INVAL, pft_tbd_init(&t, NULL, g_work, need));
    REFUSED(PFT_ERR_INVAL, pft_tbd_reset(NULL));
    REFUSED(PFT_ERR_INVAL, pft_tbd_update(NULL, &fr));
    REFUSED(PFT_ERR_INVAL, pft_tbd_search_estimate(&t, NULL));
    REFUSED(PFT_ERR_INVAL, pft_tbd_search_estimate(NULL, &e));
    /* a layer of the manager (the live track's) is not a standalone filter: the standalone
     * calls refuse it and change nothing, neither the layer nor the manager */
    REFUSED(PFT_ERR_STATE, pft_tbd_filter_reset(&t.tracks[0]));
    REFUSED(PFT_ERR_STATE, pft_tbd_filter_update(&t.tracks[0], &fr));
    REFUSED(PFT_ERR_STATE, pft_tbd_filter_update(&t.search, &fr));
    /* still live */
    tbd_frame(&sim, 9, &fr);
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tbd_update(&t, &fr));
    TEST_ASSERT_TRUE(memcmp(g_snap + sizeof t, g_work, need) != 0);
    /* a never initialised (zeroed) manager refuses reset and update, changing nothing */
    static pft_tbd_t z;
    memset(&z, 0, sizeof z);
    snap_begin();
    snap_add(&z, sizeof z);
    REFUSED(PFT_ERR_STATE, pft_tbd_reset(&z));
    TEST_ASSERT_TRUE(pft_tbd_update(&z, &fr) != PFT_OK);
    snap_check("pft_tbd_update(never initialised)");
}

static void test_tbd_filter_init_and_results_refusals(void)
{
    static pft_tbd_filter_t f;
    pft_tbd_config_t c;
    tbd_cfg(&c);
    const size_t need = pft_tbd_filter_workspace_size(&c);
    TEST_ASSERT_TRUE(need > 0u && need <= sizeof g_work);
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tbd_filter_init(&f, &c, g_work, need));
    pft_rng_t sim;
    pft_rng_seed(&sim, 7u);
    pft_frame_t fr;
    for (int k = 1; k <= 5; ++k) {
        tbd_frame(&sim, k, &fr);
        TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tbd_filter_update(&f, &fr));
    }
    static pft_tbd_estimate_t e;
    memset(&e, 0x5A, sizeof e);
    snap_begin();
    snap_add(&f, sizeof f);
    snap_add(g_work, need);
    snap_add(&e, sizeof e);
    pft_tbd_config_t bad = c;
    bad.n_search = 0u;
    REFUSED(PFT_ERR_CONFIG, pft_tbd_filter_init(&f, &bad, g_work, need));
    bad = c;
    bad.width = 0u;
    REFUSED(PFT_ERR_CONFIG, pft_tbd_filter_init(&f, &bad, g_work, need));
    REFUSED(PFT_ERR_NOMEM, pft_tbd_filter_init(&f, &c, g_work, SHORT(need)));
    REFUSED(PFT_ERR_INVAL, pft_tbd_filter_init(&f, &c, NULL, need));
    REFUSED(PFT_ERR_INVAL, pft_tbd_filter_init(&f, NULL, g_work, need));
    REFUSED(PFT_ERR_INVAL, pft_tbd_filter_reset(NULL));
    REFUSED(PFT_ERR_INVAL, pft_tbd_filter_estimate(&f, NULL));
    REFUSED(PFT_ERR_INVAL, pft_tbd_filter_estimate(NULL, &e));
    tbd_frame(&sim, 6, &fr);
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tbd_filter_update(&f, &fr));
    TEST_ASSERT_TRUE(memcmp(g_snap + sizeof f, g_work, need) != 0);
    /* a never initialised (zeroed) filter refuses reset, changing nothing */
    static pft_tbd_filter_t z;
    memset(&z, 0, sizeof z);
    snap_begin();
    snap_add(&z, sizeof z);
    REFUSED(PFT_ERR_STATE, pft_tbd_filter_reset(&z));
}

/* pft_tbd_meas_init: m untouched on a refused cfg (pft_tbd.h). */
static void test_tbd_meas_init_refusals(void)
{
    pft_tbd_config_t c;
    tbd_cfg(&c);
    static pft_tbd_meas_t m;
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tbd_meas_init(&m, &c));
    snap_begin();
    snap_add(&m, sizeof m);
    pft_tbd_config_t bad = c;
    bad.noise_sigma = PFT_C(0.0);
    REFUSED(PFT_ERR_CONFIG, pft_tbd_meas_init(&m, &bad));
    bad = c;
    bad.height = 0u;
    REFUSED(PFT_ERR_CONFIG, pft_tbd_meas_init(&m, &bad));
    REFUSED(PFT_ERR_INVAL, pft_tbd_meas_init(&m, NULL));
}

/* --------------------------------------- pte ---------------------------------------------- */
#define PNR 32
static pft_real_t g_z[PNR];
static uint64_t g_gs = 0x2545F4914F6CDD1Du;

/* a range profile of unit noise with a target of amplitude 4 at cell pos */
static void pte_profile(double pos)
{
    for (int u = 0; u < PNR; ++u) {
        const double d = u - pos;
        g_z[u] = R(pft_test_gauss(&g_gs) + 4.0 * exp(-d * d / 0.72));
    }
}

static void test_pte_refusals(void)
{
    static pft_pte_t p;
    pft_pte_config_t c;
    pft_pte_config_default(&c);
    c.in.n_range = PNR;
    c.in.n_doppler = 1u;
    c.max_tracks = 2u;
    c.init_threshold = R(16.0);
    const size_t need = pft_pte_workspace_size(&c);
    TEST_ASSERT_TRUE(need > 0u && need <= sizeof g_work);
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_pte_init(&p, &c, g_work, need));
    const pft_real_t pos[2] = {R(10.0), R(0.0)}, vel[2] = {R(0.2), R(0.0)};
    const pft_real_t pv[2] = {R(0.2), R(1.0)}, vv[2] = {R(0.01), R(1.0)};
    uint16_t id = 0u;
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_pte_start(&p, pos, vel, pv, vv, R(4.0), 5u, &id));
    for (int k = 0; k < 12; ++k) {
        pte_profile(10.0 + 0.2 * k);
        TEST_ASSERT_EQUAL_INT(PFT_OK, pft_pte_update_real(&p, g_z));
    }
    TEST_ASSERT_TRUE(pft_pte_reports(&p, NULL, 0) >= 1u);
    pft_real_t vt = R(-3.0);
    id = 777u;
    snap_begin();
    snap_add(&p, sizeof p);
    snap_add(g_work, need);
    snap_add(&vt, sizeof vt);
    snap_add(&id, sizeof id);
    /* init on a live instance */
    pft_pte_config_t bad = c;
    bad.max_tracks = 0u;
    REFUSED(PFT_ERR_CONFIG, pft_pte_init(&p, &bad, g_work, need));
    bad = c;
    bad.in.n_range = 0u;
    REFUSED(PFT_ERR_CONFIG, pft_pte_init(&p, &bad, g_work, need));
    REFUSED(PFT_ERR_NOMEM, pft_pte_init(&p, &c, g_work, SHORT(need)));
    REFUSED(PFT_ERR_INVAL, pft_pte_init(&p, NULL, g_work, need));
    REFUSED(PFT_ERR_INVAL, pft_pte_init(&p, &c, NULL, need));
    REFUSED(PFT_ERR_INVAL, pft_pte_reset(NULL));
    /* frames: NaN and infinity in F32, a wrong size, NULL */
    static float f32[PNR];
    for (int u = 0; u < PNR; ++u) {
        f32[u] = 0.5f;
    }
    pft_frame_t f;
    memset(&f, 0, sizeof f);
    f.data = f32;
    f.width = PNR;
    f.height = 1u;
    f.stride_bytes = 4u * PNR;
    f.format = PFT_PIX_F32;
    f32[PNR - 1] = NAN;
    REFUSED(PFT_ERR_FORMAT, pft_pte_update(&p, &f));
    f32[PNR - 1] = -INFINITY;
    REFUSED(PFT_ERR_FORMAT, pft_pte_update(&p, &f));
    f32[PNR - 1] = 0.5f;
    f.width = PNR + 1u;
    f.stride_bytes = 4u * (PNR + 1u);
    REFUSED(PFT_ERR_FORMAT, pft_pte_update(&p, &f));
    f.width = PNR;
    f.stride_bytes = 4u * PNR;
    f.format = PFT_PIX_RGB888;
    REFUSED(PFT_ERR_FORMAT, pft_pte_update(&p, &f));
    f.format = PFT_PIX_F32;
    REFUSED(PFT_ERR_INVAL, pft_pte_update(NULL, &f));
    REFUSED(PFT_ERR_INVAL, pft_pte_update_real(NULL, g_z));
    /* a cue with a bad argument: nothing changes, *id untouched */
    const pft_real_t zero2[2] = {PFT_C(0.0), PFT_C(0.0)};
    const pft_real_t neg2[2] = {R(-1.0), R(1.0)};
    REFUSED(PFT_ERR_INVAL, pft_pte_start(&p, NULL, vel, pv, vv, R(4.0), 5u, &id));
    REFUSED(PFT_ERR_INVAL, pft_pte_start(&p, pos, NULL, pv, vv, R(4.0), 5u, &id));
    REFUSED(PFT_ERR_INVAL, pft_pte_start(&p, pos, vel, NULL, vv, R(4.0), 5u, &id));
    REFUSED(PFT_ERR_INVAL, pft_pte_start(&p, pos, vel, pv, NULL, R(4.0), 5u, &id));
    REFUSED(PFT_ERR_INVAL, pft_pte_start(&p, pos, vel, pv, vv, R(4.0), 5u, NULL));
    REFUSED(PFT_ERR_INVAL, pft_pte_start(&p, pos, vel, pv, vv, R(4.0), 0u, &id));
    REFUSED(PFT_ERR_INVAL, pft_pte_start(&p, pos, vel, zero2, vv, R(4.0), 5u, &id));
    REFUSED(PFT_ERR_INVAL, pft_pte_start(&p, pos, vel, pv, neg2, R(4.0), 5u, &id));
    REFUSED(PFT_ERR_INVAL, pft_pte_start(NULL, pos, vel, pv, vv, R(4.0), 5u, &id));
    /* the threshold Monte Carlo refuses before it resets the instance */
    REFUSED(PFT_ERR_INVAL, pft_pte_threshold(&p, PFT_C(0.0), 100u, 1u, &vt));
    REFUSED(PFT_ERR_INVAL, pft_pte_threshold(&p, PFT_C(1.0), 100u, 1u, &vt));
    REFUSED(PFT_ERR_INVAL, pft_pte_threshold(&p, R(0.5), 0u, 1u, &vt));
    REFUSED(PFT_ERR_INVAL, pft_pte_threshold(&p, R(0.5), 4u * PFT_PTE_MC_TOPK, 1u, &vt)); /* k > top-k */
    REFUSED(PFT_ERR_INVAL, pft_pte_threshold(&p, R(0.1), 100u, 1u, NULL));
    REFUSED(PFT_ERR_INVAL, pft_pte_threshold(NULL, R(0.1), 100u, 1u, &vt));
    /* still live */
    pte_profile(12.6);
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_pte_update_real(&p, g_z));
    TEST_ASSERT_TRUE(memcmp(g_snap + sizeof p, g_work, need) != 0);
    /* never initialised (zeroed): reset and update refused, nothing written */
    static pft_pte_t z;
    memset(&z, 0, sizeof z);
    snap_begin();
    snap_add(&z, sizeof z);
    REFUSED(PFT_ERR_INVAL, pft_pte_reset(&z));
    REFUSED(PFT_ERR_INVAL, pft_pte_update_real(&z, g_z));
    REFUSED(PFT_ERR_INVAL, pft_pte_start(&z, pos, vel, pv, vv, R(4.0), 5u, &id));
}

static void test_pte_dp_dbt_init_and_threshold_refusals(void)
{
    /* DP-TBD: a live instance (a full batch held) */
    static pft_pte_dp_t dp;
    pft_pte_dp_config_t dc;
    pft_pte_dp_config_default(&dc);
    dc.in.n_range = PNR;
    dc.in.n_doppler = 1u;
    size_t need = pft_pte_dp_workspace_size(&dc);
    TEST_ASSERT_TRUE(need > 0u && need <= sizeof g_work);
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_pte_dp_init(&dp, &dc, g_work, need));
    for (int k = 0; k < 12; ++k) {
        pte_profile(8.0 + 0.3 * k);
        TEST_ASSERT_EQUAL_INT(PFT_OK, pft_pte_dp_update_real(&dp, g_z));
    }
    pft_real_t vt = R(-3.0);
    snap_begin();
    snap_add(&dp, sizeof dp);
    snap_add(g_work, need);
    snap_add(&vt, sizeof vt);
    pft_pte_dp_config_t dbad = dc;
    dbad.frames = 0u;
    REFUSED(PFT_ERR_CONFIG, pft_pte_dp_init(&dp, &dbad, g_work, need));
    REFUSED(PFT_ERR_NOMEM, pft_pte_dp_init(&dp, &dc, g_work, SHORT(need)));
    REFUSED(PFT_ERR_INVAL, pft_pte_dp_init(&dp, NULL, g_work, need));
    REFUSED(PFT_ERR_INVAL, pft_pte_dp_init(&dp, &dc, NULL, need));
    REFUSED(PFT_ERR_INVAL, pft_pte_dp_reset(NULL));
    REFUSED(PFT_ERR_INVAL, pft_pte_dp_threshold(&dp, PFT_C(0.0), 100u, 1u, &vt));
    REFUSED(PFT_ERR_INVAL, pft_pte_dp_threshold(&dp, PFT_C(1.0), 100u, 1u, &vt));
    REFUSED(PFT_ERR_INVAL, pft_pte_dp_threshold(&dp, R(0.5), 0u, 1u, &vt));
    REFUSED(PFT_ERR_INVAL, pft_pte_dp_threshold(&dp, R(0.5), 4u * PFT_PTE_MC_TOPK, 1u, &vt));
    REFUSED(PFT_ERR_INVAL, pft_pte_dp_threshold(&dp, R(0.1), 100u, 1u, NULL));
    pte_profile(11.9);
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_pte_dp_update_real(&dp, g_z));
    TEST_ASSERT_TRUE(memcmp(g_snap + sizeof dp, g_work, need) != 0);
    static pft_pte_dp_t dz;
    memset(&dz, 0, sizeof dz);
    snap_begin();
    snap_add(&dz, sizeof dz);
    REFUSED(PFT_ERR_INVAL, pft_pte_dp_reset(&dz));
    REFUSED(PFT_ERR_INVAL, pft_pte_dp_update_real(&dz, g_z));
    REFUSED(PFT_ERR_INVAL, pft_pte_dp_threshold(&dz, R(0.1), 100u, 1u, &vt));

    /* DBT: a live instance with a confirmed track */
    static pft_pte_dbt_t b;
    pft_pte_dbt_config_t bc;
    pft_pte_dbt_config_default(&bc);
    bc.in.n_range = PNR;
    bc.in.n_doppler = 1u;
    need = pft_pte_dbt_workspace_size(&bc);
    TEST_ASSERT_TRUE(need > 0u && need <= sizeof g_work);
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_pte_dbt_init(&b, &bc, g_work, need));
    for (int k = 0; k < 6; ++k) {
        memset(g_z, 0, sizeof g_z);
        g_z[10 + k / 2] = R(8.0);
        TEST_ASSERT_EQUAL_INT(PFT_OK, pft_pte_dbt_update_real(&b, g_z));
    }
    snap_begin();
    snap_add(&b, sizeof b);
    snap_add(g_work, need);
    pft_pte_dbt_config_t bbad = bc;
    bbad.in.noise_sigma = PFT_C(0.0);
    REFUSED(PFT_ERR_CONFIG, pft_pte_dbt_init(&b, &bbad, g_work, need));
    REFUSED(PFT_ERR_NOMEM, pft_pte_dbt_init(&b, &bc, g_work, SHORT(need)));
    REFUSED(PFT_ERR_INVAL, pft_pte_dbt_init(&b, NULL, g_work, need));
    REFUSED(PFT_ERR_INVAL, pft_pte_dbt_init(&b, &bc, NULL, need));
    REFUSED(PFT_ERR_INVAL, pft_pte_dbt_reset(NULL));
    static pft_pte_dbt_t z;
    memset(&z, 0, sizeof z);
    snap_begin();
    snap_add(&z, sizeof z);
    REFUSED(PFT_ERR_INVAL, pft_pte_dbt_reset(&z));
    REFUSED(PFT_ERR_INVAL, pft_pte_dbt_update_real(&z, g_z));
}

/* pft_pte_normalize / _real: nothing written on a refusal (pft_pte.h). */
static void test_pte_normalize_refusals(void)
{
    pft_pte_input_t in;
    pft_pte_input_default(&in);
    in.n_range = PNR;
    in.n_doppler = 1u;
    static pft_real_t zeta[PNR], scratch[PNR];
    static float f32[PNR];
    for (int u = 0; u < PNR; ++u) {
        f32[u] = 1.0f;
        zeta[u] = R(-7.0);
        scratch[u] = R(-5.0);
        g_z[u] = R(1.0);
    }
    pft_frame_t f;
    memset(&f, 0, sizeof f);
    f.data = f32;
    f.width = PNR;
    f.height = 1u;
    f.stride_bytes = 4u * PNR;
    f.format = PFT_PIX_F32;
    snap_begin();
    snap_add(zeta, sizeof zeta);
    snap_add(scratch, sizeof scratch);
    REFUSED(PFT_ERR_INVAL, pft_pte_normalize(NULL, &f, zeta, scratch));
    REFUSED(PFT_ERR_INVAL, pft_pte_normalize(&in, &f, NULL, scratch));
    REFUSED(PFT_ERR_INVAL, pft_pte_normalize(&in, NULL, zeta, scratch));
    f32[3] = NAN;
    REFUSED(PFT_ERR_FORMAT, pft_pte_normalize(&in, &f, zeta, scratch));
    f32[3] = 1.0f;
    f.width = PNR - 1u;
    REFUSED(PFT_ERR_FORMAT, pft_pte_normalize(&in, &f, zeta, scratch));
    f.width = PNR;
    pft_pte_input_t bad = in;
    bad.noise_sigma = PFT_C(0.0);
    REFUSED(PFT_ERR_CONFIG, pft_pte_normalize(&bad, &f, zeta, scratch));
    REFUSED(PFT_ERR_CONFIG, pft_pte_normalize_real(&bad, g_z, zeta));
    bad = in;
    bad.noise = PFT_PTE_NOISE_CFAR;
    REFUSED(PFT_ERR_INVAL, pft_pte_normalize(&bad, &f, zeta, NULL)); /* CFAR needs scratch */
    REFUSED(PFT_ERR_INVAL, pft_pte_normalize_real(&in, NULL, zeta));
    REFUSED(PFT_ERR_INVAL, pft_pte_normalize_real(&in, zeta, zeta)); /* in place */
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_pte_normalize(&in, &f, zeta, scratch));
    TEST_ASSERT_TRUE(memcmp(g_snap, zeta, sizeof zeta) != 0);
}

/* --------------------------------------- pre ---------------------------------------------- */
#define QW 40
#define QH 32
static uint16_t g_ir[QW * QH];

static pft_frame_t ir_frame(uint32_t k)
{
    uint32_t s = 12345u + 977u * k;
    for (int i = 0; i < QW * QH; ++i) {
        s = s * 1664525u + 1013904223u;
        g_ir[i] = (uint16_t)(4000u + (uint32_t)((i % QW) * 20) + (s >> 24));
    }
    pft_frame_t f;
    memset(&f, 0, sizeof f);
    f.data = g_ir;
    f.width = QW;
    f.height = QH;
    f.stride_bytes = 2u * QW;
    f.format = PFT_PIX_U16;
    f.bit_depth = 14u;
    f.seq = k;
    return f;
}

static void test_pre_init_and_results_refusals(void)
{
    static pft_pre_t p;
    pft_pre_config_t c;
    pft_pre_config_default(&c);
    c.width = QW;
    c.height = QH;
    c.tile = 16u;
    const size_t need = pft_pre_workspace_size(&c);
    TEST_ASSERT_TRUE(need > 0u && need <= sizeof g_work);
    /* before the first frame: no residual to lend */
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_pre_init(&p, &c, g_work, need));
    pft_frame_t out;
    memset(&out, 0x5A, sizeof out);
    snap_begin();
    snap_add(&p, sizeof p);
    snap_add(g_work, need);
    REFUSED(PFT_ERR_STATE, pft_pre_frame(&p, &out));
    for (uint32_t k = 1; k <= 3u; ++k) {
        pft_frame_t f = ir_frame(k);
        TEST_ASSERT_EQUAL_INT(PFT_OK, pft_pre_update(&p, &f));
    }
    static pft_pre_stats_t st;
    memset(&st, 0x5A, sizeof st);
    memset(&out, 0x5A, sizeof out);
    snap_begin();
    snap_add(&p, sizeof p);
    snap_add(g_work, need);
    snap_add(&st, sizeof st);
    snap_add(&out, sizeof out);
    pft_pre_config_t bad = c;
    bad.tile = 4u;
    REFUSED(PFT_ERR_CONFIG, pft_pre_init(&p, &bad, g_work, need));
    bad = c;
    bad.width = 0u;
    REFUSED(PFT_ERR_CONFIG, pft_pre_init(&p, &bad, g_work, need));
    REFUSED(PFT_ERR_NOMEM, pft_pre_init(&p, &c, g_work, SHORT(need)));
    REFUSED(PFT_ERR_INVAL, pft_pre_init(&p, NULL, g_work, need));
    REFUSED(PFT_ERR_INVAL, pft_pre_init(&p, &c, NULL, need));
    REFUSED(PFT_ERR_INVAL, pft_pre_reset(NULL));
    REFUSED(PFT_ERR_INVAL, pft_pre_frame(&p, NULL));
    REFUSED(PFT_ERR_INVAL, pft_pre_frame(NULL, &out));
    REFUSED(PFT_ERR_INVAL, pft_pre_stats(&p, NULL));
    REFUSED(PFT_ERR_INVAL, pft_pre_stats(NULL, &st));
    pft_frame_t f = ir_frame(4u);
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_pre_update(&p, &f));
    TEST_ASSERT_TRUE(memcmp(g_snap + sizeof p, g_work, need) != 0);
    /* never initialised (zeroed): reset, update and the results refused, nothing written */
    static pft_pre_t z;
    memset(&z, 0, sizeof z);
    memset(&out, 0x5A, sizeof out);
    snap_begin();
    snap_add(&z, sizeof z);
    snap_add(&out, sizeof out);
    REFUSED(PFT_ERR_INVAL, pft_pre_reset(&z));
    REFUSED(PFT_ERR_INVAL, pft_pre_update(&z, &f));
    REFUSED(PFT_ERR_STATE, pft_pre_frame(&z, &out)); /* no frame yet */
}

/* --------------------------------------- tsa ---------------------------------------------- */
#define AW 64
#define AH 40
#define ANP 40
static uint8_t g_rgb[AH][AW][3];

/* grey texture with a two-coloured 12 x 8 target whose top-left pixel is (x0, y0) */
static pft_frame_t rgb_frame(int x0, int y0)
{
    uint32_t s = 99u;
    for (int y = 0; y < AH; ++y) {
        for (int x = 0; x < AW; ++x) {
            s = s * 1664525u + 1013904223u;
            const uint8_t g = (uint8_t)(90u + (s >> 27) * 3u);
            g_rgb[y][x][0] = g;
            g_rgb[y][x][1] = g;
            g_rgb[y][x][2] = (uint8_t)(g - 10u);
        }
    }
    for (int y = y0; y < y0 + 8; ++y) {
        for (int x = x0; x < x0 + 12; ++x) {
            g_rgb[y][x][0] = x < x0 + 6 ? 200 : 230;
            g_rgb[y][x][1] = x < x0 + 6 ? 190 : 40;
            g_rgb[y][x][2] = 40;
        }
    }
    pft_frame_t f;
    memset(&f, 0, sizeof f);
    f.data = g_rgb;
    f.width = AW;
    f.height = AH;
    f.stride_bytes = 3u * AW;
    f.format = PFT_PIX_RGB888;
    return f;
}

static void tsa_cfg(pft_tsa_config_t *c)
{
    pft_tsa_config_default(c);
    c->width = AW;
    c->height = AH;
    c->max_target_w = 24u;
    c->max_target_h = 24u;
    c->n_particles = ANP;
    c->snake_points = 16u;
    c->seed = 4u;
    pft_tsa_snake_params_default(&c->snake, 24u, 24u);
}

static void test_tsa_results_before_start_and_reset_refusals(void)
{
    static pft_tsa_t t;
    pft_tsa_config_t c;
    tsa_cfg(&c);
    const size_t need = pft_tsa_workspace_size(&c);
    TEST_ASSERT_TRUE(need > 0u && need <= sizeof g_work);
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tsa_init(&t, &c, g_work, need));
    static pft_tsa_hist_t h;
    static pft_tsa_kpix_t kp[24 * 24];
    pft_tsa_kernel_t k;
    memset(&h, 0x5A, sizeof h);
    memset(kp, 0x5A, sizeof kp);
    memset(&k, 0, sizeof k);
    k.pix = kp;
    k.cap = 24u * 24u;
    /* IDLE: no template, no kernel yet */
    snap_begin();
    snap_add(&t, sizeof t);
    snap_add(g_work, need);
    snap_add(&h, sizeof h);
    snap_add(kp, sizeof kp);
    REFUSED(PFT_ERR_STATE, pft_tsa_template(&t, &h));
    REFUSED(PFT_ERR_STATE, pft_tsa_kernel(&t, &k));
    /* tracking: a kernel larger than the caller's capacity is refused, out untouched */
    pft_frame_t f = rgb_frame(20, 14);
    const pft_tsa_pt_t box[4] = {{19, 13}, {32, 13}, {32, 22}, {19, 22}};
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tsa_start(&t, &f, box, 4u));
    f = rgb_frame(21, 14);
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tsa_update(&t, &f));
    f = rgb_frame(22, 15);
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tsa_update(&t, &f));
    k.cap = 3u;
    pft_tsa_kernel_t kc = k;
    snap_begin();
    snap_add(&t, sizeof t);
    snap_add(g_work, need);
    snap_add(kp, sizeof kp);
    snap_add(&kc, sizeof kc);
    REFUSED(PFT_ERR_NOMEM, pft_tsa_kernel(&t, &kc));
    REFUSED(PFT_ERR_INVAL, pft_tsa_kernel(NULL, &kc));
    REFUSED(PFT_ERR_INVAL, pft_tsa_template(NULL, &h));
    REFUSED(PFT_ERR_INVAL, pft_tsa_reset(NULL));
    REFUSED(PFT_ERR_INVAL, pft_tsa_update(NULL, &f));
    REFUSED(PFT_ERR_INVAL, pft_tsa_start(NULL, &f, box, 4u));
    REFUSED(PFT_ERR_INVAL, pft_tsa_estimate(NULL, NULL));
    f = rgb_frame(23, 15);
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tsa_update(&t, &f));
    TEST_ASSERT_TRUE(memcmp(g_snap + sizeof t, g_work, need) != 0);
    /* never initialised (zeroed): reset and update refused, nothing written */
    static pft_tsa_t z;
    memset(&z, 0, sizeof z);
    snap_begin();
    snap_add(&z, sizeof z);
    REFUSED(PFT_ERR_INVAL, pft_tsa_reset(&z));
    REFUSED(PFT_ERR_INVAL, pft_tsa_update(&z, &f));
    REFUSED(PFT_ERR_INVAL, pft_tsa_start(&z, &f, box, 4u));
}

/* Building blocks: the documented outputs stay untouched on a refusal. */
static void test_tsa_building_block_refusals(void)
{
    pft_frame_t f = rgb_frame(20, 14);
    const pft_tsa_pt_t box[4] = {{19, 13}, {32, 13}, {32, 22}, {19, 22}};
    static pft_tsa_kpix_t kp[24 * 24];
    static int32_t cross[PFT_TSA_MAX_POINTS];
    pft_tsa_kernel_t k;
    memset(&k, 0, sizeof k);
    k.pix = kp;
    k.cap = 24u * 24u;
    pft_tsa_pt_t origin;
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tsa_kernel_build(&k, box, 4u, 16u, cross, &origin));
    static pft_tsa_hist_t h;
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tsa_hist(&f, &k, origin.x, origin.y, &h));
    /* histogram: NULL, a U16 or F32 frame */
    snap_begin();
    snap_add(&h, sizeof h);
    snap_add(&k, sizeof k);
    snap_add(kp, sizeof kp);
    pft_frame_t g = f;
    g.format = PFT_PIX_U16;
    REFUSED(PFT_ERR_FORMAT, pft_tsa_hist(&g, &k, origin.x, origin.y, &h));
    g.format = PFT_PIX_F32;
    g.stride_bytes = 4u * AW;
    REFUSED(PFT_ERR_FORMAT, pft_tsa_hist(&g, &k, origin.x, origin.y, &h));
    REFUSED(PFT_ERR_INVAL, pft_tsa_hist(NULL, &k, origin.x, origin.y, &h));
    REFUSED(PFT_ERR_INVAL, pft_tsa_hist(&f, NULL, origin.x, origin.y, &h));
    REFUSED(PFT_ERR_INVAL, pft_tsa_hist(&f, &k, origin.x, origin.y, NULL));
    /* kernel: k (and its pixels) and origin unchanged on every refusal */
    pft_tsa_pt_t org2 = {-3, -4};
    snap_begin();
    snap_add(&k, sizeof k);
    snap_add(kp, sizeof kp);
    snap_add(&org2, sizeof org2);
    const pft_tsa_pt_t line[3] = {{10, 10}, {20, 20}, {30, 30}};
    const pft_tsa_pt_t wide[4] = {{0, 0}, {300, 0}, {300, 10}, {0, 10}};
    REFUSED(PFT_ERR_INVAL, pft_tsa_kernel_build(&k, box, 2u, 16u, cross, &org2));
    REFUSED(PFT_ERR_INVAL, pft_tsa_kernel_build(&k, box, PFT_TSA_MAX_POINTS + 1u, 16u, cross, &org2));
    REFUSED(PFT_ERR_INVAL, pft_tsa_kernel_build(&k, NULL, 4u, 16u, cross, &org2));
    REFUSED(PFT_ERR_INVAL, pft_tsa_kernel_build(&k, box, 4u, 16u, NULL, &org2));
    REFUSED(PFT_ERR_INVAL, pft_tsa_kernel_build(&k, box, 4u, 16u, cross, NULL));
    REFUSED(PFT_ERR_DEGENERATE, pft_tsa_kernel_build(&k, line, 3u, 16u, cross, &org2));
    REFUSED(PFT_ERR_RANGE, pft_tsa_kernel_build(&k, wide, 4u, 16u, cross, &org2));
    pft_tsa_kernel_t small = k;
    small.cap = 5u;
    snap_add(&small, sizeof small);
    REFUSED(PFT_ERR_NOMEM, pft_tsa_kernel_build(&small, box, 4u, 16u, cross, &org2));
    /* polygon resampling: out untouched */
    static pft_tsa_pt_t pts[16];
    memset(pts, 0x5A, sizeof pts);
    snap_begin();
    snap_add(pts, sizeof pts);
    const pft_tsa_pt_t dot[3] = {{5, 5}, {5, 5}, {5, 5}};
    REFUSED(PFT_ERR_INVAL, pft_tsa_poly_resample(box, 2u, pts, 16u));
    REFUSED(PFT_ERR_INVAL, pft_tsa_poly_resample(NULL, 4u, pts, 16u));
    REFUSED(PFT_ERR_INVAL, pft_tsa_poly_resample(box, 4u, NULL, 16u));
    REFUSED(PFT_ERR_INVAL, pft_tsa_poly_resample(dot, 3u, pts, 16u)); /* zero perimeter */
    /* snake: the contour untouched when refused at the start */
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tsa_poly_resample(box, 4u, pts, 16u));
    pft_tsa_snake_params_t prm;
    pft_tsa_snake_params_default(&prm, 24u, 24u);
    static uint8_t flags[16];
    static uint8_t swork[PFT_TSA_SNAKE_WORK_BYTES(24u, 24u, 6u)];
    TEST_ASSERT_EQUAL_UINT((unsigned)sizeof swork,
                           (unsigned)pft_tsa_snake_work_size(24u, 24u, prm.margin));
    uint32_t done = 77u; /* a refusal reports 0 passes run (not part of the snapshot) */
    snap_begin();
    snap_add(pts, sizeof pts);
    REFUSED(PFT_ERR_INVAL, pft_tsa_snake(NULL, pts, 16u, &prm, 5u, flags, swork, sizeof swork, &done));
    REFUSED(PFT_ERR_INVAL, pft_tsa_snake(&f, NULL, 16u, &prm, 5u, flags, swork, sizeof swork, &done));
    REFUSED(PFT_ERR_INVAL, pft_tsa_snake(&f, pts, PFT_TSA_MIN_POINTS - 1u, &prm, 5u, flags, swork,
                                         sizeof swork, &done));
    REFUSED(PFT_ERR_INVAL, pft_tsa_snake(&f, pts, 16u, NULL, 5u, flags, swork, sizeof swork, &done));
    REFUSED(PFT_ERR_INVAL, pft_tsa_snake(&f, pts, 16u, &prm, 5u, NULL, swork, sizeof swork, &done));
    REFUSED(PFT_ERR_INVAL, pft_tsa_snake(&f, pts, 16u, &prm, 5u, flags, NULL, sizeof swork, &done));
    pft_tsa_snake_params_t pb = prm;
    pb.margin = 2u;
    REFUSED(PFT_ERR_INVAL, pft_tsa_snake(&f, pts, 16u, &pb, 5u, flags, swork, sizeof swork, &done));
    REFUSED(PFT_ERR_NOMEM, pft_tsa_snake(&f, pts, 16u, &prm, 5u, flags, swork, sizeof swork - 1u,
                                         &done));
    pb = prm;
    pb.max_w = 8u; /* the contour box (14 x 10) is larger than the work's layout */
    REFUSED(PFT_ERR_NOMEM, pft_tsa_snake(&f, pts, 16u, &pb, 5u, flags, swork, sizeof swork, &done));
    g = f;
    g.format = PFT_PIX_F32;
    g.stride_bytes = 4u * AW;
    REFUSED(PFT_ERR_FORMAT, pft_tsa_snake(&g, pts, 16u, &prm, 5u, flags, swork, sizeof swork, &done));
    TEST_ASSERT_EQUAL_UINT32(0u, done);
    /* motion: coefficients c untouched outside beta in [0, 64], q in [0, 10000] */
    pft_tsa_motion_free_t mc;
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tsa_motion_free_coef(&mc, R(2.0), R(1.0)));
    snap_begin();
    snap_add(&mc, sizeof mc);
    REFUSED(PFT_ERR_INVAL, pft_tsa_motion_free_coef(&mc, R(-0.5), R(1.0)));
    REFUSED(PFT_ERR_INVAL, pft_tsa_motion_free_coef(&mc, R(64.5), R(1.0)));
    REFUSED(PFT_ERR_INVAL, pft_tsa_motion_free_coef(&mc, R(2.0), R(-1.0)));
    REFUSED(PFT_ERR_INVAL, pft_tsa_motion_free_coef(&mc, R(2.0), R(10001.0)));
    REFUSED(PFT_ERR_INVAL, pft_tsa_motion_free_coef(NULL, R(2.0), R(1.0)));
    /* motion fit: out untouched */
    const pft_real_t o[4] = {R(1.0), R(2.0), R(3.5), R(5.0)};
    const pft_real_t zw[4] = {PFT_C(0.0), PFT_C(0.0), PFT_C(0.0), PFT_C(0.0)};
    pft_tsa_motion_fit_t fit;
    memset(&fit, 0x5A, sizeof fit);
    snap_begin();
    snap_add(&fit, sizeof fit);
    REFUSED(PFT_ERR_INVAL, pft_tsa_motion_fit(NULL, NULL, 4u, R(2.0), 2u, &fit));
    REFUSED(PFT_ERR_INVAL, pft_tsa_motion_fit(o, NULL, 0u, R(2.0), 2u, &fit));
    REFUSED(PFT_ERR_INVAL, pft_tsa_motion_fit(o, NULL, PFT_TSA_MOTION_MAX_K + 1u, R(2.0), 2u, &fit));
    REFUSED(PFT_ERR_INVAL, pft_tsa_motion_fit(o, NULL, 4u, PFT_C(0.0), 2u, &fit));
    REFUSED(PFT_ERR_INVAL, pft_tsa_motion_fit(o, NULL, 4u, R(2.0), 3u, &fit));
    REFUSED(PFT_ERR_INVAL, pft_tsa_motion_fit(o, zw, 4u, R(2.0), 2u, &fit));
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tsa_motion_fit(o, NULL, 4u, R(2.0), 2u, &fit));
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_resample_refusals_leave_idx_and_rng);
    RUN_TEST(test_pf_engine_refusals);
    RUN_TEST(test_pf_init_short_workspace_zeroes_instance_only);
    RUN_TEST(test_pf_model_init_refusals);
    RUN_TEST(test_tbd_manager_init_and_results_refusals);
    RUN_TEST(test_tbd_filter_init_and_results_refusals);
    RUN_TEST(test_tbd_meas_init_refusals);
    RUN_TEST(test_pte_refusals);
    RUN_TEST(test_pte_dp_dbt_init_and_threshold_refusals);
    RUN_TEST(test_pte_normalize_refusals);
    RUN_TEST(test_pre_init_and_results_refusals);
    RUN_TEST(test_tsa_results_before_start_and_reset_refusals);
    RUN_TEST(test_tsa_building_block_refusals);
    return UNITY_END();
}
