/*
 * Cross-target determinism: replays the calls behind tests/vectors/core_q16_vectors.h (the
 * q16 results of a host build) and compares.
 *   q16 builds (host, Cortex-M3, Cortex-M7, AArch64): every value bit-identical.
 *   float builds: integer streams (RNG u32, bounded draws) identical; real results agree with
 *   the q16 ones within the q16 error bound plus float rounding (tol_raw below), Gaussian
 *   draws within the difference the builds' uniform resolutions explain (16 vs 24 bits).
 */
#include <stdlib.h>
#include "pft_test_support.h"
#include "core_vectors_spec.h"
#include "core_q16_vectors.h"

void setUp(void) {}
void tearDown(void) {}

static pft_gv_results_t got;

static void check_i32(const char *name, const int32_t *ref, const int32_t *val, size_t n,
                      int32_t tol_abs, double tol_rel)
{
    for (size_t i = 0; i < n; ++i) {
        double d = (double)val[i] - (double)ref[i];
        double tol = (double)tol_abs + tol_rel * (double)labs((long)ref[i]);
        if (d < -tol || d > tol) {
            UnityPrint(name);
            UnityPrint(" index ");
            UnityPrintNumber((UNITY_INT)i);
            UnityPrint(": expected ");
            UnityPrintNumber((UNITY_INT)ref[i]);
            UnityPrint(" got ");
            UnityPrintNumber((UNITY_INT)val[i]);
            UNITY_PRINT_EOL();
            TEST_FAIL_MESSAGE(name);
        }
    }
}

static void check_u32(const char *name, const uint32_t *ref, const uint32_t *val, size_t n,
                      double tol_abs)
{
    for (size_t i = 0; i < n; ++i) {
        double d = (double)val[i] - (double)ref[i];
        if (d < -tol_abs || d > tol_abs) {
            UnityPrint(name);
            UnityPrint(" index ");
            UnityPrintNumber((UNITY_INT)i);
            UNITY_PRINT_EOL();
            TEST_FAIL_MESSAGE(name);
        }
    }
}

#ifdef PFT_NUMERIC_Q16
#define EXACT 1
#else
#define EXACT 0
#endif
/* float vs q16, in Q16.16 raw units: q16 bound (<= 1.1 LSB, docs/fixed_point.md) + rounding of
 * the float result to raw (0.5) + float's own relative precision (2 ulp = 2^-22 relative). */
#define TOL_A (EXACT ? 0 : 2)
#define TOL_R (EXACT ? 0.0 : 2.4e-7)

static void test_rng_streams(void)
{
    check_u32("rng_u32", gv_rng_u32, got.rng_u32, PFT_GV_N_RNG, 0.0);
    check_u32("rng_below", gv_rng_below, got.rng_below, PFT_GV_N_RNG, 0.0);
    /* float keeps 24 bits of the draw, q16 16: they differ by less than 2^-16 */
    check_i32("rng_uniform", gv_rng_uniform, got.rng_uniform, PFT_GV_N_RNG, EXACT ? 0 : 1, 0.0);
    /* Box-Muller from 16-bit (q16) vs 24-bit (float) uniforms: the truncation of u1, u2 moves
     * a draw by about 2pi r 2^-16 + 2^-16/(u1 r) with r = sqrt(-2 ln u1), i.e. about 12 raw
     * for r near 2 (measured here: 11 raw at most); 48 raw leaves room for the u1 term. */
    check_i32("rng_gauss", gv_rng_gauss, got.rng_gauss, PFT_GV_N_RNG, EXACT ? 0 : 48, 0.0);
    /* the ziggurat decides on integers only: the builds draw the same Q24 magnitudes, which
     * q16 rounds to Q16.16 and float scales (then rounded to raw here): within 1 raw; after
     * 200 000 draws both have consumed the same words */
    check_i32("rng_zig", gv_rng_zig, got.rng_zig, PFT_GV_N_ZIG, EXACT ? 0 : 1, 0.0);
    TEST_ASSERT_EQUAL_UINT32_MESSAGE(gv_zig_run[1], got.zig_run[1], "ziggurat words consumed");
#if EXACT
    TEST_ASSERT_EQUAL_UINT32_MESSAGE(gv_zig_run[0], got.zig_run[0], "ziggurat run hash");
#endif
}

