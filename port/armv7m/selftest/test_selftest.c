/* test_selftest.c -- checks of the ARMv7-M test route itself (the Cortex-M7
 * and the Cortex-M4F): IEEE double precision (the M7's FPU, the M4F's
 * software), single precision on the FPU, libm, printf of doubles, 64-bit
 * integers, setjmp/longjmp across floating-point callee-saved registers, large
 * static and stack storage, the port counter, and (on the target) the core,
 * its FPU and the runtime configuration.
 *
 * Built like tests/unit/test_*.c (ogk_test.h, cmocka or the shim runner) for
 * QEMU by `make test-arm-selftest` (M7) and `make test-m4f-selftest` (M4F),
 * which also build it:
 *   -DOGK_SELFTEST_INJECT_FAILURES  adds inject_* tests that must all fail;
 *       the target checks QEMU's exit code equals their number and that the
 *       host build diffs identically between real cmocka and the shim;
 *   -DOGK_SELFTEST_INJECT_FAULT     divides by zero: QEMU must exit 250;
 *   -DOGK_SELFTEST_INJECT_OVERFLOW  overflows the main stack: QEMU must exit 251.
 *
 * References are independent of the code under test: exact IEEE-754 bit
 * patterns, mathematical constants to 20 digits, C-standard printf output. */
#include "ogk_test.h"
#include "ogk_port.h"

#include <float.h>
#include <stdio.h>
#include <string.h>

#if defined(__arm__)
#include "ogk_armv7m.h"

/* The core this build is for, from the compiler's FPU macros (not from the runtime under test):
 * hardware double precision (fpv5-d16) is the Cortex-M7, single precision only (fpv4-sp-d16) the
 * Cortex-M4F. Its CPUID part number and MVFR0's double-precision field (ARMv7-M ARM B4.1.2, B4.6.4)
 * are checked on the board that runs it. */
#if !defined(__ARM_FP) || ((__ARM_FP & 0x4) == 0) || !defined(__ARM_PCS_VFP)
#error "the ARMv7-M route is built with a hardware FPU and the hard-float ABI (-mfloat-abi=hard)"
#endif
#if (__ARM_FP & 0x8) != 0
#define SELFTEST_CORE "cortex-m7"
#define SELFTEST_CPUID_PART 0xC27u /* Cortex-M7 */
#define SELFTEST_MVFR0_DOUBLE 2u   /* double precision in hardware */
#else
#define SELFTEST_CORE "cortex-m4f"
#define SELFTEST_CPUID_PART 0xC24u /* Cortex-M4 */
#define SELFTEST_MVFR0_DOUBLE 0u   /* no double precision: doubles are library calls */
#endif
#endif

/* Two units in the last place of x. */
static double two_ulp(double x)
{
    return 2.0 * (nextafter(fabs(x), INFINITY) - fabs(x));
}

static uint64_t bits_of(double x)
{
    uint64_t bits;
    memcpy(&bits, &x, sizeof bits);
    return bits;
}

static uint32_t bits_of_float(float x)
{
    uint32_t bits;
    memcpy(&bits, &x, sizeof bits);
    return bits;
}

/* Inputs through volatile objects so that nothing is folded at compile time:
 * the target's FPU and libm compute every value below. */
static volatile double v_two = 2.0;
static volatile double v_one = 1.0;
static volatile double v_half = 0.5;
static volatile double v_ten = 10.0;
static volatile double v_tenth = 0.1;
static volatile float vf_two = 2.0f;
static volatile float vf_one = 1.0f;
static volatile float vf_ten = 10.0f;
static volatile float vf_tenth = 0.1f;

static void test_sqrt_is_correctly_rounded(void **state)
{
    (void)state;
    /* IEEE 754 requires sqrt to be correctly rounded: sqrt(2) rounds to
     * 0x1.6a09e667f3bcdp+0 (1.41421356237309504880... lies 0.27 ulp above). */
    assert_int_equal(bits_of(sqrt(v_two)), UINT64_C(0x3FF6A09E667F3BCD));
    assert_int_equal(bits_of(v_one / 3.0), UINT64_C(0x3FD5555555555555));
    assert_int_equal(bits_of(v_tenth + 0.2), UINT64_C(0x3FD3333333333334));
}

