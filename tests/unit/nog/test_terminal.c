/* test_terminal.c -- terminal steering along the velocity to be gained
 * (ogk/terminal.h): the direction against the unit vector of v_go, the
 * window, the latch, and the rejections.
 *
 * Both precisions (ogk_test.h). In float the velocities (about V_REF = 3.1e3
 * m/s) are known to an ulp of 2.4e-4 m/s, so the direction of v_go, a
 * difference of them, to about eps V_REF / |v_go|: 4 eps (1 + V_REF / |v_go|)
 * for a direction. The shaped plan's end conditions and its other figures
 * are measured (make unit-errors), tolerances ten times the worst. */
#include "ogk_test.h"

#include <string.h>

#include "endgame_fixture.h"
#include "ogk/terminal.h"


static ogk_nav_state_t nav_at(double t_s, double v_r, double dv_t, double v_n)
{
    ogk_nav_state_t nav;
    (void)memset(&nav, 0, sizeof nav);
    nav.t_s = t_s;
    nav.r_m = R_F + 120.0;
    nav.v_r_mps = v_r;
    nav.v_t_mps = sqrt(MU / R_F) + dv_t;
    nav.v_n_mps = v_n;
    return nav;
}

#define V_REF 3.1e3 /* [m/s] the orbital speed: float's resolution of the velocities */

/* The command's thrust direction (ogk/types.h) against v_go / |v_go|. */
static void assert_along(const ogk_thrust_cmd_t *cmd, double g_r, double g_t, double g_n)
{
    const double norm = sqrt((g_r * g_r) + (g_t * g_t) + (g_n * g_n));
    const double tol = OGK_TEST_TOL(1e-14, 4.0 * FLT_EPSILON * (1.0 + (V_REF / norm)));
    OGK_ASSERT_NEAR(cos(cmd->beta_rad) * sin(cmd->alpha_rad), g_r / norm, tol);
    OGK_ASSERT_NEAR(cos(cmd->beta_rad) * cos(cmd->alpha_rad), g_t / norm, tol);
    OGK_ASSERT_NEAR(sin(cmd->beta_rad), g_n / norm, tol);
    /* a complete r-t-n command (ogk/types.h): the same direction as u, full thrust with the engine on */
    assert_int_equal((int)cmd->frame, (int)OGK_FRAME_RTN);
    OGK_ASSERT_NEAR(cmd->u[0], g_r / norm, tol);
    OGK_ASSERT_NEAR(cmd->u[1], g_t / norm, tol);
    OGK_ASSERT_NEAR(cmd->u[2], g_n / norm, tol);
    OGK_ASSERT_NEAR(cmd->throttle, ((cmd->flags & OGK_THRUST_FLAG_ENGINE_ON) != 0u) ? 1.0 : 0.0, 0.0);
}

/* req: OGK-NOG-017 */
static void test_outside_window_passes_law_command(void **state)
{
    const ogk_terminal_config_t cfg = terminal_config();
    ogk_terminal_t ctx;
    const ogk_nav_state_t nav = nav_at(100.0, 3.0, -40.0, -4.0);
    const ogk_thrust_cmd_t law = law_command(100.0);
    ogk_thrust_cmd_t out;
    (void)state;
    OGK_ASSERT_STATUS(ogk_terminal_init(&ctx, &cfg), OGK_OK);
    OGK_ASSERT_STATUS(ogk_terminal_step(&ctx, &nav, 103.5, &law, &out), OGK_OK);
    assert_true(memcmp(&out, &law, sizeof out) == 0);
    assert_false(ctx.engaged);
}

/* req: OGK-NOG-017 */
static void test_window_steers_along_vgo_and_latches(void **state)
{
    const ogk_terminal_config_t cfg = terminal_config();
    ogk_terminal_t ctx;
    ogk_nav_state_t nav = nav_at(100.0, 3.0, -40.0, -4.0);
    ogk_thrust_cmd_t law = law_command(100.0);
    ogk_thrust_cmd_t out;
    (void)state;
    OGK_ASSERT_STATUS(ogk_terminal_init(&ctx, &cfg), OGK_OK);
    OGK_ASSERT_STATUS(ogk_terminal_step(&ctx, &nav, 102.9, &law, &out), OGK_OK);
    assert_along(&out, -3.0, 40.0, 4.0);
    assert_int_equal(out.law_flags, OGK_TERMINAL_FLAG_ENGAGED);
    assert_int_equal(out.flags, OGK_THRUST_FLAG_ENGINE_ON);
    OGK_ASSERT_NEAR(out.t_s, 100.0, 0.0);
    /* A later prediction far away does not hand the end back to the law. */
    nav = nav_at(100.02, 2.0, -39.0, -3.0);
    law = law_command(100.02);
    law.flags = 0u; /* engine off: passed through */
    OGK_ASSERT_STATUS(ogk_terminal_step(&ctx, &nav, 150.0, &law, &out), OGK_OK);
    assert_along(&out, -2.0, 39.0, 3.0);
    assert_int_equal(out.flags, 0u);
}

/* Thrust along v_go shrinks v_go along its own direction: with gravity left
 * out, the command does not turn at all while v_go is nulled. */
/* req: OGK-NOG-017 */
static void test_direction_constant_while_vgo_shrinks(void **state)
{
    const ogk_terminal_config_t cfg = terminal_config();
    ogk_terminal_t ctx;
    ogk_nav_state_t nav = nav_at(104.0, 5.0, -60.0, -3.0);
    ogk_thrust_cmd_t out;
    ogk_thrust_cmd_t first;
    int k;
    (void)state;
    (void)memset(&first, 0, sizeof first);
    OGK_ASSERT_STATUS(ogk_terminal_init(&ctx, &cfg), OGK_OK);
    for (k = 0; k < 150; ++k) {
        const ogk_thrust_cmd_t law = law_command(nav.t_s);
        const double a_dt = 17.7 * 0.02; /* thrust acceleration times the control period */
        OGK_ASSERT_STATUS(ogk_terminal_step(&ctx, &nav, 106.0, &law, &out), OGK_OK);
        if (k == 0) {
            first = out;
        }
        /* float: as |v_go| shrinks to 2 a dt (0.7 m/s), its direction is known to
         * 4 eps V_REF / |v_go| */
        OGK_ASSERT_NEAR(out.alpha_rad, first.alpha_rad, OGK_TEST_TOL(1e-12, 4.0 * FLT_EPSILON * V_REF / (2.0 * a_dt)));
        OGK_ASSERT_NEAR(out.beta_rad, first.beta_rad, OGK_TEST_TOL(1e-12, 4.0 * FLT_EPSILON * V_REF / (2.0 * a_dt)));
        nav.v_r_mps += a_dt * cos(out.beta_rad) * sin(out.alpha_rad);
        nav.v_t_mps += a_dt * cos(out.beta_rad) * cos(out.alpha_rad);
        nav.v_n_mps += a_dt * sin(out.beta_rad);
        nav.t_s += 0.02;
        if (fabs(nav.v_t_mps - sqrt(MU / R_F)) < (2.0 * a_dt)) {
            break;
        }
    }
    assert_true(k > 100); /* 60 m/s at 17.7 m/s^2: about 170 steps of 20 ms */
}

