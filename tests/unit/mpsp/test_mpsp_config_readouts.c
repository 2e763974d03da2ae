/* test_mpsp_config_readouts.c -- paths of the MPSP configuration and read-outs that the other
 * tests leave unrun (make coverage, docs/evidence/coverage.md; moved from test_gate_misc.c):
 *  - MPSP: every range check of the configuration one by one, the held weights propagated
 *    again, trajectory copies without some outputs, the state read-out against an RK4 step,
 *    partial Jacobian and jump outputs against the full ones, and a control rate overflow. */
#include "ogk_test.h"

#include <float.h>
#include <string.h>

#include "mpsp_fixture.h"
#include "ogk/internal/mpsp_test.h" /* ogk_mpsp_step_jacobian, ogk_mpsp_switch_jump */
#include "ogk/mpsp.h"
#include "ogk/rk4.h"

/* ------------------------------------------------------------------ mpsp */

static ogk_mpsp_t ctx;
static ogk_mpsp_config_t cfg;

static int setup_mpsp(void **state)
{
    (void)state;
    if (mpsp_fixture_config(&cfg, 3u, 2u) != OGK_OK) {
        return -1;
    }
    return (ogk_mpsp_init(&ctx, &cfg) == OGK_OK) ? 0 : -1;
}

/* Every range check of ogk_mpsp_init on its own (ogk/mpsp.h): one field out of range, the
 * rest the fixture's valid mission. */
/* req: OGK-MPSP-007 */
static void test_mpsp_config_one_field_at_a_time(void **state)
{
    static ogk_mpsp_t tmp;
    unsigned k;
    (void)state;
    for (k = 0u; k < 24u; ++k) {
        ogk_mpsp_config_t c = cfg;
        ogk_status expected = OGK_E_CONFIG;
        switch (k) {
        case 0u: c.mu = NAN; expected = OGK_E_NONFINITE; break;
        case 1u: c.x0_nom[3] = INFINITY; expected = OGK_E_NONFINITE; break;
        case 2u: c.r_f[1] = NAN; expected = OGK_E_NONFINITE; break;
        case 3u: c.v_f[2] = -INFINITY; expected = OGK_E_NONFINITE; break;
        case 4u: c.r_eps[0] = NAN; expected = OGK_E_NONFINITE; break;
        case 5u: c.mu = -1.0; break;
        case 6u: c.t_max = 0.0; break;
        case 7u: c.c_exhaust = -1.0; break;
        case 8u: c.fourier_period = 0.0; break;
        case 9u: c.h_max = 0.0; break;
        case 10u: c.delta_max = 0.0; break;
        case 11u: c.delta_tau_0 = 0.0; break;
        case 12u: c.delta_tau_0 = 1.5; break;
        case 13u: c.delta_tau_min = -0.1; break;
        case 14u: c.r_lambda = 0.0; break;
        case 15u: c.tol_r = 0.0; break;
        case 16u: c.tol_v = 0.0; break;
        case 17u: c.tol_lambda_m = 0.0; break;
        case 18u: c.s_tol = 0.0; break;
        case 19u: c.max_outer = 0u; break;
        case 20u: c.n_seg_tol_step = 0u; break;
        case 21u: /* at the centre of a gravity field */
            c.x0_nom[0] = 0.0;
            c.x0_nom[1] = 0.0;
            c.x0_nom[2] = 0.0;
            break;
        case 22u: /* the basis phase omega (tf - t_ref) overflows at tf only (float: 1e30) */
            c.tf = OGK_TEST_PICK(1e300, 1e30);
            c.h_max = OGK_TEST_PICK(1e299, 1e29);
            c.fourier_period = 1e-9;
            break;
        default: c.max_newton = 0u; break;
        }
        (void)memset(&tmp, 0, sizeof tmp);
        OGK_ASSERT_STATUS(ogk_mpsp_init(&tmp, &c), expected);
        assert_true(tmp.init_marker != OGK_MPSP_INIT_MARKER);
    }
    {
        /* one step longer than the whole span: a single step of tf - t0 */
        ogk_mpsp_config_t c = cfg;
        c.h_max = 1e13;
        OGK_ASSERT_STATUS(ogk_mpsp_init(&tmp, &c), OGK_OK);
        assert_int_equal(tmp.n_steps, 1u);
    }
}

static ogk_real_t traj_t[OGK_MPSP_MAX_NODES];
static ogk_real_t traj_x[OGK_MPSP_MAX_NODES * 8u];
static uint8_t traj_mode[OGK_MPSP_MAX_NODES];

