/* test_gate_misc.c -- paths of rk4.c, linalg.c and the MPSP read-outs that the other tests leave
 * unrun (make coverage, docs/coverage.md):
 *  - RK4: each problem check, non-finite arguments, a switching function that returns NaN, a
 *    step shorter than the slop (one step), S = 0 everywhere (no event), a bisection that
 *    runs to the last bit of the bracket, a switch located at the very end of a step, and the
 *    dense output filling up exactly at a switch node;
 *  - linalg: a factorization or check that fails on its first entry (the loops stop there), and
 *    a right-hand side inside the QR workspace;
 *  - MPSP: every range check of the configuration one by one, the held weights propagated
 *    again, trajectory copies without some outputs, the state read-out against an RK4 step,
 *    partial Jacobian and jump outputs against the full ones, and a control rate overflow. */
#include "ogk_test.h"

#include <float.h>
#include <string.h>

#include "mpsp_fixture.h"
#include "ogk/internal/mpsp_test.h" /* ogk_mpsp_step_jacobian, ogk_mpsp_switch_jump */
#include "ogk/linalg.h"
#include "ogk/mpsp.h"
#include "ogk/rk4.h"

/* ------------------------------------------------------------------ rk4 */

/* mode 1: x' = -x, mode 0: x' = +x */
static ogk_status rhs_decay(void *user, double t, const double *x, int mode, double *xdot)
{
    (void)user;
    (void)t;
    xdot[0] = (mode != 0) ? -x[0] : x[0];
    return OGK_OK;
}

/* S = t - t_root, with t_root in *user */
static ogk_status sw_root(void *user, double t, const double *x, int mode, double *s)
{
    const double *t_root = (const double *)user;
    (void)x;
    (void)mode;
    *s = t - *t_root;
    return OGK_OK;
}

/* S = (t - t_root) - 1e-17: t - t_root is a multiple of 2^-54 for t, t_root in [0.25, 0.5),
 * so S is never exactly 0 on a double there */
static ogk_status sw_root_off(void *user, double t, const double *x, int mode, double *s)
{
    const double *t_root = (const double *)user;
    (void)x;
    (void)mode;
    *s = (t - *t_root) - 1e-17;
    return OGK_OK;
}

static ogk_status sw_zero(void *user, double t, const double *x, int mode, double *s)
{
    (void)user;
    (void)t;
    (void)x;
    (void)mode;
    *s = 0.0;
    return OGK_OK;
}

static ogk_status sw_nan(void *user, double t, const double *x, int mode, double *s)
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
    const double x0[1] = {1.0};
    double xf[1] = {-7.0};
    double xn[1] = {-7.0};
    double dt_buf[4];
    double dx_buf[4];
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
        const double bad[1] = {NAN};
        OGK_ASSERT_STATUS(ogk_rk4_step(&p, 0.0, bad, 0.1, 1, xn), OGK_E_NONFINITE);
    }
    {
        /* two states, the first one NaN: found without looking further */
        const double bad2[2] = {NAN, 0.0};
        double xn2[2] = {-7.0, -7.0};
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
    const double x0[1] = {1.0};
    double xf[1];
    (void)state;
    /* tf - t0 far below one step h (ratio under the slop): one step of tf - t0 */
    p = problem(NULL, NULL);
    p.h = 1.0;
    OGK_ASSERT_STATUS(ogk_rk4_propagate(&p, 0.0, x0, 1, 1e-12, &res, xf, NULL), OGK_OK);
    assert_int_equal(res.n_steps, 1u);
    OGK_ASSERT_NEAR(res.t_reached, 1e-12, 0.0);
    OGK_ASSERT_REL(xf[0], 1.0 - 1e-12, 1e-15, 0.0);
    /* S identically 0: no sign to leave, so no event; plain decay */
    p = problem(sw_zero, NULL);
    OGK_ASSERT_STATUS(ogk_rk4_propagate(&p, 0.0, x0, 1, 1.0, &res, xf, NULL), OGK_OK);
    assert_int_equal(res.n_switches, 0u);
    assert_int_equal(res.mode_final, 1);
    OGK_ASSERT_REL(xf[0], exp(-1.0), 1e-4, 0.0);
    /* S never exactly 0 on a double and s_tol = 0, t_tol = 1e-300 below any bracket: the
     * bisection runs to the last bit of the bracket and accepts its far end */
    t_root = 0.37;
    p = problem(sw_root_off, &t_root);
    p.s_tol = 0.0;
    p.t_tol = 1e-300;
    OGK_ASSERT_STATUS(ogk_rk4_propagate(&p, 0.0, x0, 1, 1.0, &res, xf, NULL), OGK_OK);
    assert_int_equal(res.n_switches, 1u);
    assert_int_equal(res.sw[0].how, OGK_SWITCH_BY_TIME_TOL);
    assert_true(res.sw[0].bisections > 40u);
    assert_true(res.sw[0].s > 0.0); /* the far end: S already of the new sign */
    OGK_ASSERT_NEAR(res.sw[0].t, 0.37, 2e-16);
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
    const double x0[1] = {1.0};
    double xf[1];
    double dt_buf[2];
    double dx_buf[2];
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
    OGK_ASSERT_NEAR(res.t_reached, 0.37, 1e-9); /* stopped at the switch */
}

/* ------------------------------------------------------------------ linalg */

static ogk_qr_t qr_ws;

