/*
 * ir_probe: the IR pipeline's library calls (the preprocessing stage, the clutter map and the
 * TBD manager) over a headerless raw sequence of little-endian u16 frames, with the settings
 * `pft run` gives them for the shipped IR scenarios (host_tools/tbd/ir_pipeline.cpp with the
 * defaults of TrackerSettings: temporal background, clutter map, the recommended preset with
 * full-frame births, the scene-motion test pft_tbd_scene raising the map). It builds on every preset (host,
 * AArch64 Linux, bare-metal Cortex-M with semihosting file input), so the same frame bytes
 * give the instructions per frame of pft_pre_update_inplace, the clutter map
 * (pft_pre_clutter_update_inplace, or pft_pre_clutter_update with MAP copy) and pft_tbd_update
 * on every instruction set: each call is bracketed by pft_work_mark_begin / pft_work_mark_end
 * (the QEMU plugin tests/soak/qemu_marks.c counts between them) inside irp_measured
 * (callgrind's --toggle-collect and --dump-after on the host), so the counts come in threes per
 * frame: stage, map, manager. Measurement tool, not a test:
 * host_tools/scripts/ir_cost_targets.sh, docs/results/ir_clutter.md ("Branch ira53", "Branch
 * irmap").
 *
 *   ir_probe IN.u16 W H BITS FRAMES SEED PARTICLES [MAP [BLOCK [MARKS [MEAN PERSIST ALPHA [MAP8 [ANCHOR]]]]]]
 *   (the scenario's bit depth, frame count, seed and search particles: 14, N, 1, 12000 for
 *   procedural_384x288.json; MAP: inplace (default, as pft run: the map's output over the
 *   stage's residual) or copy (the map's own output buffer, as before branch irmap); BLOCK: the
 *   map's pft_pre_clutter_config_t.block, 0 (default, as pft run), 2 or 4; MARKS: 3 (default:
 *   the work markers bracket the stage, the map and the manager) or 2 (the map's call is not
 *   bracketed, so the QEMU plugin's regions alternate stage, manager, odd and even, as
 *   host_tools/scripts/a53_mca.py reads them; callgrind's dumps stay three per frame) or 1 (the
 *   stage's call is not bracketed: the regions alternate map, manager, for a53_mca.py model
 *   --regions map,manager);
 *   MEAN PERSIST ALPHA: the tracker fields clutter_mean (0 or 1), clutter_persist (0..) and
 *   clutter_alpha (a real, as in the scenario) the map is configured with, as
 *   make_clutter_config does; default 0 0 0.1, the pipeline's defaults; "1 4 0.2" is the best
 *   setting of docs/results/ir_clutter.md; MAP8: 1 for pft_pre_clutter_config_t.map8; ANCHOR: 1
 *   for pft_pre_clutter_config_t.anchor, default 0)
 * Prints per frame: seq, the stage's flags, then every confirmed track (id x y, 3 decimals),
 * and at the end the workspace sizes and three FNV-1a checksums over all frames, outside the
 * measured calls: of the stage's residual, of the map's output and of every confirmed track's
 * fields (all their bits, not the 3 decimals), so that two builds' outputs can be compared bit
 * for bit under QEMU. Memory: one static arena of IRP_ARENA_BYTES (the
 * bare-metal builds set it to what the board's 4 MiB of RAM leaves); too small is reported.
 *
 *   ir_probe -c PROBE.CFG IN.u16 FRAMES
 *   (the flight build of any tbd_ir scenario, docs/results/ir_clutter.md "Branch ircost31":
 *   `pft bench --scenario F --frames N --seed S --probe-out DIR [--backgrounds DIR]` writes
 *   DIR/frames.u16 and DIR/probe.cfg, the library configurations the host pipeline
 *   (host_tools/tbd/ir_pipeline.cpp) builds from the scenario and its settings between the
 *   calls, key value lines (tests/tools/ir_probe_fields.h; a file of the other numeric is
 *   refused). Per frame the probe makes the pipeline's library calls as IrPipeline::step makes
 *   them: the stage (pft_pre_update, or pft_pre_update_inplace on its own copy of the frame),
 *   the flat field (pft_pre_flat_update over the residual, or a copy of it, with the raw frame
 *   as its level frame under flat_relative), the clutter map (pft_pre_clutter_update or
 *   _inplace with the stage's shift), the manager (pft_tbd_set_shift under integ_shift, then
 *   pft_tbd_update on the map's output, or on an all-masked frame without evidence) and after it
 *   pft_tbd_tracks (pft_tbd_tentative with scene_tentative), pft_tbd_scene_update and
 *   pft_pre_clutter_raise under the tracks found moving with the scene: five measured slots
 *   per frame, stage, flat, map, manager, after (a call the configuration does not make leaves
 *   its slot nearly empty). Prints per frame "F seq flags F shift X Y ev E map H tracks N" and
 *   each reported track's id and the bits of x, y, vx, vy, intensity, p_exist, the lines
 *   DIR/expect.txt holds from the host pipeline (ctest host_ir_probe_flight compares them),
 *   and at the end FNV-1a checksums of the stage's residual, the flat field's and the map's
 *   outputs and the reported tracks. host_tools/scripts/ir_cost_targets.sh with IRC_FLIGHT
 *   drives it on every target.)
 */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "pft/pft_pre.h"
#include "pft/pft_tbd.h"
#include "pft/pft_tbd_scene.h"
#include "pft_work_marks.h"
#include "ir_probe_fields.h"

#ifndef IRP_ARENA_BYTES
#define IRP_ARENA_BYTES (96u * 1024u * 1024u)
#endif

static uint64_t g_arena[IRP_ARENA_BYTES / 8u];
static size_t g_used;

static void *arena_take(size_t n)
{
    const size_t words = (n + 7u) / 8u;
    if (words > sizeof g_arena / 8u - g_used) {
        return NULL;
    }
    void *p = &g_arena[g_used];
    g_used += words;
    return p;
}

/* FNV-1a, 64 bits, over n bytes */
static uint64_t fnv1a(uint64_t h, const void *p, size_t n)
{
    const unsigned char *b = (const unsigned char *)p;
    for (size_t i = 0; i < n; ++i) {
        h = (h ^ b[i]) * 1099511628211ull;
    }
    return h;
}

