/* startup.c -- reset, fault handling and exit reporting of the bare-metal
 * ARMv7-M builds: the Cortex-M7 on QEMU's mps2-an500, the Cortex-M4F on
 * mps2-an386 (one memory map for both, mps2.ld). Compiled with
 * -DOGK_ARMV7M_CORE='"cortex-m7"' (or "cortex-m4f"): the label of every
 * report below and the program's name.
 *
 * Boot sequence (Reset_Handler, then ogk_armv7m_c_start):
 *   1. enable the FPU: CPACR (0xE000ED88) CP10/CP11 full access, dsb, isb;
 *      with -mfloat-abi=hard the first VFP instruction faults otherwise.
 *   2. leave the small handler stack (MSP, from vector 0) for the main stack:
 *      PSP = __StackTop, CONTROL.SPSEL = 1. Faults are then handled on MSP
 *      even when the main stack is exhausted.
 *   3. trap integer division by zero (CCR.DIV_0_TRP): the core would silently
 *      return 0 and hide a kernel bug.
 *   4. copy .data from its load image in CODE, zero .bss.
 *   5. paint the main stack with a pattern, for the high-water mark printed
 *      at exit.
 *   6. MPU: CODE read-only + executable, RAM read-write + execute-never,
 *      nothing else (no background map for privileged code). The main stack
 *      is at the bottom of RAM, so an overflow faults at once (MemManage,
 *      escalated to HardFault, which runs with the MPU off).
 *   7. newlib: semihosting stdio handles, constructors, then main(); the
 *      return value goes to exit(), which newlib's rdimon turns into
 *      SYS_EXIT_EXTENDED, so it becomes QEMU's exit code.
 *
 * We do not call newlib's _start (rdimon-crt0): it asks the debugger for the
 * heap and stack placement (SYS_HEAPINFO), and QEMU answers with the largest
 * RAM of the board (its 16 MiB PSRAM: 0x60000000 on the an500, 0x21000000 on
 * the an386), so the stack would silently
 * leave the linker-script memory map; it also parses the semihosting command
 * line, which makes instruction counts depend on the length of the ELF path.
 *
 * Every fault (HardFault, MemManage, BusFault, UsageFault, NMI, stray
 * interrupt) prints its cause and the stacked PC through semihosting and
 * exits QEMU with OGK_ARMV7M_EXIT_FAULT, or OGK_ARMV7M_EXIT_STACK when the fault is
 * a main-stack overflow. */
#include <errno.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>

#include "ogk_armv7m.h"

#if !defined(OGK_ARMV7M_CORE)
#error "startup.c: define OGK_ARMV7M_CORE, the core's name as a string literal (\"cortex-m7\", \"cortex-m4f\")"
#endif

/* ------------------------------------------------------------ linker symbols */
/* Declared as functions so that the vector table can hold __StackTop without
 * an object-to-function pointer cast; only their addresses are used. */
extern void __StackTop(void);
extern uint32_t __StackLimit[];
extern void __HandlerStackTop(void);
extern char __HeapBase[];
extern char __HeapLimit[];
extern uint32_t __data_load__[];
extern uint32_t __data_start__[];
extern uint32_t __data_end__[];
extern uint32_t __bss_start__[];
extern uint32_t __bss_end__[];

/* ------------------------------------------------------------ newlib hooks */
extern void initialise_monitor_handles(void); /* librdimon: opens :tt for stdio */
extern void __libc_init_array(void);
extern void __libc_fini_array(void);
extern int main(int argc, char **argv);

