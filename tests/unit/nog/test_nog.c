/* test_nog.c -- VTD-NOG flight law on a synthetic table whose every output
 * has a closed form: straight-line nominal, constant nominal costate with
 * thrust angle ALPHA0, and sparse gains.
 *
 * Both precisions (ogk_test.h); the table is written in the build's element
 * type (table_writer.h). Float tolerances are a few roundings of the
 * quantity's own scale: angles from the unit costate 4 eps (ANG_EPS), tau
 * (a quotient of times) 2 eps tau, and the state's errors the float
 * resolution of the nominal's magnitudes (r ~ 9e6 m: ulp 1 m; v_t ~ 1.1e4
 * m/s: ulp 1e-3 m/s; t ~ 100 s), 4 eps of each. The magnitudes near the
 * type's overflow (1e308, DBL_MAX) are float's (1e38, FLT_MAX). */
#include "ogk_test.h"

#include <float.h>
#include <string.h>

#include "ogk/nog.h"
#include "nog_fixture.h"
#include "table_writer.h"

#define GRID 5u
#define K_TF_VT 2.0      /* dt_f = K_TF_VT dv_t [s per m/s] */
#define K_L6_RATE 0.02   /* dlam_vn' = K_L6_RATE dv_n */
#define K_L4_T 0.05      /* dlam_vr = K_L4_T dt (time-state error) */
#define K_L1_R 1.0e-3    /* dlam_r = K_L1_R dr: not flown (eq. 27 uses lambda_v only) */
#define K_L1_RATE 2.0e-3 /* dlam_r' = K_L1_RATE dr */
#define PI 3.14159265358979323846
#define N_VALUES (GRID * (1u + OGK_NOG_ENTRY_LEN))
#define ANG_EPS (4.0 * FLT_EPSILON)     /* float: an angle from the unit costate */
#define R_SCALE 9.0e6                   /* [m] the nominal's largest radius */
#define V_SCALE 1.1e4                   /* [m/s] its largest speed */
#define TABLE_BYTES (OGK_TABLE_HEADER_SIZE + TW_REAL_BYTES * N_VALUES)

static const double tau_grid[GRID] = {0.0, 0.25, 0.5, 0.75, 1.0};

static uint8_t buf[TABLE_BYTES];
/* 8-byte aligned bytes for the in-place view (and 8 spare to misalign). */
static union {
    double align;
    uint8_t b[TABLE_BYTES + 8u];
} vbuf;
static ogk_nog_table_t table;
static ogk_nog_t nog;

static void build_table(double tf_last_node)
{
    const uint32_t dims[1] = {OGK_NOG_ENTRY_LEN};
    size_t k, i;
    memset(buf, 0, sizeof buf);
    tw_header(buf, OGK_NOG_TABLE_KIND, 1u, dims, GRID);
    for (k = 0u; k < GRID; ++k) {
        double row[OGK_NOG_ENTRY_LEN];
        memset(row, 0, sizeof row);
        nominal_state(tau_grid[k], &row[OGK_NOG_OFF_X]);
        for (i = 0u; i < 7u; ++i) {
            row[OGK_NOG_OFF_XDOT + i] = x_rate[i];
        }
        if (k == GRID - 1u) {
            row[OGK_NOG_OFF_XDOT + 6u] = tf_last_node;
        }
        /* Thrust along (sin a, cos a, 0) in r-t-n: lambda_v = -(sin a, cos a, 0). */
        row[OGK_NOG_OFF_LAM + 3u] = -sin(ALPHA0);
        row[OGK_NOG_OFF_LAM + 4u] = -cos(ALPHA0);
        if (k + 1u < GRID) { /* gains are zero (unused) at tau = 1 */
            row[OGK_NOG_OFF_GAIN + 5u * 7u + 5u] = K_L6_VN;   /* dlam_vn from dv_n */
            row[OGK_NOG_OFF_GAIN + 3u * 7u + 6u] = K_L4_T;    /* dlam_vr from dt */
            row[OGK_NOG_OFF_GAIN + 7u * 7u + 4u] = K_TF_VT;   /* dt_f from dv_t */
            row[OGK_NOG_OFF_NRATE + 5u * 7u + 5u] = K_L6_RATE;
            row[OGK_NOG_OFF_GAIN + 0u * 7u + 0u] = K_L1_R;    /* dlam_r from dr */
            row[OGK_NOG_OFF_NRATE + 0u * 7u + 0u] = K_L1_RATE;
        }
        tw_put_real(buf + OGK_TABLE_HEADER_SIZE + TW_REAL_BYTES * k, tau_grid[k]);
        for (i = 0u; i < OGK_NOG_ENTRY_LEN; ++i) {
            tw_put_real(buf + OGK_TABLE_HEADER_SIZE + TW_REAL_BYTES * (GRID + k * OGK_NOG_ENTRY_LEN + i),
                       row[i]);
        }
    }
    tw_seal(buf, N_VALUES);
}

static ogk_nog_config_t config(void)
{
    return nog_fixture_config(&table);
}

static ogk_nog_nav_t nav_at(ogk_real_t t, ogk_real_t tau)
{
    return nog_fixture_nav_at(t, tau);
}

static int setup(void **state)
{
    ogk_nog_config_t cfg;
    (void)state;
    build_table(TF_STAR);
    if (ogk_nog_table_load(&table, buf, TABLE_BYTES) != OGK_OK) {
        return -1;
    }
    cfg = config();
    return (ogk_nog_init(&nog, &cfg) == OGK_OK) ? 0 : -1;
}

/* req: OGK-NOG-001 */
static void test_table_load_and_rejections(void **state)
{
    (void)state;
    assert_int_equal(table.n_grid, GRID);
    OGK_ASSERT_NEAR(table.t_f_star_s, TF_STAR, 0.0);
    buf[OGK_TABLE_HEADER_SIZE + 100u] ^= 0x01u;
    OGK_ASSERT_STATUS(ogk_nog_table_load(&table, buf, TABLE_BYTES), OGK_E_TABLE_CRC);
    assert_int_equal(table.n_grid, 0u);
    build_table(TF_STAR * 1.01); /* t_f* of the last node disagrees */
    OGK_ASSERT_STATUS(ogk_nog_table_load(&table, buf, TABLE_BYTES), OGK_E_TABLE_TYPE);
    build_table(TF_STAR);
    tw_put_real(buf + OGK_TABLE_HEADER_SIZE + TW_REAL_BYTES * (GRID - 1u), 0.9); /* grid must end at 1 */
    tw_seal(buf, N_VALUES);
    OGK_ASSERT_STATUS(ogk_nog_table_load(&table, buf, TABLE_BYTES), OGK_E_TABLE_DIM);
    build_table(TF_STAR);
    OGK_ASSERT_STATUS(ogk_nog_table_load(&table, buf, TABLE_BYTES - TW_REAL_BYTES), OGK_E_TABLE_TRUNCATED);
    OGK_ASSERT_STATUS(ogk_nog_table_load(&table, buf, TABLE_BYTES), OGK_OK);
}

/* req: OGK-NOG-006 */
static void test_on_nominal_no_correction(void **state)
{
    ogk_nog_nav_t nav = nav_at(0.0, 0.0);
    ogk_nog_sample_t s;
    (void)state;
    OGK_ASSERT_STATUS(ogk_nog_sample(&nog, &nav, &s), OGK_OK);
    OGK_ASSERT_NEAR(s.tau_k, 0.0, 0.0);
    OGK_ASSERT_NEAR(s.t_f_s, TF_STAR, 1e-12);
    OGK_ASSERT_NEAR(s.tau_next, 2.0 / TF_STAR, OGK_TEST_TOL(1e-15, 2.0 * FLT_EPSILON * 0.02));
    OGK_ASSERT_NEAR(s.t_cutoff_s, TF_STAR, 1e-12);
    OGK_ASSERT_NEAR(s.alpha_rad, ALPHA0, OGK_TEST_TOL(1e-15, ANG_EPS));
    OGK_ASSERT_NEAR(s.beta_rad, 0.0, 0.0);
    assert_int_equal(s.flags, 0u);
}

