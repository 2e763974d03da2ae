/* test_mpsp_solve.c -- MPSP guidance loops (ogk/mpsp.h, docs/design/mpsp.md):
 *   - Newton (eqs. 44-46, Algorithm 1) on a synthetic rendezvous built here:
 *     a two-switch trajectory of the normalised two-body problem is made
 *     consistent (lambda_m(tf) = 0) by MPSP itself, then its target, its
 *     thrust and its initial state are perturbed and MPSP must hit the new
 *     conditions; each answer is checked by flying the returned weights with
 *     ogk_mpsp_propagate, and the last steps must contract quadratically;
 *   - the continuation (Algorithm 2) when Delta_max forbids the direct step;
 *   - failure: OGK_E_NOT_CONVERGED with the nominal weights as safe command;
 *   - bad inputs and configurations give their codes. */
#include "ogk_test.h"

#include <string.h>

#include "ogk/internal/mpsp_test.h" /* ogk_mpsp_step_jacobian */
#include "ogk/mpsp.h"

#define NX OGK_MPSP_NX
#define NY OGK_MPSP_NY

#define GRID_STEPS 400.0 /* the same on the host and on QEMU (about 0.3 s there) */
/* The solves' tolerances in float (ogk_test.h): the float solves stall near 3e-7 at unit scale
 * (measured: this file's problem and test_mpsp_solve.c's 400-step one converge to 3e-7 at most, not
 * to 1e-7, their terminal states carrying some 40 to 400 roundings); 1e-5 is thirty times that
 * floor. The terminal conditions flown again are checked to the same tolerance. */
#define MPSP_TOL_F 1e-5


static ogk_mpsp_t ctx;
static ogk_mpsp_config_t cfg;      /* consistent nominal (built in setup) */
static ogk_mpsp_config_t cfg_work;
static ogk_mpsp_result_t res;

static const ogk_real_t w3[21] = {
    2.0, 0.05, 0.02, 0.6, 0.03, -0.02, 0.01,   /* lambda_v,x */
    0.6, 0.0, 0.2, 0.01, -0.02, 0.0, 0.01,     /* lambda_v,y */
    0.0, 0.05, 0.0, 0.01, 0.0, 0.0, -0.01};    /* lambda_v,z */
static const ogk_real_t x0_3d[7] = {1.0, 0.0, 0.01, 0.0, 1.0, 0.02, 1.0};

static void orbit_config(ogk_mpsp_config_t *c)
{
    size_t i;
    (void)memset(c, 0, sizeof *c);
    c->mu = 1.0;
    c->t_max = 0.1;
    c->c_exhaust = 1.0;
    c->t0 = 0.0;
    c->tf = 2.0;
    (void)memcpy(c->x0_nom, x0_3d, sizeof x0_3d);
    c->fourier_order = 3u;
    c->fourier_period = 4.0;
    c->fourier_t_ref = 0.0;
    c->h_max = 2.0 / GRID_STEPS;
    c->delta_max = 1.0;
    c->delta_tau_0 = 0.5;
    c->delta_tau_min = 0.1;
    for (i = 0u; i < OGK_MPSP_MAX_WEIGHTS; ++i) {
        c->r_eps[i] = 1.0;
    }
    c->r_lambda = 1.0;
    c->tol_r = OGK_TEST_TOL(1e-10, MPSP_TOL_F);
    c->tol_v = OGK_TEST_TOL(1e-10, MPSP_TOL_F);
    c->tol_lambda_m = OGK_TEST_TOL(1e-10, MPSP_TOL_F);
    c->s_tol = OGK_TEST_TOL(1e-12, 16.0 * FLT_EPSILON); /* float: 16 eps of |S| ~ 1 (test_rk4.c) */
    c->max_newton = 20u;
    c->max_outer = 30u;
    c->n_seg_tol = 0u;
    c->n_seg_tol_step = 2u;
    (void)memcpy(c->weights_nom, w3, sizeof w3);
    c->lambda_m0_nom = 0.0;
}

/* The nominal: fly w3, take its r(tf), v(tf) as the target, and let MPSP
 * bring lambda_m(tf) to 0 (eq. 7); the result is the consistent nominal. */
