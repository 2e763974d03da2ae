/* test_terminal.c -- terminal steering along the velocity to be gained
 * (ogk/terminal.h): the direction against the unit vector of v_go, the
 * window, the latch, and the rejections. */
#include "ogk_test.h"

#include <string.h>

#include "ogk/terminal.h"

#define MU 3.986004e14
#define R_F 42164.0e3

static ogk_terminal_config_t config(void)
{
    ogk_terminal_config_t cfg;
    (void)ogk_terminal_config_default(&cfg);
    cfg.mu_m3_s2 = MU;
    cfg.target_radius_m = R_F;
    cfg.window_s = 3.0;
    return cfg;
}

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

static ogk_thrust_cmd_t law_command(double t_s)
{
    ogk_thrust_cmd_t cmd;
    (void)memset(&cmd, 0, sizeof cmd);
    cmd.t_s = t_s;
    cmd.alpha_rad = 0.5;
    cmd.beta_rad = -0.25;
    cmd.flags = OGK_THRUST_FLAG_ENGINE_ON;
    cmd.law_flags = 0x2u;
    return cmd;
}

/* The command's thrust direction (ogk/types.h) against v_go / |v_go|. */
static void assert_along(const ogk_thrust_cmd_t *cmd, double g_r, double g_t, double g_n)
{
    const double norm = sqrt((g_r * g_r) + (g_t * g_t) + (g_n * g_n));
    OGK_ASSERT_NEAR(cos(cmd->beta_rad) * sin(cmd->alpha_rad), g_r / norm, 1e-14);
    OGK_ASSERT_NEAR(cos(cmd->beta_rad) * cos(cmd->alpha_rad), g_t / norm, 1e-14);
    OGK_ASSERT_NEAR(sin(cmd->beta_rad), g_n / norm, 1e-14);
}

static void test_outside_window_passes_law_command(void **state)
{
    const ogk_terminal_config_t cfg = config();
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

static void test_window_steers_along_vgo_and_latches(void **state)
{
    const ogk_terminal_config_t cfg = config();
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
static void test_direction_constant_while_vgo_shrinks(void **state)
{
    const ogk_terminal_config_t cfg = config();
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
        OGK_ASSERT_NEAR(out.alpha_rad, first.alpha_rad, 1e-12);
        OGK_ASSERT_NEAR(out.beta_rad, first.beta_rad, 1e-12);
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

static void test_vgo_zero_holds_direction(void **state)
{
    const ogk_terminal_config_t cfg = config();
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

static void test_rejections_change_nothing(void **state)
{
    const ogk_terminal_config_t cfg = config();
    ogk_terminal_t ctx;
    ogk_terminal_t before;
    ogk_nav_state_t nav = nav_at(100.0, 3.0, -40.0, -4.0);
    ogk_thrust_cmd_t law = law_command(100.0);
    ogk_thrust_cmd_t out;
    (void)state;
    OGK_ASSERT_STATUS(ogk_terminal_init(&ctx, &cfg), OGK_OK);
    /* Not engaged: the law's command, marked safe. */
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

static void test_contract(void **state)
{
    ogk_terminal_config_t cfg = config();
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
    cfg = config();
    cfg.target_radius_m = 0.0;
    OGK_ASSERT_STATUS(ogk_terminal_init(&ctx, &cfg), OGK_E_CONFIG);
    cfg = config();
    cfg.window_s = NAN;
    OGK_ASSERT_STATUS(ogk_terminal_init(&ctx, &cfg), OGK_E_CONFIG);
    cfg = config();
    cfg.mu_m3_s2 = 1.0e308;
    cfg.target_radius_m = 1.0e-300; /* circular speed overflows */
    OGK_ASSERT_STATUS(ogk_terminal_init(&ctx, &cfg), OGK_E_CONFIG);
    /* Any positive mu and radius are admitted (a normalised problem: mu = 0.5, R_f = 0.5). */
    cfg = config();
    cfg.mu_m3_s2 = 0.5;
    cfg.target_radius_m = 0.5;
    OGK_ASSERT_STATUS(ogk_terminal_init(&ctx, &cfg), OGK_OK);
    OGK_ASSERT_NEAR(ctx.v_target_mps, 1.0, 0.0);
    /* window 0: never engaged */
    cfg = config();
    cfg.window_s = 0.0;
    OGK_ASSERT_STATUS(ogk_terminal_init(&ctx, &cfg), OGK_OK);
    OGK_ASSERT_STATUS(ogk_terminal_step(&ctx, &nav, 100.0, &law, &out), OGK_OK);
    assert_true(memcmp(&out, &law, sizeof out) == 0);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_outside_window_passes_law_command),
        cmocka_unit_test(test_window_steers_along_vgo_and_latches),
        cmocka_unit_test(test_direction_constant_while_vgo_shrinks),
        cmocka_unit_test(test_vgo_zero_holds_direction),
        cmocka_unit_test(test_rejections_change_nothing),
        cmocka_unit_test(test_contract),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
