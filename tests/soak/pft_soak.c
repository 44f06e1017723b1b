/* Soak test: every tracker over a long run of frames (noise, and targets coming and going),
 * checking at every frame that
 *  - every update of a well-formed frame is accepted (PFT_OK);
 *  - no result is NaN or infinite (float build) and every estimate lies in its domain (the
 *    image, or the range profile, grown by a stated margin; probabilities and similarities in
 *    [0, 1]; counts within their configured bounds);
 * and over the whole run that the false-track rate (frames with a reported track farther than
 * a gate from every true target) is flat: split into `segments` equal segments, no segment's
 * rate exceeds 2 x the median segment rate + 0.02 (checked from 100000 frames on).
 * Trackers: tbd (RBPF-TBD manager), pf (SIR engine with the TBD model), tsa (TSA-AK), pte
 * (PTE-TBD), pte_dp (DP-TBD, sliding), pte_dbt (Kalman DBT). Frames are U16 (tbd, pf, pte
 * family) or RGB888 (tsa), drawn from the soak's own generator (xorshift64 + Box-Muller),
 * so float and q16 builds see the same frames.
 *
 * Usage: pft_soak [--frames N] [--tracker NAME|all] [--seed S] [--segments K] [--quiet] [--known]
 *                 [--trace] [--tbd-bern] [--tbd-bounded] [--tbd-search N] [--pf-budget K]
 *                 [--pte-budget B] [--pte-lines W]
 * --trace prints "trace <frame> <tracks>" after every update (tracks: confirmed tracks or
 * reports; tsa: 1 while tracking), to group per-frame work by load (run_soak.sh work); tbd and
 * pf add the existence probability of the search layer / filter after the frame.
 * --tbd-bern runs the tbd manager with its search layer in Bernoulli form (birth_share 0.5);
 * --tbd-bounded runs it with the settings of pft_tbd_config_bounded over the recommended ones
 * (Bernoulli form, theta1 0.475) and half the search particles, 500;
 * --tbd-search N gives its search layer N particles instead of 1000 (or 500).
 * --pf-budget K runs pf with the TBD model's birth budget K (pft_pf_tbd_model_set_budget; of
 * its 500 particles).
 * --pte-budget B runs pte with step_budget B (at most B track steps per update; of its 3 slots).
 * --pte-lines W runs pte with line_budget W (at most W units per update: line x frame sums,
 * response blocks and edge rows, docs/algorithms.md 5.8) and checks after every update that
 * it did no more (the count of the last update, a white-box read); with --trace it prints
 * "pte_units <units>" before each update's trace line.
 * --known counts the known open defects listed in docs/reliability.md apart instead of
 * failing on them (the ctest soak_short uses it; soak_short_strict, disabled, does not).
 * Exit code 0 and the line "pft_soak: PASS" when every check held. docs/reliability.md gives
 * the long runs; tests/CMakeLists.txt registers a short run (ctest soak_short). */
#include <math.h>
#include <stdio.h>
#include <time.h>
#include <stdlib.h>
#include <string.h>

#include "pft/pft.h"

/* ------------------------------------ generator ------------------------------------------- */
typedef struct {
    uint64_t s;
} rng_t;

static uint64_t rnext(rng_t *r)
{
    uint64_t x = r->s;
    x ^= x << 13;
    x ^= x >> 7;
    x ^= x << 17;
    r->s = x;
    return x;
}
static double runif(rng_t *r) { return (double)(rnext(r) >> 11) * (1.0 / 9007199254740992.0); }
static double rgauss(rng_t *r)
{
    double u1 = runif(r), u2 = runif(r);
    if (u1 < 1e-300) {
        u1 = 1e-300;
    }
    return sqrt(-2.0 * log(u1)) * cos(6.283185307179586 * u2);
}

/* Up to MAXT targets at once; each lives `left` more frames, moves at constant velocity and
 * dies early when it leaves the field. Births after random gaps. */
#define MAXT 3
typedef struct {
    bool on;
    double x, y, vx, vy, amp;
    int left;
} tgt_t;

typedef struct {
    rng_t r;
    tgt_t t[MAXT];
    int nmax;           /* targets at once */
    int gap;            /* frames until the next birth */
    double w, h;        /* field: [0, w) x [0, h) */
    double vmax, amp_lo, amp_hi;
    int life_lo, life_hi, gap_lo, gap_hi;
    double margin;      /* births this far inside the field */
} scene_t;

static int rint_in(rng_t *r, int lo, int hi) { return lo + (int)(runif(r) * (double)(hi - lo + 1)); }

