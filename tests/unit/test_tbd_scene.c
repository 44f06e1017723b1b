/*
 * The scene-motion test of the IR pipeline (pft_tbd_scene.h): configuration check naming the
 * refused field, workspace size (the macro, one word less refused), refused input leaves
 * instance, workspace and output byte for byte unchanged, reset, and known answers: a track
 * moving with the scene is CLUTTER at its n + 1-th frame and not before (and stays so, with its
 * clamped pixel); a track moving at 0.5 px/frame against the scene is reported from its 4th
 * frame (the early report), one at 0.25 px/frame from its n + 1-th; a curved path (a parabola)
 * fails the line fit and is never reported, but is from its 4th frame with the fit off; a
 * tentative track is held, and found CLUTTER like the others; a full table gives NO_SLOT and
 * takes over the slot of the id fed least recently; a history is forgotten forget_frames
 * frames after its last frame; the report hold (hold_frames k) reports a track from the k-th
 * frame it passes the tests, counting no tentative frame, and leaves CLUTTER as it is; the
 * spread-dependent hold (spread_px, spread_hold) shortens it for frames with a small position
 * spread, reads pos_var only when on, and refuses a negative one; its existence bound
 * (spread_exist) keeps the short hold from frames whose p_exist is below it, reads p_exist only
 * when on; the longer look (slow_frames)
 * keeps a slow track undecided until its window shows it moving (reported at the frame its
 * displacement reaches the sqrt-scaled gate, exactly at the bound) or static (CLUTTER at
 * slow_frames), and a track below slow_low_px CLUTTER at once; the entering-edge hold (edge_px)
 * holds a track still in the frame within edge_px of the border the scene's shift brings content
 * in from (reported without the option), but not the same track mid-frame, at the leaving
 * border, or one that enters at that border and moves inward; the short hold's speed bound
 * (move_px, move_hold) keeps a compact track slower than it against the scene on the longer
 * hold, exactly at the bound not. Positions and shifts are multiples of 2^-16 px, so that both
 * builds give the same answers exactly.
 */
#include <string.h>

#include "pft_test_support.h"
#include "pft/pft_tbd_scene.h"

void setUp(void) {}
void tearDown(void) {}

#define SLOTS 4u
static uint64_t g_work[PFT_TBD_SCENE_WORKSPACE_BYTES(SLOTS, PFT_TBD_SCENE_MAX_FRAMES) / 8u + 1u];
static uint64_t g_copy[sizeof(g_work) / 8u];

/* Q16.16 px */
#define Q(v) ((int32_t)((v) * 65536.0))

/* a Q16.16 count of px as a pft_real_t (exact in both builds below 2^24 LSB) */
static pft_real_t rq(int32_t q)
{
#ifdef PFT_NUMERIC_Q16
    return q;
#else
    return (float)q / 65536.0f;
#endif
}

static void init(pft_tbd_scene_t *s, pft_tbd_scene_config_t *cfg)
{
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tbd_scene_init(s, cfg, g_work, pft_tbd_scene_workspace_size(cfg)));
}

static pft_tbd_scene_track_t trk(uint32_t id, pft_real_t x, pft_real_t y, bool tentative)
{
    pft_tbd_scene_track_t t;
    memset(&t, 0, sizeof t);
    t.id = id;
    t.x = x;
    t.y = y;
    t.tentative = tentative;
    return t;
}

/* one track, one frame: its decision */
static pft_tbd_scene_out_t one(pft_tbd_scene_t *s, pft_tbd_scene_track_t t, int32_t sx, int32_t sy)
{
    pft_tbd_scene_out_t o;
    memset(&o, 0xA5, sizeof o);
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tbd_scene_update(s, &t, 1u, sx, sy, &o));
    TEST_ASSERT_EQUAL_UINT32(t.id, o.id);
    return o;
}

