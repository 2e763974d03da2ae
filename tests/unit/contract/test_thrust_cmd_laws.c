/* test_thrust_cmd_laws.c -- each law's contract call for the one thrust command (ogk/types.h)
 * against an independent closed form, and the command fed to CPD:
 *   - NMPC (ogk_nmpc_thrust_cmd): the model thrusts along cos(a) r_hat + sin(a) theta_hat, a from
 *     the local vertical; types.h's direction is (cos b sin alpha, cos b cos alpha, sin b) in
 *     (r, t, n) with t = theta_hat in the plane. Equating the two: b = 0, sin alpha = cos a,
 *     cos alpha = sin a, i.e. alpha = pi/2 - a (mod 2 pi): the 90-degree relation checked here,
 *     with the node angles spanning more than a turn, a throttled engine, the end of the plan and
 *     every safe command; and CPD fed it equals CPD fed the same thrust as an inertial Cartesian
 *     vector at polar angle theta;
 *   - MPSP (ogk_mpsp_thrust_cmd): u = -lambda_v / |lambda_v| with lambda_v from the Fourier basis
 *     written out here (Appendix C), throttle = [S < 0] with S = 1 - lambda_m - |lambda_v| c / m
 *     (eq. 10) from the held trajectory's state; the rejections;
 *   - BLT (ogk_blt_thrust_cmd): u = (A + B tau) / |A + B tau| (eq. 22) in a burn, the next burn's
 *     A / |A| in a coast, (1, 0, 0) after the end; the synodic command rotated to inertial by
 *     the binary's angle, then to CPD. */
#include "ogk_test.h"

/* Float tolerances (ogk_test.h): a unit vector's component or an angle (at most pi) made of sines and
 * cosines of float angles carries a few roundings: CMD_EPS = 8 eps pi; in double the tolerances as
 * always. Copies of the caller's values are compared with those values as stored (ogk_real_t). */
#define CMD_EPS (8.0 * FLT_EPSILON * 3.14159265358979323846)

#include <stdbool.h>
#include <string.h>

#include "ogk/blt.h"
#include "ogk/cpd.h"
#include "ogk/mpsp.h"
#include "ogk/nmpc.h"
#include "ogk/thrust_cmd.h"
#include "ogk/types.h"

#include "blt_fixture.h"
#include "mpsp_fixture.h"
#include "nmpc_fixture.h"

#define PI 3.14159265358979323846

static ogk_nmpc_t nmpc;
static ogk_nmpc_plan_t plan;
static ogk_mpsp_t mpsp;
static ogk_blt_t blt;

/* a - b reduced to (-pi, pi] */
static double angle_diff(double a, double b)
{
    double d = fmod(a - b, 2.0 * PI);
    if (d > PI) {
        d -= 2.0 * PI;
    } else if (d <= -PI) {
        d += 2.0 * PI;
    } else {
        /* in range */
    }
    return d;
}

static void assert_unit_and_angles(const ogk_thrust_cmd_t *c)
{
    OGK_ASSERT_NEAR(sqrt((c->u[0] * c->u[0]) + (c->u[1] * c->u[1]) + (c->u[2] * c->u[2])), 1.0, OGK_TEST_TOL(1e-15, CMD_EPS));
    if (c->frame == OGK_FRAME_RTN) {
        OGK_ASSERT_NEAR(c->u[0], cos(c->beta_rad) * sin(c->alpha_rad), OGK_TEST_TOL(1e-15, CMD_EPS));
        OGK_ASSERT_NEAR(c->u[1], cos(c->beta_rad) * cos(c->alpha_rad), OGK_TEST_TOL(1e-15, CMD_EPS));
        OGK_ASSERT_NEAR(c->u[2], sin(c->beta_rad), OGK_TEST_TOL(1e-15, CMD_EPS));
    } else {
        OGK_ASSERT_NEAR(c->alpha_rad, 0.0, 0.0);
        OGK_ASSERT_NEAR(c->beta_rad, 0.0, 0.0);
    }
}

