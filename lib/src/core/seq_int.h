/* Sequence numbers of frames (pft_types.h pft_seq_mode_t, docs/design.md "Time, sequence
 * numbers and lost frames"): the one rule every frame-fed tracker applies before it touches its
 * state. Not API. */
#ifndef PFT_SEQ_INT_H
#define PFT_SEQ_INT_H

#include "pft/pft_types.h"

/* Frame periods from the last accepted frame (last, valid when have) to seq, in *k:
 * 1 with PFT_SEQ_IGNORE or without a reference; seq - last (uint32, wrap-safe) when it is in
 * 1..max_gap; 0 when it is above max_gap (the caller restarts). PFT_ERR_SEQ (*k = 0) for a
 * duplicate (difference 0) or a number from the past (difference >= 2^31). */
static inline pft_status_t pft_seq_gap_(pft_seq_mode_t mode, uint32_t max_gap, bool have,
                                        uint32_t last, uint32_t seq, uint32_t *k)
{
    uint32_t d = seq - last;
    *k = 1u;
    if (mode != PFT_SEQ_USE || !have) {
        return PFT_OK;
    }
    if (d == 0u || d >= 0x80000000u) {
        *k = 0u;
        return PFT_ERR_SEQ;
    }
    *k = d > max_gap ? 0u : d;
    return PFT_OK;
}

#endif
