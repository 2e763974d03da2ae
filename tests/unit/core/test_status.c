/* test_status.c -- every status code has its own name; unknown codes are reported. */
#include "ogk_test.h"

#include <string.h>

#include "ogk/real.h"
#include "ogk/status.h"
#include "ogk/version.h"

/* req: OGK-CORE-001 */
static void test_each_code_named_and_distinct(void **state)
{
    unsigned i, j;
    const char *names[OGK_STATUS_COUNT];
    (void)state;
    for (i = 0u; i < (unsigned)OGK_STATUS_COUNT; ++i) {
        OGK_ASSERT_STATUS(ogk_status_name((ogk_status)i, &names[i]), OGK_OK);
        assert_non_null(names[i]);
        assert_true(strncmp(names[i], "OGK_", 4u) == 0);
        for (j = 0u; j < i; ++j) {
            assert_true(strcmp(names[i], names[j]) != 0);
        }
    }
    assert_true(strcmp(names[OGK_OK], "OGK_OK") == 0);
    assert_true(strcmp(names[OGK_E_TABLE_CRC], "OGK_E_TABLE_CRC") == 0);
    assert_true(strcmp(names[OGK_E_SAFE_COMMAND], "OGK_E_SAFE_COMMAND") == 0);
}

/* req: OGK-CORE-001 */
static void test_unknown_code_and_null(void **state)
{
    const char *name = NULL;
    (void)state;
    OGK_ASSERT_STATUS(ogk_status_name(OGK_STATUS_COUNT, &name), OGK_E_RANGE);
    assert_true(strcmp(name, "OGK_E_UNKNOWN") == 0);
    OGK_ASSERT_STATUS(ogk_status_name(OGK_OK, NULL), OGK_E_NULL);
}

/* req: OGK-CORE-002 */
static void test_version(void **state)
{
    const char *text = NULL;
    (void)state;
    OGK_ASSERT_STATUS(ogk_version(&text), OGK_OK);
    assert_true(strcmp(text, OGK_VERSION_STRING) == 0);
    OGK_ASSERT_STATUS(ogk_version(NULL), OGK_E_NULL);
}

/* req: OGK-CORE-028 */
/* The library's real type as compiled (what a binding checks before passing
 * a real): 8 bytes in the default (double) build, 4 with OGK_REAL_SINGLE=1. */
static void test_real_bytes(void **state)
{
    uint32_t bytes = 0u;
    (void)state;
    OGK_ASSERT_STATUS(ogk_real_bytes(&bytes), OGK_OK);
    assert_int_equal(bytes, sizeof(ogk_real_t));
    assert_int_equal(bytes, (OGK_REAL_SINGLE != 0) ? 4u : 8u);
    OGK_ASSERT_STATUS(ogk_real_bytes(NULL), OGK_E_NULL);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_each_code_named_and_distinct),
        cmocka_unit_test(test_unknown_code_and_null),
        cmocka_unit_test(test_version),
        cmocka_unit_test(test_real_bytes),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