/* ------------------------------------------------------------------ NMPC */

#define NMPC_N 6u
#define NMPC_TF 4.0

/* A plan of NMPC_N subintervals over [0, NMPC_TF] with node angles from -3.5 to 4.0 rad (more
 * than a turn) and, throttled, node throttles including 0. */
static void nmpc_setup(uint32_t engine)
{
    static const double alpha[NMPC_N + 1u] = {-3.5, -2.0, 0.0, 0.5 * 3.14159265358979323846, 1.0, 2.5, 4.0};
    static const double w[NMPC_N + 1u] = {1.0, 0.5, 0.0, 0.25, 1.0, 0.75, 1.0};
    ogk_nmpc_config_t c;
    uint32_t k;
    nmpc_fx_mars(&c, NMPC_N);
    c.engine = engine;
    OGK_ASSERT_STATUS(ogk_nmpc_init(&nmpc, &c), OGK_OK);
    nmpc_fx_mars_guess(&c, NMPC_N, NMPC_TF, &plan);
    plan.nu = (engine == OGK_NMPC_ENGINE_THROTTLED) ? 2u : 1u;
    for (k = 0u; k <= NMPC_N; ++k) {
        plan.u[k * plan.nu] = alpha[k];
        if (plan.nu == 2u) {
            plan.u[(k * plan.nu) + 1u] = w[k];
        }
    }
    OGK_ASSERT_STATUS(ogk_nmpc_load_plan(&nmpc, &plan), OGK_OK);
}

/* req: OGK-NMPC-009 */
static void test_nmpc_angle_from_the_vertical(void **state)
{
    uint32_t i;
    ogk_nmpc_command_t nc;
    ogk_thrust_cmd_t c;
    (void)state;
    nmpc_setup(OGK_NMPC_ENGINE_CONSTANT);
    for (i = 0u; i <= 48u; ++i) {
        const double t = NMPC_TF * (double)i / 48.0;
        OGK_ASSERT_STATUS(ogk_nmpc_command(&nmpc, t, &nc), OGK_OK);
        OGK_ASSERT_STATUS(ogk_nmpc_thrust_cmd(&nmpc, t, &c), OGK_OK);
        assert_int_equal((int)c.frame, (int)OGK_FRAME_RTN);
        OGK_ASSERT_NEAR(angle_diff(c.alpha_rad, (0.5 * PI) - nc.alpha), 0.0, OGK_TEST_TOL(1e-14, CMD_EPS));
        assert_true((c.alpha_rad > -PI) && (c.alpha_rad <= PI));
        OGK_ASSERT_NEAR(c.beta_rad, 0.0, 0.0);
        OGK_ASSERT_NEAR(c.u[0], cos(nc.alpha), OGK_TEST_TOL(1e-15, CMD_EPS)); /* radial */
        OGK_ASSERT_NEAR(c.u[1], sin(nc.alpha), OGK_TEST_TOL(1e-15, CMD_EPS)); /* along theta_hat = t */
        OGK_ASSERT_NEAR(c.u[2], 0.0, 0.0);
        assert_unit_and_angles(&c);
        OGK_ASSERT_NEAR(c.throttle, 1.0, 0.0);
        OGK_ASSERT_NEAR(c.t_s, (ogk_real_t)t, 0.0);
        assert_int_equal(c.flags, OGK_THRUST_FLAG_ENGINE_ON);
        assert_int_equal(c.law_flags, nc.law_flags);
    }
    /* the node angles themselves: a = 0 (radially out) is alpha = pi/2, a = pi/2 (along t) is 0 */
    OGK_ASSERT_STATUS(ogk_nmpc_thrust_cmd(&nmpc, 2.0 * NMPC_TF / (double)NMPC_N, &c), OGK_OK);
    OGK_ASSERT_NEAR(c.alpha_rad, 0.5 * PI, OGK_TEST_TOL(1e-15, CMD_EPS));
    OGK_ASSERT_STATUS(ogk_nmpc_thrust_cmd(&nmpc, 3.0 * NMPC_TF / (double)NMPC_N, &c), OGK_OK);
    OGK_ASSERT_NEAR(c.alpha_rad, 0.0, OGK_TEST_TOL(1e-15, CMD_EPS));
    /* node 0: a = -3.5, alpha = pi/2 + 3.5 - 2 pi */
    OGK_ASSERT_STATUS(ogk_nmpc_thrust_cmd(&nmpc, 0.0, &c), OGK_OK);
    OGK_ASSERT_NEAR(c.alpha_rad, (0.5 * PI) + 3.5 - (2.0 * PI), OGK_TEST_TOL(1e-14, CMD_EPS));
    /* past t_f: the last node's, END_OF_PLAN */
    OGK_ASSERT_STATUS(ogk_nmpc_thrust_cmd(&nmpc, NMPC_TF + 1.0, &c), OGK_OK);
    assert_true((c.law_flags & OGK_NMPC_FLAG_END_OF_PLAN) != 0u);
    OGK_ASSERT_NEAR(angle_diff(c.alpha_rad, (0.5 * PI) - 4.0), 0.0, OGK_TEST_TOL(1e-14, CMD_EPS));
}

