/* ogk_test.h -- common includes and assertions of the kernel unit tests.
 *
 * On the host this pulls in cmocka; on the bare-metal Cortex-M7 build the
 * include path puts port/cortex-m7/testrunner/cmocka.h first, a small runner
 * with the same API subset and the same summary lines. Tests use only:
 * cmocka_unit_test, cmocka_run_group_tests, assert_true, assert_false,
 * assert_int_equal, assert_int_not_equal, assert_non_null, assert_null,
 * print_error, print_message, fail, plus the OGK_ASSERT_* macros below. */
#ifndef OGK_TEST_H
#define OGK_TEST_H

#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <float.h>
#include <math.h>
#include <cmocka.h>

#include "ogk/real.h"

/* ------------------------------------------------------------ the precision under test
 * The tests compile with the kernel's configuration (-DOGK_REAL_SINGLE=1 for the float build: make
 * test-unit-host-single, test-unit-m4f), so ogk_real_t is the kernel's real type. Arrays and structs
 * handed to the kernel are ogk_real_t; an independent reference may stay double.
 *
 * OGK_TEST_TOL(tol_double, tol_single): the one way a test states a tolerance (or any bound of a
 * computed value) that depends on the precision: the first in the double build (the tolerance the test
 * has always had, the same expression), the second in the float build. Every single-precision value
 * carries its reason where it is not obvious: float's epsilon times the problem's scale or condition,
 * or "measured worst X on M4F and host" (the tolerance then ten times the worst first measured on the
 * host, rounded up to 1, 2 or 5 times a power of ten; docs/design/precision-unit-tests.md gives the table).
 * OGK_TEST_EPS is the build's unit round-off in the same form (DBL_EPSILON or FLT_EPSILON), for bounds
 * written as c * eps * scale. A fact of one precision only (a value beyond float's range, a 1e-300
 * pivot) is under #if !OGK_REAL_SINGLE with a comment saying why, or has its float equivalent. */
#if OGK_REAL_SINGLE
#define OGK_TEST_TOL(tol_double, tol_single) (tol_single)
#else
#define OGK_TEST_TOL(tol_double, tol_single) (tol_double)
#endif
#define OGK_TEST_EPS OGK_TEST_TOL(DBL_EPSILON, (double)FLT_EPSILON)

/* OGK_TEST_PICK(value_double, value_single): an input whose magnitude is tied to the type's range
 * (near its overflow, below its pivot floor, ...): the value the test has always used in the double
 * build, the float build's counterpart on the same side of the same limit. Not a tolerance. */
#define OGK_TEST_PICK(value_double, value_single) OGK_TEST_TOL(value_double, value_single)

/* The neighbour of x towards y in the build's real type (one ulp of ogk_real_t: nextafter's double
 * neighbour would round back to x in the float build). */
#if OGK_REAL_SINGLE
#define OGK_TEST_NEXTAFTER(x, y) ((double)nextafterf((float)(x), (float)(y)))
#else
#define OGK_TEST_NEXTAFTER(x, y) nextafter((x), (y))
#endif

/* With -DOGK_TEST_MEASURE (never in the gates: make unit-errors, tests/unit/unit_errors.py), every
 * OGK_ASSERT_NEAR / _LE / _LT site prints "OGK_ERR file:line value bound ratio expression" each time its
 * worst ratio value / bound so far grows (a zero bound: ratio 0 for a zero value, inf otherwise): the
 * measured errors of docs/design/precision-unit-tests.md. Otherwise nothing. */