/* req: OGK-NOG-017 */
static void test_vgo_zero_holds_direction(void **state)
{
    const ogk_terminal_config_t cfg = terminal_config();
    ogk_terminal_t ctx;
    const ogk_nav_state_t nav = nav_at(105.0, 0.0, 0.0, 0.0);
    const ogk_thrust_cmd_t law = law_command(105.0);
    ogk_thrust_cmd_t out;
    (void)state;
    OGK_ASSERT_STATUS(ogk_terminal_init(&ctx, &cfg), OGK_OK);
    OGK_ASSERT_STATUS(ogk_terminal_step(&ctx, &nav, 105.5, &law, &out), OGK_OK);
    OGK_ASSERT_NEAR(out.alpha_rad, law.alpha_rad, 0.0); /* the law's direction at engagement */
    OGK_ASSERT_NEAR(out.beta_rad, law.beta_rad, 0.0);
}

/* req: OGK-NOG-017 */
static void test_rejections_change_nothing(void **state)
{
    const ogk_terminal_config_t cfg = terminal_config();
    ogk_terminal_t ctx;
    ogk_terminal_t before;
    ogk_nav_state_t nav = nav_at(100.0, 3.0, -40.0, -4.0);
    ogk_thrust_cmd_t law = law_command(100.0);
    ogk_thrust_cmd_t out;
    (void)state;
    OGK_ASSERT_STATUS(ogk_terminal_init(&ctx, &cfg), OGK_OK);
    /* Not engaged: the law's command, marked safe (phi is read by the shaped window: checked too). */
    nav.phi_rad = INFINITY;
    before = ctx;
    OGK_ASSERT_STATUS(ogk_terminal_step(&ctx, &nav, 100.5, &law, &out), OGK_E_NONFINITE);
    assert_true(memcmp(&ctx, &before, sizeof ctx) == 0);
    nav.phi_rad = 0.0;
    nav.v_n_mps = NAN;
    before = ctx;
    OGK_ASSERT_STATUS(ogk_terminal_step(&ctx, &nav, 100.5, &law, &out), OGK_E_NONFINITE);
    assert_true(memcmp(&ctx, &before, sizeof ctx) == 0);
    OGK_ASSERT_NEAR(out.alpha_rad, law.alpha_rad, 0.0);
    assert_int_equal(out.flags, OGK_THRUST_FLAG_ENGINE_ON | OGK_THRUST_FLAG_SAFE);
    /* Engaged: the last terminal command, marked safe. */
    nav = nav_at(100.0, 3.0, -40.0, -4.0);
    OGK_ASSERT_STATUS(ogk_terminal_step(&ctx, &nav, 102.0, &law, &out), OGK_OK);
    before = ctx;
    nav.r_m = -1.0;
    OGK_ASSERT_STATUS(ogk_terminal_step(&ctx, &nav, 102.0, &law, &out), OGK_E_RANGE);
    assert_true(memcmp(&ctx, &before, sizeof ctx) == 0);
    assert_along(&out, -3.0, 40.0, 4.0);
    assert_true((out.flags & OGK_THRUST_FLAG_SAFE) != 0u);
    nav = nav_at(100.0, 3.0, -40.0, -4.0);
    OGK_ASSERT_STATUS(ogk_terminal_step(&ctx, &nav, -5.0, &law, &out), OGK_E_RANGE);
    nav.v_t_mps = 2.0 * OGK_TERMINAL_V_MAX_MPS;
    OGK_ASSERT_STATUS(ogk_terminal_step(&ctx, &nav, 102.0, &law, &out), OGK_E_RANGE);
    /* A NaN law command with a bad state: the last terminal one. */
    law.alpha_rad = NAN;
    OGK_ASSERT_STATUS(ogk_terminal_step(&ctx, &nav, 102.0, &law, &out), OGK_E_NONFINITE);
    assert_along(&out, -3.0, 40.0, 4.0);
    assert_int_equal(out.law_flags, OGK_TERMINAL_FLAG_ENGAGED);
    assert_true(memcmp(&ctx, &before, sizeof ctx) == 0);
    /* Reset: the law flies again. */
    law = law_command(100.0);
    OGK_ASSERT_STATUS(ogk_terminal_reset(&ctx), OGK_OK);
    nav = nav_at(50.0, 3.0, -40.0, -4.0);
    OGK_ASSERT_STATUS(ogk_terminal_step(&ctx, &nav, 102.0, &law, &out), OGK_OK);
    assert_true(memcmp(&out, &law, sizeof out) == 0);
}

/* Shaped window, first step (no energy rate yet: the law's time to go): the
 * plan's acceleration, integrated here in closed form over its duration, must take
 * the velocity to 0 and the position to (1 - k) times the miss of a linear
 * decay, x + x' T / 2 (ogk/terminal.h), on both axes, for k = 1 and k = 0.4. */
