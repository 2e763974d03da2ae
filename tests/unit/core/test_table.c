/* test_table.c -- the table loader accepts a well-formed table and rejects
 * each kind of damage with its own status. The writer here is the test's
 * own, written from the layout documented in ogk/table.h, in the build's
 * element type (table_writer.h: F64 for the double kernel, F32 for the float
 * one; the values below are exact in both). */
#include "ogk_test.h"

#include <string.h>

#include "ogk/table.h"
#include "table_writer.h"

#define KIND_TEST 0x54455354u /* "TEST" */
#define GRID 5u
#define ROWS 2u
#define COLS 3u
#define N_VALUES (GRID * (1u + ROWS * COLS))
#define TABLE_BYTES (OGK_TABLE_HEADER_SIZE + TW_REAL_BYTES * N_VALUES)

static double entry_value(unsigned k, unsigned idx)
{
    return 100.0 * (double)k + (double)idx + 0.25;
}

/* Recomputes both CRCs after a deliberate edit of the header. */
static void seal(uint8_t *buf)
{
    tw_seal(buf, N_VALUES);
}

static void build(uint8_t *buf)
{
    const uint32_t dims[2] = {ROWS, COLS};
    unsigned k, i;
    memset(buf, 0, TABLE_BYTES);
    tw_header(buf, KIND_TEST, 2u, dims, GRID);
    for (k = 0u; k < GRID; ++k) {
        tw_put_real(buf + OGK_TABLE_HEADER_SIZE + TW_REAL_BYTES * k, 0.25 * (double)k);
        for (i = 0u; i < ROWS * COLS; ++i) {
            tw_put_real(buf + OGK_TABLE_HEADER_SIZE + TW_REAL_BYTES * (GRID + k * ROWS * COLS + i),
                    entry_value(k, i));
        }
    }
    seal(buf);
}

static ogk_table_spec_t spec(void)
{
    ogk_table_spec_t s;
    memset(&s, 0, sizeof s);
    s.kind = KIND_TEST;
    s.ndims = 2u;
    s.dims[0] = ROWS;
    s.dims[1] = COLS;
    s.min_grid = 2u;
    s.max_grid = 100u;
    return s;
}

static uint8_t table_buf[TABLE_BYTES + 8u];

/* req: OGK-CORE-017 */
static void test_valid_table_reads_back(void **state)
{
    ogk_table_spec_t s = spec();
    ogk_table_view_t v;
    ogk_real_t grid[GRID];
    ogk_real_t data[GRID * ROWS * COLS];
    ogk_real_t one;
    unsigned k, i;
    (void)state;
    build(table_buf);
    OGK_ASSERT_STATUS(ogk_table_open(table_buf, TABLE_BYTES, &s, &v), OGK_OK);
    assert_int_equal(v.grid_size, GRID);
    assert_int_equal(v.entry_len, ROWS * COLS);
    OGK_ASSERT_STATUS(ogk_table_read_grid(&v, grid, GRID), OGK_OK);
    OGK_ASSERT_STATUS(ogk_table_read_data(&v, data, GRID * ROWS * COLS), OGK_OK);
    for (k = 0u; k < GRID; ++k) {
        OGK_ASSERT_NEAR(grid[k], 0.25 * (double)k, 0.0);
        for (i = 0u; i < ROWS * COLS; ++i) {
            OGK_ASSERT_NEAR(data[k * ROWS * COLS + i], entry_value(k, i), 0.0);
        }
    }
    OGK_ASSERT_STATUS(ogk_table_get(&v, 3u, 4u, &one), OGK_OK);
    OGK_ASSERT_NEAR(one, entry_value(3u, 4u), 0.0);
    OGK_ASSERT_STATUS(ogk_table_get(&v, GRID, 0u, &one), OGK_E_RANGE);
    OGK_ASSERT_STATUS(ogk_table_get(&v, 0u, ROWS * COLS, &one), OGK_E_RANGE);
    OGK_ASSERT_STATUS(ogk_table_read_grid(&v, grid, GRID - 1u), OGK_E_DIM);
    /* A zero dims entry in the spec accepts any size there. */
    s.dims[1] = 0u;
    OGK_ASSERT_STATUS(ogk_table_open(table_buf, TABLE_BYTES, &s, &v), OGK_OK);
}

