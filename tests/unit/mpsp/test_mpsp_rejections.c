/* test_mpsp_rejections.c -- MPSP paths the other MPSP tests leave unrun (make coverage,
 * docs/evidence/coverage.md): every rejection of the read-out entry points, the configuration's grid and
 * basis-phase checks, a propagation that fails (mass depleted) inside ogk_mpsp_solve, and the
 * non-finite control read-out. Coarse grid (40 RK4 steps): cheap on the host and on QEMU. */
#include "ogk_test.h"

#include <float.h>
#include <string.h>

#include "mpsp_fixture.h"
#include "ogk/internal/mpsp_test.h" /* ogk_mpsp_step_jacobian, ogk_mpsp_switch_jump */
#include "ogk/mpsp.h"

static ogk_mpsp_t ctx;
static ogk_mpsp_t blank; /* never initialised */
static ogk_mpsp_config_t cfg;

static void small_config(ogk_mpsp_config_t *c)
{
    OGK_ASSERT_STATUS(mpsp_fixture_config(c, 3u, 2u), OGK_OK);
}

static int setup(void **state)
{
    (void)state;
    small_config(&cfg);
    return ogk_mpsp_init(&ctx, &cfg) == OGK_OK ? 0 : -1;
}

/* req: OGK-MPSP-007 */
static void test_config_grid_and_phase(void **state)
{
    ogk_mpsp_config_t c;
    ogk_mpsp_t tmp;
    (void)state;
    c = cfg;
    c.h_max = OGK_TEST_PICK(1e-300, 1e-30); /* (tf - t0) / h_max far over OGK_MPSP_MAX_STEPS */
    OGK_ASSERT_STATUS(ogk_mpsp_init(&tmp, &c), OGK_E_CONFIG);
    c = cfg;
    c.h_max = 2.0 / 40.5; /* not a whole number of steps: rounded up to 41 */
    OGK_ASSERT_STATUS(ogk_mpsp_init(&tmp, &c), OGK_OK);
    assert_int_equal(tmp.n_steps, 41u);
    c = cfg;
    c.fourier_period = OGK_REAL_MIN; /* omega = 2 pi / period overflows */
    OGK_ASSERT_STATUS(ogk_mpsp_init(&tmp, &c), OGK_E_CONFIG);
    c = cfg;
    c.fourier_t_ref = -OGK_REAL_MAX; /* omega (t0 - t_ref) overflows */
    OGK_ASSERT_STATUS(ogk_mpsp_init(&tmp, &c), OGK_E_CONFIG);
    assert_true(tmp.init_marker != OGK_MPSP_INIT_MARKER);
}

/* The edges of the configuration ranges (ogk/mpsp.h): each admitted or refused
 * value at its bound. */
/* req: OGK-MPSP-007 */
static void test_config_range_edges(void **state)
{
    ogk_mpsp_config_t c;
    ogk_mpsp_t tmp;
    const size_t n_weights = OGK_MPSP_NU * ((2u * 3u) + 1u); /* fourier_order 3 */
    (void)state;
    c = cfg;
    c.c_exhaust = 0.0; /* mass flow T / c undefined */
    OGK_ASSERT_STATUS(ogk_mpsp_init(&tmp, &c), OGK_E_CONFIG);
    c = cfg;
    c.max_outer = 1u; /* one continuation level is a valid problem */
    c.n_seg_tol_step = 1u;
    OGK_ASSERT_STATUS(ogk_mpsp_init(&tmp, &c), OGK_OK);
    c = cfg;
    c.mu = 0.0; /* no gravity: the origin is a valid start */
    c.x0_nom[0] = 0.0;
    c.x0_nom[1] = 0.0;
    c.x0_nom[2] = 0.0;
    OGK_ASSERT_STATUS(ogk_mpsp_init(&tmp, &c), OGK_OK);
    c = cfg;
    c.x0_nom[0] = 0.5; /* |r| = 0.5 (normalised units): valid with gravity */
    c.x0_nom[1] = 0.0;
    c.x0_nom[2] = 0.0;
    OGK_ASSERT_STATUS(ogk_mpsp_init(&tmp, &c), OGK_OK);
    c = cfg;
    c.r_eps[n_weights] = 0.0; /* past the weights in use: not read */
    OGK_ASSERT_STATUS(ogk_mpsp_init(&tmp, &c), OGK_OK);
    c.r_eps[n_weights - 1u] = 0.0; /* the last weight in use */
    OGK_ASSERT_STATUS(ogk_mpsp_init(&tmp, &c), OGK_E_CONFIG);
}

