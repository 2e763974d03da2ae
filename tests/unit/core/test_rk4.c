/* test_rk4.c -- RK4 order and switching detection against closed forms.
 *
 * Both precisions (ogk_test.h). The root tolerances the tests give the kernel
 * (s_tol, t_tol) are a few units of the build's round-off of S and t in float
 * (1e-12 and 1e-14 are below float's resolution); each float bound of a
 * switching time or state says what it is made of. */
#include "ogk_test.h"

#include <string.h>

#include "ogk/rk4.h"

#define PI 3.14159265358979323846

/* ---------------------------------------------------------------- models */

/* Two-body, mu = 1: x = [r(3), v(3)]. */
static ogk_status two_body(void *user, ogk_real_t t, const ogk_real_t *x, int mode, ogk_real_t *xdot)
{
    const double r2 = x[0] * x[0] + x[1] * x[1] + x[2] * x[2];
    const double inv_r3 = 1.0 / (r2 * sqrt(r2));
    (void)user;
    (void)t;
    (void)mode;
    xdot[0] = x[3];
    xdot[1] = x[4];
    xdot[2] = x[5];
    xdot[3] = -x[0] * inv_r3;
    xdot[4] = -x[1] * inv_r3;
    xdot[5] = -x[2] * inv_r3;
    return OGK_OK;
}

/* x' = x: one RK4 step multiplies by the 4th-order Taylor polynomial of e^h. */
static ogk_status growth(void *user, ogk_real_t t, const ogk_real_t *x, int mode, ogk_real_t *xdot)
{
    (void)user;
    (void)t;
    (void)mode;
    xdot[0] = x[0];
    return OGK_OK;
}

/* Minimum-fuel double integrator: primer lambda_v(t) = c1 - c2 t, thrust
 * u = -sign(lambda_v) when on (mode 1), S = |lambda_v| - 1. */
typedef struct {
    double c1, c2;
} primer_t;

static ogk_status fuel_di_rhs(void *user, ogk_real_t t, const ogk_real_t *x, int mode, ogk_real_t *xdot)
{
    const primer_t *pr = (const primer_t *)user;
    const double lambda_v = pr->c1 - pr->c2 * t;
    xdot[0] = x[1];
    xdot[1] = (mode == 1) ? ((lambda_v > 0.0) ? -1.0 : 1.0) : 0.0;
    return OGK_OK;
}

static ogk_status fuel_di_switch(void *user, ogk_real_t t, const ogk_real_t *x, int mode, ogk_real_t *s)
{
    const primer_t *pr = (const primer_t *)user;
    (void)x;
    (void)mode;
    *s = fabs(pr->c1 - pr->c2 * t) - 1.0;
    return OGK_OK;
}

/* Double integrator x'' = mode with a state-dependent switch S = sin(x). */
static ogk_status push_rhs(void *user, ogk_real_t t, const ogk_real_t *x, int mode, ogk_real_t *xdot)
{
    (void)user;
    (void)t;
    xdot[0] = x[1];
    xdot[1] = (double)mode;
    return OGK_OK;
}

static ogk_status sin_x_switch(void *user, ogk_real_t t, const ogk_real_t *x, int mode, ogk_real_t *s)
{
    (void)user;
    (void)t;
    (void)mode;
    *s = sin(x[0]);
    return OGK_OK;
}

static ogk_status sin_t_switch(void *user, ogk_real_t t, const ogk_real_t *x, int mode, ogk_real_t *s)
{
    (void)user;
    (void)x;
    (void)mode;
    *s = sin(20.0 * t);
    return OGK_OK;
}

static ogk_status jump_switch(void *user, ogk_real_t t, const ogk_real_t *x, int mode, ogk_real_t *s)
{
    (void)user;
    (void)x;
    (void)mode;
    *s = (t < 1.0) ? 1.0 : -1.0;
    return OGK_OK;
}