/* req: OGK-NOG-005 */
static void test_flight_time_update_and_eq31(void **state)
{
    /* dv_t = +1.5 m/s at t = 0: dt_f = 3 s. Next sample at t = 2:
     * tau_1 = 2 / 103 (eq. 31), the time-state error dt = 2 - 100 tau_1. */
    ogk_nog_nav_t nav = nav_at(0.0, 0.0);
    ogk_nog_sample_t s;
    ogk_thrust_cmd_t c;
    const double tf0 = TF_STAR + K_TF_VT * 1.5;
    const double tau1 = 2.0 / tf0;
    const double dt1 = 2.0 - TF_STAR * tau1;
    double lam4, lam5;
    (void)state;
    nav.v_t_mps += 1.5;
    OGK_ASSERT_STATUS(ogk_nog_sample(&nog, &nav, &s), OGK_OK);
    OGK_ASSERT_NEAR(s.dt_f_s, 3.0, 1e-12);
    OGK_ASSERT_NEAR(s.t_cutoff_s, tf0, 1e-12);
    OGK_ASSERT_NEAR(s.dx[4], 1.5, 1e-9);
    nav = nav_at(2.0, tau1);
    OGK_ASSERT_STATUS(ogk_nog_sample(&nog, &nav, &s), OGK_OK);
    OGK_ASSERT_NEAR(s.tau_k, tau1, OGK_TEST_TOL(1e-15, 2.0 * FLT_EPSILON * 0.02));
    OGK_ASSERT_NEAR(s.dx[6], dt1, OGK_TEST_TOL(1e-12, 4.0 * FLT_EPSILON * 2.0)); /* t - t_f* tau at t = 2 */
    OGK_ASSERT_NEAR(s.dt_f_s, 0.0, 1e-10); /* on the nominal state again (v_t rounding) */
    /* The time-state error moves lambda_vr: alpha = atan2(-lam4, -lam5). */
    lam4 = -sin(ALPHA0) + K_L4_T * dt1;
    lam5 = -cos(ALPHA0);
    OGK_ASSERT_NEAR(s.alpha_rad, atan2(-lam4, -lam5), OGK_TEST_TOL(1e-12, ANG_EPS));
    OGK_ASSERT_STATUS(ogk_nog_thrust_cmd(&nog, 3.0, &c), OGK_OK);
    assert_true(c.t_s == 3.0);
    assert_int_equal(c.flags, OGK_THRUST_FLAG_ENGINE_ON);
    {
        ogk_real_t tau = -1.0;
        OGK_ASSERT_STATUS(ogk_nog_tau_at(&nog, 3.0, &tau), OGK_OK);
        OGK_ASSERT_NEAR(tau, tau1 + 1.0 / TF_STAR, OGK_TEST_TOL(1e-15, 2.0 * FLT_EPSILON * 0.03));
        OGK_ASSERT_STATUS(ogk_nog_tau_at(&nog, 1.0, &tau), OGK_E_RANGE);
        OGK_ASSERT_STATUS(ogk_nog_tau_at(&nog, NAN, &tau), OGK_E_NONFINITE);
        OGK_ASSERT_STATUS(ogk_nog_tau_at(&nog, 3.0, NULL), OGK_E_NULL);
    }
}

/* A radius error dr = 100 m: dx_k = [dr, 0, ...] (x*(0) is the first node,
 * exactly), [dlam_k; dt_f] = G dx_k moves lambda_r only (G row 0, K_L1_R dr)
 * with the rate N dx_k (K_L1_RATE dr), and the flown direction, -lambda_v of
 * eq. (27), stays the nominal one, as does t_f. */
/* req: OGK-NOG-007 */
static void test_radius_error_moves_lambda_r_only(void **state)
{
    ogk_nog_nav_t nav = nav_at(0.0, 0.0);
    ogk_nog_sample_t s;
    ogk_thrust_cmd_t c;
    size_t i;
    (void)state;
    nav.r_m += 100.0;
    OGK_ASSERT_STATUS(ogk_nog_sample(&nog, &nav, &s), OGK_OK);
    OGK_ASSERT_NEAR(s.dx[0], 100.0, 0.0);
    for (i = 1u; i < 7u; ++i) {
        OGK_ASSERT_NEAR(s.dx[i], 0.0, 0.0);
    }
    /* float: the gains are rounded to float (eps / 2), one product more */
    OGK_ASSERT_NEAR(nog.dlam_k[0], K_L1_R * 100.0, OGK_TEST_TOL(1e-15, 2.0 * FLT_EPSILON * 0.1));
    OGK_ASSERT_NEAR(nog.dlam_rate[0], K_L1_RATE * 100.0, OGK_TEST_TOL(1e-15, 2.0 * FLT_EPSILON * 0.2));
    for (i = 1u; i < 7u; ++i) {
        OGK_ASSERT_NEAR(nog.dlam_k[i], 0.0, 0.0);
        OGK_ASSERT_NEAR(nog.dlam_rate[i], 0.0, 0.0);
    }
    OGK_ASSERT_NEAR(s.t_f_s, TF_STAR, 0.0);
    OGK_ASSERT_NEAR(s.alpha_rad, ALPHA0, OGK_TEST_TOL(1e-15, ANG_EPS));
    OGK_ASSERT_NEAR(s.beta_rad, 0.0, 0.0);
    OGK_ASSERT_STATUS(ogk_nog_thrust_cmd(&nog, 1.0, &c), OGK_OK);
    OGK_ASSERT_NEAR(c.alpha_rad, ALPHA0, OGK_TEST_TOL(1e-15, ANG_EPS));
    OGK_ASSERT_NEAR(c.beta_rad, 0.0, 0.0);
}

/* On the nominal inside the later intervals: the cubic Hermite of a
 * straight line with its own slope is the line, x*(tau) = x0 + tau x', so
 * dx = 0 (to rounding of 7e6..9e6 m), no correction, t_f = t_f*. tau = 0.4
 * and 0.6 are interior points of [0.25, 0.5] and [0.5, 0.75]. */
/* req: OGK-NOG-006 */
static void test_on_nominal_in_every_interval(void **state)
{
    static const double taus[3] = {0.0, 0.4, 0.6};
    ogk_nog_sample_t s;
    size_t k;
    size_t i;
    (void)state;
    for (k = 0u; k < 3u; ++k) {
        ogk_nog_nav_t nav = nav_at(TF_STAR * taus[k], taus[k]);
        OGK_ASSERT_STATUS(ogk_nog_sample(&nog, &nav, &s), OGK_OK);
        /* float: dx is the float resolution of the nominal's magnitudes (4 eps
         * of r, of v_t the largest of the others); dt_f = K_TF_VT dv_t; alpha
         * moves with the time-state error (4 eps of t_f*) through K_L4_T */
        OGK_ASSERT_NEAR(s.tau_k, taus[k], OGK_TEST_TOL(1e-15, 2.0 * FLT_EPSILON * 0.6));
        OGK_ASSERT_NEAR(s.dx[0], 0.0, OGK_TEST_TOL(1e-8, 4.0 * FLT_EPSILON * R_SCALE));
        for (i = 1u; i < 7u; ++i) {
            OGK_ASSERT_NEAR(s.dx[i], 0.0, OGK_TEST_TOL(1e-11, 4.0 * FLT_EPSILON * V_SCALE));
        }
        OGK_ASSERT_NEAR(s.t_f_s, TF_STAR, OGK_TEST_TOL(1e-9, K_TF_VT * 4.0 * FLT_EPSILON * V_SCALE));
        OGK_ASSERT_NEAR(s.alpha_rad, ALPHA0, OGK_TEST_TOL(1e-12, ANG_EPS * (1.0 + K_L4_T * TF_STAR)));
        assert_int_equal(s.flags, 0u);
        assert_int_equal(nog.n_samples, k + 1u); /* good samples taken */
    }
}

/* req: OGK-NOG-007 */
static void test_out_of_plane_with_first_order_hold(void **state)
{
    /* dv_n = 2 m/s: dlam_vn = 0.02 at tau_k, rate 0.04 per unit tau; beta
     * = atan2(-lam6, |lam_inplane|) with |lam_inplane| = 1. */
    ogk_nog_nav_t nav = nav_at(0.0, 0.0);
    ogk_nog_sample_t s;
    ogk_thrust_cmd_t c;
    const double t = 1.5;
    const double tau = t / TF_STAR;
    const double lam6 = K_L6_VN * 2.0 + K_L6_RATE * 2.0 * tau;
    (void)state;
    nav.v_n_mps = 2.0;
    OGK_ASSERT_STATUS(ogk_nog_sample(&nog, &nav, &s), OGK_OK);
    OGK_ASSERT_NEAR(s.beta_rad, atan2(-K_L6_VN * 2.0, 1.0), OGK_TEST_TOL(1e-14, ANG_EPS));
    OGK_ASSERT_STATUS(ogk_nog_thrust_cmd(&nog, t, &c), OGK_OK);
    OGK_ASSERT_NEAR(c.beta_rad, atan2(-lam6, 1.0), OGK_TEST_TOL(1e-14, ANG_EPS));
    OGK_ASSERT_NEAR(c.alpha_rad, ALPHA0, OGK_TEST_TOL(1e-14, ANG_EPS));
    /* the one command of every law (ogk/types.h): r-t-n, the primer vector -lambda_v / |lambda_v|
     * = (sin ALPHA0, cos ALPHA0, -lam6) / sqrt(1 + lam6^2) as u, full thrust */
    assert_int_equal((int)c.frame, (int)OGK_FRAME_RTN);
    OGK_ASSERT_NEAR(c.u[0], sin(ALPHA0) / sqrt(1.0 + (lam6 * lam6)), OGK_TEST_TOL(1e-15, ANG_EPS));
    OGK_ASSERT_NEAR(c.u[1], cos(ALPHA0) / sqrt(1.0 + (lam6 * lam6)), OGK_TEST_TOL(1e-15, ANG_EPS));
    OGK_ASSERT_NEAR(c.u[2], -lam6 / sqrt(1.0 + (lam6 * lam6)), OGK_TEST_TOL(1e-15, ANG_EPS));
    OGK_ASSERT_NEAR(c.throttle, 1.0, 0.0);
    OGK_ASSERT_NEAR(c.t_s, t, 0.0);
    assert_int_equal(c.flags, OGK_THRUST_FLAG_ENGINE_ON);
}