/* req: OGK-MPSP-009 */
static void test_mpsp_readouts(void **state)
{
    ogk_mpsp_prop_t a;
    ogk_mpsp_prop_t b;
    size_t count = 0u;
    size_t n;
    size_t i;
    ogk_real_t x[8];
    ogk_real_t xn[8];
    (void)state;
    OGK_ASSERT_STATUS(ogk_mpsp_state_at(&ctx, 0.5, NULL), OGK_E_NULL);
    OGK_ASSERT_STATUS(ogk_mpsp_state_at(&ctx, 0.5, x), OGK_E_NOT_INIT); /* no trajectory yet */
    OGK_ASSERT_STATUS(ogk_mpsp_propagate(&ctx, w3, 0.0, x0_3d, 1.0, &a), OGK_OK);
    /* the held weights again, no summary wanted: the same trajectory */
    OGK_ASSERT_STATUS(ogk_mpsp_propagate(&ctx, ctx.weights, 0.0, x0_3d, 1.0, NULL), OGK_OK);
    OGK_ASSERT_STATUS(ogk_mpsp_propagate(&ctx, ctx.weights, 0.0, x0_3d, 1.0, &b), OGK_OK);
    assert_true(memcmp(&a, &b, sizeof a) == 0);
    /* the node count alone, then states and modes without times */
    OGK_ASSERT_STATUS(ogk_mpsp_trajectory(&ctx, NULL, NULL, NULL, 0u, &count), OGK_E_DIM);
    n = count;
    OGK_ASSERT_STATUS(ogk_mpsp_trajectory(&ctx, NULL, NULL, NULL, n, &count), OGK_OK);
    assert_int_equal(count, n);
    OGK_ASSERT_STATUS(ogk_mpsp_trajectory(&ctx, NULL, traj_x, traj_mode, n, &count), OGK_OK);
    for (i = 0u; i < 7u; ++i) {
        OGK_ASSERT_NEAR(traj_x[i], x0_3d[i], 0.0);
    }
    OGK_ASSERT_STATUS(ogk_mpsp_trajectory(&ctx, traj_t, NULL, NULL, n, &count), OGK_OK);
    OGK_ASSERT_NEAR(traj_t[0], cfg.t0, 0.0);
    OGK_ASSERT_NEAR(traj_t[n - 1u], cfg.tf, 0.0);
    /* the read-out at a node is the node; half-way through an interval it is the RK4 step
     * from the interval's first node, to the O(h^3) of pchip (h = 0.05: 2 h^3 = 2.5e-4; a
     * wrong interval or segment is off by ~ |x'| h = 1e-2) */
    OGK_ASSERT_STATUS(ogk_mpsp_state_at(&ctx, traj_t[1], x), OGK_OK);
    for (i = 0u; i < 8u; ++i) {
        OGK_ASSERT_REL(x[i], traj_x[8u + i], 1e-15, 1e-15);
    }
    {
        const double th = 0.5 * (traj_t[0] + traj_t[1]);
        OGK_ASSERT_STATUS(ogk_mpsp_state_at(&ctx, th, x), OGK_OK);
        OGK_ASSERT_STATUS(ogk_mpsp_step_jacobian(&ctx, w3, 1.0, traj_t[0], traj_x, th - traj_t[0],
                                                 (int)traj_mode[0], xn, NULL, NULL),
                          OGK_OK);
        for (i = 0u; i < 8u; ++i) {
            OGK_ASSERT_NEAR(x[i], xn[i], 2.5e-4);
        }
    }
    /* before the first switch of a trajectory with two or more: the segment ends there */
    assert_true(ctx.n_switch_nodes >= 2u);
    {
        const size_t s = ctx.switch_node[0];
        const double tq = 0.5 * (traj_t[s - 1u] + traj_t[s]);
        OGK_ASSERT_STATUS(ogk_mpsp_state_at(&ctx, tq, x), OGK_OK);
        OGK_ASSERT_STATUS(ogk_mpsp_step_jacobian(&ctx, w3, 1.0, traj_t[s - 1u],
                                                 &traj_x[8u * (s - 1u)], tq - traj_t[s - 1u],
                                                 (int)traj_mode[s - 1u], xn, NULL, NULL),
                          OGK_OK);
        for (i = 0u; i < 8u; ++i) {
            OGK_ASSERT_NEAR(x[i], xn[i], 2.5e-4);
        }
    }
}

