/* test_rk4_edge_cases.c -- paths of rk4.c that the other tests leave unrun (make coverage,
 * docs/evidence/coverage.md; moved from test_gate_misc.c):
 *  - RK4: each problem check, non-finite arguments, a switching function that returns NaN, a
 *    step shorter than the slop (one step), S = 0 everywhere (no event), a bisection that
 *    runs to the last bit of the bracket, a switch located at the very end of a step, and the
 *    dense output filling up exactly at a switch node. */
#include "ogk_test.h"

#include <float.h>
#include <string.h>

#include "ogk/rk4.h"

/* ------------------------------------------------------------------ rk4 */

/* mode 1: x' = -x, mode 0: x' = +x */
static ogk_status rhs_decay(void *user, ogk_real_t t, const ogk_real_t *x, int mode, ogk_real_t *xdot)
{
    (void)user;
    (void)t;
    xdot[0] = (mode != 0) ? -x[0] : x[0];
    return OGK_OK;
}

/* S = t - t_root, with t_root in *user */
static ogk_status sw_root(void *user, ogk_real_t t, const ogk_real_t *x, int mode, ogk_real_t *s)
{
    const double *t_root = (const double *)user;
    (void)x;
    (void)mode;
    *s = t - *t_root;
    return OGK_OK;
}

/* S = (t - t_root) - 1e-17: t - t_root is a multiple of 2^-54 for t, t_root in [0.25, 0.5),
 * so S is never exactly 0 on a double there */
static ogk_status sw_root_off(void *user, ogk_real_t t, const ogk_real_t *x, int mode, ogk_real_t *s)
{
    const double *t_root = (const double *)user;
    (void)x;
    (void)mode;
    *s = (t - *t_root) - 1e-17;
    return OGK_OK;
}

static ogk_status sw_zero(void *user, ogk_real_t t, const ogk_real_t *x, int mode, ogk_real_t *s)
{
    (void)user;
    (void)t;
    (void)x;
    (void)mode;
    *s = 0.0;
    return OGK_OK;
}

static ogk_status sw_nan(void *user, ogk_real_t t, const ogk_real_t *x, int mode, ogk_real_t *s)
{
    (void)user;
    (void)t;
    (void)x;
    (void)mode;
    *s = NAN;
    return OGK_OK;
}

static ogk_rk4_problem_t problem(ogk_switch_fn sw, double *t_root)
{
    ogk_rk4_problem_t p;
    (void)memset(&p, 0, sizeof p);
    p.n = 1u;
    p.h = 0.25;
    p.rhs = rhs_decay;
    p.sw = sw;
    p.user = t_root;
    p.s_tol = 1e-12;
    p.t_tol = 1e-9;
    return p;
}