/* req: OGK-NMPC-009 */
static void test_nmpc_throttle_and_safe(void **state)
{
    ogk_thrust_cmd_t c;
    ogk_nmpc_t zero;
    (void)state;
    nmpc_setup(OGK_NMPC_ENGINE_THROTTLED);
    OGK_ASSERT_STATUS(ogk_nmpc_thrust_cmd(&nmpc, 1.0 * NMPC_TF / (double)NMPC_N, &c), OGK_OK);
    OGK_ASSERT_NEAR(c.throttle, 0.5, OGK_TEST_TOL(1e-15, CMD_EPS));
    assert_int_equal(c.flags, OGK_THRUST_FLAG_ENGINE_ON);
    OGK_ASSERT_STATUS(ogk_nmpc_thrust_cmd(&nmpc, 2.0 * NMPC_TF / (double)NMPC_N, &c), OGK_OK);
    OGK_ASSERT_NEAR(c.throttle, 0.0, 0.0); /* w = 0: engine off, still a direction */
    assert_int_equal(c.flags, 0u);
    assert_unit_and_angles(&c);
    OGK_ASSERT_STATUS(ogk_nmpc_thrust_cmd(&nmpc, 2.5 * NMPC_TF / (double)NMPC_N, &c), OGK_OK);
    OGK_ASSERT_NEAR(c.throttle, 0.125, OGK_TEST_TOL(1e-15, CMD_EPS));
    /* the safe commands: NMPC's (engine off, a = 0: radially out) converted */
    OGK_ASSERT_STATUS(ogk_nmpc_thrust_cmd(&nmpc, NAN, &c), OGK_E_NONFINITE);
    OGK_ASSERT_NEAR(c.t_s, 0.0, 0.0);
    OGK_ASSERT_NEAR(c.alpha_rad, (ogk_real_t)(0.5 * PI), 0.0);
    OGK_ASSERT_NEAR(c.u[0], 1.0, 0.0);
    OGK_ASSERT_NEAR(c.throttle, 0.0, 0.0);
    assert_int_equal(c.flags, OGK_THRUST_FLAG_SAFE);
    OGK_ASSERT_STATUS(ogk_nmpc_reset(&nmpc), OGK_OK); /* no plan */
    OGK_ASSERT_STATUS(ogk_nmpc_thrust_cmd(&nmpc, 1.0, &c), OGK_E_RANGE);
    assert_int_equal(c.flags, OGK_THRUST_FLAG_SAFE);
    OGK_ASSERT_NEAR(c.t_s, 1.0, 0.0);
    (void)memset(&zero, 0, sizeof zero);
    OGK_ASSERT_STATUS(ogk_nmpc_thrust_cmd(&zero, 1.0, &c), OGK_E_NOT_INIT);
    assert_int_equal(c.flags, OGK_THRUST_FLAG_SAFE);
    OGK_ASSERT_STATUS(ogk_nmpc_thrust_cmd(NULL, 1.0, &c), OGK_E_NULL);
    assert_int_equal(c.flags, OGK_THRUST_FLAG_SAFE);
    OGK_ASSERT_STATUS(ogk_nmpc_thrust_cmd(&nmpc, 1.0, NULL), OGK_E_NULL);
}

