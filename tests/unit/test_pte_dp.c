/*
 * DP-TBD (pft_pte.h): the merit recursion and backtracking recover a target's path cell for
 * cell; the velocity gate is enforced (a target jumping further than the gate is not summed,
 * one moving at the gate is); the known-amplitude merit; multi-target extraction with
 * cancellation and stable ids in sliding mode; the noise-only Monte Carlo threshold holds
 * its false-alarm rate on fresh noise; range-Doppler paths; workspace formula; refused input
 * leaves every byte unchanged.
 *
 * Profiles are 64 cells, batches 8-10 frames, so the file runs in seconds under QEMU.
 */
#include <math.h>
#include <string.h>

#include "pft_test_support.h"
#include "pft/pft_pte.h"

void setUp(void) {}
void tearDown(void) {}

#define NR 64
#define ND 12

static pft_real_t R(double v) { return pft_test_from_double(v); }
static double D(pft_real_t v) { return pft_test_to_double(v); }

/* pft_pte_dp_config_default for n_range x n_doppler frames */
static void dp_config(pft_pte_dp_config_t *c, int n_range, int n_doppler)
{
    pft_pte_dp_config_default(c);
    c->in.n_range = (uint16_t)n_range;
    c->in.n_doppler = (uint16_t)n_doppler;
}

static uint64_t g_work[PFT_PTE_DP_WORKSPACE_BYTES(NR, ND, 16, 4) / 8 + 8];
static uint64_t g_copy[sizeof(g_work) / 8];
static pft_pte_report_t g_rep[PFT_PTE_MAX_TRACKS];
static int16_t g_path[2 * PFT_PTE_MAX_FRAMES];
static pft_real_t g_z[NR * ND];

/* deterministic N(0,1) */
static uint64_t g_s;
static double gauss(void) { return pft_test_gauss(&g_s); }

/* profile with noise sigma and targets of amplitude a at cell positions pos[] (psf 0.6) */
static void profile(double sigma, int n, const double *pos, const double *amp)
{
    for (int u = 0; u < NR; ++u) {
        double v = sigma * gauss();
        for (int t = 0; t < n; ++t) {
            double d = u - pos[t];
            v += amp[t] * exp(-d * d / (2 * 0.36));
        }
        g_z[u] = R(v);
    }
}

static pft_real_t peak_of(const pft_pte_dp_t *dp)
{
    pft_real_t v = PFT_C(0.0);
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_pte_dp_peak(dp, &v));
    return v;
}

static void init_dp(pft_pte_dp_t *dp, pft_pte_dp_config_t *c)
{
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_pte_dp_config_check(c, NULL));
    size_t need = pft_pte_dp_workspace_size(c);
    TEST_ASSERT_TRUE(need <= sizeof(g_work));
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_pte_dp_init(dp, c, g_work, need));
}

static void test_workspace_formula(void)
{
    pft_pte_dp_config_t c;
    dp_config(&c, NR, 1);
    TEST_ASSERT_EQUAL_UINT32(PFT_PTE_DP_WORKSPACE_BYTES(NR, 1, 10, 4), pft_pte_dp_workspace_size(&c));
    c.frames = 16;
    c.in.n_doppler = ND;
    TEST_ASSERT_EQUAL_UINT32(PFT_PTE_DP_WORKSPACE_BYTES(NR, ND, 16, 4), pft_pte_dp_workspace_size(&c));
    size_t need = pft_pte_dp_workspace_size(&c);
    pft_pte_dp_t dp;
    /* exact fit at an unaligned start works, one byte less does not; nothing outside is touched */
    uint8_t *buf = (uint8_t *)g_work;
    pft_test_guard_fill(buf, sizeof(g_work));
    TEST_ASSERT_EQUAL_INT(PFT_ERR_NOMEM, pft_pte_dp_init(&dp, &c, buf + 1, need - 1));
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_pte_dp_init(&dp, &c, buf + 1, need));
    TEST_ASSERT_TRUE(pft_test_guard_intact(buf, sizeof(g_work), 1, 1 + need));
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_pte_dp_reset(&dp));
    /* refused configurations: PFT_ERR_CONFIG naming the field, workspace size 0 */
    const char *field = "x";
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_pte_dp_config_check(&c, &field));
    TEST_ASSERT_NULL(field);
    c.frames = 1;
    TEST_ASSERT_EQUAL_INT(PFT_ERR_CONFIG, pft_pte_dp_init(&dp, &c, g_work, sizeof(g_work)));
    TEST_ASSERT_EQUAL_UINT32(0, pft_pte_dp_workspace_size(&c));
    TEST_ASSERT_EQUAL_INT(PFT_ERR_CONFIG, pft_pte_dp_config_check(&c, &field));
    TEST_ASSERT_EQUAL_STRING("frames", field);
    c.frames = 10;
    c.gate[0] = PFT_PTE_MAX_GATE + 1u;
    TEST_ASSERT_EQUAL_INT(PFT_ERR_CONFIG, pft_pte_dp_config_check(&c, &field));
    TEST_ASSERT_EQUAL_STRING("gate[0]", field);
    c.gate[0] = 1;
    c.in.noise_sigma = R(0.0);
    TEST_ASSERT_EQUAL_INT(PFT_ERR_CONFIG, pft_pte_dp_config_check(&c, &field));
    TEST_ASSERT_EQUAL_STRING("in.noise_sigma", field);
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_pte_dp_config_check(NULL, &field));
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_pte_dp_init(&dp, NULL, g_work, sizeof(g_work)));
    TEST_ASSERT_EQUAL_UINT32(0, pft_pte_dp_workspace_size(NULL));
}

