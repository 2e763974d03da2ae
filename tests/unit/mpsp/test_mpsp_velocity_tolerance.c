/* test_mpsp_velocity_tolerance.c -- MC/DC of ogk_mpsp's convergence test (docs/evidence/coverage.md, "MC/DC"): the
 * velocity tolerance decides alone. With the position tolerance wide open (1 LU) and a target
 * that differs from the flown nominal in velocity only, the first Newton iterate is within tol_r
 * but not tol_v; the solve must go on until the velocity is within tol_v, which is checked by
 * flying the returned command with ogk_mpsp_propagate (not by the solver's own figures). */
#include "ogk_test.h"

#include <string.h>

#include "ogk/mpsp.h"
#include "mpsp_fixture.h"

static ogk_mpsp_t ctx;
static ogk_mpsp_config_t cfg;
static ogk_mpsp_result_t res;

/* req: OGK-MPSP-005 */
static void test_velocity_tolerance_decides_alone(void **state)
{
    ogk_mpsp_prop_t prop;
    ogk_real_t target[6]; /* handed to the kernel: its type */
    double dv = 0.0;
    size_t i;
    (void)state;
    OGK_ASSERT_STATUS(mpsp_fixture_config(&cfg, 20u, 30u), OGK_OK);
    OGK_ASSERT_STATUS(ogk_mpsp_init(&ctx, &cfg), OGK_OK);
    /* the nominal weights flown: their r(tf), v(tf) become the target's, v_y moved by 2e-3 */
    OGK_ASSERT_STATUS(ogk_mpsp_propagate(&ctx, w3, 0.0, x0_3d, 1.0, &prop), OGK_OK);
    (void)memcpy(target, prop.x_f, sizeof target);
    target[4] += 2.0e-3;
    cfg.tol_r = 1.0;
    cfg.tol_v = MPSP_FX_TOL;
    cfg.tol_lambda_m = MPSP_FX_TOL;
    (void)memcpy(cfg.r_f, target, 3u * sizeof target[0]);
    (void)memcpy(cfg.v_f, &target[3], 3u * sizeof target[0]);
    OGK_ASSERT_STATUS(ogk_mpsp_init(&ctx, &cfg), OGK_OK);
    OGK_ASSERT_STATUS(ogk_mpsp_solve(&ctx, x0_3d, 1.0, NULL, &res), OGK_OK);
    assert_int_equal(res.converged, 1);
    assert_true(res.newton_iterations >= 1u);
    OGK_ASSERT_STATUS(ogk_mpsp_propagate(&ctx, res.weights, res.lambda_m0, x0_3d, 1.0, &prop), OGK_OK);
    for (i = 3u; i < 6u; ++i) {
        dv += (prop.x_f[i] - target[i]) * (prop.x_f[i] - target[i]);
    }
    assert_true(sqrt(dv) <= MPSP_FX_TOL);
    OGK_ASSERT_NEAR(prop.x_f[7], 0.0, MPSP_FX_TOL);
    OGK_ASSERT_NEAR(sqrt(dv), res.err_v, 1.0e-13);
}

/* The fixture made consistent: its flown w3 gives the target r(tf), v(tf), and MPSP brings
 * lambda_m(tf) to 0; the result becomes the nominal weights. */
static void consistent_nominal(ogk_mpsp_config_t *c)
{
    ogk_mpsp_prop_t prop;
    OGK_ASSERT_STATUS(mpsp_fixture_config(c, 20u, 30u), OGK_OK);
    OGK_ASSERT_STATUS(ogk_mpsp_init(&ctx, c), OGK_OK);
    OGK_ASSERT_STATUS(ogk_mpsp_propagate(&ctx, w3, 0.0, x0_3d, 1.0, &prop), OGK_OK);
    (void)memcpy(c->r_f, prop.x_f, sizeof c->r_f);
    (void)memcpy(c->v_f, &prop.x_f[3], sizeof c->v_f);
    OGK_ASSERT_STATUS(ogk_mpsp_init(&ctx, c), OGK_OK);
    OGK_ASSERT_STATUS(ogk_mpsp_solve(&ctx, x0_3d, 1.0, NULL, &res), OGK_OK);
    (void)memcpy(c->weights_nom, res.weights, sizeof c->weights_nom);
    c->lambda_m0_nom = res.lambda_m0;
}