/* CPD fed NMPC's r-t-n command equals CPD fed the same thrust as an inertial Cartesian vector,
 * cos(a) (cos theta, sin theta, 0) + sin(a) (-sin theta, cos theta, 0), at polar angle theta. */
/* req: OGK-NMPC-009 OGK-CPD-010 */
static void test_nmpc_feeds_cpd(void **state)
{
    ogk_nmpc_command_t nc;
    ogk_thrust_cmd_t c;
    ogk_thrust_cmd_t cart;
    ogk_cpd_input_t in_a;
    ogk_cpd_input_t in_b;
    ogk_nav_state_t nav;
    uint32_t i;
    (void)state;
    nmpc_setup(OGK_NMPC_ENGINE_CONSTANT);
    for (i = 0u; i < 8u; ++i) {
        const double t = 0.45 * (double)i;
        const double theta = -2.5 + (0.7 * (double)i);
        ogk_real_t u_i[3];
        OGK_ASSERT_STATUS(ogk_nmpc_command(&nmpc, t, &nc), OGK_OK);
        OGK_ASSERT_STATUS(ogk_nmpc_thrust_cmd(&nmpc, t, &c), OGK_OK);
        u_i[0] = (cos(nc.alpha) * cos(theta)) - (sin(nc.alpha) * sin(theta));
        u_i[1] = (cos(nc.alpha) * sin(theta)) + (sin(nc.alpha) * cos(theta));
        u_i[2] = 0.0;
        OGK_ASSERT_STATUS(ogk_thrust_cmd_from_unit(t, OGK_FRAME_INERTIAL, u_i, 1.0,
                                                   OGK_THRUST_FLAG_ENGINE_ON, 0u, &cart), OGK_OK);
        (void)memset(&nav, 0, sizeof nav);
        nav.xi_rad = theta;
        (void)memset(&in_a, 0, sizeof in_a);
        (void)memset(&in_b, 0, sizeof in_b);
        OGK_ASSERT_STATUS(ogk_cpd_input_from_thrust_cmd(&in_a, &c, &nav), OGK_OK);
        OGK_ASSERT_STATUS(ogk_cpd_input_from_thrust_cmd(&in_b, &cart, &nav), OGK_OK);
        OGK_ASSERT_NEAR(angle_diff(in_a.alpha_c, in_b.alpha_c), 0.0, OGK_TEST_TOL(1e-14, CMD_EPS));
        OGK_ASSERT_NEAR(in_a.beta_c, 0.0, 0.0);
        OGK_ASSERT_NEAR(in_b.beta_c, 0.0, OGK_TEST_TOL(1e-15, CMD_EPS));
    }
}

/* ------------------------------------------------------------------ MPSP */

/* lambda_v(t) of the fixture's weights w3: FOURIER basis of order 3 (Appendix C) written out. */
static void mpsp_lambda_v(const ogk_mpsp_config_t *c, const ogk_real_t *w, double t, double *lv)
{
    const double th = 2.0 * PI * (t - c->fourier_t_ref) / c->fourier_period;
    const double h[7] = {0.5, cos(th), sin(th), cos(2.0 * th), sin(2.0 * th), cos(3.0 * th), sin(3.0 * th)};
    size_t i;
    size_t q;
    for (i = 0u; i < 3u; ++i) {
        lv[i] = 0.0;
        for (q = 0u; q < 7u; ++q) {
            lv[i] += h[q] * w[(i * 7u) + q];
        }
    }
}

