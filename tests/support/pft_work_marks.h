/* Region markers for the QEMU plugin tests/soak/qemu_marks.c, which counts the guest
 * instructions executed between a call of pft_work_mark_begin and the next call of
 * pft_work_mark_end (tests/soak/run_soak.sh work-qemu, tests/target/run_cycles.sh). Include it
 * in exactly one translation unit of a program: it defines the two functions (external, so the
 * plugin finds them by name; not inlined; different bodies so the compiler cannot fold them). */
#ifndef PFT_WORK_MARKS_H
#define PFT_WORK_MARKS_H

#include <stdint.h>

volatile uint32_t g_mark_begins, g_mark_ends;
__attribute__((noinline)) void pft_work_mark_begin(void);
__attribute__((noinline)) void pft_work_mark_end(void);
__attribute__((noinline)) void pft_work_mark_begin(void) { g_mark_begins++; }
__attribute__((noinline)) void pft_work_mark_end(void) { g_mark_ends++; }

#endif
