/* Multi-target RBPF-TBD / PF-TBD manager: search layer + track layers (docs/algorithms.md 2.6-2.7). */
#include <stddef.h>
#include <string.h>

#include "tbd_int.h"
#include "../core/seq_int.h"

size_t pft_tbd_workspace_size(const pft_tbd_config_t *cfg)
{
    if (pft_tbd_config_check(cfg, NULL) != PFT_OK) {
        return 0u;
    }
    const size_t integ =
        cfg->integ_alpha > PFT_C(0.0) ? PFT_TBD_INTEG_BYTES(cfg->width, cfg->height) : 0u;
    const size_t layers =
        PFT_TBD_SEARCH_BYTES(cfg->search_layers, cfg->width, cfg->height, cfg->birth_peaks);
    if (cfg->frame_format == PFT_PIX_RES16) {
        return PFT_TBD_WORKSPACE_BYTES_RES16(cfg->n_search, cfg->n_track, cfg->max_targets,
                                             cfg->kind, cfg->width, cfg->height,
                                             cfg->birth_peaks) +
               integ + layers;
    }
    return PFT_TBD_WORKSPACE_BYTES_PEAKS(cfg->n_search, cfg->n_track, cfg->max_targets,
                                         cfg->kind, cfg->width, cfg->height, cfg->birth_peaks) +
           integ + layers;
}

/* Search layers (cfg.search_layers, docs/algorithms.md 2.14): H >= 1. */
static uint32_t layers_n_(const pft_tbd_config_t *cfg)
{
    return cfg->search_layers >= 2u ? (uint32_t)cfg->search_layers : 1u;
}

/* Search layer h (0: t->search). */
static pft_tbd_filter_t *layer_(pft_tbd_t *t, uint32_t h)
{
    return h == 0u ? &t->search : &t->search_x[h - 1u];
}

static const pft_tbd_filter_t *layer_c_(const pft_tbd_t *t, uint32_t h)
{
    return h == 0u ? &t->search : &t->search_x[h - 1u];
}

/* Its confirmation count. */
static uint8_t *above_(pft_tbd_t *t, uint32_t h)
{
    return h == 0u ? &t->above : &t->above_x[h - 1u];
}

/* The integration's bins (cfg.integ_alpha > 0): 2 x 2 pixels each, 0 when off. */
static size_t integ_n_(const pft_tbd_config_t *cfg)
{
    return cfg->integ_alpha > PFT_C(0.0)
               ? (((size_t)cfg->width + 1u) / 2u) * (((size_t)cfg->height + 1u) / 2u)
               : 0u;
}

/* Birth candidate slots: one per pixel for B_k, K with birth peaks (PFT_TBD_CAND_N_). */
static size_t cand_n_(const pft_tbd_config_t *cfg)
{
    return PFT_TBD_CAND_N_(cfg->width, cfg->height, cfg->birth_peaks);
}

/* Per-line counts: w + h + 1 (the peak scan's rows and tiles, the hand-over gate). */
static size_t lines_n_(const pft_tbd_config_t *cfg)
{
    return (size_t)cfg->width + cfg->height + 1u;
}

/* The frame is read in place (cfg.frame_format PFT_PIX_RES16): no real-valued frame. */
static bool in_place_(const pft_tbd_config_t *cfg) { return cfg->frame_format == PFT_PIX_RES16; }

/* Reals of the real-valued frame (0 when the frame is read in place). */
static size_t img_n_(const pft_tbd_config_t *cfg)
{
    return in_place_(cfg) ? 0u : pft_tbd_img_len_(cfg->width, cfg->height);
}

/* Carves every buffer of the manager from ws. With commit == false nothing is written
 * anywhere (a dry run that only checks the size). */
static void carve_all_(pft_tbd_t *t, const pft_tbd_config_t *cfg, pft_ws_t *ws, bool commit)
{
    const size_t nimg = img_n_(cfg);
    pft_real_t *img = nimg > 0u ? (pft_real_t *)pft_ws_take(ws, nimg * sizeof(pft_real_t)) : NULL;
    uint32_t *mask =
        (uint32_t *)pft_ws_take(ws, pft_tbd_mask_len_(cfg->width, cfg->height) * sizeof(uint32_t));
    uint32_t *cand = (uint32_t *)pft_ws_take(ws, cand_n_(cfg) * sizeof(uint32_t));
    pft_tbd_tab_t *tab = (pft_tbd_tab_t *)pft_ws_take(ws, sizeof(pft_tbd_tab_t));
    pft_tbd_filter_t *tracks =
        (pft_tbd_filter_t *)pft_ws_take(ws, (size_t)cfg->max_targets * sizeof(pft_tbd_filter_t));
    pft_tbd_track_t *records =
        (pft_tbd_track_t *)pft_ws_take(ws, (size_t)cfg->max_targets * sizeof(pft_tbd_track_t));
    pft_tbd_event_t *events = (pft_tbd_event_t *)pft_ws_take(
        ws, ((size_t)cfg->max_targets + 1u) * sizeof(pft_tbd_event_t));
    pft_tbd_filter_t scratch;
    pft_real_t *res = NULL;
    uint32_t *lines = NULL;
    pft_real_t *peak_rows = NULL;
    pft_real_t *peak_val = NULL;
    pft_tbd_filter_t *sf = commit ? &t->search : &scratch;
    sf->n = cfg->n_search;
    sf->kind = cfg->kind;
    pft_tbd_particles_carve_(sf, ws);
    for (uint32_t k = 0; k < cfg->max_targets; ++k) {
        pft_tbd_filter_t *tf = commit ? &tracks[k] : &scratch;
        tf->n = cfg->n_track;
        tf->kind = cfg->kind;
        pft_tbd_particles_carve_(tf, ws);
    }
    res = (pft_real_t *)pft_ws_take(ws, (size_t)cfg->max_targets * PFT_TBD_PSF_SAVE_REALS_ *
                                            sizeof(pft_real_t));
    lines = (uint32_t *)pft_ws_take(ws, lines_n_(cfg) * sizeof(uint32_t));
    if (cfg->birth_peaks > 0u) {
        /* after every other buffer: the layout without peaks is unchanged */
        peak_rows = (pft_real_t *)pft_ws_take(ws, 6u * (size_t)cfg->width * sizeof(pft_real_t));
        peak_val = (pft_real_t *)pft_ws_take(ws, (size_t)cfg->birth_peaks * sizeof(pft_real_t));
    }
    int32_t *prect = NULL;
    uint8_t *pflag = NULL;
    pft_real_t *rowbuf = NULL;
    if (in_place_(cfg)) {
        /* after every other buffer: the frame's patches, row flags, row and window scratch */
        prect = (int32_t *)pft_ws_take(ws, 4u * (size_t)cfg->max_targets * sizeof(int32_t));
        pflag = (uint8_t *)pft_ws_take(ws, (size_t)cfg->height);
        rowbuf = (pft_real_t *)pft_ws_take(
            ws, ((size_t)cfg->width + 2u + PFT_TBD_WIN_REALS_) * sizeof(pft_real_t));
    }
    uint16_t *integ0 = NULL;
    uint16_t *integ1 = NULL;
    if (integ_n_(cfg) > 0u) {
        /* after every other buffer: the layout without the integration is unchanged */
        integ0 = (uint16_t *)pft_ws_take(ws, integ_n_(cfg) * sizeof(uint16_t));
        integ1 = (uint16_t *)pft_ws_take(ws, integ_n_(cfg) * sizeof(uint16_t));
    }
    pft_tbd_filter_t *search_x = NULL;
    uint32_t *cand_x = NULL;
    if (layers_n_(cfg) > 1u) {
        /* after every other buffer: the layout with one search layer is unchanged */
        search_x = (pft_tbd_filter_t *)pft_ws_take(
            ws, (size_t)(layers_n_(cfg) - 1u) * sizeof(pft_tbd_filter_t));
        cand_x = (uint32_t *)pft_ws_take(ws, cand_n_(cfg) * sizeof(uint32_t));
    }
    if (commit) {
        t->search_x = search_x;
        t->cand_x = cand_x;
        t->integ[0] = integ0;
        t->integ[1] = integ1;
        t->base = nimg > 0u ? (void *)img : (void *)mask;
        t->prect = prect;
        t->pflag = pflag;
        t->rowbuf = rowbuf;
        t->peak_rows = peak_rows;
        t->peak_val = peak_val;
        t->res = res;
        t->tab = tab;
        t->img = img;
        t->mask = mask;
        t->cand = cand;
        t->lines = lines;
        t->tracks = tracks;
        t->records = records;
        t->events = events;
    }
}