static int setup(void **state)
{
    ogk_mpsp_prop_t prop;
    (void)state;
    orbit_config(&cfg);
    if (ogk_mpsp_init(&ctx, &cfg) != OGK_OK ||
        ogk_mpsp_propagate(&ctx, w3, 0.0, x0_3d, 1.0, &prop) != OGK_OK || prop.n_switches != 2u) {
        return -1;
    }
    (void)memcpy(cfg.r_f, prop.x_f, sizeof cfg.r_f);
    (void)memcpy(cfg.v_f, &prop.x_f[3], sizeof cfg.v_f);
    if (ogk_mpsp_init(&ctx, &cfg) != OGK_OK ||
        ogk_mpsp_solve(&ctx, x0_3d, 1.0, NULL, &res) != OGK_OK || res.converged != 1u ||
        !(fabs(prop.x_f[7]) > 0.1)) {
        return -1;
    }
    (void)memcpy(cfg.weights_nom, res.weights, sizeof res.weights);
    cfg.lambda_m0_nom = res.lambda_m0;
    return 0;
}

/* Flies the returned command with the kernel's propagation and checks the
 * terminal conditions independently of the solver's own bookkeeping. */
static void check_flown(const ogk_real_t *x0, ogk_real_t scale, const ogk_real_t *target, double tol)
{
    ogk_mpsp_prop_t prop;
    size_t i;
    OGK_ASSERT_STATUS(ogk_mpsp_propagate(&ctx, res.weights, res.lambda_m0, x0, scale, &prop),
                      OGK_OK);
    for (i = 0u; i < 6u; ++i) {
        OGK_ASSERT_NEAR(prop.x_f[i], target[i], tol);
    }
    OGK_ASSERT_NEAR(prop.x_f[7], 0.0, tol);
    OGK_ASSERT_NEAR(prop.x_f[6], res.m_f, 1e-15);
    assert_int_equal(prop.n_switches, res.n_switches);
}

static void nominal_target(ogk_real_t *target)
{
    (void)memcpy(target, cfg.r_f, 3u * sizeof target[0]);
    (void)memcpy(&target[3], cfg.v_f, 3u * sizeof target[0]);
}

/* ||dY|| of the last steps: e_{k+1} <= 10 e_k^2 (the observed constant is ~0.6). */
static void check_quadratic_tail(void)
{
    const uint32_t n = res.n_log;
    assert_true(n >= 2u);
    assert_true(res.dy_norm_log[n - 1u] <= 10.0 * res.dy_norm_log[n - 2u] * res.dy_norm_log[n - 2u]);
}

/* req: OGK-MPSP-005 */
static void test_nominal_needs_no_iteration(void **state)
{
    ogk_real_t target[6];
    (void)state;
    OGK_ASSERT_STATUS(ogk_mpsp_init(&ctx, &cfg), OGK_OK);
    assert_int_equal(ctx.n_seg_nom, 3);
    OGK_ASSERT_STATUS(ogk_mpsp_solve(&ctx, x0_3d, 1.0, NULL, &res), OGK_OK);
    assert_int_equal(res.converged, 1);
    assert_int_equal(res.newton_iterations, 0);
    assert_int_equal(res.n_thrust_arcs, 2);
    assert_int_equal(res.n_segments, 3);
    nominal_target(target);
    check_flown(x0_3d, 1.0, target, OGK_TEST_TOL(1e-10, MPSP_TOL_F));
}

/* req: OGK-MPSP-005 OGK-MPSP-004 */
static void test_newton_recovers_perturbed_target(void **state)
{
    ogk_real_t target[6];
    (void)state;
    OGK_ASSERT_STATUS(ogk_mpsp_init(&ctx, &cfg), OGK_OK);
    nominal_target(target);
    target[0] += 1e-2;
    target[1] -= 5e-3;
    target[2] -= 5e-3;
    target[4] += 5e-3;
    OGK_ASSERT_STATUS(ogk_mpsp_solve(&ctx, x0_3d, 1.0, target, &res), OGK_OK);
    assert_int_equal(res.converged, 1);
    assert_true(res.newton_iterations >= 2u && res.newton_iterations <= 6u);
    assert_int_equal(res.outer_steps, 0);
    assert_int_equal(res.n_log, res.newton_iterations);
    /* the offset; float: the offsets applied to terminal states of size ~1, rounded to their
     * ulps (4 of them): 16 eps */
    OGK_ASSERT_NEAR(res.dy_norm_log[0], sqrt(1e-4 + 3.0 * 25e-6), OGK_TEST_TOL(1e-9, 16.0 * FLT_EPSILON));
    assert_true(res.err_r <= cfg.tol_r && res.err_v <= cfg.tol_v &&
                fabs(res.lambda_mf) <= cfg.tol_lambda_m);
    OGK_ASSERT_NEAR(res.tau_reached, 1.0, 0.0);
    check_quadratic_tail();
    check_flown(x0_3d, 1.0, target, OGK_TEST_TOL(1e-10, MPSP_TOL_F));
}

