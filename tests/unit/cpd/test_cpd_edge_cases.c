/* test_cpd_edge_cases.c -- CPD paths test_cpd.c leaves unrun (make coverage, docs/evidence/coverage.md): the
 * commanded direction exactly opposite x_b (the deterministic pitch-around of the body pointing
 * error), each sign bound of the configuration, and a finite but absurd configuration whose
 * command comes out non-finite (the safe command, never NaN handed to the actuators).
 *
 * Both precisions (ogk_test.h). In float the residues of sin(pi), cos(pi/2) are 8.7e-8 and
 * 4.4e-8 (pi, pi/2 are not floats): the direction is behind to within 1e-7 rad, the error's
 * magnitude and its pitch axis pi to CPD_EPS pi (test_cpd.c). A subnormal period and the
 * smallest normal bound are float's. */
#include "ogk_test.h"

#include <float.h>
#include <string.h>

#include "ogk/cpd.h"

#define PI 3.14159265358979323846
#define CPD_EPS (16.0 * FLT_EPSILON)

static ogk_cpd_input_t zero_input(void)
{
    ogk_cpd_input_t in;
    (void)memset(&in, 0, sizeof in);
    return in;
}

static ogk_cpd_config_t default_config(void)
{
    ogk_cpd_config_t cfg;
    OGK_ASSERT_STATUS(ogk_cpd_config_default(&cfg), OGK_OK);
    return cfg;
}

/* Pitch +90 deg with the command at alpha = -90 deg, beta = 180 deg, phi = 180 deg: every
 * sine and cosine involved is 0, +-1 or the rounding residue of sin(pi), cos(pi/2), and the
 * commanded direction comes out as t_b = (-1, 0, 0) exactly: behind, with no lateral part to
 * give a rotation axis. The rotation vector is then pi about y_b (deterministic); its length
 * is the pointing angle pi whichever axis is chosen. */
/* req: OGK-CPD-004 */
static void test_exactly_behind(void **state)
{
    const double psi = 0.0;
    const double theta = 0.5 * PI;
    const double phi_roll = 0.0;
    const double alpha_c = -0.5 * PI;
    const double beta_c = PI;
    const double xi = 0.0;
    const double phi = PI;
    ogk_real_t ey = -7.0;
    ogk_real_t ez = -7.0;
    ogk_cpd_t ctx;
    ogk_cpd_config_t cfg = default_config();
    ogk_cpd_input_t in = zero_input();
    ogk_cpd_output_t out;
    (void)state;
    OGK_ASSERT_STATUS(ogk_cpd_pointing_error_body(psi, theta, phi_roll, alpha_c, beta_c, xi, phi,
                                                  &ey, &ez),
                      OGK_OK);
    OGK_ASSERT_NEAR(hypot(ey, ez), PI, OGK_TEST_TOL(1e-12, CPD_EPS * PI));
    OGK_ASSERT_NEAR(fabs(ey), PI, OGK_TEST_TOL(1e-12, CPD_EPS * PI)); /* pitch, not yaw, turns the vehicle around */
    OGK_ASSERT_NEAR(ez, 0.0, OGK_TEST_TOL(1e-12, CPD_EPS * PI));
    OGK_ASSERT_STATUS(ogk_cpd_init(&ctx, &cfg), OGK_OK);
    in.psi = psi;
    in.theta = theta;
    in.phi_roll = phi_roll;
    in.alpha_c = alpha_c;
    in.beta_c = beta_c;
    in.xi = xi;
    in.phi = phi;
    OGK_ASSERT_STATUS(ogk_cpd_step(&ctx, &in, &out), OGK_OK);
    assert_true((out.flags & OGK_CPD_FLAG_BEHIND) != 0u);
    assert_true((out.flags & OGK_CPD_FLAG_SAT_Y) != 0u);
    OGK_ASSERT_NEAR(out.err_y, ey, 0.0);
    OGK_ASSERT_NEAR(out.err_z, ez, 0.0);
    /* full pitch deflection towards the error, no yaw command */
    OGK_ASSERT_NEAR(fabs(out.delta_yc), cfg.delta_yc_max, 0.0);
    OGK_ASSERT_NEAR(out.delta_zc, 0.0, 1e-12);
}