/* The smallest entry, one scalar per node (ndims 1, dims {1}: entry_len 1):
 * grid t_k = k and values y_k = 2 k + 0.5 read back exactly. */
/* req: OGK-CORE-017 */
static void test_scalar_entries(void **state)
{
    const uint32_t dims[1] = {1u};
    static uint8_t scalar_buf[OGK_TABLE_HEADER_SIZE + TW_REAL_BYTES * 2u * GRID];
    ogk_table_spec_t s = spec();
    ogk_table_view_t v;
    ogk_real_t value;
    unsigned k;
    (void)state;
    memset(scalar_buf, 0, sizeof scalar_buf);
    tw_header(scalar_buf, KIND_TEST, 1u, dims, GRID);
    for (k = 0u; k < GRID; ++k) {
        tw_put_real(scalar_buf + OGK_TABLE_HEADER_SIZE + TW_REAL_BYTES * k, (double)k);
        tw_put_real(scalar_buf + OGK_TABLE_HEADER_SIZE + TW_REAL_BYTES * (GRID + k), 2.0 * (double)k + 0.5);
    }
    tw_seal(scalar_buf, 2u * GRID);
    s.ndims = 1u;
    s.dims[0] = 1u;
    s.dims[1] = 0u;
    OGK_ASSERT_STATUS(ogk_table_open(scalar_buf, sizeof scalar_buf, &s, &v), OGK_OK);
    assert_int_equal(v.entry_len, 1u);
    assert_int_equal(v.grid_size, GRID);
    for (k = 0u; k < GRID; ++k) {
        OGK_ASSERT_STATUS(ogk_table_get(&v, k, 0u, &value), OGK_OK);
        OGK_ASSERT_NEAR(value, 2.0 * (double)k + 0.5, 0.0);
    }
    OGK_ASSERT_STATUS(ogk_table_get(&v, 0u, 1u, &value), OGK_E_RANGE);
}

/* req: OGK-CORE-017 */
static void test_corrupted_payload_byte(void **state)
{
    ogk_table_spec_t s = spec();
    ogk_table_view_t v;
    (void)state;
    build(table_buf);
    table_buf[OGK_TABLE_HEADER_SIZE + 77u] ^= 0x10u;
    OGK_ASSERT_STATUS(ogk_table_open(table_buf, TABLE_BYTES, &s, &v), OGK_E_TABLE_CRC);
    assert_null(v.buf); /* view cleared: nothing can be read from it */
}

/* req: OGK-CORE-017 */
static void test_corrupted_header_byte(void **state)
{
    ogk_table_spec_t s = spec();
    ogk_table_view_t v;
    (void)state;
    build(table_buf);
    table_buf[33] ^= 0x01u; /* grid size, header CRC not updated */
    OGK_ASSERT_STATUS(ogk_table_open(table_buf, TABLE_BYTES, &s, &v), OGK_E_TABLE_CRC);
}

/* req: OGK-CORE-017 */
static void test_wrong_dimension(void **state)
{
    ogk_table_spec_t s = spec();
    ogk_table_view_t v;
    (void)state;
    build(table_buf);
    s.dims[0] = ROWS + 1u;
    OGK_ASSERT_STATUS(ogk_table_open(table_buf, TABLE_BYTES, &s, &v), OGK_E_TABLE_DIM);
    s = spec();
    s.ndims = 3u;
    OGK_ASSERT_STATUS(ogk_table_open(table_buf, TABLE_BYTES, &s, &v), OGK_E_TABLE_DIM);
    s = spec();
    s.max_grid = GRID - 1u;
    OGK_ASSERT_STATUS(ogk_table_open(table_buf, TABLE_BYTES, &s, &v), OGK_E_TABLE_DIM);
}