/* req: OGK-MPSP-001 OGK-MPSP-008 */
static void test_propagate_rejections(void **state)
{
    ogk_mpsp_prop_t prop;
    ogk_real_t x[7];
    ogk_real_t w[21];
    (void)state;
    OGK_ASSERT_STATUS(ogk_mpsp_propagate(NULL, w3, 0.0, x0_3d, 1.0, &prop), OGK_E_NULL);
    OGK_ASSERT_STATUS(ogk_mpsp_propagate(&ctx, w3, 0.0, NULL, 1.0, &prop), OGK_E_NULL);
    OGK_ASSERT_STATUS(ogk_mpsp_propagate(&blank, w3, 0.0, x0_3d, 1.0, &prop), OGK_E_NOT_INIT);
    OGK_ASSERT_STATUS(ogk_mpsp_propagate(&ctx, w3, 0.0, x0_3d, NAN, &prop), OGK_E_NONFINITE);
    OGK_ASSERT_STATUS(ogk_mpsp_propagate(&ctx, w3, 0.0, x0_3d, 0.0, &prop), OGK_E_RANGE);
    (void)memcpy(x, x0_3d, sizeof x);
    x[6] = 0.0;
    OGK_ASSERT_STATUS(ogk_mpsp_propagate(&ctx, w3, 0.0, x, 1.0, &prop), OGK_E_RANGE);
    OGK_ASSERT_STATUS(ogk_mpsp_propagate(&ctx, NULL, 0.0, x0_3d, 1.0, &prop), OGK_E_NULL);
    (void)memcpy(w, w3, sizeof w);
    w[20] = INFINITY;
    OGK_ASSERT_STATUS(ogk_mpsp_propagate(&ctx, w, 0.0, x0_3d, 1.0, &prop), OGK_E_NONFINITE);
    OGK_ASSERT_STATUS(ogk_mpsp_propagate(&ctx, w3, NAN, x0_3d, 1.0, &prop), OGK_E_NONFINITE);
    /* mass depleted on the way (m0 = 0.1, dm/dt = -0.1 while thrusting): eq. (16) undefined */
    x[6] = 0.1;
    assert_true(ogk_mpsp_propagate(&ctx, w3, 0.0, x, 1.0, &prop) != OGK_OK);
}

/* req: OGK-MPSP-009 OGK-MPSP-008 */
static void test_readout_rejections(void **state)
{
    ogk_mpsp_prop_t prop;
    ogk_real_t t[4];
    ogk_real_t x[8];
    ogk_real_t u[3];
    size_t count = 0u;
    (void)state;
    OGK_ASSERT_STATUS(ogk_mpsp_trajectory(NULL, t, NULL, NULL, 4u, &count), OGK_E_NULL);
    OGK_ASSERT_STATUS(ogk_mpsp_trajectory(&ctx, t, NULL, NULL, 4u, NULL), OGK_E_NULL);
    OGK_ASSERT_STATUS(ogk_mpsp_trajectory(&blank, t, NULL, NULL, 4u, &count), OGK_E_NOT_INIT);
    OGK_ASSERT_STATUS(ogk_mpsp_state_at(NULL, 0.0, x), OGK_E_NULL);
    OGK_ASSERT_STATUS(ogk_mpsp_state_at(&blank, 0.0, x), OGK_E_NOT_INIT);
    OGK_ASSERT_STATUS(ogk_mpsp_propagate(&ctx, w3, 0.0, x0_3d, 1.0, &prop), OGK_OK);
    OGK_ASSERT_STATUS(ogk_mpsp_trajectory(&ctx, t, NULL, NULL, 4u, &count), OGK_E_DIM);
    assert_true(count > 4u);
    OGK_ASSERT_STATUS(ogk_mpsp_state_at(&ctx, NAN, x), OGK_E_NONFINITE);
    assert_true(ogk_mpsp_state_at(&ctx, 5.0, x) != OGK_OK); /* after tf */
    OGK_ASSERT_STATUS(ogk_mpsp_state_at(&ctx, 1.0, x), OGK_OK);
    OGK_ASSERT_STATUS(ogk_mpsp_control(NULL, w3, 0.0, u, NULL), OGK_E_NULL);
    OGK_ASSERT_STATUS(ogk_mpsp_control(&blank, w3, 0.0, u, NULL), OGK_E_NOT_INIT);
    OGK_ASSERT_STATUS(ogk_mpsp_control(&ctx, w3, NAN, u, NULL), OGK_E_NONFINITE);
    {
        /* finite weights whose sum overflows: never OGK_OK with a non-finite output */
        ogk_real_t w[21];
        size_t i;
        for (i = 0u; i < 21u; ++i) {
            w[i] = DBL_MAX;
        }
        OGK_ASSERT_STATUS(ogk_mpsp_control(&ctx, w, 0.0, u, NULL), OGK_E_NONFINITE);
        OGK_ASSERT_STATUS(ogk_mpsp_control(&ctx, w3, 0.0, u, NULL), OGK_OK);
    }
}