/* req: OGK-CORE-021 OGK-CORE-011 */
static void test_linalg_first_entry_failures(void **state)
{
    ogk_lu_t lu;
    ogk_chol_t ch;
    const double A2[4] = {4.0, 1.0, 1.0, 3.0};
    const double b2[2] = {1.0, 2.0};
    double x[3] = {-7.0, -7.0, -7.0};
    (void)state;
    /* the first permutation entry out of range: found before the others are looked at */
    OGK_ASSERT_STATUS(ogk_lu_factor(&lu, A2, 2u), OGK_OK);
    lu.perm[0] = 7u;
    OGK_ASSERT_STATUS(ogk_lu_solve(&lu, b2, x), OGK_E_NOT_INIT);
    OGK_ASSERT_NEAR(x[0], -7.0, 0.0);
    {
        /* not symmetric in its first off-diagonal pair (1, 0) / (0, 1) */
        const double A3[9] = {4.0, 1.0, 0.0, 2.0, 4.0, 0.0, 0.0, 0.0, 4.0};
        OGK_ASSERT_STATUS(ogk_chol_factor(&ch, A3, 3u), OGK_E_NOT_POSDEF);
        assert_int_equal(ch.n, 0u);
    }
    {
        /* not symmetric in the pair (2, 0) / (0, 2), found before (2, 1) is looked at */
        const double A3[9] = {4.0, 0.0, 1.0, 0.0, 4.0, 0.0, 2.0, 0.0, 4.0};
        OGK_ASSERT_STATUS(ogk_chol_factor(&ch, A3, 3u), OGK_E_NOT_POSDEF);
        assert_int_equal(ch.n, 0u);
    }
    {
        /* negative first pivot */
        const double A3[9] = {-1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0};
        OGK_ASSERT_STATUS(ogk_chol_factor(&ch, A3, 3u), OGK_E_NOT_POSDEF);
        assert_int_equal(ch.n, 0u);
    }
    {
        /* first column zero: rank deficient from the first diagonal entry of R */
        const double A32[6] = {0.0, 1.0, 0.0, 2.0, 0.0, 3.0};
        const double b3[3] = {1.0, 2.0, 3.0};
        OGK_ASSERT_STATUS(ogk_lstsq(&qr_ws, A32, 3u, 2u, b3, x), OGK_E_SINGULAR);
        /* a right-hand side that lies inside the workspace */
        OGK_ASSERT_STATUS(ogk_lstsq(&qr_ws, A32, 3u, 2u, qr_ws.tau, x), OGK_E_RANGE);
        /* and a solution that would be written into it */
        OGK_ASSERT_STATUS(ogk_lstsq(&qr_ws, A32, 3u, 2u, b3, qr_ws.tau), OGK_E_RANGE);
        OGK_ASSERT_NEAR(x[0], -7.0, 0.0);
    }
}

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
        case 22u: /* the basis phase omega (tf - t_ref) overflows at tf only */
            c.tf = 1e300;
            c.h_max = 1e299;
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

static double traj_t[OGK_MPSP_MAX_NODES];
static double traj_x[OGK_MPSP_MAX_NODES * 8u];
static uint8_t traj_mode[OGK_MPSP_MAX_NODES];

/* req: OGK-MPSP-009 */
static void test_mpsp_readouts(void **state)
{
    ogk_mpsp_prop_t a;
    ogk_mpsp_prop_t b;
    size_t count = 0u;
    size_t n;
    size_t i;
    double x[8];
    double xn[8];
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
    double lv[3] = {-7.0, -7.0, -7.0};
    double lvd[3];
    double w[21];
    size_t c;
    (void)state;
    OGK_ASSERT_STATUS(ogk_mpsp_control(&ctx, NULL, 0.0, lv, NULL), OGK_E_NULL);
    OGK_ASSERT_STATUS(ogk_mpsp_control(&ctx, w3, 0.0, NULL, NULL), OGK_E_NULL);
    (void)memcpy(w, w3, sizeof w);
    w[4] = NAN;
    OGK_ASSERT_STATUS(ogk_mpsp_control(&ctx, w, 0.0, lv, NULL), OGK_E_NONFINITE);
    OGK_ASSERT_NEAR(lv[0], -7.0, 0.0);
    /* sine weights of 1e308 at t = t_ref: lambda_v = 0 exactly (every sine is 0), its rate
     * 1e308 (w + 2 w + 3 w) omega overflows */
    (void)memset(w, 0, sizeof w);
    for (c = 0u; c < 3u; ++c) {
        w[c * 7u + 2u] = 1e308;
        w[c * 7u + 4u] = 1e308;
        w[c * 7u + 6u] = 1e308;
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
    double dy[OGK_MPSP_NY];
    double w[21];
    double lm = 0.25;
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
static double jx_full[64];
static double jw_full[8u * 21u];
static double jx_part[64];
static double jw_part[8u * 21u];

/* req: OGK-MPSP-003 */
static void test_mpsp_partial_jacobians(void **state)
{
    double x[8];
    double bad[8];
    double w_bad[21];
    double xn[8];
    double dx_full[8];
    double dw_full[21];
    double dx_part[8];
    double dw_part[21];
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
    double x[8];
    double w[21];
    double jx[64];
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
        w[c * 7u + 2u] = 1e308;
        w[c * 7u + 4u] = 1e308;
        w[c * 7u + 6u] = 1e308;
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
        OGK_ASSERT_NEAR(prop.x_f[i], c.r_f[i], 1e-9);
        OGK_ASSERT_NEAR(prop.x_f[3u + i], c.v_f[i], 1e-9);
    }
    OGK_ASSERT_NEAR(prop.x_f[7], 0.0, 1e-9);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_rk4_problem_and_argument_checks),
        cmocka_unit_test(test_rk4_degenerate_grids_and_switches),
        cmocka_unit_test(test_rk4_dense_full_at_switch),
        cmocka_unit_test(test_linalg_first_entry_failures),
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
