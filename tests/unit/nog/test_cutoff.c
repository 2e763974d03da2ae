/* test_cutoff.c -- energy cut-off monitor (ogk/cutoff.h) against the analytic
 * crossing of a constant-acceleration burn along the velocity. */
#include "ogk_test.h"

#include <float.h>
#include <string.h>

#include "endgame_fixture.h"
#include "ogk/cutoff.h"

#define ACCEL 17.7   /* [m/s^2] thrust acceleration at the end of the LEO-to-GEO burn */
#define DT 0.02      /* [s] control period */
#define T_CROSS 105.8123 /* [s] time the energy reaches the target (not on the 20 ms grid) */

/* On the target circle r = a, with the speed reaching the circular speed at
 * T_CROSS while accelerating at ACCEL along the velocity (transverse): the
 * energy v^2/2 - mu/r reaches -mu/(2a) exactly when v = sqrt(mu/a). */
static ogk_nav_state_t burn_state(double t_s)
{
    ogk_nav_state_t nav;
    (void)memset(&nav, 0, sizeof nav);
    nav.t_s = t_s;
    nav.r_m = A_TARGET;
    nav.v_t_mps = sqrt(MU / A_TARGET) - (ACCEL * (T_CROSS - t_s));
    return nav;
}

/* Steps the monitor on the 20 ms grid from t0 until it decides or t_end. */
static ogk_cutoff_out_t fly(ogk_cutoff_t *ctx, double t0, double t_end, double t_predicted)
{
    ogk_cutoff_out_t out;
    int k;
    (void)memset(&out, 0, sizeof out);
    for (k = 0; (k < 100000) && ((t0 + (k * DT)) <= t_end); ++k) {
        const ogk_nav_state_t nav = burn_state(t0 + (k * DT));
        OGK_ASSERT_STATUS(ogk_cutoff_step(ctx, &nav, t_predicted, &out), OGK_OK);
        if ((out.flags & OGK_CUTOFF_FLAG_DECIDED) != 0u) {
            break;
        }
    }
    return out;
}

/* req: OGK-NOG-016 */
static void test_crossing_between_control_steps(void **state)
{
    const ogk_cutoff_config_t cfg = cutoff_config(DT);
    ogk_cutoff_t ctx;
    ogk_cutoff_out_t out;
    (void)state;
    OGK_ASSERT_STATUS(ogk_cutoff_init(&ctx, &cfg), OGK_OK);
    /* Prediction 1.2 s late (a thrust fluctuation after the last sample). */
    out = fly(&ctx, 100.0, 120.0, T_CROSS + 1.2);
    assert_true((out.flags & OGK_CUTOFF_FLAG_DECIDED) != 0u);
    /* Backward-difference rate of a quadratic energy: error ~ (a^2 dt^2)/(v a),
     * about 1e-6 s here; 1e-5 s is 0.2 mm/s of injection velocity. */
    OGK_ASSERT_NEAR(out.t_cutoff_s, T_CROSS, 1.0e-5);
    /* Energy rate v a, measured over the last period. */
    OGK_ASSERT_REL(out.energy_rate_w_kg, sqrt(MU / A_TARGET) * ACCEL, 1.0e-3, 1.0);
    /* Decided cut-off latches. */
    {
        const ogk_nav_state_t later = burn_state(T_CROSS + 0.5);
        ogk_cutoff_out_t again;
        OGK_ASSERT_STATUS(ogk_cutoff_step(&ctx, &later, T_CROSS + 3.0, &again), OGK_OK);
        assert_true((again.flags & OGK_CUTOFF_FLAG_DECIDED) != 0u);
        OGK_ASSERT_NEAR(again.t_cutoff_s, out.t_cutoff_s, 0.0);
    }
    /* A rejected call after the decision reports the decided cut-off. */
    {
        ogk_nav_state_t bad = burn_state(T_CROSS + 0.6);
        ogk_cutoff_out_t again;
        bad.r_m = NAN;
        OGK_ASSERT_STATUS(ogk_cutoff_step(&ctx, &bad, T_CROSS + 3.0, &again), OGK_E_NONFINITE);
        assert_int_equal(again.flags, OGK_CUTOFF_FLAG_DECIDED);
        OGK_ASSERT_NEAR(again.t_cutoff_s, out.t_cutoff_s, 0.0);
    }
}

