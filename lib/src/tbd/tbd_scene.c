/*
 * The scene-motion test of the IR pipeline (pft_tbd_scene.h; docs/algorithms.md 9.11).
 * Integer arithmetic only, so that the float and q16 builds decide alike: positions in Q16.16
 * px (int32), the scene's cumulative shift in Q16.16 px (int64), squared distances in Q32.32
 * (int64). Bounds that keep every product inside int64 are given at each step.
 */
#include <string.h>

#include "pft/pft_tbd_scene.h"

#include "../core/config_int.h"

void pft_tbd_scene_config_default(pft_tbd_scene_config_t *cfg)
{
    if (cfg == NULL) {
        return;
    }
    memset(cfg, 0, sizeof(*cfg));
    cfg->frames = 5u;
    cfg->max_tracks = 16u;
    cfg->gate_px = PFT_C(0.15);
    cfg->fit_px = PFT_C(0.2);
    cfg->early_px = PFT_C(0.5);
    cfg->forget_frames = 64u;
    cfg->width = 384u;
    cfg->height = 288u;
    cfg->hold_frames = 1u;
    cfg->spread_px = PFT_C(0.0);
    cfg->spread_hold = 1u;
    cfg->slow_frames = 0u;
    cfg->slow_low_px = PFT_C(0.0);
    cfg->slow_gate_px = PFT_C(0.15);
    cfg->spread_exist = PFT_C(0.0);
    cfg->edge_px = PFT_C(0.0);
    cfg->edge_still_px = PFT_C(0.1);
    cfg->edge_shift_px = PFT_C(0.2);
    cfg->move_px = PFT_C(0.0);
    cfg->move_hold = 0u;
}

/* a threshold in [0, 256] px (0: the test it sets is off) */
static bool sc_thr_ok_(pft_real_t v)
{
    return v >= PFT_C(0.0) && v <= PFT_C(256.0);
}

pft_status_t pft_tbd_scene_config_check(const pft_tbd_scene_config_t *cfg, const char **field)
{
    const char *bad = NULL;
    if (cfg == NULL) {
        return pft_config_verdict_(false, NULL, field);
    }
    if (cfg->frames < 1u || cfg->frames > PFT_TBD_SCENE_MAX_FRAMES) {
        bad = "frames";
    } else if (cfg->max_tracks < 1u || cfg->max_tracks > PFT_TBD_SCENE_MAX_TRACKS) {
        bad = "max_tracks";
    } else if (!sc_thr_ok_(cfg->gate_px)) {
        bad = "gate_px";
    } else if (!sc_thr_ok_(cfg->fit_px)) {
        bad = "fit_px";
    } else if (!sc_thr_ok_(cfg->early_px)) {
        bad = "early_px";
    } else if (cfg->forget_frames < 1u || cfg->forget_frames > (1u << 30)) {
        bad = "forget_frames";
    } else if (cfg->width < 1u || cfg->width > PFT_CFG_MAX_IMAGE_SIDE) {
        bad = "width";
    } else if (cfg->height < 1u || cfg->height > PFT_CFG_MAX_IMAGE_SIDE) {
        bad = "height";
    } else if (cfg->hold_frames < 1u || cfg->hold_frames > PFT_TBD_SCENE_MAX_HOLD) {
        bad = "hold_frames";
    } else if (!sc_thr_ok_(cfg->spread_px)) {
        bad = "spread_px";
    } else if (cfg->spread_hold < 1u || cfg->spread_hold > cfg->hold_frames) {
        bad = "spread_hold";
    } else if (cfg->slow_frames != 0u &&
               (cfg->slow_frames < 2u * cfg->frames || cfg->slow_frames > PFT_TBD_SCENE_MAX_FRAMES)) {
        bad = "slow_frames";
    } else if (cfg->slow_frames != 0u && !(cfg->slow_low_px >= PFT_C(0.0) && cfg->slow_low_px <= cfg->gate_px)) {
        bad = "slow_low_px";
    } else if (cfg->slow_frames != 0u && !(cfg->slow_gate_px > PFT_C(0.0) && cfg->slow_gate_px <= PFT_C(256.0))) {
        bad = "slow_gate_px";
    } else if (!(cfg->spread_exist >= PFT_C(0.0) && cfg->spread_exist <= PFT_C(1.0))) {
        bad = "spread_exist";
    } else if (!sc_thr_ok_(cfg->edge_px)) {
        bad = "edge_px";
    } else if (!sc_thr_ok_(cfg->edge_still_px)) {
        bad = "edge_still_px";
    } else if (!sc_thr_ok_(cfg->edge_shift_px)) {
        bad = "edge_shift_px";
    } else if (!sc_thr_ok_(cfg->move_px)) {
        bad = "move_px";
    } else if (cfg->move_hold != 0u && (cfg->move_hold < cfg->spread_hold || cfg->move_hold > cfg->hold_frames)) {
        bad = "move_hold";
    } else {
        /* accepted */
    }
    return pft_config_verdict_(true, bad, field);
}

