/* Number-type differences the filters need (private, not installed): kept here so that no
 * tracker source tests PFT_NUMERIC_Q16 itself.
 *
 * pft_p16_: a probability that gates a random decision, quantised to 1/65536 steps the same
 * way in both builds (a draw u of 16 bits decides "u < p16"), so float and q16 builds make the
 * same discrete decisions from the same integer draws (docs/design.md, "Determinism").
 *
 * pft_span_ok_: whether n steps of size d (e.g. image columns times the pixel pitch) stay well
 * inside what positions can hold: below 16384 in q16 (half the Q16.16 range, so a position and
 * a difference of two positions never saturate), always true in float.
 */
#ifndef PFT_CORE_NUM_INT_H
#define PFT_CORE_NUM_INT_H

#include "pft/pft_real.h"

#ifdef PFT_NUMERIC_Q16
static inline uint32_t pft_p16_(pft_real_t p)
{
    return (uint32_t)pft_clamp(p, PFT_C(0.0), PFT_C(1.0));
}
static inline bool pft_span_ok_(uint32_t n, pft_real_t d)
{
    return (int64_t)n * d < ((int64_t)16384 << 16);
}
#else
static inline uint32_t pft_p16_(pft_real_t p)
{
    return (uint32_t)(pft_clamp(p, PFT_C(0.0), PFT_C(1.0)) * 65536.0f + 0.5f);
}
static inline bool pft_span_ok_(uint32_t n, pft_real_t d)
{
    (void)n;
    (void)d;
    return true;
}
#endif

#endif