/* req: OGK-MPSP-010 */
static void test_mpsp_primer_vector_and_bang_off_bang(void **state)
{
    ogk_mpsp_config_t c;
    ogk_mpsp_prop_t prop;
    ogk_thrust_cmd_t cmd;
    uint32_t i;
    uint32_t n_thrust = 0u;
    uint32_t n_coast = 0u;
    (void)state;
    OGK_ASSERT_STATUS(mpsp_fixture_config(&c, 20u, 30u), OGK_OK);
    OGK_ASSERT_STATUS(ogk_mpsp_init(&mpsp, &c), OGK_OK);
    /* no trajectory held yet (n_seg_nom given: init propagates nothing) */
    OGK_ASSERT_STATUS(ogk_mpsp_thrust_cmd(&mpsp, 1.0, &cmd), OGK_E_NOT_INIT);
    OGK_ASSERT_STATUS(ogk_mpsp_propagate(&mpsp, w3, 0.0, x0_3d, 1.0, &prop), OGK_OK);
    assert_true(prop.n_switches >= 1u);
    for (i = 0u; i <= 200u; ++i) {
        const double t = c.t0 + ((c.tf - c.t0) * (double)i / 200.0);
        double lv[3];
        ogk_real_t x[OGK_MPSP_NX];
        double nlv;
        double s;
        bool near_switch = false;
        uint32_t j;
        OGK_ASSERT_STATUS(ogk_mpsp_thrust_cmd(&mpsp, t, &cmd), OGK_OK);
        assert_int_equal((int)cmd.frame, (int)OGK_FRAME_INERTIAL);
        assert_unit_and_angles(&cmd);
        mpsp_lambda_v(&c, w3, t, lv);
        nlv = sqrt((lv[0] * lv[0]) + (lv[1] * lv[1]) + (lv[2] * lv[2]));
        OGK_ASSERT_NEAR(cmd.u[0], -lv[0] / nlv, OGK_TEST_TOL(1e-14, CMD_EPS));
        OGK_ASSERT_NEAR(cmd.u[1], -lv[1] / nlv, OGK_TEST_TOL(1e-14, CMD_EPS));
        OGK_ASSERT_NEAR(cmd.u[2], -lv[2] / nlv, OGK_TEST_TOL(1e-14, CMD_EPS));
        OGK_ASSERT_NEAR(cmd.t_s, (ogk_real_t)t, 0.0);
        assert_int_equal(cmd.law_flags, 0u);
        /* eq. (10) on the held state, away from the switches (where the sign is the integrator's) */
        OGK_ASSERT_STATUS(ogk_mpsp_state_at(&mpsp, t, x), OGK_OK);
        s = 1.0 - x[7] - (nlv * c.c_exhaust / x[6]);
        for (j = 0u; j < prop.n_switches; ++j) {
            near_switch = near_switch || (fabs(t - prop.t_switch[j]) < 1e-6);
        }
        if (!near_switch) {
            OGK_ASSERT_NEAR(cmd.throttle, (s < 0.0) ? 1.0 : 0.0, 0.0);
            assert_int_equal(cmd.flags, (s < 0.0) ? OGK_THRUST_FLAG_ENGINE_ON : 0u);
        }
        if (cmd.throttle > 0.0) {
            ++n_thrust;
        } else {
            ++n_coast;
        }
    }
    assert_true((n_thrust > 10u) && (n_coast > 10u)); /* both arcs sampled */
}