/* the frame's rows (w 16-bit pixels each) into h */
static uint64_t fnv1a_frame(uint64_t h, const pft_frame_t *f)
{
    for (uint32_t r = 0; r < f->height; ++r) {
        h = fnv1a(h, (const unsigned char *)f->data + (size_t)r * f->stride_bytes, 2u * (size_t)f->width);
    }
    return h;
}

/* a confirmed track's fields (no padding bytes) into h */
static uint64_t fnv1a_track(uint64_t h, const pft_tbd_track_t *t)
{
    h = fnv1a(h, &t->id, sizeof t->id);
    h = fnv1a(h, &t->x, sizeof t->x);
    h = fnv1a(h, &t->y, sizeof t->y);
    h = fnv1a(h, &t->vx, sizeof t->vx);
    h = fnv1a(h, &t->vy, sizeof t->vy);
    h = fnv1a(h, &t->intensity, sizeof t->intensity);
    h = fnv1a(h, t->pos_cov, sizeof t->pos_cov);
    h = fnv1a(h, &t->p_exist, sizeof t->p_exist);
    h = fnv1a(h, &t->log_mean_lr, sizeof t->log_mean_lr);
    h = fnv1a(h, &t->first_frame, sizeof t->first_frame);
    h = fnv1a(h, &t->age, sizeof t->age);
    h = fnv1a(h, &t->last_seq, sizeof t->last_seq);
    h = fnv1a(h, &t->last_timestamp_us, sizeof t->last_timestamp_us);
    return fnv1a(h, &t->sprt_llr, sizeof t->sprt_llr);
}

/* double -> pft_real_t as the host tools convert (host_tools/common/real.hpp) */
static pft_real_t to_real(double v)
{
#ifdef PFT_NUMERIC_Q16
    const double s = nearbyint(v * 65536.0);
    if (s > 2147483647.0) {
        return PFT_REAL_MAX;
    }
    if (s < -2147483647.0) {
        return PFT_REAL_MIN;
    }
    return (pft_real_t)s;
#else
    return (pft_real_t)v;
#endif
}

static double from_real(pft_real_t v)
{
#ifdef PFT_NUMERIC_Q16
    return (double)v / 65536.0;
#else
    return (double)v;
#endif
}

/* One measured call: the stage (pre), the clutter map (cl) or the manager (tbd). */
typedef struct {
    pft_pre_t *pre;
    pft_pre_clutter_t *cl;
    pft_tbd_t *tbd;
    const pft_frame_t *f;
    uint16_t *buf;   /* stage: the frame's buffer; map in place: the residual's */
    int32_t sx, sy;  /* map: the scene's shift */
    int ev;          /* map: evidence */
    int inplace;     /* map: pft_pre_clutter_update_inplace */
    int unmarked;    /* no work markers around this call (MARKS 2: the map; 1: the stage) */
    pft_status_t (*fn)(void *ctx); /* mode -c: the call (or none: NULL with pre, cl and tbd NULL) */
    void *ctx;
} irp_call_t;

/* The three measured calls go through one function that callgrind toggles on and dumps after
 * (host: --toggle-collect=irp_measured --dump-after=irp_measured; two functions each with both
 * options gave empty dumps with valgrind 3.19), so the dumps come in the order stage, map,
 * manager; and the work markers bracket each call for the QEMU plugin. A count is the library
 * call and a few constant instructions of the call itself. */
__attribute__((noinline, noclone)) pft_status_t irp_measured(const irp_call_t *c);
__attribute__((noinline, noclone)) pft_status_t irp_measured(const irp_call_t *c)
{
    pft_status_t s;
    if (!c->unmarked) {
        pft_work_mark_begin();
    }
    if (c->fn != NULL) {
        s = c->fn(c->ctx);
    } else if (c->pre == NULL && c->cl == NULL && c->tbd == NULL) {
        s = PFT_OK; /* mode -c: a call the configuration does not make (its slot still counted) */
    } else if (c->pre != NULL) {
        s = pft_pre_update_inplace(c->pre, c->f, c->buf);
    } else if (c->cl != NULL) {
        s = c->inplace ? pft_pre_clutter_update_inplace(c->cl, c->f, (int16_t *)(void *)c->buf,
                                                        c->sx, c->sy, c->ev != 0)
                       : pft_pre_clutter_update(c->cl, c->f, c->sx, c->sy, c->ev != 0);
    } else {
        s = pft_tbd_update(c->tbd, c->f);
    }
    if (!c->unmarked) {
        pft_work_mark_end();
    }
    return s;
}

/* ---- mode -c: the flight build of any tbd_ir scenario ----------------------------------- */

/* The configurations of probe.cfg (`pft bench --probe-out`, host_tools/tbd/ir_probe_out.cpp):
 * the library's structs as the host pipeline builds them and its settings between the calls. */
typedef struct {
    pft_pre_config_t pre;
    pft_pre_flat_config_t flat;
    pft_pre_clutter_config_t cl;
    pft_tbd_config_t tbd;
    pft_tbd_scene_config_t sc;
    unsigned long long pipe[16]; /* IRP_PIPELINE_FIELDS in order */
    unsigned n_pre, n_flat, n_cl, n_tbd, n_sc, n_pipe; /* keys read per section */
} irp_setup_t;

enum {
#define IRP_PIPE_ENUM(name) IRP_PIPE_##name,
    IRP_PIPELINE_FIELDS(IRP_PIPE_ENUM) IRP_PIPE_COUNT
};
#define IRP_COUNT(F, K, T) +1u