static ogk_status failing_rhs(void *user, ogk_real_t t, const ogk_real_t *x, int mode, ogk_real_t *xdot)
{
    (void)user;
    (void)x;
    (void)mode;
    xdot[0] = 1.0;
    return (t > 0.5) ? OGK_E_RANGE : OGK_OK;
}

static ogk_status nan_rhs(void *user, ogk_real_t t, const ogk_real_t *x, int mode, ogk_real_t *xdot)
{
    (void)user;
    (void)x;
    (void)mode;
    xdot[0] = (t > 0.5) ? NAN : 1.0;
    return OGK_OK;
}

static ogk_rk4_problem_t problem(size_t n, double h, ogk_rhs_fn rhs, ogk_switch_fn sw, void *user)
{
    ogk_rk4_problem_t p;
    memset(&p, 0, sizeof p);
    p.n = n;
    p.h = h;
    p.rhs = rhs;
    p.sw = sw;
    p.user = user;
    /* float: 16 eps of |S| ~ 1 and of t (two ulps at t = 10, the longest run) */
    p.s_tol = OGK_TEST_TOL(1e-12, 16.0 * FLT_EPSILON);
    p.t_tol = OGK_TEST_TOL(1e-14, 16.0 * FLT_EPSILON);
    return p;
}

static ogk_rk4_result_t res;

/* ---------------------------------------------------------------- tests */

/* req: OGK-CORE-013 */
static void test_single_step_is_taylor_polynomial(void **state)
{
    const ogk_real_t h = 0.1; /* the step as the kernel has it */
    ogk_rk4_problem_t p = problem(1u, h, growth, NULL, NULL);
    ogk_real_t x = 1.0;
    (void)state;
    OGK_ASSERT_STATUS(ogk_rk4_step(&p, 0.0, &x, h, 0, &x), OGK_OK);
    /* float: one ulp of x = 1.105 */
    OGK_ASSERT_NEAR(x, 1.0 + h + h * h / 2.0 + h * h * h / 6.0 + h * h * h * h / 24.0,
                    OGK_TEST_TOL(1e-16, 1.105 * FLT_EPSILON));
    OGK_ASSERT_STATUS(ogk_rk4_step(&p, 0.0, &x, 0.0, 0, &x), OGK_E_RANGE);
}

/* Error after one period of an e = 0.1 orbit (the exact state returns to the
 * start); halving the step must divide it by about 2^4 = 16. */
static double orbit_error(size_t steps)
{
    const double e = 0.1;
    const ogk_real_t x0[6] = {1.0 - e, 0.0, 0.0, 0.0, sqrt((1.0 + e) / (1.0 - e)), 0.0};
    ogk_real_t xf[6];
    double err = 0.0;
    size_t i;
    ogk_rk4_problem_t p = problem(6u, 2.0 * PI / (double)steps, two_body, NULL, NULL);
    if (ogk_rk4_propagate(&p, 0.0, x0, 0, 2.0 * PI, &res, xf, NULL) != OGK_OK) {
        return -1.0;
    }
    for (i = 0u; i < 6u; ++i) {
        err = fmax(err, fabs(xf[i] - x0[i]));
    }
    return err;
}

#if OGK_REAL_SINGLE
/* x'' = -x: x = (x, v), exact after one period 2 pi: back to (1, 0). */
static ogk_status oscillator(void *user, ogk_real_t t, const ogk_real_t *x, int mode, ogk_real_t *xdot)
{
    (void)user;
    (void)t;
    (void)mode;
    xdot[0] = x[1];
    xdot[1] = -x[0];
    return OGK_OK;
}

static double oscillator_error(size_t steps)
{
    const ogk_real_t x0[2] = {1.0, 0.0};
    ogk_real_t xf[2];
    ogk_rk4_problem_t p = problem(2u, 2.0 * PI / (double)steps, oscillator, NULL, NULL);
    if (ogk_rk4_propagate(&p, 0.0, x0, 0, 2.0 * PI, &res, xf, NULL) != OGK_OK) {
        return -1.0;
    }
    return fmax(fabs(xf[0] - 1.0), fabs(xf[1]));
}
#endif