static void test_libm_matches_constants(void **state)
{
    (void)state;
    /* Values of the constants to 20 significant digits (tables of e, ln 10,
     * pi, sin/cos 1/2); libm is allowed 2 ulp. */
    const double e_ref = 2.7182818284590452354;
    const double ln10_ref = 2.3025850929940456840;
    const double pi_ref = 3.1415926535897932385;
    const double sin_half_ref = 0.47942553860420300027;
    const double cos_half_ref = 0.87758256189037271612;
    OGK_ASSERT_NEAR(exp(v_one), e_ref, two_ulp(e_ref));
    OGK_ASSERT_NEAR(log(v_ten), ln10_ref, two_ulp(ln10_ref));
    OGK_ASSERT_NEAR(4.0 * atan2(v_one, v_one), pi_ref, two_ulp(pi_ref));
    OGK_ASSERT_NEAR(sin(v_half), sin_half_ref, two_ulp(sin_half_ref));
    OGK_ASSERT_NEAR(cos(v_half), cos_half_ref, two_ulp(cos_half_ref));
    OGK_ASSERT_NEAR(pow(v_two, 0.5), sqrt(v_two), two_ulp(1.4142135623730951));
#if defined(__arm__) && ((__ARM_FP & 0x8) == 0)
    /* Without a double-precision FPU (the M4F), newlib's fma is x * y + z rounded twice
     * (libm/common/s_fma.c), not fused: 0.1 * 10 rounds to 1 and the 2^-54 is lost. The kernel calls
     * no fma; this records the library's behaviour, so that a change of it shows here. */
    assert_int_equal(bits_of(fma(v_tenth, v_ten, -1.0)), bits_of(0.0));
#else
    OGK_ASSERT_NEAR(fma(v_tenth, v_ten, -1.0), 5.5511151231257827e-17, 0.0);
#endif
}

static void test_subnormals_are_not_flushed(void **state)
{
    (void)state;
    /* FPSCR.FZ must be 0: the kernel's tolerances assume full IEEE doubles. */
    volatile double tiny = DBL_MIN;
    const double quarter = tiny / 4.0;
    assert_true(quarter > 0.0);
    assert_int_equal(fpclassify(quarter), FP_SUBNORMAL);
    assert_int_equal(bits_of(quarter), UINT64_C(0x0004000000000000));
    assert_true(isnan(v_one * NAN));
    assert_true(isinf(v_one / 0.0));
}

/* Single precision, as the kernel's OGK_REAL_SINGLE build computes (on the FPU of both cores):
 * correctly rounded sqrt and division, a fused multiply-add, subnormals not flushed to zero. */
static void test_single_precision_is_ieee(void **state)
{
    (void)state;
    /* sqrt(2) rounds to 0x1.6a09e6p+0 (the root lies 0.20 ulp above), 1/3 to 0x1.555556p-2 */
    assert_int_equal(bits_of_float(sqrtf(vf_two)), 0x3FB504F3u);
    assert_int_equal(bits_of_float(vf_one / 3.0f), 0x3EAAAAABu);
    /* 0.1f * 10 is 1 + 2^-26 exactly: fused, 2^-26 remains; rounded first, 0 would */
    assert_int_equal(bits_of_float(fmaf(vf_tenth, vf_ten, -1.0f)), 0x32800000u);
    volatile float tiny = FLT_MIN;
    const float quarter = tiny / 4.0f;
    assert_int_equal(fpclassify(quarter), FP_SUBNORMAL);
    assert_int_equal(bits_of_float(quarter), 0x00200000u);
#if defined(__arm__)
    /* the FPU's own square root, not a library's */
    float root;
    __asm__ volatile("vsqrt.f32 %0, %1" : "=t"(root) : "t"(vf_two));
    assert_int_equal(bits_of_float(root), 0x3FB504F3u);
    uint32_t fpscr;
    __asm__ volatile("vmrs %0, fpscr" : "=r"(fpscr));
    assert_int_equal((fpscr >> 24) & 1u, 0u); /* FZ: subnormals kept */
#endif
}

static void test_printf_of_doubles(void **state)
{
    (void)state;
    /* newlib-nano prints nothing for %f/%g/%e unless _printf_float is linked:
     * this route uses the full newlib. */
    char text[64];
    (void)snprintf(text, sizeof text, "%.17g", v_tenth);
    assert_string_equal(text, "0.10000000000000001");
    (void)snprintf(text, sizeof text, "%.3e", v_ten * 6.02214076e22);
    assert_string_equal(text, "6.022e+23");
    (void)snprintf(text, sizeof text, "%f|%g", -2.5 * v_one, 1e-310 * v_one);
    assert_string_equal(text, "-2.500000|1e-310");
    (void)snprintf(text, sizeof text, "%llu %lld", (unsigned long long)UINT64_MAX,
                   (long long)INT64_MIN);
    assert_string_equal(text, "18446744073709551615 -9223372036854775808");
}