static void scene_step(scene_t *s)
{
    for (int i = 0; i < s->nmax; ++i) {
        tgt_t *t = &s->t[i];
        if (!t->on) {
            continue;
        }
        t->x += t->vx;
        t->y += t->vy;
        if (--t->left <= 0 || t->x < 0.0 || t->y < 0.0 || t->x > s->w - 1.0 || t->y > s->h - 1.0) {
            t->on = false;
        }
    }
    if (--s->gap > 0) {
        return;
    }
    s->gap = rint_in(&s->r, s->gap_lo, s->gap_hi);
    for (int i = 0; i < s->nmax; ++i) {
        tgt_t *t = &s->t[i];
        if (t->on) {
            continue;
        }
        t->on = true;
        t->x = s->margin + runif(&s->r) * (s->w - 1.0 - 2.0 * s->margin);
        t->y = (s->h > 1.5) ? s->margin + runif(&s->r) * (s->h - 1.0 - 2.0 * s->margin) : 0.0;
        t->vx = (2.0 * runif(&s->r) - 1.0) * s->vmax;
        t->vy = (s->h > 1.5) ? (2.0 * runif(&s->r) - 1.0) * s->vmax : 0.0;
        t->amp = s->amp_lo + runif(&s->r) * (s->amp_hi - s->amp_lo);
        t->left = rint_in(&s->r, s->life_lo, s->life_hi);
        break;
    }
}

/* Distance from (x, y) to the nearest live target (1e9 if none). */
static double nearest(const scene_t *s, double x, double y)
{
    double best = 1e9;
    for (int i = 0; i < s->nmax; ++i) {
        if (s->t[i].on) {
            double d = hypot(x - s->t[i].x, y - s->t[i].y);
            best = d < best ? d : best;
        }
    }
    return best;
}

static int live(const scene_t *s)
{
    int n = 0;
    for (int i = 0; i < s->nmax; ++i) {
        n += s->t[i].on ? 1 : 0;
    }
    return n;
}

/* ------------------------------------ work markers --------------------------------------- */
/* Called just before and just after every tracker update: the QEMU plugin qemu_marks.c counts
 * the guest instructions between them (run_soak.sh work-qemu). */
#include "pft_work_marks.h"

/* The update of one frame between the markers. */
#define MARKED(call) (pft_work_mark_begin(), mark_status_ = (call), pft_work_mark_end(), mark_status_)
static pft_status_t mark_status_;

/* ------------------------------------ checks ---------------------------------------------- */
typedef struct {
    const char *name;
    uint64_t frames, fail_status, fail_nan, fail_domain, false_frames, track_frames;
    uint64_t seg_frames[64], seg_false[64];
    double seg_cpu[64];         /* CPU seconds per segment (reported, never asserted) */
    clock_t t0;
    double worst;               /* largest |coordinate| reported */
    char first_fail[160];
} stat_t;

static int g_segments = 10;
static bool g_known;        /* --known: count known defects apart (they do not fail) */
static bool g_trace;        /* --trace: one line per frame, "trace <frame> <tracks>" */
static bool g_tbd_bern;     /* --tbd-bern: the tbd manager's search layer in Bernoulli form */
static bool g_tbd_bounded;  /* --tbd-bounded: the bounded preset, half the search particles */
static uint32_t g_pf_budget; /* --pf-budget K: the TBD model's birth budget (0: off) */
static uint32_t g_pte_budget; /* --pte-budget B: PTE-TBD's step_budget (0: off) */
static uint32_t g_pte_lines;  /* --pte-lines W: PTE-TBD's line_budget (0: off) */
static uint32_t g_tbd_search; /* --tbd-search N: its search particles (0: the default 1000) */
static uint64_t g_total;

static stat_t g_known_stat = {.name = "known"};

static double R(pft_real_t v) { return (double)pft_to_float(v); }

static void fail(stat_t *st, uint64_t *counter, uint64_t k, const char *what, double v)
{
    (*counter)++;
    if (st->first_fail[0] == '\0') {
        (void)snprintf(st->first_fail, sizeof st->first_fail, "frame %llu: %s (%g)",
                       (unsigned long long)k, what, v);
    }
}

/* A real result: finite, and inside [lo, hi] when lo < hi. */
static void check_real(stat_t *st, uint64_t k, const char *what, pft_real_t v, double lo, double hi)
{
    double d = R(v);
    if (!isfinite(d)) {
        fail(st, &st->fail_nan, k, what, d);
        return;
    }
    if (fabs(d) > st->worst) {
        st->worst = fabs(d);
    }
    if (lo < hi && (d < lo || d > hi)) {
        fail(st, &st->fail_domain, k, what, d);
    }
}

static void trace(uint64_t k, size_t n)
{
    if (g_trace) {
        printf("trace %llu %u\n", (unsigned long long)k, (unsigned)n);
    }
}

/* tbd and pf: also the existence probability of the search layer / the filter after the frame
 * (the share of its particles with E = 1 at the next frame follows it; only they are moved
 * and weighed on the pixels) */
static void trace_p(uint64_t k, size_t n, double p)
{
    if (g_trace) {
        printf("trace %llu %u %.4f\n", (unsigned long long)k, (unsigned)n, p);
    }
}

static void count_frame(stat_t *st, uint64_t k, bool false_track, bool track)
{
    int seg = (int)(k * (uint64_t)g_segments / g_total);
    clock_t now = clock();
    if (st->frames == 0u) {
        st->t0 = now;
    }
    st->seg_cpu[seg] += (double)(now - st->t0) / CLOCKS_PER_SEC;
    st->t0 = now;
    st->frames++;
    st->seg_frames[seg]++;
    if (false_track) {
        st->false_frames++;
        st->seg_false[seg]++;
    }
    if (track) {
        st->track_frames++;
    }
}