/* req: OGK-CORE-013 OGK-CORE-021 */
static void test_rk4_problem_and_argument_checks(void **state)
{
    double t_root = 0.37;
    ogk_rk4_problem_t p;
    ogk_rk4_result_t res;
    const ogk_real_t x0[1] = {1.0};
    ogk_real_t xf[1] = {-7.0};
    ogk_real_t xn[1] = {-7.0};
    ogk_real_t dt_buf[4];
    ogk_real_t dx_buf[4];
    uint8_t dm_buf[4];
    ogk_rk4_dense_t d;
    unsigned k;
    (void)state;
    for (k = 0u; k < 5u; ++k) {
        p = problem(sw_root, &t_root);
        switch (k) {
        case 0u: p.rhs = NULL; break;
        case 1u: p.h = NAN; break;
        case 2u: p.s_tol = NAN; break;
        case 3u: p.s_tol = -1e-12; break;
        default: p.t_tol = INFINITY; break;
        }
        OGK_ASSERT_STATUS(ogk_rk4_propagate(&p, 0.0, x0, 1, 1.0, &res, xf, NULL),
                          (k == 0u) ? OGK_E_NULL : OGK_E_RANGE);
        OGK_ASSERT_STATUS(ogk_rk4_step(&p, 0.0, x0, 0.1, 1, xn),
                          (k == 0u) ? OGK_E_NULL : OGK_E_RANGE);
    }
    p = problem(sw_root, &t_root);
    {
        const ogk_real_t bad[1] = {NAN};
        OGK_ASSERT_STATUS(ogk_rk4_step(&p, 0.0, bad, 0.1, 1, xn), OGK_E_NONFINITE);
    }
    {
        /* two states, the first one NaN: found without looking further */
        const ogk_real_t bad2[2] = {NAN, 0.0};
        ogk_real_t xn2[2] = {-7.0, -7.0};
        p.n = 2u;
        OGK_ASSERT_STATUS(ogk_rk4_step(&p, 0.0, bad2, 0.1, 1, xn2), OGK_E_NONFINITE);
        OGK_ASSERT_NEAR(xn2[0], -7.0, 0.0);
        p.n = 1u;
    }
    OGK_ASSERT_STATUS(ogk_rk4_propagate(&p, 0.0, x0, 1, 1.0, NULL, xf, NULL), OGK_E_NULL);
    OGK_ASSERT_STATUS(ogk_rk4_propagate(&p, 0.0, x0, 1, 1.0, &res, NULL, NULL), OGK_E_NULL);
    d.t = dt_buf;
    d.x = NULL;
    d.mode = dm_buf;
    d.capacity = 4u;
    d.count = 0u;
    OGK_ASSERT_STATUS(ogk_rk4_propagate(&p, 0.0, x0, 1, 1.0, &res, xf, &d), OGK_E_NULL);
    d.x = dx_buf;
    d.mode = NULL;
    OGK_ASSERT_STATUS(ogk_rk4_propagate(&p, 0.0, x0, 1, 1.0, &res, xf, &d), OGK_E_NULL);
    OGK_ASSERT_STATUS(ogk_rk4_propagate(&p, NAN, x0, 1, 1.0, &res, xf, NULL), OGK_E_NONFINITE);
    OGK_ASSERT_NEAR(xf[0], -7.0, 0.0);
    OGK_ASSERT_NEAR(xn[0], -7.0, 0.0);
    /* a switching function that returns NaN at t0 */
    p = problem(sw_nan, NULL);
    OGK_ASSERT_STATUS(ogk_rk4_propagate(&p, 0.0, x0, 1, 1.0, &res, xf, NULL), OGK_E_NONFINITE);
    OGK_ASSERT_NEAR(res.t_reached, 0.0, 0.0);
}