/* req: OGK-NOG-017 */
static void test_shaped_plan_meets_its_end_conditions(void **state)
{
    static const double gains[2] = {1.0, 0.4};
    size_t g;
    (void)state;
    for (g = 0u; g < 2u; ++g) {
        ogk_terminal_config_t cfg = terminal_config();
        ogk_terminal_t ctx;
        ogk_nav_state_t nav = nav_at(100.0, 12.0, -45.0, -3.0);
        const ogk_thrust_cmd_t law = law_command(100.0);
        ogk_thrust_cmd_t out;
        const double k = gains[g];
        const double t_go = 2.5;
        double dr;
        double z;
        double z_dot;
        double g_r;
        double g_n;
        double T;
        double v_end;
        double x_end;
        cfg.shape_gain = k;
        cfg.shape_gain_normal = 1.4 * k - 0.4; /* 1.0 and 0.16: the axes have their own gains */
        cfg.shape_hold_s = 0.5;
        nav.phi_rad = 2.0e-7;
        OGK_ASSERT_STATUS(ogk_terminal_init(&ctx, &cfg), OGK_OK);
        OGK_ASSERT_STATUS(ogk_terminal_step(&ctx, &nav, 100.0 + t_go, &law, &out), OGK_OK);
        assert_false(ctx.plan.in_hold);
        T = ctx.plan.duration_s;
        OGK_ASSERT_NEAR(T, t_go, 0.0);
        dr = nav.r_m - R_F;
        g_r = (((nav.v_t_mps * nav.v_t_mps) + (nav.v_n_mps * nav.v_n_mps)) / nav.r_m) - (MU / (nav.r_m * nav.r_m));
        v_end = nav.v_r_mps + ((ctx.plan.accel_r0_mps2 + g_r) * T) + (0.5 * ctx.plan.accel_r1_mps3 * T * T);
        x_end = dr + (nav.v_r_mps * T) + (0.5 * (ctx.plan.accel_r0_mps2 + g_r) * T * T) +
                ((ctx.plan.accel_r1_mps3 * T * T * T) / 6.0);
        /* float: measured worst 4.4e-5 on M4F and host */
        OGK_ASSERT_NEAR(v_end, 0.0, OGK_TEST_TOL(1e-12, 5e-4));
        /* float: measured worst 4.4e-5 on M4F and host */
        OGK_ASSERT_NEAR(x_end, (1.0 - k) * (dr + (0.5 * nav.v_r_mps * T)), OGK_TEST_TOL(1e-9, 5e-4));
        z = nav.r_m * sin(nav.phi_rad);
        z_dot = (nav.v_r_mps * sin(nav.phi_rad)) + (nav.v_n_mps * cos(nav.phi_rad));
        g_n = -(MU * z) / (nav.r_m * nav.r_m * nav.r_m);
        v_end = z_dot + ((ctx.plan.accel_n0_mps2 + g_n) * T) + (0.5 * ctx.plan.accel_n1_mps3 * T * T);
        x_end = z + (z_dot * T) + (0.5 * (ctx.plan.accel_n0_mps2 + g_n) * T * T) +
                ((ctx.plan.accel_n1_mps3 * T * T * T) / 6.0);
        /* float: measured worst 4.7e-7 on M4F and host */
        OGK_ASSERT_NEAR(v_end, 0.0, OGK_TEST_TOL(1e-12, 5e-6));
        /* float: measured worst 2.6e-7 on M4F and host */
        OGK_ASSERT_NEAR(x_end, (1.0 - cfg.shape_gain_normal) * (z + (0.5 * z_dot * T)), OGK_TEST_TOL(1e-9, 5e-6));
        /* the tangential component nulls the along-track speed error over T */
        /* float: measured worst 5.4e-5 on M4F and host */
        OGK_ASSERT_NEAR(ctx.plan.accel_t_mps2, (sqrt(MU / R_F) - nav.v_t_mps) / T, OGK_TEST_TOL(1e-12, 1e-3));
        /* the command is the plan's direction at its start */
        /* float: an angle from the plan's own components, 4 eps */
        OGK_ASSERT_NEAR(out.alpha_rad, atan2(ctx.plan.accel_r0_mps2, ctx.plan.accel_t_mps2),
                        OGK_TEST_TOL(1e-15, 4.0 * FLT_EPSILON));
        assert_int_equal(out.law_flags, OGK_TERMINAL_FLAG_ENGAGED);
        /* with a lead, its direction that much later (the same plan: same state, same T) */
        cfg.shape_lead_s = 0.4;
        OGK_ASSERT_STATUS(ogk_terminal_init(&ctx, &cfg), OGK_OK);
        OGK_ASSERT_STATUS(ogk_terminal_step(&ctx, &nav, 100.0 + t_go, &law, &out), OGK_OK);
        {
            const double a_r = ctx.plan.accel_r0_mps2 + (0.4 * ctx.plan.accel_r1_mps3);
            const double a_n = ctx.plan.accel_n0_mps2 + (0.4 * ctx.plan.accel_n1_mps3);
            const double a_t = ctx.plan.accel_t_mps2;
            /* float: angles from the plan's own components, 4 eps */
            OGK_ASSERT_NEAR(out.alpha_rad, atan2(a_r, a_t), OGK_TEST_TOL(1e-15, 4.0 * FLT_EPSILON));
            OGK_ASSERT_NEAR(out.beta_rad, atan2(a_n, hypot(a_r, a_t)), OGK_TEST_TOL(1e-15, 4.0 * FLT_EPSILON));
        }
        /* a lead beyond the plan's end: its end */
        cfg.shape_lead_s = 10.0;
        OGK_ASSERT_STATUS(ogk_terminal_init(&ctx, &cfg), OGK_OK);
        OGK_ASSERT_STATUS(ogk_terminal_step(&ctx, &nav, 100.0 + t_go, &law, &out), OGK_OK);
        OGK_ASSERT_NEAR(out.alpha_rad,
                        atan2(ctx.plan.accel_r0_mps2 + (t_go * ctx.plan.accel_r1_mps3), ctx.plan.accel_t_mps2),
                        OGK_TEST_TOL(1e-15, 4.0 * FLT_EPSILON));
    }
}

/* Inertial two-body propagation (RK4 at the 20 ms control period) of a
 * vehicle thrusting at a constant acceleration along the terminal command,
 * from 3 s before the circular target's energy is reached, cut at that
 * energy: with shaping (k = 1, hold 0.5 s) the radius and the plane-normal
 * position miss are a small fraction of pure v_go's, with the velocity still
 * nulled. The reference is the test's own propagation, not the kernel's plan. */
typedef struct {
    double pos[3];
    double vel[3];
} state6_t;

static void to_nav(const state6_t *s, double t_s, ogk_nav_state_t *nav, double e_r[3], double e_t[3],
                   double e_n[3])
{
    const double r = sqrt((s->pos[0] * s->pos[0]) + (s->pos[1] * s->pos[1]) + (s->pos[2] * s->pos[2]));
    const double xi = atan2(s->pos[1], s->pos[0]);
    const double phi = asin(s->pos[2] / r);
    size_t i;
    e_r[0] = cos(phi) * cos(xi);
    e_r[1] = cos(phi) * sin(xi);
    e_r[2] = sin(phi);
    e_t[0] = -sin(xi);
    e_t[1] = cos(xi);
    e_t[2] = 0.0;
    e_n[0] = -sin(phi) * cos(xi);
    e_n[1] = -sin(phi) * sin(xi);
    e_n[2] = cos(phi);
    (void)memset(nav, 0, sizeof *nav);
    nav->t_s = t_s;
    nav->r_m = r;
    nav->xi_rad = xi;
    nav->phi_rad = phi;
    for (i = 0u; i < 3u; ++i) {
        nav->v_r_mps += s->vel[i] * e_r[i];
        nav->v_t_mps += s->vel[i] * e_t[i];
        nav->v_n_mps += s->vel[i] * e_n[i];
    }
}

static void deriv(const state6_t *s, const double thrust[3], state6_t *d)
{
    const double r = sqrt((s->pos[0] * s->pos[0]) + (s->pos[1] * s->pos[1]) + (s->pos[2] * s->pos[2]));
    size_t i;
    for (i = 0u; i < 3u; ++i) {
        d->pos[i] = s->vel[i];
        d->vel[i] = (-(MU * s->pos[i]) / (r * r * r)) + thrust[i];
    }
}

static void axpy(const state6_t *s, double h, const state6_t *d, state6_t *out)
{
    size_t i;
    for (i = 0u; i < 3u; ++i) {
        out->pos[i] = s->pos[i] + (h * d->pos[i]);
        out->vel[i] = s->vel[i] + (h * d->vel[i]);
    }
}

