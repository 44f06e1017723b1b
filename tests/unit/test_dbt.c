/*
 * Kalman detect-before-track baseline (pft_dbt.h): plots (run centroids, range-Doppler local
 * maxima), 2-of-3 confirmation, deletion after 3 misses, the chi-square gate, tracking
 * accuracy of a clean target, false tracks from noise plots, workspace formula, refused input
 * leaves every byte unchanged.
 */
#include <math.h>
#include <string.h>

#include "pft_test_support.h"
#include "pft/pft_dbt.h"

void setUp(void) {}
void tearDown(void) {}

#define NR 64

static pft_real_t R(double v) { return pft_test_from_double(v); }
static double D(pft_real_t v) { return pft_test_to_double(v); }

static uint64_t g_work[PFT_DBT_WORKSPACE_BYTES(NR, 8, 32, 64) / 8 + 8];
static uint64_t g_copy[sizeof(g_work) / 8];
static pft_real_t g_z[NR * 8];

static uint64_t g_s;
static double gauss(void) { return pft_test_gauss(&g_s); }

static void init_dbt(pft_dbt_t *b, const pft_dbt_config_t *c)
{
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_dbt_config_check(c));
    size_t need = pft_dbt_workspace_size(c);
    TEST_ASSERT_TRUE(need > 0u && need <= sizeof(g_work));
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_dbt_init(b, c, g_work, need));
}

/* noise-free profile with spikes: value v at cell u */
static void spikes(int n, const int *u, const double *v)
{
    memset(g_z, 0, sizeof(g_z));
    for (int i = 0; i < n; ++i) {
        g_z[u[i]] = R(v[i]);
    }
}

static void test_workspace_and_config(void)
{
    pft_dbt_config_t c;
    pft_dbt_config_default(&c, NR, 1);
    TEST_ASSERT_DOUBLE_WITHIN(1e-4, 6.63, D(c.gate));
    TEST_ASSERT_EQUAL_UINT32(PFT_DBT_WORKSPACE_BYTES(NR, 1, 32, 64), pft_dbt_workspace_size(&c));
    pft_dbt_config_default(&c, NR, 8);
    TEST_ASSERT_DOUBLE_WITHIN(1e-4, 9.21, D(c.gate));
    TEST_ASSERT_EQUAL_UINT32(PFT_DBT_WORKSPACE_BYTES(NR, 8, 32, 64), pft_dbt_workspace_size(&c));
    pft_dbt_t b;
    size_t need = pft_dbt_workspace_size(&c);
    TEST_ASSERT_EQUAL_INT(PFT_ERR_NOMEM, pft_dbt_init(&b, &c, g_work, need - 8u));
    c.confirm_m = 4; /* more hits than frames */
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_dbt_config_check(&c));
}

/* Runs of cells above the threshold give one plot each at the zeta-weighted centroid. */
static void test_plots(void)
{
    pft_dbt_config_t c;
    pft_dbt_config_default(&c, NR, 1);
    pft_dbt_t b;
    init_dbt(&b, &c);
    int u[5] = {10, 11, 12, 20, 21};
    double v[5] = {3.0, 5.0, 3.0, 4.0, 2.5};
    spikes(5, u, v);
    g_z[30] = R(2.0); /* below the 2.326 threshold */
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_dbt_update_real(&b, g_z));
    const pft_dbt_plot_t *pl;
    TEST_ASSERT_EQUAL_UINT32(2, pft_dbt_plots(&b, &pl));
    TEST_ASSERT_DOUBLE_WITHIN(1e-3, 11.0, D(pl[0].pos[0]));
    TEST_ASSERT_DOUBLE_WITHIN(1e-3, 5.0, D(pl[0].peak));
    TEST_ASSERT_DOUBLE_WITHIN(1e-3, (20 * 4.0 + 21 * 2.5) / 6.5, D(pl[1].pos[0]));
    /* no track is confirmed from one frame */
    TEST_ASSERT_EQUAL_UINT32(0, pft_dbt_reports(&b, NULL));
}