static void test_config_and_workspace(void)
{
    pft_tbd_scene_config_t cfg;
    const char *field = "x";
    pft_tbd_scene_config_default(&cfg);
    TEST_ASSERT_EQUAL_UINT32(5u, cfg.frames);
    TEST_ASSERT_EQUAL_UINT32(64u, cfg.forget_frames);
    TEST_ASSERT_EQUAL_UINT32(1u, cfg.hold_frames);
    TEST_ASSERT_EQUAL_UINT32(1u, cfg.spread_hold);
    TEST_ASSERT_EQUAL_DOUBLE(0.0, pft_test_to_double(cfg.spread_px));
    TEST_ASSERT_EQUAL_DOUBLE(0.0, pft_test_to_double(cfg.move_px));
    TEST_ASSERT_EQUAL_UINT32(0u, cfg.move_hold);
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tbd_scene_config_check(&cfg, &field));
    TEST_ASSERT_NULL(field);
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_tbd_scene_config_check(NULL, &field));
    TEST_ASSERT_EQUAL_UINT32(0u, (uint32_t)pft_tbd_scene_workspace_size(NULL));
    static const struct {
        const char *name;
        int which;
    } bad[] = {{"frames", 0}, {"frames", 1}, {"max_tracks", 2}, {"max_tracks", 3}, {"gate_px", 4},
               {"gate_px", 5}, {"fit_px", 6}, {"fit_px", 7}, {"early_px", 8}, {"early_px", 9},
               {"forget_frames", 10}, {"forget_frames", 11}, {"width", 12}, {"width", 13},
               {"height", 14}, {"height", 15}, {"hold_frames", 16}, {"hold_frames", 17},
               {"spread_px", 18}, {"spread_px", 19}, {"spread_hold", 20}, {"spread_hold", 21},
               {"slow_frames", 22}, {"slow_frames", 23}, {"slow_low_px", 24}, {"slow_low_px", 25},
               {"slow_gate_px", 26}, {"slow_gate_px", 27}, {"spread_exist", 28}, {"spread_exist", 29},
               {"edge_px", 30}, {"edge_px", 31}, {"edge_still_px", 32}, {"edge_still_px", 33},
               {"edge_shift_px", 34}, {"edge_shift_px", 35}, {"move_px", 36}, {"move_px", 37},
               {"move_hold", 38}, {"move_hold", 39}};
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; ++i) {
        pft_tbd_scene_config_t b = cfg;
        switch (bad[i].which) {
        case 0: b.frames = 0u; break;
        case 1: b.frames = PFT_TBD_SCENE_MAX_FRAMES + 1u; break;
        case 2: b.max_tracks = 0u; break;
        case 3: b.max_tracks = PFT_TBD_SCENE_MAX_TRACKS + 1u; break;
        case 4: b.gate_px = PFT_C(-0.125); break;
        case 5: b.gate_px = PFT_C(256.5); break;
        case 6: b.fit_px = PFT_C(-0.25); break;
        case 7: b.fit_px = PFT_C(257.0); break;
        case 8: b.early_px = PFT_C(-1.0); break;
        case 9: b.early_px = PFT_C(300.0); break;
        case 10: b.forget_frames = 0u; break;
        case 11: b.forget_frames = (1u << 30) + 1u; break;
        case 12: b.width = 0u; break;
        case 13: b.width = PFT_CFG_MAX_IMAGE_SIDE + 1u; break;
        case 14: b.height = 0u; break;
        case 15: b.height = PFT_CFG_MAX_IMAGE_SIDE + 1u; break;
        case 16: b.hold_frames = 0u; break;
        case 17: b.hold_frames = PFT_TBD_SCENE_MAX_HOLD + 1u; break;
        case 18: b.spread_px = PFT_C(-0.5); break;
        case 19: b.spread_px = PFT_C(256.5); break;
        case 20: b.spread_hold = 0u; break;
        case 21: b.hold_frames = 3u; b.spread_hold = 4u; break; /* more than hold_frames */
        case 22: b.slow_frames = 9u; break;                      /* less than 2 * frames */
        case 23: b.slow_frames = PFT_TBD_SCENE_MAX_FRAMES + 1u; break;
        case 24: b.slow_frames = 10u; b.slow_low_px = PFT_C(-0.125); break;
        case 25: b.slow_frames = 10u; b.slow_low_px = PFT_C(0.25); break; /* above gate_px 0.15 */
        case 26: b.slow_frames = 10u; b.slow_gate_px = PFT_C(0.0); break;
        case 27: b.slow_frames = 10u; b.slow_gate_px = PFT_C(256.5); break;
        case 28: b.spread_exist = PFT_C(-0.125); break;
        case 29: b.spread_exist = PFT_C(1.5); break;
        case 30: b.edge_px = PFT_C(-0.125); break;
        case 31: b.edge_px = PFT_C(256.5); break;
        case 32: b.edge_still_px = PFT_C(-0.125); break;
        case 33: b.edge_still_px = PFT_C(256.5); break;
        case 34: b.edge_shift_px = PFT_C(-0.125); break;
        case 35: b.edge_shift_px = PFT_C(256.5); break;
        case 36: b.move_px = PFT_C(-0.125); break;
        case 37: b.move_px = PFT_C(256.5); break;
        case 38: b.move_hold = 2u; break; /* above hold_frames 1 */
        default:
            b.hold_frames = 4u;
            b.spread_hold = 2u;
            b.move_hold = 1u; /* below spread_hold */
            break;
        }
        TEST_ASSERT_EQUAL_INT(PFT_ERR_CONFIG, pft_tbd_scene_config_check(&b, &field));
        TEST_ASSERT_EQUAL_STRING(bad[i].name, field);
        TEST_ASSERT_EQUAL_UINT32(0u, (uint32_t)pft_tbd_scene_workspace_size(&b));
        pft_tbd_scene_t s;
        memset(&s, 0x5A, sizeof s);
        pft_tbd_scene_t s0 = s;
        TEST_ASSERT_EQUAL_INT(PFT_ERR_CONFIG, pft_tbd_scene_init(&s, &b, g_work, sizeof g_work));
        TEST_ASSERT_EQUAL_MEMORY(&s0, &s, sizeof s);
    }
    /* the fit and the early report can be off; the bounds are accepted */
    cfg.fit_px = PFT_C(0.0);
    cfg.early_px = PFT_C(0.0);
    cfg.gate_px = PFT_C(256.0);
    cfg.frames = PFT_TBD_SCENE_MAX_FRAMES;
    cfg.max_tracks = SLOTS;
    cfg.hold_frames = PFT_TBD_SCENE_MAX_HOLD;
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tbd_scene_config_check(&cfg, &field));
    const size_t ws = pft_tbd_scene_workspace_size(&cfg);
    TEST_ASSERT_EQUAL_UINT32((uint32_t)PFT_TBD_SCENE_WORKSPACE_BYTES(SLOTS, PFT_TBD_SCENE_MAX_FRAMES), (uint32_t)ws);
    /* 4 slots of 32 positions: the slots and the positions, 8-byte aligned, and the alignment slack */
    TEST_ASSERT_EQUAL_UINT32((uint32_t)(7u + 4u * 24u + 4u * 32u * 24u), (uint32_t)ws);
    pft_tbd_scene_t s;
    memset(&s, 0x5A, sizeof s);
    pft_tbd_scene_t s0 = s;
    TEST_ASSERT_EQUAL_INT(PFT_ERR_NOMEM, pft_tbd_scene_init(&s, &cfg, g_work, ws - 8u));
    TEST_ASSERT_EQUAL_MEMORY(&s0, &s, sizeof s);
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_tbd_scene_init(NULL, &cfg, g_work, ws));
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_tbd_scene_init(&s, NULL, g_work, ws));
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_tbd_scene_init(&s, &cfg, NULL, ws));
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tbd_scene_init(&s, &cfg, g_work, ws));
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_tbd_scene_reset(NULL));
    TEST_ASSERT_EQUAL_UINT32(0u, pft_tbd_scene_frame(&s));
    TEST_ASSERT_EQUAL_UINT32(0u, pft_tbd_scene_frame(NULL));
    TEST_ASSERT_EQUAL_UINT32(0u, pft_tbd_scene_overflows(NULL));
    TEST_ASSERT_EQUAL_UINT32(0u, pft_tbd_scene_positions(NULL, 1u));
    TEST_ASSERT_FALSE(pft_tbd_scene_is_clutter(NULL, 1u));
    /* the longer look: off by default, read only when on; slow_frames 20 keeps 21 positions */
    pft_tbd_scene_config_default(&cfg);
    TEST_ASSERT_EQUAL_UINT32(0u, cfg.slow_frames);
    TEST_ASSERT_EQUAL_DOUBLE(0.0, pft_test_to_double(cfg.slow_low_px));
    cfg.slow_low_px = PFT_C(-1.0);
    cfg.slow_gate_px = PFT_C(0.0);
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tbd_scene_config_check(&cfg, &field));
    pft_tbd_scene_config_default(&cfg);
    cfg.max_tracks = SLOTS;
    cfg.slow_frames = 20u;
    TEST_ASSERT_EQUAL_UINT32((uint32_t)PFT_TBD_SCENE_WORKSPACE_BYTES(SLOTS, 20u),
                             (uint32_t)pft_tbd_scene_workspace_size(&cfg));
    TEST_ASSERT_EQUAL_UINT32((uint32_t)(7u + 4u * 24u + 4u * 21u * 24u), (uint32_t)pft_tbd_scene_workspace_size(&cfg));
}

/* moves exactly with the scene (0.25, -0.125 px per frame): CLUTTER at the 6th frame, HOLD
 * before; it stays CLUTTER; its pixel is round(x), round(y) clamped to the frame */
