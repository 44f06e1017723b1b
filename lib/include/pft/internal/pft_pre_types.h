/*
 * NOT API. Layout of the preprocessing instance, here only so that a firmware can declare
 * instances statically (sizeof) and PFT_PRE_WORKSPACE_BYTES can be evaluated. Fields may
 * change in any release: read results through the calls of pft_pre.h, which includes this
 * file.
 */
#ifndef PFT_INTERNAL_PRE_TYPES_H
#define PFT_INTERNAL_PRE_TYPES_H

#include "pft/pft_pre.h"

#ifdef __cplusplus
extern "C" {
#endif

/** @cond internal */
/* Tiles along a side of n pixels. */
#define PFT_PRE_NT_(n, t) (((size_t)(n) + (size_t)(t) - 1u) / (size_t)(t))
/* bg_young_scale: the ages of the table of excess variances (64 on: old) and the scale table's entries */
#define PFT_PRE_YOUNG_AGES_ 64u
#define PFT_PRE_YOUNG_SC_ 65u
/** @endcond */

struct pft_pre_s {
    pft_pre_config_t cfg;  /* sat_level resolved */
    /* workspace buffers */
    int16_t *res;          /* residual (R units) then whitened (Q8.8), w * h; inplace: the
                              caller's frame buffer of the last accepted update (NULL before) */
    uint16_t *bg;          /* TEMPORAL background (U units), w * h; bg_anchor: (w + 3) * (h + 3) cells */
    uint16_t *bgv;         /* the background as registration reads it: bg, or (bg_anchor) the grid read at the last frame's position into res */
    uint32_t bgs;          /* row stride of bgv (elements): w */
    int32_t *aring;        /* bg_anchor: 4 frame rows interpolated along x, (w + 3) each (the slot of row y - 4 also the residual's vertical blends of row y) */
    uint8_t *agex, *agey;  /* bg_gate_young: frames each grid column (w + 3) and row (h + 3) has held the scene before this frame, saturating at 255 (NULL without it) */
    uint8_t *sage;         /* bg_stale_reinit: the age of every background value (frames since learnt, 127: never; w * h, bg_anchor (w + 3) * (h + 3)) (NULL without it) */
    uint8_t *sline;        /* bg_stale_reinit: scratch, 2 (w + 3) + h + 3 bytes */
    uint8_t *srow;         /* bg_stale_reinit: the largest age of each row (h; bg_anchor h + 3 grid rows, an upper bound), with PFT_PRE_AGE_STALE_ (128) on a re-warped row with stale pixels */
    int64_t *gsum;         /* bg_gate_local: per tile the sums of the innovation e and (relative) of the level B over the cells updated in this frame, U units, 2 * ntx * nty (NULL without it) */
    int32_t *gm;           /* bg_gate_local: per tile m of the last frame's update (mean: U units; relative: rho, Q16), ntx * nty */
    uint32_t *gcnt;        /* bg_gate_local: per tile the cells in gsum, ntx * nty */
    int32_t *tlev;         /* sigma_level: per tile the level c its sigma is taken about (R units), ntx * nty (NULL without it) */
    int32_t *lsum;         /* sigma_level: per tile column of the current tile row the sum of the clipped residual and the count, 2 * ntx */
    int32_t *colq;         /* column offsets, R units Q8 */
    int32_t *colnow;       /* this frame's column offsets in working units */
    int32_t *csum;         /* column sums of the clipped residual (R units) */
    uint16_t *hist;        /* histograms of one tile row, ntx * PFT_PRE_BINS */
    uint32_t *tsig;        /* sigma per tile, R units Q4 (0: unknown) */
    uint32_t *tmul;        /* 2^28 / sigma per tile */
    uint32_t *rowm;        /* multipliers of one row at the tile columns (interpolation) */
    int32_t *pzc, *pbc;    /* TEMPORAL column projections of z and of b */
    int32_t *pzr, *pbr;    /* TEMPORAL row projections */
    int32_t *line;         /* one row: TEMPORAL z - c in U units (-1: masked), LOCAL b (R units) */
    int32_t *vb;           /* TEMPORAL vertical blend of the tap rows of one row; bg_anchor: with bwl, the converted frame rows y and y - 1 (in turns) */
    int32_t *bwl;          /* TEMPORAL background prediction of one row; bg_anchor: with vb, the converted frame rows y and y - 1 */
    uint16_t *prev;        /* TEMPORAL former values of the background row written last; bg_anchor with bg_young_scale: the columns' excess of this frame (Q16) */
    uint32_t *colo, *colg; /* LOCAL column sums (outer, guard), padded by ro + 1 each side */
    uint32_t *ring;        /* LOCAL packed rows, (2 ro + 2) * w */
    pft_pre_peak_t *peaks; /* heap during a frame, sorted after it */
    /* derived */
    uint32_t ntx, nty;     /* tiles per row, per column */
    uint32_t rawmask;      /* 2^bits - 1 */
    uint8_t rs;            /* fraction bits of the residual */
    uint8_t bf;            /* fraction bits of the background */
    uint16_t yexc[PFT_PRE_YOUNG_AGES_]; /* bg_young_scale: per age a the excess variance of a young cell's residual, (1 - alpha)^(2a + 1), Q16 */
    uint16_t ysc[PFT_PRE_YOUNG_SC_];    /* bg_young_scale: the scale 1 / sqrt(1 + E) at E = 1024 j / 65536, Q15 (32768 = 1) */
    /* state */
    uint32_t frames;       /* accepted since init/reset */
    uint32_t bg_frames;    /* frames in the background since it was (re)started */
    uint32_t last_seq;
    int32_t shift_prev[2]; /* last shift, Q16.16 px (the prediction's base) */
    bool jumped;           /* this frame: the integer search found a jump */
    int32_t aphi[2];       /* bg_anchor: fraction of the scene position of pixel (0, 0), Q16 in [0, 65536) */
    int32_t avlo[2], avhi[2]; /* bg_anchor: cells (x, then y; -1 .. w + 1) holding the scene, inclusive */
    pft_pre_stats_t st;
    uint32_t n_peaks;
    bool sig_known;        /* some tile sigma was estimated since init/reset */
    bool fused;            /* this frame: rows whitened as they are made (last frame's sigmas) */
    int32_t last_row;      /* fused: the row made last (-1: none) */
};

struct pft_pre_clutter_s {
    pft_pre_clutter_config_t cfg;
    uint16_t *m;           /* map, sigma^2 Q6.10, w * h (NULL with cfg.map8) */
    uint8_t *m8;           /* map8: the map's 8-bit codes, w * h (NULL without cfg.map8) */
    uint16_t *row;         /* map8: the row being updated, decoded, w (NULL without cfg.map8) */
    uint16_t *mu;          /* mean, sigma Q4.11 plus 32768, w * h (NULL without cfg.mean) */
    uint16_t *pc;          /* persistence counter, frames Q8, w * h (NULL without cfg.persist) */
    int16_t *out;          /* output, Q8.8 sigma, w * h (inplace: the caller's buffer of the last update, NULL before) */
    uint16_t *ring;        /* former values of the last blur + 1 rows, (blur + 1) * w (map8: the decoded rows y - blur .. y + blur, (2 blur + 1) * w) */
    uint32_t *vs;          /* vertical sums (or maxima) of one row; the warp's row buffer; c of a row with the mean */
    uint32_t *hs;          /* the square's sums (or maxima) of one row; the warp's row buffer */
    uint32_t *acc;         /* block: per block of a row, the sum of t and the count; per pixel with map8: the fused warp's two carried rows (NULL per pixel without map8) */
    int32_t *sacc;         /* block: per block of a row, the sums of clamp(8 r) and r (NULL per pixel) */
    uint8_t *age;          /* floor_age: the ages of the w columns, then of the h rows, frames capped at floor_age (NULL without) */
    uint32_t gw, gh;       /* the map's grid: w x h, or the blocks' ceil(w / B) x ceil(h / B) */
    uint32_t lb;           /* log2(B), 0 per pixel */
    int64_t ax, ay;        /* anchor: the sum of the shifts given since init/reset, Q16.16 px */
    int64_t px, py;        /* anchor: the rounded position at which the stored arrays lie, px */
    uint32_t frames;       /* frames with evidence since init/reset */
    uint32_t updates;      /* accepted updates since init/reset */
    uint32_t seq;
    uint64_t timestamp_us;
};

struct pft_pre_flat_s {
    pft_pre_flat_config_t cfg;
    int32_t *m;            /* map per block: running mean, sigma Q16 (relative: sigma per count Q24), nbx * nby */
    int32_t *sum;          /* this frame's sums of the gated residual per block, Q8.8 */
    uint32_t *cnt;         /* this frame's pixels per block that entered the sum */
    uint32_t *lsum;        /* relative: this frame's sums of their levels (counts) per block */
    int32_t *rowv;         /* the map interpolated to one row at the block columns, sigma Q16 */
    uint32_t nbx, nby;     /* blocks per row, per column */
    uint32_t lb;           /* log2(block) */
    uint32_t frames;       /* frames with evidence since init/reset */
    int32_t *sc;           /* rescale: per block the corrected residual's robust sd, sigma Q16 (NULL without) */
    int32_t *sq;           /* rescale: per block the multiplier 2^32 / sc (Q16) */
    uint32_t *nall;        /* rescale: this frame's unmasked pixels per block */
    uint32_t *nlo;         /* rescale: this frame's pixels per block with |v| <= 0.6745 sc */
    int32_t *rowq;         /* rescale: the multipliers interpolated to one row at the block columns */
};

#ifdef __cplusplus
}
#endif
#endif
