/* test_interp.c -- linear and pchip interpolation: exactness where it must be
 * exact, hand-computed Fritsch-Butland slopes, shape preservation, and range
 * errors instead of silent extrapolation.
 *
 * Both precisions (ogk_test.h): a float tolerance is the double one's
 * multiple of the unit round-off (1e-15 is 4.5 DBL_EPSILON, 1e-14 45, 1e-13
 * 450: the same multiples of FLT_EPSILON), and the magnitudes of the range
 * tests (subnormal, tiny and huge secants, the scaled harmonic mean's bands)
 * are float's where the build is (interp.c: the direct range [1e-15, 1e15],
 * the scaling 2^-75; double [1e-150, 1e150], 2^-537). */
#include "ogk_test.h"

#include "ogk/interp.h"

/* req: OGK-CORE-015 */
static void test_linear_exact_on_affine_data(void **state)
{
    const ogk_real_t grid[4] = {0.0, 0.1, 0.5, 1.0};
    ogk_real_t values[8];
    ogk_real_t out[2];
    unsigned k;
    (void)state;
    for (k = 0u; k < 4u; ++k) {
        values[2u * k] = 3.0 - 2.0 * grid[k];
        values[2u * k + 1u] = 7.0 * grid[k];
    }
    for (k = 0u; k <= 20u; ++k) {
        /* tau as the kernel sees it; in float the node values 3 - 2 t_k and
         * 7 t_k are rounded too (t_k = 0.1 is not a float): a few roundings of
         * magnitudes up to 3 and 7, 8 eps of each */
        const ogk_real_t tau = 0.05 * (double)k;
        OGK_ASSERT_STATUS(ogk_interp_linear(grid, 4u, values, 2u, tau, out), OGK_OK);
        OGK_ASSERT_NEAR(out[0], 3.0 - 2.0 * tau, OGK_TEST_TOL(1e-15, 8.0 * FLT_EPSILON * 3.0));
        OGK_ASSERT_NEAR(out[1], 7.0 * tau, OGK_TEST_TOL(1e-15, 8.0 * FLT_EPSILON * 7.0));
    }
}

/* req: OGK-CORE-015 */
static void test_out_of_range_is_reported(void **state)
{
    const ogk_real_t grid[3] = {0.0, 0.5, 1.0};
    const ogk_real_t values[3] = {1.0, 2.0, 3.0};
    ogk_real_t slopes[3];
    ogk_real_t out = -99.0;
    (void)state;
    OGK_ASSERT_STATUS(ogk_interp_linear(grid, 3u, values, 1u, -1e-12, &out), OGK_E_RANGE);
#if OGK_REAL_SINGLE
    /* 1 + 1e-12 is 1 in float: the next float above 1 instead */
    OGK_ASSERT_STATUS(ogk_interp_linear(grid, 3u, values, 1u, 1.0 + FLT_EPSILON, &out), OGK_E_RANGE);
#else
    OGK_ASSERT_STATUS(ogk_interp_linear(grid, 3u, values, 1u, 1.0 + 1e-12, &out), OGK_E_RANGE);
#endif
    OGK_ASSERT_STATUS(ogk_interp_linear(grid, 3u, values, 1u, NAN, &out), OGK_E_NONFINITE);
    OGK_ASSERT_NEAR(out, -99.0, 0.0); /* untouched */
    OGK_ASSERT_STATUS(ogk_interp_pchip_slopes(grid, 3u, values, 1u, slopes), OGK_OK);
    OGK_ASSERT_STATUS(ogk_interp_pchip(grid, 3u, values, slopes, 1u, 1.5, &out), OGK_E_RANGE);
    OGK_ASSERT_STATUS(ogk_interp_linear(grid, 3u, values, 1u, 1.0, &out), OGK_OK);
    OGK_ASSERT_NEAR(out, 3.0, 0.0);
}

/* req: OGK-CORE-015 */
static void test_bad_grid(void **state)
{
    const ogk_real_t flat[3] = {0.0, 0.5, 0.5};
    const ogk_real_t values[3] = {1.0, 2.0, 3.0};
    ogk_real_t slopes[3];
    ogk_real_t out;
    (void)state;
    OGK_ASSERT_STATUS(ogk_interp_check_grid(flat, 3u), OGK_E_RANGE);
    OGK_ASSERT_STATUS(ogk_interp_pchip_slopes(flat, 3u, values, 1u, slopes), OGK_E_RANGE);
    OGK_ASSERT_STATUS(ogk_interp_check_grid(flat, 1u), OGK_E_DIM);
    OGK_ASSERT_STATUS(ogk_interp_linear(flat, 3u, values, 0u, 0.1, &out), OGK_E_DIM);
    OGK_ASSERT_STATUS(ogk_interp_linear(NULL, 3u, values, 1u, 0.1, &out), OGK_E_NULL);
}