/* Range-Doppler: one plot per local maximum, centroid over its 3x3 block. */
static void test_plots_2d(void)
{
    pft_dbt_config_t c;
    pft_dbt_config_default(&c, NR, 8);
    pft_dbt_t b;
    init_dbt(&b, &c);
    memset(g_z, 0, sizeof(g_z));
    g_z[3 * NR + 10] = R(6.0);
    g_z[3 * NR + 11] = R(3.0);
    g_z[4 * NR + 10] = R(3.0);
    g_z[6 * NR + 40] = R(4.0);
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_dbt_update_real(&b, g_z));
    const pft_dbt_plot_t *pl;
    TEST_ASSERT_EQUAL_UINT32(2, pft_dbt_plots(&b, &pl));
    TEST_ASSERT_DOUBLE_WITHIN(1e-3, 10.25, D(pl[0].pos[0]));
    TEST_ASSERT_DOUBLE_WITHIN(1e-3, 3.25, D(pl[0].pos[1]));
    TEST_ASSERT_DOUBLE_WITHIN(1e-3, 40.0, D(pl[1].pos[0]));
    TEST_ASSERT_DOUBLE_WITHIN(1e-3, 6.0, D(pl[1].pos[1]));
}

/* hit, miss, hit: confirmed at the third frame; then three misses delete it. A single blip
 * is never confirmed. */
static void test_confirm_and_delete(void)
{
    pft_dbt_config_t c;
    pft_dbt_config_default(&c, NR, 1);
    pft_dbt_t b;
    init_dbt(&b, &c);
    int u = 30;
    double v = 5.0;
    const pft_mftbd_report_t *r;
    spikes(1, &u, &v);
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_dbt_update_real(&b, g_z));
    TEST_ASSERT_EQUAL_UINT32(0, pft_dbt_reports(&b, NULL));
    spikes(0, NULL, NULL);
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_dbt_update_real(&b, g_z));
    TEST_ASSERT_EQUAL_UINT32(0, pft_dbt_reports(&b, NULL));
    spikes(1, &u, &v);
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_dbt_update_real(&b, g_z));
    TEST_ASSERT_EQUAL_UINT32(1, pft_dbt_reports(&b, &r));
    TEST_ASSERT_EQUAL_UINT16(1, r[0].id);
    TEST_ASSERT_TRUE(r[0].detected);
    TEST_ASSERT_DOUBLE_WITHIN(0.05, 30.0, D(r[0].pos[0]));
    spikes(0, NULL, NULL);
    for (int k = 0; k < 2; ++k) {
        TEST_ASSERT_EQUAL_INT(PFT_OK, pft_dbt_update_real(&b, g_z));
        TEST_ASSERT_EQUAL_UINT32(1, pft_dbt_reports(&b, &r));
        TEST_ASSERT_FALSE(r[0].detected);
    }
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_dbt_update_real(&b, g_z));
    TEST_ASSERT_EQUAL_UINT32(0, pft_dbt_reports(&b, NULL));
    /* a single blip followed by two empty frames: never confirmed */
    pft_dbt_reset(&b);
    u = 50;
    spikes(1, &u, &v);
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_dbt_update_real(&b, g_z));
    spikes(0, NULL, NULL);
    for (int k = 0; k < 4; ++k) {
        TEST_ASSERT_EQUAL_INT(PFT_OK, pft_dbt_update_real(&b, g_z));
        TEST_ASSERT_EQUAL_UINT32(0, pft_dbt_reports(&b, NULL));
    }
    /* the blip's tentative track was deleted: a new blip at the same place needs 2 hits again */
    u = 50;
    spikes(1, &u, &v);
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_dbt_update_real(&b, g_z));
    TEST_ASSERT_EQUAL_UINT32(0, pft_dbt_reports(&b, NULL));
}

/* A confirmed track at 30 (velocity ~0, P_rr + R ~ 0.3): a plot 6 cells away is outside the
 * chi-square gate (36 / 0.3 >> 6.63) and does not move the track; one 0.5 cell away does. */
static void test_gate(void)
{
    pft_dbt_config_t c;
    pft_dbt_config_default(&c, NR, 1);
    pft_dbt_t b;
    init_dbt(&b, &c);
    int u = 30;
    double v = 5.0;
    const pft_mftbd_report_t *r;
    for (int k = 0; k < 4; ++k) {
        spikes(1, &u, &v);
        TEST_ASSERT_EQUAL_INT(PFT_OK, pft_dbt_update_real(&b, g_z));
    }
    TEST_ASSERT_EQUAL_UINT32(1, pft_dbt_reports(&b, &r));
    double before = D(r[0].pos[0]);
    u = 36;
    spikes(1, &u, &v);
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_dbt_update_real(&b, g_z));
    TEST_ASSERT_EQUAL_UINT32(1, pft_dbt_reports(&b, &r));
    TEST_ASSERT_FALSE(r[0].detected);
    TEST_ASSERT_DOUBLE_WITHIN(0.05, before, D(r[0].pos[0]));
    /* the far plot started a tentative track: two tracks after its second hit */
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_dbt_update_real(&b, g_z));
    TEST_ASSERT_EQUAL_UINT32(2, pft_dbt_reports(&b, NULL));
}