/* req: OGK-MPSP-005 */
static void test_thrust_and_initial_state_perturbations(void **state)
{
    ogk_real_t target[6];
    ogk_real_t x0[7];
    (void)state;
    OGK_ASSERT_STATUS(ogk_mpsp_init(&ctx, &cfg), OGK_OK);
    nominal_target(target);
    /* Table 6 style: T_max (1 + eta), eta = +5 % */
    OGK_ASSERT_STATUS(ogk_mpsp_solve(&ctx, x0_3d, 1.05, NULL, &res), OGK_OK);
    assert_int_equal(res.converged, 1);
    assert_true(res.newton_iterations >= 1u);
    check_quadratic_tail();
    check_flown(x0_3d, 1.05, target, OGK_TEST_TOL(1e-10, MPSP_TOL_F));
    /* Table 3 style: r0 + dr0, v0 + dv0 */
    (void)memcpy(x0, x0_3d, sizeof x0);
    x0[0] += 2e-3;
    x0[4] -= 1e-3;
    x0[5] += 1e-3;
    OGK_ASSERT_STATUS(ogk_mpsp_solve(&ctx, x0, 1.0, NULL, &res), OGK_OK);
    assert_int_equal(res.converged, 1);
    check_flown(x0, 1.0, target, OGK_TEST_TOL(1e-10, MPSP_TOL_F));
}

/* The second-order sweep (OGK_MPSP_SWEEP_MID2, the default of
 * ogk_mpsp_config_default): Newton's residual is the exact propagation's, so
 * the solution meets the same tolerances, flown again; its Jacobian is
 * within O(h^2) of the exact one (test_mpsp_sensitivity.c), so the iteration
 * counts stay within one of the exact sweep's on the same perturbations
 * (target offset, eta = +5 %, initial-state offset). */
/* req: OGK-MPSP-005 OGK-MPSP-003 */
static void test_mid2_sweep_same_iterations(void **state)
{
    static ogk_mpsp_config_t cfg_mid2;
    ogk_real_t target[6];
    ogk_real_t target_p[6];
    ogk_real_t x0[7];
    uint32_t ni[2][3];
    size_t sw;
    (void)state;
    nominal_target(target);
    (void)memcpy(target_p, target, sizeof target_p);
    target_p[0] += 1e-2;
    target_p[1] -= 5e-3;
    target_p[2] -= 5e-3;
    target_p[4] += 5e-3;
    (void)memcpy(x0, x0_3d, sizeof x0);
    x0[0] += 2e-3;
    x0[4] -= 1e-3;
    x0[5] += 1e-3;
    cfg_mid2 = cfg;
    for (sw = 0u; sw < 2u; ++sw) {
        cfg_mid2.sens_sweep = (sw == 0u) ? OGK_MPSP_SWEEP_RK4 : OGK_MPSP_SWEEP_MID2;
        OGK_ASSERT_STATUS(ogk_mpsp_init(&ctx, &cfg_mid2), OGK_OK);
        OGK_ASSERT_STATUS(ogk_mpsp_solve(&ctx, x0_3d, 1.0, target_p, &res), OGK_OK);
        assert_int_equal(res.converged, 1);
        ni[sw][0] = res.newton_iterations;
        check_flown(x0_3d, 1.0, target_p, OGK_TEST_TOL(1e-10, MPSP_TOL_F));
        OGK_ASSERT_STATUS(ogk_mpsp_solve(&ctx, x0_3d, 1.05, NULL, &res), OGK_OK);
        assert_int_equal(res.converged, 1);
        ni[sw][1] = res.newton_iterations;
        check_flown(x0_3d, 1.05, target, OGK_TEST_TOL(1e-10, MPSP_TOL_F));
        OGK_ASSERT_STATUS(ogk_mpsp_solve(&ctx, x0, 1.0, NULL, &res), OGK_OK);
        assert_int_equal(res.converged, 1);
        ni[sw][2] = res.newton_iterations;
        check_flown(x0, 1.0, target, OGK_TEST_TOL(1e-10, MPSP_TOL_F));
    }
    for (sw = 0u; sw < 3u; ++sw) {
        print_message("Newton iterations, exact / mid2 sweep: %u / %u\n", (unsigned)ni[0][sw],
                      (unsigned)ni[1][sw]);
        assert_true((ni[1][sw] + 1u >= ni[0][sw]) && (ni[1][sw] <= ni[0][sw] + 1u));
    }
}