/* Sets up t (cfg checked, work_len enough) on work: every layer seeded, no tracks. */
static void build_(pft_tbd_t *t, const pft_tbd_config_t *cfg, void *work, size_t work_len)
{
    if (cfg != &t->cfg) {
        memset(t, 0, sizeof(*t));
        t->cfg = *cfg;
    } else {
        /* pft_tbd_reset: the instance's own configuration stays in place (no copy of it on the
         * stack), everything around it is cleared as above */
        const size_t off = offsetof(pft_tbd_t, cfg);
        const size_t end = off + sizeof(t->cfg);
        memset(t, 0, off);
        memset((unsigned char *)t + end, 0, sizeof(*t) - end);
    }
    /* setup_ clears a filter's buffer pointers: set up first, carve after. */
    pft_tbd_filter_setup_(&t->search, cfg, cfg->n_search, cfg->kind, true,
                          cfg->force_constraint, cfg->seed);
    pft_ws_t ws2;
    pft_ws_init(&ws2, work, work_len);
    const size_t nimg = img_n_(cfg);
    if (nimg > 0u) {
        (void)pft_ws_take(&ws2, nimg * sizeof(pft_real_t));
    }
    (void)pft_ws_take(&ws2, pft_tbd_mask_len_(cfg->width, cfg->height) * sizeof(uint32_t));
    (void)pft_ws_take(&ws2, cand_n_(cfg) * sizeof(uint32_t));
    (void)pft_ws_take(&ws2, sizeof(pft_tbd_tab_t));
    pft_tbd_filter_t *tracks =
        (pft_tbd_filter_t *)pft_ws_take(&ws2, (size_t)cfg->max_targets * sizeof(pft_tbd_filter_t));
    for (uint32_t k = 0; k < cfg->max_targets; ++k) {
        pft_tbd_filter_setup_(&tracks[k], cfg, cfg->n_track, cfg->kind, false, false,
                              cfg->seed + 1u + k);
    }
    pft_ws_init(&ws2, work, work_len);
    carve_all_(t, cfg, &ws2, true);
    pft_tbd_tab_setup_(t->tab, cfg);
    t->search.tab = t->tab;
    for (uint32_t k = 0; k < cfg->max_targets; ++k) {
        t->tracks[k].tab = t->tab;
    }
    if (nimg > 0u) {
        memset(t->img, 0, nimg * sizeof(pft_real_t));
    } else {
        memset(t->prect, 0, 4u * (size_t)cfg->max_targets * sizeof(int32_t));
        memset(t->pflag, 0, (size_t)cfg->height);
        memset(t->rowbuf, 0, ((size_t)cfg->width + 2u + PFT_TBD_WIN_REALS_) * sizeof(pft_real_t));
    }
    memset(t->res, 0, (size_t)cfg->max_targets * PFT_TBD_PSF_SAVE_REALS_ * sizeof(pft_real_t));
    memset(t->mask, 0, pft_tbd_mask_len_(cfg->width, cfg->height) * sizeof(uint32_t));
    memset(t->cand, 0, cand_n_(cfg) * sizeof(uint32_t));
    memset(t->lines, 0, lines_n_(cfg) * sizeof(uint32_t));
    memset(t->records, 0, (size_t)cfg->max_targets * sizeof(pft_tbd_track_t));
    memset(t->events, 0, ((size_t)cfg->max_targets + 1u) * sizeof(pft_tbd_event_t));
    if (cfg->birth_peaks > 0u) {
        memset(t->peak_rows, 0, 6u * (size_t)cfg->width * sizeof(pft_real_t));
        memset(t->peak_val, 0, (size_t)cfg->birth_peaks * sizeof(pft_real_t));
    }
    if (integ_n_(cfg) > 0u) {
        memset(t->integ[0], 0, integ_n_(cfg) * sizeof(uint16_t));
        memset(t->integ[1], 0, integ_n_(cfg) * sizeof(uint16_t));
    }
    pft_tbd_filter_clear_(&t->search);
    for (uint32_t k = 0; k < cfg->max_targets; ++k) {
        pft_tbd_filter_clear_(&t->tracks[k]);
    }
    const uint32_t nl = layers_n_(cfg);
    if (nl > 1u) {
        /* the search layers (docs/algorithms.md 2.14): layer h runs on the h-th of nl equal
         * slices of the n_search particles (cleared above), its generator seeded apart */
        const uint32_t m = cfg->n_search / nl;
        memset(t->cand_x, 0, cand_n_(cfg) * sizeof(uint32_t));
        for (uint32_t h = 1u; h < nl; ++h) {
            pft_tbd_filter_t *f = &t->search_x[h - 1u];
            pft_tbd_filter_setup_(f, cfg, m, cfg->kind, true, cfg->force_constraint,
                                  cfg->seed + ((uint64_t)h << 32));
            const size_t o = (size_t)h * m;
            f->cur.x = t->search.cur.x + o;
            f->cur.y = t->search.cur.y + o;
            f->cur.in = t->search.cur.in + o;
            f->cur.vx = t->search.cur.vx + o;
            f->cur.vy = t->search.cur.vy + o;
            f->cur.e = t->search.cur.e + o;
            f->cur.w = t->search.cur.w + o;
            f->tab = t->tab;
        }
        t->search.n = m;
        t->search.log_n = pft_log_count_(m);
    }
    t->next_id = 1u;
}

pft_status_t pft_tbd_init(pft_tbd_t *t, const pft_tbd_config_t *cfg, void *work, size_t work_len)
{
    if (t == NULL || cfg == NULL || work == NULL) {
        return PFT_ERR_INVAL;
    }
    if (pft_tbd_config_check(cfg, NULL) != PFT_OK) {
        return PFT_ERR_CONFIG;
    }
    pft_ws_t ws;
    pft_ws_init(&ws, work, work_len);
    carve_all_(t, cfg, &ws, false);
    if (pft_ws_status(&ws) != PFT_OK) {
        return PFT_ERR_NOMEM;
    }
    build_(t, cfg, work, work_len);
    return PFT_OK;
}

pft_status_t pft_tbd_reset(pft_tbd_t *t)
{
    if (t == NULL) {
        return PFT_ERR_INVAL;
    }
    if (t->base == NULL) {
        return PFT_ERR_STATE;
    }
    /* the workspace starts at the (aligned) first buffer: build it again from there, with the
     * configuration kept where it is */
    const size_t len = pft_tbd_workspace_size(&t->cfg) - (PFT_WS_ALIGN - 1u);
    build_(t, &t->cfg, t->base, len);
    return PFT_OK;
}

uint32_t pft_tbd_frame(const pft_tbd_t *t) { return t == NULL ? 0u : t->frame; }

static uint32_t count_alive_(const pft_tbd_filter_t *f)
{
    uint32_t a = 0;
    for (uint32_t s = 0; s < f->n; ++s) {
        a += f->cur.e[s] != 0u ? 1u : 0u;
    }
    return a;
}

static void record_from_est_(pft_tbd_track_t *r, const pft_tbd_estimate_t *e)
{
    r->x = e->x;
    r->y = e->y;
    r->vx = e->vx;
    r->vy = e->vy;
    r->intensity = e->intensity;
    r->pos_cov[0] = e->pos_cov[0];
    r->pos_cov[1] = e->pos_cov[1];
    r->pos_cov[2] = e->pos_cov[2];
    r->p_exist = e->p_exist;
    r->log_mean_lr = e->log_mean_lr;
}

static void push_event_(pft_tbd_t *t, pft_tbd_event_kind_t kind, uint32_t id, pft_real_t x,
                        pft_real_t y)
{
    if (t->n_events > t->cfg.max_targets) {
        return; /* cannot happen: at most max_targets endings and one confirmation */
    }
    pft_tbd_event_t *ev = &t->events[t->n_events++];
    ev->kind = kind;
    ev->id = id;
    ev->frame = t->frame;
    ev->x = x;
    ev->y = y;
    ev->last_seq = t->last_seq;
    ev->last_timestamp_us = t->last_ts;
}

/* Half-size of the subtracted PSF window. */
static uint8_t psf_half_(const pft_tbd_config_t *cfg)
{
    return (uint8_t)(cfg->window + cfg->residual_margin);
}

/* The pixels subtract_psf_(.., x, y, .., half) touches: the window grown to half-size half,
 * clipped to the image (at most (2 PFT_TBD_MAX_PSF_HALF + 1)^2 pixels). With restore false
 * they are copied from img into save (one slot of t->res), with restore true back from save:
 * the tracks' PSFs are subtracted from img in place and put back exactly, so the manager
 * holds no second full frame. */
static void psf_save_(const pft_tbd_config_t *cfg, pft_real_t *img, pft_real_t *save,
                      pft_real_t x, pft_real_t y, uint8_t half, bool restore)
{
    pft_tbd_region_t r = pft_tbd_window_int_(cfg, x, y);
    int32_t dp = (int32_t)half - (int32_t)cfg->window;
    int32_t clo = r.col_lo - dp < 0 ? 0 : r.col_lo - dp;
    int32_t chi = r.col_hi + dp > (int32_t)cfg->width - 1 ? (int32_t)cfg->width - 1 : r.col_hi + dp;
    int32_t rlo = r.row_lo - dp < 0 ? 0 : r.row_lo - dp;
    int32_t rhi = r.row_hi + dp > (int32_t)cfg->height - 1 ? (int32_t)cfg->height - 1 : r.row_hi + dp;
    const size_t stride = pft_tbd_stride_(cfg->width);
    size_t k = 0u;
    for (int32_t row = rlo; row <= rhi; ++row) {
        size_t o = (size_t)(row + 1) * stride + 1u;
        for (int32_t col = clo; col <= chi; ++col) {
            if (restore) {
                img[o + (size_t)col] = save[k];
            } else {
                save[k] = img[o + (size_t)col];
            }
            ++k;
        }
    }
}

/* img -= h / sigma of a track record's intensity at (x, y) (internal frame), the pixels it
 * touches saved first into slot `slot` of t->res. */
