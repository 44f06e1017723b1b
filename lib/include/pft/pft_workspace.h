/**
 * @file pft_workspace.h
 * @brief Carving typed buffers out of one caller-provided workspace (no malloc).
 *
 * Convention for every module XXX:
 *   size_t pft_xxx_workspace_size(const pft_xxx_config_t *cfg);  exact bytes needed
 *   PFT_XXX_WORKSPACE_BYTES(...)                                 same, as a constant expression
 *   pft_status_t pft_xxx_init(pft_xxx_t *inst, const pft_xxx_config_t *cfg,
 *                             void *work, size_t work_len);      PFT_ERR_NOMEM if short
 * Buffers are carved in a fixed order, each aligned to PFT_WS_ALIGN, so the size formula is
 * the sum of PFT_WS_ROUND(count * sizeof(elem)) over the buffers, plus PFT_WS_ALIGN - 1 for an
 * unaligned start.
 */
#ifndef PFT_WORKSPACE_H
#define PFT_WORKSPACE_H

#include "pft/pft_types.h"

#ifdef __cplusplus
extern "C" {
#endif

/** Alignment of every buffer carved from a workspace (bytes). */
#define PFT_WS_ALIGN 8u
/** bytes rounded up to a multiple of PFT_WS_ALIGN (a constant expression for constants). */
#define PFT_WS_ROUND(bytes) ((((size_t)(bytes)) + (PFT_WS_ALIGN - 1u)) & ~(size_t)(PFT_WS_ALIGN - 1u))

/** A workspace being carved: set up by pft_ws_init, consumed by pft_ws_take. */
typedef struct {
    uint8_t *base; /**< aligned start of the usable buffer (NULL: empty workspace) */
    size_t len;    /**< usable bytes from base */
    size_t used;   /**< bytes already carved */
    bool short_; /**< set once any carve failed */
} pft_ws_t;

/** Starts carving from buf[0..len); the start is aligned up to PFT_WS_ALIGN. A NULL buf, or
 *  one shorter than its alignment padding, gives an empty workspace. */
void pft_ws_init(pft_ws_t *ws, void *buf, size_t len);
/** Next buffer of `bytes` (rounded up to PFT_WS_ALIGN), or NULL (and ws->short_ set) when it
 *  does not fit. A failure is sticky for pft_ws_status, later takes that fit still succeed.
 *  A zero-byte take never fails; it returns NULL when the workspace has no buffer. */
void *pft_ws_take(pft_ws_t *ws, size_t bytes);
/** PFT_OK if every carve fitted, else PFT_ERR_NOMEM. */
static inline pft_status_t pft_ws_status(const pft_ws_t *ws)
{
    return ws->short_ ? PFT_ERR_NOMEM : PFT_OK;
}

#ifdef __cplusplus
}
#endif
#endif