/* req: OGK-MPSP-005 */
static void test_continuation_when_newton_is_not_allowed(void **state)
{
    ogk_real_t target[6];
    (void)state;
    cfg_work = cfg;
    cfg_work.delta_max = 0.03; /* the offset below (0.040) is out of reach directly */
    OGK_ASSERT_STATUS(ogk_mpsp_init(&ctx, &cfg_work), OGK_OK);
    nominal_target(target);
    target[0] += 3e-2;
    target[1] -= 1.5e-2;
    target[2] -= 1.5e-2;
    target[4] += 1.5e-2;
    OGK_ASSERT_STATUS(ogk_mpsp_solve(&ctx, x0_3d, 1.0, target, &res), OGK_OK);
    assert_int_equal(res.converged, 1);
    assert_true(res.outer_steps >= 2u);
    assert_int_equal(res.inner_loops, res.outer_steps + 1u);
    OGK_ASSERT_NEAR(res.tau_reached, 1.0, 0.0);
    /* The first Newton step is taken at tau = delta_tau_0 = 0.5: half the offset. */
    OGK_ASSERT_NEAR(res.dy_norm_log[0], 0.5 * sqrt(9e-4 + 3.0 * 2.25e-4), OGK_TEST_TOL(1e-9, 16.0 * FLT_EPSILON));
    check_flown(x0_3d, 1.0, target, OGK_TEST_TOL(1e-10, MPSP_TOL_F));
}

/* Algorithm 1's Newton budget: max_newton steps are all taken and the result of the last one is
 * checked (j = 0 .. max_newton: the check after the last step is what converges here). With one
 * step fewer the direct loop fails and the continuation has to take over. */
/* req: OGK-MPSP-005 */
static void test_newton_budget_is_exact(void **state)
{
    ogk_real_t target[6];
    uint32_t needed;
    (void)state;
    nominal_target(target);
    target[0] += 1e-2;
    target[1] -= 5e-3;
    target[2] -= 5e-3;
    target[4] += 5e-3;
    OGK_ASSERT_STATUS(ogk_mpsp_init(&ctx, &cfg), OGK_OK);
    OGK_ASSERT_STATUS(ogk_mpsp_solve(&ctx, x0_3d, 1.0, target, &res), OGK_OK);
    needed = res.newton_iterations;
    assert_true(needed >= 2u);
    cfg_work = cfg;
    cfg_work.max_newton = needed;
    OGK_ASSERT_STATUS(ogk_mpsp_init(&ctx, &cfg_work), OGK_OK);
    OGK_ASSERT_STATUS(ogk_mpsp_solve(&ctx, x0_3d, 1.0, target, &res), OGK_OK);
    assert_int_equal(res.converged, 1);
    assert_int_equal(res.newton_iterations, needed);
    assert_int_equal(res.outer_steps, 0); /* the direct loop converged on its last step */
    cfg_work.max_newton = needed - 1u;
    OGK_ASSERT_STATUS(ogk_mpsp_init(&ctx, &cfg_work), OGK_OK);
    (void)ogk_mpsp_solve(&ctx, x0_3d, 1.0, target, &res);
    assert_true(res.outer_steps > 0u); /* the direct loop ran out of steps */
}

/* Algorithm 1 lines 10-14 and Algorithm 2 line 24: the N_seg tolerance. The trajectories near
 * this nominal have 3 segments; a configured N_seg,nom of 5 or 6 makes every Newton step fail the
 * segment check until the continuation has widened N_seg,tol (by n_seg_tol_step = 2 after each
 * failed continuation) to |3 - N_seg,nom|: 0 -> 2 for N_seg,nom = 5 (the difference equals the
 * tolerance: accepted, since the test is |dN| > N_seg,tol), 0 -> 2 -> 4 for 6. Kills the
 * N_seg,tol step mutants (issue 8): a step of 1 (6: 3 instead of 4), no step (never solved),
 * and >= for > in the check (5: 4 instead of 2). */
/* req: OGK-MPSP-005 */
static void test_segment_tolerance_widened_by_its_step(void **state)
{
    static const uint32_t n_seg_nom[2] = {5u, 6u};
    static const uint32_t expected_tol[2] = {2u, 4u};
    ogk_real_t target[6];
    size_t c;
    (void)state;
    nominal_target(target);
    target[0] += 1e-2;
    target[1] -= 5e-3;
    target[2] -= 5e-3;
    target[4] += 5e-3;
    for (c = 0u; c < 2u; ++c) {
        cfg_work = cfg;
        cfg_work.n_seg_nom = n_seg_nom[c];
        cfg_work.n_seg_tol = 0u;
        cfg_work.n_seg_tol_step = 2u;
        OGK_ASSERT_STATUS(ogk_mpsp_init(&ctx, &cfg_work), OGK_OK);
        assert_int_equal(ctx.n_seg_nom, n_seg_nom[c]);
        OGK_ASSERT_STATUS(ogk_mpsp_solve(&ctx, x0_3d, 1.0, target, &res), OGK_OK);
        assert_int_equal(res.converged, 1);
        assert_int_equal(res.n_seg_tol, expected_tol[c]);
        assert_int_equal(res.n_segments, 3);
        assert_true(res.outer_steps >= 2u);
        OGK_ASSERT_NEAR(res.tau_reached, 1.0, 0.0);
        check_flown(x0_3d, 1.0, target, OGK_TEST_TOL(1e-10, MPSP_TOL_F));
    }
}

