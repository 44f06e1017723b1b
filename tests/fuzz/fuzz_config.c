/* libFuzzer harness: configurations of every tracker from fuzzed bytes.
 * The first byte picks the tracker (tbd manager, tbd filter, pf engine with the bearings, the
 * linear-Gaussian or the TBD model, tsa, pte, pte_dp, pte_dbt); a small valid configuration is
 * then changed by up to 12 (offset, length, bytes) patches, whatever the struct's layout (in the
 * float build this gives NaN, infinities and subnormals too). Then:
 *  - config_check: PFT_OK with *field NULL, or PFT_ERR_CONFIG with *field naming a field;
 *    NULL cfg gives PFT_ERR_INVAL;
 *  - workspace_size: 0 exactly for a refused configuration; the *_WORKSPACE_BYTES macro gives
 *    the same number; init refuses one byte less (PFT_ERR_NOMEM) and takes the exact size;
 *  - init refuses a refused configuration with PFT_ERR_CONFIG;
 *  - a few updates on synthetic frames (when the configuration's per-frame work is small
 *    enough for a fuzzer), reset, and the same frames again give the same results;
 *  - through ASan + UBSan: no out-of-bounds access and no undefined behaviour.
 * FZ_CHECK aborts on a violated property. */
#include <stddef.h>

#include "fuzz_common.h"

uint8_t fz_pix[FZ_PIX_BYTES];
uint8_t fz_snap_ws[FZ_SNAP_BYTES];
uint8_t fz_snap_inst[1u << 16];

/* Workspaces start one byte past an 8-byte boundary: the worst alignment, where the exact
 * workspace size is needed to the byte (the 7 bytes of slack are all used). */
#define WS_CAP (1u << 20)
static uint8_t g_ws_mem[WS_CAP + 16u] __attribute__((aligned(16)));
static uint8_t g_ws2_mem[(1u << 20) + 16u] __attribute__((aligned(16)));
#define g_ws (g_ws_mem + 1)
#define g_ws2 (g_ws2_mem + 1)
#define NFR 2u            /* frames per pass */
/* Work bound of a configuration's updates (taps, particle-pixels, snake patch pixels per
 * frame; docs/reliability.md, "Per-input work"): 10^5, about 8 (tsa) to 34 (tbd) times the
 * small valid configurations the patches start from. Above it the configuration is still
 * checked, sized and initialised, only its updates are skipped (until commit 2b96ec9 the bound
 * was 2 x 10^6 per frame and the snake's gradient patch was not counted: the 20 slowest inputs
 * of a corpus of 914 took 64-155 ms each and 84 % of the replay time). */
#define WORK_CAP 100000u
#define PF_N_CAP 1000u /* particles of a pf configuration whose updates run (5000 before) */

static const char *g_field;

/* A patch may leave a bool holding neither 0 nor 1, which no caller can produce without
 * undefined behaviour of its own: keep the low bit (read through a byte). */
#define FZ_BOOL(b) ((b) = ((*(const uint8_t *)(const void *)&(b)) & 1u) != 0u)

/* Checks the config_check contract; true when the configuration is accepted. */
static bool check_contract(pft_status_t st)
{
    FZ_CHECK(st == PFT_OK || st == PFT_ERR_CONFIG);
    if (st == PFT_OK) {
        FZ_CHECK(g_field == NULL);
        return true;
    }
    FZ_CHECK(g_field != NULL && g_field[0] != '\0');
    return false;
}

/* Synthetic frames: noise plus a bright blob, all from a seed (same frames on both passes). */
static pft_frame_t synth(uint32_t seed, uint32_t k, uint16_t w, uint16_t h, pft_pixfmt_t fmt)
{
    pft_frame_t fr;
    memset(&fr, 0, sizeof fr);
    fr.width = w;
    fr.height = h;
    fr.format = fmt;
    fr.stride_bytes = (uint32_t)w * pft_pixfmt_bytes(fmt);
    fr.seq = k;
    fr.data = fz_pix;
    uint32_t s = (seed * 2654435761u + k) | 1u;
    uint32_t cx = seed % (w + 1u), cy = (seed >> 8) % (h + 1u);
    for (uint32_t y = 0; y < h; ++y) {
        for (uint32_t x = 0; x < w; ++x) {
            uint32_t v = (fz_xorshift(&s) & 31u) + 40u;
            uint32_t dx = x > cx + k ? x - cx - k : cx + k - x, dy = y > cy ? y - cy : cy - y;
            if (dx < 4u && dy < 4u) {
                v += 120u;
            }
            uint8_t *p = fz_pix + (size_t)y * fr.stride_bytes + (size_t)x * pft_pixfmt_bytes(fmt);
            if (fmt == PFT_PIX_U8) {
                p[0] = (uint8_t)v;
            } else if (fmt == PFT_PIX_RGB888) {
                p[0] = (uint8_t)v;
                p[1] = (uint8_t)(v / 2u);
                p[2] = (uint8_t)(255u - v);
            }
        }
    }
    return fr;
}

/* PFT_FUZZ_VERBOSE=1 in the environment prints every byte range a patch changed, as
 * "offset+length: old -> new" (hex), to name the fields of a reproducer. */