/* req: OGK-CORE-013 */
static void test_fourth_order_convergence_two_body(void **state)
{
#if OGK_REAL_SINGLE
    /* In float the one-orbit error of the e = 0.1 orbit has a round-off floor
     * of about 5e-6 (measured: 5.0e-6 at 400 steps, 8.0e-6 at 800; double
     * 1.4e-8, 8.6e-10): the order is not visible there. It is on one period of
     * x'' = -x at 32 and 64 steps, whose truncation errors (7.7e-5, 4.7e-6)
     * stand far above float's round-off (float and double differ by 1e-7 at
     * 64 steps): ratio 16.2 (double 15.8), the same window. */
    double e1;
    double e2;
    (void)state;
    print_message("two-body one orbit (float, round-off floor): err(400) = %.3e, err(800) = %.3e\n",
                  orbit_error(400u), orbit_error(800u));
    e1 = oscillator_error(32u);
    e2 = oscillator_error(64u);
    assert_true(e1 > 0.0 && e2 > 0.0);
    print_message("oscillator one period: err(32) = %.3e, err(64) = %.3e, ratio = %.2f\n",
                  e1, e2, e1 / e2);
    assert_true(e1 / e2 > 14.5 && e1 / e2 < 17.5);
    assert_true(e2 < 1e-5);
    assert_int_equal(res.n_steps, 64u);
#else
    const double e1 = orbit_error(400u);
    const double e2 = orbit_error(800u);
    (void)state;
    assert_true(e1 > 0.0 && e2 > 0.0);
    print_message("two-body one orbit: err(400) = %.3e, err(800) = %.3e, ratio = %.2f\n",
                  e1, e2, e1 / e2);
    assert_true(e1 / e2 > 14.5 && e1 / e2 < 17.5);
    assert_true(e2 < 1e-6);
    assert_int_equal(res.n_steps, 800u);
#endif
}

/* req: OGK-CORE-014 */
static void test_bang_off_bang_double_integrator(void **state)
{
    primer_t pr = {3.0, 1.0};
    ogk_rk4_problem_t p = problem(2u, 0.3, fuel_di_rhs, fuel_di_switch, &pr);
    const ogk_real_t x0[2] = {0.0, 0.0};
    ogk_real_t xf[2];
    (void)state;
    OGK_ASSERT_STATUS(ogk_rk4_propagate(&p, 0.0, x0, 1, 6.0, &res, xf, NULL), OGK_OK);
    assert_int_equal(res.n_switches, 2u);
    /* Closed form: |3 - t| = 1 at t = 2 (off) and t = 4 (on). Float: the
     * root is where |S| <= s_tol or the bracket is below t_tol (16 eps each;
     * |S'| = 1), plus ulps of t (a few eps): 32 eps. */
    OGK_ASSERT_NEAR(res.sw[0].t, 2.0, OGK_TEST_TOL(1e-10, 32.0 * FLT_EPSILON));
    OGK_ASSERT_NEAR(res.sw[1].t, 4.0, OGK_TEST_TOL(1e-10, 32.0 * FLT_EPSILON));
    assert_int_equal(res.sw[0].mode_after, 0);
    assert_int_equal(res.sw[1].mode_after, 1);
    assert_int_equal(res.sw[0].how, OGK_SWITCH_BY_S_TOL);
    assert_true(fabs(res.sw[0].s) <= OGK_TEST_TOL(1e-12, 16.0 * FLT_EPSILON));
    /* u = -1 on [0,2], coast to 4, u = +1 to 6: x = -2 - 4 - 4 + 2 = -8, v = 0.
     * Float: each switch's error (32 eps) times the time left (<= 4), two
     * switches (256 eps), and 20 steps rounding |x| <= 8 (80 eps): 400 eps. */
    OGK_ASSERT_NEAR(xf[0], -8.0, OGK_TEST_TOL(1e-9, 400.0 * FLT_EPSILON));
    OGK_ASSERT_NEAR(xf[1], 0.0, OGK_TEST_TOL(1e-9, 400.0 * FLT_EPSILON));
    assert_int_equal(res.mode_final, 1);
    OGK_ASSERT_NEAR(res.t_reached, 6.0, 0.0);
}