/* req: OGK-MPSP-006 */
static void test_failure_returns_safe_command(void **state)
{
    ogk_real_t target[6];
    size_t i;
    (void)state;
    cfg_work = cfg;
    cfg_work.max_newton = 1u; /* one Newton step per inner loop cannot reach 1e-13 (float: 1e-8, below its floor) */
    cfg_work.tol_r = OGK_TEST_TOL(1e-13, 1e-8);
    cfg_work.tol_v = OGK_TEST_TOL(1e-13, 1e-8);
    cfg_work.tol_lambda_m = OGK_TEST_TOL(1e-13, 1e-8);
    OGK_ASSERT_STATUS(ogk_mpsp_init(&ctx, &cfg_work), OGK_OK);
    nominal_target(target);
    target[0] += 1e-2;
    target[1] -= 5e-3;
    target[2] -= 5e-3;
    OGK_ASSERT_STATUS(ogk_mpsp_solve(&ctx, x0_3d, 1.0, target, &res), OGK_E_NOT_CONVERGED);
    assert_int_equal(res.converged, 0);
    OGK_ASSERT_NEAR(res.tau_reached, 0.0, 0.0);
    for (i = 0u; i < ctx.n_weights; ++i) {
        OGK_ASSERT_NEAR(res.weights[i], cfg.weights_nom[i], 0.0);
    }
    OGK_ASSERT_NEAR(res.lambda_m0, cfg.lambda_m0_nom, 0.0);
    /* The safe command is reported as flown: it misses by the offset. */
    OGK_ASSERT_NEAR(res.err_r, sqrt(1e-4 + 2.0 * 25e-6), OGK_TEST_TOL(1e-9, 16.0 * FLT_EPSILON));
    /* Bounded: at most max_outer continuation loops, plus the direct one. */
    assert_true(res.inner_loops <= cfg_work.max_outer + 1u);
    assert_true(res.n_seg_tol > cfg_work.n_seg_tol); /* Alg. 2 widened N_seg,tol */
}

/* req: OGK-MPSP-007 */
static void test_init_rejects_bad_config(void **state)
{
    (void)state;
    OGK_ASSERT_STATUS(ogk_mpsp_init(NULL, &cfg), OGK_E_NULL);
    OGK_ASSERT_STATUS(ogk_mpsp_init(&ctx, NULL), OGK_E_NULL);
    cfg_work = cfg;
    cfg_work.mu = NAN;
    OGK_ASSERT_STATUS(ogk_mpsp_init(&ctx, &cfg_work), OGK_E_NONFINITE);
    assert_true(ctx.init_marker != OGK_MPSP_INIT_MARKER);
    cfg_work = cfg;
    cfg_work.weights_nom[20] = INFINITY;
    OGK_ASSERT_STATUS(ogk_mpsp_init(&ctx, &cfg_work), OGK_E_NONFINITE);
    cfg_work = cfg;
    cfg_work.fourier_order = 0u;
    OGK_ASSERT_STATUS(ogk_mpsp_init(&ctx, &cfg_work), OGK_E_CONFIG);
    cfg_work.fourier_order = OGK_MPSP_MAX_ORDER + 1u;
    OGK_ASSERT_STATUS(ogk_mpsp_init(&ctx, &cfg_work), OGK_E_CONFIG);
    cfg_work = cfg;
    cfg_work.h_max = (cfg.tf - cfg.t0) / ((double)OGK_MPSP_MAX_STEPS + 1.0);
    OGK_ASSERT_STATUS(ogk_mpsp_init(&ctx, &cfg_work), OGK_E_CONFIG);
    cfg_work.h_max = (cfg.tf - cfg.t0) / (double)OGK_MPSP_MAX_STEPS; /* exactly the limit */
    cfg_work.n_seg_nom = 3u;
    OGK_ASSERT_STATUS(ogk_mpsp_init(&ctx, &cfg_work), OGK_OK);
    cfg_work = cfg;
    cfg_work.tf = cfg.t0;
    OGK_ASSERT_STATUS(ogk_mpsp_init(&ctx, &cfg_work), OGK_E_CONFIG);
    cfg_work = cfg;
    cfg_work.r_eps[5] = 0.0;
    OGK_ASSERT_STATUS(ogk_mpsp_init(&ctx, &cfg_work), OGK_E_CONFIG);
    cfg_work = cfg;
    cfg_work.max_newton = 0u;
    OGK_ASSERT_STATUS(ogk_mpsp_init(&ctx, &cfg_work), OGK_E_CONFIG);
    cfg_work = cfg;
    cfg_work.delta_tau_min = cfg.delta_tau_0;
    OGK_ASSERT_STATUS(ogk_mpsp_init(&ctx, &cfg_work), OGK_E_CONFIG);
    cfg_work = cfg;
    cfg_work.x0_nom[6] = 0.0;
    OGK_ASSERT_STATUS(ogk_mpsp_init(&ctx, &cfg_work), OGK_E_CONFIG);
    /* A nominal that cannot be flown (lambda_v = 0 while S < 0) when N_seg,nom
     * must be counted at init. */
    cfg_work = cfg;
    (void)memset(cfg_work.weights_nom, 0, sizeof cfg_work.weights_nom);
    cfg_work.lambda_m0_nom = 2.0;
    OGK_ASSERT_STATUS(ogk_mpsp_init(&ctx, &cfg_work), OGK_E_CONFIG);
}