/* req: OGK-CORE-014 */
static void test_rk4_degenerate_grids_and_switches(void **state)
{
    double t_root = 0.37;
    ogk_rk4_problem_t p;
    ogk_rk4_result_t res;
    const ogk_real_t x0[1] = {1.0};
    ogk_real_t xf[1];
    (void)state;
    /* tf - t0 far below one step h (ratio under the slop): one step of tf - t0 */
    p = problem(NULL, NULL);
    p.h = 1.0;
    OGK_ASSERT_STATUS(ogk_rk4_propagate(&p, 0.0, x0, 1, 1e-12, &res, xf, NULL), OGK_OK);
    assert_int_equal(res.n_steps, 1u);
    OGK_ASSERT_NEAR(res.t_reached, (ogk_real_t)1e-12, 0.0); /* the end time as the kernel has it */
    OGK_ASSERT_REL(xf[0], 1.0 - 1e-12, OGK_TEST_TOL(1e-15, 4.5 * FLT_EPSILON), 0.0);
    /* S identically 0: no sign to leave, so no event; plain decay */
    p = problem(sw_zero, NULL);
    OGK_ASSERT_STATUS(ogk_rk4_propagate(&p, 0.0, x0, 1, 1.0, &res, xf, NULL), OGK_OK);
    assert_int_equal(res.n_switches, 0u);
    assert_int_equal(res.mode_final, 1);
    OGK_ASSERT_REL(xf[0], exp(-1.0), 1e-4, 0.0);
    /* S never exactly 0 on a double and s_tol = 0, t_tol = 1e-300 below any bracket: the
     * bisection runs to the last bit of the bracket and accepts its far end. Float: S is
     * never 0 either (0.37 is not a float), t_tol = 1e-30 (1e-300 is 0 there), and the last
     * bit of a bracket of 0.25 at 0.37 is 2^-25 (23 halvings; double 2^-54, 52) */
    t_root = 0.37;
    p = problem(sw_root_off, &t_root);
    p.s_tol = 0.0;
    p.t_tol = OGK_TEST_PICK(1e-300, 1e-30);
    OGK_ASSERT_STATUS(ogk_rk4_propagate(&p, 0.0, x0, 1, 1.0, &res, xf, NULL), OGK_OK);
    assert_int_equal(res.n_switches, 1u);
    assert_int_equal(res.sw[0].how, OGK_SWITCH_BY_TIME_TOL);
    assert_true(res.sw[0].bisections > OGK_TEST_TOL(40u, 20u));
    assert_true(res.sw[0].s > 0.0); /* the far end: S already of the new sign */
    /* 2e-16 is 3.6 ulps of 0.37 (2^-54); float: 4 ulps (2^-25 each) */
    OGK_ASSERT_NEAR(res.sw[0].t, 0.37, OGK_TEST_TOL(2e-16, FLT_EPSILON));
    /* root 1e-12 before the end of the second step (t = 0.5), t_tol = 1e-9: the bracket
     * keeps its upper end, and the switch is accepted at the step's end exactly */
    t_root = 0.5 - 1e-12;
    p = problem(sw_root, &t_root);
    p.s_tol = 0.0;
    OGK_ASSERT_STATUS(ogk_rk4_propagate(&p, 0.0, x0, 1, 1.0, &res, xf, NULL), OGK_OK);
    assert_int_equal(res.n_switches, 1u);
    OGK_ASSERT_NEAR(res.sw[0].t, 0.5, 0.0);
    assert_int_equal(res.sw[0].mode_after, 0);
    assert_int_equal(res.mode_final, 0);
    OGK_ASSERT_NEAR(res.t_reached, 1.0, 0.0);
    /* decay for 0.5, growth for 0.5: back to x0 (RK4 error at h = 0.25) */
    OGK_ASSERT_REL(xf[0], 1.0, 1e-4, 0.0);
}

/* The dense output has room for t0 and the first step's end only: it runs out at the
 * switch node inside the second step. */
/* req: OGK-CORE-014 */
static void test_rk4_dense_full_at_switch(void **state)
{
    double t_root = 0.37;
    ogk_rk4_problem_t p = problem(sw_root, &t_root);
    ogk_rk4_result_t res;
    ogk_rk4_dense_t d;
    const ogk_real_t x0[1] = {1.0};
    ogk_real_t xf[1];
    ogk_real_t dt_buf[2];
    ogk_real_t dx_buf[2];
    uint8_t dm_buf[2];
    (void)state;
    d.t = dt_buf;
    d.x = dx_buf;
    d.mode = dm_buf;
    d.capacity = 2u;
    d.count = 0u;
    OGK_ASSERT_STATUS(ogk_rk4_propagate(&p, 0.0, x0, 1, 1.0, &res, xf, &d), OGK_E_DIM);
    assert_int_equal(d.count, 2u);
    OGK_ASSERT_NEAR(dt_buf[1], 0.25, 0.0);
    assert_int_equal(res.n_switches, 1u);
    /* stopped at the switch; float: t_tol = 1e-9 is below float's resolution, so the
     * bracket runs to its last bit: 4 ulps of 0.37 */
    OGK_ASSERT_NEAR(res.t_reached, 0.37, OGK_TEST_TOL(1e-9, FLT_EPSILON));
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_rk4_problem_and_argument_checks),
        cmocka_unit_test(test_rk4_degenerate_grids_and_switches),
        cmocka_unit_test(test_rk4_dense_full_at_switch),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