/* req: OGK-CORE-017 */
static void test_truncated_and_oversized(void **state)
{
    ogk_table_spec_t s = spec();
    ogk_table_view_t v;
    (void)state;
    build(table_buf);
    OGK_ASSERT_STATUS(ogk_table_open(table_buf, TABLE_BYTES - 1u, &s, &v), OGK_E_TABLE_TRUNCATED);
    OGK_ASSERT_STATUS(ogk_table_open(table_buf, 20u, &s, &v), OGK_E_TABLE_TRUNCATED);
    OGK_ASSERT_STATUS(ogk_table_open(table_buf, TABLE_BYTES + TW_REAL_BYTES, &s, &v), OGK_E_TABLE_SIZE);
}

/* req: OGK-CORE-017 */
static void test_magic_version_type_kind(void **state)
{
    ogk_table_spec_t s = spec();
    ogk_table_view_t v;
    (void)state;
    build(table_buf);
    table_buf[0] = 'X';
    OGK_ASSERT_STATUS(ogk_table_open(table_buf, TABLE_BYTES, &s, &v), OGK_E_TABLE_MAGIC);
    build(table_buf);
    tw_put_u16(table_buf + 4, 2u);
    seal(table_buf);
    OGK_ASSERT_STATUS(ogk_table_open(table_buf, TABLE_BYTES, &s, &v), OGK_E_TABLE_VERSION);
    build(table_buf);
    tw_put_u16(table_buf + 6, (uint16_t)TW_OTHER_TYPE); /* the other precision's element */
    seal(table_buf);
    OGK_ASSERT_STATUS(ogk_table_open(table_buf, TABLE_BYTES, &s, &v), OGK_E_TABLE_TYPE);
    build(table_buf);
    s.kind = KIND_TEST + 1u;
    OGK_ASSERT_STATUS(ogk_table_open(table_buf, TABLE_BYTES, &s, &v), OGK_E_TABLE_TYPE);
}

/* req: OGK-CORE-017 */
static void test_inconsistent_payload_size_and_nan(void **state)
{
    ogk_table_spec_t s = spec();
    ogk_table_view_t v;
    (void)state;
    build(table_buf);
    tw_put_u32(table_buf + 36, TW_REAL_BYTES * N_VALUES - TW_REAL_BYTES);
    seal(table_buf);
    OGK_ASSERT_STATUS(ogk_table_open(table_buf, TABLE_BYTES, &s, &v), OGK_E_TABLE_SIZE);
    build(table_buf);
    tw_put_real(table_buf + OGK_TABLE_HEADER_SIZE + TW_REAL_BYTES * 9u, NAN);
    seal(table_buf);
    OGK_ASSERT_STATUS(ogk_table_open(table_buf, TABLE_BYTES, &s, &v), OGK_E_NONFINITE);
}

/* The finiteness scan covers the whole payload, both ends included: the
 * first value (grid[0]) and the last (the last entry's last element). */
/* req: OGK-CORE-017 */
static void test_nonfinite_first_and_last_value(void **state)
{
    ogk_table_spec_t s = spec();
    ogk_table_view_t v;
    (void)state;
    build(table_buf);
    tw_put_real(table_buf + OGK_TABLE_HEADER_SIZE, NAN);
    seal(table_buf);
    OGK_ASSERT_STATUS(ogk_table_open(table_buf, TABLE_BYTES, &s, &v), OGK_E_NONFINITE);
    assert_null(v.buf);
    build(table_buf);
    tw_put_real(table_buf + OGK_TABLE_HEADER_SIZE, -INFINITY);
    seal(table_buf);
    OGK_ASSERT_STATUS(ogk_table_open(table_buf, TABLE_BYTES, &s, &v), OGK_E_NONFINITE);
    build(table_buf);
    tw_put_real(table_buf + OGK_TABLE_HEADER_SIZE + TW_REAL_BYTES * (N_VALUES - 1u), INFINITY);
    seal(table_buf);
    OGK_ASSERT_STATUS(ogk_table_open(table_buf, TABLE_BYTES, &s, &v), OGK_E_NONFINITE);
    build(table_buf); /* and the undamaged table opens */
    OGK_ASSERT_STATUS(ogk_table_open(table_buf, TABLE_BYTES, &s, &v), OGK_OK);
}