/* positions kept per slot: frames + 1, or slow_frames + 1 with the longer look on */
static uint32_t sc_ring_(const pft_tbd_scene_config_t *cfg)
{
    return (cfg->slow_frames > cfg->frames ? cfg->slow_frames : cfg->frames) + 1u;
}

size_t pft_tbd_scene_workspace_size(const pft_tbd_scene_config_t *cfg)
{
    if (pft_tbd_scene_config_check(cfg, NULL) != PFT_OK) {
        return 0u;
    }
    return PFT_TBD_SCENE_WORKSPACE_BYTES(cfg->max_tracks, sc_ring_(cfg) - 1u);
}

/* v (px) in Q16.16, rounded to nearest; saturated to +-(2^31 - 1) (+-32768 px) */
static int32_t sc_q16_(pft_real_t v)
{
#ifdef PFT_NUMERIC_Q16
    return v;
#else
    float t = v * 65536.0f; /* exact: a power of two */
    if (t >= 2147483648.0f) {
        return INT32_MAX;
    }
    if (t <= -2147483648.0f) {
        return -INT32_MAX;
    }
    if (fabsf(t) < 8388608.0f) {
        t = floorf(t + 0.5f); /* exact below 2^23; above, t is already an integer */
    }
    return (int32_t)t;
#endif
}

/* whether v is a number (float build: not NaN; q16: always) */
static bool sc_finite_(pft_real_t v)
{
#ifdef PFT_NUMERIC_Q16
    (void)v;
    return true;
#else
    return v >= -3.402823466e+38f && v <= 3.402823466e+38f;
#endif
}

pft_status_t pft_tbd_scene_init(pft_tbd_scene_t *s, const pft_tbd_scene_config_t *cfg, void *work,
                                size_t work_len)
{
    if (s == NULL || cfg == NULL || work == NULL) {
        return PFT_ERR_INVAL;
    }
    if (pft_tbd_scene_config_check(cfg, NULL) != PFT_OK) {
        return PFT_ERR_CONFIG;
    }
    pft_ws_t ws;
    pft_ws_init(&ws, work, work_len);
    pft_tbd_scene_slot_t *slot = pft_ws_take(&ws, (size_t)cfg->max_tracks * sizeof(pft_tbd_scene_slot_t));
    pft_tbd_scene_pos_t *pos =
        pft_ws_take(&ws, (size_t)cfg->max_tracks * (size_t)sc_ring_(cfg) * sizeof(pft_tbd_scene_pos_t));
    if (pft_ws_status(&ws) != PFT_OK) {
        return PFT_ERR_NOMEM;
    }
    memset(s, 0, sizeof(*s));
    s->cfg = *cfg;
    s->slot = slot;
    s->pos = pos;
    s->gate_q = sc_q16_(cfg->gate_px);
    s->early_q = sc_q16_(cfg->early_px);
    s->fit_q = sc_q16_(cfg->fit_px);
    s->spread_q = sc_q16_(cfg->spread_px);
    s->ring = sc_ring_(cfg);
    s->slow_low_q = sc_q16_(cfg->slow_low_px);
    s->slow_q = sc_q16_(cfg->slow_gate_px);
    s->exist_q = cfg->spread_px > PFT_C(0.0) ? sc_q16_(cfg->spread_exist) : 0;
    s->edge_q = sc_q16_(cfg->edge_px);
    s->edge_still_q = sc_q16_(cfg->edge_still_px);
    s->edge_shift_q = sc_q16_(cfg->edge_shift_px);
    s->move_q = cfg->spread_px > PFT_C(0.0) ? sc_q16_(cfg->move_px) : 0;
    s->move_need = cfg->move_hold != 0u ? cfg->move_hold : cfg->hold_frames;
    return pft_tbd_scene_reset(s);
}

