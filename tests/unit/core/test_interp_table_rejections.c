/* test_interp_table_rejections.c -- the argument, dimension and size rejections of interp.c and
 * table.c that test_interp.c and test_table.c leave unrun (make coverage, docs/evidence/coverage.md):
 * NULL arguments, grids too short, non-finite grid and values, each header field out of the
 * spec of ogk/table.h, size fields that would overflow, and the readers on a zeroed view. The
 * size checks need only a sealed header: they all come before the payload is looked at. */
#include "ogk_test.h"

#include <float.h>
#include <string.h>

#include "ogk/crc32.h"
#include "ogk/interp.h"
#include "ogk/table.h"
#include "table_writer.h"

#define KIND 0x47415445u /* "GATE" */

/* ------------------------------------------------------------------ interp */

static const ogk_real_t grid3[3] = {0.0, 1.0, 3.0};
static const ogk_real_t vals3[3] = {1.0, 2.0, 4.0};

/* req: OGK-CORE-015 OGK-CORE-021 */
static void test_interp_null_arguments(void **state)
{
    ogk_real_t out[2] = {-7.0, -7.0};
    ogk_real_t slopes[3] = {-7.0, -7.0, -7.0};
    size_t k = 99u;
    (void)state;
    OGK_ASSERT_STATUS(ogk_interp_check_grid(NULL, 3u), OGK_E_NULL);
    OGK_ASSERT_STATUS(ogk_interp_locate(NULL, 3u, 0.5, &k), OGK_E_NULL);
    OGK_ASSERT_STATUS(ogk_interp_locate(grid3, 3u, 0.5, NULL), OGK_E_NULL);
    OGK_ASSERT_STATUS(ogk_interp_linear(grid3, 3u, NULL, 1u, 0.5, out), OGK_E_NULL);
    OGK_ASSERT_STATUS(ogk_interp_linear(grid3, 3u, vals3, 1u, 0.5, NULL), OGK_E_NULL);
    OGK_ASSERT_STATUS(ogk_interp_pchip_slopes(grid3, 3u, NULL, 1u, slopes), OGK_E_NULL);
    OGK_ASSERT_STATUS(ogk_interp_pchip_slopes(grid3, 3u, vals3, 1u, NULL), OGK_E_NULL);
    OGK_ASSERT_STATUS(ogk_interp_pchip(grid3, 3u, NULL, slopes, 1u, 0.5, out), OGK_E_NULL);
    OGK_ASSERT_STATUS(ogk_interp_pchip(grid3, 3u, vals3, NULL, 1u, 0.5, out), OGK_E_NULL);
    OGK_ASSERT_STATUS(ogk_interp_pchip(grid3, 3u, vals3, slopes, 1u, 0.5, NULL), OGK_E_NULL);
    /* nothing written on a rejection */
    assert_int_equal(k, 99u);
    OGK_ASSERT_NEAR(out[0], -7.0, 0.0);
    OGK_ASSERT_NEAR(slopes[0], -7.0, 0.0);
}

/* req: OGK-CORE-015 OGK-CORE-021 */
static void test_interp_dimensions(void **state)
{
    ogk_real_t out[2] = {-7.0, -7.0};
    ogk_real_t slopes[3] = {-7.0, -7.0, -7.0};
    size_t k = 99u;
    (void)state;
    /* a one-node grid has no interval */
    OGK_ASSERT_STATUS(ogk_interp_check_grid(grid3, 1u), OGK_E_DIM);
    OGK_ASSERT_STATUS(ogk_interp_locate(grid3, 1u, 0.0, &k), OGK_E_DIM);
    OGK_ASSERT_STATUS(ogk_interp_linear(grid3, 1u, vals3, 1u, 0.0, out), OGK_E_DIM);
    OGK_ASSERT_STATUS(ogk_interp_pchip_slopes(grid3, 1u, vals3, 1u, slopes), OGK_E_DIM);
    /* m = 0 quantities per node */
    OGK_ASSERT_STATUS(ogk_interp_linear(grid3, 3u, vals3, 0u, 0.5, out), OGK_E_DIM);
    OGK_ASSERT_STATUS(ogk_interp_pchip_slopes(grid3, 3u, vals3, 0u, slopes), OGK_E_DIM);
    OGK_ASSERT_STATUS(ogk_interp_pchip(grid3, 3u, vals3, slopes, 0u, 0.5, out), OGK_E_DIM);
    assert_int_equal(k, 99u);
    OGK_ASSERT_NEAR(out[0], -7.0, 0.0);
    OGK_ASSERT_NEAR(slopes[0], -7.0, 0.0);
}