static void test_with_scene_marked_after_n_plus_1(void)
{
    pft_tbd_scene_config_t cfg;
    pft_tbd_scene_t s;
    pft_tbd_scene_config_default(&cfg);
    cfg.max_tracks = SLOTS;
    init(&s, &cfg);
    for (uint32_t k = 1u; k <= 9u; ++k) {
        const pft_real_t x = pft_add(PFT_C(382.5), pft_mul_i(PFT_C(0.25), (int32_t)k));
        const pft_real_t y = pft_sub(PFT_C(10.375), pft_mul_i(PFT_C(0.125), (int32_t)k));
        pft_tbd_scene_out_t o = one(&s, trk(7u, x, y, false), Q(0.25), Q(-0.125));
        TEST_ASSERT_EQUAL_UINT32(k < 6u ? k : 6u, o.positions);
        TEST_ASSERT_EQUAL_INT(k < 6u ? PFT_TBD_SCENE_HOLD : PFT_TBD_SCENE_CLUTTER, o.decision);
        TEST_ASSERT_EQUAL_UINT32(383u, o.px); /* 382.75 .. 384.75, clamped to 383 */
        TEST_ASSERT_EQUAL_UINT32(k <= 7u ? 10u : 9u, o.py); /* 10.25 .. 9.5 (ties up), 9.375, 9.25 */
        TEST_ASSERT_EQUAL(k >= 6u, pft_tbd_scene_is_clutter(&s, 7u));
    }
    /* then it moves away against the scene: CLUTTER for good */
    pft_tbd_scene_out_t o = one(&s, trk(7u, PFT_C(100.0), PFT_C(100.0), false), 0, 0);
    TEST_ASSERT_EQUAL_INT(PFT_TBD_SCENE_CLUTTER, o.decision);
    /* gate_px 0: nothing is CLUTTER; the same track is reported from its 6th frame */
    cfg.gate_px = PFT_C(0.0);
    init(&s, &cfg);
    for (int32_t k = 1; k <= 7; ++k) {
        o = one(&s, trk(7u, pft_add(PFT_C(50.0), pft_mul_i(PFT_C(0.25), k)), PFT_C(20.0), false), Q(0.25), 0);
        TEST_ASSERT_EQUAL_INT(k < 6 ? PFT_TBD_SCENE_HOLD : PFT_TBD_SCENE_REPORT, o.decision);
    }
    cfg.gate_px = PFT_C(0.15);
    /* at the gate: 5 frames at 9830 / 65536 px per frame against the scene (the gate 0.15 px in
     * Q16.16) is not below 5 * gate: not CLUTTER; one LSB per frame less is */
    TEST_ASSERT_EQUAL_INT32(9830, Q(0.15)); /* 0.15 * 65536 = 9830.4 */
    for (int32_t step = 9830; step >= 9829; --step) {
        init(&s, &cfg);
        for (int32_t k = 1; k <= 8; ++k) {
            o = one(&s, trk(3u, rq(Q(50.0) + k * (Q(0.25) + step)), PFT_C(20.0), false), Q(0.25), 0);
            if (k < 6) {
                TEST_ASSERT_EQUAL_INT(PFT_TBD_SCENE_HOLD, o.decision);
            } else {
                TEST_ASSERT_EQUAL_INT(step == 9830 ? PFT_TBD_SCENE_REPORT : PFT_TBD_SCENE_CLUTTER, o.decision);
            }
        }
    }
}

/* 0.5 px per frame against the scene (scene 0.25, track 0.75 px per frame, straight): the early
 * report from the 4th frame; 0.25 px per frame: from the 6th */
static void test_against_scene_reported_early(void)
{
    pft_tbd_scene_config_t cfg;
    pft_tbd_scene_t s;
    pft_tbd_scene_config_default(&cfg);
    cfg.max_tracks = SLOTS;
    init(&s, &cfg);
    for (uint32_t k = 1u; k <= 8u; ++k) {
        pft_tbd_scene_track_t t[2];
        pft_tbd_scene_out_t o[2];
        t[0] = trk(1u, pft_add(PFT_C(20.0), pft_mul_i(PFT_C(0.75), (int32_t)k)), PFT_C(40.0), false);
        t[1] = trk(2u, pft_add(PFT_C(60.0), pft_mul_i(PFT_C(0.5), (int32_t)k)), PFT_C(40.0), false);
        TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tbd_scene_update(&s, t, 2u, Q(0.25), 0, o));
        TEST_ASSERT_EQUAL_INT(k < 4u ? PFT_TBD_SCENE_HOLD : PFT_TBD_SCENE_REPORT, o[0].decision);
        TEST_ASSERT_EQUAL_INT(k < 6u ? PFT_TBD_SCENE_HOLD : PFT_TBD_SCENE_REPORT, o[1].decision);
    }
    /* the early report off: from the 6th frame */
    cfg.early_px = PFT_C(0.0);
    init(&s, &cfg);
    for (uint32_t k = 1u; k <= 7u; ++k) {
        pft_tbd_scene_out_t o =
            one(&s, trk(1u, pft_add(PFT_C(20.0), pft_mul_i(PFT_C(0.75), (int32_t)k)), PFT_C(40.0), false), Q(0.25), 0);
        TEST_ASSERT_EQUAL_INT(k < 6u ? PFT_TBD_SCENE_HOLD : PFT_TBD_SCENE_REPORT, o.decision);
    }
    /* a tentative track is held however it moves, and counts its positions */
    cfg.early_px = PFT_C(0.5);
    init(&s, &cfg);
    for (uint32_t k = 1u; k <= 7u; ++k) {
        pft_tbd_scene_out_t o =
            one(&s, trk(1u, pft_add(PFT_C(20.0), pft_mul_i(PFT_C(0.75), (int32_t)k)), PFT_C(40.0), true), Q(0.25), 0);
        TEST_ASSERT_EQUAL_INT(PFT_TBD_SCENE_HOLD, o.decision);
    }
    pft_tbd_scene_out_t o = one(&s, trk(1u, PFT_C(26.0), PFT_C(40.0), false), Q(0.25), 0);
    TEST_ASSERT_EQUAL_INT(PFT_TBD_SCENE_REPORT, o.decision);
    /* a tentative track moving with the scene is found CLUTTER at its 6th frame */
    init(&s, &cfg);
    for (uint32_t k = 1u; k <= 6u; ++k) {
        o = one(&s, trk(9u, pft_add(PFT_C(20.0), pft_mul_i(PFT_C(0.25), (int32_t)k)), PFT_C(40.0), true), Q(0.25), 0);
        TEST_ASSERT_EQUAL_INT(k < 6u ? PFT_TBD_SCENE_HOLD : PFT_TBD_SCENE_CLUTTER, o.decision);
    }
}

/* the report hold: a track at 0.5 px/frame against the scene passes the tests from its 4th
 * frame (the early report); with hold k it is reported from its (3 + k)-th frame and on every
 * frame after; k = 1 is no hold. A track held by the fit for a while counts only the frames it
 * passes; tentative frames count none; a track moving with the scene is CLUTTER whatever k. */
