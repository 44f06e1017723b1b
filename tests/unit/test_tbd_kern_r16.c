/*
 * The peak scan's products on a RES16 frame read in place (lib/src/tbd/tbd_meas.c,
 * peak_hrow_r16_ and peak_vrow_, docs/algorithms.md 2.11) against the arithmetic they replace.
 *
 * Known answer: pft_kmul_r16_(pft_kr16_tap_(t), a, b) is pft_kmula_(t, z) for z = the sum of
 * the two converted pixels pft_kres16_(a) + pft_kres16_(b) (what the scan computed on the
 * converted row), and pft_kmul_u_(t, z) is pft_kmula_(t, z) for taps in [0, 1] and |z| < 2^14;
 * pft_kmula_(1, z) is z. Equality bit for bit, no tolerance: the scan's peaks are chosen by
 * comparisons and ties of these values, so any other rounding could change the births. Every
 * int16 value a but the masked code is tried with several b (0, its neighbour, extremes) and
 * taps: 0, 1, the taps of PSF sigmas 0.5, 0.7, 1.0 and 2.0 at offset 0 (exp(-1 / (2 s^2))),
 * 2^-8 and 1 - 2^-16, odd values; pft_kmul_u_ over z spread through +-2^14 (both signs, the
 * values just below and above each multiple of 2^-16 boundary in q16, i.e. every 16-bit low
 * half near 0 and 2^15).
 */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "pft_test_support.h"
#include "pft/pft_real.h"
#include "../../lib/src/core/kern_int.h"

void setUp(void) {}
void tearDown(void) {}

static pft_real_t taps_[12];
static char msg_[160];
static uint32_t n_taps_;

static void make_taps_(void)
{
    static const double sig[4] = {0.5, 0.7, 1.0, 2.0};
    n_taps_ = 0u;
    taps_[n_taps_++] = PFT_C(0.0);
    taps_[n_taps_++] = PFT_REAL_ONE;
    for (int k = 0; k < 4; ++k) {
        taps_[n_taps_++] = pft_test_from_double(exp(-1.0 / (2.0 * sig[k] * sig[k])));
    }
    taps_[n_taps_++] = pft_test_from_double(1.0 / 256.0);
    taps_[n_taps_++] = pft_test_from_double(1.0 - 1.0 / 65536.0);
    taps_[n_taps_++] = pft_test_from_double(0.123456);
    taps_[n_taps_++] = pft_test_from_double(0.5);
    taps_[n_taps_++] = pft_test_from_double(0.999);
}

static void test_kmul_r16_is_kmula_of_the_converted_pixels(void)
{
    make_taps_();
    uint32_t bad = 0u;
    for (uint32_t k = 0; k < n_taps_; ++k) {
        const pft_real_t t = taps_[k];
        TEST_ASSERT_TRUE(pft_kr16_tap_ok_(t));
        const pft_real_t tp = pft_kr16_tap_(t);
        for (int32_t a = -32767; a <= 32767; ++a) {
            const int32_t bs[5] = {0, a > -32767 ? a - 1 : a, 32767, -32767, (a * 7) % 32768};
            for (int q = 0; q < 5; ++q) {
                const int16_t aa = (int16_t)a;
                const int16_t bb = (int16_t)bs[q];
                const pft_real_t want =
                    pft_kmula_(t, pft_kaddr_(pft_kres16_(aa), pft_kres16_(bb)));
                const pft_real_t got = pft_kmul_r16_(tp, aa, bb);
                if (memcmp(&want, &got, sizeof want) != 0 && bad++ == 0u) {
                    snprintf(msg_, sizeof msg_, "t %.9g a %d b %d: %.9g, pft_kmula_ %.9g",
                             pft_test_to_double(t), (int)aa, (int)bb, pft_test_to_double(got),
                             pft_test_to_double(want));
                }
            }
        }
    }
    TEST_ASSERT_EQUAL_UINT32_MESSAGE(0u, bad, msg_);
}

static void test_kmul_u_is_kmula(void)
{
    make_taps_();
    uint32_t bad = 0u;
    for (uint32_t k = 0; k < n_taps_; ++k) {
        const pft_real_t t = taps_[k];
        TEST_ASSERT_TRUE(pft_kmul_u_ok_(t));
        for (int32_t i = -40000; i <= 40000; ++i) {
            /* spread over +-2^14 (i 2^14 / 40000 in q16 bits, plus low halves near 0 and 2^15
             * in q16) */
            const double zd = (double)i * (16383.0 / 40000.0) + (double)(i % 7) * (1.0 / 65536.0);
            const pft_real_t z = pft_test_from_double(zd);
            const pft_real_t want = pft_kmula_(t, z);
            const pft_real_t got = pft_kmul_u_(t, z);
            if (memcmp(&want, &got, sizeof want) != 0 && bad++ == 0u) {
                snprintf(msg_, sizeof msg_, "t %.9g z %.9g: %.9g, pft_kmula_ %.9g",
                         pft_test_to_double(t), zd, pft_test_to_double(got),
                         pft_test_to_double(want));
            }
        }
        /* the centre tap 1: pft_kmula_(1, z) is z (peak_vrow_ adds the value itself) */
        for (int32_t i = -1000; i <= 1000; ++i) {
            const pft_real_t z = pft_test_from_double((double)i * 16.383 + 1.0 / 65536.0 * (i % 3));
            const pft_real_t one = pft_kmula_(PFT_REAL_ONE, z);
            TEST_ASSERT_EQUAL_MEMORY(&z, &one, sizeof z);
        }
    }
    TEST_ASSERT_EQUAL_UINT32_MESSAGE(0u, bad, msg_);
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_kmul_r16_is_kmula_of_the_converted_pixels);
    RUN_TEST(test_kmul_u_is_kmula);
    return UNITY_END();
}