static void fz_show_diff(const char *what, const void *before, const void *after, size_t size)
{
    if (getenv("PFT_FUZZ_VERBOSE") == NULL) {
        return;
    }
    const uint8_t *a = (const uint8_t *)before, *b = (const uint8_t *)after;
    for (size_t i = 0; i < size; ++i) {
        if (a[i] == b[i]) {
            continue;
        }
        size_t j = i;
        while (j < size && a[j] != b[j]) {
            ++j;
        }
        fprintf(stderr, "%s offset %zu+%zu:", what, i, j - i);
        for (size_t k = i; k < j; ++k) {
            fprintf(stderr, " %02x->%02x", a[k], b[k]);
        }
        fprintf(stderr, "\n");
        i = j;
    }
}
#define FZ_PATCH(f, obj, n)                                                                   \
    do {                                                                                      \
        static uint8_t before_[sizeof(obj)];                                                   \
        memcpy(before_, &(obj), sizeof(obj));                                                 \
        fz_patch((f), &(obj), sizeof(obj), (n));                                              \
        fz_show_diff(#obj, before_, &(obj), sizeof(obj));                                      \
    } while (0)

/* ----------------------------------------- tbd -------------------------------------------- */

static void fuzz_tbd(fz_t *f, bool manager)
{
    static pft_tbd_t t;
    static pft_tbd_filter_t flt;
    pft_tbd_config_t c;
    pft_tbd_config_default(&c);
    c.width = 16u;
    c.height = 16u;
    c.n_search = 200u;
    c.n_track = 50u;
    c.max_targets = 2u;
    FZ_PATCH(f, c, 12u);
    FZ_BOOL(c.birth_correction);
    FZ_BOOL(c.dis_ratio_test);
    FZ_BOOL(c.d_current);
    FZ_BOOL(c.force_constraint);
    FZ_BOOL(c.residual_search);
    FZ_BOOL(c.residual_tracks);
    g_field = (const char *)&g_field;
    bool ok = check_contract(pft_tbd_config_check(&c, &g_field));
    size_t ws = manager ? pft_tbd_workspace_size(&c) : pft_tbd_filter_workspace_size(&c);
    FZ_CHECK(ok == (ws > 0u));
    if (!ok) {
        FZ_CHECK(manager ? pft_tbd_init(&t, &c, g_ws, WS_CAP) == PFT_ERR_CONFIG
                         : pft_tbd_filter_init(&flt, &c, g_ws, WS_CAP) == PFT_ERR_CONFIG);
        return;
    }
    size_t macro = manager ? PFT_TBD_WORKSPACE_BYTES_PEAKS(c.n_search, c.n_track, c.max_targets,
                                                           c.kind, c.width, c.height,
                                                           c.birth_peaks)
                           : PFT_TBD_FILTER_WORKSPACE_BYTES(c.n_search, c.kind, c.width,
                                                            c.height);
    if (manager && c.integ_alpha > PFT_C(0.0)) {
        /* the header's rule: the integration adds PFT_TBD_INTEG_BYTES to the figure */
        macro += PFT_TBD_INTEG_BYTES(c.width, c.height);
    }
    FZ_CHECK(macro == ws);
    if (ws > WS_CAP) {
        return;
    }
    if (manager) {
        FZ_CHECK(pft_tbd_init(&t, &c, g_ws, ws - 1u) == PFT_ERR_NOMEM);
        FZ_CHECK(pft_tbd_init(&t, &c, g_ws, ws) == PFT_OK);
    } else {
        FZ_CHECK(pft_tbd_filter_init(&flt, &c, g_ws, ws - 1u) == PFT_ERR_NOMEM);
        FZ_CHECK(pft_tbd_filter_init(&flt, &c, g_ws, ws) == PFT_OK);
    }
    uint64_t win = (2u * (uint64_t)c.window + 1u) * (2u * (uint64_t)c.window + 1u);
    uint64_t work = ((uint64_t)c.n_search + (manager ? (uint64_t)c.max_targets * c.n_track : 0u)) *
                    win + (uint64_t)c.width * c.height;
    if (work > WORK_CAP || (size_t)c.width * c.height > 128u * 128u) {
        return;
    }
    uint32_t seed = fz_u32(f);
    pft_tbd_estimate_t e[2][NFR];
    memset(e, 0, sizeof e);
    for (uint32_t pass = 0; pass < 2u; ++pass) {
        for (uint32_t k = 0; k < NFR; ++k) {
            pft_frame_t fr = synth(seed, k, c.width, c.height, PFT_PIX_U8);
            if (manager) {
                FZ_CHECK(pft_tbd_update(&t, &fr) == PFT_OK);
                FZ_CHECK(pft_tbd_tracks(&t, NULL, 0u) <= c.max_targets);
                FZ_CHECK(pft_tbd_search_estimate(&t, &e[pass][k]) == PFT_OK);
            } else {
                FZ_CHECK(pft_tbd_filter_update(&flt, &fr) == PFT_OK);
                FZ_CHECK(pft_tbd_filter_estimate(&flt, &e[pass][k]) == PFT_OK);
            }
            FZ_CHECK(fz_finite(e[pass][k].p_exist) && fz_finite(e[pass][k].x) &&
                     fz_finite(e[pass][k].log_mean_lr));
        }
        FZ_CHECK(manager ? pft_tbd_reset(&t) == PFT_OK : pft_tbd_filter_reset(&flt) == PFT_OK);
    }
    FZ_CHECK(memcmp(e[0], e[1], sizeof e[0]) == 0);
}

/* ------------------------------------------ pf -------------------------------------------- */
static void fuzz_pf(fz_t *f)
{
    static pft_pf_t pf;
    static pft_pf_bearings_model_t mb;
    static pft_pf_lg_model_t ml;
    static pft_pf_tbd_model_t mt;
    pft_pf_config_t c;
    pft_pf_config_default(&c);
    c.n_particles = 100u;
    uint8_t which = fz_u8(f) % 3u;
    pft_tbd_config_t tc;
    pft_status_t ms;
    if (which == 0u) {
        pft_pf_bearings_config_t bc;
        pft_pf_bearings_config_default(&bc, 1000);
        FZ_PATCH(f, bc, 6u);
        ms = pft_pf_bearings_model_init(&mb, &bc, &c.model);
    } else if (which == 1u) {
        pft_pf_lg_config_t lc;
        memset(&lc, 0, sizeof lc);
        lc.dim = 2u;
        lc.meas = 1u;
        lc.F[0] = lc.F[3] = lc.Lq[0] = lc.Lq[3] = lc.L0[0] = lc.L0[3] = lc.H[0] = PFT_C(1.0);
        lc.r_sd[0] = lc.r_sd[1] = PFT_C(1.0);
        FZ_PATCH(f, lc, 6u);
        ms = pft_pf_lg_model_init(&ml, &lc, &c.model);
    } else {
        pft_tbd_config_default(&tc);
        tc.width = 16u;
        tc.height = 16u;
        FZ_PATCH(f, tc, 6u);
        FZ_BOOL(tc.birth_correction);
        FZ_BOOL(tc.dis_ratio_test);
        FZ_BOOL(tc.d_current);
        FZ_BOOL(tc.force_constraint);
        FZ_BOOL(tc.residual_search);
        FZ_BOOL(tc.residual_tracks);
        size_t mws = pft_pf_tbd_model_workspace_size(&tc);
        if (mws == 0u || mws > (1u << 20)) {
            return;
        }
        FZ_CHECK(pft_pf_tbd_model_init(&mt, &tc, g_ws2, mws - 1u, &c.model) == PFT_ERR_NOMEM);
        ms = pft_pf_tbd_model_init(&mt, &tc, g_ws2, mws, &c.model);
        FZ_CHECK(ms == PFT_OK);
        /* the birth budget: 0 (off) .. 255 particles, against n_particles patched below */
        FZ_CHECK(pft_pf_tbd_model_set_budget(&mt, fz_u8(f)) == PFT_OK);
    }
    FZ_CHECK(ms == PFT_OK || ms == PFT_ERR_CONFIG);
    if (ms != PFT_OK) {
        return;
    }
    /* the engine's own fields are patched, the model interface is kept */
    pft_pf_model_t model = c.model;
    FZ_PATCH(f, c, 6u);
    c.model = model;
    g_field = (const char *)&g_field;
    bool ok = check_contract(pft_pf_config_check(&c, &g_field));
    size_t ws = pft_pf_workspace_size(&c);
    FZ_CHECK(ok == (ws > 0u));
    if (!ok) {
        FZ_CHECK(pft_pf_init(&pf, &c, g_ws, WS_CAP) == PFT_ERR_CONFIG);
        return;
    }
    FZ_CHECK(ws == PFT_PF_WORKSPACE_BYTES(c.n_particles, c.model.dim));
    if (ws > WS_CAP || c.n_particles > PF_N_CAP) {
        return;
    }
    FZ_CHECK(pft_pf_init(&pf, &c, g_ws, ws - 1u) == PFT_ERR_NOMEM);
    FZ_CHECK(pft_pf_init(&pf, &c, g_ws, ws) == PFT_OK);
    uint32_t seed = fz_u32(f);
    pft_real_t est[2][NFR][PFT_PF_MAX_DIM];
    memset(est, 0, sizeof est);
    for (uint32_t pass = 0; pass < 2u; ++pass) {
        for (uint32_t k = 0; k < NFR; ++k) {
            pft_real_t z[2] = {pft_div(pft_from_int((int32_t)(seed % 200u) + (int32_t)k), pft_from_int(100)),
                               pft_from_int((int32_t)(seed >> 24) - 128)};
            pft_frame_t fr = synth(seed, k, 16u, 16u, PFT_PIX_U8);
            const void *meas = (which == 2u) ? (const void *)&fr : (const void *)z;
            if (which == 2u && (tc.width != 16u || tc.height != 16u)) {
                return; /* frames of other sizes: covered by fuzz_frames */
            }
            FZ_CHECK(pft_pf_update(&pf, meas) == PFT_OK);
            FZ_CHECK(pft_pf_estimate(&pf, est[pass][k]) == PFT_OK);
            for (uint16_t i = 0; i < c.model.dim; ++i) {
                FZ_CHECK(fz_finite(est[pass][k][i]));
            }
        }
        FZ_CHECK(pft_pf_reset(&pf) == PFT_OK);
    }
    FZ_CHECK(memcmp(est[0], est[1], sizeof est[0]) == 0);
}

/* ------------------------------------------ tsa ------------------------------------------- */
static void fuzz_tsa(fz_t *f)
{
    static pft_tsa_t t;
    pft_tsa_config_t c;
    pft_tsa_config_default(&c);
    c.width = 48u;
    c.height = 40u;
    c.max_target_w = 16u;
    c.max_target_h = 16u;
    c.n_particles = 20u;
    c.snake_points = 12u;
    c.init_passes = 2u;
    pft_tsa_snake_params_default(&c.snake, c.max_target_w, c.max_target_h);
    FZ_PATCH(f, c, 12u);
    FZ_BOOL(c.fit_rho_weights);
    FZ_BOOL(c.loss_search);
    FZ_BOOL(c.gain_select);
    g_field = (const char *)&g_field;
    bool ok = check_contract(pft_tsa_config_check(&c, &g_field));
    size_t ws = pft_tsa_workspace_size(&c);
    FZ_CHECK(ok == (ws > 0u));
    if (!ok) {
        FZ_CHECK(pft_tsa_init(&t, &c, g_ws, WS_CAP) == PFT_ERR_CONFIG);
        return;
    }
    FZ_CHECK(ws == PFT_TSA_WORKSPACE_BYTES(c.n_particles, c.max_target_w, c.max_target_h,
                                           c.snake_points, c.snake.margin, c.map_margin));
    if (ws > WS_CAP) {
        return;
    }
    FZ_CHECK(pft_tsa_init(&t, &c, g_ws, ws - 1u) == PFT_ERR_NOMEM);
    FZ_CHECK(pft_tsa_init(&t, &c, g_ws, ws) == PFT_OK);
    /* per frame: the particles' histograms; the snake, which recomputes its gradient patch,
     * (max_w + 2 margin + 2)(max_h + 2 margin + 2) pixels, every margin - 2 passes (init_passes
     * at the start, update_max_passes per update); the code map, (max_w + 2 map_margin)
     * (max_h + 2 map_margin) codes clipped to the frame; the frame */
    uint64_t patch = ((uint64_t)c.max_target_w + 2u * c.snake.margin + 2u) *
                     ((uint64_t)c.max_target_h + 2u * c.snake.margin + 2u);
    uint64_t chunk = (c.snake.margin > 3u) ? (uint64_t)c.snake.margin - 2u : 1u;
    uint64_t passes = (c.init_passes > c.update_max_passes) ? c.init_passes : c.update_max_passes;
    uint64_t mw = (uint64_t)c.max_target_w + 2u * c.map_margin;
    uint64_t mh = (uint64_t)c.max_target_h + 2u * c.map_margin;
    uint64_t work = (uint64_t)(c.n_particles + 1u) * c.max_target_w * c.max_target_h +
                    (passes / chunk + 1u) * patch + passes * c.snake_points * 81u +
                    (mw < c.width ? mw : c.width) * (mh < c.height ? mh : c.height) +
                    (uint64_t)c.width * c.height;
    if (work > WORK_CAP || (size_t)c.width * c.height > 64u * 64u) {
        return;
    }
    uint32_t seed = fz_u32(f);
    pft_tsa_estimate_t e[2][NFR];
    memset(e, 0, sizeof e);
    for (uint32_t pass = 0; pass < 2u; ++pass) {
        pft_frame_t fr = synth(seed, 0u, c.width, c.height, PFT_PIX_RGB888);
        uint32_t cx = seed % (c.width + 1u), cy = (seed >> 8) % (c.height + 1u);
        pft_tsa_pt_t box[4] = {{(int16_t)(cx - 4u), (int16_t)(cy - 4u)},
                               {(int16_t)(cx + 4u), (int16_t)(cy - 4u)},
                               {(int16_t)(cx + 4u), (int16_t)(cy + 4u)},
                               {(int16_t)(cx - 4u), (int16_t)(cy + 4u)}};
        if (pft_tsa_start(&t, &fr, box, 4u) != PFT_OK) {
            return; /* a box the configuration refuses (size, position) */
        }
        for (uint32_t k = 0; k < NFR; ++k) {
            fr = synth(seed, k + 1u, c.width, c.height, PFT_PIX_RGB888);
            FZ_CHECK(pft_tsa_update(&t, &fr) == PFT_OK);
            FZ_CHECK(pft_tsa_estimate(&t, &e[pass][k]) == PFT_OK);
            FZ_CHECK(fz_finite(e[pass][k].x) && fz_finite(e[pass][k].y) &&
                     fz_finite(e[pass][k].rho) && fz_finite(e[pass][k].beta_next));
        }
        FZ_CHECK(pft_tsa_reset(&t) == PFT_OK);
    }
    FZ_CHECK(memcmp(e[0], e[1], sizeof e[0]) == 0);
}

/* ------------------------------------------ pte ------------------------------------------- */
static pft_real_t g_z[4096];

static void synth_real(uint32_t seed, uint32_t k, size_t n)
{
    uint32_t s = (seed * 2654435761u + k) | 1u;
    for (size_t i = 0; i < n; ++i) {
        g_z[i] = pft_div(pft_from_int((int32_t)(fz_xorshift(&s) & 0xFFu) - 128), pft_from_int(64));
    }
    if (n > 0u) {
        g_z[(seed + k) % n] = PFT_C(6.0);
    }
}

static void pte_in(pft_pte_input_t *in)
{
    in->n_range = 40u;
    in->n_doppler = 1u;
    in->cfar_ref = 4u;
    in->cfar_guard = 1u;
}


/* The range-profile trackers: NFR + 3 frames, reset, the same frames again: every update
 * accepted, at most max_reports reports, the same reports both times. The adapters give the
 * three trackers one signature. */
typedef pft_status_t (*pte_update_fn_)(void *inst, const pft_real_t *z);
typedef size_t (*pte_reports_fn_)(const void *inst, pft_pte_report_t *out, size_t max);
typedef pft_status_t (*pte_reset_fn_)(void *inst);

static void pte_twice_(void *inst, pte_update_fn_ update, pte_reports_fn_ reports, pte_reset_fn_ reset,
                       uint32_t seed, size_t cells, uint32_t max_reports)
{
    static pft_pte_report_t r[2][NFR + 3u][2];
    memset(r, 0, sizeof r);
    for (uint32_t pass = 0; pass < 2u; ++pass) {
        for (uint32_t k = 0; k < NFR + 3u; ++k) {
            synth_real(seed, k, cells);
            FZ_CHECK(update(inst, g_z) == PFT_OK);
            FZ_CHECK(reports(inst, r[pass][k], 2u) <= max_reports);
        }
        FZ_CHECK(reset(inst) == PFT_OK);
    }
    FZ_CHECK(memcmp(r[0], r[1], sizeof r[0]) == 0);
}

static pft_status_t pte_update_(void *p, const pft_real_t *z) { return pft_pte_update_real(p, z); }
static size_t pte_reports_(const void *p, pft_pte_report_t *r, size_t m) { return pft_pte_reports(p, r, m); }
static pft_status_t pte_reset_(void *p) { return pft_pte_reset(p); }
static pft_status_t dp_update_(void *p, const pft_real_t *z) { return pft_pte_dp_update_real(p, z); }
static size_t dp_reports_(const void *p, pft_pte_report_t *r, size_t m) { return pft_pte_dp_reports(p, r, m); }
static pft_status_t dp_reset_(void *p) { return pft_pte_dp_reset(p); }
static pft_status_t dbt_update_(void *p, const pft_real_t *z) { return pft_pte_dbt_update_real(p, z); }
static size_t dbt_reports_(const void *p, pft_pte_report_t *r, size_t m) { return pft_pte_dbt_reports(p, r, m); }
static pft_status_t dbt_reset_(void *p) { return pft_pte_dbt_reset(p); }

static void fuzz_pte(fz_t *f)
{
    static pft_pte_t p;
    pft_pte_config_t c;
    pft_pte_config_default(&c);
    pte_in(&c.in);
    c.init_frames = 4u;
    c.max_len = 8u;
    c.scan_steps = 4u;
    c.max_tracks = 2u;
    c.init_threshold = PFT_C(8.0);
    const uint8_t bud = fz_u8(f);
    c.step_budget = (uint8_t)(bud % 3u); /* off, 1 or 2 of the 2 slots */
    /* line_budget off, 60 (below its smallest, 90: refused), 120 or 180 (the same byte) */
    c.line_budget = (uint16_t)(((uint32_t)bud / 3u % 4u) * 60u);
    FZ_PATCH(f, c, 12u);
    g_field = (const char *)&g_field;
    bool ok = check_contract(pft_pte_config_check(&c, &g_field));
    size_t ws = pft_pte_workspace_size(&c);
    FZ_CHECK(ok == (ws > 0u));
    if (!ok) {
        FZ_CHECK(pft_pte_init(&p, &c, g_ws, WS_CAP) == PFT_ERR_CONFIG);
        return;
    }
    if (ws > WS_CAP) {
        return;
    }
    FZ_CHECK(pft_pte_init(&p, &c, g_ws, ws - 1u) == PFT_ERR_NOMEM);
    FZ_CHECK(pft_pte_init(&p, &c, g_ws, ws) == PFT_OK);
    uint64_t cells = (uint64_t)c.in.n_range * c.in.n_doppler;
    uint64_t nax = (c.in.n_doppler > 1u) ? 2u : 1u;
    uint64_t scan = 2u * (uint64_t)c.scan_steps + 1u;
    uint64_t ops = (uint64_t)c.max_tracks * c.n_dir[0] * (nax == 2u ? c.n_dir[1] : 1u) *
                   c.max_len * (nax == 2u ? scan * scan * 225u : scan * 15u);
    uint64_t dp = ((uint64_t)c.max_tracks + 1u) * c.init_frames * cells *
                  (2u * (uint64_t)c.init_gate[0] + 1u) * (2u * (uint64_t)c.init_gate[1] + 1u);
    if (ops > WORK_CAP || dp > WORK_CAP || cells > 4096u) {
        return;
    }
    uint32_t seed = fz_u32(f);
    pte_twice_(&p, pte_update_, pte_reports_, pte_reset_, seed, (size_t)cells, c.max_tracks);
    pft_real_t vt;
    pft_status_t st = pft_pte_threshold(&p, fz_real(f), fz_u8(f) % 6u, fz_u8(f), &vt);
    FZ_CHECK(st == PFT_OK || st == PFT_ERR_INVAL);
}

static void fuzz_pte_dp(fz_t *f)
{
    static pft_pte_dp_t p;
    pft_pte_dp_config_t c;
    pft_pte_dp_config_default(&c);
    pte_in(&c.in);
    c.frames = 4u;
    c.max_targets = 2u;
    c.threshold = PFT_C(8.0);
    FZ_PATCH(f, c, 12u);
    g_field = (const char *)&g_field;
    bool ok = check_contract(pft_pte_dp_config_check(&c, &g_field));
    size_t ws = pft_pte_dp_workspace_size(&c);
    FZ_CHECK(ok == (ws > 0u));
    if (!ok) {
        FZ_CHECK(pft_pte_dp_init(&p, &c, g_ws, WS_CAP) == PFT_ERR_CONFIG);
        return;
    }
    FZ_CHECK(ws == PFT_PTE_DP_WORKSPACE_BYTES(c.in.n_range, c.in.n_doppler, c.frames, c.max_targets));
    if (ws > WS_CAP) {
        return;
    }
    FZ_CHECK(pft_pte_dp_init(&p, &c, g_ws, ws - 1u) == PFT_ERR_NOMEM);
    FZ_CHECK(pft_pte_dp_init(&p, &c, g_ws, ws) == PFT_OK);
    uint64_t cells = (uint64_t)c.in.n_range * c.in.n_doppler;
    uint64_t dp = ((uint64_t)c.max_targets + 1u) * c.frames * cells *
                  (2u * (uint64_t)c.gate[0] + 1u) * (2u * (uint64_t)c.gate[1] + 1u);
    if (dp > WORK_CAP || cells > 4096u) {
        return;
    }
    uint32_t seed = fz_u32(f);
    pte_twice_(&p, dp_update_, dp_reports_, dp_reset_, seed, (size_t)cells, c.max_targets);
    pft_real_t vt;
    pft_status_t st = pft_pte_dp_threshold(&p, fz_real(f), fz_u8(f) % 6u, fz_u8(f), &vt);
    FZ_CHECK(st == PFT_OK || st == PFT_ERR_INVAL);
}

static void fuzz_pte_dbt(fz_t *f)
{
    static pft_pte_dbt_t p;
    pft_pte_dbt_config_t c;
    pft_pte_dbt_config_default(&c);
    pte_in(&c.in);
    c.max_tracks = 8u;
    c.max_dets = 16u;
    FZ_PATCH(f, c, 12u);
    g_field = (const char *)&g_field;
    bool ok = check_contract(pft_pte_dbt_config_check(&c, &g_field));
    size_t ws = pft_pte_dbt_workspace_size(&c);
    FZ_CHECK(ok == (ws > 0u));
    if (!ok) {
        FZ_CHECK(pft_pte_dbt_init(&p, &c, g_ws, WS_CAP) == PFT_ERR_CONFIG);
        return;
    }
    FZ_CHECK(ws == PFT_PTE_DBT_WORKSPACE_BYTES(c.in.n_range, c.in.n_doppler, c.max_tracks, c.max_dets));
    if (ws > WS_CAP) {
        return;
    }
    FZ_CHECK(pft_pte_dbt_init(&p, &c, g_ws, ws - 1u) == PFT_ERR_NOMEM);
    FZ_CHECK(pft_pte_dbt_init(&p, &c, g_ws, ws) == PFT_OK);
    uint64_t cells = (uint64_t)c.in.n_range * c.in.n_doppler;
    if (cells > 4096u) {
        return;
    }
    uint32_t seed = fz_u32(f);
    pte_twice_(&p, dbt_update_, dbt_reports_, dbt_reset_, seed, (size_t)cells, c.max_tracks);
}

/* ------------------------------- preprocessing (pft_pre_*) -------------------------------- */
/* Frame buffers of the preprocessing choices (64 x 64 at most, 2 bytes per pixel) and a
 * bad-pixel map for frames up to 64 px wide. */
static uint8_t g_raw[FZ_PRE_SIDE * FZ_PRE_SIDE * 2u];
static int16_t g_res[FZ_PRE_SIDE * FZ_PRE_SIDE];
static uint8_t g_bad[FZ_PRE_SIDE * ((FZ_PRE_SIDE + 7u) / 8u)];
#define PRE_NFR 4u /* frames per pass: a start, then updates with and without evidence */

/* The stage: option bits set on a small valid configuration (so that the anchored background
 * and its gates, inplace, the bad map and the cost levers are reached without the patches
 * having to find them), then the patches; raw frames of the four kinds, twice around a reset. */
static void fuzz_pre_stage(fz_t *f)
{
    static pft_pre_t p;
    pft_pre_config_t c;
    pft_pre_config_default(&c);
    c.width = 32u;
    c.height = 24u;
    c.tile = 8u;
    c.peak_max = 16u;
    c.reg_search = 4u;
    static const uint8_t depths[5] = {8u, 12u, 14u, 16u, 0u};
    uint8_t d = fz_u8(f);
    c.format = (d % 6u == 5u) ? PFT_PIX_U8 : PFT_PIX_U16;
    c.bit_depth = (c.format == PFT_PIX_U8) ? 8u : depths[d % 6u % 5u];
    uint16_t o = fz_u16(f);
    c.method = (o & 1u) ? PFT_PRE_BG_TEMPORAL : PFT_PRE_BG_LOCAL;
    c.bg_anchor = (o & 2u) != 0u;
    c.bg_gate = (o & 4u) ? 512u : 0u;
    c.bg_gate_shift = (o & 8u) ? 3u : 0u;
    c.bg_gate_young = (o & 16u) ? 8u : 0u;
    c.bg_gate_local = (uint8_t)((o >> 5) % 3u);
    c.bg_masked_taps = (uint8_t)((o >> 7) % 3u);
    c.inplace = (o & 512u) != 0u;
    c.sigma_bracket = (o & 1024u) != 0u;
    c.sigma_interp = (o & 2048u) == 0u;
    c.sigma_current = (o & 4096u) == 0u;
    c.edge_k = (o & 8192u) ? 1024u : 0u;
    c.reg_bin = (o & 16384u) != 0u;
    bool bad = (o & 32768u) != 0u;
    c.sigma_level = d >= 192u; /* o's bits are all used */
    c.bg_young_scale = (d & 64u) != 0u; /* refused without bg_gate_young (o's bit 16) */
    FZ_PATCH(f, c, 12u);
    FZ_BOOL(c.bg_young_scale);
    FZ_BOOL(c.sigma_level);
    FZ_BOOL(c.warp_cubic);
    FZ_BOOL(c.sigma_interp);
    FZ_BOOL(c.sigma_current);
    FZ_BOOL(c.inplace);
    FZ_BOOL(c.reg_bin);
    FZ_BOOL(c.sigma_bracket);
    FZ_BOOL(c.bg_anchor);
    /* the bad map is a pointer: NULL or a map of the harness, never patched bytes */
    c.bad_map = (bad && c.width <= FZ_PRE_SIDE && c.height <= FZ_PRE_SIDE) ? g_bad : NULL;
    if (c.bad_map != NULL) {
        memset(g_bad, 0, sizeof g_bad); /* the same map for the same input */
        fz_bytes(f, g_bad, 8u);         /* the first rows' bits */
    }
    g_field = (const char *)&g_field;
    bool ok = check_contract(pft_pre_config_check(&c, &g_field));
    size_t ws = pft_pre_workspace_size(&c);
    FZ_CHECK(ok == (ws > 0u));
    if (!ok) {
        FZ_CHECK(pft_pre_init(&p, &c, g_ws, WS_CAP) == PFT_ERR_CONFIG);
        return;
    }
    size_t macro;
    if (c.bg_anchor) {
        /* the header's rule: ANCHOR, plus YOUNG_BYTES and LOCAL_BYTES with those options */
        macro = PFT_PRE_WORKSPACE_BYTES_ANCHOR(c.width, c.height, c.local_outer, c.tile, c.peak_max) +
                (c.bg_gate_young != 0u ? PFT_PRE_YOUNG_BYTES(c.width, c.height) : 0u) +
                (c.bg_gate_local != 0u ? PFT_PRE_LOCAL_BYTES(c.width, c.height, c.tile) : 0u);
        if (c.bg_gate_young != 0u && c.bg_gate_local == 0u) {
            FZ_CHECK(macro == PFT_PRE_WORKSPACE_BYTES_ANCHOR_YOUNG(c.width, c.height, c.local_outer,
                                                                  c.tile, c.peak_max));
        }
        if (c.bg_gate_young == 0u && c.bg_gate_local != 0u) {
            FZ_CHECK(macro == PFT_PRE_WORKSPACE_BYTES_ANCHOR_LOCAL(c.width, c.height, c.local_outer,
                                                                  c.tile, c.peak_max));
        }
    } else if (c.inplace) {
        macro = PFT_PRE_WORKSPACE_BYTES_INPLACE(c.width, c.height, c.method, c.local_outer, c.tile,
                                                c.peak_max);
    } else {
        macro = PFT_PRE_WORKSPACE_BYTES(c.width, c.height, c.method, c.local_outer, c.tile,
                                        c.peak_max);
    }
    /* the header's rule for bg_stale_reinit: PFT_PRE_STALE_BYTES more, with or without bg_anchor */
    macro += (c.bg_stale_reinit != 0u) ? PFT_PRE_STALE_BYTES(c.width, c.height) : 0u;
    /* and for sigma_level: PFT_PRE_LEVEL_BYTES more, with or without bg_anchor */
    macro += c.sigma_level ? PFT_PRE_LEVEL_BYTES(c.width, c.height, c.tile) : 0u;
    FZ_CHECK(macro == ws);
    if (ws > WS_CAP) {
        return;
    }
    FZ_CHECK(pft_pre_init(&p, &c, g_ws, ws - 1u) == PFT_ERR_NOMEM);
    FZ_CHECK(pft_pre_init(&p, &c, g_ws, ws) == PFT_OK);
    if (c.width > FZ_PRE_SIDE || c.height > FZ_PRE_SIDE) {
        return;
    }
    uint32_t seed = fz_u32(f);
    uint8_t kinds = fz_u8(f); /* two bits per frame: noise, constant, zero, saturated */
    size_t n = (size_t)c.width * c.height;
    static int16_t outs[2][PRE_NFR][FZ_PRE_SIDE * FZ_PRE_SIDE];
    static pft_pre_stats_t st[2][PRE_NFR];
    static uint32_t sig[2][PRE_NFR][64];
    memset(st, 0, sizeof st);
    memset(sig, 0, sizeof sig);
    for (uint32_t pass = 0; pass < 2u; ++pass) {
        for (uint32_t k = 0; k < PRE_NFR; ++k) {
            pft_frame_t fr = fz_pre_raw(g_raw, seed, k, c.width, c.height, c.format, c.bit_depth,
                                        (kinds >> (2u * k)) & 3u);
            if (c.inplace) {
                FZ_CHECK(pft_pre_update(&p, &fr) == PFT_ERR_STATE);
                FZ_CHECK(pft_pre_update_inplace(&p, &fr, (uint16_t *)(void *)g_raw) == PFT_OK);
            } else {
                FZ_CHECK(pft_pre_update(&p, &fr) == PFT_OK);
            }
            fz_pre_check_stats(&p, c.width, c.height, c.peak_max, c.peak_threshold);
            FZ_CHECK(pft_pre_stats(&p, &st[pass][k]) == PFT_OK);
            FZ_CHECK(st[pass][k].frames == k + 1u && st[pass][k].seq == k);
            pft_frame_t out;
            FZ_CHECK(pft_pre_frame(&p, &out) == PFT_OK);
            for (uint32_t y = 0; y < c.height; ++y) {
                memcpy(&outs[pass][k][(size_t)y * c.width],
                       (const uint8_t *)out.data + (size_t)y * out.stride_bytes, 2u * c.width);
            }
            size_t nt = pft_pre_sigma(&p, sig[pass][k], 64u);
            FZ_CHECK(nt == PFT_PRE_NT_(c.width, c.tile) * PFT_PRE_NT_(c.height, c.tile));
        }
        FZ_CHECK(pft_pre_reset(&p) == PFT_OK);
        pft_pre_stats_t z;
        FZ_CHECK(pft_pre_stats(&p, &z) == PFT_OK && z.frames == 0u);
    }
    FZ_CHECK(memcmp(st[0], st[1], sizeof st[0]) == 0);
    FZ_CHECK(memcmp(sig[0], sig[1], sizeof sig[0]) == 0);
    for (uint32_t k = 0; k < PRE_NFR; ++k) {
        FZ_CHECK(memcmp(outs[0][k], outs[1][k], n * 2u) == 0);
    }
}

/* The clutter map: option bits, patches, then residual frames with and without evidence and
 * a drifting shift, twice around a reset. */
static void fuzz_pre_clutter(fz_t *f)
{
    static pft_pre_clutter_t m;
    pft_pre_clutter_config_t c;
    pft_pre_clutter_config_default(&c);
    c.width = 32u;
    c.height = 24u;
    uint8_t o = fz_u8(f);
    c.mean = (o & 1u) != 0u;
    c.persist = (c.mean && (o & 2u)) ? 3u : 0u;
    c.veto = (o & 4u) ? 8192u : 0u;
    c.inplace = (o & 8u) != 0u;
    c.block = (uint8_t)(((o >> 4) % 3u) * 2u);
    c.map8 = c.block == 0u && (o & 64u) != 0u;
    c.anchor = c.block == 0u && (o & 128u) != 0u;
    c.mean_floor = (c.mean && c.block == 0u && (o & 2u)) ? 128u : 0u;
    c.floor_age = (c.mean_floor != 0u && (o & 4u)) ? 3u : 0u;
    FZ_PATCH(f, c, 12u);
    FZ_BOOL(c.box);
    FZ_BOOL(c.mean);
    FZ_BOOL(c.inplace);
    FZ_BOOL(c.map8);
    FZ_BOOL(c.anchor);
    g_field = (const char *)&g_field;
    bool ok = check_contract(pft_pre_clutter_config_check(&c, &g_field));
    size_t ws = pft_pre_clutter_workspace_size(&c);
    FZ_CHECK(ok == (ws > 0u));
    if (!ok) {
        FZ_CHECK(pft_pre_clutter_init(&m, &c, g_ws, WS_CAP) == PFT_ERR_CONFIG);
        return;
    }
    size_t macro = c.map8 ? PFT_PRE_CLUTTER_WORKSPACE_BYTES_MAP8(c.width, c.height, c.mean, c.blur,
                                                                 c.persist != 0u, c.inplace)
                          : PFT_PRE_CLUTTER_WORKSPACE_BYTES_BLOCK(c.width, c.height, c.mean, c.blur,
                                                                  c.persist != 0u, c.block, c.inplace);
    if (!c.map8 && c.block == 0u) {
        FZ_CHECK(macro == (c.inplace ? PFT_PRE_CLUTTER_WORKSPACE_BYTES_INPLACE(c.width, c.height, c.mean,
                                                                              c.blur, c.persist != 0u)
                                     : PFT_PRE_CLUTTER_WORKSPACE_BYTES(c.width, c.height, c.mean,
                                                                       c.blur, c.persist != 0u)));
    }
    /* floor_age: the ages' bytes on top of every form */
    macro += c.floor_age != 0u ? PFT_PRE_CLUTTER_WORKSPACE_BYTES_AGE(c.width, c.height) : 0u;
    FZ_CHECK(macro == ws);
    if (ws > WS_CAP) {
        return;
    }
    FZ_CHECK(pft_pre_clutter_init(&m, &c, g_ws, ws - 1u) == PFT_ERR_NOMEM);
    FZ_CHECK(pft_pre_clutter_init(&m, &c, g_ws, ws) == PFT_OK);
    if (c.width > FZ_PRE_SIDE || c.height > FZ_PRE_SIDE) {
        return;
    }
    pft_frame_t none;
    FZ_CHECK(pft_pre_clutter_frame(&m, &none) == PFT_ERR_STATE);
    uint32_t seed = fz_u32(f);
    uint8_t ev = fz_u8(f);
    int32_t sx = (int32_t)(int8_t)fz_u8(f) * 4096, sy = (int32_t)(int8_t)fz_u8(f) * 4096;
    size_t n = (size_t)c.width * c.height;
    static int16_t outs[2][PRE_NFR][FZ_PRE_SIDE * FZ_PRE_SIDE];
    static uint32_t at[2][PRE_NFR];
    memset(at, 0, sizeof at);
    for (uint32_t pass = 0; pass < 2u; ++pass) {
        for (uint32_t k = 0; k < PRE_NFR; ++k) {
            pft_frame_t fr = fz_pre_res(g_res, seed, k, c.width, c.height);
            bool e = ((ev >> k) & 1u) == 0u;
            if (c.inplace) {
                FZ_CHECK(pft_pre_clutter_update(&m, &fr, sx, sy, e) == PFT_ERR_STATE);
                FZ_CHECK(pft_pre_clutter_update_inplace(&m, &fr, g_res, sx, sy, e) == PFT_OK);
            } else {
                FZ_CHECK(pft_pre_clutter_update(&m, &fr, sx, sy, e) == PFT_OK);
            }
            pft_frame_t out;
            FZ_CHECK(pft_pre_clutter_frame(&m, &out) == PFT_OK);
            FZ_CHECK(out.format == PFT_PIX_RES16 && out.width == c.width && out.height == c.height &&
                     out.seq == k);
            for (uint32_t y = 0; y < c.height; ++y) {
                memcpy(&outs[pass][k][(size_t)y * c.width],
                       (const uint8_t *)out.data + (size_t)y * out.stride_bytes, 2u * c.width);
            }
            at[pass][k] = pft_pre_clutter_at(&m, seed % c.width, (seed >> 8) % c.height);
            FZ_CHECK(pft_pre_clutter_at(&m, c.width, 0u) == 0u);
        }
        FZ_CHECK(pft_pre_clutter_raise(&m, c.width, 0u, 2048u) == PFT_ERR_INVAL);
        FZ_CHECK(pft_pre_clutter_raise(&m, 0u, 0u, 4096u) == PFT_OK);
        FZ_CHECK(pft_pre_clutter_reset(&m) == PFT_OK);
    }
    FZ_CHECK(memcmp(at[0], at[1], sizeof at[0]) == 0);
    for (uint32_t k = 0; k < PRE_NFR; ++k) {
        FZ_CHECK(memcmp(outs[0][k], outs[1][k], n * 2u) == 0);
    }
}

/* The flat-field correction: patches, then residual frames (and level frames with relative),
 * twice around a reset. */
static void fuzz_pre_flat(fz_t *f)
{
    static pft_pre_flat_t fl;
    pft_pre_flat_config_t c;
    pft_pre_flat_config_default(&c);
    c.width = 32u;
    c.height = 24u;
    c.block = 8u;
    uint8_t o = fz_u8(f);
    c.relative = (o & 1u) != 0u;
    c.rescale = (o & 2u) != 0u;
    FZ_PATCH(f, c, 12u);
    FZ_BOOL(c.relative);
    FZ_BOOL(c.rescale);
    g_field = (const char *)&g_field;
    bool ok = check_contract(pft_pre_flat_config_check(&c, &g_field));
    size_t ws = pft_pre_flat_workspace_size(&c);
    FZ_CHECK(ok == (ws > 0u));
    if (!ok) {
        FZ_CHECK(pft_pre_flat_init(&fl, &c, g_ws, WS_CAP) == PFT_ERR_CONFIG);
        return;
    }
    /* the header's rule for rescale: PFT_PRE_FLAT_WORKSPACE_BYTES_RESCALE */
    FZ_CHECK(ws == (c.rescale ? PFT_PRE_FLAT_WORKSPACE_BYTES_RESCALE(c.width, c.height, c.block)
                              : PFT_PRE_FLAT_WORKSPACE_BYTES(c.width, c.height, c.block)));
    if (ws > WS_CAP) {
        return;
    }
    FZ_CHECK(pft_pre_flat_init(&fl, &c, g_ws, ws - 1u) == PFT_ERR_NOMEM);
    FZ_CHECK(pft_pre_flat_init(&fl, &c, g_ws, ws) == PFT_OK);
    if (c.width > FZ_PRE_SIDE || c.height > FZ_PRE_SIDE) {
        return;
    }
    uint32_t seed = fz_u32(f);
    uint8_t ev = fz_u8(f);
    uint8_t lk = fz_u8(f);
    size_t n = (size_t)c.width * c.height;
    static int16_t outs[2][PRE_NFR][FZ_PRE_SIDE * FZ_PRE_SIDE];
    static int32_t at[2][PRE_NFR];
    memset(at, 0, sizeof at);
    for (uint32_t pass = 0; pass < 2u; ++pass) {
        for (uint32_t k = 0; k < PRE_NFR; ++k) {
            pft_frame_t fr = fz_pre_res(g_res, seed, k, c.width, c.height);
            pft_frame_t lv = fz_pre_raw(g_raw, seed, k, c.width, c.height,
                                        (lk & 16u) ? PFT_PIX_U8 : PFT_PIX_U16, (uint8_t)(8u + lk % 9u),
                                        (lk >> (2u * (k % 2u))) & 3u);
            bool e = ((ev >> k) & 1u) == 0u;
            FZ_CHECK(pft_pre_flat_update(&fl, &fr, g_res, c.relative ? &lv : NULL, e) == PFT_OK);
            memcpy(outs[pass][k], g_res, n * 2u);
            at[pass][k] = pft_pre_flat_at(&fl, seed % c.width, (seed >> 8) % c.height);
            FZ_CHECK(pft_pre_flat_at(&fl, 0u, c.height) == 0);
        }
        FZ_CHECK(pft_pre_flat_reset(&fl) == PFT_OK);
    }
    FZ_CHECK(memcmp(at[0], at[1], sizeof at[0]) == 0);
    for (uint32_t k = 0; k < PRE_NFR; ++k) {
        FZ_CHECK(memcmp(outs[0][k], outs[1][k], n * 2u) == 0);
    }
}

static void fuzz_pre(fz_t *f)
{
    switch (fz_u8(f) % 3u) {
    case 0: fuzz_pre_stage(f); break;
    case 1: fuzz_pre_clutter(f); break;
    default: fuzz_pre_flat(f); break;
    }
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);
int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    static bool once;
    if (!once) { /* NULL configurations, once per process */
        once = true;
        FZ_CHECK(pft_tbd_config_check(NULL, NULL) == PFT_ERR_INVAL && pft_tbd_workspace_size(NULL) == 0u);
        FZ_CHECK(pft_pf_config_check(NULL, NULL) == PFT_ERR_INVAL && pft_pf_workspace_size(NULL) == 0u);
        FZ_CHECK(pft_tsa_config_check(NULL, NULL) == PFT_ERR_INVAL && pft_tsa_workspace_size(NULL) == 0u);
        FZ_CHECK(pft_pte_config_check(NULL, NULL) == PFT_ERR_INVAL && pft_pte_workspace_size(NULL) == 0u);
        FZ_CHECK(pft_pte_dp_config_check(NULL, NULL) == PFT_ERR_INVAL && pft_pte_dp_workspace_size(NULL) == 0u);
        FZ_CHECK(pft_pte_dbt_config_check(NULL, NULL) == PFT_ERR_INVAL && pft_pte_dbt_workspace_size(NULL) == 0u);
        FZ_CHECK(pft_pre_config_check(NULL, NULL) == PFT_ERR_INVAL && pft_pre_workspace_size(NULL) == 0u);
        FZ_CHECK(pft_pre_clutter_config_check(NULL, NULL) == PFT_ERR_INVAL &&
                 pft_pre_clutter_workspace_size(NULL) == 0u);
        FZ_CHECK(pft_pre_flat_config_check(NULL, NULL) == PFT_ERR_INVAL && pft_pre_flat_workspace_size(NULL) == 0u);
    }
    fz_t f = {data, size};
    /* 9 choices; the committed seeds' first bytes are below 9, so a seed picks what it picked
     * when there were 8 (modulo 8) */
    switch (fz_u8(&f) % 9u) {
    case 0: fuzz_tbd(&f, true); break;
    case 1: fuzz_tbd(&f, false); break;
    case 2: fuzz_pf(&f); break;
    case 3: fuzz_tsa(&f); break;
    case 4: fuzz_pte(&f); break;
    case 5: fuzz_pte_dp(&f); break;
    case 6: fuzz_pte_dbt(&f); break;
    case 8: fuzz_pre(&f); break;
    default: fuzz_tbd(&f, (size & 1u) != 0u); break;
    }
    return 0;
}