/* req: OGK-MPSP-010 */
static void test_mpsp_rejections(void **state)
{
    ogk_mpsp_config_t c;
    ogk_mpsp_prop_t prop;
    ogk_thrust_cmd_t cmd;
    ogk_mpsp_t *ctx = &mpsp;
    (void)state;
    OGK_ASSERT_STATUS(mpsp_fixture_config(&c, 20u, 30u), OGK_OK);
    OGK_ASSERT_STATUS(ogk_mpsp_init(ctx, &c), OGK_OK);
    OGK_ASSERT_STATUS(ogk_mpsp_propagate(ctx, w3, 0.0, x0_3d, 1.0, &prop), OGK_OK);
    OGK_ASSERT_STATUS(ogk_mpsp_thrust_cmd(ctx, 1.0, NULL), OGK_E_NULL);
    OGK_ASSERT_STATUS(ogk_mpsp_thrust_cmd(NULL, 1.0, &cmd), OGK_E_NULL);
    assert_int_equal(cmd.flags, OGK_THRUST_FLAG_SAFE);
    assert_int_equal((int)cmd.frame, (int)OGK_FRAME_INERTIAL);
    OGK_ASSERT_NEAR(cmd.u[0], 1.0, 0.0);
    OGK_ASSERT_NEAR(cmd.throttle, 0.0, 0.0);
    OGK_ASSERT_STATUS(ogk_mpsp_thrust_cmd(ctx, NAN, &cmd), OGK_E_NONFINITE);
    OGK_ASSERT_NEAR(cmd.t_s, 0.0, 0.0);
    OGK_ASSERT_STATUS(ogk_mpsp_thrust_cmd(ctx, c.tf + 0.1, &cmd), OGK_E_RANGE);
    assert_int_equal(cmd.flags, OGK_THRUST_FLAG_SAFE);
    OGK_ASSERT_STATUS(ogk_mpsp_thrust_cmd(ctx, c.t0 - 0.1, &cmd), OGK_E_RANGE);
    /* no direction: lambda_v = 0, or not finite (weights edited behind the context's back) */
    (void)memset(ctx->weights, 0, sizeof ctx->weights);
    OGK_ASSERT_STATUS(ogk_mpsp_thrust_cmd(ctx, 1.0, &cmd), OGK_E_SAFE_COMMAND);
    assert_int_equal(cmd.flags, OGK_THRUST_FLAG_SAFE);
    ctx->weights[0] = 1e308;
    ctx->weights[1] = 1e308;
    ctx->weights[3] = 1e308;
    OGK_ASSERT_STATUS(ogk_mpsp_thrust_cmd(ctx, 0.0, &cmd), OGK_E_SAFE_COMMAND);
    assert_int_equal(cmd.flags, OGK_THRUST_FLAG_SAFE);
    /* a failed propagation holds no trajectory */
    OGK_ASSERT_STATUS(ogk_mpsp_reset(ctx), OGK_OK);
    OGK_ASSERT_STATUS(ogk_mpsp_thrust_cmd(ctx, 1.0, &cmd), OGK_E_NOT_INIT);
    ctx->init_marker = 0u;
    OGK_ASSERT_STATUS(ogk_mpsp_thrust_cmd(ctx, 1.0, &cmd), OGK_E_NOT_INIT);
}

/* ------------------------------------------------------------------ BLT */

static void blt_direction(const ogk_real_t *seg, double tau, double *u)
{
    const double w[3] = {seg[0] + (seg[3] * tau), seg[1] + (seg[4] * tau), seg[2] + (seg[5] * tau)};
    const double n = sqrt((w[0] * w[0]) + (w[1] * w[1]) + (w[2] * w[2]));
    u[0] = w[0] / n;
    u[1] = w[1] / n;
    u[2] = w[2] / n;
}