/* Flies the end of the burn; returns the final nav state (r-t-n). */
static ogk_nav_state_t fly_end(double shape_gain)
{
    ogk_terminal_config_t cfg = terminal_config();
    ogk_terminal_t ctx;
    const double accel = 17.7;
    const double h = 0.02;
    const double energy_f = -MU / (2.0 * R_F);
    state6_t s;
    ogk_nav_state_t nav;
    double t = 100.0;
    int k;
    cfg.shape_gain = shape_gain;
    cfg.shape_gain_normal = shape_gain;
    cfg.shape_hold_s = 0.5;
    (void)ogk_terminal_init(&ctx, &cfg);
    /* at xi = 0: r 40 m low and climbing 14 m/s, 6 m below the plane, 3 m/s towards it, 50 m/s slow */
    s.pos[0] = R_F - 40.0;
    s.pos[1] = 0.0;
    s.pos[2] = -6.0;
    s.vel[0] = 14.0;
    s.vel[1] = sqrt(MU / R_F) - 50.0;
    s.vel[2] = 3.0;
    for (k = 0; k < 400; ++k) {
        double e_r[3], e_t[3], e_n[3], thrust[3];
        const ogk_thrust_cmd_t law = law_command(t);
        ogk_thrust_cmd_t out;
        state6_t k1, k2, k3, k4, tmp;
        size_t i;
        to_nav(&s, t, &nav, e_r, e_t, e_n);
        if ((0.5 * ((nav.v_r_mps * nav.v_r_mps) + (nav.v_t_mps * nav.v_t_mps) + (nav.v_n_mps * nav.v_n_mps))) -
                (MU / nav.r_m) >=
            energy_f) {
            break;
        }
        OGK_ASSERT_STATUS(ogk_terminal_step(&ctx, &nav, 102.8, &law, &out), OGK_OK);
        for (i = 0u; i < 3u; ++i) {
            thrust[i] = accel * ((cos(out.beta_rad) * sin(out.alpha_rad) * e_r[i]) +
                                 (cos(out.beta_rad) * cos(out.alpha_rad) * e_t[i]) + (sin(out.beta_rad) * e_n[i]));
        }
        deriv(&s, thrust, &k1);
        axpy(&s, 0.5 * h, &k1, &tmp);
        deriv(&tmp, thrust, &k2);
        axpy(&s, 0.5 * h, &k2, &tmp);
        deriv(&tmp, thrust, &k3);
        axpy(&s, h, &k3, &tmp);
        deriv(&tmp, thrust, &k4);
        for (i = 0u; i < 3u; ++i) {
            s.pos[i] += (h / 6.0) * (k1.pos[i] + (2.0 * k2.pos[i]) + (2.0 * k3.pos[i]) + k4.pos[i]);
            s.vel[i] += (h / 6.0) * (k1.vel[i] + (2.0 * k2.vel[i]) + (2.0 * k3.vel[i]) + k4.vel[i]);
        }
        t += h;
    }
    assert_true((k > 100) && (k < 400)); /* about 2.8 s of thrust */
    assert_true(ctx.plan.in_hold == (shape_gain > 0.0)); /* v_go steering after the hold */
    return nav;
}

/* req: OGK-NOG-017 */
static void test_shaped_window_steers_out_the_position_miss(void **state)
{
    const ogk_nav_state_t pure = fly_end(0.0);
    const ogk_nav_state_t shaped = fly_end(1.0);
    const double dr_pure = pure.r_m - R_F;
    const double dr_shaped = shaped.r_m - R_F;
    const double z_pure = pure.r_m * sin(pure.phi_rad);
    const double z_shaped = shaped.r_m * sin(shaped.phi_rad);
    (void)state;
    assert_true(fabs(dr_pure) > 10.0);       /* -40 + 14 x 2.8 / 2 m, about -20 m */
    assert_true(fabs(z_pure) > 1.5);         /* -6 + 3 x 2.8 / 2 m, about -2 m */
    assert_true(fabs(dr_shaped) < 0.05 * fabs(dr_pure));
    assert_true(fabs(z_shaped) < 0.05 * fabs(z_pure));
    assert_true(fabs(shaped.v_r_mps) < 0.5); /* one control period of thrust: 0.35 m/s */
    assert_true(fabs(shaped.v_n_mps) < 0.5);
}

/* The shaped window's fallbacks: the law's time to go while the energy is not
 * rising (or on a repeated time tag), and v_go steering when the plan
 * overflows (a radius near 0, inside the envelope). */
/* req: OGK-NOG-017 */
static void test_shaped_fallbacks(void **state)
{
    ogk_terminal_config_t cfg = terminal_config();
    ogk_terminal_t ctx;
    ogk_nav_state_t nav = nav_at(100.0, 12.0, -45.0, -3.0);
    const ogk_thrust_cmd_t law = law_command(100.0);
    ogk_thrust_cmd_t out;
    (void)state;
    cfg.shape_gain = 1.0;
    cfg.shape_gain_normal = 1.0;
    cfg.shape_hold_s = 0.5;
    OGK_ASSERT_STATUS(ogk_terminal_init(&ctx, &cfg), OGK_OK);
    OGK_ASSERT_STATUS(ogk_terminal_step(&ctx, &nav, 102.5, &law, &out), OGK_OK);
    OGK_ASSERT_NEAR(ctx.plan.duration_s, 102.5 - 100.0, 0.0);
    /* the same time tag again, 1 m/s faster: no rate (not an infinite one), the law's time to go */
    nav.v_t_mps += 1.0;
    OGK_ASSERT_STATUS(ogk_terminal_step(&ctx, &nav, 102.4, &law, &out), OGK_OK);
    /* float: 102.4 as a float (half an ulp, 3.8e-6 s; 1 eps of it written) */
    OGK_ASSERT_NEAR(ctx.plan.duration_s, 102.4 - 100.0, OGK_TEST_TOL(0.0, FLT_EPSILON * 102.4));
    assert_false(ctx.plan.in_hold);
    nav.v_t_mps -= 1.0;
    /* 20 ms later, slower: the energy falls, the law's time to go */
    nav.t_s += 0.02;
    nav.v_t_mps -= 1.0;
    OGK_ASSERT_STATUS(ogk_terminal_step(&ctx, &nav, 102.5, &law, &out), OGK_OK);
    OGK_ASSERT_NEAR(ctx.plan.duration_s, 102.5 - nav.t_s, 1e-12);
    /* 20 ms later, faster by 0.35 m/s: the time to the energy cut-off, (E_f - E) / (dE/dt) */
    {
        const double e0 = (0.5 * ((nav.v_r_mps * nav.v_r_mps) + (nav.v_t_mps * nav.v_t_mps) +
                                  (nav.v_n_mps * nav.v_n_mps))) - (MU / nav.r_m);
        double e1;
        nav.t_s += 0.02;
        nav.v_t_mps += 0.35;
        e1 = (0.5 * ((nav.v_r_mps * nav.v_r_mps) + (nav.v_t_mps * nav.v_t_mps) + (nav.v_n_mps * nav.v_n_mps))) -
             (MU / nav.r_m);
        OGK_ASSERT_STATUS(ogk_terminal_step(&ctx, &nav, 102.5, &law, &out), OGK_OK);
        /* float: measured worst 4.4e-4 on M4F and host */
        OGK_ASSERT_NEAR(ctx.plan.duration_s, ((-MU / (2.0 * R_F)) - e1) / ((e1 - e0) / 0.02), OGK_TEST_TOL(1e-6, 5e-3));
        assert_true(ctx.plan.duration_s > 2.0); /* 45 m/s at 17.5 m/s^2 */
    }
    /* a radius whose energy overflows (-inf): no energy is kept, so the next step has no rate and
     * plans on the law's time to go (an infinite rate would give T = 0, the hold). Float: 1e-30 m
     * (mu / r = 4e44, beyond FLT_MAX) */
    OGK_ASSERT_STATUS(ogk_terminal_reset(&ctx), OGK_OK);
    nav = nav_at(100.0, 12.0, -45.0, -3.0);
    nav.r_m = OGK_TEST_PICK(1.0e-310, 1.0e-30);
    OGK_ASSERT_STATUS(ogk_terminal_step(&ctx, &nav, 102.5, &law, &out), OGK_OK);
    assert_false(ctx.has_last);
    nav = nav_at(100.02, 12.0, -45.0, -3.0);
    OGK_ASSERT_STATUS(ogk_terminal_step(&ctx, &nav, 102.5, &law, &out), OGK_OK);
    assert_false(ctx.plan.in_hold);
    OGK_ASSERT_NEAR(ctx.plan.duration_s, 102.5 - 100.02, OGK_TEST_TOL(0.0, FLT_EPSILON * 100.02)); /* float: 100.02 rounded */
    /* a radius of 1e-200 m: mu / r^2 overflows, no plan, v_go steering (float: 1e-13 m, mu / r =
     * 4e27 finite, mu / r^2 = 4e40 not) */
    OGK_ASSERT_STATUS(ogk_terminal_reset(&ctx), OGK_OK);
    nav = nav_at(100.0, 12.0, -45.0, -3.0);
    nav.r_m = OGK_TEST_PICK(1.0e-200, 1.0e-13);
    OGK_ASSERT_STATUS(ogk_terminal_step(&ctx, &nav, 102.5, &law, &out), OGK_OK);
    assert_along(&out, -12.0, 45.0, 3.0);
    assert_false(ctx.plan.in_hold);
}

