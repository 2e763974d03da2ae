/* ogk_port.h -- platform services for tests and benchmarks.
 *
 * The kernel (kernel/) never includes this header: it has no notion of time
 * or platform. Tests and benchmarks link one implementation:
 *   port/host/ogk_port_host.c      x86-64 Linux: clock_gettime(CLOCK_MONOTONIC), ns
 *   port/armv7m/ogk_port_armv7m.c  Cortex-M7, Cortex-M4F: DWT cycle counter (CYCCNT), cycles
 *
 * QEMU does not model the DWT: under qemu-system-arm the cycle counter reads
 * as 0 and ogk_port_counter_init() returns false. Repeatable ARM cost figures
 * come from counting executed instructions with the QEMU TCG plugin in
 * port/qemu-plugin/ (docs/guides/ports.md); those are instruction counts, not cycles.
 * On real Cortex-M7 or M4F silicon the counter gives core clock cycles. */
#ifndef OGK_PORT_H
#define OGK_PORT_H

#include <stdbool.h>
#include <stdint.h>

typedef enum {
    OGK_PORT_UNIT_NS = 0,     /* nanoseconds of a monotonic clock */
    OGK_PORT_UNIT_CYCLES = 1  /* core clock cycles */
} ogk_port_unit;

/* Starts the counter (enables the DWT on the Cortex-M7; nothing on the host).
 * Returns true when the counter advances, false when this platform (or its
 * emulator) does not provide it; ogk_port_counter_now() then returns 0. */
bool ogk_port_counter_init(void);

/* True when ogk_port_counter_init() found a counter that advances. */
bool ogk_port_counter_live(void);

/* Current counter value in ogk_port_counter_unit() units. Monotonic while
 * live. On the Cortex-M7 the 32-bit CYCCNT is widened to 64 bits in software:
 * call at least once every 2^32 cycles (8.6 s at 500 MHz) to see every wrap. */
uint64_t ogk_port_counter_now(void);

/* Unit of ogk_port_counter_now() and its short name ("ns", "cycles"). */
ogk_port_unit ogk_port_counter_unit(void);
const char *ogk_port_counter_unit_name(void);

/* Platform name for reports ("host", "cortex-m7", "cortex-m4f"). */
const char *ogk_port_name(void);

#endif /* OGK_PORT_H */