static void test_report_hold(void)
{
    static const uint32_t holds[] = {1u, 2u, 3u, 5u};
    pft_tbd_scene_config_t cfg;
    pft_tbd_scene_t s;
    for (size_t h = 0u; h < sizeof holds / sizeof holds[0]; ++h) {
        const uint32_t hold = holds[h];
        pft_tbd_scene_config_default(&cfg);
        cfg.max_tracks = SLOTS;
        cfg.hold_frames = hold;
        init(&s, &cfg);
        for (uint32_t k = 1u; k <= 12u; ++k) {
            pft_tbd_scene_track_t t[2];
            pft_tbd_scene_out_t o[2];
            t[0] = trk(1u, pft_add(PFT_C(20.0), pft_mul_i(PFT_C(0.75), (int32_t)k)), PFT_C(40.0), false);
            t[1] = trk(2u, pft_add(PFT_C(60.0), pft_mul_i(PFT_C(0.25), (int32_t)k)), PFT_C(40.0), false);
            TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tbd_scene_update(&s, t, 2u, Q(0.25), 0, o));
            TEST_ASSERT_EQUAL_INT(k < 3u + hold ? PFT_TBD_SCENE_HOLD : PFT_TBD_SCENE_REPORT, o[0].decision);
            TEST_ASSERT_EQUAL_INT(k < 6u ? PFT_TBD_SCENE_HOLD : PFT_TBD_SCENE_CLUTTER, o[1].decision);
        }
        /* tentative for its first 7 frames (positions count, passes do not): then it passes on
         * every frame (n + 1 positions, a straight line) and is reported from its (7 + k)-th */
        init(&s, &cfg);
        for (uint32_t k = 1u; k <= 14u; ++k) {
            pft_tbd_scene_out_t o = one(
                &s, trk(3u, pft_add(PFT_C(20.0), pft_mul_i(PFT_C(0.75), (int32_t)k)), PFT_C(40.0), k <= 7u), Q(0.25), 0);
            TEST_ASSERT_EQUAL_INT(k < 7u + hold ? PFT_TBD_SCENE_HOLD : PFT_TBD_SCENE_REPORT, o.decision);
        }
        /* passes on frames 4..6, jumps off its line at frame 7 (held by the fit until the jump
         * has left its last n + 1 positions, frame 13), then passes again: the passes before
         * the jump count, so hold k reports at frame 3 + k for k <= 3, and k = 5 at frame 14 */
        init(&s, &cfg);
        for (uint32_t k = 1u; k <= 16u; ++k) {
            const pft_real_t x = pft_add(PFT_C(20.0), pft_mul_i(PFT_C(0.75), (int32_t)k));
            const pft_real_t y = k == 7u ? PFT_C(43.0) : PFT_C(40.0);
            pft_tbd_scene_out_t o = one(&s, trk(4u, x, y, false), Q(0.25), 0);
            bool rep;
            if (k >= 7u && k <= 12u) {
                rep = false;
            } else if (hold <= 3u) {
                rep = k >= 3u + hold;
            } else {
                rep = k >= 14u; /* passes 4, 5, 6, 13, 14: the 5th at frame 14 */
            }
            TEST_ASSERT_EQUAL_INT(rep ? PFT_TBD_SCENE_REPORT : PFT_TBD_SCENE_HOLD, o.decision);
        }
    }
}

/* the spread-dependent hold's configuration of the two tests below: hold_frames 4,
 * spread_hold 2, the given spread_px and spread_exist */
static pft_tbd_scene_config_t spread_cfg_(pft_real_t spread_px, pft_real_t exist)
{
    pft_tbd_scene_config_t cfg;
    pft_tbd_scene_config_default(&cfg);
    cfg.max_tracks = SLOTS;
    cfg.hold_frames = 4u;
    cfg.spread_px = spread_px;
    cfg.spread_hold = 2u;
    cfg.spread_exist = exist;
    return cfg;
}

/* the spread-dependent hold (spread_px 0.5, spread_hold 2, hold_frames 4): a track at 0.75 px
 * per frame against the scene passes from its 4th frame (early); with a position variance of
 * 0.2 px^2 (spread 0.447 px) it is reported from its 2nd pass (frame 5), with exactly 0.25
 * (0.5 px: at most spread_px) too, with 0.3 (0.548 px) from its 4th (frame 7); a spread that
 * falls to 0.2 at frame 6 reports it there (its 3rd pass); with spread_px 0 (off) pos_var is not
 * read (a negative one is accepted) and the hold is hold_frames */
static void test_spread_hold(void)
{
    static const struct {
        pft_real_t spread_px;
        pft_real_t var_early; /* pos_var on frames 1..5 */
        pft_real_t var_late;  /* from frame 6 on */
        uint32_t first;       /* the first frame reported */
    } cases[] = {{PFT_C(0.5), PFT_C(0.2), PFT_C(0.2), 5u},  {PFT_C(0.5), PFT_C(0.25), PFT_C(0.25), 5u},
                 {PFT_C(0.5), PFT_C(0.3), PFT_C(0.3), 7u},  {PFT_C(0.5), PFT_C(0.3), PFT_C(0.2), 6u},
                 {PFT_C(0.0), PFT_C(-1.0), PFT_C(-1.0), 7u}, {PFT_C(0.0), PFT_C(0.2), PFT_C(0.2), 7u}};
    pft_tbd_scene_config_t cfg;
    pft_tbd_scene_t s;
    for (size_t c = 0u; c < sizeof cases / sizeof cases[0]; ++c) {
        cfg = spread_cfg_(cases[c].spread_px, PFT_C(0.0));
        init(&s, &cfg);
        for (uint32_t k = 1u; k <= 10u; ++k) {
            pft_tbd_scene_track_t t = trk(1u, pft_add(PFT_C(20.0), pft_mul_i(PFT_C(0.75), (int32_t)k)), PFT_C(40.0), false);
            t.pos_var = k <= 5u ? cases[c].var_early : cases[c].var_late;
            const pft_tbd_scene_out_t o = one(&s, t, Q(0.25), 0);
            TEST_ASSERT_EQUAL_INT(k < cases[c].first ? PFT_TBD_SCENE_HOLD : PFT_TBD_SCENE_REPORT, o.decision);
        }
    }
    /* refused with spread_px > 0: a negative pos_var (float: a NaN too), nothing written */
    cfg = spread_cfg_(PFT_C(0.5), PFT_C(0.0));
    init(&s, &cfg);
    for (uint32_t k = 1u; k <= 3u; ++k) {
        pft_tbd_scene_track_t t = trk(1u, pft_from_int(10 + (int32_t)k), PFT_C(10.0), false);
        (void)one(&s, t, 0, 0);
    }
    pft_tbd_scene_t s1 = s;
    static uint64_t w1[sizeof(g_work) / 8u];
    memcpy(w1, g_work, sizeof g_work);
    pft_tbd_scene_track_t t[2];
    pft_tbd_scene_out_t o[2], o0[2];
    memset(o, 0x3C, sizeof o);
    memcpy(o0, o, sizeof o);
    t[0] = trk(1u, PFT_C(14.0), PFT_C(10.0), false);
    t[1] = trk(2u, PFT_C(30.0), PFT_C(10.0), false);
    t[1].pos_var = PFT_C(-0.25);
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_tbd_scene_update(&s, t, 2u, 0, 0, o));
#ifdef PFT_NUMERIC_FLOAT
    volatile float zero = 0.0f;
    t[1].pos_var = zero / zero; /* NaN */
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_tbd_scene_update(&s, t, 2u, 0, 0, o));
#endif
    TEST_ASSERT_EQUAL_MEMORY(&s1, &s, sizeof s);
    TEST_ASSERT_EQUAL_MEMORY(w1, g_work, sizeof g_work);
    TEST_ASSERT_EQUAL_MEMORY(o0, o, sizeof o);
    t[1].pos_var = PFT_C(0.0);
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tbd_scene_update(&s, t, 2u, 0, 0, o));
}