static void test_int64_arithmetic(void **state)
{
    (void)state;
    volatile uint64_t all_ones = UINT64_MAX;
    volatile int64_t minus_seven = -7;
    assert_int_equal(all_ones / 3u, UINT64_C(0x5555555555555555));
    assert_int_equal(all_ones % 10u, 5u);
    assert_true(minus_seven / 2 == -3);
    assert_true(minus_seven % 2 == -1);
    assert_int_equal((uint64_t)0xFFFFFFFFu * 0xFFFFFFFFu * (all_ones & 1u),
                     UINT64_C(0xFFFFFFFE00000001));
}

/* --- setjmp/longjmp and the FP callee-saved registers d8-d15 (AAPCS-VFP;
 * s16-s31 on the M4F's single-precision FPU, the same registers).
 * newlib's setjmp for Armv7E-M does not save d8-d15, and longjmp skips the
 * epilogues that would restore them. */
static jmp_buf jump_target;

static __attribute__((noinline)) double opaque_value(double x)
{
    return sqrt(x) * 3.0;
}

/* Sets s16-s31 (d8-d15) to -1.0f (its own prologue saves them, the epilogue
 * never runs); single-precision moves, which both FPUs have. */
static __attribute__((noinline)) void clobber_fp_registers(void)
{
#if defined(__ARM_PCS_VFP)
    __asm__ volatile("vmov.f32 s16, #-1.0\n\tvmov.f32 s17, #-1.0\n\t"
                     "vmov.f32 s18, #-1.0\n\tvmov.f32 s19, #-1.0\n\t"
                     "vmov.f32 s20, #-1.0\n\tvmov.f32 s21, #-1.0\n\t"
                     "vmov.f32 s22, #-1.0\n\tvmov.f32 s23, #-1.0\n\t"
                     "vmov.f32 s24, #-1.0\n\tvmov.f32 s25, #-1.0\n\t"
                     "vmov.f32 s26, #-1.0\n\tvmov.f32 s27, #-1.0\n\t"
                     "vmov.f32 s28, #-1.0\n\tvmov.f32 s29, #-1.0\n\t"
                     "vmov.f32 s30, #-1.0\n\tvmov.f32 s31, #-1.0\n\t" ::
                         : "d8", "d9", "d10", "d11", "d12", "d13", "d14", "d15");
#endif
}

static __attribute__((noinline)) void clobber_fp_and_jump(void)
{
    clobber_fp_registers();
    longjmp(jump_target, 7);
}

static void test_setjmp_keeps_unmodified_locals(void **state)
{
    (void)state;
    /* kept is never modified after setjmp, so C99 7.13.2.1 guarantees its
     * value after the longjmp (gcc keeps such locals in memory around a
     * returns_twice call, which is what makes this hold on the target). */
    const double kept = opaque_value(v_two);
    const int jumped = setjmp(jump_target);
    if (jumped == 0) {
        clobber_fp_and_jump();
    }
    assert_int_equal(jumped, 7);
    assert_int_equal(bits_of(kept), bits_of(3.0 * sqrt(v_two)));
}

#if defined(__ARM_PCS_VFP) && defined(OGK_CMOCKA_SHIM)
/* The runner's callers must get d8-d15 back when a test that changed them
 * fails (the shim saves them around its setjmp). */
static void nested_clobbers_fp_then_fails(void **state)
{
    (void)state;
    clobber_fp_registers();
    __asm__ volatile("vmov.f32 s16, #-1.0\n\tvmov.f32 s17, #-1.0" ::: "d8"); /* live at the longjmp */
    fail();
}

static void test_runner_restores_fp_registers(void **state)
{
    (void)state;
    const struct CMUnitTest nested[] = {cmocka_unit_test(nested_clobbers_fp_then_fails)};
    register double kept __asm__("d8") = opaque_value(v_two);
    __asm__ volatile("" : "+w"(kept)); /* in d8 at the call */
    print_message("(nested group: one test that must fail)\n");
    const int failures = cmocka_run_group_tests(nested, NULL, NULL);
    __asm__ volatile("" : "+w"(kept)); /* read back from d8 */
    assert_int_equal(failures, 1);
    assert_int_equal(bits_of(kept), bits_of(3.0 * sqrt(v_two)));
}
#endif

