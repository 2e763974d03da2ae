/* ogk_armv7m.h -- services of the bare-metal ARMv7-M runtime (startup.c: the Cortex-M7 on QEMU's
 * mps2-an500, the Cortex-M4F on mps2-an386) that tests and benchmarks may use. Not part of the kernel.
 *
 * startup.c and ogk_port_armv7m.c are compiled with OGK_ARMV7M_CORE, the core's name as a string
 * ("cortex-m7", "cortex-m4f"): it labels the runtime's reports and is ogk_port_name(). */
#ifndef OGK_ARMV7M_H
#define OGK_ARMV7M_H

#include <stdint.h>

/* QEMU exit codes of the runtime itself (a test's own exit code is its
 * number of failed tests, far below these). */
#define OGK_ARMV7M_EXIT_FAULT 250 /* HardFault/MemManage/BusFault/UsageFault/NMI/stray IRQ */
#define OGK_ARMV7M_EXIT_STACK 251 /* stack exhausted (paint at the stack limit gone) */

/* Writes a NUL-terminated string to the host's console through semihosting
 * (SYS_WRITE0), bypassing stdio. */
void ogk_armv7m_write(const char *text);

/* Ends the QEMU run with exit code `code` (SYS_EXIT_EXTENDED), without
 * running atexit handlers or flushing stdio. */
void ogk_armv7m_exit(int code) __attribute__((noreturn));

/* Bytes of the stack written so far (deepest point reached since reset). */
uint32_t ogk_armv7m_stack_high_water(void);

/* Paints the stack again from its limit up to the address `top` (which must lie below the
 * caller's frame), so that ogk_armv7m_stack_high_water restarts from there: a benchmark measures one
 * call's stack by repainting below its own frame first. */
void ogk_armv7m_stack_repaint_below(uintptr_t top);

#endif /* OGK_ARMV7M_H */
