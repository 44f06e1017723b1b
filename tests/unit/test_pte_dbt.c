/*
 * Kalman detect-before-track baseline (pft_pte.h): plots (run centroids, range-Doppler local
 * maxima), 2-of-3 confirmation, deletion after 3 misses, the chi-square gate, tracking
 * accuracy of a clean target, false tracks from noise plots, workspace formula, refused input
 * leaves every byte unchanged.
 */
#include <math.h>
#include <string.h>

#include "pft_test_support.h"
#include "pft/pft_pte.h"

void setUp(void) {}
void tearDown(void) {}

#define NR 64

static pft_real_t R(double v) { return pft_test_from_double(v); }
static double D(pft_real_t v) { return pft_test_to_double(v); }

/* pft_pte_dbt_config_default for n_range x n_doppler frames */
static void dbt_config(pft_pte_dbt_config_t *c, int n_range, int n_doppler)
{
    pft_pte_dbt_config_default(c);
    c->in.n_range = (uint16_t)n_range;
    c->in.n_doppler = (uint16_t)n_doppler;
}

static uint64_t g_work[PFT_PTE_DBT_WORKSPACE_BYTES(NR, 8, 32, 64) / 8 + 8];
static uint64_t g_copy[sizeof(g_work) / 8];
static pft_pte_report_t g_rep[PFT_PTE_DBT_MAX_TRACKS];
static pft_pte_dbt_plot_t g_plots[8];
static pft_real_t g_z[NR * 8];

static uint64_t g_s;
static double gauss(void) { return pft_test_gauss(&g_s); }

static void init_dbt(pft_pte_dbt_t *b, const pft_pte_dbt_config_t *c)
{
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_pte_dbt_config_check(c, NULL));
    size_t need = pft_pte_dbt_workspace_size(c);
    TEST_ASSERT_TRUE(need > 0u && need <= sizeof(g_work));
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_pte_dbt_init(b, c, g_work, need));
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
    pft_pte_dbt_config_t c;
    pft_pte_dbt_config_default(&c);
    TEST_ASSERT_EQUAL_UINT16(150, c.in.n_range);
    TEST_ASSERT_EQUAL_UINT16(1, c.in.n_doppler);
    TEST_ASSERT_TRUE(D(c.gate) == 0.0); /* by the number of axes at init (test_default_gate) */
    c.in.n_range = NR;
    TEST_ASSERT_EQUAL_UINT32(PFT_PTE_DBT_WORKSPACE_BYTES(NR, 1, 32, 64), pft_pte_dbt_workspace_size(&c));
    c.in.n_doppler = 8;
    TEST_ASSERT_EQUAL_UINT32(PFT_PTE_DBT_WORKSPACE_BYTES(NR, 8, 32, 64), pft_pte_dbt_workspace_size(&c));
    pft_pte_dbt_t b;
    size_t need = pft_pte_dbt_workspace_size(&c);
    uint8_t *buf = (uint8_t *)g_work;
    pft_test_guard_fill(buf, sizeof(g_work));
    TEST_ASSERT_EQUAL_INT(PFT_ERR_NOMEM, pft_pte_dbt_init(&b, &c, buf + 1, need - 1));
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_pte_dbt_init(&b, &c, buf + 1, need));
    TEST_ASSERT_TRUE(pft_test_guard_intact(buf, sizeof(g_work), 1, 1 + need));
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_pte_dbt_reset(&b));
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_pte_dbt_reset(NULL));
    const char *field = NULL;
    c.confirm_m = 4; /* more hits than frames */
    TEST_ASSERT_EQUAL_INT(PFT_ERR_CONFIG, pft_pte_dbt_config_check(&c, &field));
    TEST_ASSERT_EQUAL_STRING("confirm_m", field);
    TEST_ASSERT_EQUAL_INT(PFT_ERR_CONFIG, pft_pte_dbt_init(&b, &c, g_work, sizeof(g_work)));
    TEST_ASSERT_EQUAL_UINT32(0, pft_pte_dbt_workspace_size(&c));
    c.confirm_m = 2;
    c.q[1] = R(-1.0);
    TEST_ASSERT_EQUAL_INT(PFT_ERR_CONFIG, pft_pte_dbt_config_check(&c, &field));
    TEST_ASSERT_EQUAL_STRING("q[1]", field);
    c.q[1] = R(0.0);
    c.gate = R(-1.0);
    TEST_ASSERT_EQUAL_INT(PFT_ERR_CONFIG, pft_pte_dbt_config_check(&c, &field));
    TEST_ASSERT_EQUAL_STRING("gate", field);
    c.gate = R(0.0);
    c.in.n_range = 1;
    TEST_ASSERT_EQUAL_INT(PFT_ERR_CONFIG, pft_pte_dbt_config_check(&c, &field));
    TEST_ASSERT_EQUAL_STRING("in.n_range", field);
    c.in.n_range = NR;
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_pte_dbt_config_check(&c, &field));
    TEST_ASSERT_NULL(field);
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_pte_dbt_config_check(NULL, &field));
}