/* req: OGK-CORE-015 */
static void test_pchip_slopes_by_hand(void **state)
{
    /* h = (1, 2), secants d = (1, 2). Interior (Fritsch-Butland weighted
     * harmonic mean): w0 = 2*2+1 = 5, w1 = 2+2*1 = 4, slope = 9 / (5/1 + 4/2) = 9/7.
     * Ends (three-point, shape-preserving): left ((2+2)*1 - 1*2)/3 = 2/3,
     * right ((4+1)*2 - 2*1)/3 = 8/3. */
    const ogk_real_t grid[3] = {0.0, 1.0, 3.0};
    const ogk_real_t values[3] = {0.0, 1.0, 5.0};
    ogk_real_t slopes[3];
    ogk_real_t out;
    (void)state;
    OGK_ASSERT_STATUS(ogk_interp_pchip_slopes(grid, 3u, values, 1u, slopes), OGK_OK);
    OGK_ASSERT_NEAR(slopes[0], 2.0 / 3.0, OGK_TEST_TOL(1e-15, 4.5 * FLT_EPSILON));
    OGK_ASSERT_NEAR(slopes[1], 9.0 / 7.0, OGK_TEST_TOL(1e-15, 4.5 * FLT_EPSILON));
    OGK_ASSERT_NEAR(slopes[2], 8.0 / 3.0, OGK_TEST_TOL(1e-15, 4.5 * FLT_EPSILON));
    /* Hermite cubic at the middle of [1, 3]: (y0 + y1)/2 + h (m0 - m1)/8. */
    OGK_ASSERT_STATUS(ogk_interp_pchip(grid, 3u, values, slopes, 1u, 2.0, &out), OGK_OK);
    OGK_ASSERT_NEAR(out, 3.0 + 2.0 * (9.0 / 7.0 - 8.0 / 3.0) / 8.0, OGK_TEST_TOL(1e-14, 45.0 * FLT_EPSILON));
}

/* Several quantities per node (values[k m + j]): each column gets its own
 * slopes at every node, the ends included. The columns are the by-hand data
 * above, y, and the affine images 2 y + 7 and -y: pchip slopes scale with the
 * data (the clamps compare signs and ratios only) and ignore a constant, so
 * they are (2/3, 9/7, 8/3), twice that, and minus that. */
/* req: OGK-CORE-015 */
static void test_pchip_end_slopes_of_every_column(void **state)
{
    const ogk_real_t grid[3] = {0.0, 1.0, 3.0};
    const ogk_real_t values[9] = {0.0, 7.0, -0.0, 1.0, 9.0, -1.0, 5.0, 17.0, -5.0};
    const double slope_y[3] = {2.0 / 3.0, 9.0 / 7.0, 8.0 / 3.0};
    const double factor[3] = {1.0, 2.0, -1.0};
    const double offset[3] = {0.0, 7.0, 0.0};
    const double mid_y = 3.0 + 2.0 * (9.0 / 7.0 - 8.0 / 3.0) / 8.0; /* y(2), as above */
    ogk_real_t slopes[9];
    ogk_real_t out[3];
    unsigned k, j;
    (void)state;
    OGK_ASSERT_STATUS(ogk_interp_pchip_slopes(grid, 3u, values, 3u, slopes), OGK_OK);
    for (k = 0u; k < 3u; ++k) {
        for (j = 0u; j < 3u; ++j) {
            OGK_ASSERT_NEAR(slopes[3u * k + j], factor[j] * slope_y[k], OGK_TEST_TOL(1e-14, 45.0 * FLT_EPSILON));
        }
    }
    OGK_ASSERT_STATUS(ogk_interp_pchip(grid, 3u, values, slopes, 3u, 2.0, out), OGK_OK);
    for (j = 0u; j < 3u; ++j) {
        OGK_ASSERT_NEAR(out[j], factor[j] * mid_y + offset[j], OGK_TEST_TOL(1e-13, 450.0 * FLT_EPSILON));
    }
}