/* req: OGK-CORE-015 OGK-CORE-021 */
static void test_interp_nonfinite(void **state)
{
    ogk_real_t grid[3] = {0.0, 1.0, 3.0};
    ogk_real_t vals[3] = {1.0, 2.0, 4.0};
    ogk_real_t slopes[3] = {-7.0, -7.0, -7.0};
    (void)state;
    grid[1] = NAN;
    OGK_ASSERT_STATUS(ogk_interp_check_grid(grid, 3u), OGK_E_NONFINITE);
    OGK_ASSERT_STATUS(ogk_interp_pchip_slopes(grid, 3u, vals, 1u, slopes), OGK_E_NONFINITE);
    grid[1] = 1.0;
    grid[2] = INFINITY;
    OGK_ASSERT_STATUS(ogk_interp_check_grid(grid, 3u), OGK_E_NONFINITE);
    grid[2] = 3.0;
    vals[2] = -INFINITY;
    OGK_ASSERT_STATUS(ogk_interp_pchip_slopes(grid, 3u, vals, 1u, slopes), OGK_E_NONFINITE);
    OGK_ASSERT_NEAR(slopes[0], -7.0, 0.0);
    vals[2] = 4.0;
    OGK_ASSERT_STATUS(ogk_interp_pchip_slopes(grid, 3u, vals, 1u, slopes), OGK_OK);
    /* interior: weighted harmonic mean of the secants 1 and 1 is 1 */
    OGK_ASSERT_NEAR(slopes[1], 1.0, OGK_TEST_TOL(1e-15, 4.5 * FLT_EPSILON));
}

/* Fritsch-Butland interior slope (w0 + w1) / (w0 / d0 + w1 / d1), w0 = 2 h1 + h0,
 * w1 = h1 + 2 h0, evaluated directly on values where that cannot overflow: the reference for
 * the kernel's scaled form. */
static double fb_slope(double h0, double h1, double d0, double d1)
{
    const double w0 = (2.0 * h1) + h0;
    const double w1 = h1 + (2.0 * h0);
    return (w0 + w1) / ((w0 / d0) + (w1 / d1));
}

/* The scaled form of the interior slope is taken when one secant or one weight leaves
 * [1e-150, 1e150] (float build: [1e-15, 1e15], OGK_REAL_ROOT_TINY / _BIG; each float case
 * below sits where its double one does, the magnitudes scaled to that range); it must
 * agree with the formula. One case per operand. Tolerance 1e-14 relative: 45 eps, in
 * float 45 FLT_EPSILON. */