/* gate 0 (the default) is PFT_PTE_DBT_GATE_1AXIS for range-time and PFT_PTE_DBT_GATE_2AXES
 * for range-Doppler frames: the same reports, frame for frame, as the explicit gate. */
static void run_gate(int nd, double gate, pft_pte_report_t *out, uint32_t *counts)
{
    pft_pte_dbt_config_t c;
    dbt_config(&c, NR, (uint16_t)nd);
    c.gate = R(gate);
    pft_pte_dbt_t b;
    init_dbt(&b, &c);
    g_s = 606;
    for (int k = 0; k < 20; ++k) {
        for (int d = 0; d < nd; ++d) {
            for (int u = 0; u < NR; ++u) {
                double dr = u - (20.0 + 0.4 * k), dd = d - 3.0;
                g_z[d * NR + u] = R(gauss() + 3.5 * exp(-(dr * dr + dd * dd) / 0.72));
            }
        }
        TEST_ASSERT_EQUAL_INT(PFT_OK, pft_pte_dbt_update_real(&b, g_z));
        counts[k] = (uint32_t)pft_pte_dbt_reports(&b, out + 4 * k, 4);
    }
}

static void test_default_gate(void)
{
    static pft_pte_report_t a[80], e[80];
    uint32_t na[20], ne[20], total = 0;
    for (int nd = 1; nd <= 8; nd += 7) {
        memset(a, 0, sizeof(a));
        memset(e, 0, sizeof(e));
        run_gate(nd, 0.0, a, na);
        run_gate(nd, nd > 1 ? 9.21 : 6.63, e, ne);
        TEST_ASSERT_EQUAL_MEMORY(ne, na, sizeof(na));
        TEST_ASSERT_EQUAL_MEMORY(e, a, sizeof(a));
        for (int k = 0; k < 20; ++k) {
            total += na[k];
        }
    }
    TEST_ASSERT_TRUE(total > 20u); /* the runs do make tracks */
}

/* Runs of cells above the threshold give one plot each at the zeta-weighted centroid. */
static void test_plots(void)
{
    pft_pte_dbt_config_t c;
    dbt_config(&c, NR, 1);
    pft_pte_dbt_t b;
    init_dbt(&b, &c);
    int u[5] = {10, 11, 12, 20, 21};
    double v[5] = {3.0, 5.0, 3.0, 4.0, 2.5};
    spikes(5, u, v);
    g_z[30] = R(2.0); /* below the 2.326 threshold */
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_pte_dbt_update_real(&b, g_z));
    const pft_pte_dbt_plot_t *pl = g_plots;
    TEST_ASSERT_EQUAL_UINT32(2, pft_pte_dbt_plots(&b, g_plots, 8));
    TEST_ASSERT_DOUBLE_WITHIN(1e-3, 11.0, D(pl[0].pos[0]));
    TEST_ASSERT_DOUBLE_WITHIN(1e-3, 5.0, D(pl[0].peak));
    TEST_ASSERT_DOUBLE_WITHIN(1e-3, (20 * 4.0 + 21 * 2.5) / 6.5, D(pl[1].pos[0]));
    /* no track is confirmed from one frame */
    TEST_ASSERT_EQUAL_UINT32(0, pft_pte_dbt_reports(&b, NULL, 0));
}