/* req: OGK-CORE-015 */
static void test_pchip_interpolates_and_preserves_shape(void **state)
{
    /* Monotone step-like data with a flat part and an extremum. */
    const ogk_real_t grid[7] = {0.0, 0.1, 0.2, 0.45, 0.6, 0.8, 1.0};
    const ogk_real_t values[7] = {0.0, 0.05, 1.0, 1.0, 1.2, 0.3, 0.2};
    ogk_real_t slopes[7];
    ogk_real_t out, prev;
    unsigned k;
    (void)state;
    OGK_ASSERT_STATUS(ogk_interp_pchip_slopes(grid, 7u, values, 1u, slopes), OGK_OK);
    for (k = 0u; k < 7u; ++k) {
        OGK_ASSERT_STATUS(ogk_interp_pchip(grid, 7u, values, slopes, 1u, grid[k], &out), OGK_OK);
        OGK_ASSERT_NEAR(out, values[k], OGK_TEST_TOL(1e-15, 4.5 * FLT_EPSILON));
    }
    /* Rising on [0, 0.2], constant on [0.2, 0.45], rising then falling: no
     * overshoot anywhere (values stay within each interval's end values). */
    prev = 0.0;
    for (k = 0u; k <= 1000u; ++k) {
        const double tau = 0.001 * (double)k;
        size_t iv;
        double lo, hi;
        OGK_ASSERT_STATUS(ogk_interp_pchip(grid, 7u, values, slopes, 1u, tau, &out), OGK_OK);
        OGK_ASSERT_STATUS(ogk_interp_locate(grid, 7u, tau, &iv), OGK_OK);
        lo = fmin(values[iv], values[iv + 1u]);
        hi = fmax(values[iv], values[iv + 1u]);
        assert_true(out >= lo - OGK_TEST_TOL(1e-14, 45.0 * FLT_EPSILON) && out <= hi + OGK_TEST_TOL(1e-14, 45.0 * FLT_EPSILON));
        if (tau <= 0.2) {
            assert_true(out >= prev - OGK_TEST_TOL(1e-15, 4.5 * FLT_EPSILON));
        }
        prev = out;
    }
}

/* req: OGK-CORE-015 */
static void test_pchip_two_points_is_linear(void **state)
{
    const ogk_real_t grid[2] = {0.0, 1.0};
    const ogk_real_t values[2] = {2.0, 4.0};
    ogk_real_t slopes[2];
    ogk_real_t out;
    (void)state;
    OGK_ASSERT_STATUS(ogk_interp_pchip_slopes(grid, 2u, values, 1u, slopes), OGK_OK);
    OGK_ASSERT_STATUS(ogk_interp_pchip(grid, 2u, values, slopes, 1u, 0.3, &out), OGK_OK);
    OGK_ASSERT_NEAR(out, 2.6, OGK_TEST_TOL(1e-15, 4.5 * FLT_EPSILON));
}

/* Two nodes, two quantities: each column's slope is its own secant, (4 - 2)
 * and (-3 - 10), at both nodes, and the interpolant is each column's line. */
/* req: OGK-CORE-015 */
static void test_pchip_two_points_every_column(void **state)
{
    const ogk_real_t grid[2] = {0.0, 1.0};
    const ogk_real_t values[4] = {2.0, 10.0, 4.0, -3.0};
    ogk_real_t slopes[4];
    ogk_real_t out[2];
    (void)state;
    OGK_ASSERT_STATUS(ogk_interp_pchip_slopes(grid, 2u, values, 2u, slopes), OGK_OK);
    OGK_ASSERT_NEAR(slopes[0], 2.0, 0.0);
    OGK_ASSERT_NEAR(slopes[1], -13.0, 0.0);
    OGK_ASSERT_NEAR(slopes[2], 2.0, 0.0);
    OGK_ASSERT_NEAR(slopes[3], -13.0, 0.0);
    OGK_ASSERT_STATUS(ogk_interp_pchip(grid, 2u, values, slopes, 2u, 0.3, out), OGK_OK);
    OGK_ASSERT_NEAR(out[0], 2.6, OGK_TEST_TOL(1e-15, 4.5 * FLT_EPSILON));
    OGK_ASSERT_NEAR(out[1], 10.0 - 13.0 * 0.3, OGK_TEST_TOL(1e-14, 45.0 * FLT_EPSILON));
}