/* the existence bound of the spread-dependent hold (spread_px 0.5, spread_hold 2, hold_frames 4,
 * spread_exist 0.75; pos_var 0.2 px^2 on every frame, so every pass is compact): a track at 0.75 px
 * per frame against the scene passes from its 4th frame; with p_exist 0.875 it is reported from
 * its 2nd pass (frame 5), with exactly 0.75 too (at least the bound), with 0.625 from its 4th
 * (frame 7, the wide tracks' hold), with 0.625 to frame 5 and 0.875 from frame 6 at frame 6 (its
 * 3rd pass, the first at the bound); with spread_exist 0 (off) p_exist is not read (a NaN is
 * accepted in the float build) and the track is reported at frame 5; with spread_px 0 the bound
 * is not read either (frame 7); with the bound on, a NaN p_exist is refused (float build) */
static void test_spread_exist(void)
{
    static const struct {
        pft_real_t spread_px;
        pft_real_t exist;   /* spread_exist */
        pft_real_t p_early; /* p_exist on frames 1..5 */
        pft_real_t p_late;  /* from frame 6 on */
        uint32_t first;     /* the first frame reported */
    } cases[] = {{PFT_C(0.5), PFT_C(0.75), PFT_C(0.875), PFT_C(0.875), 5u},
                 {PFT_C(0.5), PFT_C(0.75), PFT_C(0.75), PFT_C(0.75), 5u},
                 {PFT_C(0.5), PFT_C(0.75), PFT_C(0.625), PFT_C(0.625), 7u},
                 {PFT_C(0.5), PFT_C(0.75), PFT_C(0.625), PFT_C(0.875), 6u},
                 {PFT_C(0.5), PFT_C(0.0), PFT_C(0.125), PFT_C(0.125), 5u},
                 {PFT_C(0.0), PFT_C(0.75), PFT_C(0.875), PFT_C(0.875), 7u}};
    pft_tbd_scene_config_t cfg;
    pft_tbd_scene_t s;
    for (size_t c = 0u; c < sizeof cases / sizeof cases[0]; ++c) {
        cfg = spread_cfg_(cases[c].spread_px, cases[c].exist);
        init(&s, &cfg);
        for (uint32_t k = 1u; k <= 10u; ++k) {
            pft_tbd_scene_track_t t = trk(1u, pft_add(PFT_C(20.0), pft_mul_i(PFT_C(0.75), (int32_t)k)), PFT_C(40.0), false);
            t.pos_var = PFT_C(0.2);
            t.p_exist = k <= 5u ? cases[c].p_early : cases[c].p_late;
            const pft_tbd_scene_out_t o = one(&s, t, Q(0.25), 0);
            TEST_ASSERT_EQUAL_INT(k < cases[c].first ? PFT_TBD_SCENE_HOLD : PFT_TBD_SCENE_REPORT, o.decision);
        }
    }
#ifdef PFT_NUMERIC_FLOAT
    volatile float zero = 0.0f;
    pft_tbd_scene_out_t o;
    pft_tbd_scene_track_t t = trk(1u, PFT_C(20.0), PFT_C(40.0), false);
    t.pos_var = PFT_C(0.2);
    t.p_exist = zero / zero; /* NaN */
    cfg = spread_cfg_(PFT_C(0.5), PFT_C(0.0));
    init(&s, &cfg); /* the bound off: not read */
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tbd_scene_update(&s, &t, 1u, 0, 0, &o));
    cfg.spread_exist = PFT_C(0.75);
    init(&s, &cfg);
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_tbd_scene_update(&s, &t, 1u, 0, 0, &o));
    TEST_ASSERT_EQUAL_UINT32(0u, pft_tbd_scene_frame(&s));
#endif
}

/* the speed bound of the short hold (spread_px 0.5, spread_hold 2, hold_frames 4; pos_var 0.2 px^2
 * and p_exist 1 on every frame, so every pass is compact): track A moves 0.75 px per frame in the
 * frame, the scene 0.25 (0.5 px per frame against it: passes from its 4th frame, early), track B
 * 0.5 px per frame (0.25 against the scene: passes from its 6th frame, n + 1). Without the bound
 * A is reported from frame 5 (2nd pass), B from frame 7; with move_px 0.5, A moved exactly m
 * 0.5 px over its m frames (at least the bound): frame 5; with move_px 0.5 + 2^-16 it needs
 * hold_frames passes (frame 7), with move_hold 3 three (frame 6); B under move_px 0.3 needs four
 * (frame 9), under 0.25 exactly it keeps frame 7; with spread_px 0 the bound is not read (both at
 * hold_frames: frames 7 and 9). */
static void test_move_bound(void)
{
    static const struct {
        pft_real_t spread_px;
        int32_t move_q;    /* move_px, Q16.16 */
        uint32_t move_hold;
        pft_real_t speed;  /* px per frame in the frame */
        uint32_t first;    /* the first frame reported */
    } cases[] = {{PFT_C(0.5), 0, 0u, PFT_C(0.75), 5u},
                 {PFT_C(0.5), Q(0.5), 0u, PFT_C(0.75), 5u},
                 {PFT_C(0.5), Q(0.5) + 1, 0u, PFT_C(0.75), 7u},
                 {PFT_C(0.5), Q(0.5) + 1, 3u, PFT_C(0.75), 6u},
                 {PFT_C(0.5), 0, 0u, PFT_C(0.5), 7u},
                 {PFT_C(0.5), Q(0.3), 0u, PFT_C(0.5), 9u},
                 {PFT_C(0.5), Q(0.25), 0u, PFT_C(0.5), 7u},
                 {PFT_C(0.0), Q(0.5) + 1, 0u, PFT_C(0.75), 7u},
                 {PFT_C(0.0), Q(0.3), 0u, PFT_C(0.5), 9u}};
    pft_tbd_scene_config_t cfg;
    pft_tbd_scene_t s;
    for (size_t c = 0u; c < sizeof cases / sizeof cases[0]; ++c) {
        cfg = spread_cfg_(cases[c].spread_px, PFT_C(0.0));
        cfg.move_px = rq(cases[c].move_q);
        cfg.move_hold = cases[c].move_hold;
        init(&s, &cfg);
        for (uint32_t k = 1u; k <= 12u; ++k) {
            pft_tbd_scene_track_t t = trk(1u, pft_add(PFT_C(20.0), pft_mul_i(cases[c].speed, (int32_t)k)), PFT_C(40.0), false);
            t.pos_var = PFT_C(0.2);
            t.p_exist = PFT_C(1.0);
            const pft_tbd_scene_out_t o = one(&s, t, Q(0.25), 0);
            TEST_ASSERT_EQUAL_INT(k < cases[c].first ? PFT_TBD_SCENE_HOLD : PFT_TBD_SCENE_REPORT, o.decision);
        }
    }
}