/* req: OGK-CORE-014 */
static void test_state_dependent_switch_with_dense_output(void **state)
{
    /* x'' = mode, x(0) = 0.1, v(0) = 0, S = sin x: switches where x = k pi. */
    static ogk_real_t dt[64], dx[128];
    static uint8_t dmode[64];
    ogk_rk4_dense_t dense = {dt, dx, dmode, 64u, 0u};
    ogk_rk4_problem_t p = problem(2u, 0.25, push_rhs, sin_x_switch, NULL);
    const ogk_real_t x0[2] = {0.1, 0.0};
    const double t1 = sqrt(2.0 * (PI - 0.1));
    const double v1 = t1;
    const double t2 = t1 + PI / v1;
    const double tau3 = -v1 + sqrt(v1 * v1 + 2.0 * PI);
    const double t3 = t2 + tau3;
    const double v3 = v1 + tau3;
    const ogk_real_t tf = t3 + 0.5; /* the final time as the kernel has it */
    ogk_real_t xf[2];
    size_t k, i;
    (void)state;
    OGK_ASSERT_STATUS(ogk_rk4_propagate(&p, 0.0, x0, 1, tf, &res, xf, &dense), OGK_OK);
    assert_int_equal(res.n_switches, 3u);
    /* float: as above, |S'| = |v cos x| >= 2.4 at the roots */
    OGK_ASSERT_NEAR(res.sw[0].t, t1, OGK_TEST_TOL(1e-10, 32.0 * FLT_EPSILON));
    OGK_ASSERT_NEAR(res.sw[1].t, t2, OGK_TEST_TOL(1e-10, 32.0 * FLT_EPSILON));
    OGK_ASSERT_NEAR(res.sw[2].t, t3, OGK_TEST_TOL(1e-10, 32.0 * FLT_EPSILON));
    /* float: three switch errors (32 eps) times |v| (<= 3.5) and the time
     * left (<= 3), about 300 eps, and 25 steps rounding |x| <= 12 (150 eps) */
    OGK_ASSERT_NEAR(xf[0], 3.0 * PI + 0.5 * v3, OGK_TEST_TOL(1e-9, 500.0 * FLT_EPSILON));
    OGK_ASSERT_NEAR(xf[1], v3, OGK_TEST_TOL(1e-9, 500.0 * FLT_EPSILON));
    /* Dense output: grid nodes plus one node per switch, in time order, the
     * modes on each step consistent with the events. */
    assert_int_equal(dense.count, (size_t)ceil(tf / 0.25) + 1u + 3u);
    OGK_ASSERT_NEAR(dense.t[0], 0.0, 0.0);
    OGK_ASSERT_NEAR(dense.t[dense.count - 1u], tf, 0.0);
    for (k = 1u; k < dense.count; ++k) {
        assert_true(dense.t[k] > dense.t[k - 1u]);
    }
    for (i = 0u; i < res.n_switches; ++i) {
        const size_t node = res.sw[i].dense_index;
        OGK_ASSERT_NEAR(dense.t[node], res.sw[i].t, 0.0);
        assert_int_equal(dense.mode[node], (uint8_t)res.sw[i].mode_after);
        assert_int_equal(dense.mode[node - 1u], (uint8_t)(1 - res.sw[i].mode_after));
        /* float: |S| <= s_tol, or the bracket t_tol (16 eps) times |S'| <= 3.5 */
        OGK_ASSERT_NEAR(fabs(sin(dense.x[2u * node])), 0.0, OGK_TEST_TOL(1e-12, 64.0 * FLT_EPSILON));
    }
    OGK_ASSERT_NEAR(dense.x[2u * (dense.count - 1u)], xf[0], 0.0);
}