/* req: OGK-NOG-009 */
static void test_end_game_limits(void **state)
{
    ogk_nog_nav_t nav = nav_at(0.0, 0.0);
    ogk_nog_sample_t s;
    (void)state;
    nav.v_t_mps += 50.0; /* dt_f = 100 s, clipped to 10 s */
    nav.v_n_mps = 1000.0; /* dlam_vn = 10: about 84 deg, clipped to 0.5 rad */
    OGK_ASSERT_STATUS(ogk_nog_sample(&nog, &nav, &s), OGK_OK);
    OGK_ASSERT_NEAR(s.dt_f_s, 10.0, 0.0);
    assert_true((s.flags & OGK_NOG_FLAG_LIMITED) != 0u);
    OGK_ASSERT_NEAR(fabs(s.beta_rad), 0.5, OGK_TEST_TOL(1e-9, ANG_EPS));
}

/* |dt_f| at the bound is not clipped: dv_t = 5 m/s gives dt_f = 10 s =
 * dtf_max exactly (2 x 5, both exact), flown as is and not flagged LIMITED;
 * one ulp more of dv_t is clipped to 10 s and flagged. */
/* req: OGK-NOG-009 */
static void test_dt_f_at_the_bound_is_not_limited(void **state)
{
    ogk_nog_config_t cfg = config();
    ogk_nog_nav_t nav = nav_at(0.0, 0.0);
    ogk_nog_sample_t s;
    (void)state;
    nav.v_t_mps += 5.0;
    OGK_ASSERT_STATUS(ogk_nog_sample(&nog, &nav, &s), OGK_OK);
    OGK_ASSERT_NEAR(s.dt_f_s, 10.0, 0.0);
    assert_int_equal(s.flags & OGK_NOG_FLAG_LIMITED, 0u);
    OGK_ASSERT_STATUS(ogk_nog_init(&nog, &cfg), OGK_OK);
    nav.v_t_mps = OGK_TEST_NEXTAFTER(nav.v_t_mps, 1.0e4);
    OGK_ASSERT_STATUS(ogk_nog_sample(&nog, &nav, &s), OGK_OK);
    OGK_ASSERT_NEAR(s.dt_f_s, 10.0, 0.0);
    assert_true((s.flags & OGK_NOG_FLAG_LIMITED) != 0u);
}

/* du_max = pi admits every direction: a correction that reverses the thrust
 * exactly (dlam_v = -2 lambda*_v, from a gain on dphi = 1 rad, so lambda_v
 * = -lambda*_v) flies unscaled and unflagged, alpha = ALPHA0 - pi. */
/* req: OGK-NOG-009 */
static void test_du_max_pi_admits_a_reversal(void **state)
{
    ogk_nog_config_t cfg = config();
    ogk_nog_nav_t nav = nav_at(0.0, 0.0);
    ogk_nog_sample_t s;
    const size_t row0 = OGK_TABLE_HEADER_SIZE + TW_REAL_BYTES * GRID;
    (void)state;
    tw_put_real(buf + row0 + TW_REAL_BYTES * (OGK_NOG_OFF_GAIN + 3u * 7u + 2u), 2.0 * sin(ALPHA0));
    tw_put_real(buf + row0 + TW_REAL_BYTES * (OGK_NOG_OFF_GAIN + 4u * 7u + 2u), 2.0 * cos(ALPHA0));
    tw_seal(buf, N_VALUES);
    OGK_ASSERT_STATUS(ogk_nog_table_load(&table, buf, TABLE_BYTES), OGK_OK);
    cfg.du_max_rad = PI;
    OGK_ASSERT_STATUS(ogk_nog_init(&nog, &cfg), OGK_OK);
    nav.phi_rad = 1.0;
    OGK_ASSERT_STATUS(ogk_nog_sample(&nog, &nav, &s), OGK_OK);
    assert_true((s.flags & OGK_NOG_FLAG_LIMITED) == 0u);
    OGK_ASSERT_NEAR(s.alpha_rad, ALPHA0 - PI, OGK_TEST_TOL(1e-15, ANG_EPS * PI)); /* an angle near pi */
    OGK_ASSERT_NEAR(s.beta_rad, 0.0, 0.0);
    /* the same correction under du_max = pi / 2 is scaled to that angle */
    cfg.du_max_rad = 0.5 * PI;
    OGK_ASSERT_STATUS(ogk_nog_init(&nog, &cfg), OGK_OK);
    OGK_ASSERT_STATUS(ogk_nog_sample(&nog, &nav, &s), OGK_OK);
    assert_true((s.flags & OGK_NOG_FLAG_LIMITED) != 0u);
}

/* req: OGK-NOG-008 OGK-NOG-009 */
static void test_freeze_and_termination(void **state)
{
    /* Last gain node at tau = 0.75: a sample at tau = 0.8 is frozen. */
    ogk_nog_nav_t nav = nav_at(0.0, 0.0);
    ogk_nog_sample_t s;
    ogk_thrust_cmd_t c;
    (void)state;
    nav.v_n_mps = 2.0;
    OGK_ASSERT_STATUS(ogk_nog_sample(&nog, &nav, &s), OGK_OK);
    nav = nav_at(80.0, 0.8);
    nav.v_n_mps = 50.0; /* would be a large correction: ignored when frozen */
    OGK_ASSERT_STATUS(ogk_nog_sample(&nog, &nav, &s), OGK_OK);
    assert_true((s.flags & OGK_NOG_FLAG_FROZEN) != 0u);
    /* dlam held from the first sample's first-order hold at tau = 0.8. */
    OGK_ASSERT_NEAR(s.beta_rad, atan2(-(K_L6_VN * 2.0 + K_L6_RATE * 2.0 * 0.8), 1.0), OGK_TEST_TOL(1e-12, ANG_EPS));
    nav = nav_at(98.5, 0.985);
    OGK_ASSERT_STATUS(ogk_nog_sample(&nog, &nav, &s), OGK_OK);
    assert_true((s.flags & OGK_NOG_FLAG_TERMINATING) != 0u);
    OGK_ASSERT_NEAR(s.t_cutoff_s, 100.0, 1e-9);
    OGK_ASSERT_STATUS(ogk_nog_thrust_cmd(&nog, 100.5, &c), OGK_OK);
    assert_true((c.law_flags & OGK_NOG_FLAG_CUTOFF) != 0u);
    assert_true((c.flags & OGK_THRUST_FLAG_ENGINE_ON) == 0u); /* engine off */
    OGK_ASSERT_NEAR(c.throttle, 0.0, 0.0);
    OGK_ASSERT_NEAR(c.u[0], cos(c.beta_rad) * sin(c.alpha_rad), OGK_TEST_TOL(1e-16, ANG_EPS)); /* still a direction */
    OGK_ASSERT_NEAR(c.u[2], sin(c.beta_rad), OGK_TEST_TOL(1e-16, ANG_EPS));
    {
        ogk_real_t tau = -1.0;
        OGK_ASSERT_STATUS(ogk_nog_tau_at(&nog, 100.5, &tau), OGK_OK);
        OGK_ASSERT_NEAR(tau, 1.0, 0.0);
    }
    /* A sample past the cut-off (tau > 1) is rejected with the safe command. */
    nav = nav_at(101.0, 1.0);
    OGK_ASSERT_STATUS(ogk_nog_sample(&nog, &nav, &s), OGK_E_RANGE);
    assert_true((s.flags & OGK_NOG_FLAG_SAFE) != 0u && (s.flags & OGK_NOG_FLAG_CUTOFF) != 0u);
    OGK_ASSERT_NEAR(s.beta_rad, atan2(-(K_L6_VN * 2.0 + K_L6_RATE * 2.0 * 0.8), 1.0), OGK_TEST_TOL(1e-12, ANG_EPS));
}

/* The time bound of the envelope, t_s <= 2 t_f* + dtf_max = 210 s, is
 * closed: at 210 s the time is usable but past the cut-off, so the sample is
 * shown at tau = 210 / 100 = 2.1 (CUTOFF), not committed; one ulp later it is
 * outside the envelope and nothing moves (tau_k = 0 of the first sample). */
/* req: OGK-NOG-010 */
static void test_sample_at_the_envelope_time_bound(void **state)
{
    ogk_nog_nav_t nav = nav_at(0.0, 0.0);
    ogk_nog_sample_t s;
    const double t_max = 2.0 * TF_STAR + 10.0;
    (void)state;
    OGK_ASSERT_STATUS(ogk_nog_sample(&nog, &nav, &s), OGK_OK);
    nav = nav_at(t_max, 1.0);
    OGK_ASSERT_STATUS(ogk_nog_sample(&nog, &nav, &s), OGK_E_RANGE);
    OGK_ASSERT_NEAR(s.tau_k, t_max / TF_STAR, OGK_TEST_TOL(1e-15, 2.0 * FLT_EPSILON * 2.1));
    assert_true((s.flags & OGK_NOG_FLAG_SAFE) != 0u && (s.flags & OGK_NOG_FLAG_CUTOFF) != 0u);
    OGK_ASSERT_NEAR(nog.tau_k, 0.0, 0.0); /* shown, not committed */
    assert_int_equal(nog.n_samples, 1u);
    nav.t_s = OGK_TEST_NEXTAFTER(t_max, 1.0e3);
    OGK_ASSERT_STATUS(ogk_nog_sample(&nog, &nav, &s), OGK_E_RANGE);
    OGK_ASSERT_NEAR(s.tau_k, 0.0, 0.0);
    assert_true((s.flags & OGK_NOG_FLAG_SAFE) != 0u && (s.flags & OGK_NOG_FLAG_CUTOFF) == 0u);
}

