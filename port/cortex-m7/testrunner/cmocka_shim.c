/* cmocka_shim.c -- the runner behind testrunner/cmocka.h (see there).
 *
 * Portable C99 + stdio: it builds for the bare-metal Cortex-M7 and for the
 * host, where `make test-arm-selftest` diffs its output against real cmocka. */
#include "cmocka.h"

#include <setjmp.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* Error text of the running test, printed after "[  ERROR   ] --- " when it
 * fails (cmocka's cm_error_message; fixed size here: no heap needed). */
#define CM_SHIM_MESSAGE_SIZE 2048u

static char cm_shim_message[CM_SHIM_MESSAGE_SIZE];
static size_t cm_shim_message_len;
static jmp_buf cm_shim_test_exit;
static int cm_shim_in_test;

static void cm_shim_vappend(const char *format, va_list args)
{
    if (cm_shim_message_len >= CM_SHIM_MESSAGE_SIZE - 1u) {
        return;
    }
    const size_t room = CM_SHIM_MESSAGE_SIZE - cm_shim_message_len;
    const int written = vsnprintf(cm_shim_message + cm_shim_message_len, room, format, args);
    if (written > 0) {
        const size_t w = (size_t)written;
        cm_shim_message_len += (w < room) ? w : room - 1u;
    }
}

static void cm_shim_append(const char *format, ...) __attribute__((format(printf, 1, 2)));
static void cm_shim_append(const char *format, ...)
{
    va_list args;
    va_start(args, format);
    cm_shim_vappend(format, args);
    va_end(args);
}

/* stdout and stderr reach the host as separate streams (QEMU semihosting
 * writes each immediately); flushing stdout first keeps the merged 2>&1
 * order the same as cmocka's on a terminal. */
void print_message(const char *format, ...)
{
    va_list args;
    va_start(args, format);
    (void)vfprintf(stdout, format, args);
    va_end(args);
    (void)fflush(stdout);
}

void print_error(const char *format, ...)
{
    va_list args;
    (void)fflush(stdout);
    va_start(args, format);
    (void)vfprintf(stderr, format, args);
    va_end(args);
    (void)fflush(stderr);
}

void _fail(const char *file, int line)
{
    cm_shim_append("[   LINE   ] --- %s:%u: error: Failure!", file, (unsigned)line);
    if (cm_shim_in_test) {
        longjmp(cm_shim_test_exit, 1);
    }
    /* An assertion outside a test (e.g. in a group fixture): nothing to
     * return to, so report and stop as a failure. */
    print_error("[  ERROR   ] --- %s\n", cm_shim_message);
    (void)fflush(stdout);
    exit(1);
}

void _assert_true(LargestIntegralType result, const char *expression,
                  const char *file, int line)
{
    if (!result) {
        cm_shim_append("%s\n", expression);
        _fail(file, line);
    }
}

void _assert_int_equal(LargestIntegralType a, LargestIntegralType b,
                       const char *file, int line)
{
    if (a != b) {
        cm_shim_append("%#llx != %#llx\n", a, b);
        _fail(file, line);
    }
}

void _assert_int_not_equal(LargestIntegralType a, LargestIntegralType b,
                           const char *file, int line)
{
    if (a == b) {
        cm_shim_append("%#llx == %#llx\n", a, b);
        _fail(file, line);
    }
}

void _assert_string_equal(const char *a, const char *b, const char *file, int line)
{
    if (a == NULL || b == NULL || strcmp(a, b) != 0) {
        cm_shim_append("\"%s\" != \"%s\"\n", a != NULL ? a : "(null)",
                       b != NULL ? b : "(null)");
        _fail(file, line);
    }
}

void _assert_string_not_equal(const char *a, const char *b, const char *file, int line)
{
    if (a != NULL && b != NULL && strcmp(a, b) == 0) {
        cm_shim_append("\"%s\" == \"%s\"\n", a, b);
        _fail(file, line);
    }
}

void _assert_in_range(LargestIntegralType value, LargestIntegralType minimum,
                      LargestIntegralType maximum, const char *file, int line)
{
    if (value < minimum || value > maximum) {
        cm_shim_append("%llu is not within the range %llu-%llu\n", value, minimum,
                       maximum);
        _fail(file, line);
    }
}

/* newlib's setjmp for Armv7E-M saves r4-r11, sp and lr but not the VFP
 * callee-saved registers d8-d15, and a longjmp out of a failing test skips
 * the epilogues that would restore them. Declaring them clobbered here makes
 * this function save them in its prologue and restore them in its epilogue,
 * which runs on both returns from setjmp: the runner's callers get their
 * d8-d15 back even when a test that used them fails. */
#if defined(__ARM_PCS_VFP)
#define CM_SHIM_FP_CLOBBER() \
    __asm__ volatile("" ::: "d8", "d9", "d10", "d11", "d12", "d13", "d14", "d15", "memory")
#else
#define CM_SHIM_FP_CLOBBER() ((void)0)
#endif

/* Runs one fixture or test body; returns 0 when it completed, 1 when an
 * assertion left it through longjmp. */
static int cm_shim_run_fixture(CMFixtureFunction fixture, void **state, int *fixture_rc)
{
    CM_SHIM_FP_CLOBBER();
    cm_shim_in_test = 1;
    if (setjmp(cm_shim_test_exit) != 0) {
        cm_shim_in_test = 0;
        return 1;
    }
    *fixture_rc = fixture(state);
    cm_shim_in_test = 0;
    return 0;
}

static int cm_shim_run_test(CMUnitTestFunction test, void **state)
{
    CM_SHIM_FP_CLOBBER();
    cm_shim_in_test = 1;
    if (setjmp(cm_shim_test_exit) != 0) {
        cm_shim_in_test = 0;
        return 1;
    }
    test(state);
    cm_shim_in_test = 0;
    return 0;
}

/* One test with its own fixtures; 0 = passed. */
static int cm_shim_run_one(const struct CMUnitTest *test, void *group_state)
{
    void *state = (test->initial_state != NULL) ? test->initial_state : group_state;
    int rc = 0;
    cm_shim_message_len = 0u;
    cm_shim_message[0] = '\0';

    if (test->setup_func != NULL) {
        if (cm_shim_run_fixture(test->setup_func, &state, &rc) != 0 || rc != 0) {
            if (rc != 0) {
                cm_shim_append("Test setup failed");
            }
            print_error("[  ERROR   ] --- %s\n", cm_shim_message);
            return 1;
        }
    }
    int failed = cm_shim_run_test(test->test_func, &state);
    if (test->teardown_func != NULL) {
        rc = 0;
        if (cm_shim_run_fixture(test->teardown_func, &state, &rc) != 0 || rc != 0) {
            if (rc != 0) {
                cm_shim_append("Test teardown failed");
            }
            failed = 1;
        }
    }
    if (failed) {
        print_error("[  ERROR   ] --- %s\n", cm_shim_message);
    }
    return failed;
}

int _cmocka_run_group_tests(const char *group_name,
                            const struct CMUnitTest *tests, size_t number_of_tests,
                            CMFixtureFunction group_setup,
                            CMFixtureFunction group_teardown)
{
    /* Failed-test names are kept by index: a fixed bound, no heap. */
    enum { CM_SHIM_MAX_LISTED = 256 };
    size_t failed_index[CM_SHIM_MAX_LISTED];
    size_t failed = 0u;
    size_t passed = 0u;
    void *group_state = NULL;
    int rc = 0;
    (void)group_name;

    /* A group may run inside a test (the selftest does): keep the
     * enclosing test's exit point and message. */
    jmp_buf outer_exit;
    char outer_message[CM_SHIM_MESSAGE_SIZE];
    const int outer_in_test = cm_shim_in_test;
    const size_t outer_message_len = cm_shim_message_len;
    memcpy(outer_exit, cm_shim_test_exit, sizeof outer_exit);
    memcpy(outer_message, cm_shim_message, sizeof outer_message);
    cm_shim_in_test = 0;

    print_message("[==========] Running %u test(s).\n", (unsigned)number_of_tests);

    if (group_setup != NULL) {
        cm_shim_message_len = 0u;
        cm_shim_message[0] = '\0';
        if (cm_shim_run_fixture(group_setup, &group_state, &rc) != 0 || rc != 0) {
            print_error("[  ERROR   ] --- %s\n",
                        cm_shim_message_len > 0u ? cm_shim_message : "Group setup failed");
            print_error("[  FAILED  ] GROUP SETUP\n");
            failed = number_of_tests;
            goto restore_outer;
        }
    }

    for (size_t i = 0u; i < number_of_tests; ++i) {
        print_message("[ RUN      ] %s\n", tests[i].name);
        if (cm_shim_run_one(&tests[i], group_state) == 0) {
            print_message("[       OK ] %s\n", tests[i].name);
            ++passed;
        } else {
            print_message("[  FAILED  ] %s\n", tests[i].name);
            if (failed < (size_t)CM_SHIM_MAX_LISTED) {
                failed_index[failed] = i;
            }
            ++failed;
        }
    }

    if (group_teardown != NULL) {
        cm_shim_message_len = 0u;
        cm_shim_message[0] = '\0';
        if (cm_shim_run_fixture(group_teardown, &group_state, &rc) != 0 || rc != 0) {
            print_error("[  ERROR   ] --- %s\n",
                        cm_shim_message_len > 0u ? cm_shim_message : "Group teardown failed");
            print_error("[  FAILED  ] GROUP TEARDOWN\n");
            ++failed;
        }
    }

    print_message("[==========] %u test(s) run.\n", (unsigned)number_of_tests);
    print_error("[  PASSED  ] %u test(s).\n", (unsigned)passed);
    if (failed > 0u) {
        print_error("[  FAILED  ] %u test(s), listed below:\n", (unsigned)failed);
        const size_t listed = failed < (size_t)CM_SHIM_MAX_LISTED ? failed : CM_SHIM_MAX_LISTED;
        for (size_t k = 0u; k < listed; ++k) {
            const size_t i = failed_index[k];
            if (i < number_of_tests) {
                print_error("[  FAILED  ] %s\n", tests[i].name);
            }
        }
        print_error("\n %u FAILED TEST(S)\n", (unsigned)failed);
    }

restore_outer:
    memcpy(cm_shim_test_exit, outer_exit, sizeof outer_exit);
    memcpy(cm_shim_message, outer_message, sizeof outer_message);
    cm_shim_message_len = outer_message_len;
    cm_shim_in_test = outer_in_test;
    return (int)failed;
}
