/*
 * Input stage of the pte family (pft_pte.h): frame conversion (U8, U16 with bit depth, F32),
 * fixed-sigma normalisation and clamping, the cell-averaging CFAR (exact value on a constant
 * profile, edges, floor, adaptation to a step in the noise level), the one-pass F32 path bit
 * for bit against the step-by-step conversion, and refusal of bad frames with nothing
 * written.
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

/* pft_pte_input_default for n_range x n_doppler frames */
static void input_config(pft_pte_input_t *c, int n_range, int n_doppler)
{
    pft_pte_input_default(c);
    c->n_range = (uint16_t)n_range;
    c->n_doppler = (uint16_t)n_doppler;
}

static pft_real_t g_z[NR];
static pft_real_t g_zeta[NR];
static pft_real_t g_scratch[NR];

static void test_defaults_and_check(void)
{
    pft_pte_input_t in;
    pft_pte_input_default(&in);
    TEST_ASSERT_EQUAL_UINT16(150, in.n_range);
    TEST_ASSERT_EQUAL_UINT16(1, in.n_doppler);
    const char *field = "x";
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_pte_input_check(&in, &field));
    TEST_ASSERT_NULL(field);
    TEST_ASSERT_EQUAL_INT(PFT_PTE_NOISE_FIXED, in.noise);
    TEST_ASSERT_EQUAL_UINT8(16u, in.cfar_ref);
    pft_pte_input_t b = in;
    b.n_range = 1;
    TEST_ASSERT_EQUAL_INT(PFT_ERR_CONFIG, pft_pte_input_check(&b, &field));
    TEST_ASSERT_EQUAL_STRING("n_range", field);
    b = in;
    b.noise_sigma = R(0.0);
    TEST_ASSERT_EQUAL_INT(PFT_ERR_CONFIG, pft_pte_input_check(&b, &field));
    TEST_ASSERT_EQUAL_STRING("noise_sigma", field);
    b = in;
    b.cfar_ref = 0;
    TEST_ASSERT_EQUAL_INT(PFT_ERR_CONFIG, pft_pte_input_check(&b, &field));
    TEST_ASSERT_EQUAL_STRING("cfar_ref", field);
    b = in;
    b.n_doppler = 0;
    TEST_ASSERT_EQUAL_INT(PFT_ERR_CONFIG, pft_pte_input_check(&b, NULL));
    TEST_ASSERT_EQUAL_INT(PFT_ERR_CONFIG, pft_pte_normalize_real(&b, g_z, g_zeta));
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_pte_input_check(NULL, &field));
}

static void test_fixed_sigma_and_clamp(void)
{
    pft_pte_input_t in;
    input_config(&in, NR, 1);
    in.noise_sigma = R(2.0);
    in.zeta_clip = R(5.0);
    for (int u = 0; u < NR; ++u) {
        g_z[u] = R(0.25 * (u - 32));
    }
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_pte_normalize_real(&in, g_z, g_zeta));
    for (int u = 0; u < NR; ++u) {
        double want = 0.125 * (u - 32);
        want = want > 5.0 ? 5.0 : (want < -5.0 ? -5.0 : want);
        TEST_ASSERT_DOUBLE_WITHIN(3e-5, want, D(g_zeta[u]));
    }
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_pte_normalize_real(&in, g_z, g_z));
}

/* |z| = 2 everywhere: sigma^ = sqrt(pi/2) * 2 at every cell, edges included. */
static void test_cfar_constant_profile(void)
{
    pft_pte_input_t in;
    input_config(&in, NR, 1);
    in.noise = PFT_PTE_NOISE_CFAR;
    in.noise_sigma = R(0.01);
    in.cfar_ref = 8;
    in.cfar_guard = 2;
    for (int u = 0; u < NR; ++u) {
        g_z[u] = R((u & 1) ? 2.0 : -2.0);
    }
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_pte_normalize_real(&in, g_z, g_zeta));
    const double s = sqrt(3.14159265358979 / 2.0) * 2.0;
    for (int u = 0; u < NR; ++u) {
        TEST_ASSERT_DOUBLE_WITHIN(2e-3, ((u & 1) ? 2.0 : -2.0) / s, D(g_zeta[u]));
    }
    /* the floor binds on an all-zero profile with one cell at 1: sigma = floor */
    memset(g_z, 0, sizeof(g_z));
    g_z[30] = R(1.0);
    in.noise_sigma = R(0.5);
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_pte_normalize_real(&in, g_z, g_zeta));
    TEST_ASSERT_DOUBLE_WITHIN(2e-4, 2.0, D(g_zeta[30]));
}

