/* The verdict of a tracker's config_check (private, not installed): one place for the contract
 * of docs/design.md ("One API pattern for every tracker"): PFT_ERR_INVAL for a NULL
 * configuration, PFT_ERR_CONFIG naming the first refused field in *field, PFT_OK with *field
 * NULL; field itself may be NULL. */
#ifndef PFT_CORE_CONFIG_INT_H
#define PFT_CORE_CONFIG_INT_H

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

#endif