/* req: OGK-CORE-014 */
static void test_switch_overflow_is_an_error(void **state)
{
    ogk_rk4_problem_t p = problem(1u, 0.01, growth, sin_t_switch, NULL);
    const ogk_real_t x0[1] = {1.0};
    ogk_real_t xf[1];
    (void)state;
    /* sin(20 t) > 0 at the first step, then roots at k pi / 20: 63 in [0, 10]. */
    OGK_ASSERT_STATUS(ogk_rk4_propagate(&p, 0.0, x0, 1, 10.0, &res, xf, NULL),
                      OGK_E_SWITCH_OVERFLOW);
    assert_int_equal(res.n_switches, OGK_RK4_MAX_SWITCHES);
    /* float: s_tol / |S'| (|S'| = 20) or the bracket t_tol (16 eps), plus two ulps of t = 10 (16 eps) */
    OGK_ASSERT_NEAR(res.t_reached, (double)(OGK_RK4_MAX_SWITCHES + 1u) * PI / 20.0,
                    OGK_TEST_TOL(1e-9, 32.0 * FLT_EPSILON));
    OGK_ASSERT_NEAR(xf[0], exp(res.t_reached), 1e-6 * exp(res.t_reached));
}

/* req: OGK-CORE-014 */
static void test_discontinuous_switch_stops_on_time_tolerance(void **state)
{
    ogk_rk4_problem_t p = problem(1u, 0.3, growth, jump_switch, NULL);
    const ogk_real_t x0[1] = {1.0};
    ogk_real_t xf[1];
    (void)state;
    p.t_tol = 1e-9;
    OGK_ASSERT_STATUS(ogk_rk4_propagate(&p, 0.0, x0, 1, 2.0, &res, xf, NULL), OGK_OK);
    assert_int_equal(res.n_switches, 1u);
    assert_int_equal(res.sw[0].how, OGK_SWITCH_BY_TIME_TOL);
    assert_true(res.sw[0].t >= 1.0 && res.sw[0].t - 1.0 <= 1e-9);
}