/* req: OGK-MPSP-002 OGK-MPSP-008 */
static void test_mpsp_control_rejections(void **state)
{
    ogk_real_t lv[3] = {-7.0, -7.0, -7.0};
    ogk_real_t lvd[3];
    ogk_real_t w[21];
    size_t c;
    (void)state;
    OGK_ASSERT_STATUS(ogk_mpsp_control(&ctx, NULL, 0.0, lv, NULL), OGK_E_NULL);
    OGK_ASSERT_STATUS(ogk_mpsp_control(&ctx, w3, 0.0, NULL, NULL), OGK_E_NULL);
    (void)memcpy(w, w3, sizeof w);
    w[4] = NAN;
    OGK_ASSERT_STATUS(ogk_mpsp_control(&ctx, w, 0.0, lv, NULL), OGK_E_NONFINITE);
    OGK_ASSERT_NEAR(lv[0], -7.0, 0.0);
    /* sine weights of 1e308 at t = t_ref: lambda_v = 0 exactly (every sine is 0), its rate
     * 1e308 (w + 2 w + 3 w) omega overflows (float: 1e38) */
    (void)memset(w, 0, sizeof w);
    for (c = 0u; c < 3u; ++c) {
        w[c * 7u + 2u] = OGK_TEST_PICK(1e308, 1e38);
        w[c * 7u + 4u] = OGK_TEST_PICK(1e308, 1e38);
        w[c * 7u + 6u] = OGK_TEST_PICK(1e308, 1e38);
    }
    OGK_ASSERT_STATUS(ogk_mpsp_control(&ctx, w, cfg.fourier_t_ref, lv, NULL), OGK_OK);
    OGK_ASSERT_NEAR(lv[0], 0.0, 0.0);
    OGK_ASSERT_STATUS(ogk_mpsp_control(&ctx, w, cfg.fourier_t_ref, lv, lvd), OGK_E_NONFINITE);
}

/* ogk_mpsp_newton_update: each argument rejected on its own, nothing written. */
/* req: OGK-MPSP-004 OGK-MPSP-008 */
static void test_mpsp_newton_update_arguments(void **state)
{
    static ogk_mpsp_t blank; /* never initialised */
    ogk_real_t dy[OGK_MPSP_NY];
    ogk_real_t w[21];
    ogk_real_t lm = 0.25;
    (void)state;
    (void)memset(dy, 0, sizeof dy);
    dy[0] = 1e-3;
    (void)memcpy(w, w3, sizeof w);
    OGK_ASSERT_STATUS(ogk_mpsp_newton_update(&ctx, NULL, w, &lm), OGK_E_NULL);
    OGK_ASSERT_STATUS(ogk_mpsp_newton_update(&ctx, dy, NULL, &lm), OGK_E_NULL);
    OGK_ASSERT_STATUS(ogk_mpsp_newton_update(&blank, dy, w, &lm), OGK_E_NOT_INIT);
    OGK_ASSERT_STATUS(ogk_mpsp_propagate(&ctx, w3, 0.0, x0_3d, 1.0, NULL), OGK_OK);
    OGK_ASSERT_STATUS(ogk_mpsp_sensitivity(&ctx, NULL, NULL), OGK_OK);
    w[9] = NAN;
    OGK_ASSERT_STATUS(ogk_mpsp_newton_update(&ctx, dy, w, &lm), OGK_E_NONFINITE);
    OGK_ASSERT_NEAR(lm, 0.25, 0.0);
    w[9] = w3[9];
    assert_true(memcmp(w, w3, sizeof w) == 0);
    /* the same call with finite weights takes a step */
    OGK_ASSERT_STATUS(ogk_mpsp_newton_update(&ctx, dy, w, &lm), OGK_OK);
    assert_true(memcmp(w, w3, sizeof w) != 0);
}

/* Partial outputs of ogk_mpsp_step_jacobian and ogk_mpsp_switch_jump are the full call's. */
static ogk_real_t jx_full[64];
static ogk_real_t jw_full[8u * 21u];
static ogk_real_t jx_part[64];
static ogk_real_t jw_part[8u * 21u];