/* The angle between the shaped plan's thrust direction at time t of the plan
 * and its direction with no position part (k = 0: the velocity-nulling plan,
 * -x'/T - g_r, (v_c - v_t)/T, -z'/T - g_n), both rebuilt here from the plan's
 * coefficients and the state. */
static double plan_tilt(const ogk_terminal_t *ctx, const ogk_nav_state_t *nav, double t)
{
    const double T = ctx->plan.duration_s;
    const double g_r = (((nav->v_t_mps * nav->v_t_mps) + (nav->v_n_mps * nav->v_n_mps)) / nav->r_m) -
                       (MU / (nav->r_m * nav->r_m));
    const double z = nav->r_m * sin(nav->phi_rad);
    const double z_dot = (nav->v_r_mps * sin(nav->phi_rad)) + (nav->v_n_mps * cos(nav->phi_rad));
    const double g_n = -(MU * z) / (nav->r_m * nav->r_m * nav->r_m);
    const double p[3] = {ctx->plan.accel_r0_mps2 + (ctx->plan.accel_r1_mps3 * t), ctx->plan.accel_t_mps2,
                         ctx->plan.accel_n0_mps2 + (ctx->plan.accel_n1_mps3 * t)};
    const double v[3] = {(-nav->v_r_mps / T) - g_r, (sqrt(MU / R_F) - nav->v_t_mps) / T, (-z_dot / T) - g_n};
    const double cross[3] = {(p[1] * v[2]) - (p[2] * v[1]), (p[2] * v[0]) - (p[0] * v[2]),
                             (p[0] * v[1]) - (p[1] * v[0])};
    const double dot = (p[0] * v[0]) + (p[1] * v[1]) + (p[2] * v[2]);
    return atan2(sqrt((cross[0] * cross[0]) + (cross[1] * cross[1]) + (cross[2] * cross[2])), dot);
}

/* Turn limit (terminal.h): the bound is the angle a vehicle turning at an
 * angular acceleration a leaves and regains from rest within the shaped part
 * S = window - hold of the window, here integrated step by step (bang-bang,
 * S / 4 accelerating, S / 4 braking, then back); a plan whose tilt from the
 * velocity-nulling direction would exceed it is scaled down to it, at its
 * start and at its end, and the same state with no limit tilts further; a
 * plan inside the bound is the unlimited one to the bit. */