/* Negative braking accelerations and a negative feed-forward clip are refused one by one. */
/* req: OGK-CPD-006 */
static void test_config_sign_bounds(void **state)
{
    ogk_cpd_t ctx;
    unsigned k;
    (void)state;
    for (k = 0u; k < 5u; ++k) {
        ogk_cpd_config_t cfg = default_config();
        switch (k) {
        case 0u: cfg.approach_accel_x = -OGK_REAL_MIN; break;
        case 1u: cfg.approach_accel_y = -1.0; break;
        case 2u: cfg.approach_accel_z = -1.0; break;
        case 3u: cfg.ff_period_s = -0.01; break;
        default: cfg.ff_rate_max = -1.0; break;
        }
        (void)memset(&ctx, 0x5A, sizeof ctx);
        OGK_ASSERT_STATUS(ogk_cpd_init(&ctx, &cfg), OGK_E_CONFIG);
        assert_true(ctx.init_marker != OGK_CPD_INIT_MARKER);
    }
    {
        ogk_cpd_config_t cfg = default_config();
        cfg.approach_accel_x = 0.0; /* 0: off, allowed */
        cfg.ff_rate_max = 0.0;
        OGK_ASSERT_STATUS(ogk_cpd_init(&ctx, &cfg), OGK_OK);
    }
}

/* A control period of 1e-320 s (float: 1e-40; subnormal, finite, > 0: accepted) makes the feed-forward rate
 * (d_prev x d_now) / period overflow; its clip turns inf into NaN. The step must answer with
 * the safe command (all zero, SAFE) and OGK_E_SAFE_COMMAND, and keep it as its last command. */
/* req: OGK-CPD-009 OGK-CPD-007 */
static void test_overflowing_feedforward_gives_safe_command(void **state)
{
    ogk_cpd_t ctx;
    ogk_cpd_config_t cfg = default_config();
    ogk_cpd_input_t in = zero_input();
    ogk_cpd_output_t out;
    (void)state;
    cfg.ff_period_s = OGK_TEST_PICK(1.0e-320, 1.0e-40);
    cfg.ff_rate_max = 1.0;
    OGK_ASSERT_STATUS(ogk_cpd_init(&ctx, &cfg), OGK_OK);
    in.alpha_c = 0.1;
    OGK_ASSERT_STATUS(ogk_cpd_step(&ctx, &in, &out), OGK_OK); /* no previous direction yet */
    assert_true(isfinite(out.delta_yc) && isfinite(out.delta_zc));
    in.alpha_c = 0.2;
    in.beta_c = 0.1;
    OGK_ASSERT_STATUS(ogk_cpd_step(&ctx, &in, &out), OGK_E_SAFE_COMMAND);
    assert_int_equal(out.flags, OGK_CPD_FLAG_SAFE);
    OGK_ASSERT_NEAR(out.m_xc, 0.0, 0.0);
    OGK_ASSERT_NEAR(out.delta_yc, 0.0, 0.0);
    OGK_ASSERT_NEAR(out.delta_zc, 0.0, 0.0);
    OGK_ASSERT_NEAR(out.err_y, 0.0, 0.0);
    OGK_ASSERT_NEAR(out.psi_c, 0.0, 0.0);
    assert_int_equal(ctx.last.flags, OGK_CPD_FLAG_SAFE);
    OGK_ASSERT_NEAR(ctx.last.delta_yc, 0.0, 0.0);
    /* the same step with feed-forward off is a normal command */
    cfg.ff_period_s = 0.0;
    OGK_ASSERT_STATUS(ogk_cpd_init(&ctx, &cfg), OGK_OK);
    OGK_ASSERT_STATUS(ogk_cpd_step(&ctx, &in, &out), OGK_OK);
    assert_true((out.flags & OGK_CPD_FLAG_SAFE) == 0u);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_exactly_behind),
        cmocka_unit_test(test_config_sign_bounds),
        cmocka_unit_test(test_overflowing_feedforward_gives_safe_command),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
