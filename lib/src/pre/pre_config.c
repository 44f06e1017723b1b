/* Preprocessing stage: defaults, the configuration check that names the refused field, the
 * workspace, init/reset and the calls that copy results out. */
#include <string.h>

#include "pre_int.h"

void pft_pre_config_default(pft_pre_config_t *cfg)
{
    if (cfg == NULL) {
        return;
    }
    memset(cfg, 0, sizeof(*cfg));
    cfg->width = 384u;
    cfg->height = 288u;
    cfg->format = PFT_PIX_U16;
    cfg->bit_depth = 14u;
    cfg->method = PFT_PRE_BG_TEMPORAL;
    cfg->sat_level = 0u;
    cfg->dead_level = 0u;
    cfg->bad_map = NULL;
    cfg->local_outer = 4u;
    cfg->local_guard = 1u;
    cfg->bg_alpha = 9830u;
    cfg->reg_search = 8u;
    cfg->reg_iters = 2u;
    cfg->reg_step = 2u;
    cfg->warp_cubic = true;
    cfg->col_alpha = 4096u;
    cfg->tile = 32u;
    cfg->sigma_interp = true;
    cfg->sigma_current = true;
    cfg->sigma_floor = 8u;
    cfg->edge_k = 0u;
    cfg->peak_max = 64u;
    cfg->peak_threshold = 768;
    cfg->inplace = false;
    cfg->sigma_step = 1u;
    cfg->sigma_every = 1u;
    cfg->reg_bin = false;
    cfg->sigma_bracket = false;
    cfg->bg_anchor = false;
    cfg->bg_gate = 0u;
    cfg->bg_gate_shift = 0u;
    cfg->bg_gate_young = 0u;
    cfg->bg_gate_local = 0u;
    cfg->bg_masked_taps = 0u;
    cfg->bg_stale_reinit = 0u;
    cfg->bg_young_clip = 0u;
    cfg->sigma_level = false;
    cfg->bg_edge_narrow = 0u;
    cfg->bg_young_scale = false;
}

/* 2^bits - 1 of a configuration whose format and bit depth are valid. */
static uint32_t max_raw_(const pft_pre_config_t *c)
{
    return c->format == PFT_PIX_U8 ? 255u : (1u << c->bit_depth) - 1u;
}