/* req: OGK-NOG-010 OGK-NOG-012 */
static void test_bad_navigation_gives_safe_command(void **state)
{
    ogk_nog_nav_t nav = nav_at(0.0, 0.0);
    ogk_nog_sample_t s;
    ogk_thrust_cmd_t c;
    (void)state;
    nav.v_t_mps += 1.5; /* dt_f = 3 s in force */
    OGK_ASSERT_STATUS(ogk_nog_sample(&nog, &nav, &s), OGK_OK);
    nav = nav_at(2.0, 0.02);
    nav.v_r_mps = NAN;
    OGK_ASSERT_STATUS(ogk_nog_sample(&nog, &nav, &s), OGK_E_NONFINITE);
    assert_true((s.flags & OGK_NOG_FLAG_SAFE) != 0u);
    OGK_ASSERT_NEAR(s.t_f_s, 103.0, 1e-12);            /* last valid correction held */
    OGK_ASSERT_NEAR(s.tau_k, 2.0 / 103.0, OGK_TEST_TOL(1e-15, 2.0 * FLT_EPSILON * 0.02)); /* tau still advanced */
    OGK_ASSERT_NEAR(s.alpha_rad, ALPHA0, OGK_TEST_TOL(1e-12, ANG_EPS));
    nav = nav_at(1.0, 0.01); /* time going backwards */
    OGK_ASSERT_STATUS(ogk_nog_sample(&nog, &nav, &s), OGK_E_RANGE);
    assert_true((s.flags & OGK_NOG_FLAG_SAFE) != 0u);
    OGK_ASSERT_STATUS(ogk_nog_thrust_cmd(&nog, 1.0, &c), OGK_E_RANGE);
    assert_true((c.law_flags & OGK_NOG_FLAG_SAFE) != 0u);
    assert_true((c.flags & OGK_THRUST_FLAG_SAFE) != 0u);
    OGK_ASSERT_STATUS(ogk_nog_thrust_cmd(&nog, NAN, &c), OGK_E_NONFINITE);
    /* The context is still usable: a good sample goes through. */
    nav = nav_at(4.0, 4.0 / 103.0);
    OGK_ASSERT_STATUS(ogk_nog_sample(&nog, &nav, &s), OGK_OK);
    assert_true((s.flags & OGK_NOG_FLAG_SAFE) == 0u);
}

/* req: OGK-NOG-004 */
static void test_init_errors(void **state)
{
    ogk_nog_config_t cfg = config();
    ogk_nog_t ctx;
    ogk_nog_table_t empty;
    ogk_nog_nav_t nav = nav_at(0.0, 0.0);
    ogk_nog_sample_t s;
    (void)state;
    OGK_ASSERT_STATUS(ogk_nog_init(NULL, &cfg), OGK_E_NULL);
    cfg.sample_interval_s = 0.0;
    OGK_ASSERT_STATUS(ogk_nog_init(&ctx, &cfg), OGK_E_CONFIG);
    OGK_ASSERT_STATUS(ogk_nog_sample(&ctx, &nav, &s), OGK_E_NOT_INIT);
    cfg = config();
    cfg.dtf_max_s = 0.6 * TF_STAR;
    OGK_ASSERT_STATUS(ogk_nog_init(&ctx, &cfg), OGK_E_CONFIG);
    cfg = config();
    cfg.du_max_rad = NAN;
    OGK_ASSERT_STATUS(ogk_nog_init(&ctx, &cfg), OGK_E_CONFIG);
    cfg = config();
    cfg.tau_freeze = 1.0;
    OGK_ASSERT_STATUS(ogk_nog_init(&ctx, &cfg), OGK_E_CONFIG);
    memset(&empty, 0, sizeof empty);
    cfg = config();
    cfg.table = &empty;
    OGK_ASSERT_STATUS(ogk_nog_init(&ctx, &cfg), OGK_E_NOT_INIT);
    cfg.table = NULL;
    OGK_ASSERT_STATUS(ogk_nog_init(&ctx, &cfg), OGK_E_NULL);
}

/* The documented ranges of ogk_nog_config_t, at their closed ends and one
 * ulp outside: Delta t_S in (0, t_f*], dt_f max in (0, t_f* / 2], du max in
 * (0, pi], tau_freeze in [0, 1). */
/* req: OGK-NOG-004 */
static void test_config_range_boundaries(void **state)
{
    ogk_nog_config_t cfg = config();
    ogk_nog_t ctx;
    (void)state;
    cfg.sample_interval_s = TF_STAR;
    OGK_ASSERT_STATUS(ogk_nog_init(&ctx, &cfg), OGK_OK);
    cfg.sample_interval_s = OGK_TEST_NEXTAFTER(TF_STAR, 2.0 * TF_STAR);
    OGK_ASSERT_STATUS(ogk_nog_init(&ctx, &cfg), OGK_E_CONFIG);
    cfg = config();
    cfg.dtf_max_s = 0.5 * TF_STAR;
    OGK_ASSERT_STATUS(ogk_nog_init(&ctx, &cfg), OGK_OK);
    cfg.dtf_max_s = OGK_TEST_NEXTAFTER(0.5 * TF_STAR, TF_STAR);
    OGK_ASSERT_STATUS(ogk_nog_init(&ctx, &cfg), OGK_E_CONFIG);
    cfg = config();
    cfg.du_max_rad = PI;
    OGK_ASSERT_STATUS(ogk_nog_init(&ctx, &cfg), OGK_OK);
    cfg.du_max_rad = OGK_TEST_NEXTAFTER(PI, 4.0);
    OGK_ASSERT_STATUS(ogk_nog_init(&ctx, &cfg), OGK_E_CONFIG);
    cfg = config();
    cfg.tau_freeze = OGK_TEST_NEXTAFTER(1.0, 0.0);
    OGK_ASSERT_STATUS(ogk_nog_init(&ctx, &cfg), OGK_OK);
    cfg.tau_freeze = -0.0;
    OGK_ASSERT_STATUS(ogk_nog_init(&ctx, &cfg), OGK_OK);
    cfg.tau_freeze = -OGK_REAL_MIN;
    OGK_ASSERT_STATUS(ogk_nog_init(&ctx, &cfg), OGK_E_CONFIG);
}

/* req: OGK-NOG-004 */
static void test_config_default(void **state)
{
    ogk_nog_config_t cfg;
    ogk_nog_t ctx;
    (void)state;
    OGK_ASSERT_STATUS(ogk_nog_config_default(NULL), OGK_E_NULL);
    memset(&cfg, 0xA5, sizeof cfg);
    OGK_ASSERT_STATUS(ogk_nog_config_default(&cfg), OGK_OK);
    assert_null(cfg.table);
    assert_null(cfg.view);
    OGK_ASSERT_NEAR(cfg.sample_interval_s, 2.0, 0.0);
    OGK_ASSERT_NEAR(cfg.dtf_max_s, 40.0, 0.0);
    OGK_ASSERT_NEAR(cfg.du_max_rad, 1.0471975511965976, OGK_TEST_TOL(1e-16, FLT_EPSILON)); /* float: 1 ulp of pi/3 */
    OGK_ASSERT_NEAR(cfg.tau_freeze, 0.0, 0.0);
    OGK_ASSERT_STATUS(ogk_nog_init(&ctx, &cfg), OGK_E_NULL); /* no table bound */
    cfg.table = &table;
    OGK_ASSERT_STATUS(ogk_nog_init(&ctx, &cfg), OGK_OK);
    assert_true(ctx.init_marker == OGK_NOG_INIT_MARKER);
}

/* Two contexts fed the same samples give bit-identical outputs. */
static void fly_both(ogk_nog_t *a, ogk_nog_t *b)
{
    static const double times[4] = {0.0, 2.0, 4.0, 80.0};
    size_t i;
    for (i = 0u; i < 4u; ++i) {
        ogk_nog_nav_t nav = nav_at(times[i], times[i] / TF_STAR);
        ogk_nog_sample_t sa, sb;
        ogk_thrust_cmd_t ca, cb;
        nav.v_t_mps += 1.5;
        nav.v_n_mps = 2.0;
        OGK_ASSERT_STATUS(ogk_nog_sample(a, &nav, &sa), ogk_nog_sample(b, &nav, &sb));
        assert_true(memcmp(&sa, &sb, sizeof sa) == 0);
        OGK_ASSERT_STATUS(ogk_nog_thrust_cmd(a, times[i] + 1.0, &ca),
                          ogk_nog_thrust_cmd(b, times[i] + 1.0, &cb));
        assert_true(memcmp(&ca, &cb, sizeof ca) == 0);
    }
}