/* req: OGK-BLT-008 */
static void test_blt_burn_coast_and_after(void **state)
{
    ogk_blt_config_t c;
    ogk_blt_transfer_t tr;
    ogk_blt_transfer_t sol;
    ogk_blt_report_t rep;
    ogk_thrust_cmd_t cmd;
    double u[3];
    uint32_t i;
    (void)state;
    blt_fx_bcb_config(&c, 0);
    blt_fx_bcb(&tr);
    blt_fx_make_target(&blt, &c, &tr);
    /* nothing held yet: the safe command */
    OGK_ASSERT_STATUS(ogk_blt_thrust_cmd(&blt, tr.t0, &cmd), OGK_E_SAFE_COMMAND);
    assert_int_equal((int)cmd.frame, (int)OGK_FRAME_SYNODIC);
    assert_int_equal(cmd.flags, OGK_THRUST_FLAG_SAFE);
    assert_int_equal(cmd.law_flags, OGK_BLT_FLAG_SAFE);
    OGK_ASSERT_NEAR(cmd.u[0], 1.0, 0.0);
    OGK_ASSERT_STATUS(ogk_blt_solve(&blt, &tr, &sol, &rep), OGK_OK);
    {
        const double t1 = sol.t0 + sol.seg[0][6];   /* end of the first burn */
        const double t2 = t1 + sol.seg[1][6];       /* end of the coast */
        const double t3 = t2 + sol.seg[2][6];       /* end of the transfer */
        for (i = 0u; i < 40u; ++i) {
            const double t = sol.t0 + ((t3 - sol.t0) * ((double)i + 0.5) / 40.0);
            OGK_ASSERT_STATUS(ogk_blt_thrust_cmd(&blt, t, &cmd), OGK_OK);
            assert_int_equal((int)cmd.frame, (int)OGK_FRAME_SYNODIC);
            assert_unit_and_angles(&cmd);
            OGK_ASSERT_NEAR(cmd.t_s, (ogk_real_t)t, 0.0);
            assert_int_equal(cmd.law_flags, 0u);
            if (t < t1) {
                blt_direction(sol.seg[0], t - sol.t0, u);
            } else if (t < t2) {
                blt_direction(sol.seg[2], 0.0, u); /* coast: the next burn's start */
            } else {
                blt_direction(sol.seg[2], t - t2, u);
            }
            OGK_ASSERT_NEAR(cmd.u[0], u[0], OGK_TEST_TOL(1e-15, CMD_EPS));
            OGK_ASSERT_NEAR(cmd.u[1], u[1], OGK_TEST_TOL(1e-15, CMD_EPS));
            OGK_ASSERT_NEAR(cmd.u[2], u[2], OGK_TEST_TOL(1e-15, CMD_EPS));
            if ((t < t1) || (t >= t2)) {
                OGK_ASSERT_NEAR(cmd.throttle, 1.0, 0.0);
                assert_int_equal(cmd.flags, OGK_THRUST_FLAG_ENGINE_ON);
            } else {
                OGK_ASSERT_NEAR(cmd.throttle, 0.0, 0.0);
                assert_int_equal(cmd.flags, 0u);
            }
        }
        /* after the end: engine off, no burn follows */
        OGK_ASSERT_STATUS(ogk_blt_thrust_cmd(&blt, t3 + 0.1, &cmd), OGK_OK);
        OGK_ASSERT_NEAR(cmd.throttle, 0.0, 0.0);
        OGK_ASSERT_NEAR(cmd.u[0], 1.0, 0.0);
        assert_int_equal(cmd.flags, 0u);
    }
    /* a coast followed by a coast (the configuration edited behind the context's back): no burn
     * follows, (1, 0, 0); then by a burn whose A is zero: (1, 0, 0) too */
    blt.cfg.segment_kind[2] = OGK_BLT_SEG_COAST;
    OGK_ASSERT_STATUS(ogk_blt_thrust_cmd(&blt, sol.t0 + sol.seg[0][6] + 0.01, &cmd), OGK_OK);
    OGK_ASSERT_NEAR(cmd.u[0], 1.0, 0.0);
    OGK_ASSERT_NEAR(cmd.throttle, 0.0, 0.0);
    blt.cfg.segment_kind[2] = OGK_BLT_SEG_BURN;
    blt.held.seg[2][0] = 0.0;
    blt.held.seg[2][1] = 0.0;
    blt.held.seg[2][2] = 0.0;
    OGK_ASSERT_STATUS(ogk_blt_thrust_cmd(&blt, sol.t0 + sol.seg[0][6] + 0.01, &cmd), OGK_OK);
    OGK_ASSERT_NEAR(cmd.u[0], 1.0, 0.0);
    OGK_ASSERT_NEAR(cmd.u[1], 0.0, 0.0);
    /* the rejections of ogk_blt_command, each with the safe command */
    OGK_ASSERT_STATUS(ogk_blt_thrust_cmd(&blt, sol.t0 - 0.1, &cmd), OGK_E_RANGE);
    assert_int_equal(cmd.flags, OGK_THRUST_FLAG_SAFE);
    OGK_ASSERT_STATUS(ogk_blt_thrust_cmd(&blt, NAN, &cmd), OGK_E_NONFINITE);
    OGK_ASSERT_NEAR(cmd.t_s, 0.0, 0.0);
    OGK_ASSERT_STATUS(ogk_blt_thrust_cmd(NULL, 1.0, &cmd), OGK_E_NULL);
    assert_int_equal(cmd.flags, OGK_THRUST_FLAG_SAFE);
    OGK_ASSERT_STATUS(ogk_blt_thrust_cmd(&blt, 1.0, NULL), OGK_E_NULL);
}

