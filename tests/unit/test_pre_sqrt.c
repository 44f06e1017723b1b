/*
 * The clutter map's square root (lib/src/pre/pre_clutter.c, pft_pre_sqrt_q10_, private): for
 * every mm in 0..65535, the whole range of the map's mean M in Q6.10, it equals the integer
 * square root it replaces, pft_pre_isqrt64_(mm << 10), and floor(sqrt(mm 2^10)) computed in
 * double (exact here: mm 2^10 < 2^26). Both functions are internal to the library (declared
 * in lib/src/pre/pre_int.h, not installed); the test declares them itself.
 */
#include <math.h>
#include <stdint.h>

#include "pft_test_support.h"

uint32_t pft_pre_isqrt64_(uint64_t v);
uint32_t pft_pre_sqrt_q10_(uint32_t mm);

void setUp(void) {}
void tearDown(void) {}

static void test_sqrt_q10_every_value(void)
{
    uint32_t bad = 0u;
    for (uint32_t mm = 0u; mm <= 65535u; ++mm) {
        const uint32_t s = pft_pre_sqrt_q10_(mm);
        const uint32_t ref = pft_pre_isqrt64_((uint64_t)mm << 10);
        const uint32_t dbl = (uint32_t)floor(sqrt((double)mm * 1024.0));
        if (s != ref || s != dbl) {
            ++bad;
        }
    }
    /* exact: no tolerance (both are floor(sqrt(mm 2^10))) */
    TEST_ASSERT_EQUAL_UINT32_MESSAGE(0u, bad, "values differing from the integer square root");
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_sqrt_q10_every_value);
    return UNITY_END();
}