/* req: OGK-MPSP-004 */
static void test_newton_update_rejections(void **state)
{
    ogk_real_t dy[OGK_MPSP_NY];
    ogk_real_t w[21];
    ogk_real_t lm = 0.0;
    ogk_mpsp_prop_t prop;
    (void)state;
    (void)memset(dy, 0, sizeof dy);
    (void)memcpy(w, w3, sizeof w);
    OGK_ASSERT_STATUS(ogk_mpsp_newton_update(NULL, dy, w, &lm), OGK_E_NULL);
    OGK_ASSERT_STATUS(ogk_mpsp_newton_update(&ctx, dy, w, NULL), OGK_E_NULL);
    OGK_ASSERT_STATUS(ogk_mpsp_propagate(&ctx, w3, 0.0, x0_3d, 1.0, &prop), OGK_OK);
    OGK_ASSERT_STATUS(ogk_mpsp_newton_update(&ctx, dy, w, &lm), OGK_E_NOT_INIT); /* no sensitivities */
    OGK_ASSERT_STATUS(ogk_mpsp_sensitivity(&ctx, NULL, NULL), OGK_OK);
    dy[3] = NAN;
    OGK_ASSERT_STATUS(ogk_mpsp_newton_update(&ctx, dy, w, &lm), OGK_E_NONFINITE);
    dy[3] = 0.0;
    lm = INFINITY;
    OGK_ASSERT_STATUS(ogk_mpsp_newton_update(&ctx, dy, w, &lm), OGK_E_NONFINITE);
    lm = 0.0;
    OGK_ASSERT_STATUS(ogk_mpsp_newton_update(&ctx, dy, w, &lm), OGK_OK);
    OGK_ASSERT_NEAR(lm, 0.0, 0.0); /* dy = 0: no step */
}

/* req: OGK-MPSP-006 */
static void test_solve_with_failing_propagation(void **state)
{
    ogk_mpsp_result_t res;
    ogk_real_t x[7];
    size_t i;
    (void)state;
    (void)memcpy(x, x0_3d, sizeof x);
    x[6] = 0.1; /* the mass runs out before tf: no trajectory to correct */
    assert_true(ogk_mpsp_solve(&ctx, x, 1.0, NULL, &res) != OGK_OK);
    assert_int_equal(res.converged, 0u);
    for (i = 0u; i < OGK_MPSP_NY; ++i) {
        assert_true(res.dy[i] == HUGE_VAL);
    }
    assert_true(res.err_r == HUGE_VAL && res.err_v == HUGE_VAL && res.lambda_mf == HUGE_VAL);
    OGK_ASSERT_NEAR(res.m_f, 0.0, 0.0);
}

/* ogk_mpsp_step_jacobian and ogk_mpsp_switch_jump: argument rejections, and states where
 * eq. (16) is undefined (mass 0, r = 0 with gravity, lambda_v = 0 while thrusting). */