/* x = 100 + k + 0.25 k^2: rms about the fitted line 0.25 px over 4 frames, 0.418 over 5, 0.624
 * over 6 (every window of 6): never within 0.2; with the fit off, reported from the 4th frame
 * (early); with fit 0.25, reported at the 4th (rms exactly 0.25), held at the 5th and on */
/* the longer look (n 5, gate 0.15 px, slow_frames L, slow_low_px 0.05, slow_gate_px 0.25), scene
 * 0.25 px per frame: track 1 at 0.125 px per frame against the scene (0.625 px over 5 frames:
 * below the gate's 0.75, above slow_low's 0.25) is undecided (HOLD) until its window m = 20
 * (frame 21), where 0.125 m = sqrt(5 m) 0.25 exactly (2.5 px: the bound passes), then REPORT;
 * with L 19 it is CLUTTER at frame 20 instead (m = L = 19: 2.375 < 2.44 px); track 2 at
 * 0.0625 px per frame (0.3125 px over 5) is undecided to frame 20 and CLUTTER at frame 21; track
 * 3 moving with the scene is CLUTTER at frame 6 (below slow_low); with the option off, track 1 is
 * CLUTTER at frame 6. */
static void test_slow_look(void)
{
    pft_tbd_scene_config_t cfg;
    pft_tbd_scene_t s;
    pft_tbd_scene_config_default(&cfg);
    cfg.max_tracks = SLOTS;
    cfg.slow_frames = 20u;
    cfg.slow_low_px = PFT_C(0.05);
    cfg.slow_gate_px = PFT_C(0.25);
    init(&s, &cfg);
    for (uint32_t k = 1u; k <= 30u; ++k) {
        pft_tbd_scene_track_t t[3];
        pft_tbd_scene_out_t o[3];
        t[0] = trk(1u, pft_add(PFT_C(20.0), pft_mul_i(PFT_C(0.375), (int32_t)k)), PFT_C(40.0), false);
        t[1] = trk(2u, pft_add(PFT_C(60.0), pft_mul_i(PFT_C(0.3125), (int32_t)k)), PFT_C(40.0), false);
        t[2] = trk(3u, pft_add(PFT_C(100.0), pft_mul_i(PFT_C(0.25), (int32_t)k)), PFT_C(40.0), false);
        TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tbd_scene_update(&s, t, 3u, Q(0.25), 0, o));
        TEST_ASSERT_EQUAL_INT(k <= 20u ? PFT_TBD_SCENE_HOLD : PFT_TBD_SCENE_REPORT, o[0].decision);
        TEST_ASSERT_EQUAL_INT(k <= 20u ? PFT_TBD_SCENE_HOLD : PFT_TBD_SCENE_CLUTTER, o[1].decision);
        TEST_ASSERT_EQUAL_INT(k <= 5u ? PFT_TBD_SCENE_HOLD : PFT_TBD_SCENE_CLUTTER, o[2].decision);
        TEST_ASSERT_EQUAL_UINT32(k < 21u ? k : 21u, o[0].positions);
    }
    TEST_ASSERT_FALSE(pft_tbd_scene_is_clutter(&s, 1u));
    TEST_ASSERT_TRUE(pft_tbd_scene_is_clutter(&s, 2u));
    TEST_ASSERT_EQUAL_UINT32(21u, pft_tbd_scene_positions(&s, 1u));
    /* L 19: track 1 never reaches its gate */
    cfg.slow_frames = 19u;
    init(&s, &cfg);
    for (uint32_t k = 1u; k <= 22u; ++k) {
        pft_tbd_scene_out_t o =
            one(&s, trk(1u, pft_add(PFT_C(20.0), pft_mul_i(PFT_C(0.375), (int32_t)k)), PFT_C(40.0), false), Q(0.25), 0);
        TEST_ASSERT_EQUAL_INT(k < 20u ? PFT_TBD_SCENE_HOLD : PFT_TBD_SCENE_CLUTTER, o.decision);
    }
    /* off: CLUTTER at the 6th frame, 6 positions kept */
    cfg.slow_frames = 0u;
    init(&s, &cfg);
    for (uint32_t k = 1u; k <= 8u; ++k) {
        pft_tbd_scene_out_t o =
            one(&s, trk(1u, pft_add(PFT_C(20.0), pft_mul_i(PFT_C(0.375), (int32_t)k)), PFT_C(40.0), false), Q(0.25), 0);
        TEST_ASSERT_EQUAL_INT(k < 6u ? PFT_TBD_SCENE_HOLD : PFT_TBD_SCENE_CLUTTER, o.decision);
        TEST_ASSERT_EQUAL_UINT32(k < 6u ? k : 6u, o.positions);
    }
}

static void test_curved_path_fails_the_fit(void)
{
    pft_tbd_scene_config_t cfg;
    pft_tbd_scene_t s;
    static const pft_real_t fits[3] = {PFT_C(0.2), PFT_C(0.0), PFT_C(0.25)};
    pft_tbd_scene_config_default(&cfg);
    cfg.max_tracks = SLOTS;
    for (int f = 0; f < 3; ++f) {
        cfg.fit_px = fits[f];
        init(&s, &cfg);
        for (int32_t k = 1; k <= 12; ++k) {
            const pft_real_t x = pft_add(pft_from_int(100 + k), pft_mul_i(PFT_C(0.25), k * k));
            pft_tbd_scene_out_t o = one(&s, trk(5u, x, PFT_C(30.0), false), 0, 0);
            int want = PFT_TBD_SCENE_HOLD;
            if (f == 1 && k >= 4) {
                want = PFT_TBD_SCENE_REPORT;
            }
            if (f == 2 && k == 4) {
                want = PFT_TBD_SCENE_REPORT;
            }
            TEST_ASSERT_EQUAL_INT(want, o.decision);
        }
    }
}

/* a full table: 2 slots, 3 tracks in one list: the third gets NO_SLOT; a new id takes over the
 * slot of the id fed least recently (lowest slot on a tie) */
