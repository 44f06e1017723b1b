/*
 * MPS2 / QEMU semihosting helpers: console, clock, and the frame source adapter over the
 * file port (newlib's stdio already goes over semihosting, so no second reader is needed).
 */
#include <string.h>

#include "pft/pft_port_mps2.h"

#define SYS_CLOCK 0x10u
#define SYS_WRITE0 0x04u
#define SYS_ELAPSED 0x30u
#define SYS_TICKFREQ 0x31u

int32_t pft_mps2_semihost_call(uint32_t op, void *arg)
{
    register uint32_t r0 __asm__("r0") = op;
    register void *r1 __asm__("r1") = arg;
    __asm__ volatile("bkpt 0xab" : "+r"(r0) : "r"(r1) : "memory");
    return (int32_t)r0;
}

void pft_mps2_console_write(const char *s)
{
    if (s != NULL) {
        (void)pft_mps2_semihost_call(SYS_WRITE0, (void *)(uintptr_t)s);
    }
}

void pft_mps2_console_write_u32(uint32_t v)
{
    char txt[11];
    uint32_t i = sizeof txt - 1u;
    txt[i] = '\0';
    do {
        txt[--i] = (char)('0' + (v % 10u));
        v /= 10u;
    } while (v != 0u && i > 0u);
    pft_mps2_console_write(&txt[i]);
}

uint64_t pft_mps2_now_us(void *ctx)
{
    (void)ctx;
    volatile uint32_t ticks[2] = {0u, 0u};
    int32_t freq = pft_mps2_semihost_call(SYS_TICKFREQ, NULL);
    if (freq > 0 && pft_mps2_semihost_call(SYS_ELAPSED, (void *)(uintptr_t)ticks) == 0) {
        uint64_t t = ((uint64_t)ticks[1] << 32) | ticks[0];
        uint64_t f = (uint64_t)freq;
        return (t / f) * 1000000u + ((t % f) * 1000000u) / f;
    }
    int32_t cs = pft_mps2_semihost_call(SYS_CLOCK, NULL); /* centiseconds */
    return (cs > 0) ? (uint64_t)cs * 10000u : 0u;
}

void pft_mps2_runner_hooks(pft_runner_hooks_t *hooks)
{
    if (hooks != NULL) {
        memset(hooks, 0, sizeof *hooks);
        hooks->now_us = pft_mps2_now_us;
    }
}

pft_status_t pft_mps2_file_source_init(pft_file_source_t *fs, const pft_file_config_t *cfg,
                                       pft_frame_source_t *src)
{
    if (src == NULL) {
        return PFT_ERR_INVAL;
    }
    pft_status_t st = pft_file_source_init(fs, cfg);
    if (st == PFT_OK) {
        *src = pft_file_as_source(fs);
    }
    return st;
}
