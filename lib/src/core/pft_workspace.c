/*
 * Workspace carving: a bump allocator over one caller buffer. The start is aligned up to
 * PFT_WS_ALIGN and every take is rounded up to a multiple of it, so every returned pointer is
 * PFT_WS_ALIGN-aligned and the bytes used are exactly the sum of PFT_WS_ROUND(bytes) plus the
 * start padding (< PFT_WS_ALIGN).
 */
#include "pft/pft_workspace.h"

void pft_ws_init(pft_ws_t *ws, void *buf, size_t len)
{
    ws->base = NULL;
    ws->len = 0u;
    ws->used = 0u;
    ws->short_ = false;
    if (buf != NULL) {
        const uintptr_t addr = (uintptr_t)buf;
        const size_t pad = (size_t)((PFT_WS_ALIGN - (addr % PFT_WS_ALIGN)) % PFT_WS_ALIGN);
        if (pad <= len) {
            ws->base = (uint8_t *)buf + pad;
            ws->len = len - pad;
        } else {
            /* Not even the padding fits: an empty workspace at the aligned address would lie
             * outside the buffer, so keep none. */
            ws->len = 0u;
        }
    }
}

void *pft_ws_take(pft_ws_t *ws, size_t bytes)
{
    size_t rounded;
    void *p;
    if (ws == NULL) {
        return NULL;
    }
    if (bytes > (size_t)-1 - (PFT_WS_ALIGN - 1u)) {
        ws->short_ = true; /* rounding would wrap */
        return NULL;
    }
    rounded = PFT_WS_ROUND(bytes);
    if (ws->base == NULL) {
        /* No buffer: only empty takes succeed (they return NULL, which is not an error). */
        if (rounded != 0u) {
            ws->short_ = true;
        }
        return NULL;
    }
    if (rounded > ws->len - ws->used) {
        ws->short_ = true;
        return NULL;
    }
    p = ws->base + ws->used;
    ws->used += rounded;
    return p;
}