/* req: OGK-NOG-016 */
static void test_prediction_early_is_overridden(void **state)
{
    const ogk_cutoff_config_t cfg = cutoff_config(DT);
    ogk_cutoff_t ctx;
    ogk_cutoff_out_t out;
    (void)state;
    OGK_ASSERT_STATUS(ogk_cutoff_init(&ctx, &cfg), OGK_OK);
    /* Prediction 1.5 s early: the engine burns on past it to the crossing. */
    out = fly(&ctx, 100.0, 120.0, T_CROSS - 1.5);
    OGK_ASSERT_NEAR(out.t_cutoff_s, T_CROSS, 1.0e-5);
}

/* req: OGK-NOG-016 */
static void test_not_armed_before_window(void **state)
{
    const ogk_cutoff_config_t cfg = cutoff_config(DT);
    ogk_cutoff_t ctx;
    ogk_cutoff_out_t out;
    (void)state;
    OGK_ASSERT_STATUS(ogk_cutoff_init(&ctx, &cfg), OGK_OK);
    /* Energy crosses at T_CROSS but the prediction says 20 s later: not armed
     * until 18 s after the crossing (energy above target then: cut at once). */
    out = fly(&ctx, 100.0, T_CROSS + 17.0, T_CROSS + 20.0);
    assert_true((out.flags & OGK_CUTOFF_FLAG_DECIDED) == 0u);
    assert_true((out.flags & OGK_CUTOFF_FLAG_BACKSTOP) != 0u);
    assert_true((out.flags & OGK_CUTOFF_FLAG_ARMED) == 0u);
    /* float: the time as a float (half an ulp of 136 s, 1 eps of it written) */
    OGK_ASSERT_NEAR(out.t_cutoff_s, T_CROSS + 30.0, OGK_TEST_TOL(1.0e-9, FLT_EPSILON * (T_CROSS + 30.0)));
    out = fly(&ctx, T_CROSS + 18.0, T_CROSS + 19.0, T_CROSS + 20.0);
    assert_true((out.flags & OGK_CUTOFF_FLAG_DECIDED) != 0u);
    OGK_ASSERT_NEAR(out.t_cutoff_s, T_CROSS + 18.0, OGK_TEST_TOL(1.0e-9, FLT_EPSILON * (T_CROSS + 18.0)));
}

/* req: OGK-NOG-016 */
static void test_backstop_when_energy_short(void **state)
{
    ogk_cutoff_config_t cfg = cutoff_config(DT);
    ogk_cutoff_t ctx;
    ogk_cutoff_out_t out;
    (void)state;
    cfg.target_sma_m = 2.0 * A_TARGET; /* never reached by this burn before the backstop */
    OGK_ASSERT_STATUS(ogk_cutoff_init(&ctx, &cfg), OGK_OK);
    out = fly(&ctx, 100.0, 115.0, 104.0);
    assert_true((out.flags & OGK_CUTOFF_FLAG_DECIDED) != 0u);
    /* First 20 ms grid time at or after 104 + 10 s. */
    OGK_ASSERT_NEAR(out.t_cutoff_s, 114.0, 1.0e-9);
}