/* req: OGK-NOG-002 OGK-CORE-023 */
static void test_table_view_in_place(void **state)
{
    ogk_nog_table_view_t view;
    ogk_nog_config_t cfg = config();
    ogk_nog_t ctx;
    (void)state;
    memcpy(vbuf.b, buf, TABLE_BYTES);
    if (OGK_TEST_BIG_ENDIAN) {
        /* The valid image cannot be read in place here: the view is left
         * unusable, and the copying loader decodes the same bytes. */
        memset(&view, 0, sizeof view);
        OGK_ASSERT_STATUS(ogk_nog_table_view(&view, vbuf.b, TABLE_BYTES), OGK_E_BYTE_ORDER);
        assert_int_equal(view.n_grid, 0u);
        assert_true(view.init_marker == 0u && view.tau == NULL && view.generation == 1u);
        cfg.table = NULL;
        cfg.view = &view;
        OGK_ASSERT_STATUS(ogk_nog_init(&ctx, &cfg), OGK_E_NOT_INIT);
        OGK_ASSERT_STATUS(ogk_nog_table_load(&table, vbuf.b, TABLE_BYTES), OGK_OK);
        assert_int_equal(table.n_grid, GRID);
        OGK_ASSERT_NEAR(table.t_f_star_s, TF_STAR, 0.0);
        cfg.table = &table;
        cfg.view = NULL;
        OGK_ASSERT_STATUS(ogk_nog_init(&nog, &cfg), OGK_OK); /* re-bound after the reload */
        OGK_ASSERT_STATUS(ogk_nog_init(&ctx, &cfg), OGK_OK);
        fly_both(&nog, &ctx);
        return;
    }
    OGK_ASSERT_STATUS(ogk_nog_table_view(&view, vbuf.b, TABLE_BYTES), OGK_OK);
    assert_int_equal(view.n_grid, GRID);
    assert_true(view.init_marker == OGK_NOG_VIEW_MARKER);
    OGK_ASSERT_NEAR(view.t_f_star_s, TF_STAR, 0.0);
    /* in place: no copy, the pointers are into the bytes */
    assert_true((const void *)view.tau == (const void *)&vbuf.b[OGK_TABLE_HEADER_SIZE]);
    assert_true((const void *)view.entry ==
                (const void *)&vbuf.b[OGK_TABLE_HEADER_SIZE + TW_REAL_BYTES * GRID]);
    cfg.table = NULL;
    cfg.view = &view;
    OGK_ASSERT_STATUS(ogk_nog_init(&ctx, &cfg), OGK_OK);
    fly_both(&nog, &ctx); /* RAM table and view: the same numbers */
    cfg.table = &table;
    OGK_ASSERT_STATUS(ogk_nog_init(&ctx, &cfg), OGK_E_CONFIG); /* both bound */
}

/* req: OGK-NOG-002 OGK-CORE-023 */
static void test_table_view_rejections(void **state)
{
    ogk_nog_table_view_t view;
    ogk_nog_config_t cfg = config();
    ogk_nog_t ctx;
    (void)state;
    OGK_ASSERT_STATUS(ogk_nog_table_view(NULL, vbuf.b, TABLE_BYTES), OGK_E_NULL);
    OGK_ASSERT_STATUS(ogk_nog_table_view(&view, NULL, TABLE_BYTES), OGK_E_NULL);
    /* misaligned copy of a good table */
    memcpy(&vbuf.b[1], buf, TABLE_BYTES);
    OGK_ASSERT_STATUS(ogk_nog_table_view(&view, &vbuf.b[1], TABLE_BYTES), OGK_E_ALIGN);
    assert_int_equal(view.n_grid, 0u);
    assert_true(view.init_marker == 0u);
    cfg.table = NULL;
    cfg.view = &view; /* an unvalidated view cannot be flown */
    OGK_ASSERT_STATUS(ogk_nog_init(&ctx, &cfg), OGK_E_NOT_INIT);
    /* half the element's size: 4 in the double build, 2 in the float one */
    memcpy(&vbuf.b[TW_REAL_BYTES / 2u], buf, TABLE_BYTES);
    OGK_ASSERT_STATUS(ogk_nog_table_view(&view, &vbuf.b[TW_REAL_BYTES / 2u], TABLE_BYTES), OGK_E_ALIGN);
    /* corrupted payload, header, magic; wrong length; then the same bytes, good */
    memcpy(vbuf.b, buf, TABLE_BYTES);
    vbuf.b[OGK_TABLE_HEADER_SIZE + 100u] ^= 0x01u;
    OGK_ASSERT_STATUS(ogk_nog_table_view(&view, vbuf.b, TABLE_BYTES), OGK_E_TABLE_CRC);
    assert_int_equal(view.n_grid, 0u);
    memcpy(vbuf.b, buf, TABLE_BYTES);
    vbuf.b[20] ^= 0x40u;
    OGK_ASSERT_STATUS(ogk_nog_table_view(&view, vbuf.b, TABLE_BYTES), OGK_E_TABLE_CRC);
    memcpy(vbuf.b, buf, TABLE_BYTES);
    vbuf.b[0] = (uint8_t)'X';
    OGK_ASSERT_STATUS(ogk_nog_table_view(&view, vbuf.b, TABLE_BYTES), OGK_E_TABLE_MAGIC);
    memcpy(vbuf.b, buf, TABLE_BYTES);
    OGK_ASSERT_STATUS(ogk_nog_table_view(&view, vbuf.b, TABLE_BYTES - TW_REAL_BYTES),
                      OGK_E_TABLE_TRUNCATED);
    OGK_ASSERT_STATUS(ogk_nog_table_view(&view, vbuf.b, TABLE_BYTES + TW_REAL_BYTES), OGK_E_TABLE_SIZE);
    /* content checks shared with the loader (read in place: after the byte-order check) */
    build_table(TF_STAR * 1.01);
    memcpy(vbuf.b, buf, TABLE_BYTES);
    OGK_ASSERT_STATUS(ogk_nog_table_view(&view, vbuf.b, TABLE_BYTES),
                      OGK_TEST_BIG_ENDIAN ? OGK_E_BYTE_ORDER : OGK_E_TABLE_TYPE);
    build_table(TF_STAR);
    memcpy(vbuf.b, buf, TABLE_BYTES);
    OGK_ASSERT_STATUS(ogk_nog_table_view(&view, vbuf.b, TABLE_BYTES), OGK_TEST_VIEW_OK);
    OGK_ASSERT_STATUS(ogk_nog_init(&ctx, &cfg), OGK_TEST_BIG_ENDIAN ? OGK_E_NOT_INIT : OGK_OK);
}

/* req: OGK-NOG-004 */
static void test_reset(void **state)
{
    ogk_nog_config_t cfg = config();
    ogk_nog_t fresh;
    ogk_nog_t zero;
    (void)state;
    OGK_ASSERT_STATUS(ogk_nog_reset(NULL), OGK_E_NULL);
    memset(&zero, 0, sizeof zero);
    OGK_ASSERT_STATUS(ogk_nog_reset(&zero), OGK_E_NOT_INIT);
    OGK_ASSERT_STATUS(ogk_nog_init(&fresh, &cfg), OGK_OK);
    fly_both(&nog, &fresh);                 /* both now hold a correction */
    OGK_ASSERT_STATUS(ogk_nog_reset(&nog), OGK_OK);
    OGK_ASSERT_STATUS(ogk_nog_init(&fresh, &cfg), OGK_OK);
    assert_true(memcmp(&nog, &fresh, sizeof nog) == 0); /* the just-initialised state */
    fly_both(&nog, &fresh);
}


/* Every double of a sample is finite. */
static int sample_is_finite(const ogk_nog_sample_t *s)
{
    size_t i;
    int ok = isfinite(s->tau_k) && isfinite(s->tau_next) && isfinite(s->t_f_s) &&
             isfinite(s->dt_f_s) && isfinite(s->t_cutoff_s) && isfinite(s->alpha_rad) &&
             isfinite(s->beta_rad);
    for (i = 0u; i < 7u; ++i) {
        ok = ok && isfinite(s->dx[i]);
    }
    return ok;
}

/* After a reload of its table, good or failed, a context answers
 * OGK_E_TABLE_STALE with the last good sample's angles and never reads the
 * (empty) grid; re-init makes it usable again. */
static void check_stale(ogk_nog_t *ctx, double held_beta)
{
    ogk_nog_nav_t nav = nav_at(30.0, 0.3);
    ogk_nog_sample_t s;
    ogk_thrust_cmd_t c;
    ogk_real_t tau = -1.0;
    OGK_ASSERT_STATUS(ogk_nog_sample(ctx, &nav, &s), OGK_E_TABLE_STALE);
    assert_true(sample_is_finite(&s));
    assert_true((s.flags & OGK_NOG_FLAG_SAFE) != 0u);
    OGK_ASSERT_NEAR(s.alpha_rad, ALPHA0, OGK_TEST_TOL(1e-12, ANG_EPS));
    OGK_ASSERT_NEAR(s.beta_rad, held_beta, 0.0);
    OGK_ASSERT_STATUS(ogk_nog_thrust_cmd(ctx, 31.0, &c), OGK_E_TABLE_STALE);
    assert_true(isfinite(c.alpha_rad) && isfinite(c.beta_rad));
    OGK_ASSERT_NEAR(c.beta_rad, held_beta, 0.0);
    assert_true((c.flags & OGK_THRUST_FLAG_SAFE) != 0u);
    assert_true((c.flags & OGK_THRUST_FLAG_ENGINE_ON) != 0u); /* before the predicted cut-off */
    OGK_ASSERT_STATUS(ogk_nog_thrust_cmd(ctx, 500.0, &c), OGK_E_TABLE_STALE);
    assert_true((c.flags & OGK_THRUST_FLAG_ENGINE_ON) == 0u); /* and off after it */
    OGK_ASSERT_STATUS(ogk_nog_tau_at(ctx, 31.0, &tau), OGK_E_TABLE_STALE);
    OGK_ASSERT_STATUS(ogk_nog_reset(ctx), OGK_E_TABLE_STALE);
}