pft_status_t pft_tbd_scene_reset(pft_tbd_scene_t *s)
{
    if (s == NULL) {
        return PFT_ERR_INVAL;
    }
    memset(s->slot, 0, (size_t)s->cfg.max_tracks * sizeof(pft_tbd_scene_slot_t));
    memset(s->pos, 0, (size_t)s->cfg.max_tracks * (size_t)s->ring * sizeof(pft_tbd_scene_pos_t));
    s->scene_x = 0;
    s->scene_y = 0;
    s->frame = 0u;
    s->overflows = 0u;
    return PFT_OK;
}

/* the slot holding id, or max_tracks */
static uint32_t sc_find_(const pft_tbd_scene_t *s, uint32_t id)
{
    uint32_t k;
    for (k = 0u; k < s->cfg.max_tracks; ++k) {
        if (s->slot[k].id == id) {
            return k;
        }
    }
    return s->cfg.max_tracks;
}

/* a slot for a new id: a free one, else the unmarked one fed least recently (lowest on a
 * tie), else max_tracks */
static uint32_t sc_take_(const pft_tbd_scene_t *s)
{
    uint32_t k, best = s->cfg.max_tracks, best_age = 0u;
    for (k = 0u; k < s->cfg.max_tracks; ++k) {
        const pft_tbd_scene_slot_t *sl = &s->slot[k];
        if (sl->id == 0u) {
            return k;
        }
        if (sl->mark == 0u) {
            const uint32_t age = s->frame - sl->last; /* wrap-safe */
            if (best == s->cfg.max_tracks || age > best_age) {
                best = k;
                best_age = age;
            }
        }
    }
    return best;
}

/* |v| limited to lim */
static int64_t sc_clamp_(int64_t v, int64_t lim)
{
    return v > lim ? lim : (v < -lim ? -lim : v);
}

/* a / b rounded to nearest, ties away from zero; b > 0 */
static int64_t sc_div_round_(int64_t a, int64_t b)
{
    return a >= 0 ? (a + b / 2) / b : -((-a + b / 2) / b);
}

/* squared displacement against the scene (Q32.32) from position a to b; each component
 * limited to 2^30 (16384 px), so the sum stays below 2^61 */
static int64_t sc_disp2_(const pft_tbd_scene_pos_t *a, const pft_tbd_scene_pos_t *b)
{
    const int64_t lim = (int64_t)1073741824; /* 2^30 */
    /* |x| < 2^31 and |sx| grows by at most 2^31 per frame: no int64 overflow for < 2^31 frames */
    const int64_t dx = sc_clamp_(((int64_t)b->x - a->x) - (b->sx - a->sx), lim);
    const int64_t dy = sc_clamp_(((int64_t)b->y - a->y) - (b->sy - a->sy), lim);
    return dx * dx + dy * dy;
}

/* whether the last m = min(count, frames + 1) positions of slot sl (ring of s->ring entries)
 * fit a straight line at constant speed within rms fit: sum of squared residuals <= m fit^2. With k_i = 2 i - (m - 1), K = sum k_i^2,
 * u_i = x_i - x_0, the residual is r_i = (m K u_i - K sum u - m (sum k u) k_i) / (m K), exact
 * before its rounding to Q16.16: m <= 32, K <= 10912, |u| < 2^32, so every term is below 2^53. */