static void subtract_psf_(const pft_tbd_t *t, pft_real_t x, pft_real_t y, pft_real_t intensity,
                          uint8_t half, uint32_t slot)
{
    const pft_tbd_meas_t *m = &t->search.model;
    const uint32_t stride = pft_tbd_stride_(t->cfg.width);
    psf_save_(&t->cfg, t->img, t->res + (size_t)slot * PFT_TBD_PSF_SAVE_REALS_, x, y, half, false);
    pft_tbd_psf_add_(m, t->img, (size_t)stride + 1u, stride, x, y,
                     pft_neg(pft_mul(intensity, m->kc)), half);
}

/* The pixel source of a scene: the real-valued frame, or the RES16 frame read in place with
 * no patch yet. */
static void scene_src_(const pft_tbd_t *t, const pft_frame_t *frame, pft_tbd_scene_t_ *sc)
{
    memset(sc, 0, sizeof(*sc));
    sc->img = t->img;
    sc->width = t->cfg.width;
    sc->height = t->cfg.height;
    if (t->img == NULL) {
        sc->r16 = (const uint8_t *)frame->data;
        sc->r16_stride = frame->stride_bytes;
        sc->prect = t->prect;
        sc->pval = t->res;
        sc->pflag = t->pflag;
        sc->rowbuf = t->rowbuf;
    }
}

/* The RES16 frame read in place: the frame minus h / sigma of a track record's intensity at
 * (x, y) (internal frame) as the next patch of sc (subtract_psf_'s values), its rows (and the
 * rows beside them) flagged. */
static void patch_psf_(const pft_tbd_t *t, pft_tbd_scene_t_ *sc, pft_real_t x, pft_real_t y,
                       pft_real_t intensity, uint8_t half)
{
    const pft_tbd_meas_t *m = &t->search.model;
    const uint32_t k = sc->n_patch;
    int32_t *rect = t->prect + 4u * (size_t)k;
    pft_tbd_psf_patch_(m, sc, rect, t->res + (size_t)k * PFT_TBD_PSF_SAVE_REALS_, x, y,
                       pft_neg(pft_mul(intensity, m->kc)), half);
    const int32_t rlo = rect[2] > 0 ? rect[2] - 1 : 0;
    const int32_t rhi = rect[3] + 1 < (int32_t)t->cfg.height ? rect[3] + 1 : (int32_t)t->cfg.height - 1;
    for (int32_t r = rlo; r <= rhi; ++r) {
        t->pflag[r] = 1u;
    }
    sc->n_patch = k + 1u;
}

/* Drops the patches of sc (the frame as it is again). */
static void patch_drop_(const pft_tbd_t *t, pft_tbd_scene_t_ *sc)
{
    if (sc->n_patch > 0u) {
        memset(t->pflag, 0, (size_t)t->cfg.height);
    }
    sc->n_patch = 0u;
}

/* Predicted position of a track record at this frame (x + v T, or x + v k T across a seq gap
 * of k periods). */
static void predict_(const pft_tbd_t *t, const pft_tbd_track_t *r, pft_real_t *x, pft_real_t *y)
{
    const pft_real_t T =
        t->gap > 1u ? pft_mul(t->cfg.T, pft_from_int((int32_t)t->gap)) : t->cfg.T;
    *x = pft_add(r->x, pft_mul(r->vx, T));
    *y = pft_add(r->y, pft_mul(r->vy, T));
}

/* The short-window evidence test: log_mean_lr < end_lr_max in each of the last n frames. */
static bool lr_says_gone_(const pft_tbd_config_t *cfg, const pft_tbd_filter_t *tf)
{
    uint32_t n = cfg->end_lr_frames;
    if (n == 0u || tf->n_lr < n) {
        return false;
    }
    for (uint32_t q = 0; q < n; ++q) {
        if (!(tf->lr_hist[q] < cfg->end_lr_max)) {
            return false;
        }
    }
    return true;
}

/* Constraint region D of a track at (x, y) (internal frame) into the mask. */
static void add_region_(const pft_tbd_config_t *cfg, uint32_t *mask, pft_real_t x, pft_real_t y)
{
    if (cfg->d_region == PFT_TBD_D_NONE) {
        return;
    }
    pft_tbd_region_t d = pft_tbd_window_int_(cfg, x, y);
    if (cfg->d_region == PFT_TBD_D_PIXEL) {
        int32_t p = (int32_t)cfg->window;
        d.col_lo += p;
        d.col_hi -= p;
        d.row_lo += p;
        d.row_hi -= p;
    }
    d.col_lo -= cfg->d_margin;
    d.col_hi += cfg->d_margin;
    d.row_lo -= cfg->d_margin;
    d.row_hi += cfg->d_margin;
    pft_tbd_mask_add_(cfg, mask, &d);
}

/* Window-centre row and column of search particle s (false: outside the image): those of
 * pft_tbd_centre_'s pixel, (j - 1) width + (i - 1), taken from the cell (i in [1, width]), so
 * without the division and remainder that split that index. */
static bool centre_rc_(const pft_tbd_filter_t *sf, uint32_t s, uint32_t *row, uint32_t *col)
{
    pft_tbd_cell_t c;
    if (!pft_tbd_cell_(&sf->model, sf->cur.x[s], sf->cur.y[s], &c)) {
        return false;
    }
    *row = (uint32_t)(c.j - 1);
    *col = (uint32_t)(c.i - 1);
    return true;
}

/* Adds (add true) or takes away the particles of row list `row` to or from the column counts
 * cc; returns how many there were. */
static uint32_t gate_row_(const pft_tbd_filter_t *sf, const uint32_t *head, uint32_t row,
                          uint32_t *cc, bool add)
{
    uint32_t k = 0u;
    for (uint32_t s = head[row]; s != PFT_TBD_NO_PIX_; s = sf->cur.w[s].n) {
        uint32_t r = 0u;
        uint32_t c = 0u;
        (void)centre_rc_(sf, s, &r, &c); /* on the list: inside, in this row */
        if (add) {
            ++cc[c];
        } else {
            --cc[c];
        }
        ++k;
    }
    return k;
}

/* Hand-over gate (docs/algorithms.md 2.7): the square of half-size handover_gate around the
 * pixel whose (2p+1)^2 neighbourhood (clipped to the image) holds the most E = 1 search
 * particles (window centres; the first such pixel in raster order). Bounded and independent of
 * the window (issue #12): the E = 1 particles are chained into one list per row through their
 * weight slots (free between updates; t->lines holds the h list heads, then w column counts);
 * the rows are visited in order with the column counts of the band of rows r - p .. r + p (the
 * list of row r + p added, that of row r - p - 1 taken away), and along a row the box sum is a
 * running sum of 2p + 1 column counts. A row whose band holds no particle is skipped (its box
 * sums are 0 and cannot beat the best). The same box sums, and the same first maximum, as a
 * summed-area table of the whole image, with per-line memory instead of one count per pixel. */
static pft_tbd_region_t build_gate_(pft_tbd_t *t, pft_tbd_filter_t *sf)
{
    const pft_tbd_config_t *cfg = &t->cfg;
    const uint32_t w = cfg->width;
    const uint32_t h = cfg->height;
    const uint32_t p = cfg->window;
    uint32_t *head = t->lines;
    uint32_t *cc = t->lines + h;
    for (uint32_t r = 0; r < h; ++r) {
        head[r] = PFT_TBD_NO_PIX_;
    }
    memset(cc, 0, (size_t)w * sizeof(uint32_t));
    for (uint32_t s = 0; s < sf->n; ++s) {
        uint32_t r = 0u;
        uint32_t c = 0u;
        if (sf->cur.e[s] != 0u && centre_rc_(sf, s, &r, &c)) {
            sf->cur.w[s].n = head[r];
            head[r] = s;
        }
    }
    uint32_t best = 0;
    uint32_t bc = 0;
    uint32_t br = 0;
    uint32_t band = 0u; /* particles in the band */
    for (uint32_t r = 0; r < p && r < h; ++r) {
        band += gate_row_(sf, head, r, cc, true);
    }
    for (uint32_t row = 0; row < h; ++row) {
        if (row + p < h) {
            band += gate_row_(sf, head, row + p, cc, true);
        }
        if (row >= p + 1u) {
            band -= gate_row_(sf, head, row - p - 1u, cc, false);
        }
        if (band == 0u) {
            continue;
        }
        /* the box of column 0: columns 0 .. p */
        uint32_t acc = 0u;
        for (uint32_t c = 0; c <= p && c < w; ++c) {
            acc += cc[c];
        }
        for (uint32_t col = 0; col < w; ++col) {
            if (col > 0u) {
                if (col + p < w) {
                    acc += cc[col + p];
                }
                if (col >= p + 1u) {
                    acc -= cc[col - p - 1u];
                }
            }
            if (acc > best) {
                best = acc;
                bc = col;
                br = row;
            }
        }
    }
    const int32_t g = (int32_t)cfg->handover_gate;
    const pft_tbd_region_t r = {(int32_t)bc - g, (int32_t)bc + g, (int32_t)br - g,
                                (int32_t)br + g};
    return r;
}

/* 1a. Track layers (no births). With residual_tracks, track k sees the frame minus the other
 * tracks' PSFs at their predicted positions (the records still hold frame k - 1); t->res is
 * restored to the frame after each layer. */