/* req: OGK-NOG-003 */
static void test_stale_table_after_failed_reload(void **state)
{
    ogk_nog_config_t cfg = config();
    ogk_nog_nav_t nav = nav_at(0.0, 0.0);
    ogk_nog_sample_t s;
    double beta;
    (void)state;
    nav.v_n_mps = 2.0;
    OGK_ASSERT_STATUS(ogk_nog_sample(&nog, &nav, &s), OGK_OK);
    beta = s.beta_rad;
    buf[OGK_TABLE_HEADER_SIZE + 100u] ^= 0x01u; /* the uplinked copy is corrupt */
    OGK_ASSERT_STATUS(ogk_nog_table_load(&table, buf, TABLE_BYTES), OGK_E_TABLE_CRC);
    assert_int_equal(table.n_grid, 0u);
    check_stale(&nog, beta);
    /* A good reload does not revive the old binding either: re-init does. */
    buf[OGK_TABLE_HEADER_SIZE + 100u] ^= 0x01u;
    OGK_ASSERT_STATUS(ogk_nog_table_load(&table, buf, TABLE_BYTES), OGK_OK);
    check_stale(&nog, beta);
    OGK_ASSERT_STATUS(ogk_nog_init(&nog, &cfg), OGK_OK);
    nav = nav_at(30.0, 0.3);
    OGK_ASSERT_STATUS(ogk_nog_sample(&nog, &nav, &s), OGK_OK);
}

/* req: OGK-CORE-028 OGK-NOG-001 OGK-NOG-002 */
/* An uplinked table made for the other precision (F32: a kernel built with
 * OGK_REAL_SINGLE=1; F64 for the float build) is refused by this kernel with
 * OGK_E_TABLE_TYPE, by the loader (table left empty) and by the in-place view
 * (view zeroed); the bound context answers stale, not broken, and flies again
 * once the build's own table is loaded and the context initialised. */
static void test_other_precision_table_refused(void **state)
{
    static union {
        double align;
        uint8_t b[OGK_TABLE_HEADER_SIZE + TW_OTHER_BYTES * N_VALUES];
    } f32;
    ogk_nog_table_view_t view;
    ogk_nog_config_t cfg = config();
    ogk_nog_nav_t nav = nav_at(0.0, 0.0);
    ogk_nog_sample_t s;
    (void)state;
    tw_to_other(buf, f32.b, N_VALUES);
    OGK_ASSERT_STATUS(ogk_nog_table_load(&table, f32.b, sizeof f32.b), OGK_E_TABLE_TYPE);
    assert_int_equal(table.n_grid, 0u);
    OGK_ASSERT_STATUS(ogk_nog_sample(&nog, &nav, &s), OGK_E_TABLE_STALE);
    memset(&view, 0, sizeof view);
    OGK_ASSERT_STATUS(ogk_nog_table_view(&view, f32.b, sizeof f32.b), OGK_E_TABLE_TYPE);
    assert_true(view.n_grid == 0u && view.tau == NULL && view.entry == NULL);
    assert_true(view.init_marker == 0u && view.generation == 1u);
    OGK_ASSERT_STATUS(ogk_nog_table_load(&table, buf, TABLE_BYTES), OGK_OK);
    assert_int_equal(table.n_grid, GRID);
    OGK_ASSERT_STATUS(ogk_nog_init(&nog, &cfg), OGK_OK);
    OGK_ASSERT_STATUS(ogk_nog_sample(&nog, &nav, &s), OGK_OK);
    OGK_ASSERT_NEAR(s.t_f_s, TF_STAR, 1e-12);
}

/* req: OGK-NOG-003 */
static void test_stale_view_after_failed_reload(void **state)
{
    ogk_nog_table_view_t view;
    ogk_nog_config_t cfg = config();
    ogk_nog_t ctx;
    ogk_nog_nav_t nav = nav_at(0.0, 0.0);
    ogk_nog_sample_t s;
    double beta;
    (void)state;
    memset(&view, 0, sizeof view);
    memcpy(vbuf.b, buf, TABLE_BYTES);
    OGK_ASSERT_STATUS(ogk_nog_table_view(&view, vbuf.b, TABLE_BYTES), OGK_TEST_VIEW_OK);
    if (OGK_TEST_BIG_ENDIAN) {
        return; /* no in-place view to bind here (test_table_view_in_place) */
    }
    cfg.table = NULL;
    cfg.view = &view;
    OGK_ASSERT_STATUS(ogk_nog_init(&ctx, &cfg), OGK_OK);
    nav.v_n_mps = 2.0;
    OGK_ASSERT_STATUS(ogk_nog_sample(&ctx, &nav, &s), OGK_OK);
    beta = s.beta_rad;
    /* The flash image is rewritten and fails validation: the view is zeroed. */
    vbuf.b[OGK_TABLE_HEADER_SIZE + 100u] ^= 0x01u;
    OGK_ASSERT_STATUS(ogk_nog_table_view(&view, vbuf.b, TABLE_BYTES), OGK_E_TABLE_CRC);
    check_stale(&ctx, beta);
    vbuf.b[OGK_TABLE_HEADER_SIZE + 100u] ^= 0x01u;
    OGK_ASSERT_STATUS(ogk_nog_table_view(&view, vbuf.b, TABLE_BYTES), OGK_OK);
    check_stale(&ctx, beta);
    OGK_ASSERT_STATUS(ogk_nog_init(&ctx, &cfg), OGK_OK);
    nav = nav_at(30.0, 0.3);
    OGK_ASSERT_STATUS(ogk_nog_sample(&ctx, &nav, &s), OGK_OK);
}

/* Finite input outside the envelope of ogk/nog.h: OGK_E_RANGE before any
 * arithmetic, every output finite, the nominal (no correction yet) flown. */
/* req: OGK-NOG-010 */
static void test_envelope_rejects_absurd_inputs(void **state)
{
    ogk_nog_sample_t s;
    ogk_thrust_cmd_t c;
    unsigned k;
    (void)state;
    for (k = 0u; k < 12u; ++k) {
        ogk_nog_nav_t nav = nav_at(10.0, 0.1);
        switch (k) {
        /* just outside each bound: 1e-15 relative in double, 2 eps (beyond
         * float's rounding of the product) in float; the finite extremes of
         * the type (OGK_REAL_MAX / _MIN, float's 1.7e38 and 1e30) */
        case 0u: nav.phi_rad = OGK_TEST_PICK(1.7e308, 1.7e38); break;
        case 1u: nav.t_s = OGK_REAL_MAX; break;
        case 2u: nav.t_s = 2.0 * TF_STAR + 10.0 + OGK_TEST_TOL(1e-9, 2.0 * FLT_EPSILON * 210.0); break; /* 2 t_f* + dtf_max */
        case 3u: nav.r_m = 1.0e9 * (1.0 + OGK_TEST_TOL(1e-15, 2.0 * FLT_EPSILON)); break;
        case 4u: nav.r_m = 0.0; break;
        case 5u: nav.phi_rad = -OGK_NOG_PHI_MAX_RAD; break;
        case 6u: nav.xi_rad = 1.0e4 * (1.0 + OGK_TEST_TOL(1e-15, 2.0 * FLT_EPSILON)); break;
        case 7u: nav.v_r_mps = -1.0e5 * (1.0 + OGK_TEST_TOL(1e-15, 2.0 * FLT_EPSILON)); break;
        case 8u: nav.v_t_mps = OGK_TEST_PICK(1.0e300, 1.0e30); break;
        case 9u: nav.v_n_mps = 1.0e5 * (1.0 + OGK_TEST_TOL(1e-15, 2.0 * FLT_EPSILON)); break;
        case 10u: nav.t_s = -OGK_REAL_MIN; break;
        default: nav.xi_rad = -OGK_REAL_MAX; break;
        }
        OGK_ASSERT_STATUS(ogk_nog_sample(&nog, &nav, &s), OGK_E_RANGE);
        assert_true(sample_is_finite(&s));
        assert_true((s.flags & OGK_NOG_FLAG_SAFE) != 0u);
        OGK_ASSERT_NEAR(s.alpha_rad, ALPHA0, OGK_TEST_TOL(1e-12, ANG_EPS));
        OGK_ASSERT_NEAR(s.beta_rad, 0.0, OGK_TEST_TOL(1e-12, ANG_EPS));
        OGK_ASSERT_NEAR(s.t_f_s, TF_STAR, 0.0);
        OGK_ASSERT_STATUS(ogk_nog_thrust_cmd(&nog, 10.0, &c), OGK_OK);
        assert_true(isfinite(c.alpha_rad) && isfinite(c.beta_rad));
    }
    /* On the envelope's edges the sample is good. */
    {
        ogk_nog_nav_t nav = nav_at(10.0, 0.1);
        nav.v_n_mps = 1.0e5;
        nav.xi_rad = 1.0e4;
        OGK_ASSERT_STATUS(ogk_nog_sample(&nog, &nav, &s), OGK_OK);
        assert_true(sample_is_finite(&s));
    }
    /* Commands far in the future are finite, with the engine off. */
    OGK_ASSERT_STATUS(ogk_nog_thrust_cmd(&nog, OGK_REAL_MAX, &c), OGK_OK);
    assert_true(isfinite(c.alpha_rad) && isfinite(c.beta_rad) && isfinite(c.t_s));
    assert_true((c.flags & OGK_THRUST_FLAG_ENGINE_ON) == 0u);
}