/* Name of the first refused field of c, NULL when c is usable. */
static const char *refused_field_(const pft_pre_config_t *c)
{
    if (c->width < 8u || c->width > PFT_CFG_MAX_IMAGE_SIDE) {
        return "width";
    }
    if (c->height < 8u || c->height > PFT_CFG_MAX_IMAGE_SIDE) {
        return "height";
    }
    if (c->format != PFT_PIX_U16 && c->format != PFT_PIX_U8) {
        return "format";
    }
    if (c->format == PFT_PIX_U8 ? c->bit_depth != 8u
                                : (c->bit_depth < 8u || c->bit_depth > 16u)) {
        return "bit_depth";
    }
    if (c->method != PFT_PRE_BG_LOCAL && c->method != PFT_PRE_BG_TEMPORAL) {
        return "method";
    }
    const uint32_t top = max_raw_(c);
    if (c->sat_level > top || (c->sat_level != 0u && c->sat_level <= c->dead_level)) {
        return "sat_level";
    }
    if (c->dead_level >= top) {
        return "dead_level";
    }
    if (c->local_outer < 1u || c->local_outer > PFT_PRE_MAX_OUTER) {
        return "local_outer";
    }
    if (c->local_guard >= c->local_outer) {
        return "local_guard";
    }
    if (c->bg_alpha == 0u) {
        return "bg_alpha";
    }
    if (c->reg_search > PFT_PRE_MAX_SEARCH) {
        return "reg_search";
    }
    if (c->reg_iters > PFT_PRE_MAX_ITERS) {
        return "reg_iters";
    }
    if (c->reg_step < 1u || c->reg_step > 8u) {
        return "reg_step";
    }
    if (c->tile < PFT_PRE_MIN_TILE) {
        return "tile"; /* an uint8_t: never above PFT_PRE_MAX_TILE */
    }
    if (c->sigma_floor == 0u) {
        return "sigma_floor";
    }
    if (c->edge_k > PFT_PRE_MAX_EDGE_K || (c->edge_k != 0u && c->method != PFT_PRE_BG_TEMPORAL)) {
        return "edge_k";
    }
    if (c->peak_max > PFT_PRE_MAX_PEAKS) {
        return "peak_max";
    }
    if (c->peak_threshold < 1) {
        return "peak_threshold";
    }
    if (c->inplace && c->format != PFT_PIX_U16) {
        return "inplace"; /* a U8 frame has 1 byte per pixel, the residual 2 */
    }
    if (c->sigma_step > PFT_PRE_MAX_SIGMA_STEP || (uint32_t)c->tile < 8u * c->sigma_step) {
        return "sigma_step"; /* at least 8 x 8 samples in a whole tile */
    }
    if (c->sigma_every > PFT_PRE_MAX_SIGMA_EVERY) {
        return "sigma_every";
    }
    if (c->reg_bin && c->reg_step < 2u) {
        return "reg_bin"; /* boxes of 2 x 2 pixels on a grid of step 1 would overlap */
    }
    if (c->sigma_bracket && (c->sigma_step > 1u || c->sigma_every > 1u)) {
        return "sigma_bracket"; /* counts of every pixel of every frame */
    }
    if (c->bg_anchor && (c->method != PFT_PRE_BG_TEMPORAL || c->inplace || c->edge_k != 0u)) {
        return "bg_anchor"; /* the grid lives in scene coordinates: no in-place ring (not built)
                             * and no edge term (it reads the background in frame coordinates) */
    }
    if (c->bg_gate != 0u && (!c->bg_anchor || c->bg_gate < PFT_PRE_MIN_BG_GATE ||
                             c->bg_gate > PFT_PRE_MAX_BG_GATE)) {
        return "bg_gate"; /* built in the anchored update only */
    }
    if (c->bg_gate_shift > PFT_PRE_MAX_BG_GATE_SHIFT || (c->bg_gate_shift != 0u && c->bg_gate == 0u)) {
        return "bg_gate_shift";
    }
    if (c->bg_gate_young != 0u && c->bg_gate == 0u) {
        return "bg_gate_young"; /* the cells exempt from a gate */
    }
    if (c->bg_gate_local > PFT_PRE_GATE_LOCAL_RELATIVE || (c->bg_gate_local != 0u && c->bg_gate == 0u)) {
        return "bg_gate_local"; /* the local part is taken off the gate's innovation */
    }
    if (c->bg_masked_taps > PFT_PRE_MASKED_TAPS_ALL || (c->bg_masked_taps != 0u && !c->bg_anchor) ||
        (c->bg_masked_taps == PFT_PRE_MASKED_TAPS_YOUNG && c->bg_gate_young == 0u)) {
        return "bg_masked_taps"; /* built in the anchored update; the young columns are bg_gate_young's */
    }
    if (c->bg_stale_reinit > PFT_PRE_MAX_BG_STALE ||
        (c->bg_stale_reinit != 0u && c->method != PFT_PRE_BG_TEMPORAL)) {
        return "bg_stale_reinit"; /* ages up to 127 (never learnt) */
    }
    if (c->bg_young_clip != 0u && (c->bg_gate_young == 0u || c->bg_young_clip < PFT_PRE_MIN_BG_GATE ||
                                   c->bg_young_clip > PFT_PRE_MAX_BG_GATE)) {
        return "bg_young_clip"; /* acts on bg_gate_young's young cells */
    }
    if (c->sigma_level && (c->sigma_step > 1u || c->sigma_every > 1u || c->sigma_bracket)) {
        return "sigma_level"; /* built in the histogram of every pixel of every frame */
    }
    if (c->bg_edge_narrow > 1u || (c->bg_edge_narrow != 0u && !c->bg_anchor)) {
        return "bg_edge_narrow"; /* built in the anchored read and update */
    }
    if (c->bg_young_scale && c->bg_gate_young == 0u) {
        return "bg_young_scale"; /* reads bg_gate_young's ages */
    }
    return NULL;
}

pft_status_t pft_pre_config_check(const pft_pre_config_t *cfg, const char **field)
{
    if (field != NULL) {
        *field = NULL;
    }
    if (cfg == NULL) {
        return PFT_ERR_INVAL;
    }
    const char *bad = refused_field_(cfg);
    if (field != NULL) {
        *field = bad;
    }
    return bad == NULL ? PFT_OK : PFT_ERR_CONFIG;
}