/* req: OGK-NOG-021 */
static void test_turn_limit_bounds_the_plans_tilt(void **state)
{
    ogk_terminal_config_t cfg = terminal_config();
    ogk_terminal_t ctx;
    ogk_terminal_t free_ctx;
    ogk_nav_state_t nav = nav_at(100.0, 30.0, -45.0, 0.0);
    const ogk_thrust_cmd_t law = law_command(100.0);
    ogk_thrust_cmd_t out;
    ogk_thrust_cmd_t free_out;
    const double a = 0.2;       /* [rad/s^2] the short-burn corner's vehicle at the end of its burn */
    const double t_go = 2.5;
    double angle = 0.0;
    double rate = 0.0;
    int k;
    (void)state;
    cfg.shape_gain = 1.0;
    cfg.shape_gain_normal = 1.0;
    cfg.shape_hold_s = 1.0;
    cfg.window_s = 3.0;
    cfg.turn_accel_rad_s2 = a;
    OGK_ASSERT_STATUS(ogk_terminal_init(&ctx, &cfg), OGK_OK);
    assert_true(ctx.tilt_limited);
    OGK_ASSERT_NEAR(ctx.plan.gain_scale, 1.0, 0.0); /* no plan yet: unscaled */
    /* rest to rest in S / 2 = 1 s: 0.5 s accelerating at a, 0.5 s braking, 1e-5 s steps */
    for (k = 0; k < 100000; ++k) {
        const double acc = (k < 50000) ? a : -a;
        angle += (rate * 1.0e-5) + (0.5 * acc * 1.0e-10);
        rate += acc * 1.0e-5;
    }
    OGK_ASSERT_NEAR(rate, 0.0, 1e-12);
    /* float: measured worst relative 1.5e-8 on M4F and host */
    OGK_ASSERT_REL(ctx.shape_tilt_max_rad, angle, OGK_TEST_TOL(1e-9, 2e-7), 0.0);
    /* float: measured worst relative 5.4e-10 on M4F and host */
    OGK_ASSERT_REL(tan(ctx.shape_tilt_max_rad), ctx.shape_tilt_max_tan, OGK_TEST_TOL(1e-15, 1e-8), 0.0);
    /* a 400 m radius miss rising at 30 m/s with 2.5 s to go: far beyond the bound */
    nav.r_m = R_F + 400.0;
    OGK_ASSERT_STATUS(ogk_terminal_step(&ctx, &nav, 100.0 + t_go, &law, &out), OGK_OK);
    assert_false(ctx.plan.in_hold);
    assert_true(ctx.plan.gain_scale > 0.0);
    assert_true(ctx.plan.gain_scale < 0.1);
    assert_true(plan_tilt(&ctx, &nav, 0.0) <= ctx.shape_tilt_max_rad * (1.0 + 1e-9));
    assert_true(plan_tilt(&ctx, &nav, t_go) <= ctx.shape_tilt_max_rad * (1.0 + 1e-9));
    assert_true(plan_tilt(&ctx, &nav, 0.0) > 0.5 * ctx.shape_tilt_max_rad); /* scaled to it, not to 0 */
    /* the plan still nulls the radial velocity at its end (a plan with a smaller gain) */
    {
        const double g_r = (((nav.v_t_mps * nav.v_t_mps) + (nav.v_n_mps * nav.v_n_mps)) / nav.r_m) -
                           (MU / (nav.r_m * nav.r_m));
        /* float: measured worst 1.7e-6 on M4F and host */
        OGK_ASSERT_NEAR(nav.v_r_mps + ((ctx.plan.accel_r0_mps2 + g_r) * t_go) +
                            (0.5 * ctx.plan.accel_r1_mps3 * t_go * t_go),
                        0.0, OGK_TEST_TOL(1e-12, 2e-5));
    }
    /* a plane-normal miss alone (420 m out of plane, closing at 20 m/s): bounded the same way, the
     * normal gain scaled; the radial plan is then the velocity-nulling one */
    {
        ogk_nav_state_t plane = nav_at(100.0, 0.0, -45.0, 20.0);
        plane.r_m = R_F;
        plane.phi_rad = 1.0e-5;
        OGK_ASSERT_STATUS(ogk_terminal_init(&free_ctx, &cfg), OGK_OK);
        OGK_ASSERT_STATUS(ogk_terminal_step(&free_ctx, &plane, 100.0 + t_go, &law, &free_out), OGK_OK);
        assert_true(free_ctx.plan.gain_scale < 0.2);
        assert_true(plan_tilt(&free_ctx, &plane, 0.0) <= free_ctx.shape_tilt_max_rad * (1.0 + 1e-9));
        assert_true(plan_tilt(&free_ctx, &plane, t_go) <= free_ctx.shape_tilt_max_rad * (1.0 + 1e-9));
        assert_true(plan_tilt(&free_ctx, &plane, 0.0) > 0.5 * free_ctx.shape_tilt_max_rad);
        /* the scaled position part is exactly the allowed one: s k |3 z' + 6 z / T| = tan(bound) |v_go| */
        {
            const double z = plane.r_m * sin(plane.phi_rad);
            const double z_dot = plane.v_n_mps * cos(plane.phi_rad);
            const double vgo = sqrt((45.0 * 45.0) + (20.0 * 20.0));
            /* float: |v_go| known to 4 eps V_REF / |v_go| relative */
            OGK_ASSERT_REL(free_ctx.plan.gain_scale * fabs((3.0 * z_dot) + ((6.0 * z) / t_go)),
                           tan(free_ctx.shape_tilt_max_rad) * vgo, OGK_TEST_TOL(1e-12, 4.0 * FLT_EPSILON * V_REF / vgo),
                           0.0);
        }
    }
    /* no limit: the same state tilts the plan further */
    cfg.turn_accel_rad_s2 = 0.0;
    OGK_ASSERT_STATUS(ogk_terminal_init(&free_ctx, &cfg), OGK_OK);
    assert_false(free_ctx.tilt_limited);
    OGK_ASSERT_STATUS(ogk_terminal_step(&free_ctx, &nav, 100.0 + t_go, &law, &free_out), OGK_OK);
    OGK_ASSERT_NEAR(free_ctx.plan.gain_scale, 1.0, 0.0);
    assert_true(plan_tilt(&free_ctx, &nav, 0.0) > 5.0 * ctx.shape_tilt_max_rad);
    assert_true(fabs(free_out.alpha_rad - out.alpha_rad) > 0.1);
    /* a 0.3 m miss at 0.02 m/s (tilt 0.017 rad): inside the bound, the unlimited plan to the bit */
    cfg.turn_accel_rad_s2 = a;
    OGK_ASSERT_STATUS(ogk_terminal_init(&ctx, &cfg), OGK_OK);
    nav = nav_at(100.0, 0.02, -45.0, 0.0);
    nav.r_m = R_F + 0.3;
    OGK_ASSERT_STATUS(ogk_terminal_step(&ctx, &nav, 100.0 + t_go, &law, &out), OGK_OK);
    OGK_ASSERT_NEAR(ctx.plan.gain_scale, 1.0, 0.0);
    OGK_ASSERT_STATUS(ogk_terminal_init(&free_ctx, &cfg), OGK_OK);
    free_ctx.tilt_limited = false;
    OGK_ASSERT_STATUS(ogk_terminal_step(&free_ctx, &nav, 100.0 + t_go, &law, &free_out), OGK_OK);
    assert_true(memcmp(&out, &free_out, sizeof out) == 0);
}

/* The turn limit binds only with shaping, a > 0 and a bound below
 * OGK_TERMINAL_TILT_MAX_RAD; a vehicle that barely turns (a = 1e-9 rad/s^2)
 * flies the velocity-nulling plan, its position part scaled to ~0. */
/* req: OGK-NOG-021 */
static void test_turn_limit_binds_only_when_it_can(void **state)
{
    ogk_terminal_config_t cfg = terminal_config();
    ogk_terminal_t ctx;
    ogk_nav_state_t nav = nav_at(100.0, 30.0, -45.0, -3.0);
    const ogk_thrust_cmd_t law = law_command(100.0);
    ogk_thrust_cmd_t out;
    (void)state;
    cfg.turn_accel_rad_s2 = 0.2;              /* not shaped: v_go steering, no limit */
    OGK_ASSERT_STATUS(ogk_terminal_init(&ctx, &cfg), OGK_OK);
    assert_false(ctx.tilt_limited);
    OGK_ASSERT_NEAR(ctx.shape_tilt_max_rad, OGK_TERMINAL_TILT_MAX_RAD, 0.0);
    cfg.shape_gain = 1.0;
    cfg.shape_hold_s = 1.0;
    cfg.turn_accel_rad_s2 = OGK_TERMINAL_TURN_ACCEL_MAX_RAD_S2; /* a S^2 / 16 far above TILT_MAX */
    OGK_ASSERT_STATUS(ogk_terminal_init(&ctx, &cfg), OGK_OK);
    assert_false(ctx.tilt_limited);
    cfg.window_s = 3.0; /* S = 2 s: a = 16 TILT_MAX / S^2 = 6 puts the bound at TILT_MAX, exactly */
    cfg.turn_accel_rad_s2 = 16.0 * OGK_TERMINAL_TILT_MAX_RAD / 4.0;
    OGK_ASSERT_STATUS(ogk_terminal_init(&ctx, &cfg), OGK_OK);
    assert_false(ctx.tilt_limited);
    cfg.turn_accel_rad_s2 = OGK_TEST_NEXTAFTER(16.0 * OGK_TERMINAL_TILT_MAX_RAD / 4.0, 0.0);
    OGK_ASSERT_STATUS(ogk_terminal_init(&ctx, &cfg), OGK_OK);
    assert_true(ctx.tilt_limited);
    cfg.window_s = 3.0;
    cfg.turn_accel_rad_s2 = 1.0e-9;
    cfg.shape_gain_normal = 1.0;
    OGK_ASSERT_STATUS(ogk_terminal_init(&ctx, &cfg), OGK_OK);
    nav.r_m = R_F + 400.0;
    nav.phi_rad = 1.0e-6;
    OGK_ASSERT_STATUS(ogk_terminal_step(&ctx, &nav, 102.5, &law, &out), OGK_OK);
    assert_true(ctx.plan.gain_scale < 1.0e-6);
    /* the velocity-nulling plan: thrust along (v_go - g T) / T, v_go's in-plane angle but for
     * g_r T = -0.016 m/s (2.5e-4 rad) */
    assert_true(fabs(out.alpha_rad - atan2(-30.0, 45.0)) < 1.0e-3);
    /* no velocity to be gained with a position miss: scale 0, the k = 0 plan */
    nav = nav_at(100.0, 0.0, 0.0, 0.0);
    nav.r_m = R_F + 400.0;
    OGK_ASSERT_STATUS(ogk_terminal_init(&ctx, &cfg), OGK_OK);
    OGK_ASSERT_STATUS(ogk_terminal_step(&ctx, &nav, 102.5, &law, &out), OGK_OK);
    /* float: v_go is then the rounding residual of the orbital speed (an ulp), not 0:
     * measured worst 6.4e-17 on M4F and host */
    OGK_ASSERT_NEAR(ctx.plan.gain_scale, 0.0, OGK_TEST_TOL(0.0, 1e-15));
}