static int cmp_d(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* Prints the tracker's line; returns true when every check held. */
static bool report(const stat_t *st, bool quiet)
{
    double rate[64], sorted[64];
    for (int i = 0; i < g_segments; ++i) {
        rate[i] = st->seg_frames[i] ? (double)st->seg_false[i] / (double)st->seg_frames[i] : 0.0;
        sorted[i] = rate[i];
    }
    qsort(sorted, (size_t)g_segments, sizeof sorted[0], cmp_d);
    double med = sorted[g_segments / 2], mx = sorted[g_segments - 1];
    bool flat_checked = st->frames >= 100000u;
    bool flat = !flat_checked || mx <= 2.0 * med + 0.02;
    bool ok = st->fail_status == 0u && st->fail_nan == 0u && st->fail_domain == 0u && flat;
    printf("%-8s frames %llu  status-fail %llu  nan %llu  domain %llu  max|coord| %.1f  "
           "track-frames %.4f  false-track %.5f (segments: median %.5f max %.5f%s)  %s\n",
           st->name, (unsigned long long)st->frames, (unsigned long long)st->fail_status,
           (unsigned long long)st->fail_nan, (unsigned long long)st->fail_domain, st->worst,
           st->frames ? (double)st->track_frames / (double)st->frames : 0.0,
           st->frames ? (double)st->false_frames / (double)st->frames : 0.0, med, mx,
           flat_checked ? "" : ", flatness not checked below 100000 frames", ok ? "ok" : "FAIL");
    if (!quiet) {
        printf("%-8s false-track rate per segment:", st->name);
        for (int i = 0; i < g_segments; ++i) {
            printf(" %.5f", rate[i]);
        }
        printf("\n%-8s CPU seconds per segment:", st->name);
        for (int i = 0; i < g_segments; ++i) {
            printf(" %.2f", st->seg_cpu[i]);
        }
        printf("\n");
    }
    if (st->first_fail[0] != '\0') {
        printf("%-8s first failure: %s\n", st->name, st->first_fail);
    }
    if (!flat) {
        printf("%-8s false-track rate not flat: max segment %.5f > 2 x median %.5f + 0.02\n",
               st->name, mx, med);
    }
    return ok;
}

/* ------------------------------------ IR frames (tbd, pf) --------------------------------- */
#define IR_W 32
#define IR_H 32
#define IR_SIGMA 2.0
#define IR_PSF 0.7
static uint16_t g_u16[IR_W * IR_H];

/* z = noise + PSF of every target; raw = (z + 64) * 256 (gain 1/256, offset -64) */
static pft_frame_t ir_frame(scene_t *s, uint64_t k)
{
    const double c0 = 1.0 / (2.0 * 3.141592653589793 * IR_PSF * IR_PSF);
    for (int r = 0; r < IR_H; ++r) {
        for (int c = 0; c < IR_W; ++c) {
            double z = IR_SIGMA * rgauss(&s->r);
            for (int i = 0; i < s->nmax; ++i) {
                const tgt_t *t = &s->t[i];
                if (t->on && fabs(c - t->x) < 4.0 && fabs(r - t->y) < 4.0) {
                    double d2 = (c - t->x) * (c - t->x) + (r - t->y) * (r - t->y);
                    z += t->amp * c0 * exp(-d2 / (2.0 * IR_PSF * IR_PSF));
                }
            }
            double raw = floor((z + 64.0) * 256.0 + 0.5);
            g_u16[r * IR_W + c] = (uint16_t)(raw < 0.0 ? 0.0 : (raw > 65535.0 ? 65535.0 : raw));
        }
    }
    pft_frame_t f;
    memset(&f, 0, sizeof f);
    f.data = g_u16;
    f.width = IR_W;
    f.height = IR_H;
    f.stride_bytes = IR_W * 2u;
    f.format = PFT_PIX_U16;
    f.seq = (uint32_t)k;
    f.timestamp_us = k * 20000u;
    return f;
}

static void ir_scene(scene_t *s, uint64_t seed)
{
    memset(s, 0, sizeof *s);
    s->r.s = seed * 0x9E3779B97F4A7C15ull + 1u;
    s->nmax = 2;
    s->gap = 50;
    s->w = IR_W;
    s->h = IR_H;
    s->vmax = 0.5;
    s->amp_lo = 25.0;
    s->amp_hi = 35.0;
    s->life_lo = 60;
    s->life_hi = 400;
    s->gap_lo = 30;
    s->gap_hi = 300;
    s->margin = 3.0;
}

static void ir_tbd_cfg(pft_tbd_config_t *c)
{
    pft_tbd_config_recommended(c);
    c->width = IR_W;
    c->height = IR_H;
    c->noise_sigma = PFT_C(2.0);
    c->pixel_gain = PFT_C(0.00390625);
    c->pixel_offset = PFT_C(-64.0);
    c->i_min = PFT_C(15.0);
    c->i_max = PFT_C(45.0);
    c->vel_var[0] = c->vel_var[1] = PFT_C(0.1);
    c->n_search = 1000u;
    c->n_track = 200u;
    c->max_targets = 3u;
}

#define IR_LO (-0.5 - 1.0)
#define IR_HI_X (IR_W - 0.5 + 1.0)
#define IR_HI_Y (IR_H - 0.5 + 1.0)
#define IR_GATE 3.0

/* One workspace for whichever tracker runs; the bare-metal boards (4 MiB of RAM) get less. */
#ifndef SOAK_WS_BYTES
#define SOAK_WS_BYTES (4u << 20)
#endif
static uint8_t g_ws[SOAK_WS_BYTES];

static bool soak_tbd(uint64_t n, uint64_t seed, bool quiet)
{
    static pft_tbd_t t;
    stat_t st = {.name = "tbd"};
    pft_tbd_config_t c;
    ir_tbd_cfg(&c);
    c.seed = seed;
    if (g_tbd_bounded) {
        /* what pft_tbd_config_bounded changes over the recommended preset (the Bernoulli search
         * layer sharing its particle budget with the track layers, theta1), with the search
         * particles scaled as it scales them (3000 of 6000: 500 of the soak's 1000) */
        pft_tbd_config_t r, b;
        pft_tbd_config_recommended(&r);
        pft_tbd_config_bounded(&b);
        c.birth_share = b.birth_share;
        c.theta1 = b.theta1;
        c.n_search = (uint32_t)((uint64_t)c.n_search * b.n_search / r.n_search);
    }
    if (g_tbd_bern) {
        /* docs/algorithms.md 2.11: every search particle is moved and weighed at every frame,
         * whatever the existence probability (the per-frame work of docs/reliability.md) */
        c.birth_share = PFT_C(0.5);
    }
    if (g_tbd_search > 0u) {
        c.n_search = g_tbd_search;
    }
    size_t ws = pft_tbd_workspace_size(&c);
    if (ws == 0u || ws > sizeof g_ws || pft_tbd_init(&t, &c, g_ws, ws) != PFT_OK) {
        printf("tbd: configuration refused\n");
        return false;
    }
    scene_t s;
    ir_scene(&s, seed);
    for (uint64_t k = 0; k < n; ++k) {
        scene_step(&s);
        pft_frame_t f = ir_frame(&s, k);
        if (MARKED(pft_tbd_update(&t, &f)) != PFT_OK) {
            fail(&st, &st.fail_status, k, "update refused", 0.0);
            continue;
        }
        pft_tbd_track_t tr[3];
        size_t nt = pft_tbd_tracks(&t, tr, 3u);
        bool false_track = false;
        if (nt > c.max_targets) {
            fail(&st, &st.fail_domain, k, "track count", (double)nt);
        }
        for (size_t i = 0; i < nt && i < 3u; ++i) {
            check_real(&st, k, "track x", tr[i].x, IR_LO, IR_HI_X);
            check_real(&st, k, "track y", tr[i].y, IR_LO, IR_HI_Y);
            check_real(&st, k, "track vx", tr[i].vx, -20.0, 20.0);
            check_real(&st, k, "track vy", tr[i].vy, -20.0, 20.0);
            check_real(&st, k, "track intensity", tr[i].intensity, 0.0, 0.0);
            check_real(&st, k, "track p_exist", tr[i].p_exist, 0.0, 1.0001);
            if (nearest(&s, R(tr[i].x), R(tr[i].y)) > IR_GATE) {
                false_track = true;
            }
        }
        pft_tbd_estimate_t e;
        (void)pft_tbd_search_estimate(&t, &e);
        check_real(&st, k, "search p_exist", e.p_exist, 0.0, 1.0001);
        check_real(&st, k, "search log_mean_lr", e.log_mean_lr, 0.0, 0.0);
        if (e.valid) {
            check_real(&st, k, "search x", e.x, IR_LO, IR_HI_X);
            check_real(&st, k, "search y", e.y, IR_LO, IR_HI_Y);
        }
        trace_p(k, nt, R(e.p_exist));
        count_frame(&st, k, false_track, nt > 0u);
    }
    return report(&st, quiet);
}

static bool soak_pf(uint64_t n, uint64_t seed, bool quiet)
{
    static pft_pf_t pf;
    static pft_pf_tbd_model_t m;
    static uint8_t mws[1u << 16];
    stat_t st = {.name = "pf"};
    pft_tbd_config_t tc;
    ir_tbd_cfg(&tc);
    pft_pf_config_t c;
    pft_pf_config_default(&c);
    c.kind = PFT_PF_SIR;
    c.n_particles = 500u;
    c.seed = seed;
    size_t need = pft_pf_tbd_model_workspace_size(&tc);
    if (need == 0u || need > sizeof mws || pft_pf_tbd_model_init(&m, &tc, mws, need, &c.model) != PFT_OK) {
        printf("pf: model configuration refused\n");
        return false;
    }
    (void)pft_pf_tbd_model_set_budget(&m, g_pf_budget);
    size_t ws = pft_pf_workspace_size(&c);
    if (ws == 0u || ws > sizeof g_ws || pft_pf_init(&pf, &c, g_ws, ws) != PFT_OK) {
        printf("pf: configuration refused\n");
        return false;
    }
    scene_t s;
    ir_scene(&s, seed);
    s.nmax = 1; /* a single-target filter */
    for (uint64_t k = 0; k < n; ++k) {
        scene_step(&s);
        pft_frame_t f = ir_frame(&s, k);
        if (MARKED(pft_pf_update(&pf, &f)) != PFT_OK) {
            fail(&st, &st.fail_status, k, "update refused", 0.0);
            continue;
        }
        pft_real_t e[PFT_PF_TBD_DIM];
        (void)pft_pf_estimate(&pf, e);
        check_real(&st, k, "P(E)", e[PFT_PF_TBD_E], 0.0, 1.0001);
        check_real(&st, k, "x", e[PFT_PF_TBD_X], IR_LO, IR_HI_X);
        check_real(&st, k, "y", e[PFT_PF_TBD_Y], IR_LO, IR_HI_Y);
        check_real(&st, k, "vx", e[PFT_PF_TBD_VX], -20.0, 20.0);
        check_real(&st, k, "vy", e[PFT_PF_TBD_VY], -20.0, 20.0);
        check_real(&st, k, "I", e[PFT_PF_TBD_I], 0.0, 0.0);
        pft_pf_stats_t ps;
        (void)pft_pf_stats(&pf, &ps);
        check_real(&st, k, "ess_ratio", ps.ess_ratio, 0.0, 1.0001);
        check_real(&st, k, "log_evidence", ps.log_evidence, 0.0, 0.0);
        bool track = R(e[PFT_PF_TBD_E]) > 0.5;
        bool false_track = track && nearest(&s, R(e[PFT_PF_TBD_X]), R(e[PFT_PF_TBD_Y])) > IR_GATE;
        trace_p(k, track ? 1u : 0u, R(e[PFT_PF_TBD_E]));
        count_frame(&st, k, false_track, track);
    }
    return report(&st, quiet);
}

/* ------------------------------------ TSA (RGB frames) ------------------------------------ */
#define V_W 64
#define V_H 48
#define V_BOX 5 /* target half-size: a 11 x 11 square */
static uint8_t g_rgb[V_W * V_H * 3];
static uint8_t g_bg[V_W * V_H * 3];

/* Textured static background plus per-frame noise; the target is a reddish square with a
 * darker core. */
static pft_frame_t v_frame(scene_t *s, uint64_t k)
{
    for (int i = 0; i < V_W * V_H * 3; ++i) {
        int v = g_bg[i] + (int)(rnext(&s->r) % 17u) - 8;
        g_rgb[i] = (uint8_t)(v < 0 ? 0 : (v > 255 ? 255 : v));
    }
    for (int j = 0; j < s->nmax; ++j) {
        const tgt_t *t = &s->t[j];
        if (!t->on) {
            continue;
        }
        int cx = (int)floor(t->x + 0.5), cy = (int)floor(t->y + 0.5);
        for (int y = cy - V_BOX; y <= cy + V_BOX; ++y) {
            for (int x = cx - V_BOX; x <= cx + V_BOX; ++x) {
                if (x < 0 || y < 0 || x >= V_W || y >= V_H) {
                    continue;
                }
                bool core = abs(x - cx) <= 2 && abs(y - cy) <= 2;
                uint8_t *p = g_rgb + 3 * (y * V_W + x);
                p[0] = core ? 120 : 220;
                p[1] = core ? 20 : 60;
                p[2] = core ? 30 : 50;
            }
        }
    }
    pft_frame_t f;
    memset(&f, 0, sizeof f);
    f.data = g_rgb;
    f.width = V_W;
    f.height = V_H;
    f.stride_bytes = V_W * 3u;
    f.format = PFT_PIX_RGB888;
    f.seq = (uint32_t)k;
    return f;
}

static bool soak_tsa(uint64_t n, uint64_t seed, bool quiet)
{
    static pft_tsa_t t;
    stat_t st = {.name = "tsa"};
    pft_tsa_config_t c;
    pft_tsa_config_default(&c);
    c.width = V_W;
    c.height = V_H;
    c.max_target_w = 24u;
    c.max_target_h = 24u;
    c.n_particles = 60u;
    c.snake_points = 16u;
    c.init_passes = 5u;
    c.seed = seed;
    size_t ws = pft_tsa_workspace_size(&c);
    if (ws == 0u || ws > sizeof g_ws || pft_tsa_init(&t, &c, g_ws, ws) != PFT_OK) {
        printf("tsa: configuration refused\n");
        return false;
    }
    scene_t s;
    memset(&s, 0, sizeof s);
    s.r.s = seed * 0x9E3779B97F4A7C15ull + 7u;
    s.nmax = 1;
    s.gap = 20;
    s.w = V_W;
    s.h = V_H;
    s.vmax = 1.0;
    s.amp_lo = s.amp_hi = 1.0;
    s.life_lo = 100;
    s.life_hi = 600;
    s.gap_lo = 100;
    s.gap_hi = 1500;
    s.margin = V_BOX + 3.0;
    for (int i = 0; i < V_W * V_H * 3; ++i) {
        int y = (i / 3) / V_W, x = (i / 3) % V_W;
        g_bg[i] = (uint8_t)(60 + 40 * (((x / 8) + (y / 8)) % 2) + (int)(rnext(&s.r) % 30u) + 10 * (i % 3));
    }
    bool was_on = false;
    bool started = false;
    /* the tracker follows the target it was started on; a new target restarts it (a cue) */
    for (uint64_t k = 0; k < n; ++k) {
        scene_step(&s);
        pft_frame_t f = v_frame(&s, k);
        bool on = s.t[0].on;
        if (on && !was_on) {
            int cx = (int)floor(s.t[0].x + 0.5), cy = (int)floor(s.t[0].y + 0.5);
            pft_tsa_pt_t box[4] = {{(int16_t)(cx - V_BOX), (int16_t)(cy - V_BOX)},
                                   {(int16_t)(cx + V_BOX), (int16_t)(cy - V_BOX)},
                                   {(int16_t)(cx + V_BOX), (int16_t)(cy + V_BOX)},
                                   {(int16_t)(cx - V_BOX), (int16_t)(cy + V_BOX)}};
            if (pft_tsa_start(&t, &f, box, 4u) != PFT_OK) {
                fail(&st, &st.fail_status, k, "start refused", 0.0);
            } else {
                started = true;
            }
            was_on = on;
            count_frame(&st, k, false, true);
            continue;
        }
        was_on = on;
        if (!started) {
            count_frame(&st, k, false, false);
            continue;
        }
        if (MARKED(pft_tsa_update(&t, &f)) != PFT_OK) {
            fail(&st, &st.fail_status, k, "update refused", 0.0);
            continue;
        }
        pft_tsa_estimate_t e;
        (void)pft_tsa_estimate(&t, &e);
        /* domain: the frame grown by the largest target box (a kernel partly inside). With
         * --known, a known defect (docs/reliability.md, S1: the estimate of a target that
         * left the view runs away) is counted apart while the tracker says it is not
         * tracking; it still fails without --known. */
        bool excuse = g_known && (e.state == PFT_TSA_OUT_OF_VIEW || e.state == PFT_TSA_LOST ||
                                  e.state == PFT_TSA_WEAK);
        stat_t *dst = excuse ? &g_known_stat : &st;
        check_real(dst, k, "x", e.x, -0.5 - c.max_target_w, V_W - 0.5 + c.max_target_w);
        check_real(dst, k, "y", e.y, -0.5 - c.max_target_h, V_H - 0.5 + c.max_target_h);
        check_real(dst, k, "vx", e.vx, -100.0, 100.0);
        check_real(dst, k, "vy", e.vy, -100.0, 100.0);
        check_real(&st, k, "rho", e.rho, 0.0, 1.0001);
        check_real(&st, k, "beta_next", e.beta_next, 0.0, R(c.beta_max) + 0.001);
        if ((uint32_t)e.state > (uint32_t)PFT_TSA_REACQUIRED) {
            fail(&st, &st.fail_domain, k, "state", (double)e.state);
        }
        /* a re-acquisition reports the target found again: a track like the tracking states */
        bool track = e.state == PFT_TSA_TRACKING || e.state == PFT_TSA_PIONEER_ONLY ||
                     e.state == PFT_TSA_REACQUIRED;
        bool false_track = track && nearest(&s, R(e.x), R(e.y)) > 2.0 * V_BOX;
        trace(k, track ? 1u : 0u);
        count_frame(&st, k, false_track, track);
    }
    if (g_known_stat.fail_domain + g_known_stat.fail_nan > 0u) {
        printf("%-8s known defect S1 (--known): %llu estimates outside the domain while not "
               "tracking, largest |coord| %.1f, first: %s\n", st.name,
               (unsigned long long)(g_known_stat.fail_domain + g_known_stat.fail_nan),
               g_known_stat.worst, g_known_stat.first_fail);
    }
    return report(&st, quiet);
}

/* ------------------------------------ radar profiles (pte family) ------------------------- */
#define P_N 100
static uint16_t g_prof[P_N];

/* range-time profile: N(0, 1) noise + amplitude x exp(-(u - r)^2 / (2 0.5^2)); raw = (z + 32)
 * * 1024 (gain 1/1024, offset -32) */
static pft_frame_t p_frame(scene_t *s, uint64_t k)
{
    for (int u = 0; u < P_N; ++u) {
        double z = rgauss(&s->r);
        for (int i = 0; i < s->nmax; ++i) {
            const tgt_t *t = &s->t[i];
            if (t->on && fabs(u - t->x) < 4.0) {
                z += t->amp * exp(-(u - t->x) * (u - t->x) / 0.5);
            }
        }
        double raw = floor((z + 32.0) * 1024.0 + 0.5);
        g_prof[u] = (uint16_t)(raw < 0.0 ? 0.0 : (raw > 65535.0 ? 65535.0 : raw));
    }
    pft_frame_t f;
    memset(&f, 0, sizeof f);
    f.data = g_prof;
    f.width = P_N;
    f.height = 1u;
    f.stride_bytes = P_N * 2u;
    f.format = PFT_PIX_U16;
    f.seq = (uint32_t)k;
    return f;
}

static void p_scene(scene_t *s, uint64_t seed)
{
    memset(s, 0, sizeof *s);
    s->r.s = seed * 0x9E3779B97F4A7C15ull + 3u;
    s->nmax = 2;
    s->gap = 40;
    s->w = P_N;
    s->h = 1.0;
    s->vmax = 0.3;
    s->amp_lo = 3.0;
    s->amp_hi = 5.0;
    s->life_lo = 80;
    s->life_hi = 500;
    s->gap_lo = 40;
    s->gap_hi = 400;
    s->margin = 5.0;
}

static void p_in(pft_pte_input_t *in)
{
    in->n_range = P_N;
    in->n_doppler = 1u;
    in->pixel_gain = PFT_C(0.0009765625);
    in->pixel_offset = PFT_C(-32.0);
}


static void p_check(stat_t *st, const scene_t *s, uint64_t k, const pft_pte_report_t *r,
                    size_t n, size_t max, bool dp)
{
    bool false_track = false;
    if (n > max) {
        fail(st, &st->fail_domain, k, "report count", (double)n);
    }
    for (size_t i = 0; i < n && i < max; ++i) {
        check_real(st, k, "pos", r[i].pos[0], -0.5 - 2.0, P_N - 0.5 + 2.0);
        check_real(st, k, "vel", r[i].vel[0], -10.0, 10.0);
        check_real(st, k, "var", r[i].var[0], 0.0, dp ? 0.0001 : 1e4);
        check_real(st, k, "score", r[i].score, 0.0, 0.0);
        check_real(st, k, "amplitude", r[i].amplitude, 0.0, 0.0);
        if (nearest(s, R(r[i].pos[0]), 0.0) > 3.0) {
            false_track = true;
        }
    }
    trace(k, n);
    count_frame(st, k, false_track, n > 0u);
}

/* The three range-profile trackers share the loop: update, copy the reports out, check them.
 * The adapters give the loop one signature for each tracker's update and reports. */
typedef pft_status_t (*p_update_fn)(void *inst, const pft_frame_t *f);
typedef size_t (*p_reports_fn)(const void *inst, pft_pte_report_t *out, size_t max);

static bool p_loop(const char *name, void *inst, p_update_fn update, p_reports_fn reports,
                   size_t max, bool dp, uint64_t n, uint64_t seed, bool quiet)
{
    stat_t st = {.name = name};
    scene_t s;
    p_scene(&s, seed);
    for (uint64_t k = 0; k < n; ++k) {
        scene_step(&s);
        pft_frame_t f = p_frame(&s, k);
        if (MARKED(update(inst, &f)) != PFT_OK) {
            fail(&st, &st.fail_status, k, "update refused", 0.0);
            continue;
        }
        static pft_pte_report_t r[16];
        size_t nr = reports(inst, r, max);
        p_check(&st, &s, k, r, nr, max, dp);
    }
    return report(&st, quiet);
}

static uint32_t g_pte_lines_max; /* --pte-lines: most line_budget units of one update */
static pft_status_t pte_update_(void *p, const pft_frame_t *f)
{
    pft_status_t st = pft_pte_update(p, f);
    const uint32_t ops = ((const pft_pte_t *)p)->n_line_ops;
    g_pte_lines_max = ops > g_pte_lines_max ? ops : g_pte_lines_max;
    if (g_trace) {
        printf("pte_units %u\n", (unsigned)ops); /* the update's line_budget units */
    }
    return st;
}
static size_t pte_reports_(const void *p, pft_pte_report_t *r, size_t m) { return pft_pte_reports(p, r, m); }
static pft_status_t dp_update_(void *p, const pft_frame_t *f) { return pft_pte_dp_update(p, f); }
static size_t dp_reports_(const void *p, pft_pte_report_t *r, size_t m) { return pft_pte_dp_reports(p, r, m); }
static pft_status_t dbt_update_(void *p, const pft_frame_t *f) { return pft_pte_dbt_update(p, f); }
static size_t dbt_reports_(const void *p, pft_pte_report_t *r, size_t m) { return pft_pte_dbt_reports(p, r, m); }

static bool soak_pte(uint64_t n, uint64_t seed, bool quiet)
{
    static pft_pte_t p;
    pft_pte_config_t c;
    pft_pte_config_default(&c);
    p_in(&c.in);
    c.max_len = 20u;
    c.max_tracks = 3u;
    c.step_budget = (uint8_t)g_pte_budget;
    c.line_budget = (uint16_t)g_pte_lines;
    size_t ws = pft_pte_workspace_size(&c);
    if (ws == 0u || ws > sizeof g_ws || pft_pte_init(&p, &c, g_ws, ws) != PFT_OK) {
        printf("pte: configuration refused\n");
        return false;
    }
    g_pte_lines_max = 0u;
    bool ok = p_loop("pte", &p, pte_update_, pte_reports_, 3u, false, n, seed, quiet);
    if (g_pte_lines != 0u) {
        printf("pte: line_budget %u, most units in one update %u\n",
               (unsigned)g_pte_lines, (unsigned)g_pte_lines_max);
        if (g_pte_lines_max > g_pte_lines) {
            printf("pte: line_budget exceeded\n");
            ok = false;
        }
    }
    return ok;
}

static bool soak_pte_dp(uint64_t n, uint64_t seed, bool quiet)
{
    static pft_pte_dp_t p;
    pft_pte_dp_config_t c;
    pft_pte_dp_config_default(&c);
    p_in(&c.in);
    c.threshold = PFT_C(18.0);
    c.max_targets = 3u;
    size_t ws = pft_pte_dp_workspace_size(&c);
    if (ws == 0u || ws > sizeof g_ws || pft_pte_dp_init(&p, &c, g_ws, ws) != PFT_OK) {
        printf("pte_dp: configuration refused\n");
        return false;
    }
    return p_loop("pte_dp", &p, dp_update_, dp_reports_, 3u, true, n, seed, quiet);
}

static bool soak_pte_dbt(uint64_t n, uint64_t seed, bool quiet)
{
    static pft_pte_dbt_t p;
    pft_pte_dbt_config_t c;
    pft_pte_dbt_config_default(&c);
    p_in(&c.in);
    c.threshold = PFT_C(3.0);
    c.max_tracks = 16u;
    size_t ws = pft_pte_dbt_workspace_size(&c);
    if (ws == 0u || ws > sizeof g_ws || pft_pte_dbt_init(&p, &c, g_ws, ws) != PFT_OK) {
        printf("pte_dbt: configuration refused\n");
        return false;
    }
    return p_loop("pte_dbt", &p, dbt_update_, dbt_reports_, 16u, false, n, seed, quiet);
}

/* ------------------------------------ main ------------------------------------------------ */
typedef bool (*soak_fn)(uint64_t n, uint64_t seed, bool quiet);
static const struct {
    const char *name;
    soak_fn fn;
} g_trackers[] = {{"tbd", soak_tbd},       {"pf", soak_pf},          {"tsa", soak_tsa},
                  {"pte", soak_pte},       {"pte_dp", soak_pte_dp},  {"pte_dbt", soak_pte_dbt}};

int main(int argc, char **argv)
{
    uint64_t frames = 3000u, seed = 1u;
    const char *which = "all";
    bool quiet = false;
    for (int i = 1; i < argc; ++i) {
        if (strcmp(argv[i], "--frames") == 0 && i + 1 < argc) {
            frames = strtoull(argv[++i], NULL, 10);
        } else if (strcmp(argv[i], "--tracker") == 0 && i + 1 < argc) {
            which = argv[++i];
        } else if (strcmp(argv[i], "--seed") == 0 && i + 1 < argc) {
            seed = strtoull(argv[++i], NULL, 10);
        } else if (strcmp(argv[i], "--segments") == 0 && i + 1 < argc) {
            g_segments = atoi(argv[++i]);
        } else if (strcmp(argv[i], "--quiet") == 0) {
            quiet = true;
        } else if (strcmp(argv[i], "--known") == 0) {
            g_known = true;
        } else if (strcmp(argv[i], "--tbd-bern") == 0) {
            g_tbd_bern = true;
        } else if (strcmp(argv[i], "--tbd-bounded") == 0) {
            g_tbd_bounded = true;
        } else if (strcmp(argv[i], "--pf-budget") == 0 && i + 1 < argc) {
            g_pf_budget = (uint32_t)strtoul(argv[++i], NULL, 10);
        } else if (strcmp(argv[i], "--pte-budget") == 0 && i + 1 < argc) {
            g_pte_budget = (uint32_t)strtoul(argv[++i], NULL, 10);
        } else if (strcmp(argv[i], "--pte-lines") == 0 && i + 1 < argc) {
            g_pte_lines = (uint32_t)strtoul(argv[++i], NULL, 10);
        } else if (strcmp(argv[i], "--tbd-search") == 0 && i + 1 < argc) {
            g_tbd_search = (uint32_t)strtoul(argv[++i], NULL, 10);
        } else if (strcmp(argv[i], "--trace") == 0) {
            g_trace = true;
        } else {
            fprintf(stderr, "usage: pft_soak [--frames N] [--tracker NAME|all] [--seed S] "
                            "[--segments K] [--quiet] [--known] [--trace] [--tbd-bern] [--tbd-bounded] [--tbd-search N] [--pf-budget K] [--pte-budget B] [--pte-lines W]\n");
            return 2;
        }
    }
    if (frames == 0u || g_segments < 1 || g_segments > 64) {
        fprintf(stderr, "pft_soak: --frames >= 1, --segments 1..64\n");
        return 2;
    }
    g_total = frames;
#if defined(PFT_NUMERIC_Q16)
    printf("pft_soak: q16 build, %llu frames per tracker, seed %llu\n", (unsigned long long)frames,
           (unsigned long long)seed);
#else
    printf("pft_soak: float build, %llu frames per tracker, seed %llu\n", (unsigned long long)frames,
           (unsigned long long)seed);
#endif
    bool ok = true, any = false;
    for (size_t i = 0; i < sizeof g_trackers / sizeof g_trackers[0]; ++i) {
        if (strcmp(which, "all") == 0 || strcmp(which, g_trackers[i].name) == 0) {
            any = true;
            ok = g_trackers[i].fn(frames, seed, quiet) && ok;
            fflush(stdout);
        }
    }
    if (!any) {
        fprintf(stderr, "pft_soak: unknown tracker %s\n", which);
        return 2;
    }
    printf("pft_soak: %s\n", ok ? "PASS" : "FAIL");
    return ok ? 0 : 1;
}
