/*
 * Bare-metal start-up for the MPS2 boards under QEMU (Cortex-M3/M4/M7).
 * The vector table at 0x0 points to pft_mps2_reset, which copies .data, enables the FPU on
 * hard-float builds, then enters newlib's _start (rdimon: clears .bss, sets up semihosting
 * stdio and argv, calls main, exits with main's return value through SYS_EXIT_EXTENDED).
 * Faults report exit code 139 through SYS_EXIT_EXTENDED themselves, so a crash can never look
 * like a pass (plain SYS_EXIT would map to exit code 0 under QEMU).
 */
#include <stdint.h>

extern uint32_t __stack_top;
extern uint32_t __etext, __data_start__, __data_end__;
extern void _start(void);
void pft_mps2_reset(void);
void pft_mps2_fault(void);
void pft_mps2_semihost_exit(uint32_t code);

void pft_mps2_semihost_exit(uint32_t code)
{
    /* SYS_EXIT_EXTENDED (0x20): r1 -> {reason ADP_Stopped_ApplicationExit, code} */
    volatile uint32_t block[2] = {0x20026u, code};
    register uint32_t r0 __asm__("r0") = 0x20u;
    register volatile uint32_t *r1 __asm__("r1") = block;
    __asm__ volatile("bkpt 0xab" : : "r"(r0), "r"(r1) : "memory");
    for (;;) {
    }
}

void pft_mps2_fault(void)
{
    pft_mps2_semihost_exit(139u);
}

void pft_mps2_reset(void)
{
    uint32_t *src = &__etext;
    uint32_t *dst = &__data_start__;
    while (dst < &__data_end__) {
        *dst++ = *src++;
    }
#if defined(__ARM_FP)
    /* CPACR: full access to CP10/CP11 before any floating-point instruction */
    *(volatile uint32_t *)0xE000ED88u |= (0xFu << 20);
    __asm__ volatile("dsb\n\tisb" ::: "memory");
#endif
    _start();
    pft_mps2_semihost_exit(134u); /* _start never returns; if it does, fail loudly */
}

typedef void (*pft_vector_t)(void);
__attribute__((section(".isr_vector"), used)) const pft_vector_t pft_mps2_vectors[16] = {
    (pft_vector_t)(uintptr_t)&__stack_top,
    pft_mps2_reset,
    pft_mps2_fault, /* NMI */
    pft_mps2_fault, /* HardFault */
    pft_mps2_fault, /* MemManage */
    pft_mps2_fault, /* BusFault */
    pft_mps2_fault, /* UsageFault */
    0, 0, 0, 0,
    pft_mps2_fault, /* SVC */
    pft_mps2_fault, /* DebugMon */
    0,
    pft_mps2_fault, /* PendSV */
    pft_mps2_fault  /* SysTick */
};