/* req: OGK-MPSP-003 */
static void test_mpsp_partial_jacobians(void **state)
{
    ogk_real_t x[8];
    ogk_real_t bad[8];
    ogk_real_t w_bad[21];
    ogk_real_t xn[8];
    ogk_real_t dx_full[8];
    ogk_real_t dw_full[21];
    ogk_real_t dx_part[8];
    ogk_real_t dw_part[21];
    (void)state;
    (void)memcpy(x, x0_3d, sizeof x0_3d);
    x[7] = 0.0;
    (void)memcpy(bad, x, sizeof bad);
    bad[2] = NAN;
    (void)memcpy(w_bad, w3, sizeof w_bad);
    w_bad[20] = INFINITY;
    OGK_ASSERT_STATUS(ogk_mpsp_step_jacobian(&ctx, w3, 1.0, 0.0, x, 0.05, 1, NULL, NULL, NULL),
                      OGK_E_NULL);
    OGK_ASSERT_STATUS(ogk_mpsp_step_jacobian(&ctx, w3, 1.0, 0.0, NULL, 0.05, 1, xn, NULL, NULL),
                      OGK_E_NULL);
    OGK_ASSERT_STATUS(ogk_mpsp_step_jacobian(&ctx, w3, 1.0, 0.0, x, NAN, 1, xn, NULL, NULL),
                      OGK_E_NONFINITE);
    OGK_ASSERT_STATUS(ogk_mpsp_step_jacobian(&ctx, w3, 1.0, 0.0, bad, 0.05, 1, xn, NULL, NULL),
                      OGK_E_NONFINITE);
    OGK_ASSERT_STATUS(ogk_mpsp_step_jacobian(&ctx, w_bad, 1.0, 0.0, x, 0.05, 1, xn, NULL, NULL),
                      OGK_E_NONFINITE);
    OGK_ASSERT_STATUS(ogk_mpsp_step_jacobian(&ctx, w3, 1.0, 0.0, x, 0.05, 1, xn, jx_full, jw_full),
                      OGK_OK);
    OGK_ASSERT_STATUS(ogk_mpsp_step_jacobian(&ctx, w3, 1.0, 0.0, x, 0.05, 1, xn, jx_part, NULL),
                      OGK_OK);
    assert_true(memcmp(jx_part, jx_full, sizeof jx_full) == 0);
    OGK_ASSERT_STATUS(ogk_mpsp_step_jacobian(&ctx, w3, 1.0, 0.0, x, 0.05, 1, xn, NULL, jw_part),
                      OGK_OK);
    assert_true(memcmp(jw_part, jw_full, sizeof jw_full) == 0);
    /* the switch jump at (0.5, x) leaving thrust */
    OGK_ASSERT_STATUS(ogk_mpsp_switch_jump(&ctx, w3, 1.0, 0.5, NULL, 1, jx_full, NULL, NULL, NULL),
                      OGK_E_NULL);
    OGK_ASSERT_STATUS(ogk_mpsp_switch_jump(&ctx, NULL, 1.0, 0.5, x, 1, jx_full, NULL, NULL, NULL),
                      OGK_E_NULL);
    OGK_ASSERT_STATUS(ogk_mpsp_switch_jump(&ctx, w3, 1.0, 0.5, bad, 1, jx_full, NULL, NULL, NULL),
                      OGK_E_NONFINITE);
    OGK_ASSERT_STATUS(ogk_mpsp_switch_jump(&ctx, w_bad, 1.0, 0.5, x, 1, jx_full, NULL, NULL, NULL),
                      OGK_E_NONFINITE);
    OGK_ASSERT_STATUS(ogk_mpsp_switch_jump(&ctx, w3, 1.0, 0.5, x, 1, jx_full, jw_full, dx_full,
                                           dw_full),
                      OGK_OK);
    OGK_ASSERT_STATUS(ogk_mpsp_switch_jump(&ctx, w3, 1.0, 0.5, x, 1, NULL, jw_part, NULL, NULL),
                      OGK_OK);
    assert_true(memcmp(jw_part, jw_full, sizeof jw_full) == 0);
    OGK_ASSERT_STATUS(ogk_mpsp_switch_jump(&ctx, w3, 1.0, 0.5, x, 1, jx_part, NULL, dx_part, NULL),
                      OGK_OK);
    assert_true(memcmp(jx_part, jx_full, sizeof jx_full) == 0);
    assert_true(memcmp(dx_part, dx_full, sizeof dx_full) == 0);
    OGK_ASSERT_STATUS(ogk_mpsp_switch_jump(&ctx, w3, 1.0, 0.5, x, 1, NULL, NULL, NULL, dw_part),
                      OGK_OK);
    assert_true(memcmp(dw_part, dw_full, sizeof dw_full) == 0);
}

/* dS/dt = S_U dU/dt (eq. 15): a constant lambda_v (only the constant basis weights) has
 * dS/dt = 0, a switch there is tangential and its time not differentiable; a rate that
 * overflows (sine weights of 1e308 at t_ref) is no better. Both are OGK_E_SINGULAR. */