/* Algorithm 2's closing step below delta_tau_min is still taken (lines 17-19 as documented in
 * mpsp.c): delta_tau_0 = 0.75, delta_tau_min = 0.3, Delta_max = 0.0085 and a target offset of
 * |dY| = 0.00992. The direct loop is refused (0.00992 > 0.0085), tau = 0.75 is within reach (0.00744),
 * then the closing step dtau = 0.25 <= delta_tau_min is taken and reaches tau = 1: two
 * continuation steps, converged, checked by flying the command. */
/* req: OGK-MPSP-005 */
static void test_closing_step_below_delta_tau_min(void **state)
{
    ogk_mpsp_prop_t prop;
    ogk_real_t target[6];
    size_t i;
    (void)state;
    consistent_nominal(&cfg);
    cfg.delta_max = 0.0085;
    cfg.delta_tau_0 = 0.75;
    cfg.delta_tau_min = 0.3;
    OGK_ASSERT_STATUS(ogk_mpsp_init(&ctx, &cfg), OGK_OK);
    (void)memcpy(target, cfg.r_f, 3u * sizeof target[0]);
    (void)memcpy(&target[3], cfg.v_f, 3u * sizeof target[0]);
    target[0] += 7.5e-3;
    target[1] -= 3.75e-3;
    target[2] -= 3.75e-3;
    target[4] += 3.75e-3;
    OGK_ASSERT_STATUS(ogk_mpsp_solve(&ctx, x0_3d, 1.0, target, &res), OGK_OK);
    assert_int_equal(res.converged, 1);
    assert_int_equal(res.outer_steps, 2);
    OGK_ASSERT_NEAR(res.tau_reached, 1.0, 0.0);
    /* the first Newton step at tau = 0.75: three quarters of the offset */
    /* float: the offsets applied to terminal states of size ~1, rounded to their ulps: 16 eps */
    OGK_ASSERT_NEAR(res.dy_norm_log[0], 0.75 * sqrt(5.625e-5 + 3.0 * 1.40625e-5), OGK_TEST_TOL(1e-9, 16.0 * FLT_EPSILON));
    OGK_ASSERT_STATUS(ogk_mpsp_propagate(&ctx, res.weights, res.lambda_m0, x0_3d, 1.0, &prop), OGK_OK);
    for (i = 0u; i < 6u; ++i) {
        OGK_ASSERT_NEAR(prop.x_f[i], target[i], MPSP_FX_TOL);
    }
    OGK_ASSERT_NEAR(prop.x_f[7], 0.0, MPSP_FX_TOL);
}

/* The give-up rule: Delta_max = 0.015 refuses the direct loop (0.0397) and tau = 0.5 (0.0199);
 * the halved step 0.25 is below delta_tau_min = 0.3 and is not a closing step: the continuation
 * gives up at every N_seg,tol level, OGK_E_NOT_CONVERGED with the nominal weights as the safe
 * command (tau_reached 0). */
/* req: OGK-MPSP-005 OGK-MPSP-006 */
static void test_give_up_below_delta_tau_min(void **state)
{
    ogk_real_t target[6];
    size_t i;
    (void)state;
    consistent_nominal(&cfg);
    cfg.delta_max = 0.015;
    cfg.delta_tau_0 = 0.5;
    cfg.delta_tau_min = 0.3;
    OGK_ASSERT_STATUS(ogk_mpsp_init(&ctx, &cfg), OGK_OK);
    (void)memcpy(target, cfg.r_f, 3u * sizeof target[0]);
    (void)memcpy(&target[3], cfg.v_f, 3u * sizeof target[0]);
    target[0] += 3e-2;
    target[1] -= 1.5e-2;
    target[2] -= 1.5e-2;
    target[4] += 1.5e-2;
    OGK_ASSERT_STATUS(ogk_mpsp_solve(&ctx, x0_3d, 1.0, target, &res), OGK_E_NOT_CONVERGED);
    assert_int_equal(res.converged, 0);
    OGK_ASSERT_NEAR(res.tau_reached, 0.0, 0.0);
    for (i = 0u; i < res.n_weights; ++i) {
        OGK_ASSERT_NEAR(res.weights[i], cfg.weights_nom[i], 0.0);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_velocity_tolerance_decides_alone),
        cmocka_unit_test(test_closing_step_below_delta_tau_min),
        cmocka_unit_test(test_give_up_below_delta_tau_min),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
