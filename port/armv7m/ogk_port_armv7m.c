/* ogk_port_armv7m.c -- ogk_port.h on the ARMv7-M cores (Cortex-M7, Cortex-M4F): the DWT cycle
 * counter. Compiled with OGK_ARMV7M_CORE, the core's name (ogk_port_name()).
 *
 * DWT_CYCCNT counts core clock cycles once DEMCR.TRCENA and DWT_CTRL.CYCCNTENA
 * are set (ARMv7-M ARM C1.8). QEMU 7.2 does not model the DWT: its registers
 * read as zero, so ogk_port_counter_init() reports the counter as not live
 * and benchmarks fall back to QEMU instruction counting (docs/guides/ports.md). */
#include "ogk_port.h"

#if !defined(OGK_ARMV7M_CORE)
#error "ogk_port_armv7m.c: define OGK_ARMV7M_CORE, the core's name as a string literal"
#endif

#define OGK_ARMV7M_REG(addr) (*(volatile uint32_t *)(uintptr_t)(addr))
#define DEMCR       0xE000EDFCu
#define DEMCR_TRCENA (1u << 24)
#define DWT_CTRL    0xE0001000u
#define DWT_CTRL_CYCCNTENA 1u
#define DWT_CYCCNT  0xE0001004u
#define DWT_LAR     0xE0001FB0u /* software lock of the M7's CoreSight registers (not in the M4's DWT register list) */
#define DWT_LAR_UNLOCK 0xC5ACCE55u

/* Software extension of the 32-bit counter to 64 bits. */
static uint32_t ogk_port_armv7m_last;
static uint64_t ogk_port_armv7m_high;
static bool ogk_port_armv7m_live;

bool ogk_port_counter_init(void)
{
    OGK_ARMV7M_REG(DEMCR) |= DEMCR_TRCENA;
    OGK_ARMV7M_REG(DWT_LAR) = DWT_LAR_UNLOCK;
    OGK_ARMV7M_REG(DWT_CYCCNT) = 0u;
    OGK_ARMV7M_REG(DWT_CTRL) |= DWT_CTRL_CYCCNTENA;

    const uint32_t first = OGK_ARMV7M_REG(DWT_CYCCNT);
    for (volatile uint32_t spin = 0u; spin < 64u; ++spin) {
        /* a few dozen cycles for the counter to move */
    }
    const uint32_t second = OGK_ARMV7M_REG(DWT_CYCCNT);

    ogk_port_armv7m_live = (second != first);
    ogk_port_armv7m_last = second;
    ogk_port_armv7m_high = 0u;
    return ogk_port_armv7m_live;
}

bool ogk_port_counter_live(void)
{
    return ogk_port_armv7m_live;
}

uint64_t ogk_port_counter_now(void)
{
    if (!ogk_port_armv7m_live) {
        return 0u;
    }
    const uint32_t now = OGK_ARMV7M_REG(DWT_CYCCNT);
    if (now < ogk_port_armv7m_last) {
        ogk_port_armv7m_high += UINT64_C(1) << 32;
    }
    ogk_port_armv7m_last = now;
    return ogk_port_armv7m_high | now;
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
    return OGK_ARMV7M_CORE;
}