/* The largest payload the format admits is OGK_TABLE_MAX_VALUES / 8 =
 * 2^25 - 1 values = 31 x (601 x 1801): entries of 30 values on a grid of
 * 1 082 401. A header claiming it passes the size checks and is then found
 * truncated (only the header is there); one value more, 2^25 = 32 x 2^20
 * (entries of 31), is too large. Both stop before the payload is read, so
 * the payload CRC is not needed. With 4-byte values (float build) the limit
 * is OGK_TABLE_MAX_VALUES / 4 = 2^26 - 1 = 8193 x 8191 (entries of 8192 on a
 * grid of 8191), and 2^26 = 64 x 2^20 (entries of 63) is one too many. */
/* req: OGK-CORE-017 */
static void test_largest_payload_size(void **state)
{
    static uint8_t hdr[OGK_TABLE_HEADER_SIZE];
#if OGK_REAL_SINGLE
    const uint32_t dims_max[1] = {8192u};
    const uint32_t dims_over[1] = {63u};
    enum { GRID_MAX = 8191u };
#else
    const uint32_t dims_max[1] = {30u};
    const uint32_t dims_over[1] = {31u};
    enum { GRID_MAX = 601u * 1801u };
#endif
    ogk_table_spec_t s = spec();
    ogk_table_view_t v;
    (void)state;
    s.ndims = 1u;
    s.dims[0] = 0u;
    s.dims[1] = 0u;
    s.max_grid = 2000000u;
    tw_header(hdr, KIND_TEST, 1u, dims_max, GRID_MAX);
    tw_seal(hdr, 0u);
    OGK_ASSERT_STATUS(ogk_table_open(hdr, sizeof hdr, &s, &v), OGK_E_TABLE_TRUNCATED);
    tw_header(hdr, KIND_TEST, 1u, dims_over, 1048576u);
    tw_seal(hdr, 0u);
    OGK_ASSERT_STATUS(ogk_table_open(hdr, sizeof hdr, &s, &v), OGK_E_TABLE_SIZE);
}

/* req: OGK-CORE-017 OGK-CORE-021 */
static void test_null_and_unopened(void **state)
{
    ogk_table_spec_t s = spec();
    ogk_table_view_t v;
    ogk_real_t grid[GRID];
    (void)state;
    build(table_buf);
    OGK_ASSERT_STATUS(ogk_table_open(NULL, TABLE_BYTES, &s, &v), OGK_E_NULL);
    OGK_ASSERT_STATUS(ogk_table_open(table_buf, TABLE_BYTES, NULL, &v), OGK_E_NULL);
    OGK_ASSERT_STATUS(ogk_table_open(table_buf, TABLE_BYTES, &s, NULL), OGK_E_NULL);
    memset(&v, 0, sizeof v);
    OGK_ASSERT_STATUS(ogk_table_read_grid(&v, grid, GRID), OGK_E_NOT_INIT);
}

/* req: OGK-CORE-017 OGK-CORE-023 */
/* The byte-order probe: pi's binary64 bits 0x400921FB54442D18 (IEEE-754),
 * least significant byte first, accepted; every reordering refused. */
