/* test_cutoff_envelope.c -- MC/DC of ogk_cutoff (docs/evidence/coverage.md, "MC/DC"): every operand of the
 * configuration and navigation-envelope conjunctions decides alone. Each case moves one field
 * just outside the range the header documents (ogk/cutoff.h) with every other field inside, and
 * the same field at its bound is accepted; the references are the documented ranges and the
 * vis-viva energy, not the code. */
#include "ogk_test.h"

#include <float.h>
#include <stddef.h>
#include <string.h>

#include "endgame_fixture.h"
#include "ogk/cutoff.h"


static ogk_nav_state_t nav_at(double t_s)
{
    ogk_nav_state_t nav;
    (void)memset(&nav, 0, sizeof nav);
    nav.t_s = t_s;
    nav.r_m = 7.0e6;
    nav.v_r_mps = 100.0;
    nav.v_t_mps = 7500.0;
    nav.v_n_mps = -20.0;
    return nav;
}

/* One configuration field set to value: init gives want, and on a rejection the context is
 * byte-identical (OGK_E_CONFIG leaves it untouched, ogk/cutoff.h). */
static void init_with(size_t offset, double value, ogk_status want)
{
    ogk_cutoff_config_t cfg = cutoff_config(0.02);
    ogk_cutoff_t ctx;
    ogk_cutoff_t before;
    (void)memset(&ctx, 0x5a, sizeof ctx);
    before = ctx;
    *(ogk_real_t *)((char *)&cfg + offset) = value;
    OGK_ASSERT_STATUS(ogk_cutoff_init(&ctx, &cfg), want);
    if (want != OGK_OK) {
        assert_true(memcmp(&ctx, &before, sizeof ctx) == 0);
    } else {
        /* vis-viva: the energy of every orbit with semi-major axis a is -mu / (2 a) */
        OGK_ASSERT_REL(ctx.energy_target_j_kg, -cfg.mu_m3_s2 / (2.0 * cfg.target_sma_m), OGK_TEST_TOL(1e-15, 4.5 * FLT_EPSILON), 0.0);
    }
}

/* req: OGK-NOG-016 */
static void test_each_config_bound_decides_alone(void **state)
{
    (void)state;
    init_with(offsetof(ogk_cutoff_config_t, target_sma_m), OGK_CUTOFF_R_MAX_M, OGK_OK);
    init_with(offsetof(ogk_cutoff_config_t, target_sma_m), OGK_TEST_NEXTAFTER(OGK_CUTOFF_R_MAX_M, DBL_MAX), OGK_E_CONFIG);
    init_with(offsetof(ogk_cutoff_config_t, arm_before_s), 0.0, OGK_OK);
    init_with(offsetof(ogk_cutoff_config_t, arm_before_s), OGK_CUTOFF_T_MAX_S, OGK_OK);
    init_with(offsetof(ogk_cutoff_config_t, arm_before_s), OGK_TEST_NEXTAFTER(OGK_CUTOFF_T_MAX_S, DBL_MAX), OGK_E_CONFIG);
    init_with(offsetof(ogk_cutoff_config_t, extend_max_s), 0.0, OGK_OK);
    init_with(offsetof(ogk_cutoff_config_t, extend_max_s), OGK_TEST_NEXTAFTER(0.0, -1.0), OGK_E_CONFIG);
    init_with(offsetof(ogk_cutoff_config_t, extend_max_s), OGK_CUTOFF_T_MAX_S, OGK_OK);
    init_with(offsetof(ogk_cutoff_config_t, extend_max_s), OGK_TEST_NEXTAFTER(OGK_CUTOFF_T_MAX_S, DBL_MAX), OGK_E_CONFIG);
    init_with(offsetof(ogk_cutoff_config_t, control_period_s), OGK_CUTOFF_T_MAX_S, OGK_OK);
    init_with(offsetof(ogk_cutoff_config_t, control_period_s), OGK_TEST_NEXTAFTER(OGK_CUTOFF_T_MAX_S, DBL_MAX), OGK_E_CONFIG);
}

/* nav with one field changed: step gives want; a rejection leaves the context unchanged and
 * reports the backstop t_predicted + extend_max_s (or T_MAX with no usable prediction). */