/* ------------------------------------------------------------ system registers */
#define OGK_ARMV7M_REG(addr) (*(volatile uint32_t *)(uintptr_t)(addr))
#define SCB_ICSR   0xE000ED04u
#define SCB_CCR    0xE000ED14u
#define SCB_SHCSR  0xE000ED24u
#define SCB_CFSR   0xE000ED28u
#define SCB_HFSR   0xE000ED2Cu
#define SCB_MMFAR  0xE000ED34u
#define SCB_BFAR   0xE000ED38u
#define CCR_DIV_0_TRP (1u << 4)
#define MPU_CTRL   0xE000ED94u
#define MPU_RNR    0xE000ED98u
#define MPU_RBAR   0xE000ED9Cu
#define MPU_RASR   0xE000EDA0u
#define CFSR_MSTKERR   (1u << 4)
#define CFSR_MMARVALID (1u << 7)
#define CFSR_STKERR    (1u << 12)
#define CFSR_BFARVALID (1u << 15)

#define OGK_ARMV7M_STACK_PAINT 0xA5C3E1F0u

/* ------------------------------------------------------------ semihosting */
#define SH_SYS_WRITE0 0x04u
#define SH_SYS_EXIT_EXTENDED 0x20u
#define SH_ADP_STOPPED_APPLICATION_EXIT 0x20026u

static uint32_t ogk_armv7m_semihost(uint32_t op, const void *arg)
{
    register uint32_t r0 __asm__("r0") = op;
    register const void *r1 __asm__("r1") = arg;
    __asm__ volatile("bkpt 0xab" : "+r"(r0) : "r"(r1) : "memory");
    return r0;
}

void ogk_armv7m_write(const char *text)
{
    (void)ogk_armv7m_semihost(SH_SYS_WRITE0, text);
}

void ogk_armv7m_exit(int code)
{
    const uint32_t block[2] = {SH_ADP_STOPPED_APPLICATION_EXIT, (uint32_t)code};
    (void)ogk_armv7m_semihost(SH_SYS_EXIT_EXTENDED, block);
    for (;;) {
        /* not reached under QEMU; on hardware without a debugger: stop here */
    }
}

/* "0x" + 8 hex digits into out[11] (NUL-terminated). */
static void ogk_armv7m_hex32(uint32_t value, char out[11])
{
    static const char digits[] = "0123456789abcdef";
    out[0] = '0';
    out[1] = 'x';
    for (unsigned i = 0u; i < 8u; ++i) {
        out[2u + i] = digits[(value >> (28u - 4u * i)) & 0xFu];
    }
    out[10] = '\0';
}

static void ogk_armv7m_write_reg(const char *name, uint32_t value)
{
    char hex[11];
    ogk_armv7m_hex32(value, hex);
    ogk_armv7m_write(" ");
    ogk_armv7m_write(name);
    ogk_armv7m_write("=");
    ogk_armv7m_write(hex);
}

/* ------------------------------------------------------------ faults */
static const char *ogk_armv7m_exception_name(uint32_t ipsr)
{
    switch (ipsr) {
    case 2u: return "NMI";
    case 3u: return "HardFault";
    case 4u: return "MemManage";
    case 5u: return "BusFault";
    case 6u: return "UsageFault";
    case 11u: return "SVCall";
    case 12u: return "DebugMonitor";
    case 14u: return "PendSV";
    case 15u: return "SysTick";
    default: return (ipsr >= 16u) ? "unexpected interrupt" : "reserved exception";
    }
}

/* Names of the set CFSR bits (ARMv7-M ARM B3.2.15). */
static void ogk_armv7m_write_cfsr_bits(uint32_t cfsr)
{
    static const struct { uint32_t bit; const char *name; } bits[] = {
        {1u << 0, "IACCVIOL"}, {1u << 1, "DACCVIOL"}, {1u << 3, "MUNSTKERR"},
        {1u << 4, "MSTKERR"}, {1u << 5, "MLSPERR"}, {1u << 8, "IBUSERR"},
        {1u << 9, "PRECISERR"}, {1u << 10, "IMPRECISERR"}, {1u << 11, "UNSTKERR"},
        {1u << 12, "STKERR"}, {1u << 13, "LSPERR"}, {1u << 16, "UNDEFINSTR"},
        {1u << 17, "INVSTATE"}, {1u << 18, "INVPC"}, {1u << 19, "NOCP"},
        {1u << 24, "UNALIGNED"}, {1u << 25, "DIVBYZERO"},
    };
    for (unsigned i = 0u; i < sizeof bits / sizeof bits[0]; ++i) {
        if ((cfsr & bits[i].bit) != 0u) {
            ogk_armv7m_write(" ");
            ogk_armv7m_write(bits[i].name);
        }
    }
}