static void test_byte_order_probe(void **state)
{
    static const uint8_t le[8] = {0x18u, 0x2Du, 0x44u, 0x54u, 0xFBu, 0x21u, 0x09u, 0x40u};
    uint8_t b[8];
    unsigned i;
    (void)state;
    OGK_ASSERT_STATUS(ogk_table_check_f64_bytes(le), OGK_OK);
#if OGK_REAL_SINGLE
    /* The float build's probe is the float nearest pi (F32 bits 0x40490FDB,
     * as its tables store it); the binary64 bytes are those of pi's literal. */
    {
        static const uint8_t le32[4] = {0xDBu, 0x0Fu, 0x49u, 0x40u};
        tw_put_real(b, OGK_TABLE_ORDER_PROBE);
        assert_true(memcmp(b, le32, sizeof le32) == 0);
    }
    tw_put_f64(b, 3.141592653589793); /* the test's own little-endian writer agrees */
#else
    tw_put_f64(b, OGK_TABLE_ORDER_PROBE); /* the test's own little-endian writer agrees */
#endif
    assert_true(memcmp(b, le, sizeof b) == 0);
    OGK_ASSERT_STATUS(ogk_table_check_f64_bytes(b), OGK_OK);
    for (i = 0u; i < 8u; ++i) {
        b[i] = le[7u - i]; /* big-endian (SPARC V8, PowerPC) */
    }
    OGK_ASSERT_STATUS(ogk_table_check_f64_bytes(b), OGK_E_BYTE_ORDER);
    for (i = 0u; i < 8u; ++i) {
        b[i] = le[(i + 4u) % 8u]; /* 32-bit words swapped (old ARM FPA) */
    }
    OGK_ASSERT_STATUS(ogk_table_check_f64_bytes(b), OGK_E_BYTE_ORDER);
    memcpy(b, le, sizeof b);
    b[7] ^= 0x80u; /* -pi: one bit off */
    OGK_ASSERT_STATUS(ogk_table_check_f64_bytes(b), OGK_E_BYTE_ORDER);
    OGK_ASSERT_STATUS(ogk_table_check_f64_bytes(NULL), OGK_E_NULL);
    /* This target, against the compiler's own statement of its byte order. */
    OGK_ASSERT_STATUS(ogk_table_check_in_place(),
                      OGK_TEST_BIG_ENDIAN ? OGK_E_BYTE_ORDER : OGK_OK);
}

/* req: OGK-CORE-028 OGK-CORE-017 */
/* The other precision's table (F32, IEEE-754 binary32, for the double kernel;
 * F64 for the float one) is refused as an element type this build does not
 * read, with the view left zeroed (unusable); the same view then opens the
 * build's own table. */
static void test_other_precision_refused(void **state)
{
    static uint8_t f32_buf[OGK_TABLE_HEADER_SIZE + TW_OTHER_BYTES * N_VALUES];
    static const ogk_table_view_t zero_view;
    ogk_table_spec_t s = spec();
    ogk_table_view_t v;
    ogk_real_t value = -1.0;
    (void)state;
    assert_int_equal(OGK_TABLE_REAL, OGK_REAL_SINGLE ? OGK_TABLE_F32 : OGK_TABLE_F64);
    build(table_buf);
    tw_to_other(table_buf, f32_buf, N_VALUES);
    memset(&v, 0xA5, sizeof v);
    OGK_ASSERT_STATUS(ogk_table_open(f32_buf, sizeof f32_buf, &s, &v), OGK_E_TABLE_TYPE);
    assert_true(memcmp(&v, &zero_view, sizeof v) == 0);
    OGK_ASSERT_STATUS(ogk_table_get(&v, 0u, 0u, &value), OGK_E_NOT_INIT);
    OGK_ASSERT_STATUS(ogk_table_open(table_buf, TABLE_BYTES, &s, &v), OGK_OK);
    OGK_ASSERT_STATUS(ogk_table_get(&v, 1u, 2u, &value), OGK_OK);
    OGK_ASSERT_NEAR(value, entry_value(1u, 2u), 0.0);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_valid_table_reads_back),
        cmocka_unit_test(test_scalar_entries),
        cmocka_unit_test(test_corrupted_payload_byte),
        cmocka_unit_test(test_corrupted_header_byte),
        cmocka_unit_test(test_wrong_dimension),
        cmocka_unit_test(test_truncated_and_oversized),
        cmocka_unit_test(test_magic_version_type_kind),
        cmocka_unit_test(test_inconsistent_payload_size_and_nan),
        cmocka_unit_test(test_nonfinite_first_and_last_value),
        cmocka_unit_test(test_largest_payload_size),
        cmocka_unit_test(test_null_and_unopened),
        cmocka_unit_test(test_byte_order_probe),
        cmocka_unit_test(test_other_precision_refused),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