static void update_tracks_(pft_tbd_t *t, const pft_frame_t *frame, bool residual)
{
    const pft_tbd_config_t *cfg = &t->cfg;
    uint8_t half = psf_half_(cfg);
    pft_tbd_scene_t_ tsc;
    scene_src_(t, frame, &tsc);
    tsc.cand = t->cand;
    for (uint32_t k = 0; k < cfg->max_targets; ++k) {
        if (t->records[k].id == 0u) {
            continue;
        }
        if (t->img == NULL) {
            /* the frame read in place: the other tracks' PSFs as patches over it */
            for (uint32_t u = 0; residual && u < cfg->max_targets; ++u) {
                if (u != k && t->records[u].id != 0u) {
                    pft_real_t px, py;
                    predict_(t, &t->records[u], &px, &py);
                    patch_psf_(t, &tsc, px, py, t->records[u].intensity, half);
                }
            }
            pft_tbd_filter_step_(&t->tracks[k], &tsc);
            patch_drop_(t, &tsc);
            continue;
        }
        uint32_t slot = 0u;
        for (uint32_t u = 0; residual && u < cfg->max_targets; ++u) {
            if (u != k && t->records[u].id != 0u) {
                pft_real_t px, py;
                predict_(t, &t->records[u], &px, &py);
                subtract_psf_(t, px, py, t->records[u].intensity, half, slot);
                ++slot;
            }
        }
        pft_tbd_filter_step_(&t->tracks[k], &tsc);
        /* put the pixels back in the reverse order (overlapping windows restore exactly) */
        for (uint32_t uu = cfg->max_targets; residual && uu > 0u; --uu) {
            const uint32_t u = uu - 1u;
            if (u != k && t->records[u].id != 0u) {
                pft_real_t px, py;
                predict_(t, &t->records[u], &px, &py);
                --slot;
                psf_save_(cfg, t->img, t->res + (size_t)slot * PFT_TBD_PSF_SAVE_REALS_, px, py,
                          half, true);
            }
        }
    }
}

/* The sequential confirmation test (docs/algorithms.md 2.12): a tentative track adds its layer's
 * frame log likelihood ratio to its sum; true when the sum has fallen to sprt_reject (the track
 * is dropped). Nothing is added once a bound is reached (the track is then confirmed or gone). */
static bool sprt_step_(const pft_tbd_config_t *cfg, pft_tbd_track_t *rec, const pft_tbd_filter_t *tf)
{
    rec->sprt_llr = pft_add(rec->sprt_llr, tf->est.log_mean_lr);
    return rec->sprt_llr <= cfg->sprt_reject;
}

/* The existence threshold of a track: theta_end_grace while its record is younger than
 * end_grace_frames (docs/algorithms.md 2.6), theta_end otherwise. */
static pft_real_t end_threshold_(const pft_tbd_config_t *cfg, const pft_tbd_track_t *rec)
{
    return rec->age < (uint32_t)cfg->end_grace_frames ? cfg->theta_end_grace : cfg->theta_end;
}

/* The existence test of a track (docs/algorithms.md 2.6): true when its layer's P is below
 * its threshold, with end_persist >= 2 only on the end_persist-th such test in a row (the count
 * kept in the record, 0 otherwise). */
static bool existence_ends_(const pft_tbd_config_t *cfg, pft_tbd_track_t *rec, const pft_tbd_filter_t *tf)
{
    const bool below = tf->est.p_exist < end_threshold_(cfg, rec);
    if (cfg->end_persist < 2u) {
        return below;
    }
    rec->end_below = below ? (uint8_t)(rec->end_below + 1u) : 0u;
    return rec->end_below >= cfg->end_persist;
}

/* 1b. Disappearance: a track ends on its layer's test, on P below its existence threshold
 * (theta_end, or theta_end_grace while young; end_persist tests in a row), with no live
 * particle left or on the short-window LR test. 2. The surviving tracks take their layers'
 * estimates and add their constraint regions (around the estimates of the previous frame, or
 * of this one with d_current) to t->mask. */
static void end_or_keep_tracks_(pft_tbd_t *t)
{
    const pft_tbd_config_t *cfg = &t->cfg;
    for (uint32_t k = 0; k < cfg->max_targets; ++k) {
        pft_tbd_track_t *rec = &t->records[k];
        if (rec->id == 0u) {
            continue;
        }
        pft_tbd_filter_t *tf = &t->tracks[k];
        pft_real_t dx0 = rec->x;
        pft_real_t dy0 = rec->y;
        const bool tentative = rec->first_frame == 0u; /* of the sequential test */
        bool ends = tf->gone || existence_ends_(cfg, rec, tf) || count_alive_(tf) == 0u ||
                    lr_says_gone_(cfg, tf);
        if (!ends && tentative) {
            ends = sprt_step_(cfg, rec, tf);
        }
        if (ends) {
            if (!tentative) {
                push_event_(t, PFT_TBD_EV_ENDED, rec->id, tf->est.x, tf->est.y);
            } /* a tentative track of the sequential test is dropped unreported */
            memset(rec, 0, sizeof(*rec));
            --t->n_tracks;
            continue;
        }
        record_from_est_(rec, &tf->est);
        if (tentative && rec->sprt_llr >= cfg->sprt_accept) {
            /* the sequential test accepts: reported from this frame on */
            rec->first_frame = t->frame;
            rec->age = 0u;
            push_event_(t, PFT_TBD_EV_CONFIRMED, rec->id, rec->x, rec->y);
        } else if (rec->age < UINT32_MAX) {
            ++rec->age;
        } else {
            /* the age stays at its limit */
        }
        rec->last_seq = t->last_seq;
        rec->last_timestamp_us = t->last_ts;
        if (cfg->d_current) {
            dx0 = rec->x;
            dy0 = rec->y;
        }
        add_region_(cfg, t->mask, dx0, dy0);
    }
}

/* A track layer started beside another (split_px, resid_split): the first free slot (the caller
 * has checked n_tracks < max_targets), its generator seeded from the id it will get, its
 * statistics reset and its frame count at 0 (the particles' hand-over does not read it). */
static uint32_t child_slot_(pft_tbd_t *t)
{
    uint32_t u = 0;
    while (u < t->cfg.max_targets && t->records[u].id != 0u) {
        ++u;
    }
    pft_tbd_filter_t *nf = &t->tracks[u];
    pft_rng_seed(&nf->rng, t->cfg.seed + t->next_id);
    pft_tbd_filter_reset_stats_(nf);
    nf->frames = 0u;
    return u;
}

/* ... and its record in slot u from its layer's estimate: a new id, this frame's seq and time,
 * confirmed (or tentative with sprt_accept > 0, carrying the statistic of a tentative parent
 * rec) as at a hand-over, its event, its region in the birth mask. */
static void child_record_(pft_tbd_t *t, const pft_tbd_track_t *rec, uint32_t u)
{
    const pft_tbd_config_t *cfg = &t->cfg;
    pft_tbd_track_t *nr = &t->records[u];
    memset(nr, 0, sizeof(*nr));
    nr->id = t->next_id++;
    record_from_est_(nr, &t->tracks[u].est);
    nr->last_seq = t->last_seq;
    nr->last_timestamp_us = t->last_ts;
    nr->first_frame = cfg->sprt_accept > PFT_C(0.0) ? 0u : t->frame; /* 0: tentative */
    nr->sprt_llr = rec->first_frame == 0u ? rec->sprt_llr : PFT_C(0.0);
    nr->search_layer = (uint8_t)PFT_TBD_LAYER_NONE; /* made by a split, not by a search layer */
    ++t->n_tracks;
    if (nr->first_frame != 0u) {
        push_event_(t, PFT_TBD_EV_CONFIRMED, nr->id, nr->x, nr->y);
    }
    add_region_(cfg, t->mask, nr->x, nr->y);
}

/* 2b. Split (cfg.split_px, docs/algorithms.md 2.7 [E]): each track layer that lived before this
 * frame's splits, whose live particles have parted into two groups (pft_tbd_filter_parts_), and
 * whose smaller group's centroid is farther than split_px from every other track, hands that
 * group to a new track layer in a free slot; the new track starts as a hand-over does (a new id,
 * confirmed or tentative, the sequential test from the parent's sum). */
static void split_tracks_(pft_tbd_t *t)
{
    const pft_tbd_config_t *cfg = &t->cfg;
    if (!(cfg->split_px > PFT_C(0.0))) {
        return;
    }
    const uint32_t id_new = t->next_id; /* tracks made here have ids from this one on */
    const pft_real_t sep2 = pft_sq(cfg->split_px);
    for (uint32_t k = 0; k < cfg->max_targets && t->n_tracks < cfg->max_targets; ++k) {
        pft_tbd_track_t *rec = &t->records[k];
        if (rec->id == 0u || rec->id >= id_new) {
            continue;
        }
        pft_tbd_filter_t *tf = &t->tracks[k];
        pft_real_t sx = PFT_C(0.0);
        pft_real_t sy = PFT_C(0.0);
        if (!pft_tbd_filter_parts_(tf, cfg->split_px, cfg->split_share, &sx, &sy)) {
            continue;
        }
        bool near = false;
        for (uint32_t u = 0; u < cfg->max_targets && !near; ++u) {
            const pft_tbd_track_t *o = &t->records[u];
            if (u != k && o->id != 0u) {
                const pft_real_t dx = pft_clamp(pft_sub(o->x, sx), PFT_C(-32.0), PFT_C(32.0));
                const pft_real_t dy = pft_clamp(pft_sub(o->y, sy), PFT_C(-32.0), PFT_C(32.0));
                near = pft_add(pft_sq(dx), pft_sq(dy)) < sep2;
            }
        }
        if (near) {
            continue;
        }
        const uint32_t u = child_slot_(t);
        pft_tbd_filter_t *nf = &t->tracks[u];
        pft_tbd_filter_split_(tf, nf);
        record_from_est_(rec, &tf->est);
        child_record_(t, rec, u);
    }
}

