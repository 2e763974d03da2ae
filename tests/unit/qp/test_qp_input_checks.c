/* test_qp_input_checks.c -- MC/DC of ogk_qp_solve's input checks (docs/evidence/coverage.md, "MC/DC"): an
 * inequality block with A_in but no b_in, and lower bounds without upper ones, each deciding
 * alone; an inconsistent first equality row and a first Cholesky panel that fails, each ending
 * its loop; the solutions against their closed forms. */
#include "ogk_test.h"

#include <string.h>

#include "ogk/qp.h"

static ogk_qp_workspace_t ws;

/* min 1/2 |x|^2 - (2, 3) . x: the unconstrained minimiser is (2, 3). */
static const ogk_real_t H[4] = {1.0, 0.0, 0.0, 1.0};
static const ogk_real_t G[2] = {-2.0, -3.0};

/* min 1/2 x'Hx + g'x over two variables, no constraint yet: each test adds its own. */
static ogk_qp_problem_t two_variable_problem(void)
{
    ogk_qp_problem_t p;
    (void)memset(&p, 0, sizeof p);
    p.n = 2u;
    p.H = H;
    p.g = G;
    return p;
}

/* req: OGK-CORE-018 OGK-CORE-021 */
static void test_inequalities_without_b_in(void **state)
{
    const ogk_real_t a_in[2] = {1.0, 1.0};
    ogk_qp_problem_t p;
    ogk_qp_solution_t sol;
    (void)state;
    p = two_variable_problem();
    p.m_in = 1u;
    p.A_in = a_in;
    p.b_in = NULL;
    OGK_ASSERT_STATUS(ogk_qp_solve(&ws, &p, &sol), OGK_E_NULL);
}

/* lb = (0, 3.5), no upper bounds: x = (2, 3.5) (the second bound active, multiplier
 * z = (H x + g)_2 = 0.5), objective 1/2 (4 + 12.25) - 4 - 10.5 = -6.375. */
/* req: OGK-CORE-018 */
static void test_lower_bounds_only(void **state)
{
    const ogk_real_t lb[2] = {0.0, 3.5};
    ogk_qp_problem_t p;
    ogk_qp_solution_t sol;
    (void)state;
    p = two_variable_problem();
    p.lb = lb;
    p.ub = NULL;
    OGK_ASSERT_STATUS(ogk_qp_solve(&ws, &p, &sol), OGK_OK);
    OGK_ASSERT_NEAR(sol.x[0], 2.0, 1e-14);
    OGK_ASSERT_NEAR(sol.x[1], 3.5, 1e-14);
    OGK_ASSERT_NEAR(sol.z_lb[1], 0.5, 1e-14);
    OGK_ASSERT_NEAR(sol.z_lb[0], 0.0, 0.0);
    OGK_ASSERT_NEAR(sol.objective, -6.375, 1e-14);
}

/* A zero first equality row with b = 1 (0 . x = 1 has no solution) before a regular one:
 * OGK_E_INFEASIBLE from the first row. */
/* req: OGK-CORE-018 */
static void test_inconsistent_zero_equality_first(void **state)
{
    const ogk_real_t a_eq[4] = {0.0, 0.0, 1.0, 0.0};
    const ogk_real_t b_eq[2] = {1.0, 0.0};
    ogk_qp_problem_t p;
    ogk_qp_solution_t sol;
    (void)state;
    p = two_variable_problem();
    p.m_eq = 2u;
    p.A_eq = a_eq;
    p.b_eq = b_eq;
    OGK_ASSERT_STATUS(ogk_qp_solve(&ws, &p, &sol), OGK_E_INFEASIBLE);
    /* with b = 0 the zero row holds for every x (0 . x = 0): x_1 = 0, x_2 free: (0, 3) */
    {
        const ogk_real_t b_ok[2] = {0.0, 0.0};
        p.b_eq = b_ok;
        OGK_ASSERT_STATUS(ogk_qp_solve(&ws, &p, &sol), OGK_OK);
        OGK_ASSERT_NEAR(sol.x[0], 0.0, 1e-14);
        OGK_ASSERT_NEAR(sol.x[1], 3.0, 1e-14);
    }
}

/* A 5 x 5 H (more than one panel of four pivot rows) with a negative first pivot: not
 * positive definite, OGK_E_NOT_POSDEF from the first panel. */
/* req: OGK-CORE-018 */
static void test_not_posdef_in_first_panel(void **state)
{
    ogk_real_t h5[25];
    const ogk_real_t g5[5] = {1.0, 1.0, 1.0, 1.0, 1.0};
    ogk_qp_problem_t p;
    ogk_qp_solution_t sol;
    size_t i;
    (void)state;
    (void)memset(h5, 0, sizeof h5);
    for (i = 0u; i < 5u; ++i) {
        h5[(i * 5u) + i] = 1.0;
    }
    h5[0] = -1.0;
    (void)memset(&p, 0, sizeof p);
    p.n = 5u;
    p.H = h5;
    p.g = g5;
    OGK_ASSERT_STATUS(ogk_qp_solve(&ws, &p, &sol), OGK_E_NOT_POSDEF);
    /* positive definite again: x = -H^-1 g = -g */
    h5[0] = 1.0;
    OGK_ASSERT_STATUS(ogk_qp_solve(&ws, &p, &sol), OGK_OK);
    for (i = 0u; i < 5u; ++i) {
        OGK_ASSERT_NEAR(sol.x[i], -1.0, 1e-14);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_inequalities_without_b_in),
        cmocka_unit_test(test_lower_bounds_only),
        cmocka_unit_test(test_inconsistent_zero_equality_first),
        cmocka_unit_test(test_not_posdef_in_first_panel),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
