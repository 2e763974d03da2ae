/* cmocka.h -- minimal stand-in for cmocka 1.1.5 on bare-metal targets.
 *
 * cmocka is packaged for Linux only; the Cortex-M7 build puts this directory
 * first on the include path so that the SAME tests/unit/test_*.c sources run
 * on QEMU. Implemented subset (what tests/unit/ogk_test.h allows, plus a few
 * common assertions): cmocka_unit_test[_setup|_teardown|_setup_teardown],
 * cmocka_run_group_tests[_name], assert_true, assert_false, assert_int_equal,
 * assert_int_not_equal, assert_non_null, assert_null, assert_ptr_equal,
 * assert_ptr_not_equal, assert_string_equal, assert_string_not_equal,
 * assert_in_range, print_error, print_message, fail, fail_msg.
 *
 * Behaviour copied from cmocka 1.1.5 (checked by diffing outputs on the host,
 * see docs/guides/ports.md): the same lines on the same streams ("[ RUN      ]",
 * "[       OK ]", "[  FAILED  ]", "[==========] N test(s) run." on stdout;
 * "[  ERROR   ] --- ...", "[  PASSED  ] N test(s).", the failure list on
 * stderr), values of integer assertions printed as %#llx, and the group's
 * return value is the number of failed tests. A failing assertion leaves
 * the test with longjmp, as cmocka does. Not implemented: mocks, expected
 * calls, test_malloc leak checks, skip(), signal catching (a crash on the
 * target is a HardFault, which the runtime reports as a QEMU exit code). */
#ifndef OGK_CMOCKA_SHIM_H
#define OGK_CMOCKA_SHIM_H

#include <stddef.h>
#include <stdint.h>

#define OGK_CMOCKA_SHIM 1

/* cmocka's LargestIntegralType; 64-bit like cmocka on LP64 hosts, so values
 * print identically on both. */
typedef unsigned long long LargestIntegralType;
#define cast_to_largest_integral_type(value) ((LargestIntegralType)(value))
#define cast_ptr_to_largest_integral_type(value) \
    ((LargestIntegralType)(uintptr_t)(value))

typedef void (*CMUnitTestFunction)(void **state);
typedef int (*CMFixtureFunction)(void **state);

struct CMUnitTest {
    const char *name;
    CMUnitTestFunction test_func;
    CMFixtureFunction setup_func;
    CMFixtureFunction teardown_func;
    void *initial_state;
};

#define cmocka_unit_test(f) { #f, f, NULL, NULL, NULL }
#define cmocka_unit_test_setup(f, setup) { #f, f, setup, NULL, NULL }
#define cmocka_unit_test_teardown(f, teardown) { #f, f, NULL, teardown, NULL }
#define cmocka_unit_test_setup_teardown(f, setup, teardown) \
    { #f, f, setup, teardown, NULL }
#define cmocka_unit_test_prestate(f, state) { #f, f, NULL, NULL, state }

#define cmocka_run_group_tests(group_tests, group_setup, group_teardown)        \
    _cmocka_run_group_tests(#group_tests, group_tests,                         \
                            sizeof(group_tests) / sizeof((group_tests)[0]),    \
                            group_setup, group_teardown)
#define cmocka_run_group_tests_name(group_name, group_tests, group_setup,      \
                                    group_teardown)                            \
    _cmocka_run_group_tests(group_name, group_tests,                           \
                            sizeof(group_tests) / sizeof((group_tests)[0]),    \
                            group_setup, group_teardown)

int _cmocka_run_group_tests(const char *group_name,
                            const struct CMUnitTest *tests, size_t number_of_tests,
                            CMFixtureFunction group_setup,
                            CMFixtureFunction group_teardown);

/* ------------------------------------------------------------ assertions */
#define assert_true(c) \
    _assert_true(cast_to_largest_integral_type(c), #c, __FILE__, __LINE__)
#define assert_false(c) \
    _assert_true(!(cast_to_largest_integral_type(c)), #c, __FILE__, __LINE__)
#define assert_non_null(c) \
    _assert_true(cast_ptr_to_largest_integral_type(c), #c, __FILE__, __LINE__)
#define assert_null(c) \
    _assert_true(!(cast_ptr_to_largest_integral_type(c)), #c, __FILE__, __LINE__)
#define assert_int_equal(a, b)                                                  \
    _assert_int_equal(cast_to_largest_integral_type(a),                        \
                      cast_to_largest_integral_type(b), __FILE__, __LINE__)
#define assert_int_not_equal(a, b)                                              \
    _assert_int_not_equal(cast_to_largest_integral_type(a),                    \
                          cast_to_largest_integral_type(b), __FILE__, __LINE__)
#define assert_ptr_equal(a, b)                                                  \
    _assert_int_equal(cast_ptr_to_largest_integral_type(a),                    \
                      cast_ptr_to_largest_integral_type(b), __FILE__, __LINE__)
#define assert_ptr_not_equal(a, b)                                              \
    _assert_int_not_equal(cast_ptr_to_largest_integral_type(a),                \
                          cast_ptr_to_largest_integral_type(b), __FILE__, __LINE__)
#define assert_string_equal(a, b) \
    _assert_string_equal((const char *)(a), (const char *)(b), __FILE__, __LINE__)
#define assert_string_not_equal(a, b) \
    _assert_string_not_equal((const char *)(a), (const char *)(b), __FILE__, __LINE__)
#define assert_in_range(value, minimum, maximum)                                \
    _assert_in_range(cast_to_largest_integral_type(value),                     \
                     cast_to_largest_integral_type(minimum),                   \
                     cast_to_largest_integral_type(maximum), __FILE__, __LINE__)

#define fail() _fail(__FILE__, __LINE__)
#define fail_msg(msg, ...)                                                      \
    do {                                                                       \
        print_error("ERROR: " msg "\n", ##__VA_ARGS__);                        \
        fail();                                                                \
    } while (0)

void _assert_true(LargestIntegralType result, const char *expression,
                  const char *file, int line);
void _assert_int_equal(LargestIntegralType a, LargestIntegralType b,
                       const char *file, int line);
void _assert_int_not_equal(LargestIntegralType a, LargestIntegralType b,
                           const char *file, int line);
void _assert_string_equal(const char *a, const char *b, const char *file, int line);
void _assert_string_not_equal(const char *a, const char *b, const char *file, int line);
void _assert_in_range(LargestIntegralType value, LargestIntegralType minimum,
                      LargestIntegralType maximum, const char *file, int line);
void _fail(const char *file, int line) __attribute__((noreturn));

/* Free-form output: print_message to stdout, print_error to stderr. */
void print_message(const char *format, ...) __attribute__((format(printf, 1, 2)));
void print_error(const char *format, ...) __attribute__((format(printf, 1, 2)));

#endif /* OGK_CMOCKA_SHIM_H */