size_t pft_pre_workspace_size(const pft_pre_config_t *c)
{
    if (pft_pre_config_check(c, NULL) != PFT_OK) {
        return 0u;
    }
    if (c->bg_anchor) {
        /* the ages of bg_gate_young and the tile sums of bg_gate_local, each beyond the grid */
        return PFT_PRE_WORKSPACE_BYTES_ANCHOR(c->width, c->height, c->local_outer, c->tile,
                                              c->peak_max) +
               (c->bg_gate_young != 0u ? PFT_PRE_YOUNG_BYTES(c->width, c->height) : 0u) +
               (c->bg_gate_local != 0u ? PFT_PRE_LOCAL_BYTES(c->width, c->height, c->tile) : 0u) +
               (c->bg_stale_reinit != 0u ? PFT_PRE_STALE_BYTES(c->width, c->height) : 0u) +
               (c->sigma_level ? PFT_PRE_LEVEL_BYTES(c->width, c->height, c->tile) : 0u);
    }
    return (c->inplace ? PFT_PRE_WORKSPACE_BYTES_INPLACE(c->width, c->height, c->method,
                                                         c->local_outer, c->tile, c->peak_max)
                       : PFT_PRE_WORKSPACE_BYTES(c->width, c->height, c->method, c->local_outer,
                                                 c->tile, c->peak_max)) +
           (c->bg_stale_reinit != 0u ? PFT_PRE_STALE_BYTES(c->width, c->height) : 0u) +
           (c->sigma_level ? PFT_PRE_LEVEL_BYTES(c->width, c->height, c->tile) : 0u);
}