/* Clean-ish target at 13 dB (A = 4.5 sigma) moving 0.2 cells/frame: one confirmed track with
 * a stable id, RMS error < 0.25 cells, velocity within 0.05. Noise plots (P_fa 1e-2 on 64
 * cells) make short false tracks: they stay below 15% of the declared points. */
static void test_tracking(void)
{
    pft_dbt_config_t c;
    pft_dbt_config_default(&c, NR, 1);
    pft_dbt_t b;
    init_dbt(&b, &c);
    g_s = 424242;
    double se = 0.0;
    int n = 0, declared = 0, wrong = 0;
    uint16_t id = 0;
    const pft_mftbd_report_t *r = NULL;
    double vel = 0.0;
    for (int k = 0; k < 150; ++k) {
        double pos = 15.0 + 0.2 * k;
        for (int u = 0; u < NR; ++u) {
            double d = u - pos;
            g_z[u] = R(gauss() + 4.5 * exp(-d * d / 0.72));
        }
        TEST_ASSERT_EQUAL_INT(PFT_OK, pft_dbt_update_real(&b, g_z));
        uint32_t m = pft_dbt_reports(&b, &r);
        for (uint32_t i = 0; i < m; ++i) {
            if (!r[i].detected) {
                continue;
            }
            declared++;
            double e = D(r[i].pos[0]) - pos;
            if (fabs(e) < 3.0) {
                if (id == 0) {
                    id = r[i].id;
                }
                TEST_ASSERT_EQUAL_UINT16(id, r[i].id);
                se += e * e;
                n++;
                vel = D(r[i].vel[0]);
            } else {
                wrong++;
            }
        }
    }
    double rms = sqrt(se / n);
    UnityPrint(" rms=");
    UnityPrintFloat(rms);
    UnityPrint(" correct=");
    UnityPrintFloat(n);
    UnityPrint(" false_fraction=");
    UnityPrintFloat((double)wrong / declared);
    TEST_ASSERT_TRUE(n > 135);
    TEST_ASSERT_TRUE(rms < 0.25);
    TEST_ASSERT_DOUBLE_WITHIN(0.05, 0.2, vel);
    TEST_ASSERT_TRUE((double)wrong / declared < 0.15);
}

static void test_bad_input_untouched(void)
{
    pft_dbt_config_t c;
    pft_dbt_config_default(&c, NR, 1);
    pft_dbt_t b;
    init_dbt(&b, &c);
    int u = 30;
    double v = 5.0;
    for (int k = 0; k < 3; ++k) {
        spikes(1, &u, &v);
        TEST_ASSERT_EQUAL_INT(PFT_OK, pft_dbt_update_real(&b, g_z));
    }
    pft_dbt_t copy = b;
    memcpy(g_copy, g_work, sizeof(g_work));
    static float f32[NR];
    pft_frame_t f = {0};
    f.data = f32;
    f.width = NR - 1;
    f.height = 1;
    f.stride_bytes = NR * 4;
    f.format = PFT_PIX_F32;
    TEST_ASSERT_EQUAL_INT(PFT_ERR_FORMAT, pft_dbt_update(&b, &f));
    f.width = NR;
    f32[0] = -INFINITY;
    TEST_ASSERT_EQUAL_INT(PFT_ERR_FORMAT, pft_dbt_update(&b, &f));
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_dbt_update(&b, NULL));
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_dbt_update_real(NULL, g_z));
    TEST_ASSERT_EQUAL_MEMORY(&copy, &b, sizeof(b));
    TEST_ASSERT_EQUAL_MEMORY(g_copy, g_work, sizeof(g_work));
    f32[0] = 0.0f;
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_dbt_update(&b, &f));
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_workspace_and_config);
    RUN_TEST(test_plots);
    RUN_TEST(test_plots_2d);
    RUN_TEST(test_confirm_and_delete);
    RUN_TEST(test_gate);
    RUN_TEST(test_tracking);
    RUN_TEST(test_bad_input_untouched);
    return UNITY_END();
}