/* req: OGK-NOG-017 */
static void test_contract(void **state)
{
    ogk_terminal_config_t cfg = terminal_config();
    ogk_terminal_t ctx;
    const ogk_nav_state_t nav = nav_at(100.0, 0.0, -1.0, 0.0);
    const ogk_thrust_cmd_t law = law_command(100.0);
    ogk_thrust_cmd_t out;
    (void)state;
    (void)memset(&ctx, 0, sizeof ctx);
    OGK_ASSERT_STATUS(ogk_terminal_config_default(NULL), OGK_E_NULL);
    OGK_ASSERT_STATUS(ogk_terminal_init(NULL, &cfg), OGK_E_NULL);
    OGK_ASSERT_STATUS(ogk_terminal_init(&ctx, NULL), OGK_E_NULL);
    OGK_ASSERT_STATUS(ogk_terminal_reset(NULL), OGK_E_NULL);
    OGK_ASSERT_STATUS(ogk_terminal_reset(&ctx), OGK_E_NOT_INIT);
    OGK_ASSERT_STATUS(ogk_terminal_step(&ctx, &nav, 101.0, &law, &out), OGK_E_NOT_INIT);
    OGK_ASSERT_STATUS(ogk_terminal_step(NULL, &nav, 101.0, &law, &out), OGK_E_NULL);
    OGK_ASSERT_STATUS(ogk_terminal_step(&ctx, NULL, 101.0, &law, &out), OGK_E_NULL);
    OGK_ASSERT_STATUS(ogk_terminal_step(&ctx, &nav, 101.0, NULL, &out), OGK_E_NULL);
    OGK_ASSERT_STATUS(ogk_terminal_step(&ctx, &nav, 101.0, &law, NULL), OGK_E_NULL);
    cfg.mu_m3_s2 = -1.0;
    OGK_ASSERT_STATUS(ogk_terminal_init(&ctx, &cfg), OGK_E_CONFIG);
    cfg = terminal_config();
    cfg.target_radius_m = 0.0;
    OGK_ASSERT_STATUS(ogk_terminal_init(&ctx, &cfg), OGK_E_CONFIG);
    cfg = terminal_config();
    cfg.window_s = NAN;
    OGK_ASSERT_STATUS(ogk_terminal_init(&ctx, &cfg), OGK_E_CONFIG);
    cfg = terminal_config();
    cfg.mu_m3_s2 = OGK_TEST_PICK(1.0e308, 1.0e38);
    cfg.target_radius_m = OGK_TEST_PICK(1.0e-300, 1.0e-30); /* circular speed overflows */
    OGK_ASSERT_STATUS(ogk_terminal_init(&ctx, &cfg), OGK_E_CONFIG);
    /* Any positive mu and radius are admitted (a normalised problem: mu = 0.5, R_f = 0.5). */
    cfg = terminal_config();
    cfg.mu_m3_s2 = 0.5;
    cfg.target_radius_m = 0.5;
    OGK_ASSERT_STATUS(ogk_terminal_init(&ctx, &cfg), OGK_OK);
    OGK_ASSERT_NEAR(ctx.v_target_mps, 1.0, 0.0);
    /* window 0: never engaged */
    cfg = terminal_config();
    cfg.window_s = 0.0;
    OGK_ASSERT_STATUS(ogk_terminal_init(&ctx, &cfg), OGK_OK);
    OGK_ASSERT_STATUS(ogk_terminal_step(&ctx, &nav, 100.0, &law, &out), OGK_OK);
    assert_true(memcmp(&out, &law, sizeof out) == 0);
    /* shaping: gain in [0, 1], hold in [HOLD_MIN, window] when the gain is positive */
    cfg = terminal_config();
    cfg.shape_gain = 1.5;
    OGK_ASSERT_STATUS(ogk_terminal_init(&ctx, &cfg), OGK_E_CONFIG);
    cfg.shape_gain = -0.1;
    OGK_ASSERT_STATUS(ogk_terminal_init(&ctx, &cfg), OGK_E_CONFIG);
    cfg.shape_gain = 0.0;
    cfg.shape_gain_normal = 1.0 + OGK_TEST_TOL(1e-12, 2.0 * FLT_EPSILON); /* just above 1 */
    OGK_ASSERT_STATUS(ogk_terminal_init(&ctx, &cfg), OGK_E_CONFIG);
    cfg.shape_gain_normal = 0.5; /* the normal gain alone turns shaping on: the hold is checked */
    cfg.shape_hold_s = cfg.window_s + 0.1;
    OGK_ASSERT_STATUS(ogk_terminal_init(&ctx, &cfg), OGK_E_CONFIG);
    cfg.shape_hold_s = 0.5 * OGK_TERMINAL_HOLD_MIN_S;
    OGK_ASSERT_STATUS(ogk_terminal_init(&ctx, &cfg), OGK_E_CONFIG);
    cfg.shape_hold_s = NAN;
    OGK_ASSERT_STATUS(ogk_terminal_init(&ctx, &cfg), OGK_E_CONFIG);
    cfg.shape_hold_s = 0.5;
    cfg.shape_lead_s = -0.1;
    OGK_ASSERT_STATUS(ogk_terminal_init(&ctx, &cfg), OGK_E_CONFIG);
    cfg.shape_lead_s = 2.0 * OGK_TERMINAL_T_MAX_S;
    OGK_ASSERT_STATUS(ogk_terminal_init(&ctx, &cfg), OGK_E_CONFIG);
    cfg.shape_lead_s = 0.0;
    cfg.shape_gain_normal = 0.0; /* off: the hold is not used */
    cfg.shape_hold_s = 1.0e6;
    OGK_ASSERT_STATUS(ogk_terminal_init(&ctx, &cfg), OGK_OK);
    cfg.shape_gain = 1.0;
    cfg.shape_hold_s = OGK_TERMINAL_HOLD_MIN_S;
    OGK_ASSERT_STATUS(ogk_terminal_init(&ctx, &cfg), OGK_OK);
    /* turn limit: finite, in [0, TURN_ACCEL_MAX] */
    cfg.turn_accel_rad_s2 = -1.0e-3;
    OGK_ASSERT_STATUS(ogk_terminal_init(&ctx, &cfg), OGK_E_CONFIG);
    cfg.turn_accel_rad_s2 = NAN;
    OGK_ASSERT_STATUS(ogk_terminal_init(&ctx, &cfg), OGK_E_CONFIG);
    cfg.turn_accel_rad_s2 = INFINITY;
    OGK_ASSERT_STATUS(ogk_terminal_init(&ctx, &cfg), OGK_E_CONFIG);
    cfg.turn_accel_rad_s2 = 2.0 * OGK_TERMINAL_TURN_ACCEL_MAX_RAD_S2;
    OGK_ASSERT_STATUS(ogk_terminal_init(&ctx, &cfg), OGK_E_CONFIG);
    cfg.turn_accel_rad_s2 = 0.2;
    OGK_ASSERT_STATUS(ogk_terminal_init(&ctx, &cfg), OGK_OK);
    /* reset keeps the configuration and the bound it gives */
    OGK_ASSERT_STATUS(ogk_terminal_reset(&ctx), OGK_OK);
    assert_true(ctx.tilt_limited);
    OGK_ASSERT_REL(ctx.shape_tilt_max_rad, 0.0625 * 0.2 * (3.0 - OGK_TERMINAL_HOLD_MIN_S) * (3.0 - OGK_TERMINAL_HOLD_MIN_S),
                   OGK_TEST_TOL(1e-15, 4.5 * FLT_EPSILON), 0.0);
}