/* req: OGK-MPSP-003 */
static void test_mpsp_tangential_switch(void **state)
{
    ogk_real_t x[8];
    ogk_real_t w[21];
    ogk_real_t jx[64];
    size_t c;
    (void)state;
    (void)memcpy(x, x0_3d, sizeof x0_3d);
    x[7] = 0.0;
    (void)memset(w, 0, sizeof w);
    w[0] = 1.0;
    w[7] = 0.5;
    w[14] = -0.25;
    OGK_ASSERT_STATUS(ogk_mpsp_switch_jump(&ctx, w, 1.0, 0.5, x, 1, jx, NULL, NULL, NULL),
                      OGK_E_SINGULAR);
    for (c = 0u; c < 3u; ++c) {
        w[c * 7u + 2u] = OGK_TEST_PICK(1e308, 1e38);
        w[c * 7u + 4u] = OGK_TEST_PICK(1e308, 1e38);
        w[c * 7u + 6u] = OGK_TEST_PICK(1e308, 1e38);
    }
    OGK_ASSERT_STATUS(ogk_mpsp_switch_jump(&ctx, w, 1.0, cfg.fourier_t_ref, x, 1, jx, NULL, NULL,
                                           NULL),
                      OGK_E_SINGULAR);
    /* the fixture's varying lambda_v at the same state: a regular switch */
    OGK_ASSERT_STATUS(ogk_mpsp_switch_jump(&ctx, w3, 1.0, 0.5, x, 1, jx, NULL, NULL, NULL), OGK_OK);
}

/* Algorithm 2's widening of N_seg,tol: the configuration states N_seg,nom = 1 while the
 * fixture's command flies 3 segments (2 switches). At N_seg,tol = 0 every Newton step is refused
 * (|3 - 1| > 0), the direct loop and the first continuation fail; N_seg,tol is widened by
 * n_seg_tol_step = 2 and the solve converges there, to the target it was given. */
/* req: OGK-MPSP-005 */
static void test_mpsp_segment_tolerance_widened(void **state)
{
    static ogk_mpsp_result_t res;
    ogk_mpsp_config_t c;
    ogk_mpsp_prop_t prop;
    size_t i;
    (void)state;
    OGK_ASSERT_STATUS(mpsp_fixture_config(&c, 8u, 10u), OGK_OK);
    OGK_ASSERT_STATUS(ogk_mpsp_init(&ctx, &c), OGK_OK);
    OGK_ASSERT_STATUS(ogk_mpsp_propagate(&ctx, w3, 0.0, x0_3d, 1.0, &prop), OGK_OK);
    assert_int_equal(prop.n_switches, 2u);
    (void)memcpy(c.r_f, prop.x_f, sizeof c.r_f); /* reachable target; lambda_m(tf) != 0 */
    (void)memcpy(c.v_f, &prop.x_f[3], sizeof c.v_f);
    c.n_seg_nom = 1u;
    c.n_seg_tol = 0u;
    c.n_seg_tol_step = 2u;
    OGK_ASSERT_STATUS(ogk_mpsp_init(&ctx, &c), OGK_OK);
    OGK_ASSERT_STATUS(ogk_mpsp_solve(&ctx, x0_3d, 1.0, NULL, &res), OGK_OK);
    assert_int_equal(res.converged, 1u);
    assert_int_equal(res.n_seg_tol, 2u);
    assert_true(res.outer_steps > 0u);
    assert_int_equal(res.n_segments, 3u);
    /* the command returned, flown again, meets the terminal conditions */
    OGK_ASSERT_STATUS(ogk_mpsp_propagate(&ctx, res.weights, res.lambda_m0, x0_3d, 1.0, &prop),
                      OGK_OK);
    for (i = 0u; i < 3u; ++i) {
        OGK_ASSERT_NEAR(prop.x_f[i], c.r_f[i], OGK_TEST_TOL(1e-9, MPSP_FX_TOL));
        OGK_ASSERT_NEAR(prop.x_f[3u + i], c.v_f[i], OGK_TEST_TOL(1e-9, MPSP_FX_TOL));
    }
    OGK_ASSERT_NEAR(prop.x_f[7], 0.0, OGK_TEST_TOL(1e-9, MPSP_FX_TOL));
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test_setup(test_mpsp_config_one_field_at_a_time, setup_mpsp),
        cmocka_unit_test_setup(test_mpsp_readouts, setup_mpsp),
        cmocka_unit_test_setup(test_mpsp_control_rejections, setup_mpsp),
        cmocka_unit_test_setup(test_mpsp_newton_update_arguments, setup_mpsp),
        cmocka_unit_test_setup(test_mpsp_partial_jacobians, setup_mpsp),
        cmocka_unit_test_setup(test_mpsp_tangential_switch, setup_mpsp),
        cmocka_unit_test(test_mpsp_segment_tolerance_widened),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