/* req: OGK-MPSP-003 */
static void test_jacobian_and_jump_rejections(void **state)
{
    ogk_real_t x[8];
    ogk_real_t xn[8];
    ogk_real_t jx[64];
    ogk_real_t zero_w[21];
    (void)state;
    (void)memcpy(x, x0_3d, sizeof x0_3d);
    x[7] = 0.0;
    (void)memset(zero_w, 0, sizeof zero_w);
    OGK_ASSERT_STATUS(ogk_mpsp_step_jacobian(NULL, w3, 1.0, 0.0, x, 0.05, 1, xn, NULL, NULL), OGK_E_NULL);
    OGK_ASSERT_STATUS(ogk_mpsp_step_jacobian(&blank, w3, 1.0, 0.0, x, 0.05, 1, xn, NULL, NULL), OGK_E_NOT_INIT);
    OGK_ASSERT_STATUS(ogk_mpsp_step_jacobian(&ctx, NULL, 1.0, 0.0, x, 0.05, 1, xn, NULL, NULL), OGK_E_NULL);
    OGK_ASSERT_STATUS(ogk_mpsp_step_jacobian(&ctx, w3, NAN, 0.0, x, 0.05, 1, xn, NULL, NULL), OGK_E_NONFINITE);
    OGK_ASSERT_STATUS(ogk_mpsp_step_jacobian(&ctx, w3, 1.0, 0.0, x, 0.05, 2, xn, NULL, NULL), OGK_E_RANGE);
    OGK_ASSERT_STATUS(ogk_mpsp_step_jacobian(&ctx, w3, 1.0, NAN, x, 0.05, 1, xn, NULL, NULL), OGK_E_NONFINITE);
    OGK_ASSERT_STATUS(ogk_mpsp_step_jacobian(&ctx, w3, 1.0, 0.0, x, 0.05, 1, xn, NULL, NULL), OGK_OK);
    /* lambda_v = 0 while thrusting: the thrust direction is undefined */
    assert_true(ogk_mpsp_step_jacobian(&ctx, zero_w, 1.0, 0.0, x, 0.05, 1, xn, jx, NULL) != OGK_OK);
    x[6] = 0.0; /* no mass */
    assert_true(ogk_mpsp_step_jacobian(&ctx, w3, 1.0, 0.0, x, 0.05, 1, xn, jx, NULL) != OGK_OK);
    assert_true(ogk_mpsp_step_jacobian(&ctx, w3, 1.0, 0.0, x, 0.05, 0, xn, jx, NULL) != OGK_OK);
    assert_true(ogk_mpsp_switch_jump(&ctx, w3, 1.0, 0.5, x, 0, jx, NULL, NULL, NULL) != OGK_OK);
    x[6] = 1.0;
    x[0] = 0.0; /* at the centre of the field */
    x[1] = 0.0;
    x[2] = 0.0;
    assert_true(ogk_mpsp_step_jacobian(&ctx, w3, 1.0, 0.0, x, 0.05, 0, xn, jx, NULL) != OGK_OK);
    assert_true(ogk_mpsp_step_jacobian(&ctx, w3, 1.0, 0.0, x, 0.05, 1, xn, NULL, NULL) != OGK_OK);
    OGK_ASSERT_STATUS(ogk_mpsp_switch_jump(NULL, w3, 1.0, 0.5, x, 0, jx, NULL, NULL, NULL), OGK_E_NULL);
    OGK_ASSERT_STATUS(ogk_mpsp_switch_jump(&ctx, w3, NAN, 0.5, x, 0, jx, NULL, NULL, NULL), OGK_E_NONFINITE);
    OGK_ASSERT_STATUS(ogk_mpsp_switch_jump(&ctx, w3, 1.0, NAN, x, 0, jx, NULL, NULL, NULL), OGK_E_NONFINITE);
    OGK_ASSERT_STATUS(ogk_mpsp_sensitivity(NULL, NULL, NULL), OGK_E_NULL);
    OGK_ASSERT_STATUS(ogk_mpsp_sensitivity(&blank, NULL, NULL), OGK_E_NOT_INIT);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_config_grid_and_phase),
        cmocka_unit_test(test_config_range_edges),
        cmocka_unit_test(test_propagate_rejections),
        cmocka_unit_test(test_readout_rejections),
        cmocka_unit_test(test_newton_update_rejections),
        cmocka_unit_test(test_solve_with_failing_propagation),
        cmocka_unit_test(test_jacobian_and_jump_rejections),
    };
    return cmocka_run_group_tests(tests, setup, NULL);
}
