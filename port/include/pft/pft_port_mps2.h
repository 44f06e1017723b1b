/**
 * @file pft_port_mps2.h
 * @brief Bare-metal Cortex-M port for the MPS2 boards under QEMU (semihosting).
 *
 * Built only for PFT_TARGET=mps2 (the m3/m7 presets), where PFT_PORT_MPS2 is defined.
 * Start-up and memory map: qemu_mps2/startup.c and mps2.ld (vector table, .data copy, FPU
 * enable, newlib's _start, faults reported as exit code 139).
 *
 * Frame input: this port is a thin adapter over the file port. newlib's rdimon stdio turns
 * fopen/fread/fwrite into semihosting SYS_OPEN/SYS_READ/SYS_WRITE, so the file port reads raw
 * and PGM/PPM sequences from the host unchanged; relative paths resolve against QEMU's
 * working directory. Everything here adds only what newlib does not give: an unbuffered
 * console write that works before or without stdio (e.g. in a fault handler) and a clock.
 */
#ifndef PFT_PORT_MPS2_H
#define PFT_PORT_MPS2_H

#include "pft/pft_port.h"
#include "pft/pft_port_file.h"

#ifdef __cplusplus
extern "C" {
#endif

/** Raw semihosting call (`bkpt 0xab`): operation in r0, parameter block in r1, result r0. */
int32_t pft_mps2_semihost_call(uint32_t op, void *arg);

/** Writes a zero-terminated string to the host console with SYS_WRITE0 (no buffering). */
void pft_mps2_console_write(const char *s);

/** Writes an unsigned decimal number with SYS_WRITE0. */
void pft_mps2_console_write_u32(uint32_t v);

/**
 * Microseconds since start: SYS_ELAPSED / SYS_TICKFREQ (QEMU: nanosecond host clock), or
 * SYS_CLOCK (10 ms steps) where those are missing. Host time, not emulated cycles: use it
 * for coarse profiling only. Signature fits pft_runner_hooks_t::now_us (ctx unused).
 */
uint64_t pft_mps2_now_us(void *ctx);

/** Runner hooks for this port: now_us = pft_mps2_now_us, the others NULL. */
void pft_mps2_runner_hooks(pft_runner_hooks_t *hooks);

/**
 * A frame source reading a raw or PGM/PPM sequence over semihosting: pft_file_source_init,
 * then `*src` = its pft_frame_source_t view. Same statuses as pft_file_source_init.
 */
pft_status_t pft_mps2_file_source_init(pft_file_source_t *fs, const pft_file_config_t *cfg,
                                       pft_frame_source_t *src);

/** Ends the program with an exit code through SYS_EXIT_EXTENDED (defined in startup.c). */
void pft_mps2_semihost_exit(uint32_t code);

#ifdef __cplusplus
}
#endif
#endif