/* One bad sample (absurd time, a time past the cut-off, NaN with an absurd
 * time) latches nothing: the next good sample, and the commands before it,
 * fly as if it had not been taken (the engine is not cut off). */
/* req: OGK-NOG-010 */
static void test_one_bad_sample_does_not_latch(void **state)
{
    static const double bad_t[3] = {1.0e6, 150.0, 2.0 + 1.0e6};
    ogk_nog_config_t cfg = config();
    ogk_nog_t ref;
    ogk_nog_nav_t nav = nav_at(0.0, 0.0);
    ogk_nog_sample_t s, sr;
    ogk_thrust_cmd_t c, cr;
    unsigned k;
    (void)state;
    OGK_ASSERT_STATUS(ogk_nog_init(&ref, &cfg), OGK_OK);
    nav.v_t_mps += 1.5;
    nav.v_n_mps = 2.0;
    OGK_ASSERT_STATUS(ogk_nog_sample(&nog, &nav, &s), OGK_OK);
    OGK_ASSERT_STATUS(ogk_nog_sample(&ref, &nav, &sr), OGK_OK);
    for (k = 0u; k < 3u; ++k) {
        const double t_good = 2.0 * (double)(k + 1u);
        nav = nav_at(bad_t[k], bad_t[k] / TF_STAR);
        if (k == 2u) {
            nav.v_t_mps = NAN; /* and an absurd time */
        }
        OGK_ASSERT_STATUS(ogk_nog_sample(&nog, &nav, &s),
                          (k == 2u) ? OGK_E_NONFINITE : OGK_E_RANGE);
        assert_true((k != 1u) || (s.flags & OGK_NOG_FLAG_CUTOFF) != 0u); /* 150 s: past it */
        assert_true(sample_is_finite(&s));
        assert_true((s.flags & OGK_NOG_FLAG_SAFE) != 0u);
        OGK_ASSERT_STATUS(ogk_nog_thrust_cmd(&nog, t_good - 1.0, &c), OGK_OK);
        assert_true((c.flags & OGK_THRUST_FLAG_ENGINE_ON) != 0u); /* engine not cut off */
        assert_true((c.flags & OGK_THRUST_FLAG_SAFE) != 0u);
        nav = nav_at(t_good, t_good / TF_STAR);
        nav.v_t_mps += 1.5;
        OGK_ASSERT_STATUS(ogk_nog_sample(&nog, &nav, &s), OGK_OK);
        OGK_ASSERT_STATUS(ogk_nog_sample(&ref, &nav, &sr), OGK_OK);
        assert_true((s.flags & OGK_NOG_FLAG_SAFE) == 0u);
        assert_true(memcmp(&s, &sr, sizeof s) == 0);
        OGK_ASSERT_STATUS(ogk_nog_thrust_cmd(&nog, t_good + 1.0, &c), OGK_OK);
        OGK_ASSERT_STATUS(ogk_nog_thrust_cmd(&ref, t_good + 1.0, &cr), OGK_OK);
        assert_true(memcmp(&c, &cr, sizeof c) == 0);
    }
}

/* A valid-CRC table whose gains are 1e308: finite input, overflowing
 * correction. The step reports it and flies the last good correction.
 * (HUGE_GAIN: 1e308, float 1e38: times a 10 m/s error, beyond the type.) */
#define HUGE_GAIN OGK_TEST_PICK(1.0e308, 1.0e38)
/* req: OGK-NOG-011 */
static void test_huge_gains_give_safe_command(void **state)
{
    ogk_nog_config_t cfg = config();
    ogk_nog_nav_t nav = nav_at(0.0, 0.0);
    ogk_nog_sample_t s;
    ogk_thrust_cmd_t c;
    size_t k;
    (void)state;
    for (k = 0u; k + 1u < GRID; ++k) {
        const size_t row = OGK_TABLE_HEADER_SIZE + TW_REAL_BYTES * (GRID + k * OGK_NOG_ENTRY_LEN);
        tw_put_real(buf + row + TW_REAL_BYTES * (OGK_NOG_OFF_GAIN + 7u * 7u + 4u), HUGE_GAIN);
        tw_put_real(buf + row + TW_REAL_BYTES * (OGK_NOG_OFF_GAIN + 5u * 7u + 5u), HUGE_GAIN);
    }
    tw_seal(buf, N_VALUES);
    OGK_ASSERT_STATUS(ogk_nog_table_load(&table, buf, TABLE_BYTES), OGK_OK);
    OGK_ASSERT_STATUS(ogk_nog_init(&nog, &cfg), OGK_OK);
    OGK_ASSERT_STATUS(ogk_nog_sample(&nog, &nav, &s), OGK_OK); /* on the nominal: dx = 0 */
    nav = nav_at(2.0, 0.02);
    nav.v_t_mps += 10.0;
    nav.v_n_mps = 10.0;
    OGK_ASSERT_STATUS(ogk_nog_sample(&nog, &nav, &s), OGK_E_SAFE_COMMAND);
    assert_true(sample_is_finite(&s));
    assert_true((s.flags & OGK_NOG_FLAG_SAFE) != 0u);
    OGK_ASSERT_NEAR(s.t_f_s, TF_STAR, 0.0);   /* the last good (nominal) correction */
    OGK_ASSERT_NEAR(s.alpha_rad, ALPHA0, OGK_TEST_TOL(1e-12, ANG_EPS));
    OGK_ASSERT_NEAR(s.beta_rad, 0.0, OGK_TEST_TOL(1e-12, ANG_EPS));
    OGK_ASSERT_STATUS(ogk_nog_thrust_cmd(&nog, 3.0, &c), OGK_OK);
    assert_true(isfinite(c.alpha_rad) && isfinite(c.beta_rad));
    assert_true((c.flags & OGK_THRUST_FLAG_SAFE) != 0u);
    /* Small enough a displacement, and the same table flies again. */
    nav = nav_at(4.0, 0.04);
    OGK_ASSERT_STATUS(ogk_nog_sample(&nog, &nav, &s), OGK_OK);
    assert_true(sample_is_finite(&s));
}

/* Only the flight-time row of G overflows (dt_f = 1e308 x 10 s per m/s =
 * inf, every dlam finite): a fault of the table, reported as the safe
 * command, not clipped to dtf_max like a large finite dt_f. */
/* req: OGK-NOG-011 */
static void test_overflowing_dt_f_alone_gives_safe_command(void **state)
{
    ogk_nog_config_t cfg = config();
    ogk_nog_nav_t nav = nav_at(0.0, 0.0);
    ogk_nog_sample_t s;
    size_t k;
    (void)state;
    for (k = 0u; k + 1u < GRID; ++k) {
        const size_t row = OGK_TABLE_HEADER_SIZE + TW_REAL_BYTES * (GRID + k * OGK_NOG_ENTRY_LEN);
        tw_put_real(buf + row + TW_REAL_BYTES * (OGK_NOG_OFF_GAIN + 7u * 7u + 4u), HUGE_GAIN);
    }
    tw_seal(buf, N_VALUES);
    OGK_ASSERT_STATUS(ogk_nog_table_load(&table, buf, TABLE_BYTES), OGK_OK);
    OGK_ASSERT_STATUS(ogk_nog_init(&nog, &cfg), OGK_OK);
    nav.v_t_mps += 10.0;
    OGK_ASSERT_STATUS(ogk_nog_sample(&nog, &nav, &s), OGK_E_SAFE_COMMAND);
    assert_true((s.flags & OGK_NOG_FLAG_SAFE) != 0u);
    OGK_ASSERT_NEAR(s.t_f_s, TF_STAR, 0.0); /* the nominal t_f, not t_f* + dtf_max */
    OGK_ASSERT_NEAR(s.alpha_rad, ALPHA0, OGK_TEST_TOL(1e-15, ANG_EPS));
}

/* A valid table (finite values) whose costate still overflows: lambda_vr
 * near DBL_MAX at the last two nodes with slopes -L, +L, so that the cubic
 * Hermite at the middle of [0.75, 1] sums to -1.806e308 = -inf (terms -0.85,
 * -0.053, -0.85, -0.053 x 1e308), and a held correction dlam_vr that grows
 * past DBL_MAX: 1.5e308 (G row 3 from dv_n = 1 at tau = 0, du_max = pi so it
 * is not scaled) continued by its rate 1.5e308 over 0.75 to +inf in the frozen
 * sample at tau = 0.75. There the costate is +inf (thrust along -r: alpha =
 * -pi/2, beta = 0, finite, flown); at tau = 0.875 it is -inf + inf = NaN: the
 * command reports OGK_E_SAFE_COMMAND and flies those held angles.
 * Float: the same arithmetic near FLT_MAX (3.403e38): big = 3.23e38 puts the
 * middle sum (1.0624 big = 3.43e38) beyond it and the sum at s = 0.2 (1.041
 * big = 3.36e38) within it, as 1.7e308 does for DBL_MAX; the held correction
 * 2e38 grows over 0.75 to 3.5e38 = +inf. */