#if OGK_REAL_SINGLE
#define S_TINY 1e-20 /* d1 */
#define S_STEP 1e-16 /* grid steps: w0 = 3e-16 below the range */
#define S_STEP_2 2e-16
#define S_STEP_3 3e-16
#define S_H0 6e14    /* w0 = 6.2e14 in range, w1 = 1.21e15 out of it */
#define S_H1 1e13
#define S_HI 1e15
#else
#define S_TINY 1e-200
#define S_STEP 1e-160
#define S_STEP_2 2e-160
#define S_STEP_3 3e-160
#define S_H0 6e149
#define S_H1 1e148
#define S_HI 1e150
#endif
/* req: OGK-CORE-015 */
static void test_interp_scaled_harmonic_slope(void **state)
{
    ogk_real_t slopes[3];
    (void)state;
    {
        /* d0 = 1, d1 = 1e-200 tiny: w / d stays representable here (w1 / d1 = 3e200) */
        const ogk_real_t g[3] = {0.0, 1.0, 2.0};
        const ogk_real_t v[3] = {-1.0, 0.0, S_TINY};
        OGK_ASSERT_STATUS(ogk_interp_pchip_slopes(g, 3u, v, 1u, slopes), OGK_OK);
        OGK_ASSERT_REL(slopes[1], fb_slope(1.0, 1.0, 1.0, v[2]), OGK_TEST_TOL(1e-14, 45.0 * FLT_EPSILON), 0.0);
        OGK_ASSERT_REL(slopes[1], 2.0 * v[2], OGK_TEST_TOL(1e-14, 45.0 * FLT_EPSILON), 0.0); /* ~ (w0 + w1) d1 / w1, w0 = w1 */
    }
    {
        /* grid steps 1e-160 (w0 out of range), secants 1 and 2 */
        const ogk_real_t g[3] = {0.0, S_STEP, S_STEP_2};
        const ogk_real_t v[3] = {0.0, S_STEP, S_STEP_3};
        OGK_ASSERT_STATUS(ogk_interp_pchip_slopes(g, 3u, v, 1u, slopes), OGK_OK);
        OGK_ASSERT_REL(slopes[1], 4.0 / 3.0, OGK_TEST_TOL(1e-14, 45.0 * FLT_EPSILON), 0.0); /* (3 + 3) / (3 / 1 + 3 / 2) */
    }
    {
        /* h0 = 6e149, h1 = 1e148: w0 = 6.2e149 in range, w1 = 1.21e150 out of it */
        const double h0 = S_H0;
        const double h1 = S_H1;
        const ogk_real_t g[3] = {0.0, h0, h0 + h1};
        const ogk_real_t v[3] = {0.0, h0, h0 + (2.0 * h1)};
        const double d0 = (v[1] - v[0]) / (g[1] - g[0]);
        const double d1 = (v[2] - v[1]) / (g[2] - g[1]);
        assert_true(((2.0 * (g[2] - g[1])) + (g[1] - g[0])) <= S_HI);
        assert_true(((g[2] - g[1]) + (2.0 * (g[1] - g[0]))) > S_HI);
        OGK_ASSERT_STATUS(ogk_interp_pchip_slopes(g, 3u, v, 1u, slopes), OGK_OK);
        OGK_ASSERT_REL(slopes[1], fb_slope(g[1] - g[0], g[2] - g[1], d0, d1), OGK_TEST_TOL(1e-14, 45.0 * FLT_EPSILON), 0.0);
    }
}

/* ------------------------------------------------------------------ table */

static uint8_t hdr[OGK_TABLE_HEADER_SIZE];

/* Header-only table: the header CRC sealed, the payload not present (every check below
 * rejects before the payload length is compared). */
static void seal_header(uint8_t *b)
{
    uint32_t crc = 0u;
    (void)ogk_crc32_update(&crc, b, 44u);
    tw_put_u32(b + 44, crc);
}

static void header(uint16_t ndims, const uint32_t *dims, uint32_t grid)
{
    tw_header(hdr, KIND, ndims, dims, grid);
    seal_header(hdr);
}

static ogk_table_spec_t any_spec(uint16_t ndims)
{
    ogk_table_spec_t s;
    (void)memset(&s, 0, sizeof s);
    s.kind = KIND;
    s.ndims = ndims;
    s.min_grid = 1u;
    s.max_grid = 0xFFFFFFFFu;
    return s;
}

static void expect_open(const ogk_table_spec_t *s, ogk_status expected)
{
    ogk_table_view_t v;
    (void)memset(&v, 0x5A, sizeof v);
    OGK_ASSERT_STATUS(ogk_table_open(hdr, sizeof hdr, s, &v), expected);
    assert_null(v.buf); /* the view is cleared on every rejection */
    assert_int_equal(v.grid_size, 0u);
}