#ifdef OGK_TEST_MEASURE
#define OGK_TEST_RECORD(value, bound, text)                                     \
    do {                                                                       \
        static double ogk_worst_ = -HUGE_VAL;                                  \
        const double ogk_rv_ = (value), ogk_rb_ = (bound);                     \
        const double ogk_rr_ = (ogk_rb_ > 0.0) ? (ogk_rv_ / ogk_rb_)           \
                               : ((ogk_rv_ > 0.0) ? HUGE_VAL : 0.0);           \
        if (ogk_rr_ > ogk_worst_ || ogk_rr_ != ogk_rr_) {                      \
            ogk_worst_ = ogk_rr_;                                              \
            print_message("OGK_ERR %s:%d %.3e %.3e %.3e %s\n", __FILE__,       \
                          __LINE__, ogk_rv_, ogk_rb_, ogk_rr_, text);          \
        }                                                                      \
    } while (0)
#else
#define OGK_TEST_RECORD(value, bound, text) ((void)0)
#endif

/* |actual - expected| <= tol, with both values printed on failure. */
#define OGK_ASSERT_NEAR(actual, expected, tol)                                  \
    do {                                                                       \
        const double ogk_a_ = (actual), ogk_e_ = (expected), ogk_t_ = (tol);   \
        OGK_TEST_RECORD(fabs(ogk_a_ - ogk_e_), ogk_t_, #actual);               \
        if (!(fabs(ogk_a_ - ogk_e_) <= ogk_t_)) {                              \
            print_error("%s = %.17g, expected %.17g +- %.3g (%s:%d)\n",        \
                        #actual, ogk_a_, ogk_e_, ogk_t_, __FILE__, __LINE__);  \
            fail();                                                            \
        }                                                                      \
    } while (0)

/* value <= bound (OGK_ASSERT_LE) and value < bound (OGK_ASSERT_LT): an error measure against its
 * tolerance, both printed on failure (assert_true(value <= bound) with the numbers). */
#define OGK_ASSERT_CMP_(value, bound, op)                                       \
    do {                                                                       \
        const double ogk_v_ = (value), ogk_b_ = (bound);                       \
        OGK_TEST_RECORD(ogk_v_, ogk_b_, #value);                               \
        if (!(ogk_v_ op ogk_b_)) {                                             \
            print_error("%s = %.17g, expected %s %.17g (%s:%d)\n", #value,     \
                        ogk_v_, #op, ogk_b_, __FILE__, __LINE__);              \
            fail();                                                            \
        }                                                                      \
    } while (0)
#define OGK_ASSERT_LE(value, bound) OGK_ASSERT_CMP_(value, bound, <=)
#define OGK_ASSERT_LT(value, bound) OGK_ASSERT_CMP_(value, bound, <)

/* |actual - expected| <= rel * max(|expected|, floor). */
#define OGK_ASSERT_REL(actual, expected, rel, floor)                            \
    OGK_ASSERT_NEAR((actual), (expected),                                      \
                    (rel) * fmax(fabs((double)(expected)), (floor)))

#define OGK_ASSERT_STATUS(expr, code) assert_int_equal((int)(expr), (int)(code))

/* 1 on a big-endian target (SPARC V8, PowerPC), as the compiler states it (gcc
 * and clang predefine __BYTE_ORDER__): the reference for the kernel's own
 * run-time check, ogk_table_check_in_place. */
#if defined(__BYTE_ORDER__) && defined(__ORDER_BIG_ENDIAN__) && \
    (__BYTE_ORDER__ == __ORDER_BIG_ENDIAN__)
#define OGK_TEST_BIG_ENDIAN 1
#else
#define OGK_TEST_BIG_ENDIAN 0
#endif
/* What ogk_nog_table_view answers for a valid, aligned image on this target. */
#define OGK_TEST_VIEW_OK (OGK_TEST_BIG_ENDIAN ? OGK_E_BYTE_ORDER : OGK_OK)

/* max_i |v[i]| over count entries (0 for none). */
static inline double ogk_test_max_abs(const ogk_real_t *v, size_t count)
{
    double m = 0.0;
    size_t i;
    for (i = 0; i < count; ++i) {
        if (fabs(v[i]) > m) {
            m = fabs(v[i]);
        }
    }
    return m;
}

#endif /* OGK_TEST_H */