/* The residual test of cfg.resid_split (docs/algorithms.md 2.7 [E]): its ring about a layer,
 * 1.5 to 5 px (squared 2.25 and 25), the least distance of a peak from another track (3 px,
 * squared 9), the largest step of the peak between frames that keeps its count (2 px, squared
 * 4), and the half-size of the scanned square (5 px). */
#define RESID_IN2_ PFT_C(2.25)
#define RESID_OUT2_ PFT_C(25.0)
#define RESID_OTHER2_ PFT_C(9.0)
#define RESID_STEP2_ PFT_C(4.0)
#define RESID_HALF_ 5
#define RESID_SPAN_ (2 * RESID_HALF_ + 1)

/* Squared distance of two points, each axis clamped to +-32 px (q16: the squares stay small). */
static pft_real_t d2_(pft_real_t ax, pft_real_t ay, pft_real_t bx, pft_real_t by)
{
    const pft_real_t dx = pft_clamp(pft_sub(ax, bx), PFT_C(-32.0), PFT_C(32.0));
    const pft_real_t dy = pft_clamp(pft_sub(ay, by), PFT_C(-32.0), PFT_C(32.0));
    return pft_add(pft_sq(dx), pft_sq(dy));
}

/* exp(-d^2 / (2 S^2)) of the model's PSF, d clamped to +-32 px. */
static pft_real_t gauss_(const pft_tbd_meas_t *m, pft_real_t d)
{
    const pft_real_t c = pft_clamp(d, PFT_C(-32.0), PFT_C(32.0));
    return pft_exp(pft_neg(pft_mul(pft_sq(c), m->inv_2s2)));
}

/* Whether pixel (i, j) (internal 1-based) may hold a second target of track k: on its ring and
 * at least 3 px from every other track. */
static bool resid_cand_(const pft_tbd_t *t, uint32_t k, pft_real_t px, pft_real_t py)
{
    const pft_tbd_track_t *rec = &t->records[k];
    const pft_real_t d2 = d2_(px, py, rec->x, rec->y);
    if (d2 < RESID_IN2_ || d2 > RESID_OUT2_) {
        return false;
    }
    for (uint32_t u = 0; u < t->cfg.max_targets; ++u) {
        const pft_tbd_track_t *o = &t->records[u];
        if (u != k && o->id != 0u && d2_(px, py, o->x, o->y) < RESID_OTHER2_) {
            return false;
        }
    }
    return true;
}

/* The largest matched residual beside track k: the frame minus the track's PSF (its intensity
 * at its estimate), filtered with the PSF's 3 x 3 taps at a zero offset, g, as
 * m = sum g r / sqrt(sum g^2), at the pixel centres of resid_cand_ in the square of half-size
 * RESID_HALF_ about the track's pixel (those whose 3 x 3 lies inside the image). Rows are read
 * one at a time; the 3-tap row sums of the last three rows are kept. Returns 0 with no pixel
 * (*px, *py untouched), else m with its pixel centre in (*px, *py). */
static pft_real_t resid_peak_(const pft_tbd_t *t, const pft_tbd_scene_t_ *sc, uint32_t k,
                              pft_real_t *px, pft_real_t *py)
{
    const pft_tbd_meas_t *m = &t->search.model;
    const pft_tbd_track_t *rec = &t->records[k];
    const int32_t w = (int32_t)t->cfg.width;
    const int32_t h = (int32_t)t->cfg.height;
    const int32_t i0 = pft_tbd_pix_(rec->x, m->inv_dx);
    const int32_t j0 = pft_tbd_pix_(rec->y, m->inv_dy);
    const int32_t ilo = i0 - RESID_HALF_ < 2 ? 2 : i0 - RESID_HALF_;
    const int32_t ihi = i0 + RESID_HALF_ > w - 1 ? w - 1 : i0 + RESID_HALF_;
    const int32_t jlo = j0 - RESID_HALF_ < 2 ? 2 : j0 - RESID_HALF_;
    const int32_t jhi = j0 + RESID_HALF_ > h - 1 ? h - 1 : j0 + RESID_HALF_;
    pft_real_t best = PFT_C(0.0);
    if (ilo > ihi || jlo > jhi) {
        return best;
    }
    const pft_real_t gx = gauss_(m, m->dx);
    const pft_real_t gy = gauss_(m, m->dy);
    const pft_real_t norm = pft_sqrt(pft_mul(pft_add(PFT_REAL_ONE, pft_mul_i(pft_sq(gx), 2)),
                                             pft_add(PFT_REAL_ONE, pft_mul_i(pft_sq(gy), 2))));
    const pft_real_t amp = pft_mul(rec->intensity, m->kc);
    pft_real_t ex[RESID_SPAN_ + 2];
    pft_real_t hs[3][RESID_SPAN_];
    for (int32_t i = ilo - 1; i <= ihi + 1; ++i) {
        ex[i - ilo + 1] = gauss_(m, pft_sub(pft_mul_i(m->dx, i), rec->x));
    }
    bool found = false;
    for (int32_t j = jlo - 1; j <= jhi + 1; ++j) {
        const pft_real_t *row = pft_tbd_row_(sc, (uint32_t)(j - 1)) + 1;
        const pft_real_t ay = pft_mul(amp, gauss_(m, pft_sub(pft_mul_i(m->dy, j), rec->y)));
        pft_real_t *hr = hs[(uint32_t)(j - jlo + 1) % 3u];
        for (int32_t i = ilo; i <= ihi; ++i) {
            const pft_real_t rl = pft_sub(row[i - 2], pft_mul(ay, ex[i - ilo]));
            const pft_real_t rc = pft_sub(row[i - 1], pft_mul(ay, ex[i - ilo + 1]));
            const pft_real_t rr = pft_sub(row[i], pft_mul(ay, ex[i - ilo + 2]));
            hr[i - ilo] = pft_add(rc, pft_mul(gx, pft_add(rl, rr)));
        }
        const int32_t jc = j - 1; /* the candidates' row: its rows above and below are in hs */
        if (jc < jlo) {
            continue;
        }
        const pft_real_t *ha = hs[(uint32_t)(jc - 1 - jlo + 1) % 3u];
        const pft_real_t *hc = hs[(uint32_t)(jc - jlo + 1) % 3u];
        const pft_real_t cy = pft_mul_i(m->dy, jc);
        for (int32_t i = ilo; i <= ihi; ++i) {
            const pft_real_t cx = pft_mul_i(m->dx, i);
            if (!resid_cand_(t, k, cx, cy)) {
                continue;
            }
            const pft_real_t v =
                pft_div(pft_add(hc[i - ilo], pft_mul(gy, pft_add(ha[i - ilo], hr[i - ilo]))), norm);
            if (!found || v > best) {
                best = v;
                *px = cx;
                *py = cy;
                found = true;
            }
        }
    }
    return best;
}

/* 2c. A second target beside a track (cfg.resid_split, docs/algorithms.md 2.7 [E]): each track
 * layer that lived before this frame (and, with resid_split_age, is young) counts the frames in
 * a row with its residual peak (resid_peak_) at least resid_split, the peak within 2 px of the
 * last one; at resid_split_frames a new track layer starts at the peak from the layer's
 * particles (pft_tbd_filter_seed_at_) as a hand-over does, and the count restarts. */
static void resid_split_tracks_(pft_tbd_t *t, const pft_frame_t *frame)
{
    const pft_tbd_config_t *cfg = &t->cfg;
    if (!(cfg->resid_split > PFT_C(0.0))) {
        return;
    }
    const uint8_t need = cfg->resid_split_frames > 1u ? cfg->resid_split_frames : 1u;
    const uint32_t id_new = t->next_id; /* tracks made here have ids from this one on */
    pft_tbd_scene_t_ sc;
    scene_src_(t, frame, &sc);
    for (uint32_t k = 0; k < cfg->max_targets; ++k) {
        pft_tbd_track_t *rec = &t->records[k];
        pft_tbd_filter_t *tf = &t->tracks[k];
        if (rec->id == 0u || rec->id >= id_new) {
            continue;
        }
        if (cfg->resid_split_age > 0u && tf->frames > (uint32_t)cfg->resid_split_age) {
            tf->resid_n = 0u;
            tf->resid_m = PFT_C(0.0);
            continue;
        }
        pft_real_t x = PFT_C(0.0);
        pft_real_t y = PFT_C(0.0);
        const pft_real_t v = resid_peak_(t, &sc, k, &x, &y);
        const bool near = tf->resid_n > 0u && !(d2_(x, y, tf->resid_x, tf->resid_y) > RESID_STEP2_);
        tf->resid_m = v;
        tf->resid_x = x;
        tf->resid_y = y;
        if (!(v >= cfg->resid_split)) {
            tf->resid_n = 0u;
            continue;
        }
        tf->resid_n = near ? (uint8_t)(tf->resid_n < UINT8_MAX ? tf->resid_n + 1u : tf->resid_n) : 1u;
        if (tf->resid_n < need || t->n_tracks >= cfg->max_targets) {
            continue;
        }
        const uint32_t u = child_slot_(t);
        pft_tbd_filter_t *nf = &t->tracks[u];
        pft_tbd_filter_seed_at_(tf, nf, pft_sub(x, rec->x), pft_sub(y, rec->y));
        tf->resid_n = 0u;
        child_record_(t, rec, u);
    }
}