static void test_math_grid(void)
{
    check_i32("mul", gv_mul, got.mul, PFT_GV_N_GRID, TOL_A, TOL_R);
    check_i32("div", gv_div, got.div, PFT_GV_N_GRID, TOL_A, TOL_R);
    check_i32("recip", gv_recip, got.recip, PFT_GV_N_GRID, TOL_A, TOL_R);
    check_i32("sqrt", gv_sqrt, got.sqrt_, PFT_GV_N_GRID, TOL_A, TOL_R);
    check_i32("exp", gv_exp, got.exp_, PFT_GV_N_GRID, TOL_A, TOL_R);
    check_i32("log", gv_log, got.log_, PFT_GV_N_GRID, TOL_A, TOL_R);
    check_i32("atan2", gv_atan2, got.atan2_, PFT_GV_N_GRID, TOL_A, TOL_R);
    /* sin/cos of arguments up to 20: float's argument carries 2^-19 absolute rounding */
    check_i32("sin", gv_sin, got.sin_, PFT_GV_N_GRID, EXACT ? 0 : 3, 0.0);
    check_i32("cos", gv_cos, got.cos_, PFT_GV_N_GRID, EXACT ? 0 : 3, 0.0);
    check_i32("from_f32", gv_from_f32, got.from_f32, PFT_GV_N_GRID, TOL_A, TOL_R);
}

static void test_weights(void)
{
    /* Q2.30 vs float weights: float keeps 24 bits, i.e. 2^-24 relative (+1 raw for rounding) */
    for (size_t i = 0; i < PFT_GV_N_GRID; ++i) {
        double tol = EXACT ? 0.0 : 1.0 + (double)gv_wexp[i] * 1.2e-7;
        double d = (double)got.wexp[i] - (double)gv_wexp[i];
        TEST_ASSERT_TRUE_MESSAGE(d >= -tol && d <= tol, "wexp");
    }
    for (size_t i = 0; i < PFT_GV_N_W; ++i) {
        double tol = EXACT ? 0.0 : 16.0 + (double)gv_lognorm_w[i] * 1e-6; /* measured 7 raw */
        double d = (double)got.lognorm_w[i] - (double)gv_lognorm_w[i];
        TEST_ASSERT_TRUE_MESSAGE(d >= -tol && d <= tol, "lognormalize weights");
    }
    check_i32("lognormalize", gv_lognorm_ret, &got.lognorm_ret, 1, TOL_A, TOL_R);
    check_i32("ess", gv_ess, &got.ess, 1, EXACT ? 0 : 4, 1e-5);
}

static void test_resampling_indices(void)
{
    /* Indices come from integer draws and cumulative weights; float may flip an index where a
     * uniform falls within float rounding of a cumulative boundary: allow none here. */
    check_u32("systematic", gv_idx_systematic, got.idx[0], PFT_GV_N_IDX, 0.0);
    check_u32("stratified", gv_idx_stratified, got.idx[1], PFT_GV_N_IDX, 0.0);
    check_u32("residual", gv_idx_residual, got.idx[2], PFT_GV_N_IDX, 0.0);
    check_u32("multinomial", gv_idx_multinomial, got.idx[3], PFT_GV_N_IDX, 0.0);
}

static void test_kalman(void)
{
    check_i32("kf4", gv_kf4, got.kf4, 20, EXACT ? 0 : 3, 1e-6);
}

int main(void)
{
    pft_gv_compute(&got);
    UNITY_BEGIN();
    RUN_TEST(test_rng_streams);
    RUN_TEST(test_math_grid);
    RUN_TEST(test_weights);
    RUN_TEST(test_resampling_indices);
    RUN_TEST(test_kalman);
    return UNITY_END();
}