/* A target moving one cell every other frame at 9.5 dB: the backtracked path is the truth. */
static void test_path_recovered(void)
{
    pft_pte_dp_config_t c;
    dp_config(&c, NR, 1);
    c.threshold = R(18.0); /* about the 1e-3 noise-only threshold of K = 10, 64 cells */
    pft_pte_dp_t dp;
    init_dp(&dp, &c);
    g_s = 12345;
    for (int k = 0; k < 10; ++k) {
        double pos = 20.0 + k / 2;
        double a = 3.0;
        profile(1.0, 1, &pos, &a);
        TEST_ASSERT_EQUAL_INT(PFT_OK, pft_pte_dp_update_real(&dp, g_z));
        TEST_ASSERT_EQUAL_UINT32(k < 9 ? 0u : 1u, pft_pte_dp_reports(&dp, NULL, 0));
    }
    TEST_ASSERT_EQUAL_UINT32(20, pft_pte_dp_path(&dp, 0, g_path, 2 * PFT_PTE_MAX_FRAMES));
    const int16_t *path = g_path;
    for (int k = 0; k < 10; ++k) {
        TEST_ASSERT_EQUAL_INT(20 + k / 2, path[2 * k]);
        TEST_ASSERT_EQUAL_INT(0, path[2 * k + 1]);
    }
    const pft_pte_report_t *r = g_rep;
    TEST_ASSERT_EQUAL_UINT32(1, pft_pte_dp_reports(&dp, g_rep, PFT_PTE_MAX_TRACKS));
    TEST_ASSERT_DOUBLE_WITHIN(0.3, 24.0, D(r[0].pos[0]));
    TEST_ASSERT_DOUBLE_WITHIN(0.15, 0.5, D(r[0].vel[0]));
    TEST_ASSERT_TRUE(r[0].detected);
    TEST_ASSERT_TRUE(D(r[0].score) > 18.0);
    TEST_ASSERT_EQUAL_UINT32(0, pft_pte_dp_path(&dp, 1, g_path, 2 * PFT_PTE_MAX_FRAMES));
    /* copy-out: at most max values, the length returned either way */
    memset(g_path, 0x7F, sizeof(g_path));
    TEST_ASSERT_EQUAL_UINT32(20, pft_pte_dp_path(&dp, 0, g_path, 3));
    TEST_ASSERT_EQUAL_INT(20, g_path[2]); /* frame 1, range */
    TEST_ASSERT_EQUAL_INT(0x7F7F, g_path[3]);
}

/* Noise-free frames with a single spike: merit = sum of the spikes the gate lets the path
 * collect. A spike jumping 5 cells per frame is not followed with gate 1 (but is with gate 5);
 * a spike moving exactly one cell per frame is followed with gate 1, not with gate 0. */
static double spike_merit(int gate, int step)
{
    pft_pte_dp_config_t c;
    dp_config(&c, NR, 1);
    c.frames = 8;
    c.gate[0] = (uint8_t)gate;
    c.threshold = R(1000.0);
    pft_pte_dp_t dp;
    init_dp(&dp, &c);
    for (int k = 0; k < 8; ++k) {
        memset(g_z, 0, sizeof(g_z));
        int u = 10 + step * k;
        g_z[u] = R(3.0);
        TEST_ASSERT_EQUAL_INT(PFT_OK, pft_pte_dp_update_real(&dp, g_z));
    }
    return D(peak_of(&dp));
}

