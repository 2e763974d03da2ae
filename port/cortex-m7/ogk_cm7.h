/* ogk_cm7.h -- services of the bare-metal Cortex-M7 runtime (startup.c) that
 * tests and benchmarks may use. Not part of the kernel. */
#ifndef OGK_CM7_H
#define OGK_CM7_H

#include <stdint.h>

/* QEMU exit codes of the runtime itself (a test's own exit code is its
 * number of failed tests, far below these). */
#define OGK_CM7_EXIT_FAULT 250 /* HardFault/MemManage/BusFault/UsageFault/NMI/stray IRQ */
#define OGK_CM7_EXIT_STACK 251 /* stack exhausted (paint at the stack limit gone) */

/* Writes a NUL-terminated string to the host's console through semihosting
 * (SYS_WRITE0), bypassing stdio. */
void ogk_cm7_write(const char *text);

/* Ends the QEMU run with exit code `code` (SYS_EXIT_EXTENDED), without
 * running atexit handlers or flushing stdio. */
void ogk_cm7_exit(int code) __attribute__((noreturn));

/* Bytes of the stack written so far (deepest point reached since reset). */
uint32_t ogk_cm7_stack_high_water(void);

/* Paints the stack again from its limit up to the address `top` (which must lie below the
 * caller's frame), so that ogk_cm7_stack_high_water restarts from there: a benchmark measures one
 * call's stack by repainting below its own frame first. */
void ogk_cm7_stack_repaint_below(uintptr_t top);

#endif /* OGK_CM7_H */