/* one "key value" line into s; 0 when the key is known and its value read */
static int irp_read_field(irp_setup_t *s, const char *key, const char *val)
{
    char *e = NULL;
    const char *dot = strchr(key, '.');
    if (dot == NULL) {
        return 1;
    }
    const size_t sl = (size_t)(dot - key);
    const char *f = dot + 1;
#define IRP_SEC(name) (sl == sizeof(name) - 1u && strncmp(key, name, sl) == 0)
#define IRP_RD_U(c, F, T) (c).F = (T)strtoull(val, &e, 10)
#define IRP_RD_I(c, F, T) (c).F = (T)strtoll(val, &e, 10)
#define IRP_RD_R(c, F, T)                                   \
    do {                                                    \
        const uint32_t u_ = (uint32_t)strtoul(val, &e, 16); \
        memcpy(&(c).F, &u_, sizeof u_);                     \
    } while (0)
    if (IRP_SEC("pipeline")) {
        unsigned k = 0u;
#define IRP_RD_PIPE(name)                          \
    if (strcmp(f, #name) == 0) {                   \
        s->pipe[k] = strtoull(val, &e, 10);        \
        s->n_pipe++;                               \
        return e == val;                           \
    }                                              \
    k++;
        IRP_PIPELINE_FIELDS(IRP_RD_PIPE)
        return 1;
    }
#define IRP_RD_PRE(F, K, T)      \
    if (strcmp(f, #F) == 0) {    \
        IRP_RD_##K(s->pre, F, T); \
        s->n_pre++;              \
        return e == val;         \
    }
#define IRP_RD_FLAT(F, K, T)      \
    if (strcmp(f, #F) == 0) {     \
        IRP_RD_##K(s->flat, F, T); \
        s->n_flat++;              \
        return e == val;          \
    }
#define IRP_RD_CL(F, K, T)      \
    if (strcmp(f, #F) == 0) {   \
        IRP_RD_##K(s->cl, F, T); \
        s->n_cl++;              \
        return e == val;        \
    }
#define IRP_RD_TBD(F, K, T)      \
    if (strcmp(f, #F) == 0) {    \
        IRP_RD_##K(s->tbd, F, T); \
        s->n_tbd++;              \
        return e == val;         \
    }
#define IRP_RD_SC(F, K, T)      \
    if (strcmp(f, #F) == 0) {   \
        IRP_RD_##K(s->sc, F, T); \
        s->n_sc++;              \
        return e == val;        \
    }
    if (IRP_SEC("pre")) {
        IRP_PRE_FIELDS(IRP_RD_PRE)
    } else if (IRP_SEC("flat")) {
        IRP_FLAT_FIELDS(IRP_RD_FLAT)
    } else if (IRP_SEC("clutter")) {
        IRP_CLUTTER_FIELDS(IRP_RD_CL)
    } else if (IRP_SEC("tbd")) {
        IRP_TBD_FIELDS(IRP_RD_TBD)
    } else if (IRP_SEC("scene")) {
        IRP_SCENE_FIELDS(IRP_RD_SC)
    }
    return 1;
}

/* probe.cfg into s (every struct from its defaults, then every listed field of the sections
 * the pipeline runs); 0 on success */
static int irp_read_setup(const char *path, irp_setup_t *s)
{
    memset(s, 0, sizeof *s);
    pft_pre_config_default(&s->pre);
    pft_pre_flat_config_default(&s->flat);
    pft_pre_clutter_config_default(&s->cl);
    pft_tbd_config_default(&s->tbd);
    pft_tbd_scene_config_default(&s->sc);
    FILE *in = fopen(path, "r");
    if (in == NULL) {
        fprintf(stderr, "ir_probe: cannot open %s\n", path);
        return 1;
    }
    char line[256];
    int ended = 0, numeric_ok = 0;
#ifdef PFT_NUMERIC_Q16
    const char *numeric = "q16";
#else
    const char *numeric = "float";
#endif
    while (!ended && fgets(line, (int)sizeof line, in) != NULL) {
        char key[96], val[64];
        if (line[0] == '#' || line[0] == '\n' || line[0] == '\r') {
            continue;
        }
        if (strncmp(line, "end", 3u) == 0) {
            ended = 1;
            continue;
        }
        if (sscanf(line, "%95s %63s", key, val) != 2) {
            fprintf(stderr, "ir_probe: %s: cannot read the line: %s", path, line);
            fclose(in);
            return 1;
        }
        if (strcmp(key, "numeric") == 0) {
            if (strcmp(val, numeric) != 0) {
                fprintf(stderr, "ir_probe: %s was written by a %s build, this is %s\n", path, val, numeric);
                fclose(in);
                return 1;
            }
            numeric_ok = 1;
            continue;
        }
        if (irp_read_field(s, key, val) != 0) {
            fprintf(stderr, "ir_probe: %s: unknown key or bad value: %s %s\n", path, key, val);
            fclose(in);
            return 1;
        }
    }
    fclose(in);
    const unsigned want_pre = 0u IRP_PRE_FIELDS(IRP_COUNT), want_flat = 0u IRP_FLAT_FIELDS(IRP_COUNT),
                   want_cl = 0u IRP_CLUTTER_FIELDS(IRP_COUNT), want_tbd = 0u IRP_TBD_FIELDS(IRP_COUNT),
                   want_sc = 0u IRP_SCENE_FIELDS(IRP_COUNT);
    if (!ended || !numeric_ok || s->n_pipe != (unsigned)IRP_PIPE_COUNT || s->n_pre != want_pre ||
        s->n_tbd != want_tbd || s->n_flat != (s->pipe[IRP_PIPE_flat] ? want_flat : 0u) ||
        s->n_cl != (s->pipe[IRP_PIPE_clutter] ? want_cl : 0u) ||
        s->n_sc != (s->pipe[IRP_PIPE_scene] ? want_sc : 0u)) {
        fprintf(stderr, "ir_probe: %s is incomplete (keys: pipeline %u/%u, pre %u/%u, flat %u, clutter %u, tbd %u/%u, scene %u; end %d, numeric %d)\n",
                path, s->n_pipe, (unsigned)IRP_PIPE_COUNT, s->n_pre, want_pre, s->n_flat, s->n_cl, s->n_tbd,
                want_tbd, s->n_sc, ended, numeric_ok);
        return 1;
    }
    return 0;
}

/* the state of one frame of mode -c, shared by its measured calls */
typedef struct {
    irp_setup_t *s;
    pft_pre_t *pre;
    pft_pre_flat_t *flat;
    pft_pre_clutter_t *cl;
    pft_tbd_t *tbd;
    pft_tbd_scene_t *scn;
    pft_frame_t raw;     /* the frame as the sensor gives it (U16) */
    uint16_t *buf;       /* the stage's input copy and residual (pre.inplace), else the flat step's copy of the residual */
    pft_frame_t res;     /* the residual after the last call */
    pft_frame_t mf, tf;  /* the map's and the manager's frames (clutter_step, IrPipeline::step) */
    pft_pre_stats_t st;
    int ev;
    pft_tbd_track_t *tr, *tent;     /* max_targets each */
    pft_tbd_scene_track_t *sin;     /* 2 max_targets */
    pft_tbd_scene_out_t *sout;
    size_t n_rep;                   /* reported tracks after the scene test, in tr[0..n_rep) */
} irp_flight_t;

static pft_status_t irp_f_stage(void *ctx)
{
    irp_flight_t *F = (irp_flight_t *)ctx;
    if (F->s->pre.inplace) {
        pft_frame_t in = F->raw;
        in.data = F->buf;
        return pft_pre_update_inplace(F->pre, &in, F->buf);
    }
    return pft_pre_update(F->pre, &F->raw);
}

static pft_status_t irp_f_flat(void *ctx)
{
    irp_flight_t *F = (irp_flight_t *)ctx;
    return pft_pre_flat_update(F->flat, &F->res, (int16_t *)(void *)F->buf,
                               F->s->pipe[IRP_PIPE_flat_relative] ? &F->raw : NULL, F->ev != 0);
}

static pft_status_t irp_f_map(void *ctx)
{
    irp_flight_t *F = (irp_flight_t *)ctx;
    return F->s->cl.inplace ? pft_pre_clutter_update_inplace(F->cl, &F->mf, (int16_t *)(uintptr_t)F->mf.data,
                                                             F->st.shift[0], F->st.shift[1], F->ev != 0)
                            : pft_pre_clutter_update(F->cl, &F->mf, F->st.shift[0], F->st.shift[1], F->ev != 0);
}

static pft_status_t irp_f_manager(void *ctx)
{
    irp_flight_t *F = (irp_flight_t *)ctx;
    return pft_tbd_update(F->tbd, &F->tf);
}

/* after the manager (IrPipeline::step and scene_test): its reported (and with scene_tentative
 * its tentative, age > 0) tracks through the scene-motion test, the map raised under those
 * found moving with the scene, the reported ones kept in tr[0..n_rep) */
static pft_status_t irp_f_after(void *ctx)
{
    irp_flight_t *F = (irp_flight_t *)ctx;
    const size_t mt = F->s->tbd.max_targets;
    size_t n = pft_tbd_tracks(F->tbd, F->tr, mt);
    if (n > mt) {
        n = mt;
    }
    F->n_rep = n;
    if (!F->s->pipe[IRP_PIPE_scene]) {
        return PFT_OK;
    }
    size_t n_all = n;
    for (size_t i = 0; i < n; ++i) {
        F->sin[i].id = F->tr[i].id;
        F->sin[i].x = F->tr[i].x;
        F->sin[i].y = F->tr[i].y;
        F->sin[i].tentative = false;
        F->sin[i].pos_var = pft_add(F->tr[i].pos_cov[0], F->tr[i].pos_cov[2]);
        F->sin[i].p_exist = F->tr[i].p_exist;
    }
    if (F->s->pipe[IRP_PIPE_scene_tentative]) {
        size_t nt = pft_tbd_tentative(F->tbd, F->tent, mt);
        if (nt > mt) {
            nt = mt;
        }
        for (size_t k = 0; k < nt; ++k) {
            const pft_tbd_track_t *r = &F->tent[k];
            if (r->age == 0u) {
                continue;
            }
            F->sin[n_all].id = r->id;
            F->sin[n_all].x = r->x;
            F->sin[n_all].y = r->y;
            F->sin[n_all].tentative = true;
            F->sin[n_all].pos_var = pft_add(r->pos_cov[0], r->pos_cov[2]);
            F->sin[n_all].p_exist = r->p_exist;
            n_all++;
        }
    }
    const pft_status_t s = pft_tbd_scene_update(F->scn, F->sin, n_all, F->ev ? F->st.shift[0] : 0,
                                                F->ev ? F->st.shift[1] : 0, F->sout);
    if (s != PFT_OK) {
        return s;
    }
    size_t kept = 0;
    for (size_t i = 0; i < n_all; ++i) {
        if (F->sout[i].decision == PFT_TBD_SCENE_CLUTTER && F->s->pipe[IRP_PIPE_clutter]) {
            (void)pft_pre_clutter_raise(F->cl, F->sout[i].px, F->sout[i].py, 16u * 1024u);
        }
        if (i < n && F->sout[i].decision == PFT_TBD_SCENE_REPORT) {
            F->tr[kept++] = F->tr[i];
        }
    }
    F->n_rep = kept;
    return PFT_OK;
}

static uint32_t irp_bits(pft_real_t v)
{
    uint32_t u;
    memcpy(&u, &v, sizeof u);
    return u;
}

/* ir_probe -c PROBE.CFG IN.u16 FRAMES: see the top of the file */
static int run_flight(int argc, char **argv)
{
    if (argc != 5) {
        fprintf(stderr, "usage: ir_probe -c PROBE.CFG IN.u16 FRAMES\n");
        return 2;
    }
    static irp_setup_t S;
    if (irp_read_setup(argv[2], &S) != 0) {
        return 2;
    }
    const uint32_t frames = (uint32_t)strtoul(argv[4], NULL, 10);
    const uint16_t W = S.pre.width, H = S.pre.height;
    const size_t npix = (size_t)W * H;
    const char *field = NULL;
    if (pft_pre_config_check(&S.pre, &field) != PFT_OK ||
        (S.pipe[IRP_PIPE_flat] && pft_pre_flat_config_check(&S.flat, &field) != PFT_OK) ||
        (S.pipe[IRP_PIPE_clutter] && pft_pre_clutter_config_check(&S.cl, &field) != PFT_OK) ||
        pft_tbd_config_check(&S.tbd, &field) != PFT_OK ||
        (S.pipe[IRP_PIPE_scene] && pft_tbd_scene_config_check(&S.sc, &field) != PFT_OK)) {
        fprintf(stderr, "ir_probe: configuration refused (field %s)\n", field ? field : "?");
        return 2;
    }
    const size_t pre_b = pft_pre_workspace_size(&S.pre);
    const size_t flat_b = S.pipe[IRP_PIPE_flat] ? pft_pre_flat_workspace_size(&S.flat) : 0u;
    const size_t cl_b = S.pipe[IRP_PIPE_clutter] ? pft_pre_clutter_workspace_size(&S.cl) : 0u;
    const size_t tbd_b = pft_tbd_workspace_size(&S.tbd);
    const size_t scn_b = S.pipe[IRP_PIPE_scene] ? pft_tbd_scene_workspace_size(&S.sc) : 0u;
    const size_t mt = S.tbd.max_targets;
    printf("workspace bytes: stage %lu, flat field %lu, clutter map %lu, manager %lu, scene test %lu, frame and copy %lu\n",
           (unsigned long)pre_b, (unsigned long)flat_b, (unsigned long)cl_b, (unsigned long)tbd_b,
           (unsigned long)scn_b, (unsigned long)(npix * 4u));
    static irp_flight_t F;
    memset(&F, 0, sizeof F);
    F.s = &S;
    uint16_t *raw = arena_take(npix * 2u);
    F.buf = arena_take(npix * 2u);
    void *pre_w = arena_take(pre_b), *flat_w = flat_b ? arena_take(flat_b) : raw,
         *cl_w = cl_b ? arena_take(cl_b) : raw, *tbd_w = arena_take(tbd_b),
         *scn_w = scn_b ? arena_take(scn_b) : raw;
    F.tr = arena_take(mt * sizeof *F.tr);
    F.tent = arena_take(mt * sizeof *F.tent);
    F.sin = arena_take(2u * mt * sizeof *F.sin);
    F.sout = arena_take(2u * mt * sizeof *F.sout);
    if (raw == NULL || F.buf == NULL || pre_w == NULL || flat_w == NULL || cl_w == NULL || tbd_w == NULL ||
        scn_w == NULL || F.tr == NULL || F.tent == NULL || F.sin == NULL || F.sout == NULL) {
        fprintf(stderr, "ir_probe: arena of %lu bytes too small (needs about %lu)\n", (unsigned long)IRP_ARENA_BYTES,
                (unsigned long)(npix * 4u + pre_b + flat_b + cl_b + tbd_b + scn_b +
                                mt * (2u * sizeof *F.tr + 2u * sizeof *F.sin + 2u * sizeof *F.sout) + 96u));
        return 3;
    }
    static pft_pre_t pre;
    static pft_pre_flat_t flat;
    static pft_pre_clutter_t cl;
    static pft_tbd_t tbd;
    static pft_tbd_scene_t scn;
    if (pft_pre_init(&pre, &S.pre, pre_w, pre_b) != PFT_OK ||
        (flat_b && pft_pre_flat_init(&flat, &S.flat, flat_w, flat_b) != PFT_OK) ||
        (scn_b && pft_tbd_scene_init(&scn, &S.sc, scn_w, scn_b) != PFT_OK) ||
        (cl_b && pft_pre_clutter_init(&cl, &S.cl, cl_w, cl_b) != PFT_OK) ||
        pft_tbd_init(&tbd, &S.tbd, tbd_w, tbd_b) != PFT_OK) {
        fprintf(stderr, "ir_probe: init failed\n");
        return 1;
    }
    F.pre = &pre;
    F.flat = &flat;
    F.cl = &cl;
    F.tbd = &tbd;
    F.scn = &scn;
    FILE *in = fopen(argv[3], "rb");
    if (in == NULL) {
        fprintf(stderr, "ir_probe: cannot open %s\n", argv[3]);
        return 1;
    }
    uint64_t h_res = 14695981039346656037ull, h_flat = h_res, h_map = h_res, h_trk = h_res;
    static const char *const names[5] = {"stage", "flat", "map", "manager", "after"};
    for (uint32_t seq = 1; seq <= frames; ++seq) {
        if (fread(raw, 2u, npix, in) != npix) {
            fprintf(stderr, "ir_probe: %s holds fewer than %lu frames\n", argv[3], (unsigned long)frames);
            return 1;
        }
        /* the frame as the host's u16_frame makes it (ir_commands.cpp) */
        memset(&F.raw, 0, sizeof F.raw);
        F.raw.data = raw;
        F.raw.width = W;
        F.raw.height = H;
        F.raw.stride_bytes = 2u * W;
        F.raw.format = PFT_PIX_U16;
        F.raw.bit_depth = (uint8_t)S.pipe[IRP_PIPE_bits];
        F.raw.seq = seq;
        F.raw.timestamp_us = (uint64_t)(seq - 1u) * 40000u;
        if (S.pre.inplace) {
            memcpy(F.buf, raw, npix * 2u); /* the pipeline's own copy (IrPipeline::preprocess) */
        }
        pft_status_t s = PFT_OK;
        uint64_t h_map_frame = 14695981039346656037ull;
        for (int k = 0; k < 5 && s == PFT_OK; ++k) {
            irp_call_t call;
            memset(&call, 0, sizeof call);
            call.ctx = &F;
            if (k == 0) {
                call.fn = irp_f_stage;
            } else if (k == 1 && S.pipe[IRP_PIPE_flat]) {
                call.fn = irp_f_flat;
            } else if (k == 2 && S.pipe[IRP_PIPE_clutter]) {
                call.fn = irp_f_map;
            } else if (k == 3) {
                call.fn = irp_f_manager;
            } else if (k == 4) {
                call.fn = irp_f_after;
            }
            if (k == 2) {
                /* the map's frame (clutter_step) */
                memset(&F.mf, 0, sizeof F.mf);
                F.mf.data = F.res.data;
                F.mf.width = W;
                F.mf.height = H;
                F.mf.stride_bytes = F.res.stride_bytes;
                F.mf.format = PFT_PIX_RES16;
                F.mf.bit_depth = 16u;
            } else if (k == 3) {
                /* the manager's frame (IrPipeline::step): the residual, or all masked without
                 * evidence (the buffer is not read again this frame); the stage's shift first
                 * with integ_shift */
                memset(&F.tf, 0, sizeof F.tf);
                F.tf.data = F.res.data;
                F.tf.stride_bytes = F.res.stride_bytes;
                if (!F.ev) {
                    int16_t *b = (int16_t *)(void *)F.buf;
                    for (size_t i = 0; i < npix; ++i) {
                        b[i] = PFT_RES16_MASKED;
                    }
                    F.tf.data = F.buf;
                    F.tf.stride_bytes = 2u * W;
                }
                F.tf.width = W;
                F.tf.height = H;
                F.tf.format = PFT_PIX_RES16;
                F.tf.bit_depth = 16u;
                F.tf.seq = seq;
                F.tf.timestamp_us = (uint64_t)seq * 1000000u;
                if (S.pipe[IRP_PIPE_integ_shift] && F.ev) {
                    s = pft_tbd_set_shift(&tbd, to_real(F.st.shift[0] / 65536.0), to_real(F.st.shift[1] / 65536.0));
                    if (s != PFT_OK) {
                        break;
                    }
                }
            }
            s = irp_measured(&call);
            if (s != PFT_OK) {
                fprintf(stderr, "ir_probe: frame %lu: %s: %s\n", (unsigned long)seq, names[k], pft_status_str(s));
                return 1;
            }
            if (k == 0) {
                pft_pre_stats(&pre, &F.st);
                pft_pre_frame(&pre, &F.res);
                h_res = fnv1a_frame(h_res, &F.res);
                F.ev = (F.st.flags & (PFT_PRE_FLAG_CONSTANT | PFT_PRE_FLAG_ALL_MASKED | PFT_PRE_FLAG_REG_LOST)) == 0u;
                if (S.pipe[IRP_PIPE_flat] && !S.pre.inplace) {
                    /* the flat step corrects a copy of the residual (IrPipeline::preprocess) */
                    for (uint32_t r = 0; r < H; ++r) {
                        memcpy(F.buf + (size_t)r * W, (const unsigned char *)F.res.data + (size_t)r * F.res.stride_bytes,
                               2u * (size_t)W);
                    }
                }
                if (S.pipe[IRP_PIPE_flat]) {
                    F.res.data = F.buf;
                    F.res.stride_bytes = 2u * W;
                }
            } else if (k == 1 && S.pipe[IRP_PIPE_flat]) {
                h_flat = fnv1a_frame(h_flat, &F.res);
            } else if (k == 2 && S.pipe[IRP_PIPE_clutter]) {
                pft_frame_t co;
                s = pft_pre_clutter_frame(&cl, &co);
                if (s != PFT_OK) {
                    fprintf(stderr, "ir_probe: frame %lu: clutter map: %s\n", (unsigned long)seq, pft_status_str(s));
                    return 1;
                }
                h_map = fnv1a_frame(h_map, &co);
                h_map_frame = fnv1a_frame(h_map_frame, &co);
                F.res.data = co.data;
                F.res.stride_bytes = co.stride_bytes;
            }
        }
        printf("F %lu flags %lu shift %ld %ld ev %d map %016llx tracks %lu", (unsigned long)seq,
               (unsigned long)F.st.flags, (long)F.st.shift[0], (long)F.st.shift[1], F.ev,
               (unsigned long long)h_map_frame, (unsigned long)F.n_rep);
        for (size_t i = 0; i < F.n_rep; ++i) {
            const pft_tbd_track_t *t = &F.tr[i];
            printf(" %lu:%08lx,%08lx,%08lx,%08lx,%08lx,%08lx", (unsigned long)t->id, (unsigned long)irp_bits(t->x),
                   (unsigned long)irp_bits(t->y), (unsigned long)irp_bits(t->vx), (unsigned long)irp_bits(t->vy),
                   (unsigned long)irp_bits(t->intensity), (unsigned long)irp_bits(t->p_exist));
            h_trk = fnv1a_track(h_trk, t);
        }
        printf("\n");
    }
    fclose(in);
    printf("ir_probe: checksums (FNV-1a 64) residual %016llx, flat %016llx, map %016llx, tracks %016llx\n",
           (unsigned long long)h_res, (unsigned long long)h_flat, (unsigned long long)h_map,
           (unsigned long long)h_trk);
    printf("ir_probe: done, %lu frames\n", (unsigned long)frames);
    return 0;
}

int main(int argc, char **argv)
{
    if (argc >= 2 && strcmp(argv[1], "-c") == 0) {
        return run_flight(argc, argv);
    }
    if (argc < 8) {
        fprintf(stderr, "usage: ir_probe IN.u16 W H BITS FRAMES SEED PARTICLES [inplace|copy [BLOCK [3|2|1 [MEAN PERSIST ALPHA [MAP8 [ANCHOR]]]]]]\n");
        return 2;
    }
    const int map_inplace = argc < 9 || strcmp(argv[8], "copy") != 0;
    if (argc >= 9 && map_inplace && strcmp(argv[8], "inplace") != 0) {
        fprintf(stderr, "ir_probe: MAP is inplace or copy, not %s\n", argv[8]);
        return 2;
    }
    const int marks = argc >= 11 ? atoi(argv[10]) : 3;
    if (marks < 1 || marks > 3) {
        fprintf(stderr, "ir_probe: MARKS is 3, 2 or 1, not %s\n", argv[10]);
        return 2;
    }
    if (argc > 11 && argc != 14 && argc != 15 && argc != 16) {
        fprintf(stderr, "ir_probe: MEAN PERSIST ALPHA come together\n");
        return 2;
    }
    const int cl_mean = argc >= 14 ? atoi(argv[11]) : 0;
    const int cl_persist = argc >= 14 ? atoi(argv[12]) : 0;
    const double cl_alpha = argc >= 14 ? atof(argv[13]) : 0.1;
    if ((cl_mean != 0 && cl_mean != 1) || cl_persist < 0 || cl_persist > 255 || !(cl_alpha > 0.0)) {
        fprintf(stderr, "ir_probe: MEAN is 0 or 1, PERSIST 0..255, ALPHA > 0\n");
        return 2;
    }
    const uint16_t W = (uint16_t)atoi(argv[2]), H = (uint16_t)atoi(argv[3]);
    const uint8_t bits = (uint8_t)atoi(argv[4]);
    const uint32_t frames = (uint32_t)atol(argv[5]);
    const uint32_t seed = (uint32_t)atol(argv[6]);
    const uint32_t particles = (uint32_t)atol(argv[7]);
    const size_t npix = (size_t)W * H;
    const char *field = NULL;

    /* make_pre_config (ir_pipeline.cpp) with TrackerSettings' defaults */
    pft_pre_config_t pc;
    pft_pre_config_default(&pc);
    pc.width = W;
    pc.height = H;
    pc.format = PFT_PIX_U16;
    pc.bit_depth = bits;
    pc.method = PFT_PRE_BG_TEMPORAL;
    pc.local_outer = 5u;
    pc.local_guard = 2u;
    pc.bg_alpha = (uint16_t)lround(0.15 * 65536.0);
    pc.tile = 32u;
    pc.edge_k = 0u;
    pc.peak_max = 0u;
    pc.reg_step = 2u;
    pc.reg_iters = 2u;
    pc.warp_cubic = true;
    pc.sigma_step = 1u;
    pc.sigma_interp = true;
    pc.sigma_every = 1u;
    pc.reg_bin = false;
    pc.sigma_current = true;
    pc.sigma_bracket = false;
    pc.inplace = true;
    if (pft_pre_config_check(&pc, &field) != PFT_OK) {
        fprintf(stderr, "ir_probe: stage configuration refused (%s)\n", field ? field : "?");
        return 2;
    }
    /* make_clutter_config: clutter_alpha 0.1, blur 1, box, thr 2, excess 1.5 (mean, persist
     * and alpha from MEAN PERSIST ALPHA when given) */
    pft_pre_clutter_config_t cc;
    pft_pre_clutter_config_default(&cc);
    cc.width = W;
    cc.height = H;
    {
        const long al = lround(cl_alpha * 65536.0);
        cc.alpha = (uint16_t)(al < 1L ? 1L : (al > 65535L ? 65535L : al));
    }
    cc.blur = 1u;
    cc.box = true;
    cc.mean = cl_mean != 0;
    cc.thr = (uint16_t)lround(2.0 * 1024.0);
    cc.veto = 0u;
    cc.persist = (uint8_t)cl_persist;
    cc.excess = (uint16_t)lround(1.5 * 256.0);
    cc.inplace = map_inplace != 0;
    cc.block = (uint8_t)(argc >= 10 ? atoi(argv[9]) : 0);
    cc.map8 = argc >= 15 && atoi(argv[14]) != 0; /* MAP8: pft_pre_clutter_config_t.map8 */
    cc.anchor = argc >= 16 && atoi(argv[15]) != 0; /* ANCHOR: pft_pre_clutter_config_t.anchor */
    if (pft_pre_clutter_config_check(&cc, &field) != PFT_OK) {
        fprintf(stderr, "ir_probe: clutter configuration refused (%s)\n", field ? field : "?");
        return 2;
    }
    /* pipeline_config: the recommended preset, psf 0.7, SNR 6..18 dB, 500 track particles,
     * 8 targets, RBPF, 256 birth peaks, birth_share 0.5, confirm_frames 2 */
    pft_tbd_config_t tc;
    pft_tbd_config_recommended(&tc);
    tc.width = W;
    tc.height = H;
    tc.psf_sigma = to_real(0.7);
    tc.noise_sigma = to_real(1.0);
    tc.pixel_gain = to_real(1.0);
    tc.pixel_offset = to_real(0.0);
    tc.frame_format = PFT_PIX_RES16;
    {
        const double area = 2.0 * 3.14159265358979323846 * 0.7 * 0.7;
        tc.i_min = to_real(area * pow(10.0, 6.0 / 20.0));
        tc.i_max = to_real(area * pow(10.0, 18.0 / 20.0));
    }
    tc.n_search = particles;
    tc.n_track = 500u;
    tc.max_targets = 8u;
    tc.kind = PFT_TBD_RBPF;
    tc.seed = seed;
    tc.birth_peaks = 256u;
    tc.peak_tile = 0u;
    tc.peak_quota = 0u;
    tc.sprt_start = 0u;
    tc.birth_share = to_real(0.5);
    tc.confirm_frames = 2u;
    tc.birth_correction = true;
    if (pft_tbd_config_check(&tc, &field) != PFT_OK) {
        fprintf(stderr, "ir_probe: manager configuration refused (%s)\n", field ? field : "?");
        return 2;
    }
    /* make_scene_config: scene_frames 5, gates 0.15, fit 0.2, early 0.5 px, max_targets slots */
    pft_tbd_scene_config_t sc;
    pft_tbd_scene_config_default(&sc);
    sc.max_tracks = tc.max_targets;
    sc.width = W;
    sc.height = H;
    if (pft_tbd_scene_config_check(&sc, &field) != PFT_OK) {
        fprintf(stderr, "ir_probe: scene test configuration refused (%s)\n", field ? field : "?");
        return 2;
    }
    const size_t pre_b = pft_pre_workspace_size(&pc), cl_b = pft_pre_clutter_workspace_size(&cc),
                 tbd_b = pft_tbd_workspace_size(&tc), scn_b = pft_tbd_scene_workspace_size(&sc);
    uint16_t *buf = arena_take(npix * 2u);
    int16_t *blank = arena_take(npix * 2u);
    void *pre_w = arena_take(pre_b), *cl_w = arena_take(cl_b), *tbd_w = arena_take(tbd_b);
    void *scn_w = arena_take(scn_b);
    printf("workspace bytes: stage %lu, clutter map %lu, manager %lu, frame and blank %lu\n",
           (unsigned long)pre_b, (unsigned long)cl_b, (unsigned long)tbd_b,
           (unsigned long)(npix * 4u));
    printf("workspace bytes: scene test %lu\n", (unsigned long)scn_b);
    if (buf == NULL || blank == NULL || pre_w == NULL || cl_w == NULL || tbd_w == NULL || scn_w == NULL) {
        fprintf(stderr, "ir_probe: arena of %lu bytes too small (needs %lu)\n",
                (unsigned long)IRP_ARENA_BYTES,
                (unsigned long)(npix * 4u + pre_b + cl_b + tbd_b + scn_b + 48u));
        return 3;
    }
    static pft_pre_t pre;
    static pft_pre_clutter_t cl;
    static pft_tbd_t tbd;
    static pft_tbd_scene_t scn;
    if (pft_pre_init(&pre, &pc, pre_w, pre_b) != PFT_OK ||
        pft_tbd_scene_init(&scn, &sc, scn_w, scn_b) != PFT_OK ||
        pft_pre_clutter_init(&cl, &cc, cl_w, cl_b) != PFT_OK ||
        pft_tbd_init(&tbd, &tc, tbd_w, tbd_b) != PFT_OK) {
        fprintf(stderr, "ir_probe: init failed\n");
        return 1;
    }
    for (size_t i = 0; i < npix; ++i) {
        blank[i] = PFT_RES16_MASKED;
    }
    FILE *in = fopen(argv[1], "rb");
    if (in == NULL) {
        fprintf(stderr, "ir_probe: cannot open %s\n", argv[1]);
        return 1;
    }
    uint64_t h_res = 14695981039346656037ull, h_map = h_res, h_trk = h_res;
    for (uint32_t seq = 1; seq <= frames; ++seq) {
        if (fread(buf, 2u, npix, in) != npix) {
            fprintf(stderr, "ir_probe: %s holds fewer than %lu frames\n", argv[1], (unsigned long)frames);
            return 1;
        }
        pft_frame_t f;
        memset(&f, 0, sizeof f);
        f.data = buf;
        f.width = W;
        f.height = H;
        f.stride_bytes = 2u * W;
        f.format = PFT_PIX_U16;
        f.bit_depth = bits;
        f.seq = seq;
        irp_call_t call;
        memset(&call, 0, sizeof call);
        call.pre = &pre;
        call.f = &f;
        call.buf = buf;
        call.unmarked = marks == 1;
        pft_status_t s = irp_measured(&call);
        if (s != PFT_OK) {
            fprintf(stderr, "ir_probe: frame %lu: stage: %s\n", (unsigned long)seq, pft_status_str(s));
            return 1;
        }
        pft_pre_stats_t st;
        pft_pre_stats(&pre, &st);
        pft_frame_t rf;
        pft_pre_frame(&pre, &rf);
        h_res = fnv1a_frame(h_res, &rf);
        const int ev = (st.flags & (PFT_PRE_FLAG_CONSTANT | PFT_PRE_FLAG_ALL_MASKED |
                                    PFT_PRE_FLAG_REG_LOST)) == 0u;
        memset(&call, 0, sizeof call);
        call.cl = &cl;
        call.f = &rf;
        call.buf = buf; /* the stage's residual is the frame's buffer (inplace) */
        call.sx = st.shift[0];
        call.sy = st.shift[1];
        call.ev = ev;
        call.inplace = map_inplace;
        call.unmarked = marks == 2;
        s = irp_measured(&call);
        pft_frame_t co;
        if (s == PFT_OK) {
            s = pft_pre_clutter_frame(&cl, &co);
        }
        if (s != PFT_OK) {
            fprintf(stderr, "ir_probe: frame %lu: clutter map: %s\n", (unsigned long)seq, pft_status_str(s));
            return 1;
        }
        h_map = fnv1a_frame(h_map, &co);
        pft_frame_t tf;
        memset(&tf, 0, sizeof tf);
        tf.data = ev ? co.data : (const void *)blank;
        tf.stride_bytes = 2u * W;
        tf.width = W;
        tf.height = H;
        tf.format = PFT_PIX_RES16;
        tf.bit_depth = 16u;
        tf.seq = seq;
        tf.timestamp_us = (uint64_t)seq * 1000000u;
        memset(&call, 0, sizeof call);
        call.tbd = &tbd;
        call.f = &tf;
        s = irp_measured(&call);
        if (s != PFT_OK) {
            fprintf(stderr, "ir_probe: frame %lu: manager: %s\n", (unsigned long)seq, pft_status_str(s));
            return 1;
        }
        pft_tbd_track_t tr[8];
        size_t n = pft_tbd_tracks(&tbd, tr, 8u);
        if (n > 8u) {
            n = 8u;
        }
        printf("%lu,%u", (unsigned long)seq, (unsigned)st.flags);
        /* the scene-motion test (IrPipeline::scene_test): the map raised under the tracks
         * found moving with the scene */
        pft_tbd_scene_track_t sin[8];
        pft_tbd_scene_out_t sout[8];
        for (size_t i = 0; i < n; ++i) {
            printf(",%lu %.3f %.3f", (unsigned long)tr[i].id, from_real(tr[i].x), from_real(tr[i].y));
            h_trk = fnv1a_track(h_trk, &tr[i]);
            sin[i].id = tr[i].id;
            sin[i].x = tr[i].x;
            sin[i].y = tr[i].y;
            sin[i].tentative = false;
            sin[i].pos_var = PFT_C(0.0);
            sin[i].p_exist = PFT_C(0.0);
        }
        s = pft_tbd_scene_update(&scn, sin, n, ev ? st.shift[0] : 0, ev ? st.shift[1] : 0, sout);
        if (s != PFT_OK) {
            fprintf(stderr, "ir_probe: frame %lu: scene test: %s\n", (unsigned long)seq, pft_status_str(s));
            return 1;
        }
        for (size_t i = 0; i < n; ++i) {
            if (sout[i].decision == PFT_TBD_SCENE_CLUTTER) {
                (void)pft_pre_clutter_raise(&cl, sout[i].px, sout[i].py, 16u * 1024u);
            }
        }
        printf("\n");
    }
    fclose(in);
    printf("ir_probe: checksums (FNV-1a 64) residual %016llx, map %016llx, tracks %016llx\n",
           (unsigned long long)h_res, (unsigned long long)h_map, (unsigned long long)h_trk);
    printf("ir_probe: done, %lu frames\n", (unsigned long)frames);
    return 0;
}