static void test_full_table(void)
{
    pft_tbd_scene_config_t cfg;
    pft_tbd_scene_t s;
    pft_tbd_scene_track_t t[3];
    pft_tbd_scene_out_t o[3];
    pft_tbd_scene_config_default(&cfg);
    cfg.max_tracks = 2u;
    init(&s, &cfg);
    t[0] = trk(1u, PFT_C(10.0), PFT_C(10.0), false);
    t[1] = trk(2u, PFT_C(20.0), PFT_C(10.0), false);
    t[2] = trk(3u, PFT_C(30.0), PFT_C(10.0), false);
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tbd_scene_update(&s, t, 2u, 0, 0, o));
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tbd_scene_update(&s, t, 3u, 0, 0, o));
    TEST_ASSERT_EQUAL_INT(PFT_TBD_SCENE_HOLD, o[0].decision);
    TEST_ASSERT_EQUAL_INT(PFT_TBD_SCENE_HOLD, o[1].decision);
    TEST_ASSERT_EQUAL_INT(PFT_TBD_SCENE_NO_SLOT, o[2].decision);
    TEST_ASSERT_EQUAL_UINT32(0u, o[2].positions);
    TEST_ASSERT_EQUAL_UINT32(30u, o[2].px);
    TEST_ASSERT_EQUAL_UINT32(1u, pft_tbd_scene_overflows(&s));
    TEST_ASSERT_EQUAL_UINT32(2u, pft_tbd_scene_positions(&s, 1u));
    TEST_ASSERT_EQUAL_UINT32(2u, pft_tbd_scene_positions(&s, 2u));
    TEST_ASSERT_EQUAL_UINT32(0u, pft_tbd_scene_positions(&s, 3u));
    /* id 2 alone, then id 3: it takes id 1's slot (fed at frame 2, id 2 at frame 3) */
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tbd_scene_update(&s, &t[1], 1u, 0, 0, o));
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tbd_scene_update(&s, &t[2], 1u, 0, 0, o));
    TEST_ASSERT_EQUAL_INT(PFT_TBD_SCENE_HOLD, o[0].decision);
    TEST_ASSERT_EQUAL_UINT32(0u, pft_tbd_scene_positions(&s, 1u));
    TEST_ASSERT_EQUAL_UINT32(3u, pft_tbd_scene_positions(&s, 2u));
    TEST_ASSERT_EQUAL_UINT32(1u, pft_tbd_scene_positions(&s, 3u));
    TEST_ASSERT_EQUAL_UINT32(1u, pft_tbd_scene_overflows(&s));
    /* ids 3 and 1 (new): 1 takes id 2's slot, 3 keeps its own */
    t[0] = trk(3u, PFT_C(30.0), PFT_C(10.0), false);
    t[1] = trk(1u, PFT_C(10.0), PFT_C(10.0), false);
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tbd_scene_update(&s, t, 2u, 0, 0, o));
    TEST_ASSERT_EQUAL_UINT32(2u, o[0].positions);
    TEST_ASSERT_EQUAL_UINT32(1u, o[1].positions);
    TEST_ASSERT_EQUAL_UINT32(0u, pft_tbd_scene_positions(&s, 2u));
    /* a tie (ids 1 and 2 both fed at frame 1): the new id takes the lower slot, id 1's */
    init(&s, &cfg);
    t[0] = trk(1u, PFT_C(10.0), PFT_C(10.0), false);
    t[1] = trk(2u, PFT_C(20.0), PFT_C(10.0), false);
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tbd_scene_update(&s, t, 2u, 0, 0, o));
    t[0] = trk(5u, PFT_C(50.0), PFT_C(10.0), false);
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tbd_scene_update(&s, t, 1u, 0, 0, o));
    TEST_ASSERT_EQUAL_UINT32(0u, pft_tbd_scene_positions(&s, 1u));
    TEST_ASSERT_EQUAL_UINT32(1u, pft_tbd_scene_positions(&s, 2u));
    TEST_ASSERT_EQUAL_UINT32(1u, pft_tbd_scene_positions(&s, 5u));
}

/* a history is kept forget_frames (64) frames after its last frame and forgotten after */
static void test_forget(void)
{
    pft_tbd_scene_config_t cfg;
    pft_tbd_scene_t s;
    pft_tbd_scene_config_default(&cfg);
    cfg.max_tracks = SLOTS;
    init(&s, &cfg);
    (void)one(&s, trk(4u, PFT_C(10.0), PFT_C(10.0), false), 0, 0);
    (void)one(&s, trk(4u, PFT_C(10.0), PFT_C(10.0), false), 0, 0); /* frame 2 */
    for (uint32_t f = 3u; f <= 66u; ++f) {
        TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tbd_scene_update(&s, NULL, 0u, Q(1.0), 0, NULL));
        TEST_ASSERT_EQUAL_UINT32(f, pft_tbd_scene_frame(&s));
        TEST_ASSERT_EQUAL_UINT32(2u, pft_tbd_scene_positions(&s, 4u)); /* f - 2 <= 64 */
    }
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tbd_scene_update(&s, NULL, 0u, 0, 0, NULL)); /* frame 67 */
    TEST_ASSERT_EQUAL_UINT32(0u, pft_tbd_scene_positions(&s, 4u));
    /* it starts over */
    pft_tbd_scene_out_t o = one(&s, trk(4u, PFT_C(10.0), PFT_C(10.0), false), 0, 0);
    TEST_ASSERT_EQUAL_UINT32(1u, o.positions);
}

/* refused input: NULL, id 0, an id twice, NaN (float): instance, workspace and output unchanged;
 * reset gives the bytes of a fresh init */
static void test_refused_input_and_reset(void)
{
    pft_tbd_scene_config_t cfg;
    pft_tbd_scene_t s, s0;
    pft_tbd_scene_track_t t[3];
    pft_tbd_scene_out_t o[3], o0[3];
    pft_tbd_scene_config_default(&cfg);
    cfg.max_tracks = SLOTS;
    init(&s, &cfg);
    s0 = s;
    memcpy(g_copy, g_work, sizeof g_work);
    for (int32_t k = 1; k <= 7; ++k) {
        t[0] = trk(1u, pft_from_int(10 + k), PFT_C(10.0), false);
        t[1] = trk(2u, PFT_C(20.0), PFT_C(10.0), false);
        TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tbd_scene_update(&s, t, 2u, Q(0.5), Q(-0.25), o));
    }
    pft_tbd_scene_t s1 = s;
    static uint64_t w1[sizeof(g_work) / 8u];
    memcpy(w1, g_work, sizeof g_work);
    memset(o, 0x3C, sizeof o);
    memcpy(o0, o, sizeof o);
    t[2] = trk(3u, PFT_C(1.0), PFT_C(1.0), false);
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_tbd_scene_update(NULL, t, 2u, 0, 0, o));
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_tbd_scene_update(&s, NULL, 2u, 0, 0, o));
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_tbd_scene_update(&s, t, 2u, 0, 0, NULL));
    t[1].id = 0u;
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_tbd_scene_update(&s, t, 3u, 0, 0, o));
    t[1].id = 3u; /* id 3 twice */
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_tbd_scene_update(&s, t, 3u, 0, 0, o));
#ifdef PFT_NUMERIC_FLOAT
    t[1] = trk(2u, PFT_C(20.0), PFT_C(10.0), false);
    volatile float zero = 0.0f;
    t[2].y = zero / zero; /* NaN */
    TEST_ASSERT_EQUAL_INT(PFT_ERR_INVAL, pft_tbd_scene_update(&s, t, 3u, 0, 0, o));
