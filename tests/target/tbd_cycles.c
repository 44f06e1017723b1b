/*
 * Instructions per frame of the TBD filters on a Cortex-M board under QEMU (not a test).
 * Under qemu-system-arm -icount shift=0 every guest instruction advances virtual time by 1 ns,
 * and SysTick on the processor clock (25 MHz on mps2) ticks once per 40 ns, so SysTick counts
 * instructions / 40. The program calibrates that ratio on a loop of known length, then runs
 * one RBPF-TBD and one PF-TBD filter (N = 6000, 20 x 20, 6 dB, the Exp. 1 target of
 * single_6db.json as a straight line) for 30 frames and prints, per filter, the instructions
 * of pft_tbd_filter_update per frame (mean and largest) and per particle update; then the
 * two-target manager of two_case1.json (recommended preset, Ns = 6000, Nt = 500, 35 frames,
 * both targets as straight lines) per frame. Frames are rendered outside the timed region.
 *
 * Every update is also framed by calls of pft_work_mark_begin / pft_work_mark_end, so that the
 * QEMU plugin tests/soak/qemu_marks.c counts it exactly on any target (tests/target/run_cycles.sh).
 * On targets without the mps2 SysTick (AArch64 Linux) the program prints only the sections
 * ("section <name> frames <F> particles <N>"), and the counts come from the plugin.
 */
#include <string.h>

#include "pft_test_support.h"
#include "pft_tbd_sim.h"
#include "pft/pft_tbd.h"

void setUp(void) {}
void tearDown(void) {}

#define W 20
#define N 6000u
#define FRAMES 30
#define SIGMA_6DB 3.256

#if defined(__ARM_ARCH_7M__) || defined(__ARM_ARCH_7EM__)
#define HAVE_SYSTICK 1
#define SYST_CSR (*(volatile uint32_t *)0xE000E010u)
#define SYST_RVR (*(volatile uint32_t *)0xE000E014u)
#define SYST_CVR (*(volatile uint32_t *)0xE000E018u)
#else
#define HAVE_SYSTICK 0
#endif

#include "pft_work_marks.h" /* region markers for the QEMU plugin */

static uint16_t g_raw[W * W];
#define NT 500u
#define MAXT 4u
#define FRAMES2 35
static uint8_t g_ws[PFT_TBD_FILTER_WORKSPACE_BYTES(N, PFT_TBD_RBPF, W, W) + 64u];
static uint8_t g_mws[PFT_TBD_WORKSPACE_BYTES(N, NT, MAXT, PFT_TBD_RBPF, W, W) + 64u];

#if HAVE_SYSTICK
static uint32_t now(void) { return SYST_CVR; }
#else
static uint32_t now(void) { return 0u; }
#endif
static uint32_t ticks(uint32_t t0, uint32_t t1) { return (t0 - t1) & 0xFFFFFFu; } /* counts down */

static void put(const char *s) { UnityPrint(s); }
static void eol(void) { UNITY_PRINT_EOL(); }
static void putu(uint32_t v) { UnityPrintNumberUnsigned(v); }

#if HAVE_SYSTICK
/* 2 instructions per iteration (subs, bne). */
static void spin(uint32_t n)
{
    __asm__ volatile("1: subs %0, %0, #1\n\tbne 1b" : "+r"(n) : : "cc");
}
#endif

static void section(const char *name, uint32_t frames, uint32_t particles)
{
    eol();
    put("section ");
    put(name);
    put(" frames ");
    putu(frames);
    put(" particles ");
    putu(particles);
}