static bool sc_fit_ok_(const pft_tbd_scene_t *s, const pft_tbd_scene_slot_t *sl, const pft_tbd_scene_pos_t *ring)
{
    const uint32_t mm = s->ring;
    const uint32_t cnt = sl->count < s->cfg.frames + 1u ? sl->count : s->cfg.frames + 1u;
    const uint32_t h0 = (sl->head + sl->count - cnt) % mm; /* the first of the last cnt */
    const int64_t m = (int64_t)cnt;
    const int64_t rlim = (int64_t)67108864; /* 2^26: 1024 px */
    int64_t kk = 0, ss = 0, fit2;
    int64_t su[2] = {0, 0}, sku[2] = {0, 0};
    int32_t x0[2];
    uint32_t i, c;
    if (cnt < 3u) {
        return true;
    }
    x0[0] = ring[h0].x;
    x0[1] = ring[h0].y;
    for (i = 0u; i < cnt; ++i) {
        const pft_tbd_scene_pos_t *p = &ring[(h0 + i) % mm];
        const int64_t k = 2 * (int64_t)i - (m - 1);
        const int64_t u[2] = {(int64_t)p->x - x0[0], (int64_t)p->y - x0[1]};
        kk += k * k;
        for (c = 0u; c < 2u; ++c) {
            su[c] += u[c];
            sku[c] += k * u[c];
        }
    }
    for (i = 0u; i < cnt; ++i) {
        const pft_tbd_scene_pos_t *p = &ring[(h0 + i) % mm];
        const int64_t k = 2 * (int64_t)i - (m - 1);
        const int64_t u[2] = {(int64_t)p->x - x0[0], (int64_t)p->y - x0[1]};
        for (c = 0u; c < 2u; ++c) {
            const int64_t num = m * kk * u[c] - kk * su[c] - m * sku[c] * k;
            const int64_t r = sc_clamp_(sc_div_round_(num, m * kk), rlim);
            ss += r * r; /* < 2^52 each, 64 terms at most */
        }
    }
    fit2 = (int64_t)s->fit_q * s->fit_q; /* fit <= 256 px: < 2^48 */
    return ss <= m * fit2;
}

/* whether the position spread sqrt(var) is at most spread_px: var (px^2) taken to Q16.16
 * (saturated at 32768 px^2) and compared exactly in Q32.32 with spread_q^2 (spread_px <= 256
 * px: < 2^48; var_q < 2^31, shifted < 2^47) */
static bool sc_spread_ok_(const pft_tbd_scene_t *s, pft_real_t var)
{
    const int64_t v = (int64_t)sc_q16_(var);
    return v * 65536 <= (int64_t)s->spread_q * s->spread_q;
}

/* the position of slot sl `back` frames before its newest (back < count) */
static const pft_tbd_scene_pos_t *sc_back_(const pft_tbd_scene_t *s, const pft_tbd_scene_slot_t *sl,
                                           const pft_tbd_scene_pos_t *ring, uint32_t back)
{
    return &ring[(sl->head + sl->count - 1u - back) % s->ring];
}

/* The longer look (cfg.slow_frames > 0) at a track whose displacement over the last n frames
 * (d2: squared, Q32.32) is below n * gate_px: 2 (CLUTTER) below n * slow_low_px; else, over the
 * longest window held, m = min(count - 1, slow_frames) frames: 0 (moving) if m >= 2 n and the
 * displacement against the scene is at least sqrt(m n) * slow_gate_px, 2 (CLUTTER) if it is not
 * and m = slow_frames, 1 (undecided) otherwise. Exact in Q32.32: n slow_low_q < 2^29 (n <= 31,
 * slow_low_px <= gate_px <= 256 px), m n slow_q^2 < 2^10 * 2^48. */