/* req: OGK-MPSP-008 */
static void test_entry_points_reject_bad_input(void **state)
{
    static ogk_mpsp_t blank;
    ogk_real_t x0[7];
    ogk_real_t target[6];
    ogk_real_t w[21];
    ogk_real_t lm0 = 0.0;
    ogk_real_t dy[NY] = {0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0};
    ogk_real_t xn[NX];
    ogk_real_t jx[NX * NX];
    ogk_mpsp_prop_t prop;
    (void)state;

    (void)memset(&blank, 0, sizeof blank);
    OGK_ASSERT_STATUS(ogk_mpsp_solve(&blank, x0_3d, 1.0, NULL, &res), OGK_E_NOT_INIT);
    OGK_ASSERT_STATUS(ogk_mpsp_propagate(&blank, w3, 0.0, x0_3d, 1.0, &prop), OGK_E_NOT_INIT);
    OGK_ASSERT_STATUS(ogk_mpsp_sensitivity(&blank, NULL, NULL), OGK_E_NOT_INIT);

    cfg_work = cfg;
    cfg_work.n_seg_nom = 3u; /* no propagation at init */
    OGK_ASSERT_STATUS(ogk_mpsp_init(&ctx, &cfg_work), OGK_OK);
    OGK_ASSERT_STATUS(ogk_mpsp_sensitivity(&ctx, NULL, NULL), OGK_E_NOT_INIT);
    (void)memcpy(w, w3, sizeof w);
    OGK_ASSERT_STATUS(ogk_mpsp_newton_update(&ctx, dy, w, &lm0), OGK_E_NOT_INIT);
    OGK_ASSERT_STATUS(ogk_mpsp_state_at(&ctx, 1.0, xn), OGK_E_NOT_INIT);

    OGK_ASSERT_STATUS(ogk_mpsp_solve(NULL, x0_3d, 1.0, NULL, &res), OGK_E_NULL);
    OGK_ASSERT_STATUS(ogk_mpsp_solve(&ctx, NULL, 1.0, NULL, &res), OGK_E_NULL);
    OGK_ASSERT_STATUS(ogk_mpsp_solve(&ctx, x0_3d, 1.0, NULL, NULL), OGK_E_NULL);
    (void)memcpy(x0, x0_3d, sizeof x0);
    x0[3] = NAN;
    OGK_ASSERT_STATUS(ogk_mpsp_solve(&ctx, x0, 1.0, NULL, &res), OGK_E_NONFINITE);
    OGK_ASSERT_STATUS(ogk_mpsp_propagate(&ctx, w3, 0.0, x0, 1.0, &prop), OGK_E_NONFINITE);
    x0[3] = 0.0;
    x0[6] = 0.0;
    OGK_ASSERT_STATUS(ogk_mpsp_solve(&ctx, x0, 1.0, NULL, &res), OGK_E_RANGE);
    OGK_ASSERT_STATUS(ogk_mpsp_solve(&ctx, x0_3d, 0.0, NULL, &res), OGK_E_RANGE);
    OGK_ASSERT_STATUS(ogk_mpsp_solve(&ctx, x0_3d, NAN, NULL, &res), OGK_E_NONFINITE);
    nominal_target(target);
    target[5] = INFINITY;
    OGK_ASSERT_STATUS(ogk_mpsp_solve(&ctx, x0_3d, 1.0, target, &res), OGK_E_NONFINITE);
    w[4] = NAN;
    OGK_ASSERT_STATUS(ogk_mpsp_propagate(&ctx, w, 0.0, x0_3d, 1.0, &prop), OGK_E_NONFINITE);
    OGK_ASSERT_STATUS(ogk_mpsp_propagate(&ctx, w3, NAN, x0_3d, 1.0, &prop), OGK_E_NONFINITE);
    {
        const ogk_real_t x8[NX] = {1.0, 0.0, 0.01, 0.0, 1.0, 0.02, 1.0, 0.0};
        OGK_ASSERT_STATUS(ogk_mpsp_step_jacobian(&ctx, w3, 1.0, 0.0, x8, 0.0, 1, xn, jx, NULL),
                          OGK_E_RANGE);
        OGK_ASSERT_STATUS(ogk_mpsp_step_jacobian(&ctx, w3, 1.0, 0.0, x8, 0.1, 2, xn, jx, NULL),
                          OGK_E_RANGE);
        OGK_ASSERT_STATUS(ogk_mpsp_step_jacobian(&ctx, w3, 1.0, 0.0, x8, 0.1, 1, NULL, jx, NULL),
                          OGK_E_NULL);
        OGK_ASSERT_STATUS(ogk_mpsp_switch_jump(&ctx, w3, 1.0, 0.5, NULL, 1, jx, NULL, NULL, NULL),
                          OGK_E_NULL);
        OGK_ASSERT_STATUS(ogk_mpsp_switch_jump(&ctx, w3, -1.0, 0.5, x8, 1, jx, NULL, NULL, NULL),
                          OGK_E_RANGE);
    }
    /* Thrusting with lambda_v = 0 (eq. 8 undefined): lambda_m0 = 2 makes S < 0. */
    (void)memset(w, 0, sizeof w);
    OGK_ASSERT_STATUS(ogk_mpsp_propagate(&ctx, w, 2.0, x0_3d, 1.0, &prop), OGK_E_CALLBACK);
    /* |lambda_v| = 1 + 0.5 cos(3 th), th = 2 pi t / period, t in [0, 2]: S = 0
     * is crossed 24 times for period 0.5 (more than OGK_MPSP_MAX_SWITCHES) and
     * 12 times for period 1. */
    cfg_work.fourier_period = 0.5;
    OGK_ASSERT_STATUS(ogk_mpsp_init(&ctx, &cfg_work), OGK_OK);
    w[0] = 2.0;
    w[5] = 0.5;
    OGK_ASSERT_STATUS(ogk_mpsp_propagate(&ctx, w, 0.0, x0_3d, 0.01, &prop),
                      OGK_E_SWITCH_OVERFLOW);
    assert_true(prop.n_switches > OGK_MPSP_MAX_SWITCHES);
    OGK_ASSERT_STATUS(ogk_mpsp_sensitivity(&ctx, NULL, NULL), OGK_E_NOT_INIT);
    cfg_work.fourier_period = 1.0;
    OGK_ASSERT_STATUS(ogk_mpsp_init(&ctx, &cfg_work), OGK_OK);
    OGK_ASSERT_STATUS(ogk_mpsp_propagate(&ctx, w, 0.0, x0_3d, 0.01, &prop), OGK_OK);
    assert_int_equal(prop.n_switches, 12);
}

