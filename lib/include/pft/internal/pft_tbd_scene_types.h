/*
 * NOT API. Layout of the scene-motion test's instance, here only so that a firmware can
 * declare instances statically (sizeof) and PFT_TBD_SCENE_WORKSPACE_BYTES can be evaluated.
 * Fields may change in any release: read results through the calls of pft_tbd_scene.h, which
 * includes this file.
 */
#ifndef PFT_INTERNAL_TBD_SCENE_TYPES_H
#define PFT_INTERNAL_TBD_SCENE_TYPES_H

#include "pft/pft_tbd_scene.h"

#ifdef __cplusplus
extern "C" {
#endif

/** @cond internal */
/* One position of a track's history: Q16.16 px, and the scene's cumulative shift (Q16.16 px)
 * at that frame. */
typedef struct {
    int64_t sx;
    int64_t sy;
    int32_t x;
    int32_t y;
} pft_tbd_scene_pos_t;

/* One slot of the table: id 0 is a free slot. */
typedef struct {
    uint32_t id;
    uint32_t last;     /* frame count of the last update that fed it */
    uint32_t count;    /* positions held, 0..ring */
    uint32_t head;     /* ring index of the oldest position */
    uint32_t clutter;  /* 1: found moving with the scene */
    uint16_t mark;     /* scratch of one update: 1 while its id is in the update's list */
    uint16_t passed;   /* frames it passed the report tests, saturated at cfg.hold_frames (<= 64) */
} pft_tbd_scene_slot_t;
/** @endcond */

struct pft_tbd_scene_s {
    pft_tbd_scene_config_t cfg;
    pft_tbd_scene_slot_t *slot; /* cfg.max_tracks */
    pft_tbd_scene_pos_t *pos;   /* cfg.max_tracks * ring, slot k at k * ring */
    int64_t scene_x;            /* the scene's cumulative shift, Q16.16 px */
    int64_t scene_y;
    int32_t gate_q;             /* gate_px, early_px, fit_px in Q16.16 */
    int32_t early_q;
    int32_t fit_q;
    int32_t spread_q;           /* spread_px in Q16.16 */
    int32_t slow_low_q;         /* slow_low_px, slow_gate_px in Q16.16 */
    int32_t slow_q;
    int32_t exist_q;            /* spread_exist in Q16.16 (0: off, also with spread_px 0) */
    int32_t edge_q;             /* edge_px, edge_still_px, edge_shift_px in Q16.16 (edge_q 0: off) */
    int32_t edge_still_q;
    int32_t edge_shift_q;
    int32_t move_q;             /* move_px in Q16.16 (0: off, also with spread_px 0) */
    uint32_t move_need;         /* move_hold, or hold_frames for 0 */
    uint32_t ring;              /* positions kept per slot: max(frames, slow_frames) + 1 */
    uint32_t frame;             /* updates since init/reset */
    uint32_t overflows;         /* NO_SLOT decisions since init/reset */
};

#ifdef __cplusplus
}
#endif

#endif /* PFT_INTERNAL_TBD_SCENE_TYPES_H */