#if OGK_REAL_SINGLE
/* The float build's split radius (ogk_terminal_step_split): r_lo_m 0 is
 * ogk_terminal_step bit for bit; the shaped plan's radius miss is
 * (r_m - R_f) + r_lo_m, so r_m = R_f + 124 m with r_lo_m = -4 m (float's
 * radius step there) flies as r_m = R_f + 120 m on the first engaged step
 * (no energy rate yet, phi = 0: nothing else reads r); a non-finite r_lo_m,
 * or one beyond OGK_REAL_EPSILON r_m, is rejected as ogk_terminal_step's
 * inputs are, the context unchanged. */
/* req: OGK-NOG-017 */
static void test_split_radius(void **state)
{
    ogk_terminal_config_t cfg = terminal_config();
    ogk_terminal_t a;
    ogk_terminal_t b;
    ogk_terminal_t before;
    ogk_nav_state_t nav = nav_at(100.0, 3.0, -40.0, -4.0);
    const ogk_nav_state_t nav_120 = nav;
    const ogk_thrust_cmd_t law = law_command(100.0);
    ogk_thrust_cmd_t out_a;
    ogk_thrust_cmd_t out_b;
    (void)state;
    cfg.shape_gain = 1.0;
    cfg.shape_gain_normal = 1.0;
    cfg.shape_hold_s = 0.5;
    (void)memset(&a, 0, sizeof a); /* the padding too: the contexts are compared byte for byte */
    (void)memset(&b, 0, sizeof b);
    OGK_ASSERT_STATUS(ogk_terminal_init(&a, &cfg), OGK_OK);
    OGK_ASSERT_STATUS(ogk_terminal_init(&b, &cfg), OGK_OK);
    OGK_ASSERT_STATUS(ogk_terminal_step_split(&a, &nav, 0.0f, 102.9, &law, &out_a), OGK_OK);
    OGK_ASSERT_STATUS(ogk_terminal_step(&b, &nav, 102.9, &law, &out_b), OGK_OK);
    assert_true(memcmp(&out_a, &out_b, sizeof out_a) == 0);
    assert_true(memcmp(&a, &b, sizeof a) == 0);

    nav.r_m = (ogk_real_t)(R_F + 124.0);
    assert_true((double)nav.r_m == R_F + 124.0);
    OGK_ASSERT_STATUS(ogk_terminal_reset(&a), OGK_OK);
    OGK_ASSERT_STATUS(ogk_terminal_reset(&b), OGK_OK);
    OGK_ASSERT_STATUS(ogk_terminal_step_split(&a, &nav, -4.0f, 102.9, &law, &out_a), OGK_OK);
    OGK_ASSERT_STATUS(ogk_terminal_step(&b, &nav_120, 102.9, &law, &out_b), OGK_OK);
    assert_true(memcmp(&out_a, &out_b, sizeof out_a) == 0);
    OGK_ASSERT_NEAR(a.r_lo_m, 0.0, 0.0); /* the step's alone */
    /* the 4 m the split carries do move the command */
    OGK_ASSERT_STATUS(ogk_terminal_reset(&b), OGK_OK);
    OGK_ASSERT_STATUS(ogk_terminal_step(&b, &nav, 102.9, &law, &out_b), OGK_OK);
    assert_true(out_a.alpha_rad != out_b.alpha_rad);

    /* rejections: the context as it was, the safe flag on the law's command */
    (void)memcpy(&before, &a, sizeof before);
    OGK_ASSERT_STATUS(ogk_terminal_step_split(&a, &nav, (ogk_real_t)NAN, 102.92, &law, &out_a), OGK_E_NONFINITE);
    assert_true(memcmp(&a, &before, sizeof a) == 0);
    assert_true((out_a.flags & OGK_THRUST_FLAG_SAFE) != 0u);
    OGK_ASSERT_STATUS(ogk_terminal_step_split(&a, &nav, 8.0f, 102.92, &law, &out_a), OGK_E_RANGE);
    assert_true(memcmp(&a, &before, sizeof a) == 0);
    OGK_ASSERT_STATUS(ogk_terminal_step_split(&a, &nav, 4.0f, 102.92, &law, &out_a), OGK_OK);
    OGK_ASSERT_STATUS(ogk_terminal_step_split(NULL, &nav, 0.0f, 102.9, &law, &out_a), OGK_E_NULL);
    OGK_ASSERT_STATUS(ogk_terminal_step_split(&a, NULL, 0.0f, 102.9, &law, &out_a), OGK_E_NULL);
}
#endif

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_outside_window_passes_law_command),
        cmocka_unit_test(test_window_steers_along_vgo_and_latches),
        cmocka_unit_test(test_direction_constant_while_vgo_shrinks),
        cmocka_unit_test(test_vgo_zero_holds_direction),
        cmocka_unit_test(test_rejections_change_nothing),
        cmocka_unit_test(test_shaped_plan_meets_its_end_conditions),
        cmocka_unit_test(test_shaped_window_steers_out_the_position_miss),
        cmocka_unit_test(test_shaped_fallbacks),
        cmocka_unit_test(test_turn_limit_bounds_the_plans_tilt),
        cmocka_unit_test(test_turn_limit_binds_only_when_it_can),
        cmocka_unit_test(test_contract),
#if OGK_REAL_SINGLE
        cmocka_unit_test(test_split_radius),
#endif
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