/* Range-Doppler: one plot per local maximum, centroid over its 3x3 block. */
static void test_plots_2d(void)
{
    pft_pte_dbt_config_t c;
    dbt_config(&c, NR, 8);
    pft_pte_dbt_t b;
    init_dbt(&b, &c);
    memset(g_z, 0, sizeof(g_z));
    g_z[3 * NR + 10] = R(6.0);
    g_z[3 * NR + 11] = R(3.0);
    g_z[4 * NR + 10] = R(3.0);
    g_z[6 * NR + 40] = R(4.0);
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_pte_dbt_update_real(&b, g_z));
    const pft_pte_dbt_plot_t *pl = g_plots;
    TEST_ASSERT_EQUAL_UINT32(2, pft_pte_dbt_plots(&b, g_plots, 8));
    TEST_ASSERT_DOUBLE_WITHIN(1e-3, 10.25, D(pl[0].pos[0]));
    TEST_ASSERT_DOUBLE_WITHIN(1e-3, 3.25, D(pl[0].pos[1]));
    TEST_ASSERT_DOUBLE_WITHIN(1e-3, 40.0, D(pl[1].pos[0]));
    TEST_ASSERT_DOUBLE_WITHIN(1e-3, 6.0, D(pl[1].pos[1]));
}

/* hit, miss, hit: confirmed at the third frame; then three misses delete it. A single blip
 * is never confirmed. */
static void test_confirm_and_delete(void)
{
    pft_pte_dbt_config_t c;
    dbt_config(&c, NR, 1);
    pft_pte_dbt_t b;
    init_dbt(&b, &c);
    int u = 30;
    double v = 5.0;
    const pft_pte_report_t *r = g_rep;
    spikes(1, &u, &v);
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_pte_dbt_update_real(&b, g_z));
    TEST_ASSERT_EQUAL_UINT32(0, pft_pte_dbt_reports(&b, NULL, 0));
    spikes(0, NULL, NULL);
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_pte_dbt_update_real(&b, g_z));
    TEST_ASSERT_EQUAL_UINT32(0, pft_pte_dbt_reports(&b, NULL, 0));
    spikes(1, &u, &v);
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_pte_dbt_update_real(&b, g_z));
    TEST_ASSERT_EQUAL_UINT32(1, pft_pte_dbt_reports(&b, g_rep, PFT_PTE_DBT_MAX_TRACKS));
    TEST_ASSERT_EQUAL_UINT16(1, r[0].id);
    TEST_ASSERT_TRUE(r[0].detected);
    TEST_ASSERT_DOUBLE_WITHIN(0.05, 30.0, D(r[0].pos[0]));
    spikes(0, NULL, NULL);
    for (int k = 0; k < 2; ++k) {
        TEST_ASSERT_EQUAL_INT(PFT_OK, pft_pte_dbt_update_real(&b, g_z));
        TEST_ASSERT_EQUAL_UINT32(1, pft_pte_dbt_reports(&b, g_rep, PFT_PTE_DBT_MAX_TRACKS));
        TEST_ASSERT_FALSE(r[0].detected);
    }
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_pte_dbt_update_real(&b, g_z));
    TEST_ASSERT_EQUAL_UINT32(0, pft_pte_dbt_reports(&b, NULL, 0));
    /* a single blip followed by two empty frames: never confirmed */
    pft_pte_dbt_reset(&b);
    u = 50;
    spikes(1, &u, &v);
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_pte_dbt_update_real(&b, g_z));
    spikes(0, NULL, NULL);
    for (int k = 0; k < 4; ++k) {
        TEST_ASSERT_EQUAL_INT(PFT_OK, pft_pte_dbt_update_real(&b, g_z));
        TEST_ASSERT_EQUAL_UINT32(0, pft_pte_dbt_reports(&b, NULL, 0));
    }
    /* the blip's tentative track was deleted: a new blip at the same place needs 2 hits again */
    u = 50;
    spikes(1, &u, &v);
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_pte_dbt_update_real(&b, g_z));
    TEST_ASSERT_EQUAL_UINT32(0, pft_pte_dbt_reports(&b, NULL, 0));
}

/* A confirmed track at 30 (velocity ~0, P_rr + R ~ 0.3): a plot 6 cells away is outside the
 * chi-square gate (36 / 0.3 >> 6.63) and does not move the track; one 0.5 cell away does. */
