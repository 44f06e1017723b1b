/* The verdict of a tracker's config_check (private, not installed): one place for the contract
 * of docs/design.md ("One API pattern for every tracker"): PFT_ERR_INVAL for a NULL
 * configuration, PFT_ERR_CONFIG naming the first refused field in *field, PFT_OK with *field
 * NULL; field itself may be NULL. */
#ifndef PFT_CORE_CONFIG_INT_H
#define PFT_CORE_CONFIG_INT_H

#include "pft/pft_real.h"
#include "pft/pft_types.h"

/* have_cfg: the configuration pointer was not NULL; bad: its first refused field or NULL. */
static inline pft_status_t pft_config_verdict_(bool have_cfg, const char *bad, const char **field)
{
    if (field != NULL) {
        *field = have_cfg ? bad : NULL;
    }
    if (!have_cfg) {
        return PFT_ERR_INVAL;
    }
    return bad != NULL ? PFT_ERR_CONFIG : PFT_OK;
}

/* The domain of a configuration real, the same in both builds: the q16 range (|v| <= 32767;
 * the float build also refuses NaN and infinities) and, for a quantity that must be positive,
 * at least one q16 LSB (2^-16: the float build refuses subnormal and tiny values that would
 * make a reciprocal or a log infinite). */
static inline bool pft_cfg_real_ok_(pft_real_t v)
{
#ifdef PFT_NUMERIC_Q16
    (void)v;
    return true;
#else
    return v >= -32767.0f && v <= 32767.0f; /* false for NaN */
#endif
}
static inline bool pft_cfg_real_pos_(pft_real_t v)
{
#ifdef PFT_NUMERIC_Q16
    return v > 0;
#else
    return v >= 1.0f / 65536.0f && v <= 32767.0f;
#endif
}
/* Every element of a[0..n) in the domain. */
static inline bool pft_cfg_reals_ok_(const pft_real_t *a, size_t n)
{
    bool ok = true;
    for (size_t k = 0; k < n; ++k) {
        ok = ok && pft_cfg_real_ok_(a[k]);
    }
    return ok;
}

#endif