pft_status_t pft_pre_init(pft_pre_t *p, const pft_pre_config_t *cfg, void *work,
                          size_t work_len)
{
    if (p == NULL || cfg == NULL || work == NULL) {
        return PFT_ERR_INVAL;
    }
    if (pft_pre_config_check(cfg, NULL) != PFT_OK) {
        return PFT_ERR_CONFIG;
    }
    const size_t w = cfg->width, h = cfg->height, npix = w * h;
    const size_t ntx = PFT_PRE_NT_(w, cfg->tile), nty = PFT_PRE_NT_(h, cfg->tile);
    const bool temporal = cfg->method == PFT_PRE_BG_TEMPORAL;
    const size_t ro = cfg->local_outer;
    pft_ws_t ws;
    pft_ws_init(&ws, work, work_len);
    int16_t *res = cfg->inplace ? NULL : pft_ws_take(&ws, npix * 2u);
    const bool anchor = cfg->bg_anchor;
    const size_t nbg = anchor ? (w + 3u) * (h + 3u) : npix;
    uint16_t *bg = temporal ? pft_ws_take(&ws, nbg * 2u) : NULL;
    int32_t *colq = pft_ws_take(&ws, w * 4u);
    int32_t *colnow = pft_ws_take(&ws, w * 4u);
    int32_t *csum = pft_ws_take(&ws, w * 4u);
    int32_t *line = pft_ws_take(&ws, w * 4u);
    uint16_t *hist = pft_ws_take(&ws, ntx * (PFT_PRE_BINS + 1u) * 2u);
    uint32_t *tsig = pft_ws_take(&ws, ntx * nty * 4u);
    uint32_t *tmul = pft_ws_take(&ws, ntx * nty * 4u);
    uint32_t *rowm = pft_ws_take(&ws, ntx * 4u);
    void *a = NULL, *b = NULL, *c = NULL, *d = NULL, *e = NULL, *g = NULL, *k = NULL;
    if (temporal) {
        a = pft_ws_take(&ws, w * 4u);
        b = pft_ws_take(&ws, w * 4u);
        c = pft_ws_take(&ws, w * 4u);
        k = pft_ws_take(&ws, w * 4u);
        g = pft_ws_take(&ws, w * 2u);
        d = pft_ws_take(&ws, h * 4u);
        e = pft_ws_take(&ws, h * 4u);
    } else {
        a = pft_ws_take(&ws, (w + 2u * ro + 2u) * 4u);
        b = pft_ws_take(&ws, (w + 2u * ro + 2u) * 4u);
        c = pft_ws_take(&ws, (2u * ro + 2u) * w * 4u);
    }
    pft_pre_peak_t *peaks = pft_ws_take(&ws, (size_t)cfg->peak_max * sizeof(pft_pre_peak_t));
    int32_t *aring = anchor ? pft_ws_take(&ws, 4u * (w + 3u) * 4u) : NULL;
    uint8_t *agex = anchor && cfg->bg_gate_young != 0u ? pft_ws_take(&ws, w + h + 6u) : NULL;
    /* bg_gate_local: per tile the sums of e and of B (int64), then m and the count (32 bits) */
    const bool glocal = cfg->bg_gate_local != 0u;
    int64_t *gsum = glocal ? pft_ws_take(&ws, ntx * nty * 16u) : NULL;
    int32_t *gm = glocal ? pft_ws_take(&ws, ntx * nty * 4u) : NULL;
    uint32_t *gcnt = glocal ? pft_ws_take(&ws, ntx * nty * 4u) : NULL;
    /* bg_stale_reinit: the ages (one byte per background value) and two lines */
    const bool stale = cfg->bg_stale_reinit != 0u;
    uint8_t *sage = stale ? pft_ws_take(&ws, (w + 3u) * (h + 3u)) : NULL;
    uint8_t *sline = stale ? pft_ws_take(&ws, 2u * (w + 3u) + h + 3u) : NULL;
    uint8_t *srow = stale ? pft_ws_take(&ws, h + 3u) : NULL;
    /* sigma_level: the tiles' levels, the sums and counts of one tile row */
    int32_t *tlev = cfg->sigma_level ? pft_ws_take(&ws, ntx * nty * 4u) : NULL;
    int32_t *lsum = cfg->sigma_level ? pft_ws_take(&ws, ntx * 8u) : NULL;
    if (pft_ws_status(&ws) != PFT_OK) {
        return PFT_ERR_NOMEM;
    }
    memset(p, 0, sizeof(*p));
    p->cfg = *cfg;
    p->rawmask = max_raw_(cfg);
    if (p->cfg.sat_level == 0u) {
        p->cfg.sat_level = (uint16_t)p->rawmask;
    }
    p->res = res;
    p->bg = bg;
    p->bgv = anchor ? (uint16_t *)(void *)res : bg; /* bg_anchor: the grid read into res */
    p->bgs = (uint32_t)w;
    p->aring = aring;
    p->agex = agex;
    p->agey = agex != NULL ? agex + w + 3u : NULL;
    p->gsum = gsum;
    p->sage = sage;
    p->sline = sline;
    p->srow = srow;
    p->tlev = tlev;
    p->lsum = lsum;
    p->gm = gm;
    p->gcnt = gcnt;
    p->colq = colq;
    p->colnow = colnow;
    p->csum = csum;
    p->line = line;
    p->hist = hist;
    p->tsig = tsig;
    p->tmul = tmul;
    p->rowm = rowm;
    if (temporal) {
        p->pzc = a;
        p->pbc = b;
        p->vb = c;
        p->bwl = k;
        p->prev = g;
        p->pzr = d;
        p->pbr = e;
    } else {
        p->colo = a;
        p->colg = b;
        p->ring = c;
    }
    p->peaks = peaks;
    p->ntx = (uint32_t)ntx;
    p->nty = (uint32_t)nty;
    const uint32_t bits = cfg->format == PFT_PIX_U8 ? 8u : cfg->bit_depth;
    p->rs = (uint8_t)(bits >= 15u ? 0u : 15u - bits);
    p->bf = (uint8_t)(16u - bits);
    /* bg_young_scale: (1 - alpha)^(2a + 1) per age a (Q16), and 1 / sqrt(1 + E) (Q15) at
     * E = j / 64, j = 0 .. 64 (docs/algorithms.md 9.13) */
    {
        const uint32_t q = 65536u - cfg->bg_alpha, q2 = (q * q + 32768u) >> 16;
        uint32_t ex = q;
        for (uint32_t i = 0u; i < PFT_PRE_YOUNG_AGES_; ++i) {
            /* an excess of 2/65536 or less scales by 1 in Q15 (the table of 1/sqrt(1 + E) between
             * its first two values): 0, so that old cells are not visited (the rounded recursion
             * would stay at 1 for ever) */
            p->yexc[i] = (uint16_t)(cfg->bg_young_scale && ex > 2u ? ex : 0u);
            ex = (ex * q2 + 32768u) >> 16;
        }
        for (uint32_t j = 0u; j < PFT_PRE_YOUNG_SC_; ++j) {
            const uint64_t den = (uint64_t)(65536u + 1024u * j);
            p->ysc[j] = (uint16_t)(cfg->bg_young_scale ? pft_pre_isqrt64_(((uint64_t)1 << 46) / den) : 0u);
        }
    }
    (void)pft_pre_reset(p);
    return PFT_OK;
}