/* The Bernoulli search layer's share of a fixed particle budget (docs/algorithms.md 2.11,
 * issue #12): with `stepped` track layers stepped at this frame, the search layer moves and
 * weighs n_search - stepped n_track particles (its first ones), at least n_search / 4, so that
 * the particles moved and weighed per frame stay n_search whatever the load. Slots that come
 * back into the set are empty (births at this step). The paper's form keeps all n_search (its
 * work follows the existence probability instead). */
static void search_budget_(pft_tbd_t *t, uint32_t stepped)
{
    const pft_tbd_config_t *cfg = &t->cfg;
    if (!(cfg->birth_share > PFT_C(0.0))) {
        return;
    }
    const uint32_t n_min = cfg->n_search / 4u > 0u ? cfg->n_search / 4u : 1u;
    const uint64_t used = (uint64_t)stepped * cfg->n_track;
    const uint32_t n0 = used + n_min >= cfg->n_search ? n_min : cfg->n_search - (uint32_t)used;
    const uint32_t nl = layers_n_(cfg);
    const uint32_t n = n0 / nl; /* each layer's share (search_layers) */
    for (uint32_t h = 0; h < nl; ++h) {
        pft_tbd_filter_t *sf = layer_(t, h);
        if (n > sf->n) {
            memset(sf->cur.e + sf->n, 0, (size_t)(n - sf->n));
        }
        sf->n = n;
    }
}

/* The birth candidates of search layer h (cfg.search_layers >= 2, docs/algorithms.md 2.14)
 * into out's cand and n_cand (the rest of the scene as it is): those of the frame's (cand,
 * n_cand) farther than search_sep from the estimate (xs[g], ys[g]) of every other layer g with
 * on[g] (its existence probability above search_hold), in t->cand_x; the frame's own list when
 * it has none (every allowed pixel) or nothing bars. */
static void layer_scene_(pft_tbd_t *t, const uint32_t *cand, uint32_t n_cand, uint32_t h,
                         const pft_real_t *xs, const pft_real_t *ys, const bool *on,
                         pft_tbd_scene_t_ *out)
{
    const pft_tbd_config_t *cfg = &t->cfg;
    const uint32_t nl = layers_n_(cfg);
    out->cand = cand;
    out->n_cand = n_cand;
    bool any = false;
    for (uint32_t g = 0; g < nl; ++g) {
        any = any || (g != h && on[g]);
    }
    if (!any || cand == NULL) {
        return;
    }
    const pft_real_t sep2 = pft_sq(cfg->search_sep);
    const uint32_t w = cfg->width;
    uint32_t n = 0u;
    for (uint32_t k = 0; k < n_cand; ++k) {
        const uint32_t p = cand[k];
        const pft_real_t cx = pft_mul_i(cfg->dx, (int32_t)(p % w) + 1);
        const pft_real_t cy = pft_mul_i(cfg->dy, (int32_t)(p / w) + 1);
        bool barred = false;
        for (uint32_t g = 0; g < nl && !barred; ++g) {
            barred = g != h && on[g] && !(d2_(cx, cy, xs[g], ys[g]) > sep2);
        }
        if (!barred) {
            t->cand_x[n++] = p;
        }
    }
    out->cand = t->cand_x;
    out->n_cand = n;
}

/* The integration of this frame (docs/algorithms.md 2.13): the last frame's sums, this frame's
 * buffer, the factor in 1/256 and the shift given by pft_tbd_set_shift in whole bins (added to
 * the remainder carried from the frames before, the new remainder kept). */
static void integ_prepare_(pft_tbd_t *t, pft_tbd_integ_t_ *ig)
{
    const pft_tbd_config_t *cfg = &t->cfg;
    ig->prev = t->integ[t->integ_i];
    ig->cur = t->integ[1u - t->integ_i];
    ig->bw = ((uint32_t)cfg->width + 1u) / 2u;
    ig->bh = ((uint32_t)cfg->height + 1u) / 2u;
    ig->a_q = (uint32_t)pft_round_int(pft_mul_i(cfg->integ_alpha, 256));
    int32_t d[2];
    for (uint32_t k = 0; k < 2u; ++k) {
        const pft_real_t acc = pft_add(t->shift_acc[k], t->shift_next[k]);
        d[k] = pft_round_int(pft_mul(acc, PFT_C(0.5)));
        t->shift_acc[k] = pft_sub(acc, pft_from_int(2 * d[k]));
        t->shift_next[k] = PFT_C(0.0);
    }
    ig->sx = d[0];
    ig->sy = d[1];
}

pft_status_t pft_tbd_set_shift(pft_tbd_t *t, pft_real_t dx, pft_real_t dy)
{
    if (t == NULL) {
        return PFT_ERR_INVAL;
    }
    if (t->base == NULL) {
        return PFT_ERR_STATE;
    }
    const pft_real_t w = pft_from_int((int32_t)t->cfg.width);
    const pft_real_t h = pft_from_int((int32_t)t->cfg.height);
    if (!(dx >= pft_neg(w) && dx <= w && dy >= pft_neg(h) && dy <= h)) {
        return PFT_ERR_INVAL;
    }
    t->shift_next[0] = dx;
    t->shift_next[1] = dy;
    return PFT_OK;
}

/* 3. The search layer, births outside the regions; with residual, on the frame minus every
 * remaining track's PSF at its current estimate. */
static void update_search_(pft_tbd_t *t, const pft_frame_t *frame, bool residual,
                           uint32_t stepped)
{
    const pft_tbd_config_t *cfg = &t->cfg;
    const pft_real_t *simg = t->img;
    const bool sub = residual && t->n_tracks > 0u;
    pft_tbd_scene_t_ ssc;
    scene_src_(t, frame, &ssc);
    uint32_t slot = 0u;
    for (uint32_t u = 0; sub && u < cfg->max_targets; ++u) {
        if (t->records[u].id == 0u) {
            continue;
        }
        if (simg == NULL) {
            patch_psf_(t, &ssc, t->records[u].x, t->records[u].y, t->records[u].intensity,
                       psf_half_(cfg));
        } else {
            subtract_psf_(t, t->records[u].x, t->records[u].y, t->records[u].intensity,
                          psf_half_(cfg), slot);
            ++slot;
        }
    }
    search_budget_(t, stepped);
    if (cfg->birth_peaks > 0u) {
        pft_tbd_integ_t_ ig;
        const bool integ = integ_n_(cfg) > 0u;
        if (integ) {
            integ_prepare_(t, &ig);
        }
        if (integ) {
            pft_tbd_scene_integ_(cfg, t->tab, simg, t->mask, t->peak_rows, t->peak_val, t->cand,
                                 t->lines, &ssc, &ig);
            t->integ_i = (uint8_t)(1u - t->integ_i); /* this frame's sums are the last */
        } else {
            pft_tbd_scene_peaks_(cfg, t->tab, simg, t->mask, t->peak_rows, t->peak_val, t->cand,
                                 t->lines, &ssc);
        }
    } else {
        pft_tbd_scene_build_(cfg, t->search.gamma_w, simg, t->mask, t->cand, &ssc);
    }
    t->n_cand = ssc.n_cand;
    t->cand_listed = ssc.cand != NULL;
    const uint32_t nl = layers_n_(cfg);
    if (nl > 1u) {
        /* docs/algorithms.md 2.14: each layer on the same frame, its births barred near the
         * last frame's estimates of the others that hold mass */
        pft_real_t xs[PFT_TBD_MAX_SEARCH];
        pft_real_t ys[PFT_TBD_MAX_SEARCH];
        bool on[PFT_TBD_MAX_SEARCH];
        for (uint32_t h = 0; h < nl; ++h) {
            const pft_tbd_filter_t *f = layer_(t, h);
            xs[h] = f->est.x;
            ys[h] = f->est.y;
            on[h] = f->est.valid && f->bq > cfg->search_hold; /* bq: 0 after a hand-over */
        }
        /* the layers from the lowest existence probability up (ties in layer order), each
         * barred near the estimates of this frame of those stepped before it: an empty layer
         * takes the strongest spot no other layer holds, and the layers that hold a spot are
         * then barred from it */
        uint32_t order[PFT_TBD_MAX_SEARCH];
        for (uint32_t h = 0; h < nl; ++h) {
            uint32_t i = h;
            while (i > 0u && layer_(t, order[i - 1u])->bq > layer_(t, h)->bq) {
                order[i] = order[i - 1u];
                --i;
            }
            order[i] = h;
        }
        const uint32_t *cand = ssc.cand; /* the frame's candidates (ssc's, put back after) */
        const uint32_t n_cand = ssc.n_cand;
        for (uint32_t i = 0; i < nl; ++i) {
            const uint32_t h = order[i];
            pft_tbd_filter_t *f = layer_(t, h);
            layer_scene_(t, cand, n_cand, h, xs, ys, on, &ssc);
            pft_tbd_filter_step_(f, &ssc);
            xs[h] = f->est.x;
            ys[h] = f->est.y;
            on[h] = f->est.valid && f->bq > cfg->search_hold;
        }
        ssc.cand = cand;
        ssc.n_cand = n_cand;
    } else {
        pft_tbd_filter_step_(&t->search, &ssc);
    }
    patch_drop_(t, &ssc);
    for (uint32_t uu = cfg->max_targets; sub && simg != NULL && uu > 0u; --uu) {
        const pft_tbd_track_t *rec = &t->records[uu - 1u];
        if (rec->id != 0u) {
            --slot;
            psf_save_(cfg, t->img, t->res + (size_t)slot * PFT_TBD_PSF_SAVE_REALS_, rec->x, rec->y,
                      psf_half_(cfg), true);
        }
    }
}

