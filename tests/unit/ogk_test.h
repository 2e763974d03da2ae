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
#include <math.h>
#include <cmocka.h>

/* |actual - expected| <= tol, with both values printed on failure. */
#define OGK_ASSERT_NEAR(actual, expected, tol)                                  \
    do {                                                                       \
        const double ogk_a_ = (actual), ogk_e_ = (expected), ogk_t_ = (tol);   \
        if (!(fabs(ogk_a_ - ogk_e_) <= ogk_t_)) {                              \
            print_error("%s = %.17g, expected %.17g +- %.3g (%s:%d)\n",        \
                        #actual, ogk_a_, ogk_e_, ogk_t_, __FILE__, __LINE__);  \
            fail();                                                            \
        }                                                                      \
    } while (0)

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
static inline double ogk_test_max_abs(const double *v, size_t count)
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