/* Called by ogk_armv7m_fault_entry with the exception stack frame
 * (r0, r1, r2, r3, r12, lr, pc, xpsr) and EXC_RETURN. Uses semihosting
 * directly, not stdio: the C library state may be what is broken. */
void ogk_armv7m_fault_report(const uint32_t *frame, uint32_t exc_return)
    __attribute__((used, noreturn));
void ogk_armv7m_fault_report(const uint32_t *frame, uint32_t exc_return)
{
    uint32_t ipsr;
    __asm__ volatile("mrs %0, ipsr" : "=r"(ipsr));
    ipsr &= 0x1FFu;
    const uint32_t cfsr = OGK_ARMV7M_REG(SCB_CFSR);
    const uint32_t mmfar = OGK_ARMV7M_REG(SCB_MMFAR);
    const uintptr_t stack_limit = (uintptr_t)__StackLimit;
    const uintptr_t frame_addr = (uintptr_t)frame;
    /* Stacking failed, or a data access just below the main stack (MMFAR
     * valid and within 16 MiB under RAM, where nothing else lives). */
    const int stack_overflow =
        ((cfsr & (CFSR_MSTKERR | CFSR_STKERR)) != 0u) || (frame_addr < stack_limit) ||
        (((cfsr & CFSR_MMARVALID) != 0u) && (mmfar < stack_limit) &&
         (mmfar >= stack_limit - 0x1000000u));

    ogk_armv7m_write("\n[" OGK_ARMV7M_CORE "] FAULT: ");
    ogk_armv7m_write(ogk_armv7m_exception_name(ipsr));
    ogk_armv7m_write_cfsr_bits(cfsr);
    if (stack_overflow) {
        ogk_armv7m_write(" -- main stack overflow (link with -Wl,--defsym=__stack_size=N,"
                      " or move large contexts to static storage)");
    }
    ogk_armv7m_write("\n[" OGK_ARMV7M_CORE "]");
    if (frame_addr >= stack_limit && (cfsr & (CFSR_MSTKERR | CFSR_STKERR)) == 0u) {
        ogk_armv7m_write_reg("pc", frame[6]);
        ogk_armv7m_write_reg("lr", frame[5]);
        ogk_armv7m_write_reg("xpsr", frame[7]);
    } else {
        ogk_armv7m_write(" (exception frame not stacked)");
    }
    ogk_armv7m_write_reg("sp", (uint32_t)frame_addr);
    ogk_armv7m_write_reg("exc_return", exc_return);
    ogk_armv7m_write("\n[" OGK_ARMV7M_CORE "]");
    ogk_armv7m_write_reg("CFSR", cfsr);
    ogk_armv7m_write_reg("HFSR", OGK_ARMV7M_REG(SCB_HFSR));
    if ((cfsr & CFSR_MMARVALID) != 0u) {
        ogk_armv7m_write_reg("MMFAR", mmfar);
    }
    if ((cfsr & CFSR_BFARVALID) != 0u) {
        ogk_armv7m_write_reg("BFAR", OGK_ARMV7M_REG(SCB_BFAR));
    }
    ogk_armv7m_write("\n[" OGK_ARMV7M_CORE "] (source line: arm-none-eabi-addr2line -e <elf> <pc>)\n");
    ogk_armv7m_exit(stack_overflow ? OGK_ARMV7M_EXIT_STACK : OGK_ARMV7M_EXIT_FAULT);
}

/* Picks the stack that holds the exception frame (MSP or PSP by EXC_RETURN
 * bit 2) and hands it to the C reporter. */