/* The contract: config_default holds the paper's algorithm settings and
 * zeros for the mission data (rejected); reset returns to the init state. */
/* req: OGK-MPSP-007 */
static void test_config_default_and_reset(void **state)
{
    static ogk_mpsp_result_t first;
    size_t n_nodes_init;
    size_t i;
    (void)state;
    OGK_ASSERT_STATUS(ogk_mpsp_config_default(NULL), OGK_E_NULL);
    (void)memset(&cfg_work, 0xA5, sizeof cfg_work);
    OGK_ASSERT_STATUS(ogk_mpsp_config_default(&cfg_work), OGK_OK);
    OGK_ASSERT_NEAR(cfg_work.delta_max, 1.0, 0.0);
    OGK_ASSERT_NEAR(cfg_work.delta_tau_0, 0.5, 0.0);
    OGK_ASSERT_NEAR(cfg_work.delta_tau_min, (ogk_real_t)0.1, 0.0);
    OGK_ASSERT_NEAR(cfg_work.r_lambda, 1.0, 0.0);
    OGK_ASSERT_NEAR(cfg_work.s_tol, (ogk_real_t)1e-12, 0.0); /* the kernel's default, as stored */
    for (i = 0u; i < OGK_MPSP_MAX_WEIGHTS; ++i) {
        OGK_ASSERT_NEAR(cfg_work.r_eps[i], 1.0, 0.0);
    }
    assert_int_equal(cfg_work.max_newton, 100u);
    assert_int_equal(cfg_work.max_outer, 50u);
    assert_int_equal(cfg_work.n_seg_tol, 0u);
    assert_int_equal(cfg_work.n_seg_tol_step, 2u);
    assert_int_equal(cfg_work.n_seg_nom, 0u);
    assert_int_equal(cfg_work.fourier_kind, OGK_MPSP_BASIS_FOURIER);
    OGK_ASSERT_NEAR(cfg_work.mu + cfg_work.t_max + cfg_work.tf + cfg_work.h_max, 0.0, 0.0);
    OGK_ASSERT_STATUS(ogk_mpsp_init(&ctx, &cfg_work), OGK_E_CONFIG); /* mission data unset */
    assert_true(ctx.init_marker != OGK_MPSP_INIT_MARKER);
    OGK_ASSERT_STATUS(ogk_mpsp_reset(&ctx), OGK_E_NOT_INIT);
    OGK_ASSERT_STATUS(ogk_mpsp_reset(NULL), OGK_E_NULL);

    /* the mission data set on top of the defaults: the test's own nominal */
    cfg_work.mu = cfg.mu;
    cfg_work.t_max = cfg.t_max;
    cfg_work.c_exhaust = cfg.c_exhaust;
    cfg_work.t0 = cfg.t0;
    cfg_work.tf = cfg.tf;
    (void)memcpy(cfg_work.x0_nom, cfg.x0_nom, sizeof cfg.x0_nom);
    (void)memcpy(cfg_work.r_f, cfg.r_f, sizeof cfg.r_f);
    (void)memcpy(cfg_work.v_f, cfg.v_f, sizeof cfg.v_f);
    cfg_work.fourier_order = cfg.fourier_order;
    cfg_work.fourier_period = cfg.fourier_period;
    cfg_work.h_max = cfg.h_max;
    cfg_work.tol_r = cfg.tol_r;
    cfg_work.tol_v = cfg.tol_v;
    cfg_work.tol_lambda_m = cfg.tol_lambda_m;
    (void)memcpy(cfg_work.weights_nom, cfg.weights_nom, sizeof cfg.weights_nom);
    cfg_work.lambda_m0_nom = cfg.lambda_m0_nom;
    OGK_ASSERT_STATUS(ogk_mpsp_init(&ctx, &cfg_work), OGK_OK);
    assert_true(ctx.init_marker == OGK_MPSP_INIT_MARKER);
    assert_int_equal(ctx.n_seg_nom, 3);
    n_nodes_init = ctx.n_nodes;
    {
        ogk_real_t target[6];
        nominal_target(target);
        target[0] += 1e-2;
        OGK_ASSERT_STATUS(ogk_mpsp_solve(&ctx, x0_3d, 1.0, target, &first), OGK_OK);
        OGK_ASSERT_STATUS(ogk_mpsp_reset(&ctx), OGK_OK);
        assert_true(ctx.init_marker == OGK_MPSP_INIT_MARKER);
        assert_int_equal(ctx.n_nodes, n_nodes_init);
        assert_int_equal(ctx.sens_valid, 0u);
        assert_int_equal(ctx.n_seg_nom, 3);
        OGK_ASSERT_STATUS(ogk_mpsp_solve(&ctx, x0_3d, 1.0, target, &res), OGK_OK);
        assert_true(memcmp(&first, &res, sizeof res) == 0);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_nominal_needs_no_iteration),
        cmocka_unit_test(test_newton_recovers_perturbed_target),
        cmocka_unit_test(test_mid2_sweep_same_iterations),
        cmocka_unit_test(test_thrust_and_initial_state_perturbations),
        cmocka_unit_test(test_continuation_when_newton_is_not_allowed),
        cmocka_unit_test(test_segment_tolerance_widened_by_its_step),
        cmocka_unit_test(test_newton_budget_is_exact),
        cmocka_unit_test(test_failure_returns_safe_command),
        cmocka_unit_test(test_init_rejects_bad_config),
        cmocka_unit_test(test_entry_points_reject_bad_input),
        cmocka_unit_test(test_config_default_and_reset),
    };
    return cmocka_run_group_tests(tests, setup, NULL);
}
