/* test_terminal_envelope.c -- MC/DC of ogk_terminal (docs/evidence/coverage.md, "MC/DC"): every operand of the
 * configuration and navigation-envelope conjunctions decides alone. Each case moves one field
 * just outside the range ogk/terminal.h documents, every other field inside, and the same field
 * at its bound is accepted; a rejected step leaves the context unchanged and outputs the law's
 * command marked safe, or the last terminal one (zeros before engagement) when the law's
 * command is not finite either (the header's contract). */
#include "ogk_test.h"

#include <float.h>
#include <stddef.h>
#include <string.h>

#include "endgame_fixture.h"
#include "ogk/terminal.h"


static ogk_nav_state_t nav_at(double t_s)
{
    ogk_nav_state_t nav;
    (void)memset(&nav, 0, sizeof nav);
    nav.t_s = t_s;
    nav.r_m = R_F + 120.0;
    nav.v_r_mps = 3.0;
    nav.v_t_mps = sqrt(MU / R_F) - 40.0;
    nav.v_n_mps = -4.0;
    return nav;
}

/* One configuration field set to value: init gives want; a rejection leaves the context
 * byte-identical; an accepted one has the circular speed sqrt(mu / R_f) of eq. (20). */
static void init_with(size_t offset, double value, ogk_status want)
{
    ogk_terminal_config_t cfg = terminal_config();
    ogk_terminal_t ctx;
    ogk_terminal_t before;
    (void)memset(&ctx, 0x5a, sizeof ctx);
    before = ctx;
    *(ogk_real_t *)((char *)&cfg + offset) = value;
    OGK_ASSERT_STATUS(ogk_terminal_init(&ctx, &cfg), want);
    if (want != OGK_OK) {
        assert_true(memcmp(&ctx, &before, sizeof ctx) == 0);
    } else {
        OGK_ASSERT_REL(ctx.v_target_mps, sqrt(cfg.mu_m3_s2 / cfg.target_radius_m), OGK_TEST_TOL(1e-15, 4.5 * FLT_EPSILON), 0.0);
    }
}

/* req: OGK-NOG-017 */
static void test_each_config_bound_decides_alone(void **state)
{
    (void)state;
    init_with(offsetof(ogk_terminal_config_t, shape_gain_normal), 0.0, OGK_OK);
    init_with(offsetof(ogk_terminal_config_t, shape_gain_normal), OGK_TEST_NEXTAFTER(0.0, -1.0), OGK_E_CONFIG);
    init_with(offsetof(ogk_terminal_config_t, target_radius_m), OGK_TERMINAL_R_MAX_M, OGK_OK);
    init_with(offsetof(ogk_terminal_config_t, target_radius_m), OGK_TEST_NEXTAFTER(OGK_TERMINAL_R_MAX_M, DBL_MAX),
              OGK_E_CONFIG);
    init_with(offsetof(ogk_terminal_config_t, window_s), 0.0, OGK_OK);
    init_with(offsetof(ogk_terminal_config_t, window_s), OGK_TEST_NEXTAFTER(0.0, -1.0), OGK_E_CONFIG);
    init_with(offsetof(ogk_terminal_config_t, window_s), OGK_TERMINAL_T_MAX_S, OGK_OK);
    init_with(offsetof(ogk_terminal_config_t, window_s), OGK_TEST_NEXTAFTER(OGK_TERMINAL_T_MAX_S, DBL_MAX), OGK_E_CONFIG);
    init_with(offsetof(ogk_terminal_config_t, turn_accel_rad_s2), 0.0, OGK_OK);
    init_with(offsetof(ogk_terminal_config_t, turn_accel_rad_s2), OGK_TEST_NEXTAFTER(0.0, -1.0), OGK_E_CONFIG);
    init_with(offsetof(ogk_terminal_config_t, turn_accel_rad_s2), OGK_TERMINAL_TURN_ACCEL_MAX_RAD_S2, OGK_OK);
    init_with(offsetof(ogk_terminal_config_t, turn_accel_rad_s2),
              OGK_TEST_NEXTAFTER(OGK_TERMINAL_TURN_ACCEL_MAX_RAD_S2, DBL_MAX), OGK_E_CONFIG);
}

/* A nav field set to value, outside the window (t_predicted - t = 500 s > 3 s): want; on a
 * rejection the context is unchanged and the output is the law's command marked safe. */
static void step_with(size_t offset, double value, double t_predicted, ogk_status want)
{
    const ogk_terminal_config_t cfg = terminal_config();
    ogk_terminal_t ctx;
    ogk_terminal_t before;
    ogk_nav_state_t nav = nav_at(100.0);
    const ogk_thrust_cmd_t law = law_command(100.0);
    ogk_thrust_cmd_t out;
    *(ogk_real_t *)((char *)&nav + offset) = value;
    OGK_ASSERT_STATUS(ogk_terminal_init(&ctx, &cfg), OGK_OK);
    before = ctx;
    OGK_ASSERT_STATUS(ogk_terminal_step(&ctx, &nav, t_predicted, &law, &out), want);
    OGK_ASSERT_NEAR(out.alpha_rad, law.alpha_rad, 0.0);
    OGK_ASSERT_NEAR(out.beta_rad, law.beta_rad, 0.0);
    if (want != OGK_OK) {
        assert_true(memcmp(&ctx, &before, sizeof ctx) == 0);
        assert_int_equal((int)out.flags, (int)(OGK_THRUST_FLAG_ENGINE_ON | OGK_THRUST_FLAG_SAFE));
    } else {
        assert_int_equal((int)out.flags, (int)OGK_THRUST_FLAG_ENGINE_ON);
        assert_false(ctx.engaged);
    }
}