/* The PSF shape test at the hand-over (cfg.shape_ring, docs/algorithms.md 2.12): on the frame
 * the search layer was weighed on (the tracks' PSFs not subtracted), around the pixel of the
 * search layer's estimate, the PSF's amplitude fitted to the 3 x 3 pixels,
 * a = sum g z / sum g^2 (g the PSF's taps at a zero sub-pixel offset), and the mean m of the
 * ring of pixels at distance 2 (Chebyshev; those inside the image). True (a point) when
 * m <= shape_ring * a; a step, a ridge or a blob wider than the PSF raises the ring. */
static bool shape_ok_(const pft_tbd_t *t, const pft_frame_t *frame, const pft_tbd_filter_t *sf)
{
    const pft_tbd_config_t *cfg = &t->cfg;
    size_t pix = 0u;
    if (!(cfg->shape_ring > PFT_C(0.0)) ||
        !pft_tbd_centre_(&sf->model, sf->est.x, sf->est.y, &pix)) {
        return true;
    }
    const int32_t w = (int32_t)cfg->width;
    const int32_t h = (int32_t)cfg->height;
    const int32_t c0 = (int32_t)(pix % (size_t)cfg->width);
    const int32_t r0 = (int32_t)(pix / (size_t)cfg->width);
    const pft_real_t two_s2 = pft_mul_i(pft_sq(cfg->psf_sigma), 2);
    const pft_real_t gx = pft_exp(pft_neg(pft_div(pft_sq(cfg->dx), two_s2)));
    const pft_real_t gy = pft_exp(pft_neg(pft_div(pft_sq(cfg->dy), two_s2)));
    pft_tbd_scene_t_ sc;
    scene_src_(t, frame, &sc);
    pft_real_t fit = PFT_C(0.0);
    pft_real_t ring = PFT_C(0.0);
    int32_t n_ring = 0;
    for (int32_t b = -2; b <= 2; ++b) {
        const int32_t r = r0 + b;
        if (r < 0 || r >= h) {
            continue;
        }
        const pft_real_t *row = pft_tbd_row_(&sc, (uint32_t)r) + 1;
        const int32_t ab = b < 0 ? -b : b;
        for (int32_t a = -2; a <= 2; ++a) {
            const int32_t c = c0 + a;
            const int32_t aa = a < 0 ? -a : a;
            if (c < 0 || c >= w) {
                continue;
            }
            if (aa == 2 || ab == 2) {
                ring = pft_add(ring, row[c]);
                ++n_ring;
            } else {
                const pft_real_t g = pft_mul(aa == 1 ? gx : PFT_REAL_ONE, ab == 1 ? gy : PFT_REAL_ONE);
                fit = pft_add(fit, pft_mul(g, row[c]));
            }
        }
    }
    const pft_real_t den = pft_mul(pft_add(PFT_REAL_ONE, pft_mul_i(pft_sq(gx), 2)),
                                   pft_add(PFT_REAL_ONE, pft_mul_i(pft_sq(gy), 2)));
    const pft_real_t amp = pft_div(fit, den);
    const pft_real_t mean = n_ring > 0 ? pft_div_i(ring, n_ring) : PFT_C(0.0);
    return !(mean > pft_mul(cfg->shape_ring, amp));
}

/* The sum the sequential test of a new track starts from (cfg.sprt_start, docs/algorithms.md
 * 2.12), read from the search layer before it is cleared: 0; its frame log likelihood ratios over
 * the frames of its confirmation; or its log odds of existence. Never below 0. */
static pft_real_t sprt_start_(const pft_tbd_t *t, const pft_tbd_filter_t *sf)
{
    const pft_tbd_config_t *cfg = &t->cfg;
    pft_real_t s = PFT_C(0.0);
    if (!(cfg->sprt_accept > PFT_C(0.0))) {
        return s;
    }
    if (cfg->sprt_start == 1u) {
        const uint32_t need = cfg->confirm_frames > 1u ? cfg->confirm_frames : 1u;
        const uint32_t n = need < sf->n_lr ? need : sf->n_lr;
        for (uint32_t q = 0; q < n; ++q) {
            s = pft_add(s, sf->lr_hist[q]);
        }
    } else if (cfg->sprt_start == 2u) {
        const pft_real_t lo = PFT_C(0.0001);
        const pft_real_t p = pft_max(sf->est.p_exist, lo);
        const pft_real_t q = pft_max(pft_sub(PFT_REAL_ONE, sf->est.p_exist), lo);
        s = pft_log(pft_div(p, q));
    } else {
        /* 0: Wald's test on the track layer alone */
    }
    return pft_max(s, PFT_C(0.0));
}

/* Search layer h's confirmation count at this frame: frames in a row with P > theta1. True
 * when it has reached confirm_frames. */
static bool count_(pft_tbd_t *t, uint32_t h)
{
    const pft_tbd_config_t *cfg = &t->cfg;
    const uint32_t need = cfg->confirm_frames > 1u ? cfg->confirm_frames : 1u;
    uint8_t *above = above_(t, h);
    if (!(layer_(t, h)->est.p_exist > cfg->theta1)) {
        *above = 0u;
        return false;
    }
    if (*above < UINT8_MAX) {
        ++*above;
    }
    return (uint32_t)*above >= need;
}

/* Search layer h starts over (its particles cleared, as at a hand-over). */
static void layer_clear_(pft_tbd_t *t, uint32_t h)
{
    pft_tbd_filter_t *sf = layer_(t, h);
    memset(sf->cur.e, 0, sf->n);
    sf->bq = PFT_C(0.0); /* birth_share: the search layer starts over */
    *above_(t, h) = 0u;
}

/* Hand-over of search layer h (its count reached, a slot free): the shape test, then its
 * particles to a new track layer (docs/algorithms.md 2.7) and the search layer cleared. */
static void handover_(pft_tbd_t *t, const pft_frame_t *frame, uint32_t h)
{
    const pft_tbd_config_t *cfg = &t->cfg;
    pft_tbd_filter_t *sf = layer_(t, h);
    if (!shape_ok_(t, frame, sf)) {
        /* not a point: the hypothesis is dropped and the search layer starts over */
        layer_clear_(t, h);
        return;
    }
    uint32_t k = 0;
    while (k < cfg->max_targets && t->records[k].id != 0u) {
        ++k;
    }
    pft_tbd_filter_t *tf = &t->tracks[k];
    pft_rng_seed(&tf->rng, cfg->seed + t->next_id);
    pft_tbd_filter_reset_stats_(tf);
    pft_tbd_region_t gate_box;
    const pft_tbd_region_t *gate = NULL;
    if (cfg->handover_gate > 0u) {
        gate_box = build_gate_(t, sf);
        gate = &gate_box;
        t->n_cand = 0u; /* pft_tbd_birth_candidates: none after a gated hand-over, as before */
    }
    if (!pft_tbd_filter_handover_(tf, sf, gate)) {
        return;
    }
    pft_tbd_track_t *rec = &t->records[k];
    memset(rec, 0, sizeof(*rec));
    rec->id = t->next_id++;
    if (gate == NULL) {
        tf->est = sf->est; /* docs/algorithms.md 2.7: the search layer's estimate */
    }
    if (cfg->handover_in_scale > PFT_C(0.0) && cfg->handover_in_scale < PFT_REAL_ONE) {
        /* docs/algorithms.md 2.7 [E]: the new layer starts from a lower intensity */
        for (uint32_t s = 0; s < tf->n; ++s) {
            tf->cur.in[s] = pft_mul(tf->cur.in[s], cfg->handover_in_scale);
        }
        tf->est.intensity = pft_mul(tf->est.intensity, cfg->handover_in_scale);
    }
    record_from_est_(rec, &tf->est);
    rec->last_seq = t->last_seq;
    rec->last_timestamp_us = t->last_ts;
    rec->first_frame = cfg->sprt_accept > PFT_C(0.0) ? 0u : t->frame; /* 0: tentative */
    rec->age = 0u;
    rec->sprt_llr = sprt_start_(t, sf);
    rec->search_layer = (uint8_t)h;
    tf->frames = 0u;
    layer_clear_(t, h);
    /* search_layers: the other layers on the same spot start over too (docs/algorithms.md 2.14) */
    const pft_real_t sep2 = pft_sq(cfg->search_sep);
    for (uint32_t g = 0; g < layers_n_(cfg); ++g) {
        const pft_tbd_filter_t *o = layer_(t, g);
        if (g != h && o->est.valid && !(d2_(o->est.x, o->est.y, sf->est.x, sf->est.y) > sep2)) {
            layer_clear_(t, g);
        }
    }
    ++t->n_tracks;
    if (rec->first_frame != 0u) {
        push_event_(t, PFT_TBD_EV_CONFIRMED, rec->id, rec->x, rec->y);
    } /* else confirmed (and reported) when its sequential test accepts it */
}

/* 4. Appearance: when a search layer's P has exceeded theta1 on confirm_frames consecutive
 * frames (docs/algorithms.md 2.11) and a slot is free, hand its particles over to a new track
 * layer (docs/algorithms.md 2.7) and clear that search layer. With search_layers, every
 * layer counts, and of those whose count is reached the one with the largest P hands over
 * (one hand-over per frame; docs/algorithms.md 2.14). */