__attribute__((naked)) void ogk_armv7m_fault_entry(void)
{
    __asm__ volatile(
        "tst lr, #4\n\t"
        "ite eq\n\t"
        "mrseq r0, msp\n\t"
        "mrsne r0, psp\n\t"
        "mov r1, lr\n\t"
        "b ogk_armv7m_fault_report\n\t");
}

/* ------------------------------------------------------------ stack watermark */
static uint32_t ogk_armv7m_stack_bytes(void)
{
    return (uint32_t)((uintptr_t)&__StackTop - (uintptr_t)__StackLimit);
}

uint32_t ogk_armv7m_stack_high_water(void)
{
    const uint32_t words = ogk_armv7m_stack_bytes() / 4u;
    uint32_t untouched = 0u;
    while (untouched < words && __StackLimit[untouched] == OGK_ARMV7M_STACK_PAINT) {
        ++untouched;
    }
    return (words - untouched) * 4u;
}

__attribute__((noinline)) void ogk_armv7m_stack_repaint_below(uintptr_t top)
{
    volatile uint32_t *word = __StackLimit;
    while ((uintptr_t)word < top) {
        *word++ = OGK_ARMV7M_STACK_PAINT;
    }
}

static void ogk_armv7m_at_exit(void)
{
    const uint32_t used = ogk_armv7m_stack_high_water();
    const uint32_t size = ogk_armv7m_stack_bytes();
    fflush(stdout);
    if (used >= size) { /* the MPU should have faulted first */
        fprintf(stderr, "[" OGK_ARMV7M_CORE "] STACK OVERFLOW: the %lu-byte main stack was exhausted\n",
                (unsigned long)size);
        fflush(stderr);
        ogk_armv7m_exit(OGK_ARMV7M_EXIT_STACK);
    }
    fprintf(stderr, "[" OGK_ARMV7M_CORE "] stack high-water mark: %lu of %lu bytes\n",
            (unsigned long)used, (unsigned long)size);
    fflush(stderr);
}

/* ------------------------------------------------------------ heap */
/* Replaces librdimon's weak _sbrk, which assumes the stack lies above the
 * heap: here the heap runs from the end of .bss to the end of RAM. */
void *_sbrk(ptrdiff_t increment);
void *_sbrk(ptrdiff_t increment)
{
    static char *heap_end = NULL;
    if (heap_end == NULL) {
        heap_end = __HeapBase;
    }
    const ptrdiff_t room_above = __HeapLimit - heap_end;
    const ptrdiff_t room_below = heap_end - __HeapBase;
    if (increment > room_above || -increment > room_below) {
        errno = ENOMEM;
        return (void *)-1;
    }
    char *previous_end = heap_end;
    heap_end += increment;
    return previous_end;
}

/* ------------------------------------------------------------ MPU */
/* PMSAv7 region attribute and size register fields (ARMv7-M ARM B3.5.9). */
#define RASR_XN            (1u << 28)
#define RASR_AP_RO         (6u << 24) /* read-only, privileged and unprivileged */
#define RASR_AP_RW         (3u << 24) /* read-write, privileged and unprivileged */
#define RASR_NORMAL_WT     (1u << 17) /* TEX=000 C=1 B=0: normal, write-through */
#define RASR_NORMAL_WBWA   ((1u << 19) | (1u << 17) | (1u << 16)) /* TEX=001 C=1 B=1 */
#define RASR_SIZE_4MIB     (21u << 1) /* 2^(SIZE+1) bytes */
#define RASR_ENABLE        1u
#define MPU_CTRL_ENABLE    1u         /* HFNMIENA=0: off in HardFault; PRIVDEFENA=0 */