/* deterministic N(0,1) for test data */
static uint64_t g_s = 88172645463325252ull;
static double gauss(void)
{
    double u[2];
    for (int i = 0; i < 2; ++i) {
        g_s ^= g_s << 13;
        g_s ^= g_s >> 7;
        g_s ^= g_s << 17;
        u[i] = ((double)(g_s >> 11) + 0.5) / 9007199254740992.0;
    }
    return sqrt(-2.0 * log(u[0])) * cos(6.283185307179586 * u[1]);
}

/* noise of sigma 1 on the left half and 4 on the right: CFAR output has unit power on both
 * sides away from the step, while a fixed sigma would leave a 4x mismatch. */
static void test_cfar_adapts_to_level_step(void)
{
    pft_pte_input_t in;
    input_config(&in, NR, 1);
    in.noise = PFT_PTE_NOISE_CFAR;
    in.noise_sigma = R(0.01);
    in.cfar_ref = 8;
    in.cfar_guard = 1;
    double pl = 0.0, pr = 0.0;
    int nl = 0, nrr = 0;
    for (int rep = 0; rep < 200; ++rep) {
        for (int u = 0; u < NR; ++u) {
            g_z[u] = R(gauss() * (u < NR / 2 ? 1.0 : 4.0));
        }
        TEST_ASSERT_EQUAL_INT(PFT_OK, pft_pte_normalize_real(&in, g_z, g_zeta));
        for (int u = 0; u < NR; ++u) {
            double v = D(g_zeta[u]);
            if (u < NR / 2 - 12) {
                pl += v * v;
                nl++;
            } else if (u > NR / 2 + 12) {
                pr += v * v;
                nrr++;
            }
        }
    }
    pl /= nl;
    pr /= nrr;
    UnityPrint(" power_left=");
    UnityPrintFloat(pl);
    UnityPrint(" power_right=");
    UnityPrintFloat(pr);
    /* 16 reference cells (8 at the edges): E[sigma^-2] inflates the power by 1.1 .. 1.2 */
    TEST_ASSERT_DOUBLE_WITHIN(0.15, 1.15, pl);
    TEST_ASSERT_DOUBLE_WITHIN(0.15, 1.15, pr);
}

static void test_frames_u8_u16_f32(void)
{
    pft_pte_input_t in;
    input_config(&in, 8, 2);
    in.pixel_gain = R(0.5);
    in.pixel_offset = R(-10.0);
    in.noise_sigma = R(2.0);
    in.zeta_clip = R(100.0);
    uint8_t u8[2 * 8];
    uint16_t u16[2 * 8];
    float f32[2 * 8];
    pft_real_t out[2 * 8];
    for (int i = 0; i < 16; ++i) {
        u8[i] = (uint8_t)(10 * i);
        u16[i] = (uint16_t)(0xF000u | (uint16_t)(10 * i)); /* high bits above bit_depth 12 */
        f32[i] = (float)(i - 8);
    }
    pft_frame_t f = {0};
    f.width = 8;
    f.height = 2;
    f.data = u8;
    f.format = PFT_PIX_U8;
    f.stride_bytes = 8;
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_pte_normalize(&in, &f, out, NULL));
    for (int i = 0; i < 16; ++i) {
        TEST_ASSERT_DOUBLE_WITHIN(1e-4, (0.5 * 10 * i - 10.0) / 2.0, D(out[i]));
    }
    f.data = u16;
    f.format = PFT_PIX_U16;
    f.bit_depth = 12;
    f.stride_bytes = 16;
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_pte_normalize(&in, &f, out, NULL));
    for (int i = 0; i < 16; ++i) {
        TEST_ASSERT_DOUBLE_WITHIN(1e-4, (0.5 * 10 * i - 10.0) / 2.0, D(out[i]));
    }
    f.data = f32;
    f.format = PFT_PIX_F32;
    f.bit_depth = 0;
    f.stride_bytes = 32;
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_pte_normalize(&in, &f, out, NULL));
    for (int i = 0; i < 16; ++i) {
        TEST_ASSERT_DOUBLE_WITHIN(1e-4, (i - 8) / 2.0, D(out[i]));
    }
}

/* F32 frames in fixed-noise mode take a one-pass path (IEEE decoding inlined in the q16
 * build): every value equals pft_from_f32, the clamp to +-32767, the multiplication by
 * 1/sigma and the zeta clamp done step by step, bit for bit, for two sigma / clip pairs. Values: random bit patterns
 * (finite) over the whole exponent range and over the range around the q16 LSB and 32767,
 * zeros, subnormals and ties. */