/* req: OGK-NOG-017 */
static void test_each_envelope_bound_decides_alone(void **state)
{
    const double over_v = OGK_TEST_NEXTAFTER(OGK_TERMINAL_V_MAX_MPS, DBL_MAX);
    const double over_t = OGK_TEST_NEXTAFTER(OGK_TERMINAL_T_MAX_S, DBL_MAX);
    (void)state;
    step_with(offsetof(ogk_nav_state_t, r_m), OGK_TERMINAL_R_MAX_M, 600.0, OGK_OK);
    step_with(offsetof(ogk_nav_state_t, r_m), OGK_TEST_NEXTAFTER(OGK_TERMINAL_R_MAX_M, DBL_MAX), 600.0, OGK_E_RANGE);
    step_with(offsetof(ogk_nav_state_t, v_r_mps), -OGK_TERMINAL_V_MAX_MPS, 600.0, OGK_OK);
    step_with(offsetof(ogk_nav_state_t, v_r_mps), -over_v, 600.0, OGK_E_RANGE);
    step_with(offsetof(ogk_nav_state_t, v_n_mps), OGK_TERMINAL_V_MAX_MPS, 600.0, OGK_OK);
    step_with(offsetof(ogk_nav_state_t, v_n_mps), over_v, 600.0, OGK_E_RANGE);
    step_with(offsetof(ogk_nav_state_t, t_s), 0.0, 600.0, OGK_OK);
    step_with(offsetof(ogk_nav_state_t, t_s), OGK_TEST_NEXTAFTER(0.0, -1.0), 600.0, OGK_E_RANGE);
    /* t and the predicted cut-off each one step beyond T_MAX (v_t = 0 is inside the envelope) */
    step_with(offsetof(ogk_nav_state_t, t_s), over_t, 600.0, OGK_E_RANGE);
    step_with(offsetof(ogk_nav_state_t, v_t_mps), 0.0, OGK_TERMINAL_T_MAX_S, OGK_OK);
    step_with(offsetof(ogk_nav_state_t, v_t_mps), 0.0, over_t, OGK_E_RANGE);
}

/* A rejected step whose law command has a NaN beta alone: the last terminal command (zeros
 * before engagement), engine bit of the law, marked safe. */
/* req: OGK-NOG-017 */
static void test_nan_beta_alone_gives_last_terminal_command(void **state)
{
    const ogk_terminal_config_t cfg = terminal_config();
    ogk_terminal_t ctx;
    ogk_terminal_t before;
    ogk_nav_state_t nav = nav_at(100.0);
    ogk_thrust_cmd_t law = law_command(100.0);
    ogk_thrust_cmd_t out;
    (void)state;
    OGK_ASSERT_STATUS(ogk_terminal_init(&ctx, &cfg), OGK_OK);
    nav.r_m = -1.0;
    law.beta_rad = NAN;
    before = ctx;
    OGK_ASSERT_STATUS(ogk_terminal_step(&ctx, &nav, 600.0, &law, &out), OGK_E_NONFINITE);
    assert_true(memcmp(&ctx, &before, sizeof ctx) == 0);
    OGK_ASSERT_NEAR(out.alpha_rad, 0.0, 0.0);
    OGK_ASSERT_NEAR(out.beta_rad, 0.0, 0.0);
    /* zero angles: the r-t-n unit vector (cos b sin a, cos b cos a, sin b) = (0, 1, 0) */
    OGK_ASSERT_NEAR(out.u[0], 0.0, 0.0);
    OGK_ASSERT_NEAR(out.u[1], 1.0, 0.0);
    OGK_ASSERT_NEAR(out.u[2], 0.0, 0.0);
    assert_int_equal((int)out.flags, (int)(OGK_THRUST_FLAG_ENGINE_ON | OGK_THRUST_FLAG_SAFE));
    assert_int_equal((int)out.law_flags, 0);
    /* the same with a finite beta: the law's command, marked safe */
    law.beta_rad = -0.25;
    OGK_ASSERT_STATUS(ogk_terminal_step(&ctx, &nav, 600.0, &law, &out), OGK_E_RANGE);
    OGK_ASSERT_NEAR(out.beta_rad, -0.25, 0.0);
    assert_int_equal((int)out.law_flags, 0x2);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_each_config_bound_decides_alone),
        cmocka_unit_test(test_each_envelope_bound_decides_alone),
        cmocka_unit_test(test_nan_beta_alone_gives_last_terminal_command),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