/* req: OGK-CORE-017 */
static void test_table_dims_outside_spec(void **state)
{
    const uint32_t d2[2] = {2u, 3u};
    const uint32_t d5[OGK_TABLE_MAX_DIMS] = {1u, 1u, 1u, 1u};
    ogk_table_spec_t s = any_spec(2u);
    (void)state;
    header(0u, d2, 4u); /* no dimension */
    s.ndims = 0u;
    expect_open(&s, OGK_E_TABLE_DIM);
    header(1u, d5, 4u);
    tw_put_u16(hdr + 12, (uint16_t)(OGK_TABLE_MAX_DIMS + 1u)); /* one dimension too many */
    seal_header(hdr);
    s.ndims = (uint16_t)(OGK_TABLE_MAX_DIMS + 1u);
    expect_open(&s, OGK_E_TABLE_DIM);
    s = any_spec(2u);
    header(2u, d2, 4u);
    tw_put_u32(hdr + 16 + 4, 0u); /* a used dimension of size 0 */
    seal_header(hdr);
    expect_open(&s, OGK_E_TABLE_DIM);
    header(2u, d2, 4u);
    tw_put_u32(hdr + 16 + 8, 7u); /* a size in an unused dimension slot */
    seal_header(hdr);
    expect_open(&s, OGK_E_TABLE_DIM);
    header(2u, d2, 4u);
    tw_put_u16(hdr + 14, 1u); /* reserved field not zero */
    seal_header(hdr);
    expect_open(&s, OGK_E_TABLE_TYPE);
}

/* req: OGK-CORE-017 */
static void test_table_grid_outside_spec(void **state)
{
    const uint32_t d2[2] = {2u, 3u};
    ogk_table_spec_t s = any_spec(2u);
    (void)state;
    header(2u, d2, 4u);
    s.min_grid = 5u; /* fewer grid points than the caller needs */
    expect_open(&s, OGK_E_TABLE_DIM);
    s.min_grid = 0u; /* even a spec that allows it: an empty grid is no table */
    header(2u, d2, 0u);
    expect_open(&s, OGK_E_TABLE_DIM);
}

/* Sizes whose products would overflow 32 bits: rejected before any multiplication wraps. */
/* req: OGK-CORE-017 */
static void test_table_size_overflow(void **state)
{
    ogk_table_spec_t s1 = any_spec(1u);
    ogk_table_spec_t s2 = any_spec(2u);
    (void)state;
    {
        const uint32_t d[2] = {0x10000u, 0x10000u}; /* entry of 2^32 values */
        header(2u, d, 1u);
        expect_open(&s2, OGK_E_TABLE_SIZE);
    }
    {
        const uint32_t d[1] = {0x0FFFFFFFu}; /* entry at the value limit itself */
        header(1u, d, 1u);
        expect_open(&s1, OGK_E_TABLE_SIZE);
    }
    {
        const uint32_t d[1] = {0x10000u}; /* grid * (1 + entry) over the limit */
        header(1u, d, 0x1000u);
        expect_open(&s1, OGK_E_TABLE_SIZE);
    }
    {
        /* 0x300 * 0x10000 values: 8 x that overflows (float build, 4-byte values:
         * 0x600 * 0x10000, 4 x that overflows) */
        const uint32_t d[1] = {0xFFFFu};
        header(1u, d, (TW_REAL_BYTES == 8u) ? 0x300u : 0x600u);
        expect_open(&s1, OGK_E_TABLE_SIZE);
    }
}

/* req: OGK-CORE-017 */
static void test_table_short_buffers(void **state)
{
    const uint32_t d2[2] = {2u, 3u};
    ogk_table_spec_t s = any_spec(2u);
    ogk_table_view_t v;
    (void)state;
    header(2u, d2, 4u);
    /* under the header: the magic decides between damage and truncation */
    OGK_ASSERT_STATUS(ogk_table_open(hdr, 3u, &s, &v), OGK_E_TABLE_TRUNCATED);
    OGK_ASSERT_STATUS(ogk_table_open(hdr, 4u, &s, &v), OGK_E_TABLE_TRUNCATED);
    hdr[1] = (uint8_t)'X';
    OGK_ASSERT_STATUS(ogk_table_open(hdr, 4u, &s, &v), OGK_E_TABLE_MAGIC);
    OGK_ASSERT_STATUS(ogk_table_open(hdr, 3u, &s, &v), OGK_E_TABLE_TRUNCATED);
    assert_null(v.buf);
}