static void test_gate(void)
{
    pft_pte_dbt_config_t c;
    dbt_config(&c, NR, 1);
    pft_pte_dbt_t b;
    init_dbt(&b, &c);
    int u = 30;
    double v = 5.0;
    const pft_pte_report_t *r = g_rep;
    for (int k = 0; k < 4; ++k) {
        spikes(1, &u, &v);
        TEST_ASSERT_EQUAL_INT(PFT_OK, pft_pte_dbt_update_real(&b, g_z));
    }
    TEST_ASSERT_EQUAL_UINT32(1, pft_pte_dbt_reports(&b, g_rep, PFT_PTE_DBT_MAX_TRACKS));
    double before = D(r[0].pos[0]);
    u = 36;
    spikes(1, &u, &v);
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_pte_dbt_update_real(&b, g_z));
    TEST_ASSERT_EQUAL_UINT32(1, pft_pte_dbt_reports(&b, g_rep, PFT_PTE_DBT_MAX_TRACKS));
    TEST_ASSERT_FALSE(r[0].detected);
    TEST_ASSERT_DOUBLE_WITHIN(0.05, before, D(r[0].pos[0]));
    /* the far plot started a tentative track: two tracks after its second hit */
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_pte_dbt_update_real(&b, g_z));
    TEST_ASSERT_EQUAL_UINT32(2, pft_pte_dbt_reports(&b, NULL, 0));
}

/* Clean-ish target at 13 dB (A = 4.5 sigma) moving 0.2 cells/frame: one confirmed track with
 * a stable id, RMS error < 0.25 cells, velocity within 0.05. Noise plots (P_fa 1e-2 on 64
 * cells) make short false tracks: they stay below 15% of the declared points. */
static void test_tracking(void)
{
    pft_pte_dbt_config_t c;
    dbt_config(&c, NR, 1);
    pft_pte_dbt_t b;
    init_dbt(&b, &c);
    g_s = 424242;
    double se = 0.0;
    int n = 0, declared = 0, wrong = 0;
    uint16_t id = 0;
    const pft_pte_report_t *r = g_rep;
    double vel = 0.0;
    for (int k = 0; k < 150; ++k) {
        double pos = 15.0 + 0.2 * k;
        for (int u = 0; u < NR; ++u) {
            double d = u - pos;
            g_z[u] = R(gauss() + 4.5 * exp(-d * d / 0.72));
        }
        TEST_ASSERT_EQUAL_INT(PFT_OK, pft_pte_dbt_update_real(&b, g_z));
        uint32_t m = (uint32_t)pft_pte_dbt_reports(&b, g_rep, PFT_PTE_DBT_MAX_TRACKS);
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
    pft_pte_dbt_config_t c;
    dbt_config(&c, NR, 1);
    pft_pte_dbt_t b;
    init_dbt(&b, &c);
    int u = 30;
    double v = 5.0;
    for (int k = 0; k < 3; ++k) {
        spikes(1, &u, &v);
        TEST_ASSERT_EQUAL_INT(PFT_OK, pft_pte_dbt_update_real(&b, g_z));
    }
    pft_pte_dbt_t copy = b;
    memcpy(g_copy, g_work, sizeof(g_work));
    static float f32[NR];
    pft_frame_t f = {0};
    f.data = f32;
    f.width = NR - 1;
    f.height = 1;
    f.stride_bytes = NR * 4;
    f.format = PFT_PIX_F32;
    TEST_ASSERT_EQUAL_INT(PFT_ERR_FORMAT, pft_pte_dbt_update(&b, &f));
    f.width = NR;
    f32[0] = -INFINITY;
    TEST_ASSERT_EQUAL_INT(PFT_ERR_FORMAT, pft_pte_dbt_update(&b, &f));
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_pte_dbt_update(&b, NULL));
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_pte_dbt_update_real(NULL, g_z));
    TEST_ASSERT_EQUAL_MEMORY(&copy, &b, sizeof(b));
    TEST_ASSERT_EQUAL_MEMORY(g_copy, g_work, sizeof(g_work));
    f32[0] = 0.0f;
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_pte_dbt_update(&b, &f));
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_workspace_and_config);
    RUN_TEST(test_default_gate);
    RUN_TEST(test_plots);
    RUN_TEST(test_plots_2d);
    RUN_TEST(test_confirm_and_delete);
    RUN_TEST(test_gate);
    RUN_TEST(test_tracking);
    RUN_TEST(test_bad_input_untouched);
    return UNITY_END();
}