/* req: OGK-CORE-015 */
static void test_locate_edges(void **state)
{
    const ogk_real_t grid[4] = {0.0, 0.25, 0.5, 1.0};
    size_t k = 99u;
    (void)state;
    OGK_ASSERT_STATUS(ogk_interp_locate(grid, 4u, 0.0, &k), OGK_OK);
    assert_int_equal(k, 0u);
    OGK_ASSERT_STATUS(ogk_interp_locate(grid, 4u, 0.25, &k), OGK_OK);
    assert_int_equal(k, 1u);
    OGK_ASSERT_STATUS(ogk_interp_locate(grid, 4u, 1.0, &k), OGK_OK);
    assert_int_equal(k, 2u);
}


/* The end-slope rule of Moler's pchip on three points, h0 = h1 = 1, where
 * the one-sided slope is s = (3 d0 - d1) / 2: zero when s and d0 differ in
 * sign; 3 d0 when the secants differ in sign and |s| > 3 |d0|; s otherwise.
 * Both ends (the right one on the mirrored data), each branch and its
 * neighbour, so a flipped or dropped clamp condition fails here. */
/* req: OGK-CORE-015 */
static void test_pchip_end_slope_clamp(void **state)
{
    static const struct {
        double y1, y2;   /* y0 = 0: d0 = y1, d1 = y2 - y1 */
        double slope;    /* expected left-end slope */
    } cases[5] = {
        {1.0, 6.0, 0.0},   /* d = (1, 5): s = -1, sign differs from d0 -> 0 */
        {1.0, 2.5, 0.75},  /* d = (1, 1.5): s = 0.75, same signs -> kept */
        {1.0, -5.0, 3.0},  /* d = (1, -6): s = 4.5 > 3 d0, secants differ in sign -> 3 d0 */
        {1.0, -1.0, 2.5},  /* d = (1, -2): s = 2.5 <= 3 d0 -> kept */
        {-1.0, 5.0, -3.0}, /* d = (-1, 6): s = -4.5 -> 3 d0 = -3 */
    };
    const ogk_real_t grid[3] = {0.0, 1.0, 2.0};
    unsigned k;
    (void)state;
    for (k = 0u; k < 5u; ++k) {
        const ogk_real_t left[3] = {0.0, cases[k].y1, cases[k].y2};
        /* mirrored: the right end sees the same secants, read backwards */
        const ogk_real_t right[3] = {cases[k].y2, cases[k].y1, 0.0};
        ogk_real_t slopes[3];
        const double expected = cases[k].slope;
        OGK_ASSERT_STATUS(ogk_interp_pchip_slopes(grid, 3u, left, 1u, slopes), OGK_OK);
        OGK_ASSERT_NEAR(slopes[0], expected, OGK_TEST_TOL(1e-15, 4.5 * FLT_EPSILON));
        OGK_ASSERT_STATUS(ogk_interp_pchip_slopes(grid, 3u, right, 1u, slopes), OGK_OK);
        OGK_ASSERT_NEAR(slopes[2], -expected, OGK_TEST_TOL(1e-15, 4.5 * FLT_EPSILON));
    }
}

/* Subnormal and tiny secants: the interior harmonic mean neither overflows
 * (w0 / d0 for a subnormal d0 was +inf, flattening the slope to 0) nor
 * underflows (d0 * d1 of two tiny secants was 0, taken as an extremum); huge
 * ones stay finite; an infinite secant is reported. */