/* --- storage: kernel contexts may take hundreds of KiB. */
#define BIG_DOUBLES 65536u /* 512 KiB */
static double big_static[BIG_DOUBLES];

static void test_large_static_storage(void **state)
{
    (void)state;
    double sum = 0.0;
    for (size_t i = 0u; i < BIG_DOUBLES; ++i) {
        sum += big_static[i]; /* .bss zeroed at reset */
    }
    assert_true(sum == 0.0);
    for (size_t i = 0u; i < BIG_DOUBLES; ++i) {
        big_static[i] = (double)i;
    }
    sum = 0.0;
    for (size_t i = 0u; i < BIG_DOUBLES; ++i) {
        sum += big_static[i];
    }
    /* sum of 0..n-1 = n (n-1) / 2, exact in double */
    assert_true(sum == (double)BIG_DOUBLES * (double)(BIG_DOUBLES - 1u) / 2.0);
}

#define FRAME_DOUBLES 32768u /* 256 KiB on the stack */

static __attribute__((noinline)) double sum_of_large_frame(volatile double *sink)
{
    volatile double frame[FRAME_DOUBLES];
    for (size_t i = 0u; i < FRAME_DOUBLES; ++i) {
        frame[i] = 0.5 * (double)i;
    }
    double sum = 0.0;
    for (size_t i = 0u; i < FRAME_DOUBLES; ++i) {
        sum += frame[i];
    }
    *sink = frame[FRAME_DOUBLES - 1u];
    return sum;
}

static void test_large_stack_frame(void **state)
{
    (void)state;
    volatile double last = 0.0;
    const double sum = sum_of_large_frame(&last);
    assert_true(sum == 0.25 * (double)FRAME_DOUBLES * (double)(FRAME_DOUBLES - 1u));
    assert_true(last == 0.5 * (double)(FRAME_DOUBLES - 1u));
#if defined(__arm__)
    assert_true(ogk_armv7m_stack_high_water() >= FRAME_DOUBLES * sizeof(double));
#endif
}

/* --- port counter */
static void test_port_counter(void **state)
{
    (void)state;
    const bool live = ogk_port_counter_init();
    assert_true(live == ogk_port_counter_live());
#if defined(__arm__)
    assert_string_equal(ogk_port_name(), SELFTEST_CORE);
    assert_int_equal(ogk_port_counter_unit(), OGK_PORT_UNIT_CYCLES);
    assert_string_equal(ogk_port_counter_unit_name(), "cycles");
#else
    assert_string_equal(ogk_port_name(), "host");
    assert_int_equal(ogk_port_counter_unit(), OGK_PORT_UNIT_NS);
    assert_string_equal(ogk_port_counter_unit_name(), "ns");
    assert_true(live); /* CLOCK_MONOTONIC exists on every Linux */
#endif
    const uint64_t before = ogk_port_counter_now();
    volatile double work = 0.0;
    for (unsigned i = 0u; i < 200000u; ++i) {
        work += sqrt((double)i);
    }
    const uint64_t after = ogk_port_counter_now();
    if (live) {
        assert_true(after > before);
    } else {
        /* QEMU: the DWT is not modelled and the port says so. */
        assert_int_equal(before, 0u);
        assert_int_equal(after, 0u);
    }
}

#if defined(__arm__)
/* --- the core and its FPU, and the runtime configuration done by startup.c */
static void test_runtime_configuration(void **state)
{
    (void)state;
    const uint32_t cpuid = *(volatile uint32_t *)0xE000ED00u;
    const uint32_t mvfr0 = *(volatile uint32_t *)0xE000EF40u;
    assert_int_equal((cpuid >> 4) & 0xFFFu, SELFTEST_CPUID_PART); /* the board runs this core */
    assert_int_equal((mvfr0 >> 4) & 0xFu, 2u);                    /* single precision in hardware */
    assert_int_equal((mvfr0 >> 8) & 0xFu, SELFTEST_MVFR0_DOUBLE);
    const uint32_t cpacr = *(volatile uint32_t *)0xE000ED88u;
    const uint32_t ccr = *(volatile uint32_t *)0xE000ED14u;
    const uint32_t mpu_ctrl = *(volatile uint32_t *)0xE000ED94u;
    assert_int_equal((cpacr >> 20) & 0xFu, 0xFu); /* CP10, CP11 full access */
    assert_int_equal((ccr >> 4) & 1u, 1u);        /* DIV_0_TRP */
    assert_int_equal(mpu_ctrl & 7u, 1u);          /* MPU on, no background map */
}
#endif