static uint32_t sc_slow_(const pft_tbd_scene_t *s, const pft_tbd_scene_slot_t *sl, const pft_tbd_scene_pos_t *ring,
                         int64_t d2)
{
    const int64_t n = (int64_t)s->cfg.frames;
    const int64_t lo = n * s->slow_low_q;
    uint32_t m;
    int64_t dm2;
    if (d2 < lo * lo) {
        return 2u;
    }
    m = sl->count - 1u;
    if (m > s->cfg.slow_frames) {
        m = s->cfg.slow_frames;
    }
    if (m < 2u * s->cfg.frames) {
        return 1u;
    }
    dm2 = sc_disp2_(sc_back_(s, sl, ring, m), sc_back_(s, sl, ring, 0u));
    if (dm2 >= (int64_t)m * n * ((int64_t)s->slow_q * s->slow_q)) {
        return 0u;
    }
    return m == s->cfg.slow_frames ? 2u : 1u;
}

/* whether, along one axis, the track moved less than still (Q16.16, < 2^29) in the frame, d its
 * frame displacement over the window (|d| < 2^32), while the scene's shift ds over the window
 * (Q16.16, |ds| < 2^37: 31 frames of < 2^31) is at least lim (< 2^29) in magnitude and the newest
 * position p (Q16.16) lies within edge_q of the border that shift brings new content in from:
 * ds < 0 the far border side - 1, ds > 0 the near one, 0 */
static bool sc_edge_axis_(int64_t p, int64_t d, int64_t ds, int64_t still, int64_t lim, int64_t edge_q,
                          uint32_t side)
{
    const int64_t far = ((int64_t)side - 1) * 65536; /* side <= PFT_CFG_MAX_IMAGE_SIDE: < 2^31 */
    if (d >= still || -d >= still) {
        return false; /* moves in the frame along this axis */
    }
    if (ds < 0 && -ds >= lim) {
        return p >= far - edge_q;
    }
    if (ds > 0 && ds >= lim) {
        return p <= edge_q;
    }
    return false;
}

/* The entering-edge hold (cfg.edge_px > 0): whether the track of slot sl, over its last m =
 * min(count - 1, frames) frames, along an axis moved less than m * edge_still_px in frame
 * coordinates while the scene moved at least m * edge_shift_px along it, its newest position
 * within edge_px of that axis's entering border. m edge_still_q and m edge_shift_q < 2^29. */
static bool sc_edge_hold_(const pft_tbd_scene_t *s, const pft_tbd_scene_slot_t *sl, const pft_tbd_scene_pos_t *ring)
{
    uint32_t m = sl->count - 1u;
    const pft_tbd_scene_pos_t *a;
    const pft_tbd_scene_pos_t *b;
    int64_t still, shift;
    if (m > s->cfg.frames) {
        m = s->cfg.frames;
    }
    if (m < 1u) {
        return false;
    }
    a = sc_back_(s, sl, ring, m);
    b = sc_back_(s, sl, ring, 0u);
    still = (int64_t)m * s->edge_still_q;
    shift = (int64_t)m * s->edge_shift_q;
    return sc_edge_axis_(b->x, (int64_t)b->x - a->x, b->sx - a->sx, still, shift, s->edge_q, s->cfg.width) ||
           sc_edge_axis_(b->y, (int64_t)b->y - a->y, b->sy - a->sy, still, shift, s->edge_q, s->cfg.height);
}

/* The speed bound of the short hold (cfg.move_px > 0): whether the track of slot sl moved less
 * than m * move_px against the scene over its last m = min(count - 1, frames) frames (compared
 * squared, exactly in Q32.32: m move_q < 2^5 * 2^24 = 2^29; the displacement's components are
 * clamped at 2^30 by sc_disp2_). */
static bool sc_slow_mover_(const pft_tbd_scene_t *s, const pft_tbd_scene_slot_t *sl, const pft_tbd_scene_pos_t *ring)
{
    uint32_t m = sl->count - 1u;
    int64_t lim;
    if (m > s->cfg.frames) {
        m = s->cfg.frames;
    }
    if (m < 1u) {
        return true; /* one position: no displacement shown yet */
    }
    lim = (int64_t)m * s->move_q;
    return sc_disp2_(sc_back_(s, sl, ring, m), sc_back_(s, sl, ring, 0u)) < lim * lim;
}