#endif
    TEST_ASSERT_EQUAL_MEMORY(&s1, &s, sizeof s);
    TEST_ASSERT_EQUAL_MEMORY(w1, g_work, sizeof g_work);
    TEST_ASSERT_EQUAL_MEMORY(o0, o, sizeof o);
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tbd_scene_reset(&s));
    TEST_ASSERT_EQUAL_MEMORY(&s0, &s, sizeof s);
    TEST_ASSERT_EQUAL_MEMORY(g_copy, g_work, sizeof g_work);
}

/* The entering-edge hold: frame 346 x 270, n 5, no report hold, edge_px 6 (x >= 339 at the far
 * border), edge_still_px 0.1, edge_shift_px 0.2; the scene shifts by -0.25 px per frame in x (new
 * content enters at the right border) and ysh per frame in y; the track moves by (vx, vy) per
 * frame in the frame. A track fixed in the frame moves
 * at +0.25 px/frame against the scene (1.25 px over 5 frames, above the gate 0.75; below the early
 * report's 1.5 px over 3): without the option REPORT from its 6th frame on. Returns the frame
 * (1-based) of the first REPORT within `frames`, 0 for none. */
static uint32_t edge_first_report(pft_real_t edge, int32_t x0, int32_t vx, int32_t y0, int32_t vy, int32_t ysh,
                                  uint32_t frames)
{
    pft_tbd_scene_config_t cfg;
    pft_tbd_scene_t s;
    uint32_t f, first = 0u;
    pft_tbd_scene_config_default(&cfg);
    cfg.width = 346u;
    cfg.height = 270u;
    cfg.edge_px = edge;
    cfg.edge_still_px = PFT_C(0.1);
    cfg.edge_shift_px = PFT_C(0.2);
    init(&s, &cfg);
    for (f = 1u; f <= frames; ++f) {
        const int32_t x = x0 + (int32_t)(f - 1u) * vx;
        const int32_t y = y0 + (int32_t)(f - 1u) * vy;
        const pft_tbd_scene_out_t o = one(&s, trk(7u, rq(x), rq(y), false), -Q(0.25), ysh);
        TEST_ASSERT_TRUE(o.decision == PFT_TBD_SCENE_HOLD || o.decision == PFT_TBD_SCENE_REPORT);
        if (o.decision == PFT_TBD_SCENE_REPORT && first == 0u) {
            first = f;
        }
        if (first != 0u) {
            TEST_ASSERT_EQUAL_INT(PFT_TBD_SCENE_REPORT, o.decision); /* once reported, on every frame */
        }
    }
    return first;
}

static void test_edge_hold(void)
{
    /* fixed in the frame at x 341 (4 px from the border 345): held with the option, reported
     * from the 6th frame without it */
    TEST_ASSERT_EQUAL_UINT32(0u, edge_first_report(PFT_C(6.0), Q(341.0), 0, Q(100.0), 0, 0, 40u));
    TEST_ASSERT_EQUAL_UINT32(6u, edge_first_report(PFT_C(0.0), Q(341.0), 0, Q(100.0), 0, 0, 40u));
    /* just inside and just outside edge_px: x 339 (6 px) held, x 338.5 reported */
    TEST_ASSERT_EQUAL_UINT32(0u, edge_first_report(PFT_C(6.0), Q(339.0), 0, Q(100.0), 0, 0, 20u));
    TEST_ASSERT_EQUAL_UINT32(6u, edge_first_report(PFT_C(6.0), Q(338.5), 0, Q(100.0), 0, 0, 20u));
    /* the same track mid-frame, and at the leaving border (x 3): reported (a constant bearing) */
    TEST_ASSERT_EQUAL_UINT32(6u, edge_first_report(PFT_C(6.0), Q(170.0), 0, Q(100.0), 0, 0, 20u));
    TEST_ASSERT_EQUAL_UINT32(6u, edge_first_report(PFT_C(6.0), Q(3.0), 0, Q(100.0), 0, 0, 20u));
    /* entering at the right border (x 344) and moving inward at 0.5 px/frame in the frame: reported
     * at the 6th frame (x 341.5, inside the band) with and without the option */
    TEST_ASSERT_EQUAL_UINT32(6u, edge_first_report(PFT_C(6.0), Q(344.0), -Q(0.5), Q(100.0), 0, 0, 20u));
    TEST_ASSERT_EQUAL_UINT32(6u, edge_first_report(PFT_C(0.0), Q(344.0), -Q(0.5), Q(100.0), 0, 0, 20u));
    /* fixed in x at x 341 while it drifts in y (0.25 px/frame, 1.25 px over 5 frames, above
     * 5 edge_still_px): x alone decides, held */
    TEST_ASSERT_EQUAL_UINT32(0u, edge_first_report(PFT_C(6.0), Q(341.0), 0, Q(100.0), -Q(0.25), 0, 20u));
    /* the y axis: the scene also shifts by +0.25 px per frame in y (content enters at the top):
     * mid-frame in x at y 3 held, at y 266 (the leaving border in y) reported */
    TEST_ASSERT_EQUAL_UINT32(0u, edge_first_report(PFT_C(6.0), Q(170.0), 0, Q(3.0), 0, Q(0.25), 20u));
    TEST_ASSERT_EQUAL_UINT32(6u, edge_first_report(PFT_C(6.0), Q(170.0), 0, Q(266.0), 0, Q(0.25), 20u));
    /* the scene's shift below edge_shift_px (0.125 px/frame in y only; x still -0.25): y 3 is not
     * an entering border, so only x could hold, and x 170 is mid-frame: reported */
    TEST_ASSERT_EQUAL_UINT32(6u, edge_first_report(PFT_C(6.0), Q(170.0), 0, Q(3.0), 0, Q(0.125), 20u));
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_config_and_workspace);
    RUN_TEST(test_with_scene_marked_after_n_plus_1);
    RUN_TEST(test_against_scene_reported_early);
    RUN_TEST(test_report_hold);
    RUN_TEST(test_spread_hold);
    RUN_TEST(test_spread_exist);
    RUN_TEST(test_move_bound);
    RUN_TEST(test_slow_look);
    RUN_TEST(test_edge_hold);
    RUN_TEST(test_curved_path_fails_the_fit);
    RUN_TEST(test_full_table);
    RUN_TEST(test_forget);
    RUN_TEST(test_refused_input_and_reset);
    return UNITY_END();
}