static void ogk_armv7m_mpu_enable(void)
{
    OGK_ARMV7M_REG(MPU_RNR) = 0u; /* CODE */
    OGK_ARMV7M_REG(MPU_RBAR) = 0x00000000u;
    OGK_ARMV7M_REG(MPU_RASR) = RASR_AP_RO | RASR_NORMAL_WT | RASR_SIZE_4MIB | RASR_ENABLE;
    OGK_ARMV7M_REG(MPU_RNR) = 1u; /* RAM */
    OGK_ARMV7M_REG(MPU_RBAR) = 0x20000000u;
    OGK_ARMV7M_REG(MPU_RASR) =
        RASR_XN | RASR_AP_RW | RASR_NORMAL_WBWA | RASR_SIZE_4MIB | RASR_ENABLE;
    __asm__ volatile("dsb" ::: "memory");
    OGK_ARMV7M_REG(MPU_CTRL) = MPU_CTRL_ENABLE;
    __asm__ volatile("dsb\n\tisb" ::: "memory");
}

/* ------------------------------------------------------------ reset */
void ogk_armv7m_c_start(void) __attribute__((used, noreturn));
void ogk_armv7m_c_start(void)
{
    OGK_ARMV7M_REG(SCB_CCR) |= CCR_DIV_0_TRP;

    for (uint32_t *dst = __data_start__, *src = __data_load__; dst < __data_end__;) {
        *dst++ = *src++;
    }
    for (uint32_t *dst = __bss_start__; dst < __bss_end__;) {
        *dst++ = 0u;
    }

    /* Paint from the stack limit up to 256 bytes below the current frame. */
    uint32_t sp;
    __asm__ volatile("mov %0, sp" : "=r"(sp));
    for (uint32_t *word = __StackLimit; (uintptr_t)word < (uintptr_t)sp - 256u;) {
        *word++ = OGK_ARMV7M_STACK_PAINT;
    }

    ogk_armv7m_mpu_enable();
    initialise_monitor_handles();
    (void)atexit(__libc_fini_array);
    __libc_init_array();
    (void)atexit(ogk_armv7m_at_exit);

    static char program_name[] = "ogk-" OGK_ARMV7M_CORE;
    char *argv[] = {program_name, NULL};
    exit(main(1, argv));
}

/* Runs on the handler stack (MSP from vector 0). Enables CP10/CP11 before
 * any C code, since the compiler may use VFP registers anywhere, then moves
 * thread mode to the main stack (PSP). */
__attribute__((naked)) void Reset_Handler(void)
{
    __asm__ volatile(
        "ldr r0, =0xE000ED88\n\t"
        "ldr r1, [r0]\n\t"
        "orr r1, r1, #(0xF << 20)\n\t"
        "str r1, [r0]\n\t"
        "dsb\n\t"
        "isb\n\t"
        "ldr r0, =__StackTop\n\t"
        "msr psp, r0\n\t"
        "mrs r0, control\n\t"
        "orr r0, r0, #2\n\t"
        "msr control, r0\n\t"
        "isb\n\t"
        "b ogk_armv7m_c_start\n\t"
        ".ltorg\n\t");
}

/* ------------------------------------------------------------ vector table */
typedef void (*ogk_armv7m_vector)(void);

/* 16 system exceptions + 32 external interrupts (the AN500 has fewer; none
 * is enabled, so any that fires is reported as a fault). */
__attribute__((section(".vectors"), used))
const ogk_armv7m_vector ogk_armv7m_vectors[16 + 32] = {
    __HandlerStackTop,   /* 0: initial MSP (handler stack) */
    Reset_Handler,       /* 1: reset */
    ogk_armv7m_fault_entry, /* 2: NMI */
    ogk_armv7m_fault_entry, /* 3: HardFault */
    ogk_armv7m_fault_entry, /* 4: MemManage */
    ogk_armv7m_fault_entry, /* 5: BusFault */
    ogk_armv7m_fault_entry, /* 6: UsageFault */
    0, 0, 0, 0,          /* 7-10: reserved */
    ogk_armv7m_fault_entry, /* 11: SVCall */
    ogk_armv7m_fault_entry, /* 12: DebugMonitor */
    0,                   /* 13: reserved */
    ogk_armv7m_fault_entry, /* 14: PendSV */
    ogk_armv7m_fault_entry, /* 15: SysTick */
    [16 ... 47] = ogk_armv7m_fault_entry,
};