/* req: OGK-CORE-015 */
static void test_pchip_tiny_and_huge_secants(void **state)
{
    const ogk_real_t grid[3] = {0.0, 0.5, 1.0};
    const ogk_real_t grid1[3] = {0.0, 1.0, 2.0};
    /* float: a subnormal 1e-40 (w0 / d0 = 7.5e39 beyond FLT_MAX), tiny
     * secants whose product 1e-50 underflows, huge ones whose square 1e60
     * overflows, a difference beyond FLT_MAX */
#if OGK_REAL_SINGLE
#define SUB 1.0e-40
#define TINY 1.0e-25
#define TINY_2 2.0e-25
#define HUGE_1 1.0e30
#define HUGE_2 2.0e30
#define OVER 1.7e38
#else
#define SUB 1.0e-310
#define TINY 1.0e-200
#define TINY_2 2.0e-200
#define HUGE_1 1.0e300
#define HUGE_2 2.0e300
#define OVER 1.7e308
#endif
    const ogk_real_t sub[3] = {0.0, SUB, 1.0};
    const ogk_real_t tiny[3] = {0.0, TINY, TINY_2};
    const ogk_real_t huge[3] = {0.0, HUGE_1, HUGE_2};
    const ogk_real_t over[3] = {-OVER, OVER, OVER};
    ogk_real_t slopes[3];
    (void)state;
    OGK_ASSERT_STATUS(ogk_interp_pchip_slopes(grid, 3u, sub, 1u, slopes), OGK_OK);
    {
        const double d0 = SUB / 0.5;
        const double d1 = (1.0 - SUB) / 0.5;
        /* equal weights: 2 d0 d1 / (d0 + d1), ~2 d0. In float the subnormal
         * d0 = 2e-40 has a resolution of FLT_TRUE_MIN / d0 = 7e-6 relative:
         * 100 times that. */
        OGK_ASSERT_REL(slopes[1], 2.0 * d0 * (d1 / (d0 + d1)), OGK_TEST_TOL(1e-9, 100.0 * 1.4e-45 / 2.0e-40), 0.0);
        assert_true(slopes[1] > 0.0 && isfinite(slopes[0]) && isfinite(slopes[2]));
    }
    OGK_ASSERT_STATUS(ogk_interp_pchip_slopes(grid1, 3u, tiny, 1u, slopes), OGK_OK);
    OGK_ASSERT_REL(slopes[0], TINY, OGK_TEST_TOL(1e-14, 45.0 * FLT_EPSILON), 0.0); /* linear data: every slope 1e-200 */
    OGK_ASSERT_REL(slopes[1], TINY, OGK_TEST_TOL(1e-14, 45.0 * FLT_EPSILON), 0.0);
    OGK_ASSERT_REL(slopes[2], TINY, OGK_TEST_TOL(1e-14, 45.0 * FLT_EPSILON), 0.0);
    OGK_ASSERT_STATUS(ogk_interp_pchip_slopes(grid1, 3u, huge, 1u, slopes), OGK_OK);
    OGK_ASSERT_REL(slopes[1], HUGE_1, OGK_TEST_TOL(1e-14, 45.0 * FLT_EPSILON), 0.0);
    OGK_ASSERT_STATUS(ogk_interp_pchip_slopes(grid1, 3u, over, 1u, slopes), OGK_E_RANGE);
}

/* Interior slope of two secants d0, d1 on the uniform grid {0, 1, 2} (equal
 * weights): the harmonic mean 2 d0 d1 / (d0 + d1), or 0 at an extremum. */
static double interior_slope(double d0, double d1)
{
    const ogk_real_t grid[3] = {0.0, 1.0, 2.0};
    const ogk_real_t values[3] = {-d0, 0.0, d1};
    ogk_real_t slopes[3];
    OGK_ASSERT_STATUS(ogk_interp_pchip_slopes(grid, 3u, values, 1u, slopes), OGK_OK);
    return slopes[1];
}

/* Every path of the harmonic mean: the direct form, each operand outside
 * [1e-150, 1e150] alone (secants and weights), the scaled form with the larger
 * magnitude first or second and above 1, within [2^-537, 1) or below 2^-537,
 * both signs and the extrema. Expected values are 2 d0 d1 / (d0 + d1) by hand
 * (weights (2 h1 + h0, h1 + 2 h0) for the non-uniform grids: 9 / 7 and 1.44). */
