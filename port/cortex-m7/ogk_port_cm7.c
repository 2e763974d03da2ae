/* ogk_port_cm7.c -- ogk_port.h on the Cortex-M7: the DWT cycle counter.
 *
 * DWT_CYCCNT counts core clock cycles once DEMCR.TRCENA and DWT_CTRL.CYCCNTENA
 * are set (ARMv7-M ARM C1.8). QEMU 7.2 does not model the DWT: its registers
 * read as zero, so ogk_port_counter_init() reports the counter as not live
 * and benchmarks fall back to QEMU instruction counting (docs/guides/ports.md). */
#include "ogk_port.h"

#define OGK_CM7_REG(addr) (*(volatile uint32_t *)(uintptr_t)(addr))
#define DEMCR       0xE000EDFCu
#define DEMCR_TRCENA (1u << 24)
#define DWT_CTRL    0xE0001000u
#define DWT_CTRL_CYCCNTENA 1u
#define DWT_CYCCNT  0xE0001004u
#define DWT_LAR     0xE0001FB0u /* software lock of the M7's CoreSight registers */
#define DWT_LAR_UNLOCK 0xC5ACCE55u

/* Software extension of the 32-bit counter to 64 bits. */
static uint32_t ogk_port_cm7_last;
static uint64_t ogk_port_cm7_high;
static bool ogk_port_cm7_live;

bool ogk_port_counter_init(void)
{
    OGK_CM7_REG(DEMCR) |= DEMCR_TRCENA;
    OGK_CM7_REG(DWT_LAR) = DWT_LAR_UNLOCK;
    OGK_CM7_REG(DWT_CYCCNT) = 0u;
    OGK_CM7_REG(DWT_CTRL) |= DWT_CTRL_CYCCNTENA;

    const uint32_t first = OGK_CM7_REG(DWT_CYCCNT);
    for (volatile uint32_t spin = 0u; spin < 64u; ++spin) {
        /* a few dozen cycles for the counter to move */
    }
    const uint32_t second = OGK_CM7_REG(DWT_CYCCNT);

    ogk_port_cm7_live = (second != first);
    ogk_port_cm7_last = second;
    ogk_port_cm7_high = 0u;
    return ogk_port_cm7_live;
}

bool ogk_port_counter_live(void)
{
    return ogk_port_cm7_live;
}

uint64_t ogk_port_counter_now(void)
{
    if (!ogk_port_cm7_live) {
        return 0u;
    }
    const uint32_t now = OGK_CM7_REG(DWT_CYCCNT);
    if (now < ogk_port_cm7_last) {
        ogk_port_cm7_high += UINT64_C(1) << 32;
    }
    ogk_port_cm7_last = now;
    return ogk_port_cm7_high | now;
}

ogk_port_unit ogk_port_counter_unit(void)
{
    return OGK_PORT_UNIT_CYCLES;
}

const char *ogk_port_counter_unit_name(void)
{
    return "cycles";
}

const char *ogk_port_name(void)
{
    return "cortex-m7";
}
