/* test_rk4_linalg_failures.c -- RK4 and linear-algebra paths the other tests leave unrun (make
 * coverage, docs/evidence/coverage.md): a right-hand side or switching function failing at every one of
 * its calls in turn (each RK4 stage, the switch evaluation at t0, inside the bisection), the
 * argument rejections of ogk_rk4_step and ogk_rk4_propagate, and factorizations that are not held
 * (ogk_lu_t / ogk_chol_t with n out of range or a corrupted permutation). */
#include "ogk_test.h"

#include <string.h>

#include "ogk/linalg.h"
#include "ogk/rk4.h"

typedef struct {
    unsigned rhs_calls;
    unsigned rhs_fail_at; /* 0: never */
    unsigned sw_calls;
    unsigned sw_fail_at;  /* 0: never */
} counter_t;

static ogk_status rhs_decay(void *user, ogk_real_t t, const ogk_real_t *x, int mode, ogk_real_t *xdot)
{
    counter_t *c = (counter_t *)user;
    (void)t;
    c->rhs_calls += 1u;
    if (c->rhs_calls == c->rhs_fail_at) {
        return OGK_E_CALLBACK;
    }
    xdot[0] = (mode != 0) ? -x[0] : x[0];
    return OGK_OK;
}

/* S = t - 0.37: one switch inside the second step of h = 0.25. */
static ogk_status sw_time(void *user, ogk_real_t t, const ogk_real_t *x, int mode, ogk_real_t *s)
{
    counter_t *c = (counter_t *)user;
    (void)x;
    (void)mode;
    c->sw_calls += 1u;
    if (c->sw_calls == c->sw_fail_at) {
        return OGK_E_CALLBACK;
    }
    *s = t - 0.37;
    return OGK_OK;
}

static ogk_rk4_problem_t problem(counter_t *c, int with_switch)
{
    ogk_rk4_problem_t p;
    memset(&p, 0, sizeof p);
    p.n = 1u;
    p.h = 0.25;
    p.rhs = rhs_decay;
    p.sw = with_switch ? sw_time : NULL;
    p.user = c;
    p.s_tol = 1e-12;
    p.t_tol = 1e-9;
    return p;
}

/* req: OGK-CORE-013 OGK-CORE-021 */
static void test_step_rejections_and_stage_failures(void **state)
{
    counter_t c;
    ogk_rk4_problem_t p;
    const ogk_real_t x[1] = {1.0};
    ogk_real_t xn[1];
    unsigned k;
    (void)state;
    memset(&c, 0, sizeof c);
    p = problem(&c, 0);
    p.h = -1.0;
    OGK_ASSERT_STATUS(ogk_rk4_step(&p, 0.0, x, 0.1, 1, xn), OGK_E_RANGE); /* bad problem */
    p = problem(&c, 0);
    OGK_ASSERT_STATUS(ogk_rk4_step(&p, 0.0, NULL, 0.1, 1, xn), OGK_E_NULL);
    OGK_ASSERT_STATUS(ogk_rk4_step(&p, 0.0, x, 0.1, 1, NULL), OGK_E_NULL);
    OGK_ASSERT_STATUS(ogk_rk4_step(&p, NAN, x, 0.1, 1, xn), OGK_E_NONFINITE);
    OGK_ASSERT_STATUS(ogk_rk4_step(&p, 0.0, x, INFINITY, 1, xn), OGK_E_NONFINITE);
    for (k = 1u; k <= 4u; ++k) { /* each of the four stages failing */
        memset(&c, 0, sizeof c);
        c.rhs_fail_at = k;
        OGK_ASSERT_STATUS(ogk_rk4_step(&p, 0.0, x, 0.1, 1, xn), OGK_E_CALLBACK);
    }
    memset(&c, 0, sizeof c);
    OGK_ASSERT_STATUS(ogk_rk4_step(&p, 0.0, x, 0.1, 1, xn), OGK_OK);
    OGK_ASSERT_REL(xn[0], exp(-0.1), 1e-6, 0.0);
}