/* A small good table for the readers. */
#define GRID 3u
#define ENTRY 2u
#define NVAL (GRID * (1u + ENTRY))
static uint8_t tbuf[OGK_TABLE_HEADER_SIZE + TW_REAL_BYTES * NVAL];

/* req: OGK-CORE-017 OGK-CORE-021 */
static void test_table_readers_reject(void **state)
{
    const uint32_t d1[1] = {ENTRY};
    ogk_table_spec_t s = any_spec(1u);
    ogk_table_view_t v;
    ogk_table_view_t zero;
    ogk_real_t grid[GRID] = {-7.0, -7.0, -7.0};
    ogk_real_t data[GRID * ENTRY];
    ogk_real_t one = -7.0;
    uint32_t i;
    (void)state;
    tw_header(tbuf, KIND, 1u, d1, GRID);
    for (i = 0u; i < NVAL; ++i) {
        tw_put_real(tbuf + OGK_TABLE_HEADER_SIZE + TW_REAL_BYTES * i, (double)i);
    }
    tw_seal(tbuf, NVAL);
    OGK_ASSERT_STATUS(ogk_table_open(tbuf, sizeof tbuf, &s, &v), OGK_OK);
    (void)memset(&zero, 0, sizeof zero);
    (void)memset(data, 0, sizeof data);
    data[0] = -7.0;
    OGK_ASSERT_STATUS(ogk_table_read_grid(NULL, grid, GRID), OGK_E_NULL);
    OGK_ASSERT_STATUS(ogk_table_read_grid(&v, NULL, GRID), OGK_E_NULL);
    OGK_ASSERT_STATUS(ogk_table_read_data(NULL, data, GRID * ENTRY), OGK_E_NULL);
    OGK_ASSERT_STATUS(ogk_table_read_data(&v, NULL, GRID * ENTRY), OGK_E_NULL);
    OGK_ASSERT_STATUS(ogk_table_read_data(&zero, data, GRID * ENTRY), OGK_E_NOT_INIT);
    OGK_ASSERT_STATUS(ogk_table_read_data(&v, data, GRID * ENTRY - 1u), OGK_E_DIM);
    OGK_ASSERT_STATUS(ogk_table_get(NULL, 0u, 0u, &one), OGK_E_NULL);
    OGK_ASSERT_STATUS(ogk_table_get(&v, 0u, 0u, NULL), OGK_E_NULL);
    OGK_ASSERT_STATUS(ogk_table_get(&zero, 0u, 0u, &one), OGK_E_NOT_INIT);
    OGK_ASSERT_NEAR(grid[0], -7.0, 0.0);
    OGK_ASSERT_NEAR(data[0], -7.0, 0.0);
    OGK_ASSERT_NEAR(one, -7.0, 0.0);
    /* and the same calls with room and a valid view read the payload */
    OGK_ASSERT_STATUS(ogk_table_read_data(&v, data, GRID * ENTRY), OGK_OK);
    OGK_ASSERT_NEAR(data[GRID * ENTRY - 1u], (double)(NVAL - 1u), 0.0);
    OGK_ASSERT_STATUS(ogk_table_get(&v, 1u, 1u, &one), OGK_OK);
    OGK_ASSERT_NEAR(one, (double)(GRID + 1u * ENTRY + 1u), 0.0);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_interp_null_arguments),
        cmocka_unit_test(test_interp_dimensions),
        cmocka_unit_test(test_interp_nonfinite),
        cmocka_unit_test(test_interp_scaled_harmonic_slope),
        cmocka_unit_test(test_table_dims_outside_spec),
        cmocka_unit_test(test_table_grid_outside_spec),
        cmocka_unit_test(test_table_size_overflow),
        cmocka_unit_test(test_table_short_buffers),
        cmocka_unit_test(test_table_readers_reject),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