static void test_velocity_gate(void)
{
    TEST_ASSERT_DOUBLE_WITHIN(1e-3, 24.0, spike_merit(1, 1)); /* follows: 8 x 3 */
    TEST_ASSERT_DOUBLE_WITHIN(1e-3, 3.0, spike_merit(0, 1));  /* cannot move */
    TEST_ASSERT_DOUBLE_WITHIN(1e-3, 3.0, spike_merit(1, 5));  /* jumps beyond the gate */
    TEST_ASSERT_DOUBLE_WITHIN(1e-3, 24.0, spike_merit(5, 5)); /* a gate of 5 follows them */
    TEST_ASSERT_DOUBLE_WITHIN(1e-3, 3.0, spike_merit(2, 3));  /* 3 cells per frame, gate 2: never chains */
    TEST_ASSERT_DOUBLE_WITHIN(1e-3, 24.0, spike_merit(3, 2));
}

/* Known-amplitude merit: l = a zeta - a^2/2, so a constant profile zeta = 1 with a = 2 gives
 * 8 * (2 - 2) = 0 and zeta = 2 gives 8 * 2 = 16. */
static void test_known_amplitude(void)
{
    pft_pte_dp_config_t c;
    dp_config(&c, NR, 1);
    c.frames = 8;
    c.amplitude = R(2.0);
    c.threshold = R(1000.0);
    pft_pte_dp_t dp;
    init_dp(&dp, &c);
    for (int k = 0; k < 8; ++k) {
        for (int u = 0; u < NR; ++u) {
            g_z[u] = R(u == 30 ? 2.0 : 1.0);
        }
        TEST_ASSERT_EQUAL_INT(PFT_OK, pft_pte_dp_update_real(&dp, g_z));
    }
    TEST_ASSERT_DOUBLE_WITHIN(1e-3, 16.0, D(peak_of(&dp)));
}

/* Two targets 25 cells apart, 10 dB, sliding over 30 frames: two reports every frame once the
 * batch is full, each with a stable id, positions within a cell. */
static void test_two_targets_ids(void)
{
    pft_pte_dp_config_t c;
    dp_config(&c, NR, 1);
    c.threshold = R(18.0);
    pft_pte_dp_t dp;
    init_dp(&dp, &c);
    g_s = 777;
    uint16_t id_a = 0, id_b = 0;
    for (int k = 0; k < 30; ++k) {
        double pos[2] = {15.0 + 0.2 * k, 45.0 - 0.1 * k};
        double amp[2] = {3.2, 3.2};
        profile(1.0, 2, pos, amp);
        TEST_ASSERT_EQUAL_INT(PFT_OK, pft_pte_dp_update_real(&dp, g_z));
        const pft_pte_report_t *r = g_rep;
        uint32_t n = (uint32_t)pft_pte_dp_reports(&dp, g_rep, PFT_PTE_MAX_TRACKS);
        if (k < 9) {
            TEST_ASSERT_EQUAL_UINT32(0, n);
            continue;
        }
        TEST_ASSERT_EQUAL_UINT32(2, n);
        for (uint32_t i = 0; i < 2; ++i) {
            double p = D(r[i].pos[0]);
            int which = p < 30.0 ? 0 : 1;
            TEST_ASSERT_DOUBLE_WITHIN(1.5, pos[which], p);
            uint16_t *id = which == 0 ? &id_a : &id_b;
            if (*id == 0) {
                *id = r[i].id;
            }
            TEST_ASSERT_EQUAL_UINT16(*id, r[i].id);
        }
    }
    TEST_ASSERT_TRUE(id_a != id_b);
}

/* The Monte Carlo threshold for pfa = 0.1 is exceeded by about 10% of fresh noise batches
 * (binomial 300 batches: 0.1 +- 0.06). */
static void test_threshold_false_alarm_rate(void)
{
    pft_pte_dp_config_t c;
    dp_config(&c, 32, 1);
    c.frames = 8;
    pft_pte_dp_t dp;
    init_dp(&dp, &c);
    pft_real_t vt;
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_pte_dp_threshold(&dp, R(0.5), 1000, 1, &vt)); /* k > 64 */
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_pte_dp_threshold(&dp, R(0.0), 100, 1, &vt));
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_pte_dp_threshold(&dp, R(0.1), 600, 99, &vt));
    double v = D(vt);
    UnityPrint(" V_T=");
    UnityPrintFloat(v);
    /* K = 8 frames of N(0,1), gate 1, 32 cells: well above the 8 x 1.6 of a free path
     * through noise maxima, well below 8 x 3 */
    TEST_ASSERT_TRUE(v > 9.0 && v < 20.0);
    c.threshold = vt;
    init_dp(&dp, &c);
    int over = 0;
    g_s = 4242;
    for (int b = 0; b < 300; ++b) {
        pft_pte_dp_reset(&dp);
        for (int k = 0; k < 8; ++k) {
            for (int u = 0; u < 32; ++u) {
                g_z[u] = R(gauss());
            }
            TEST_ASSERT_EQUAL_INT(PFT_OK, pft_pte_dp_update_real(&dp, g_z));
        }
        over += pft_pte_dp_reports(&dp, NULL, 0) > 0 ? 1 : 0;
    }
    UnityPrint(" false_alarm_rate=");
    UnityPrintFloat(over / 300.0);
    TEST_ASSERT_INT_WITHIN(18, 30, over);
}

