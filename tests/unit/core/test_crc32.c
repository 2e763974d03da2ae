/* test_crc32.c -- CRC-32 against the standard check value and a bitwise reference. */
#include "ogk_test.h"

#include <string.h>

#include "ogk/crc32.h"

/* Independent reference: one bit at a time, straight from the polynomial. */
static uint32_t crc32_bitwise(const uint8_t *data, size_t len)
{
    uint32_t c = 0xFFFFFFFFu;
    size_t i;
    int b;
    for (i = 0u; i < len; ++i) {
        c ^= data[i];
        for (b = 0; b < 8; ++b) {
            c = (c & 1u) ? (c >> 1) ^ 0xEDB88320u : (c >> 1);
        }
    }
    return ~c;
}

/* req: OGK-CORE-016 */
static void test_check_value(void **state)
{
    /* The catalogued check value of CRC-32/ISO-HDLC for "123456789". */
    const char *msg = "123456789";
    uint32_t crc = 0u;
    (void)state;
    OGK_ASSERT_STATUS(ogk_crc32_update(&crc, (const uint8_t *)msg, 9u), OGK_OK);
    assert_int_equal(crc, 0xCBF43926u);
}

/* req: OGK-CORE-016 */
static void test_incremental_matches_bitwise(void **state)
{
    uint8_t buf[1000];
    uint32_t seed = 12345u;
    uint32_t crc = 0u;
    size_t i;
    (void)state;
    for (i = 0u; i < sizeof buf; ++i) {
        seed = seed * 1664525u + 1013904223u;
        buf[i] = (uint8_t)(seed >> 24);
    }
    OGK_ASSERT_STATUS(ogk_crc32_update(&crc, buf, 123u), OGK_OK);
    OGK_ASSERT_STATUS(ogk_crc32_update(&crc, buf + 123, sizeof buf - 123u), OGK_OK);
    assert_int_equal(crc, crc32_bitwise(buf, sizeof buf));
}

/* req: OGK-CORE-016 OGK-CORE-021 */
static void test_empty_and_null(void **state)
{
    uint32_t crc = 0u;
    (void)state;
    OGK_ASSERT_STATUS(ogk_crc32_update(&crc, NULL, 0u), OGK_OK);
    assert_int_equal(crc, 0u);
    OGK_ASSERT_STATUS(ogk_crc32_update(&crc, NULL, 3u), OGK_E_NULL);
    OGK_ASSERT_STATUS(ogk_crc32_update(NULL, (const uint8_t *)"a", 1u), OGK_E_NULL);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_check_value),
        cmocka_unit_test(test_incremental_matches_bitwise),
        cmocka_unit_test(test_empty_and_null),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