/* req: OGK-NOG-016 */
static void test_bad_input_changes_nothing(void **state)
{
    const ogk_cutoff_config_t cfg = cutoff_config(DT);
    ogk_cutoff_t ctx;
    ogk_cutoff_t before;
    ogk_cutoff_out_t out;
    ogk_nav_state_t nav = burn_state(101.0);
    (void)state;
    OGK_ASSERT_STATUS(ogk_cutoff_init(&ctx, &cfg), OGK_OK);
    OGK_ASSERT_STATUS(ogk_cutoff_step(&ctx, &nav, 106.0, &out), OGK_OK);
    before = ctx;
    nav = burn_state(101.02);
    nav.v_n_mps = NAN;
    OGK_ASSERT_STATUS(ogk_cutoff_step(&ctx, &nav, 106.0, &out), OGK_E_NONFINITE);
    assert_true(memcmp(&ctx, &before, sizeof ctx) == 0);
    OGK_ASSERT_NEAR(out.t_cutoff_s, 116.0, 0.0); /* backstop of the prediction */
    nav = burn_state(101.0);                   /* time not after the last accepted call */
    OGK_ASSERT_STATUS(ogk_cutoff_step(&ctx, &nav, 106.0, &out), OGK_E_RANGE);
    nav = burn_state(101.02);
    nav.r_m = 0.0;
    OGK_ASSERT_STATUS(ogk_cutoff_step(&ctx, &nav, 106.0, &out), OGK_E_RANGE);
    nav.r_m = DBL_MIN * DBL_EPSILON;           /* a subnormal radius: mu / r overflows */
    OGK_ASSERT_STATUS(ogk_cutoff_step(&ctx, &nav, 106.0, &out), OGK_E_RANGE);
    nav = burn_state(101.02);
    nav.v_r_mps = 2.0 * OGK_CUTOFF_V_MAX_MPS;
    OGK_ASSERT_STATUS(ogk_cutoff_step(&ctx, &nav, 106.0, &out), OGK_E_RANGE);
    nav = burn_state(101.02);
    OGK_ASSERT_STATUS(ogk_cutoff_step(&ctx, &nav, -1.0, &out), OGK_E_RANGE);
    OGK_ASSERT_NEAR(out.t_cutoff_s, 116.0, 0.0); /* the last accepted call's backstop */
    assert_true(memcmp(&ctx, &before, sizeof ctx) == 0);
    /* The same decision as a monitor that never saw the bad samples. */
    out = fly(&ctx, 101.02, 120.0, T_CROSS);
    OGK_ASSERT_NEAR(out.t_cutoff_s, T_CROSS, 1.0e-5);
    /* Reset: a new burn, undecided, nothing held. */
    OGK_ASSERT_STATUS(ogk_cutoff_reset(&ctx), OGK_OK);
    nav = burn_state(50.0);
    OGK_ASSERT_STATUS(ogk_cutoff_step(&ctx, &nav, 106.0, &out), OGK_OK);
    assert_true((out.flags & OGK_CUTOFF_FLAG_DECIDED) == 0u);
    OGK_ASSERT_NEAR(out.energy_rate_w_kg, 0.0, 0.0);
}

/* Found by tests/fuzz/fuzz_cutoff_step.c: two calls a subnormal time apart
 * made the energy rate overflow to inf (and the output non-finite). */
/* req: OGK-NOG-016 */
static void test_rate_overflow_is_no_rate(void **state)
{
    const ogk_cutoff_config_t cfg = cutoff_config(DT);
    ogk_cutoff_t ctx;
    ogk_cutoff_out_t out;
    ogk_nav_state_t nav = burn_state(0.0);
    (void)state;
    OGK_ASSERT_STATUS(ogk_cutoff_init(&ctx, &cfg), OGK_OK);
    OGK_ASSERT_STATUS(ogk_cutoff_step(&ctx, &nav, 0.5, &out), OGK_OK);
    nav.t_s = OGK_REAL_MIN * OGK_REAL_EPSILON; /* the smallest subnormal of the type */
    nav.v_t_mps += 1.0;
    OGK_ASSERT_STATUS(ogk_cutoff_step(&ctx, &nav, 0.5, &out), OGK_OK);
    OGK_ASSERT_NEAR(out.energy_rate_w_kg, 0.0, 0.0);
    assert_true(isfinite(out.t_cutoff_s) && isfinite(out.energy_j_kg));
    assert_true((out.flags & OGK_CUTOFF_FLAG_DECIDED) == 0u);
}

/* req: OGK-NOG-016 */
/* Calls at least the minimum step apart whose energies differ by more than
 * DBL_MAX times that step (mu = 1e308: -1e308 J/kg at r = 1 m, -1e307 at
 * 10 m, 1 ns apart): the quotient overflows, and no rate is used. Float:
 * mu = 1e38, 10 us apart (1 ns is below float's resolution of t = 100 s):
 * beyond FLT_MAX the same way. */
static void test_rate_of_absurd_mu_is_no_rate(void **state)
{
    ogk_cutoff_config_t cfg = cutoff_config(DT);
    ogk_cutoff_t ctx;
    ogk_cutoff_out_t out;
    ogk_nav_state_t nav = burn_state(100.0);
    (void)state;
    cfg.mu_m3_s2 = OGK_TEST_PICK(1.0e308, 1.0e38);
    OGK_ASSERT_STATUS(ogk_cutoff_init(&ctx, &cfg), OGK_OK);
    nav.r_m = 1.0;
    OGK_ASSERT_STATUS(ogk_cutoff_step(&ctx, &nav, 100.5, &out), OGK_OK);
    nav.t_s += OGK_TEST_PICK(1.0e-9, 1.0e-5);
    nav.r_m = 10.0;
    OGK_ASSERT_STATUS(ogk_cutoff_step(&ctx, &nav, 100.5, &out), OGK_OK);
    OGK_ASSERT_NEAR(out.energy_rate_w_kg, 0.0, 0.0);
    assert_true(isfinite(out.t_cutoff_s) && isfinite(out.energy_j_kg));
}