/* req: OGK-CORE-013 OGK-CORE-021 */
static void test_bad_inputs(void **state)
{
    ogk_rk4_problem_t p = problem(1u, 0.1, growth, NULL, NULL);
    static ogk_real_t dt[4], dx[4];
    static uint8_t dmode[4];
    ogk_rk4_dense_t small = {dt, dx, dmode, 4u, 0u};
    ogk_real_t x0[1] = {1.0};
    ogk_real_t xf[1];
    (void)state;
    OGK_ASSERT_STATUS(ogk_rk4_propagate(NULL, 0.0, x0, 0, 1.0, &res, xf, NULL), OGK_E_NULL);
    OGK_ASSERT_STATUS(ogk_rk4_propagate(&p, 0.0, NULL, 0, 1.0, &res, xf, NULL), OGK_E_NULL);
    OGK_ASSERT_STATUS(ogk_rk4_propagate(&p, 0.0, x0, 0, 0.0, &res, xf, NULL), OGK_E_RANGE);
    OGK_ASSERT_STATUS(ogk_rk4_propagate(&p, 0.0, x0, 2, 1.0, &res, xf, NULL), OGK_E_RANGE);
    OGK_ASSERT_STATUS(ogk_rk4_propagate(&p, 0.0, x0, 0, NAN, &res, xf, NULL), OGK_E_NONFINITE);
    x0[0] = INFINITY;
    OGK_ASSERT_STATUS(ogk_rk4_propagate(&p, 0.0, x0, 0, 1.0, &res, xf, NULL), OGK_E_NONFINITE);
    x0[0] = 1.0;
    OGK_ASSERT_STATUS(ogk_rk4_propagate(&p, 0.0, x0, 0, 1.0, &res, xf, &small), OGK_E_DIM);
    p.n = 0u;
    OGK_ASSERT_STATUS(ogk_rk4_propagate(&p, 0.0, x0, 0, 1.0, &res, xf, NULL), OGK_E_DIM);
    p.n = OGK_RK4_MAX_STATE + 1u;
    OGK_ASSERT_STATUS(ogk_rk4_propagate(&p, 0.0, x0, 0, 1.0, &res, xf, NULL), OGK_E_DIM);
    p = problem(1u, -0.1, growth, NULL, NULL);
    OGK_ASSERT_STATUS(ogk_rk4_propagate(&p, 0.0, x0, 0, 1.0, &res, xf, NULL), OGK_E_RANGE);
    p = problem(1u, 1e-9, growth, NULL, NULL);
    OGK_ASSERT_STATUS(ogk_rk4_propagate(&p, 0.0, x0, 0, 1.0, &res, xf, NULL), OGK_E_STEP_LIMIT);
    p = problem(1u, 0.1, growth, sin_t_switch, NULL);
    p.t_tol = 0.0;
    OGK_ASSERT_STATUS(ogk_rk4_propagate(&p, 0.0, x0, 0, 1.0, &res, xf, NULL), OGK_E_RANGE);
}

/* req: OGK-CORE-013 */
static void test_callback_failure_and_nan_stop_cleanly(void **state)
{
    ogk_rk4_problem_t p = problem(1u, 0.1, failing_rhs, NULL, NULL);
    const ogk_real_t x0[1] = {0.0};
    ogk_real_t xf[1];
    (void)state;
    OGK_ASSERT_STATUS(ogk_rk4_propagate(&p, 0.0, x0, 0, 1.0, &res, xf, NULL), OGK_E_CALLBACK);
    assert_true(res.t_reached <= 0.5 && res.t_reached > 0.3);
    OGK_ASSERT_NEAR(xf[0], res.t_reached, 1e-12); /* last good state returned */
    p.rhs = nan_rhs;
    OGK_ASSERT_STATUS(ogk_rk4_propagate(&p, 0.0, x0, 0, 1.0, &res, xf, NULL), OGK_E_NONFINITE);
    assert_true(isfinite(xf[0]));
}

/* req: OGK-CORE-013 */
static void test_step_count_has_no_sliver(void **state)
{
    /* 1.0 / 0.1 is not exactly 10 in binary: still 10 steps, none tiny. */
    ogk_rk4_problem_t p = problem(1u, 0.1, growth, NULL, NULL);
    const ogk_real_t x0[1] = {1.0};
    ogk_real_t xf[1];
    (void)state;
    OGK_ASSERT_STATUS(ogk_rk4_propagate(&p, 0.0, x0, 0, 1.0, &res, xf, NULL), OGK_OK);
    assert_int_equal(res.n_steps, 10u);
    assert_int_equal(res.n_rhs, 40u);
    OGK_ASSERT_NEAR(xf[0], exp(1.0), 3e-6);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_single_step_is_taylor_polynomial),
        cmocka_unit_test(test_fourth_order_convergence_two_body),
        cmocka_unit_test(test_bang_off_bang_double_integrator),
        cmocka_unit_test(test_state_dependent_switch_with_dense_output),
        cmocka_unit_test(test_switch_overflow_is_an_error),
        cmocka_unit_test(test_discontinuous_switch_stops_on_time_tolerance),
        cmocka_unit_test(test_bad_inputs),
        cmocka_unit_test(test_callback_failure_and_nan_stop_cleanly),
        cmocka_unit_test(test_step_count_has_no_sliver),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