#define BIG_COSTATE OGK_TEST_PICK(1.7e308, 3.23e38)
#define BIG_DLAM OGK_TEST_PICK(1.5e308, 2.0e38)
/* req: OGK-NOG-011 */
static void test_overflowing_costate_gives_safe_command(void **state)
{
    const double big = BIG_COSTATE;
    ogk_nog_config_t cfg = config();
    ogk_nog_nav_t nav = nav_at(0.0, 0.0);
    ogk_nog_sample_t s;
    ogk_thrust_cmd_t c;
    const size_t row0 = OGK_TABLE_HEADER_SIZE + TW_REAL_BYTES * GRID;
    const size_t row3 = row0 + TW_REAL_BYTES * 3u * OGK_NOG_ENTRY_LEN;
    const size_t row4 = row0 + TW_REAL_BYTES * 4u * OGK_NOG_ENTRY_LEN;
    (void)state;
    tw_put_real(buf + row0 + TW_REAL_BYTES * (OGK_NOG_OFF_GAIN + 3u * 7u + 5u), BIG_DLAM);
    tw_put_real(buf + row0 + TW_REAL_BYTES * (OGK_NOG_OFF_NRATE + 3u * 7u + 5u), BIG_DLAM);
    tw_put_real(buf + row3 + TW_REAL_BYTES * (OGK_NOG_OFF_LAM + 3u), -big);
    tw_put_real(buf + row3 + TW_REAL_BYTES * (OGK_NOG_OFF_LAMDOT + 3u), -big);
    tw_put_real(buf + row4 + TW_REAL_BYTES * (OGK_NOG_OFF_LAM + 3u), -big);
    tw_put_real(buf + row4 + TW_REAL_BYTES * (OGK_NOG_OFF_LAMDOT + 3u), big);
    tw_seal(buf, N_VALUES);
    OGK_ASSERT_STATUS(ogk_nog_table_load(&table, buf, TABLE_BYTES), OGK_OK);
    cfg.du_max_rad = PI;
    OGK_ASSERT_STATUS(ogk_nog_init(&nog, &cfg), OGK_OK);
    nav.v_n_mps = 1.0;
    OGK_ASSERT_STATUS(ogk_nog_sample(&nog, &nav, &s), OGK_OK);
    OGK_ASSERT_NEAR(nog.dlam_k[3], (ogk_real_t)BIG_DLAM, 0.0);
    nav = nav_at(75.0, 0.75);
    nav.v_n_mps = 1.0;
    OGK_ASSERT_STATUS(ogk_nog_sample(&nog, &nav, &s), OGK_OK);
    assert_true((s.flags & OGK_NOG_FLAG_FROZEN) != 0u);
    assert_true(isinf(nog.dlam_k[3]) && nog.dlam_k[3] > 0.0);
    OGK_ASSERT_NEAR(s.alpha_rad, -0.5 * PI, OGK_TEST_TOL(1e-15, ANG_EPS));
    OGK_ASSERT_NEAR(s.beta_rad, 0.0, 0.0);
    OGK_ASSERT_STATUS(ogk_nog_thrust_cmd(&nog, 80.0, &c), OGK_OK); /* s = 0.2: -1.77e308, finite */
    OGK_ASSERT_STATUS(ogk_nog_thrust_cmd(&nog, 87.5, &c), OGK_E_SAFE_COMMAND);
    assert_true((c.flags & OGK_THRUST_FLAG_SAFE) != 0u);
    assert_true((c.flags & OGK_THRUST_FLAG_ENGINE_ON) != 0u);
    assert_true((c.law_flags & OGK_NOG_FLAG_SAFE) != 0u);
    OGK_ASSERT_NEAR(c.alpha_rad, -0.5 * PI, OGK_TEST_TOL(1e-15, ANG_EPS));
    OGK_ASSERT_NEAR(c.beta_rad, 0.0, 0.0);
    /* A time before the sample keeps its own status (and the held angles). */
    OGK_ASSERT_STATUS(ogk_nog_thrust_cmd(&nog, 70.0, &c), OGK_E_RANGE);
    assert_true((c.flags & OGK_THRUST_FLAG_SAFE) != 0u);
}

/* The deprecated name gives the command of the new one, bit for bit. */
static void assert_same_cmd(const ogk_thrust_cmd_t *a, const ogk_thrust_cmd_t *b)
{
    /* memcmp: bit for bit (the Cortex-M7 shim has no assert_memory_equal) */
    assert_int_equal(memcmp(&a->t_s, &b->t_s, sizeof a->t_s), 0);
    assert_int_equal(memcmp(&a->alpha_rad, &b->alpha_rad, sizeof a->alpha_rad), 0);
    assert_int_equal(memcmp(&a->beta_rad, &b->beta_rad, sizeof a->beta_rad), 0);
    assert_int_equal(a->flags, b->flags);
    assert_int_equal(a->law_flags, b->law_flags);
    assert_int_equal((int)a->frame, (int)b->frame);
    assert_int_equal(memcmp(a->u, b->u, sizeof a->u), 0);
    assert_int_equal(memcmp(&a->throttle, &b->throttle, sizeof a->throttle), 0);
}

/* req: OGK-NOG-012 */
static void test_deprecated_ogk_nog_command_alias(void **state)
{
    /* ogk_nog_command (deprecated, removed in 0.3) == ogk_nog_thrust_cmd:
     * same status and command on the nominal, after a corrected sample, for
     * a time before the sample, a non-finite time, after the cut-off, for an
     * uninitialised context and for NULL arguments. */
    static const double times[] = {1.0, 3.0, 50.25, 100.5, 0.5};
    ogk_nog_nav_t nav = nav_at(2.0, 0.02);
    ogk_nog_sample_t s;
    ogk_thrust_cmd_t c_new;
    ogk_thrust_cmd_t c_old;
    ogk_nog_t blank;
    size_t i;
    (void)state;
    for (i = 0u; i < sizeof times / sizeof times[0]; ++i) {
        OGK_ASSERT_STATUS(ogk_nog_command(&nog, times[i], &c_old), ogk_nog_thrust_cmd(&nog, times[i], &c_new));
        assert_same_cmd(&c_old, &c_new);
    }
    nav.v_n_mps = 2.0;
    OGK_ASSERT_STATUS(ogk_nog_sample(&nog, &nav, &s), OGK_OK);
    for (i = 0u; i < sizeof times / sizeof times[0]; ++i) {
        OGK_ASSERT_STATUS(ogk_nog_command(&nog, times[i], &c_old), ogk_nog_thrust_cmd(&nog, times[i], &c_new));
        assert_same_cmd(&c_old, &c_new);
    }
    OGK_ASSERT_STATUS(ogk_nog_command(&nog, NAN, &c_old), ogk_nog_thrust_cmd(&nog, NAN, &c_new));
    assert_same_cmd(&c_old, &c_new);
    memset(&blank, 0, sizeof blank);
    OGK_ASSERT_STATUS(ogk_nog_command(&blank, 1.0, &c_old), OGK_E_NOT_INIT);
    OGK_ASSERT_STATUS(ogk_nog_thrust_cmd(&blank, 1.0, &c_new), OGK_E_NOT_INIT);
    assert_same_cmd(&c_old, &c_new);
    OGK_ASSERT_STATUS(ogk_nog_command(NULL, 1.0, &c_old), OGK_E_NULL);
    OGK_ASSERT_STATUS(ogk_nog_command(&nog, 1.0, NULL), OGK_E_NULL);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test_setup(test_table_load_and_rejections, setup),
        cmocka_unit_test_setup(test_on_nominal_no_correction, setup),
        cmocka_unit_test_setup(test_on_nominal_in_every_interval, setup),
        cmocka_unit_test_setup(test_flight_time_update_and_eq31, setup),
        cmocka_unit_test_setup(test_radius_error_moves_lambda_r_only, setup),
        cmocka_unit_test_setup(test_out_of_plane_with_first_order_hold, setup),
        cmocka_unit_test_setup(test_end_game_limits, setup),
        cmocka_unit_test_setup(test_dt_f_at_the_bound_is_not_limited, setup),
        cmocka_unit_test_setup(test_du_max_pi_admits_a_reversal, setup),
        cmocka_unit_test_setup(test_freeze_and_termination, setup),
        cmocka_unit_test_setup(test_bad_navigation_gives_safe_command, setup),
        cmocka_unit_test_setup(test_sample_at_the_envelope_time_bound, setup),
        cmocka_unit_test_setup(test_init_errors, setup),
        cmocka_unit_test_setup(test_config_range_boundaries, setup),
        cmocka_unit_test_setup(test_config_default, setup),
        cmocka_unit_test_setup(test_table_view_in_place, setup),
        cmocka_unit_test_setup(test_table_view_rejections, setup),
        cmocka_unit_test_setup(test_reset, setup),
        cmocka_unit_test_setup(test_stale_table_after_failed_reload, setup),
        cmocka_unit_test_setup(test_stale_view_after_failed_reload, setup),
        cmocka_unit_test_setup(test_other_precision_table_refused, setup),
        cmocka_unit_test_setup(test_envelope_rejects_absurd_inputs, setup),
        cmocka_unit_test_setup(test_one_bad_sample_does_not_latch, setup),
        cmocka_unit_test_setup(test_huge_gains_give_safe_command, setup),
        cmocka_unit_test_setup(test_overflowing_dt_f_alone_gives_safe_command, setup),
        cmocka_unit_test_setup(test_overflowing_costate_gives_safe_command, setup),
        cmocka_unit_test_setup(test_deprecated_ogk_nog_command_alias, setup),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