/* req: OGK-NOG-016 */
static void test_contract(void **state)
{
    ogk_cutoff_config_t cfg = cutoff_config(DT);
    ogk_cutoff_t ctx;
    ogk_cutoff_out_t out;
    const ogk_nav_state_t nav = burn_state(100.0);
    (void)state;
    (void)memset(&ctx, 0, sizeof ctx);
    OGK_ASSERT_STATUS(ogk_cutoff_config_default(NULL), OGK_E_NULL);
    OGK_ASSERT_STATUS(ogk_cutoff_init(NULL, &cfg), OGK_E_NULL);
    OGK_ASSERT_STATUS(ogk_cutoff_init(&ctx, NULL), OGK_E_NULL);
    OGK_ASSERT_STATUS(ogk_cutoff_reset(NULL), OGK_E_NULL);
    OGK_ASSERT_STATUS(ogk_cutoff_reset(&ctx), OGK_E_NOT_INIT);
    OGK_ASSERT_STATUS(ogk_cutoff_step(&ctx, &nav, 106.0, &out), OGK_E_NOT_INIT);
    OGK_ASSERT_STATUS(ogk_cutoff_step(NULL, &nav, 106.0, &out), OGK_E_NULL);
    OGK_ASSERT_STATUS(ogk_cutoff_step(&ctx, NULL, 106.0, &out), OGK_E_NULL);
    OGK_ASSERT_STATUS(ogk_cutoff_step(&ctx, &nav, 106.0, NULL), OGK_E_NULL);
    cfg.mu_m3_s2 = 0.0;
    OGK_ASSERT_STATUS(ogk_cutoff_init(&ctx, &cfg), OGK_E_CONFIG);
    cfg = cutoff_config(DT);
    cfg.target_sma_m = -1.0;
    OGK_ASSERT_STATUS(ogk_cutoff_init(&ctx, &cfg), OGK_E_CONFIG);
    cfg = cutoff_config(DT);
    cfg.arm_before_s = -0.1;
    OGK_ASSERT_STATUS(ogk_cutoff_init(&ctx, &cfg), OGK_E_CONFIG);
    cfg = cutoff_config(DT);
    cfg.extend_max_s = INFINITY;
    OGK_ASSERT_STATUS(ogk_cutoff_init(&ctx, &cfg), OGK_E_CONFIG);
    cfg = cutoff_config(DT);
    cfg.control_period_s = 0.0;
    OGK_ASSERT_STATUS(ogk_cutoff_init(&ctx, &cfg), OGK_E_CONFIG);
    assert_int_not_equal((int)ctx.init_marker, 0x43555430); /* rejected config: still not initialised */
    /* The closed bounds are admitted: extend_max_s = T_MAX, a prediction at t = 0. */
    cfg = cutoff_config(DT);
    cfg.extend_max_s = OGK_CUTOFF_T_MAX_S;
    OGK_ASSERT_STATUS(ogk_cutoff_init(&ctx, &cfg), OGK_OK);
    OGK_ASSERT_STATUS(ogk_cutoff_step(&ctx, &nav, 0.0, &out), OGK_OK);
    OGK_ASSERT_NEAR(out.t_cutoff_s, OGK_CUTOFF_T_MAX_S, 0.0);
    assert_int_equal(out.flags, OGK_CUTOFF_FLAG_ARMED | OGK_CUTOFF_FLAG_BACKSTOP);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_crossing_between_control_steps),
        cmocka_unit_test(test_prediction_early_is_overridden),
        cmocka_unit_test(test_not_armed_before_window),
        cmocka_unit_test(test_backstop_when_energy_short),
        cmocka_unit_test(test_bad_input_changes_nothing),
        cmocka_unit_test(test_rate_overflow_is_no_rate),
        cmocka_unit_test(test_rate_of_absurd_mu_is_no_rate),
        cmocka_unit_test(test_contract),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