pft_status_t pft_pre_reset(pft_pre_t *p)
{
    if (p == NULL || p->line == NULL) {
        return PFT_ERR_INVAL;
    }
    const size_t w = p->cfg.width, h = p->cfg.height, npix = w * h;
    const size_t nt = (size_t)p->ntx * p->nty;
    if (p->cfg.inplace) {
        p->res = NULL; /* the caller's buffer: not ours to clear */
    } else {
        memset(p->res, 0, npix * 2u);
    }
    if (p->bg != NULL) {
        memset(p->bg, 0, (p->cfg.bg_anchor ? (w + 3u) * (h + 3u) : npix) * 2u);
        if (p->aring != NULL) {
            memset(p->aring, 0, 4u * (w + 3u) * 4u);
        }
        if (p->agex != NULL) {
            memset(p->agex, 0, w + h + 6u);
        }
        if (p->sage != NULL) {
            memset(p->sage, 0, (w + 3u) * (h + 3u));
            memset(p->sline, 0, 2u * (w + 3u) + h + 3u);
            memset(p->srow, 0, h + 3u);
        }
        memset(p->pzc, 0, w * 4u);
        memset(p->pbc, 0, w * 4u);
        memset(p->vb, 0, w * 4u);
        memset(p->bwl, 0, w * 4u);
        memset(p->prev, 0, w * 2u);
        memset(p->pzr, 0, h * 4u);
        memset(p->pbr, 0, h * 4u);
    } else {
        const size_t ro = p->cfg.local_outer;
        memset(p->colo, 0, (w + 2u * ro + 2u) * 4u);
        memset(p->colg, 0, (w + 2u * ro + 2u) * 4u);
        memset(p->ring, 0, (2u * ro + 2u) * w * 4u);
    }
    memset(p->colq, 0, w * 4u);
    memset(p->colnow, 0, w * 4u);
    memset(p->csum, 0, w * 4u);
    memset(p->line, 0, w * 4u);
    memset(p->hist, 0, (size_t)p->ntx * (PFT_PRE_BINS + 1u) * 2u);
    memset(p->tsig, 0, nt * 4u);
    memset(p->tmul, 0, nt * 4u);
    memset(p->rowm, 0, (size_t)p->ntx * 4u);
    if (p->gsum != NULL) {
        memset(p->gsum, 0, nt * 16u);
        memset(p->gm, 0, nt * 4u);
        memset(p->gcnt, 0, nt * 4u);
    }
    if (p->tlev != NULL) {
        memset(p->tlev, 0, nt * 4u);
        memset(p->lsum, 0, (size_t)p->ntx * 8u);
    }
    if (p->cfg.peak_max > 0u) {
        memset(p->peaks, 0, (size_t)p->cfg.peak_max * sizeof(pft_pre_peak_t));
    }
    p->frames = 0u;
    p->bg_frames = 0u;
    p->last_seq = 0u;
    p->shift_prev[0] = 0;
    p->shift_prev[1] = 0;
    p->jumped = false;
    p->aphi[0] = 0;
    p->aphi[1] = 0;
    p->avlo[0] = 0;
    p->avlo[1] = 0;
    p->avhi[0] = -1;
    p->avhi[1] = -1;
    memset(&p->st, 0, sizeof(p->st));
    p->n_peaks = 0u;
    p->sig_known = false;
    p->fused = false;
    p->last_row = -1;
    return PFT_OK;
}

pft_status_t pft_pre_frame(const pft_pre_t *p, pft_frame_t *out)
{
    if (p == NULL || out == NULL) {
        return PFT_ERR_INVAL;
    }
    if (p->frames == 0u) {
        return PFT_ERR_STATE;
    }
    memset(out, 0, sizeof(*out));
    out->data = p->res;
    out->width = p->cfg.width;
    out->height = p->cfg.height;
    out->stride_bytes = 2u * (uint32_t)p->cfg.width;
    out->format = PFT_PIX_RES16;
    out->bit_depth = 16u;
    out->timestamp_us = p->st.timestamp_us;
    out->seq = p->st.seq;
    return PFT_OK;
}

pft_status_t pft_pre_stats(const pft_pre_t *p, pft_pre_stats_t *out)
{
    if (p == NULL || out == NULL) {
        return PFT_ERR_INVAL;
    }
    *out = p->st;
    return PFT_OK;
}

size_t pft_pre_peaks(const pft_pre_t *p, pft_pre_peak_t *out, size_t max)
{
    if (p == NULL) {
        return 0u;
    }
    const size_t n = p->n_peaks;
    if (out != NULL && max > 0u && n > 0u) {
        memcpy(out, p->peaks, (n < max ? n : max) * sizeof(pft_pre_peak_t));
    }
    return n;
}

size_t pft_pre_sigma(const pft_pre_t *p, uint32_t *out, size_t max)
{
    if (p == NULL) {
        return 0u;
    }
    const size_t n = (size_t)p->ntx * p->nty;
    const uint32_t sh = 12u - p->rs; /* R Q4 -> counts Q16 */
    for (size_t i = 0; out != NULL && i < n && i < max; ++i) {
        out[i] = (p->tsig[i] & ~PFT_PRE_TILE_STALE_) << sh;
    }
    return n;
}