/* req: OGK-CORE-015 */
static void test_pchip_harmonic_mean_every_path(void **state)
{
    /* float: the range [1e-15, 1e15] and 2^-75 (2.6e-23) in place of
     * [1e-150, 1e150] and 2^-537 (4.5e-162): 1e200 -> 1e20, 1e-155 -> 1e-16,
     * 1e-200 -> 1e-25, 1e+-160 -> 1e+-16, 1e149 -> 1e14 */
#if OGK_REAL_SINGLE
    static const struct {
        double d0;
        double d1;
        double slope;
    } cases[] = {
        {1.0, 3.0, 1.5},
        {3.0e20, 1.0e20, 1.5e20},
        {1.0e20, 3.0e20, 1.5e20},
        {-3.0e20, -1.0e20, -1.5e20},
        {3.0e-16, 1.0e-16, 1.5e-16},
        {1.0e-16, 3.0e-16, 1.5e-16},
        {3.0e-25, 1.0e-25, 1.5e-25},
        {-1.0e-25, -3.0e-25, -1.5e-25},
        {1.0, 1.0e-16, 2.0e-16},
        {1.0e-16, 1.0, 2.0e-16},
        {1.0, 1.0e16, 2.0},
        {1.0e16, 1.0, 2.0},
        {1.0, -1.0, 0.0},
        {-1.0, 1.0, 0.0},
        {-1.0, 0.0, 0.0},
        {0.0, 1.0, 0.0},
    };
    static const struct {
        double h0;
        double h1;
        double slope;
    } weighted[] = {
        {1.0e-25, 2.0e-25, 9.0 / 7.0},
        {1.0e20, 2.0e20, 9.0 / 7.0},
        {5.0e14, 1.0e14, 1.44},
        {1.0e14, 5.0e14, 1.8 / 1.45},
    };
#else
    static const struct {
        double d0;
        double d1;
        double slope;
    } cases[] = {
        {1.0, 3.0, 1.5},
        {3.0e200, 1.0e200, 1.5e200},
        {1.0e200, 3.0e200, 1.5e200},
        {-3.0e200, -1.0e200, -1.5e200},
        {3.0e-155, 1.0e-155, 1.5e-155},
        {1.0e-155, 3.0e-155, 1.5e-155},
        {3.0e-200, 1.0e-200, 1.5e-200},
        {-1.0e-200, -3.0e-200, -1.5e-200},
        {1.0, 1.0e-160, 2.0e-160},
        {1.0e-160, 1.0, 2.0e-160},
        {1.0, 1.0e160, 2.0},
        {1.0e160, 1.0, 2.0},
        {1.0, -1.0, 0.0},
        {-1.0, 1.0, 0.0},
        {-1.0, 0.0, 0.0},
        {0.0, 1.0, 0.0},
    };
    /* secants 1 and 2 over steps (h0, h1): values {-h0, 0, 2 h1} */
    static const struct {
        double h0;
        double h1;
        double slope;
    } weighted[] = {
        {1.0e-200, 2.0e-200, 9.0 / 7.0}, /* both weights below 1e-150 */
        {1.0e200, 2.0e200, 9.0 / 7.0},   /* both above 1e150 */
        {5.0e149, 1.0e149, 1.44},        /* w0 = 7e149 inside, w1 = 1.1e150 above */
        {1.0e149, 5.0e149, 1.8 / 1.45},  /* w0 = 1.1e150 above, w1 = 7e149 inside */
    };
#endif
    size_t k;
    (void)state;
    for (k = 0u; k < sizeof cases / sizeof cases[0]; ++k) {
        OGK_ASSERT_REL(interior_slope(cases[k].d0, cases[k].d1), cases[k].slope, OGK_TEST_TOL(1e-14, 45.0 * FLT_EPSILON), 0.0);
    }
    for (k = 0u; k < sizeof weighted / sizeof weighted[0]; ++k) {
        const ogk_real_t grid[3] = {0.0, weighted[k].h0, weighted[k].h0 + weighted[k].h1};
        const ogk_real_t values[3] = {-weighted[k].h0, 0.0, 2.0 * weighted[k].h1};
        ogk_real_t slopes[3];
        OGK_ASSERT_STATUS(ogk_interp_pchip_slopes(grid, 3u, values, 1u, slopes), OGK_OK);
        OGK_ASSERT_REL(slopes[1], weighted[k].slope, OGK_TEST_TOL(1e-14, 45.0 * FLT_EPSILON), 0.0);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_linear_exact_on_affine_data),
        cmocka_unit_test(test_out_of_range_is_reported),
        cmocka_unit_test(test_bad_grid),
        cmocka_unit_test(test_pchip_slopes_by_hand),
        cmocka_unit_test(test_pchip_end_slopes_of_every_column),
        cmocka_unit_test(test_pchip_interpolates_and_preserves_shape),
        cmocka_unit_test(test_pchip_two_points_is_linear),
        cmocka_unit_test(test_pchip_two_points_every_column),
        cmocka_unit_test(test_locate_edges),
        cmocka_unit_test(test_pchip_end_slope_clamp),
        cmocka_unit_test(test_pchip_tiny_and_huge_secants),
        cmocka_unit_test(test_pchip_harmonic_mean_every_path),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