/* BLT's synodic command reaches CPD through the binary's angle (omega = 1: angle = theta0 + t). */
/* req: OGK-BLT-008 OGK-CPD-010 */
static void test_blt_synodic_to_cpd(void **state)
{
    ogk_blt_config_t c;
    ogk_blt_transfer_t tr;
    ogk_blt_transfer_t sol;
    ogk_blt_report_t rep;
    ogk_thrust_cmd_t syn;
    ogk_thrust_cmd_t inert;
    ogk_cpd_input_t in;
    ogk_nav_state_t nav;
    const double theta0 = 0.4;
    const double t = 0.5;
    double u[3];
    double ang;
    (void)state;
    blt_fx_moshup(&c);
    blt_fx_single_burn(&tr);
    blt_fx_make_target(&blt, &c, &tr);
    OGK_ASSERT_STATUS(ogk_blt_solve(&blt, &tr, &sol, &rep), OGK_OK);
    OGK_ASSERT_STATUS(ogk_blt_thrust_cmd(&blt, t, &syn), OGK_OK);
    blt_direction(sol.seg[0], t - sol.t0, u);
    OGK_ASSERT_NEAR(syn.u[0], u[0], OGK_TEST_TOL(1e-15, CMD_EPS));
    (void)memset(&nav, 0, sizeof nav);
    nav.xi_rad = 0.3;
    (void)memset(&in, 0, sizeof in);
    OGK_ASSERT_STATUS(ogk_cpd_input_from_thrust_cmd(&in, &syn, &nav), OGK_E_FRAME);
    ang = theta0 + t;
    OGK_ASSERT_STATUS(ogk_thrust_cmd_synodic_to_inertial(&syn, ang, &inert), OGK_OK);
    OGK_ASSERT_NEAR(inert.u[0], (cos(ang) * u[0]) - (sin(ang) * u[1]), OGK_TEST_TOL(1e-15, CMD_EPS));
    OGK_ASSERT_NEAR(inert.u[1], (sin(ang) * u[0]) + (cos(ang) * u[1]), OGK_TEST_TOL(1e-15, CMD_EPS));
    OGK_ASSERT_NEAR(inert.u[2], u[2], OGK_TEST_TOL(1e-15, CMD_EPS));
    OGK_ASSERT_STATUS(ogk_cpd_input_from_thrust_cmd(&in, &inert, &nav), OGK_OK);
    /* beta: the out-of-plane part is the synodic z, which is I3 = n at phi = 0 */
    OGK_ASSERT_NEAR(in.beta_c, asin(u[2]), OGK_TEST_TOL(1e-14, CMD_EPS));
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_nmpc_angle_from_the_vertical),
        cmocka_unit_test(test_nmpc_throttle_and_safe),
        cmocka_unit_test(test_nmpc_feeds_cpd),
        cmocka_unit_test(test_mpsp_primer_vector_and_bang_off_bang),
        cmocka_unit_test(test_mpsp_rejections),
        cmocka_unit_test(test_blt_burn_coast_and_after),
        cmocka_unit_test(test_blt_synodic_to_cpd),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