static void test_f32_fast_path_exact(void)
{
    pft_pte_input_t in;
    input_config(&in, NR, 1);
    static float px[NR];
    static pft_real_t ref[NR];
    uint32_t st = 2463534242u;
    long differ = 0;
    for (int it = 0; it < 800; ++it) {
        /* half the frames with sigma 0.7 and a clip far out, half with sigma 3 and a clip
         * at 4 (the clamp active on both signs) */
        in.noise_sigma = it < 400 ? R(0.7) : R(3.0);
        in.zeta_clip = it < 400 ? R(1000.0) : R(4.0);
        const pft_real_t inv = pft_recip(in.noise_sigma);
        for (int u = 0; u < NR; ++u) {
            st ^= st << 13;
            st ^= st >> 17;
            st ^= st << 5;
            uint32_t bits = st;
            if ((it & 3) == 1) { /* exponents around the q16 LSB (2^-16) and 32767 (2^15) */
                bits = (bits & 0x807FFFFFu) | ((uint32_t)(100u + (st >> 9) % 50u) << 23);
            } else if ((it & 3) == 2) { /* zeros, subnormals, ties at half an LSB */
                bits = (u & 3) == 0 ? (bits & 0x80000000u) : ((u & 3) == 1 ? bits & 0x807FFFFFu : 0x37000000u | (bits & 0x80000000u) | (uint32_t)u << 18);
            }
            if ((bits & 0x7F800000u) == 0x7F800000u) {
                bits &= 0xBFFFFFFFu; /* finite only (NaN/Inf are refused) */
            }
            memcpy(&px[u], &bits, 4u);
            pft_real_t v = pft_clamp(pft_from_f32(px[u]), R(-32767.0), R(32767.0));
            ref[u] = pft_clamp(pft_mul(v, inv), pft_neg(in.zeta_clip), in.zeta_clip);
        }
        pft_frame_t f;
        memset(&f, 0, sizeof(f));
        f.data = px;
        f.width = NR;
        f.height = 1;
        f.stride_bytes = 4u * NR;
        f.format = PFT_PIX_F32;
        TEST_ASSERT_EQUAL_INT(PFT_OK, pft_pte_normalize(&in, &f, g_zeta, NULL));
        for (int u = 0; u < NR; ++u) {
            differ += memcmp(&g_zeta[u], &ref[u], sizeof(pft_real_t)) != 0;
        }
    }
    TEST_ASSERT_EQUAL_INT32(0, differ);
}

static void test_bad_frames_write_nothing(void)
{
    pft_pte_input_t in;
    input_config(&in, 8, 1);
    float f32[8] = {0};
    pft_real_t out[8];
    for (int i = 0; i < 8; ++i) {
        out[i] = R(123.0);
    }
    pft_frame_t f = {0};
    f.width = 7; /* wrong width */
    f.height = 1;
    f.data = f32;
    f.format = PFT_PIX_F32;
    f.stride_bytes = 32;
    TEST_ASSERT_EQUAL_INT(PFT_ERR_FORMAT, pft_pte_normalize(&in, &f, out, NULL));
    f.width = 8;
    f.height = 2; /* wrong height */
    TEST_ASSERT_EQUAL_INT(PFT_ERR_FORMAT, pft_pte_normalize(&in, &f, out, NULL));
    f.height = 1;
    f.format = PFT_PIX_RGB888;
    TEST_ASSERT_EQUAL_INT(PFT_ERR_FORMAT, pft_pte_normalize(&in, &f, out, NULL));
    f.format = PFT_PIX_F32;
    f32[3] = NAN;
    TEST_ASSERT_EQUAL_INT(PFT_ERR_FORMAT, pft_pte_normalize(&in, &f, out, NULL));
    f32[3] = INFINITY;
    TEST_ASSERT_EQUAL_INT(PFT_ERR_FORMAT, pft_pte_normalize(&in, &f, out, NULL));
    f.data = NULL;
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_pte_normalize(&in, &f, out, NULL));
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_pte_normalize(&in, NULL, out, NULL));
    in.noise = PFT_PTE_NOISE_CFAR; /* CFAR needs its scratch row */
    f.data = f32;
    f32[3] = 1.0f;
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_pte_normalize(&in, &f, out, NULL));
    for (int i = 0; i < 8; ++i) {
        TEST_ASSERT_DOUBLE_WITHIN(1e-9, 123.0, D(out[i]));
    }
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_pte_normalize(&in, &f, out, g_scratch));
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_defaults_and_check);
    RUN_TEST(test_fixed_sigma_and_clamp);
    RUN_TEST(test_cfar_constant_profile);
    RUN_TEST(test_cfar_adapts_to_level_step);
    RUN_TEST(test_frames_u8_u16_f32);
    RUN_TEST(test_f32_fast_path_exact);
    RUN_TEST(test_bad_frames_write_nothing);
    return UNITY_END();
}