/* round(q) (Q16.16) clamped to [0, side - 1] */
static uint32_t sc_pix_(int32_t q, uint32_t side)
{
    uint32_t v;
    if (q < 0) {
        return 0u;
    }
    v = ((uint32_t)q + 32768u) >> 16; /* 0 <= q <= 2^31 - 1: no wrap */
    return v > side - 1u ? side - 1u : v;
}

pft_status_t pft_tbd_scene_update(pft_tbd_scene_t *s, const pft_tbd_scene_track_t *tracks, size_t n,
                                  int32_t shift_x, int32_t shift_y, pft_tbd_scene_out_t *out)
{
    size_t i, j;
    uint32_t k;
    if (s == NULL) {
        return PFT_ERR_INVAL;
    }
    const uint32_t mm = s->ring;            /* positions kept per slot */
    const uint32_t n1 = s->cfg.frames + 1u; /* positions of the test over n frames */
    if (n > 0u && (tracks == NULL || out == NULL)) {
        return PFT_ERR_INVAL;
    }
    for (i = 0u; i < n; ++i) {
        if (tracks[i].id == 0u || !sc_finite_(tracks[i].x) || !sc_finite_(tracks[i].y)) {
            return PFT_ERR_INVAL;
        }
        if (s->spread_q > 0 && !(tracks[i].pos_var >= PFT_C(0.0))) {
            return PFT_ERR_INVAL; /* negative (float build: or NaN) */
        }
        if (s->exist_q > 0 && !sc_finite_(tracks[i].p_exist)) {
            return PFT_ERR_INVAL; /* (float build) NaN */
        }
        for (j = 0u; j < i; ++j) {
            if (tracks[j].id == tracks[i].id) {
                return PFT_ERR_INVAL;
            }
        }
    }
    /* accepted: from here on the instance changes */
    s->frame += 1u;
    s->scene_x += shift_x;
    s->scene_y += shift_y;
    for (k = 0u; k < s->cfg.max_tracks; ++k) {
        s->slot[k].mark = 0u;
    }
    for (i = 0u; i < n; ++i) {
        k = sc_find_(s, tracks[i].id);
        if (k < s->cfg.max_tracks) {
            s->slot[k].mark = 1u;
        }
    }
    for (i = 0u; i < n; ++i) {
        const pft_tbd_scene_track_t *t = &tracks[i];
        pft_tbd_scene_out_t *o = &out[i];
        pft_tbd_scene_slot_t *sl;
        pft_tbd_scene_pos_t *ring;
        pft_tbd_scene_pos_t pnew;
        bool early = false;
        bool pass;
        uint32_t slow = 0u; /* the longer look: 1 while undecided */
        pnew.x = sc_q16_(t->x);
        pnew.y = sc_q16_(t->y);
        pnew.sx = s->scene_x;
        pnew.sy = s->scene_y;
        o->id = t->id;
        o->px = sc_pix_(pnew.x, s->cfg.width);
        o->py = sc_pix_(pnew.y, s->cfg.height);
        k = sc_find_(s, t->id);
        if (k == s->cfg.max_tracks) {
            k = sc_take_(s);
            if (k == s->cfg.max_tracks) {
                o->decision = PFT_TBD_SCENE_NO_SLOT;
                o->positions = 0u;
                s->overflows += 1u;
                continue;
            }
            memset(&s->slot[k], 0, sizeof(s->slot[k]));
            s->slot[k].id = t->id;
            s->slot[k].mark = 1u;
        }
        sl = &s->slot[k];
        ring = &s->pos[(size_t)k * mm];
        sl->last = s->frame;
        if (sl->count < mm) {
            ring[(sl->head + sl->count) % mm] = pnew;
            sl->count += 1u;
        } else {
            ring[sl->head] = pnew;
            sl->head = (sl->head + 1u) % mm;
        }
        o->positions = sl->count;
        if (sl->clutter == 0u && sl->count >= n1) {
            /* displacement over the last n frames against the scene below n * gate */
            const int64_t g = (int64_t)s->cfg.frames * s->gate_q; /* < 2^31 */
            const int64_t d2 = sc_disp2_(sc_back_(s, sl, ring, s->cfg.frames), sc_back_(s, sl, ring, 0u));
            if (d2 < g * g) {
                slow = s->cfg.slow_frames == 0u ? 2u : sc_slow_(s, sl, ring, d2);
                if (slow == 2u) {
                    sl->clutter = 1u;
                }
            }
        }
        if (sl->clutter != 0u) {
            o->decision = PFT_TBD_SCENE_CLUTTER;
            continue;
        }
        if (slow != 0u) {
            o->decision = PFT_TBD_SCENE_HOLD; /* undecided: not reported, not CLUTTER */
            continue;
        }
        if (t->tentative) {
            o->decision = PFT_TBD_SCENE_HOLD;
            continue;
        }
        if (s->early_q > 0 && sl->count >= 4u && sl->count < n1) {
            /* early report: against the scene by at least 3 early_px over the last 3 frames */
            const int64_t e = 3 * (int64_t)s->early_q; /* < 2^27 */
            early = sc_disp2_(sc_back_(s, sl, ring, 3u), sc_back_(s, sl, ring, 0u)) >= e * e;
        }
        pass = (sl->count >= n1 || early) && (s->fit_q == 0 || sc_fit_ok_(s, sl, ring));
        if (pass && s->edge_q > 0 && sc_edge_hold_(s, sl, ring)) {
            o->decision = PFT_TBD_SCENE_HOLD; /* still at the entering edge: not a pass */
        } else if (pass) {
            /* the report hold: reported from the hold_frames-th frame that passes (from the
             * spread_hold-th with a position spread of at most spread_px) */
            uint32_t need = s->cfg.hold_frames;
            if (s->spread_q > 0 && sc_spread_ok_(s, t->pos_var) &&
                (s->exist_q == 0 || sc_q16_(t->p_exist) >= s->exist_q)) {
                need = s->cfg.spread_hold; /* with spread_exist: only at an existence of at least it */
                if (s->move_q > 0 && sc_slow_mover_(s, sl, ring)) {
                    need = s->move_need; /* with move_px: only for a track not slow against the scene */
                }
            }
            if (sl->passed < s->cfg.hold_frames) {
                sl->passed = (uint16_t)(sl->passed + 1u);
            }
            o->decision = sl->passed >= need ? PFT_TBD_SCENE_REPORT : PFT_TBD_SCENE_HOLD;
        } else {
            o->decision = PFT_TBD_SCENE_HOLD;
        }
    }
    /* forget the histories forget_frames frames after their last frame */
    for (k = 0u; k < s->cfg.max_tracks; ++k) {
        pft_tbd_scene_slot_t *sl = &s->slot[k];
        if (sl->id != 0u && s->frame - sl->last > s->cfg.forget_frames) {
            memset(sl, 0, sizeof(*sl));
        }
    }
    return PFT_OK;
}

uint32_t pft_tbd_scene_positions(const pft_tbd_scene_t *s, uint32_t id)
{
    uint32_t k;
    if (s == NULL || id == 0u) {
        return 0u;
    }
    k = sc_find_(s, id);
    return k < s->cfg.max_tracks ? s->slot[k].count : 0u;
}

bool pft_tbd_scene_is_clutter(const pft_tbd_scene_t *s, uint32_t id)
{
    uint32_t k;
    if (s == NULL || id == 0u) {
        return false;
    }
    k = sc_find_(s, id);
    return k < s->cfg.max_tracks && s->slot[k].clutter != 0u;
}

uint32_t pft_tbd_scene_overflows(const pft_tbd_scene_t *s)
{
    return s == NULL ? 0u : s->overflows;
}

uint32_t pft_tbd_scene_frame(const pft_tbd_scene_t *s)
{
    return s == NULL ? 0u : s->frame;
}