/* req: OGK-CORE-013 */
static void test_propagate_fails_at_every_callback(void **state)
{
    counter_t c;
    ogk_rk4_problem_t p;
    ogk_rk4_result_t res;
    const ogk_real_t x0[1] = {1.0};
    ogk_real_t xf[1];
    unsigned rhs_total;
    unsigned sw_total;
    unsigned k;
    (void)state;
    memset(&c, 0, sizeof c);
    p = problem(&c, 1);
    OGK_ASSERT_STATUS(ogk_rk4_propagate(&p, 0.0, NULL, 1, 1.0, &res, xf, NULL), OGK_E_NULL);
    {
        ogk_rk4_dense_t d;
        memset(&d, 0, sizeof d); /* buffers missing */
        OGK_ASSERT_STATUS(ogk_rk4_propagate(&p, 0.0, x0, 1, 1.0, &res, xf, &d), OGK_E_NULL);
    }
    OGK_ASSERT_STATUS(ogk_rk4_propagate(&p, 0.0, x0, 1, 1.0, &res, xf, NULL), OGK_OK);
    assert_int_equal(res.n_switches, 1u);
    rhs_total = c.rhs_calls;
    sw_total = c.sw_calls;
    assert_true(rhs_total > 16u && sw_total > 3u); /* bisection ran */
    for (k = 1u; k <= rhs_total; ++k) {
        memset(&c, 0, sizeof c);
        c.rhs_fail_at = k;
        OGK_ASSERT_STATUS(ogk_rk4_propagate(&p, 0.0, x0, 1, 1.0, &res, xf, NULL), OGK_E_CALLBACK);
        assert_true(isfinite(res.t_reached) && res.t_reached < 1.0);
    }
    for (k = 1u; k <= sw_total; ++k) { /* k = 1: the evaluation at t0 */
        memset(&c, 0, sizeof c);
        c.sw_fail_at = k;
        OGK_ASSERT_STATUS(ogk_rk4_propagate(&p, 0.0, x0, 1, 1.0, &res, xf, NULL), OGK_E_CALLBACK);
        assert_true(isfinite(xf[0]));
    }
}

/* req: OGK-CORE-011 OGK-CORE-021 */
static void test_factorizations_not_held(void **state)
{
    ogk_lu_t lu;
    ogk_chol_t ch;
    const ogk_real_t A[4] = {4.0, 1.0, 1.0, 3.0};
    const ogk_real_t b[2] = {1.0, 2.0};
    ogk_real_t x[2];
    (void)state;
    OGK_ASSERT_STATUS(ogk_lu_factor(&lu, A, 2u), OGK_OK);
    OGK_ASSERT_STATUS(ogk_lu_solve(&lu, b, x), OGK_OK);
    lu.perm[1] = 7u; /* overwritten permutation */
    OGK_ASSERT_STATUS(ogk_lu_solve(&lu, b, x), OGK_E_NOT_INIT);
    OGK_ASSERT_STATUS(ogk_lu_factor(&lu, A, 2u), OGK_OK);
    lu.n = OGK_LA_MAX_N + 1u;
    OGK_ASSERT_STATUS(ogk_lu_solve(&lu, b, x), OGK_E_DIM);
    OGK_ASSERT_STATUS(ogk_chol_factor(&ch, A, 2u), OGK_OK);
    ch.n = OGK_LA_MAX_N + 1u;
    OGK_ASSERT_STATUS(ogk_chol_solve(&ch, b, x), OGK_E_DIM);
    OGK_ASSERT_STATUS(ogk_chol_factor(&ch, A, 2u), OGK_OK);
    {
        const ogk_real_t bad[2] = {NAN, 0.0};
        OGK_ASSERT_STATUS(ogk_chol_solve(&ch, bad, x), OGK_E_NONFINITE);
    }
    OGK_ASSERT_STATUS(ogk_chol_solve(&ch, b, x), OGK_OK);
    OGK_ASSERT_REL(4.0 * x[0] + x[1], 1.0, 1e-14, 1.0);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_step_rejections_and_stage_failures),
        cmocka_unit_test(test_propagate_fails_at_every_callback),
        cmocka_unit_test(test_factorizations_not_held),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