/* Range-Doppler: a target moving (+1 range, -1 Doppler) every other frame is recovered in
 * both axes. */
static void test_range_doppler_path(void)
{
    pft_pte_dp_config_t c;
    dp_config(&c, NR, ND);
    c.frames = 8;
    c.threshold = R(26.0); /* 3 x 3 gate over 768 cells: noise paths reach about 20 */
    pft_pte_dp_t dp;
    init_dp(&dp, &c);
    g_s = 31337;
    for (int k = 0; k < 8; ++k) {
        int r0 = 30 + k / 2, d0 = 8 - k / 2;
        for (int d = 0; d < ND; ++d) {
            for (int u = 0; u < NR; ++u) {
                double dr = u - r0, dd = d - d0;
                g_z[d * NR + u] = R(gauss() + 4.5 * exp(-(dr * dr + dd * dd) / 0.72));
            }
        }
        TEST_ASSERT_EQUAL_INT(PFT_OK, pft_pte_dp_update_real(&dp, g_z));
    }
    const pft_pte_report_t *r = g_rep;
    TEST_ASSERT_EQUAL_UINT32(1, pft_pte_dp_reports(&dp, g_rep, PFT_PTE_MAX_TRACKS));
    TEST_ASSERT_EQUAL_UINT32(16, pft_pte_dp_path(&dp, 0, g_path, 2 * PFT_PTE_MAX_FRAMES));
    const int16_t *path = g_path;
    for (int k = 0; k < 8; ++k) {
        TEST_ASSERT_EQUAL_INT(30 + k / 2, path[2 * k]);
        TEST_ASSERT_EQUAL_INT(8 - k / 2, path[2 * k + 1]);
    }
    TEST_ASSERT_DOUBLE_WITHIN(0.5, 33.0, D(r[0].pos[0]));
    TEST_ASSERT_DOUBLE_WITHIN(0.5, 5.0, D(r[0].pos[1]));
}

/* Refused frames (NULL, wrong size, NaN) change no byte of the instance or its workspace. */
static void test_bad_input_untouched(void)
{
    pft_pte_dp_config_t c;
    dp_config(&c, NR, 1);
    pft_pte_dp_t dp;
    init_dp(&dp, &c);
    g_s = 5;
    for (int k = 0; k < 12; ++k) {
        double pos = 30.0, a = 3.0;
        profile(1.0, 1, &pos, &a);
        TEST_ASSERT_EQUAL_INT(PFT_OK, pft_pte_dp_update_real(&dp, g_z));
    }
    pft_pte_dp_t copy = dp;
    memcpy(g_copy, g_work, sizeof(g_work));
    static float f32[NR + 1];
    pft_frame_t f = {0};
    f.data = f32;
    f.width = NR + 1;
    f.height = 1;
    f.stride_bytes = (NR + 1) * 4;
    f.format = PFT_PIX_F32;
    TEST_ASSERT_EQUAL_INT(PFT_ERR_FORMAT, pft_pte_dp_update(&dp, &f));
    f.width = NR;
    f32[5] = NAN;
    TEST_ASSERT_EQUAL_INT(PFT_ERR_FORMAT, pft_pte_dp_update(&dp, &f));
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_pte_dp_update(&dp, NULL));
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_pte_dp_update_real(&dp, NULL));
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_pte_dp_update(NULL, &f));
    pft_real_t pk;
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_pte_dp_peak(&dp, NULL));
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_pte_dp_peak(NULL, &pk));
    TEST_ASSERT_EQUAL_MEMORY(&copy, &dp, sizeof(dp));
    TEST_ASSERT_EQUAL_MEMORY(g_copy, g_work, sizeof(g_work));
    f32[5] = 0.0f;
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_pte_dp_update(&dp, &f));
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_workspace_formula);
    RUN_TEST(test_path_recovered);
    RUN_TEST(test_velocity_gate);
    RUN_TEST(test_known_amplitude);
    RUN_TEST(test_two_targets_ids);
    RUN_TEST(test_threshold_false_alarm_rate);
    RUN_TEST(test_range_doppler_path);
    RUN_TEST(test_bad_input_untouched);
    return UNITY_END();
}