static void confirm_(pft_tbd_t *t, const pft_frame_t *frame)
{
    const pft_tbd_config_t *cfg = &t->cfg;
    const uint32_t nl = layers_n_(cfg);
    uint32_t best = nl;
    for (uint32_t h = 0; h < nl; ++h) {
        if (count_(t, h) &&
            (best == nl || layer_(t, h)->est.p_exist > layer_(t, best)->est.p_exist)) {
            best = h;
        }
    }
    if (best == nl || t->n_tracks >= cfg->max_targets) {
        return;
    }
    handover_(t, frame, best);
}

/* periods lost frames (a seq gap): every live layer moves that many times without a frame. */
static void coast_(pft_tbd_t *t, uint32_t periods)
{
    for (uint32_t k = 0; k < t->cfg.max_targets; ++k) {
        if (t->records[k].id != 0u) {
            pft_tbd_filter_coast_(&t->tracks[k], periods);
        }
    }
    for (uint32_t h = 0; h < layers_n_(&t->cfg); ++h) {
        pft_tbd_filter_coast_(layer_(t, h), periods);
    }
}

/* A seq gap above max_gap: every track ends (an ENDED event at its last estimate), the search
 * layer starts over as on the first frame; ids and the frame count go on. */
static void restart_(pft_tbd_t *t)
{
    for (uint32_t k = 0; k < t->cfg.max_targets; ++k) {
        pft_tbd_track_t *rec = &t->records[k];
        if (rec->id != 0u) {
            if (rec->first_frame != 0u) {
                push_event_(t, PFT_TBD_EV_ENDED, rec->id, rec->x, rec->y);
            } /* a tentative track ends unreported */
            memset(rec, 0, sizeof(*rec));
        }
    }
    t->n_tracks = 0u;
    for (uint32_t h = 0; h < layers_n_(&t->cfg); ++h) {
        pft_tbd_filter_t *sf = layer_(t, h);
        *above_(t, h) = 0u;
        memset(sf->cur.e, 0, sf->n);
        pft_tbd_filter_reset_stats_(sf);
        sf->frames = 0u; /* births with eta, as on the first frame */
    }
    if (integ_n_(&t->cfg) > 0u) {
        /* the integration starts over too (the scene may have moved anywhere) */
        memset(t->integ[t->integ_i], 0, integ_n_(&t->cfg) * sizeof(uint16_t));
        t->shift_acc[0] = PFT_C(0.0);
        t->shift_acc[1] = PFT_C(0.0);
    }
}

pft_status_t pft_tbd_update(pft_tbd_t *t, const pft_frame_t *frame)
{
    if (t == NULL || frame == NULL) {
        return PFT_ERR_INVAL;
    }
    if (t->base == NULL) {
        return PFT_ERR_STATE;
    }
    const pft_tbd_config_t *cfg = &t->cfg;
    pft_status_t st = pft_tbd_frame_check_(cfg, frame);
    uint32_t gap = 1u;
    if (st == PFT_OK) {
        st = pft_seq_gap_(cfg->seq_mode, cfg->max_gap, t->seq_set, t->last_seq, frame->seq, &gap);
    }
    if (st != PFT_OK) {
        return st; /* nothing touched */
    }
    t->n_events = 0u;
    const uint32_t seen = t->seq_set ? gap : 0u;
    if (gap == 0u) {
        restart_(t); /* a gap above max_gap: the events of the ended tracks carry their last seq */
        gap = 1u;
    } else if (gap > 1u) {
        coast_(t, gap - 1u);
    } else {
        /* consecutive frames: nothing to predict beyond the update */
    }
    t->gap = gap;
    t->seq_set = true;
    t->last_seq = frame->seq;
    t->last_ts = frame->timestamp_us;
    if (t->img != NULL) {
        pft_tbd_frame_convert_(cfg, &t->search.model, frame, t->img);
    } /* else the RES16 frame is read in place (cfg.frame_format) */
    if (t->frame < UINT32_MAX) {
        ++t->frame;
    }
    memset(t->mask, 0, pft_tbd_mask_len_(cfg->width, cfg->height) * sizeof(uint32_t));
    bool res_tracks = cfg->residual_tracks && t->n_tracks > 1u;
    bool res_search = cfg->residual_search && t->n_tracks > 0u;
    const uint32_t stepped = t->n_tracks; /* track layers stepped at this frame */
    update_tracks_(t, frame, res_tracks);
    end_or_keep_tracks_(t);
    split_tracks_(t);
    resid_split_tracks_(t, frame);
    update_search_(t, frame, res_search, stepped);
    for (uint32_t h = 0; h < layers_n_(cfg); ++h) {
        pft_tbd_filter_t *sf = layer_(t, h);
        sf->est.last_seq = frame->seq;
        sf->est.last_timestamp_us = frame->timestamp_us;
        sf->est.gap = seen;
    }
    confirm_(t, frame);
    return PFT_OK;
}

/* The records of the confirmed tracks (tentative false) or of the sequential test's tentative
 * ones (first_frame 0), ordered by id, positions in public coordinates; returns how many exist. */
static size_t tracks_by_id_(const pft_tbd_t *t, pft_tbd_track_t *out, size_t max, bool tentative)
{
    if (t == NULL || t->records == NULL) {
        return 0u;
    }
    size_t n = 0;
    size_t n_sel = 0; /* the records of the kind asked for */
    for (uint32_t k = 0; k < t->cfg.max_targets; ++k) {
        n_sel += t->records[k].id != 0u && ((t->records[k].first_frame == 0u) == tentative) ? 1u : 0u;
    }
    uint32_t last = 0;
    for (uint32_t pass = 0; pass < t->cfg.max_targets && n < max && out != NULL; ++pass) {
        /* next smallest id above `last` */
        uint32_t best = UINT32_MAX;
        uint32_t bk = 0;
        bool found = false;
        for (uint32_t k = 0; k < t->cfg.max_targets; ++k) {
            uint32_t id = t->records[k].id;
            if (id != 0u && ((t->records[k].first_frame == 0u) == tentative) && id > last && id <= best) {
                best = id;
                bk = k;
                found = true;
            }
        }
        if (!found) {
            break;
        }
        out[n] = t->records[bk];
        out[n].x = pft_tbd_x_pub_(out[n].x, t->cfg.dx);
        out[n].y = pft_tbd_x_pub_(out[n].y, t->cfg.dy);
        ++n;
        last = best;
    }
    return n_sel;
}

size_t pft_tbd_tracks(const pft_tbd_t *t, pft_tbd_track_t *out, size_t max)
{
    return tracks_by_id_(t, out, max, false);
}

size_t pft_tbd_tentative(const pft_tbd_t *t, pft_tbd_track_t *out, size_t max)
{
    if (t == NULL || !(t->cfg.sprt_accept > PFT_C(0.0))) {
        return 0u; /* no sequential test: every handed-over track is confirmed */
    }
    return tracks_by_id_(t, out, max, true);
}

size_t pft_tbd_events(const pft_tbd_t *t, pft_tbd_event_t *out, size_t max)
{
    if (t == NULL || t->events == NULL) {
        return 0u;
    }
    for (size_t i = 0; i < t->n_events && i < max && out != NULL; ++i) {
        out[i] = t->events[i];
        out[i].x = pft_tbd_x_pub_(out[i].x, t->cfg.dx);
        out[i].y = pft_tbd_x_pub_(out[i].y, t->cfg.dy);
    }
    return t->n_events;
}

pft_status_t pft_tbd_search_estimate(const pft_tbd_t *t, pft_tbd_estimate_t *out)
{
    if (t == NULL || out == NULL) {
        return PFT_ERR_INVAL;
    }
    uint32_t best = 0u;
    for (uint32_t h = 1u; h < layers_n_(&t->cfg); ++h) {
        if (layer_c_(t, h)->est.p_exist > layer_c_(t, best)->est.p_exist) {
            best = h;
        }
    }
    const pft_tbd_filter_t *sf = layer_c_(t, best);
    pft_tbd_est_pub_(&sf->model, &sf->est, out);
    return PFT_OK;
}

pft_status_t pft_tbd_search_layer_estimate(const pft_tbd_t *t, uint32_t h, pft_tbd_estimate_t *out)
{
    if (t == NULL || out == NULL || h >= layers_n_(&t->cfg)) {
        return PFT_ERR_INVAL;
    }
    const pft_tbd_filter_t *sf = layer_c_(t, h);
    pft_tbd_est_pub_(&sf->model, &sf->est, out);
    return PFT_OK;
}

size_t pft_tbd_birth_candidates(const pft_tbd_t *t, uint32_t *out, size_t max)
{
    if (t == NULL || t->cand == NULL) {
        return 0u;
    }
    if (t->cand_listed) {
        for (size_t i = 0; i < t->n_cand && i < max && out != NULL; ++i) {
            out[i] = t->cand[i];
        }
        return t->n_cand;
    }
    /* the uniform proposal without a list: every allowed pixel in raster order */
    const size_t npix = (size_t)t->cfg.width * t->cfg.height;
    size_t i = 0u;
    for (size_t k = 0; k < npix && i < max && i < t->n_cand && out != NULL; ++k) {
        if (!pft_tbd_masked_(t->mask, pft_tbd_mask_words_(t->cfg.width),
                             (uint32_t)(k % t->cfg.width), (uint32_t)(k / t->cfg.width))) {
            out[i++] = (uint32_t)k;
        }
    }
    return t->n_cand;
}