static void step_with(size_t offset, double value, double t_predicted, ogk_status want)
{
    const ogk_cutoff_config_t cfg = cutoff_config(0.02);
    ogk_cutoff_t ctx;
    ogk_cutoff_t before;
    ogk_nav_state_t nav = nav_at(100.0);
    ogk_cutoff_out_t out;
    *(ogk_real_t *)((char *)&nav + offset) = value;
    OGK_ASSERT_STATUS(ogk_cutoff_init(&ctx, &cfg), OGK_OK);
    before = ctx;
    OGK_ASSERT_STATUS(ogk_cutoff_step(&ctx, &nav, t_predicted, &out), want);
    if (want != OGK_OK) {
        const bool usable = isfinite(t_predicted) && (t_predicted >= 0.0) && (t_predicted <= OGK_CUTOFF_T_MAX_S);
        assert_true(memcmp(&ctx, &before, sizeof ctx) == 0);
        OGK_ASSERT_NEAR(out.t_cutoff_s, usable ? (t_predicted + cfg.extend_max_s) : OGK_CUTOFF_T_MAX_S, 0.0);
        assert_int_equal((int)out.flags, (int)OGK_CUTOFF_FLAG_BACKSTOP);
        OGK_ASSERT_NEAR(out.energy_j_kg, 0.0, 0.0);
    } else {
        const double v2 = (nav.v_r_mps * nav.v_r_mps) + (nav.v_t_mps * nav.v_t_mps) + (nav.v_n_mps * nav.v_n_mps);
        /* float: 4.5 eps, as 1e-15 is in double (the two terms are of the order of the result) */
        OGK_ASSERT_REL(out.energy_j_kg, (0.5 * v2) - (MU / nav.r_m), OGK_TEST_TOL(1e-15, 4.5 * FLT_EPSILON), 0.0);
    }
}

/* req: OGK-NOG-016 */
static void test_each_envelope_bound_decides_alone(void **state)
{
    const double over_v = OGK_TEST_NEXTAFTER(OGK_CUTOFF_V_MAX_MPS, DBL_MAX);
    (void)state;
    step_with(offsetof(ogk_nav_state_t, r_m), OGK_CUTOFF_R_MAX_M, 1000.0, OGK_OK);
    step_with(offsetof(ogk_nav_state_t, r_m), OGK_TEST_NEXTAFTER(OGK_CUTOFF_R_MAX_M, DBL_MAX), 1000.0, OGK_E_RANGE);
    step_with(offsetof(ogk_nav_state_t, v_t_mps), -OGK_CUTOFF_V_MAX_MPS, 1000.0, OGK_OK);
    step_with(offsetof(ogk_nav_state_t, v_t_mps), -over_v, 1000.0, OGK_E_RANGE);
    step_with(offsetof(ogk_nav_state_t, v_n_mps), OGK_CUTOFF_V_MAX_MPS, 1000.0, OGK_OK);
    step_with(offsetof(ogk_nav_state_t, v_n_mps), over_v, 1000.0, OGK_E_RANGE);
    step_with(offsetof(ogk_nav_state_t, t_s), 0.0, 1000.0, OGK_OK);
    step_with(offsetof(ogk_nav_state_t, t_s), OGK_TEST_NEXTAFTER(0.0, -1.0), 1000.0, OGK_E_RANGE);
    step_with(offsetof(ogk_nav_state_t, t_s), OGK_CUTOFF_T_MAX_S, OGK_CUTOFF_T_MAX_S, OGK_OK);
    step_with(offsetof(ogk_nav_state_t, t_s), OGK_TEST_NEXTAFTER(OGK_CUTOFF_T_MAX_S, DBL_MAX), OGK_CUTOFF_T_MAX_S, OGK_E_RANGE);
}

/* req: OGK-NOG-016 */
static void test_prediction_bounds(void **state)
{
    (void)state;
    /* a prediction beyond T_MAX: rejected, and the backstop is the one known before (T_MAX) */
    step_with(offsetof(ogk_nav_state_t, t_s), 100.0, OGK_TEST_NEXTAFTER(OGK_CUTOFF_T_MAX_S, DBL_MAX), OGK_E_RANGE);
    step_with(offsetof(ogk_nav_state_t, t_s), 100.0, OGK_CUTOFF_T_MAX_S, OGK_OK);
    /* a NaN state with a usable prediction: its backstop; with a NaN prediction: T_MAX */
    step_with(offsetof(ogk_nav_state_t, r_m), NAN, 500.0, OGK_E_NONFINITE);
    step_with(offsetof(ogk_nav_state_t, r_m), 7.0e6, NAN, OGK_E_NONFINITE);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_each_config_bound_decides_alone),
        cmocka_unit_test(test_each_envelope_bound_decides_alone),
        cmocka_unit_test(test_prediction_bounds),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