static void run(pft_tbd_kind_t kind, const char *name, uint32_t per_tick)
{
    pft_tbd_config_t c;
    pft_tbd_config_default(&c);
    c.width = W;
    c.height = W;
    c.noise_sigma = pft_test_from_double(SIGMA_6DB);
    c.pixel_gain = pft_test_from_double(1.0 / 256.0);
    c.pixel_offset = pft_test_from_double(-64.0);
    c.n_search = N;
    c.kind = kind;
    c.seed = 1u;
    section(name, FRAMES, N);
    static pft_tbd_filter_t f;
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tbd_filter_init(&f, &c, g_ws, sizeof g_ws));
    pft_sim_truth_t t = {7, 22, 5.0, 6.0, 0.45, 0.25, 20.0};
    pft_rng_t sim;
    pft_rng_seed(&sim, 1u);
    uint64_t total = 0u;
    uint32_t worst = 0u;
    pft_frame_t fr;
    for (int k = 1; k <= FRAMES; ++k) {
        pft_sim_render_u16(&sim, &t, 1, k, SIGMA_6DB, W, W, g_raw, &fr);
        uint32_t t0 = now();
        pft_work_mark_begin();
        pft_status_t st = pft_tbd_filter_update(&f, &fr);
        pft_work_mark_end();
        uint32_t dt = ticks(t0, now());
        TEST_ASSERT_EQUAL_INT(PFT_OK, st);
        total += dt;
        if (dt > worst) {
            worst = dt;
        }
    }
    if (!HAVE_SYSTICK) {
        return;
    }
    eol();
    put(name);
    put(" N=6000: instructions/frame mean ");
    putu((uint32_t)(total * per_tick / FRAMES));
    put(" max ");
    putu(worst * per_tick);
    put(" per particle update ");
    putu((uint32_t)(total * per_tick / (FRAMES * (uint64_t)N)));
    eol();
}

/* The two-target manager of two_case1.json (recommended preset, Ns = 6000, Nt = 500). */
static void run_manager(uint32_t per_tick)
{
    pft_tbd_config_t c;
    pft_tbd_config_recommended(&c);
    c.width = W;
    c.height = W;
    c.noise_sigma = pft_test_from_double(SIGMA_6DB);
    c.pixel_gain = pft_test_from_double(1.0 / 256.0);
    c.pixel_offset = pft_test_from_double(-64.0);
    c.n_search = N;
    c.n_track = NT;
    c.max_targets = MAXT;
    c.kind = PFT_TBD_RBPF;
    c.seed = 1u;
    section("manager", FRAMES2, 0u);
    static pft_tbd_t m;
    TEST_ASSERT_EQUAL_INT(PFT_OK, pft_tbd_init(&m, &c, g_mws, sizeof g_mws));
    pft_sim_truth_t t[2] = {{7, 22, 1.0, 1.0, 0.70, 0.35, 20.0}, {17, 32, 2.0, 3.0, 0.55, 0.55, 20.0}};
    pft_rng_t sim;
    pft_rng_seed(&sim, 1u);
    uint64_t total = 0u;
    uint32_t worst = 0u;
    pft_frame_t fr;
    for (int k = 1; k <= FRAMES2; ++k) {
        pft_sim_render_u16(&sim, t, 2, k, SIGMA_6DB, W, W, g_raw, &fr);
        uint32_t t0 = now();
        pft_work_mark_begin();
        pft_status_t st = pft_tbd_update(&m, &fr);
        pft_work_mark_end();
        uint32_t dt = ticks(t0, now());
        TEST_ASSERT_EQUAL_INT(PFT_OK, st);
        total += dt;
        if (dt > worst) {
            worst = dt;
        }
    }
    if (!HAVE_SYSTICK) {
        return;
    }
    eol();
    put("manager Ns=6000 Nt=500 (35 frames): instructions/frame mean ");
    putu((uint32_t)(total * per_tick / FRAMES2));
    put(" max ");
    putu(worst * per_tick);
    eol();
}

static void test_cycles(void)
{
#if !HAVE_SYSTICK
    eol();
    put("no SysTick here: the counts come from the QEMU plugin (tests/target/run_cycles.sh)");
    run(PFT_TBD_RBPF, "RBPF-TBD", 0u);
    run(PFT_TBD_PF, "PF-TBD", 0u);
    run_manager(0u);
#else
    SYST_RVR = 0xFFFFFFu;
    SYST_CVR = 0u;
    SYST_CSR = 5u; /* enable, processor clock, no interrupt */
    uint32_t t0 = now();
    spin(1000000u);
    uint32_t dt = ticks(t0, now());
    eol();
    put("calibration: 2000000 instructions = ");
    putu(dt);
    put(" SysTick ticks");
    TEST_ASSERT_TRUE(dt > 0u);
    uint32_t per_tick = (2000000u + dt / 2u) / dt;
    put(" (");
    putu(per_tick);
    put(" instructions per tick)");
    run(PFT_TBD_RBPF, "RBPF-TBD", per_tick);
    run(PFT_TBD_PF, "PF-TBD", per_tick);
    run_manager(per_tick);
#endif
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_cycles);
    return UNITY_END();
}