#if defined(OGK_SELFTEST_INJECT_FAILURES)
/* --- each of these must fail; the runner must go on to the next test. */
static void inject_assert_true(void **state) { (void)state; assert_true(v_one > v_two); }
static void inject_assert_false(void **state) { (void)state; assert_false(v_one < v_two); }
static void inject_assert_int_equal(void **state)
{
    (void)state;
    assert_int_equal(-1, 1);
}
static void inject_assert_int_not_equal(void **state)
{
    (void)state;
    assert_int_not_equal(42, 42);
}
static void inject_assert_non_null(void **state) { (void)state; assert_non_null(NULL); }
static void inject_assert_null(void **state) { (void)state; assert_null(&v_one); }
static void inject_print_error_and_fail(void **state)
{
    (void)state;
    print_error("custom message %d %.3f\n", 5, 2.25);
    fail();
}
static void inject_ogk_assert_near(void **state)
{
    (void)state;
    OGK_ASSERT_NEAR(sqrt(v_two), 1.5, 1e-3);
}
static void inject_assert_string_equal(void **state)
{
    (void)state;
    assert_string_equal("alpha", "beta");
}
static void inject_assert_in_range(void **state)
{
    (void)state;
    assert_in_range(11, 1, 10);
}
static void inject_fail_after_work(void **state)
{
    (void)state;
    volatile double acc = 0.0;
    for (int i = 0; i < 10; ++i) {
        acc += v_half;
    }
    assert_true(acc == 4.0);
}
#endif

#if defined(OGK_SELFTEST_INJECT_FAULT)
static volatile int v_zero = 0;
static volatile int v_seven = 7;
static void inject_divide_by_zero(void **state)
{
    (void)state;
    volatile int quotient = v_seven / v_zero; /* DIV_0_TRP: UsageFault -> HardFault */
    (void)quotient;
}
#endif

#if defined(OGK_SELFTEST_INJECT_OVERFLOW)
static __attribute__((noinline)) double overflow_stack(volatile double *sink)
{
    volatile double frame[3u * 131072u]; /* 3 MiB > the 1 MiB main stack */
    frame[0] = *sink;
    return frame[0];
}
static void inject_stack_overflow(void **state)
{
    (void)state;
    volatile double sink = 1.0;
    (void)overflow_stack(&sink);
}
#endif

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_sqrt_is_correctly_rounded),
        cmocka_unit_test(test_libm_matches_constants),
        cmocka_unit_test(test_subnormals_are_not_flushed),
        cmocka_unit_test(test_single_precision_is_ieee),
#if defined(OGK_SELFTEST_INJECT_FAILURES)
        cmocka_unit_test(inject_assert_true),
        cmocka_unit_test(inject_assert_false),
        cmocka_unit_test(inject_assert_int_equal),
        cmocka_unit_test(inject_assert_int_not_equal),
        cmocka_unit_test(inject_assert_non_null),
        cmocka_unit_test(inject_assert_null),
        cmocka_unit_test(inject_print_error_and_fail),
        cmocka_unit_test(inject_ogk_assert_near),
        cmocka_unit_test(inject_assert_string_equal),
        cmocka_unit_test(inject_assert_in_range),
        cmocka_unit_test(inject_fail_after_work),
#endif
#if defined(OGK_SELFTEST_INJECT_FAULT)
        cmocka_unit_test(inject_divide_by_zero),
#endif
#if defined(OGK_SELFTEST_INJECT_OVERFLOW)
        cmocka_unit_test(inject_stack_overflow),
#endif
        cmocka_unit_test(test_printf_of_doubles),
        cmocka_unit_test(test_int64_arithmetic),
        cmocka_unit_test(test_setjmp_keeps_unmodified_locals),
#if defined(__ARM_PCS_VFP) && defined(OGK_CMOCKA_SHIM)
        cmocka_unit_test(test_runner_restores_fp_registers),
#endif
        cmocka_unit_test(test_large_static_storage),
        cmocka_unit_test(test_large_stack_frame),
        cmocka_unit_test(test_port_counter),
#if defined(__arm__)
        cmocka_unit_test(test_runtime_configuration),
#endif
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
