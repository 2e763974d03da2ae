/* test_thrust_cmd.c -- the one thrust-direction command of every law (ogk/types.h,
 * ogk/thrust_cmd.h) and CPD taking it in any frame (ogk_cpd_input_from_thrust_cmd):
 *   - angles <-> unit vector against the closed form of types.h, over a grid of directions and at
 *     the poles (alpha = 0 along +-n), the wrap of alpha into (-pi, pi];
 *   - every rejection with its specific code, the outputs untouched;
 *   - r-t-n from an inertial vector against r-t-n axes built here as r_hat, t_hat = z x r_hat /
 *     |z x r_hat| and n = r x t (cross products, not the kernel's rows);
 *   - synodic -> inertial against the rotation R3(-angle) written out here, and the chain
 *     synodic -> inertial -> r-t-n -> CPD equal to CPD fed the same direction as r-t-n angles;
 *   - a command set field by field the old way (memset, angles) still feeds CPD. */
#include "ogk_test.h"

/* Float tolerances (ogk_test.h): a unit vector's component or an angle (at most pi) made of sines and
 * cosines of float angles carries a few roundings: CMD_EPS = 8 eps pi; in double the tolerances as
 * always. Copies of the caller's values are compared with those values as stored (ogk_real_t). */
#define CMD_EPS (8.0 * FLT_EPSILON * 3.14159265358979323846)

#include <string.h>

#include "ogk/cpd.h"
#include "ogk/mathutil.h"
#include "ogk/thrust_cmd.h"
#include "ogk/types.h"

#define PI 3.14159265358979323846

static void cross(const ogk_real_t *a, const ogk_real_t *b, ogk_real_t *c)
{
    c[0] = (a[1] * b[2]) - (a[2] * b[1]);
    c[1] = (a[2] * b[0]) - (a[0] * b[2]);
    c[2] = (a[0] * b[1]) - (a[1] * b[0]);
}

static ogk_real_t dot(const ogk_real_t *a, const ogk_real_t *b)
{
    return (a[0] * b[0]) + (a[1] * b[1]) + (a[2] * b[2]);
}

/* r-t-n axes at (xi, phi) in the inertial frame, built from the position direction and I3. */
static void rtn_axes(ogk_real_t xi, ogk_real_t phi, ogk_real_t *r, ogk_real_t *t, ogk_real_t *n)
{
    static const ogk_real_t z[3] = {0.0, 0.0, 1.0};
    ogk_real_t zr[3];
    double norm;
    r[0] = cos(phi) * cos(xi);
    r[1] = cos(phi) * sin(xi);
    r[2] = sin(phi);
    cross(z, r, zr); /* horizontal, eastward */
    norm = sqrt(dot(zr, zr));
    t[0] = zr[0] / norm;
    t[1] = zr[1] / norm;
    t[2] = zr[2] / norm;
    cross(r, t, n);
}

/* Angle between two directions [rad]. */
static ogk_real_t angle_between(const ogk_real_t *a, const ogk_real_t *b)
{
    ogk_real_t c[3];
    cross(a, b, c);
    return atan2(sqrt(dot(c, c)), dot(a, b));
}

/* req: OGK-CORE-019 */
static void test_angles_and_unit_vectors(void **state)
{
    int i;
    int j;
    ogk_real_t u[3];
    ogk_real_t a;
    ogk_real_t b;
    (void)state;
    /* the axes: alpha = beta = 0 is t, alpha = pi/2 is r, beta = pi/2 is n */
    OGK_ASSERT_STATUS(ogk_thrust_cmd_angles_to_unit(0.0, 0.0, u), OGK_OK);
    OGK_ASSERT_NEAR(u[0], 0.0, 0.0);
    OGK_ASSERT_NEAR(u[1], 1.0, 0.0);
    OGK_ASSERT_NEAR(u[2], 0.0, 0.0);
    OGK_ASSERT_STATUS(ogk_thrust_cmd_angles_to_unit(PI / 2.0, 0.0, u), OGK_OK);
    OGK_ASSERT_NEAR(u[0], 1.0, OGK_TEST_TOL(1e-16, CMD_EPS));
    OGK_ASSERT_NEAR(u[1], 0.0, OGK_TEST_TOL(1e-16, CMD_EPS));
    OGK_ASSERT_STATUS(ogk_thrust_cmd_angles_to_unit(0.3, PI / 2.0, u), OGK_OK);
    OGK_ASSERT_NEAR(u[2], 1.0, 0.0);
    /* a grid of directions: the closed form, and back */
    for (i = -6; i <= 6; ++i) {
        for (j = -4; j <= 4; ++j) {
            const double alpha = 0.5 * (double)i;     /* -3 .. 3 rad */
            const double beta = 0.38 * (double)j;     /* -1.52 .. 1.52 rad */
            OGK_ASSERT_STATUS(ogk_thrust_cmd_angles_to_unit(alpha, beta, u), OGK_OK);
            OGK_ASSERT_NEAR(u[0], cos(beta) * sin(alpha), OGK_TEST_TOL(1e-16, CMD_EPS));
            OGK_ASSERT_NEAR(u[1], cos(beta) * cos(alpha), OGK_TEST_TOL(1e-16, CMD_EPS));
            OGK_ASSERT_NEAR(u[2], sin(beta), OGK_TEST_TOL(1e-16, CMD_EPS));
            OGK_ASSERT_STATUS(ogk_thrust_cmd_unit_to_angles(u, &a, &b), OGK_OK);
            OGK_ASSERT_NEAR(a, alpha, OGK_TEST_TOL(1e-15, CMD_EPS));
            OGK_ASSERT_NEAR(b, beta, OGK_TEST_TOL(1e-15, CMD_EPS));
        }
    }
    /* alpha comes back wrapped into (-pi, pi] */
    OGK_ASSERT_STATUS(ogk_thrust_cmd_angles_to_unit(3.5, 0.2, u), OGK_OK);
    OGK_ASSERT_STATUS(ogk_thrust_cmd_unit_to_angles(u, &a, &b), OGK_OK);
    OGK_ASSERT_NEAR(a, 3.5 - (2.0 * PI), OGK_TEST_TOL(1e-15, CMD_EPS));
    OGK_ASSERT_NEAR(b, 0.2, OGK_TEST_TOL(1e-15, CMD_EPS));
    /* the poles: alpha undefined, 0 */
    {
        const ogk_real_t up[3] = {0.0, 0.0, 1.0};
        const ogk_real_t down[3] = {0.0, 0.0, -1.0};
        OGK_ASSERT_STATUS(ogk_thrust_cmd_unit_to_angles(up, &a, &b), OGK_OK);
        OGK_ASSERT_NEAR(a, 0.0, 0.0);
        OGK_ASSERT_NEAR(b, (ogk_real_t)(PI / 2.0), 0.0);
        OGK_ASSERT_STATUS(ogk_thrust_cmd_unit_to_angles(down, &a, &b), OGK_OK);
        OGK_ASSERT_NEAR(a, 0.0, 0.0);
        OGK_ASSERT_NEAR(b, (ogk_real_t)(-PI / 2.0), 0.0);
    }
    /* within the unit tolerance: accepted (and the angles of u / |u|) */
    {
        const double s = 1.0 + (0.5 * OGK_THRUST_CMD_UNIT_TOL);
        const ogk_real_t v[3] = {0.6 * s, 0.8 * s, 0.0};
        OGK_ASSERT_STATUS(ogk_thrust_cmd_unit_to_angles(v, &a, &b), OGK_OK);
        OGK_ASSERT_NEAR(a, atan2(0.6, 0.8), OGK_TEST_TOL(1e-15, CMD_EPS));
    }
}

/* req: OGK-CORE-019 */
static void test_angle_and_vector_rejections(void **state)
{
    ogk_real_t u[3] = {7.0, 7.0, 7.0};
    ogk_real_t a = 7.0;
    ogk_real_t b = 7.0;
    /* beyond the tolerance: four times it, in either build (float: 8 eps, so 1 + 32 eps, which float
     * holds exactly, where 1 + 4e-9 would be 1) */
    const double big = 1.0 + (4.0 * OGK_THRUST_CMD_UNIT_TOL);
    const ogk_real_t v_long[3] = {0.0, big, 0.0};
    const ogk_real_t v_zero[3] = {0.0, 0.0, 0.0};
    const ogk_real_t v_huge[3] = {OGK_TEST_PICK(1e308, 1e38), OGK_TEST_PICK(1e308, 1e38),
                                  OGK_TEST_PICK(1e308, 1e38)}; /* |u| would overflow: not unit, no inf */
    const ogk_real_t v_nan[3] = {0.0, NAN, 0.0};
    const ogk_real_t v_inf[3] = {INFINITY, 0.0, 0.0};
    (void)state;
    OGK_ASSERT_STATUS(ogk_thrust_cmd_angles_to_unit(0.1, 0.2, NULL), OGK_E_NULL);
    OGK_ASSERT_STATUS(ogk_thrust_cmd_angles_to_unit(NAN, 0.2, u), OGK_E_NONFINITE);
    OGK_ASSERT_STATUS(ogk_thrust_cmd_angles_to_unit(0.1, INFINITY, u), OGK_E_NONFINITE);
    OGK_ASSERT_STATUS(ogk_thrust_cmd_angles_to_unit(2.0 * OGK_ANGLE_LIMIT, 0.2, u), OGK_E_RANGE);
    OGK_ASSERT_STATUS(ogk_thrust_cmd_angles_to_unit(0.1, -2.0 * OGK_ANGLE_LIMIT, u), OGK_E_RANGE);
    OGK_ASSERT_NEAR(u[0], 7.0, 0.0); /* untouched */
    OGK_ASSERT_STATUS(ogk_thrust_cmd_unit_to_angles(NULL, &a, &b), OGK_E_NULL);
    OGK_ASSERT_STATUS(ogk_thrust_cmd_unit_to_angles(v_zero, NULL, &b), OGK_E_NULL);
    OGK_ASSERT_STATUS(ogk_thrust_cmd_unit_to_angles(v_zero, &a, NULL), OGK_E_NULL);
    OGK_ASSERT_STATUS(ogk_thrust_cmd_unit_to_angles(v_zero, &a, &b), OGK_E_RANGE);
    OGK_ASSERT_STATUS(ogk_thrust_cmd_unit_to_angles(v_long, &a, &b), OGK_E_RANGE);
    OGK_ASSERT_STATUS(ogk_thrust_cmd_unit_to_angles(v_huge, &a, &b), OGK_E_RANGE);
    OGK_ASSERT_STATUS(ogk_thrust_cmd_unit_to_angles(v_nan, &a, &b), OGK_E_NONFINITE);
    OGK_ASSERT_STATUS(ogk_thrust_cmd_unit_to_angles(v_inf, &a, &b), OGK_E_NONFINITE);
    OGK_ASSERT_NEAR(a, 7.0, 0.0);
    OGK_ASSERT_NEAR(b, 7.0, 0.0);
}

/* req: OGK-CORE-019 */
static void test_builders(void **state)
{
    ogk_thrust_cmd_t c;
    ogk_thrust_cmd_t d;
    ogk_thrust_cmd_t keep;
    const ogk_real_t u_in[3] = {0.0, 0.6, -0.8};
    const ogk_real_t u_sy[3] = {0.48, 0.64, 0.6};
    (void)state;
    /* from the angles: a complete r-t-n command */
    (void)memset(&c, 0x5A, sizeof c);
    OGK_ASSERT_STATUS(ogk_thrust_cmd_from_angles(12.5, 0.4, -0.3, 0.75,
                                                 OGK_THRUST_FLAG_ENGINE_ON | OGK_THRUST_FLAG_LIMITED,
                                                 0x11u, &c), OGK_OK);
    OGK_ASSERT_NEAR(c.t_s, 12.5, 0.0);
    assert_int_equal((int)c.frame, (int)OGK_FRAME_RTN);
    OGK_ASSERT_NEAR(c.alpha_rad, (ogk_real_t)0.4, 0.0);
    OGK_ASSERT_NEAR(c.beta_rad, (ogk_real_t)-0.3, 0.0);
    OGK_ASSERT_NEAR(c.u[0], cos(-0.3) * sin(0.4), OGK_TEST_TOL(1e-16, CMD_EPS));
    OGK_ASSERT_NEAR(c.u[1], cos(-0.3) * cos(0.4), OGK_TEST_TOL(1e-16, CMD_EPS));
    OGK_ASSERT_NEAR(c.u[2], sin(-0.3), OGK_TEST_TOL(1e-16, CMD_EPS));
    OGK_ASSERT_NEAR(c.throttle, 0.75, 0.0);
    assert_int_equal(c.flags, OGK_THRUST_FLAG_ENGINE_ON | OGK_THRUST_FLAG_LIMITED);
    assert_int_equal(c.law_flags, 0x11u);
    /* zeroed first: the same command built twice is the same bytes (padding included) */
    (void)memset(&d, 0xA5, sizeof d);
    OGK_ASSERT_STATUS(ogk_thrust_cmd_from_angles(12.5, 0.4, -0.3, 0.75,
                                                 OGK_THRUST_FLAG_ENGINE_ON | OGK_THRUST_FLAG_LIMITED,
                                                 0x11u, &d), OGK_OK);
    assert_true(memcmp(&c, &d, sizeof c) == 0);
    /* engine off: throttle stored as 0 */
    OGK_ASSERT_STATUS(ogk_thrust_cmd_from_angles(1.0, 0.4, -0.3, 0.75, 0u, 0u, &d), OGK_OK);
    OGK_ASSERT_NEAR(d.throttle, 0.0, 0.0);
    /* from a vector: inertial keeps zero angles; r-t-n gets its angles */
    OGK_ASSERT_STATUS(ogk_thrust_cmd_from_unit(2.0, OGK_FRAME_INERTIAL, u_in, 1.0,
                                               OGK_THRUST_FLAG_ENGINE_ON, 0u, &d), OGK_OK);
    assert_int_equal((int)d.frame, (int)OGK_FRAME_INERTIAL);
    OGK_ASSERT_NEAR(d.u[1], (ogk_real_t)0.6, 0.0);
    OGK_ASSERT_NEAR(d.u[2], (ogk_real_t)-0.8, 0.0);
    OGK_ASSERT_NEAR(d.alpha_rad, 0.0, 0.0);
    OGK_ASSERT_NEAR(d.beta_rad, 0.0, 0.0);
    OGK_ASSERT_STATUS(ogk_thrust_cmd_from_unit(2.0, OGK_FRAME_RTN, c.u, 0.75,
                                               OGK_THRUST_FLAG_ENGINE_ON | OGK_THRUST_FLAG_LIMITED,
                                               0x11u, &d), OGK_OK);
    OGK_ASSERT_NEAR(d.alpha_rad, 0.4, OGK_TEST_TOL(1e-15, CMD_EPS));
    OGK_ASSERT_NEAR(d.beta_rad, -0.3, OGK_TEST_TOL(1e-15, CMD_EPS));
    OGK_ASSERT_STATUS(ogk_thrust_cmd_from_unit(2.0, OGK_FRAME_SYNODIC, u_sy, 0.0, 0u, 0u, &d), OGK_OK);
    assert_int_equal((int)d.frame, (int)OGK_FRAME_SYNODIC);
    /* the safe commands */
    OGK_ASSERT_STATUS(ogk_thrust_cmd_safe(4.0, OGK_FRAME_RTN, 0x8u, &d), OGK_OK);
    assert_int_equal(d.flags, OGK_THRUST_FLAG_SAFE);
    assert_int_equal(d.law_flags, 0x8u);
    OGK_ASSERT_NEAR(d.throttle, 0.0, 0.0);
    OGK_ASSERT_NEAR(d.u[1], 1.0, 0.0); /* along t: the zero angles */
    OGK_ASSERT_NEAR(d.alpha_rad, 0.0, 0.0);
    OGK_ASSERT_NEAR(d.t_s, 4.0, 0.0);
    OGK_ASSERT_STATUS(ogk_thrust_cmd_safe(NAN, OGK_FRAME_SYNODIC, 0u, &d), OGK_OK);
    assert_int_equal((int)d.frame, (int)OGK_FRAME_SYNODIC);
    OGK_ASSERT_NEAR(d.u[0], 1.0, 0.0);
    OGK_ASSERT_NEAR(d.t_s, 0.0, 0.0); /* a non-finite time is not carried */
    OGK_ASSERT_STATUS(ogk_thrust_cmd_safe(4.0, OGK_FRAME_INERTIAL, 0u, NULL), OGK_E_NULL);
    OGK_ASSERT_STATUS(ogk_thrust_cmd_safe(4.0, OGK_FRAME_COUNT, 0u, &d), OGK_E_FRAME);
    /* rejections: each code, the command untouched */
    keep = c;
    OGK_ASSERT_STATUS(ogk_thrust_cmd_from_angles(1.0, 0.4, -0.3, 1.0, 0u, 0u, NULL), OGK_E_NULL);
    OGK_ASSERT_STATUS(ogk_thrust_cmd_from_angles(NAN, 0.4, -0.3, 1.0, 0u, 0u, &c), OGK_E_NONFINITE);
    OGK_ASSERT_STATUS(ogk_thrust_cmd_from_angles(1.0, NAN, -0.3, 1.0, 0u, 0u, &c), OGK_E_NONFINITE);
    OGK_ASSERT_STATUS(ogk_thrust_cmd_from_angles(1.0, 0.4, -0.3, NAN, 0u, 0u, &c), OGK_E_NONFINITE);
    OGK_ASSERT_STATUS(ogk_thrust_cmd_from_angles(1.0, 1e5, -0.3, 1.0, 0u, 0u, &c), OGK_E_RANGE);
    OGK_ASSERT_STATUS(ogk_thrust_cmd_from_angles(1.0, 0.4, -0.3, 1.5, 0u, 0u, &c), OGK_E_RANGE);
    OGK_ASSERT_STATUS(ogk_thrust_cmd_from_angles(1.0, 0.4, -0.3, -0.1, 0u, 0u, &c), OGK_E_RANGE);
    OGK_ASSERT_STATUS(ogk_thrust_cmd_from_unit(1.0, OGK_FRAME_RTN, NULL, 1.0, 0u, 0u, &c), OGK_E_NULL);
    OGK_ASSERT_STATUS(ogk_thrust_cmd_from_unit(1.0, OGK_FRAME_RTN, u_in, 1.0, 0u, 0u, NULL), OGK_E_NULL);
    OGK_ASSERT_STATUS(ogk_thrust_cmd_from_unit(1.0, (ogk_frame_t)7, u_in, 1.0, 0u, 0u, &c), OGK_E_FRAME);
    OGK_ASSERT_STATUS(ogk_thrust_cmd_from_unit(1.0, OGK_FRAME_COUNT, u_in, 1.0, 0u, 0u, &c), OGK_E_FRAME);
    {
        const ogk_real_t half[3] = {0.0, 0.5, 0.0};
        const ogk_real_t nan3[3] = {0.0, 1.0, NAN};
        OGK_ASSERT_STATUS(ogk_thrust_cmd_from_unit(1.0, OGK_FRAME_RTN, half, 1.0, 0u, 0u, &c), OGK_E_RANGE);
        OGK_ASSERT_STATUS(ogk_thrust_cmd_from_unit(1.0, OGK_FRAME_RTN, nan3, 1.0, 0u, 0u, &c),
                          OGK_E_NONFINITE);
    }
    OGK_ASSERT_STATUS(ogk_thrust_cmd_from_unit(INFINITY, OGK_FRAME_RTN, u_in, 1.0, 0u, 0u, &c),
                      OGK_E_NONFINITE);
    OGK_ASSERT_STATUS(ogk_thrust_cmd_from_unit(1.0, OGK_FRAME_RTN, u_in, 2.0, 0u, 0u, &c), OGK_E_RANGE);
    assert_true(memcmp(&c, &keep, sizeof c) == 0);
}

/* r-t-n from an inertial vector against the axes built by cross products, at positions all round. */
/* req: OGK-CORE-019 */
static void test_inertial_to_rtn(void **state)
{
    int i;
    (void)state;
    for (i = 0; i < 24; ++i) {
        const double xi = -3.0 + (0.27 * (double)i);
        const double phi = -1.3 + (0.11 * (double)i);
        const double alpha = 2.9 - (0.25 * (double)i);
        const double beta = -1.2 + (0.1 * (double)i);
        ogk_real_t r[3];
        ogk_real_t t[3];
        ogk_real_t n[3];
        ogk_real_t u_i[3];
        double u_rtn[3];
        ogk_nav_state_t nav;
        ogk_thrust_cmd_t in;
        ogk_thrust_cmd_t out;
        size_t k;
        rtn_axes(xi, phi, r, t, n);
        for (k = 0u; k < 3u; ++k) {
            u_i[k] = (cos(beta) * sin(alpha) * r[k]) + (cos(beta) * cos(alpha) * t[k]) + (sin(beta) * n[k]);
        }
        (void)memset(&nav, 0, sizeof nav);
        nav.xi_rad = xi;
        nav.phi_rad = phi;
        OGK_ASSERT_STATUS(ogk_thrust_cmd_from_unit(3.0, OGK_FRAME_INERTIAL, u_i, 0.5,
                                                   OGK_THRUST_FLAG_ENGINE_ON, 0x3u, &in), OGK_OK);
        OGK_ASSERT_STATUS(ogk_thrust_cmd_to_rtn(&in, &nav, &out), OGK_OK);
        assert_int_equal((int)out.frame, (int)OGK_FRAME_RTN);
        OGK_ASSERT_NEAR(out.alpha_rad, alpha, OGK_TEST_TOL(1e-13, CMD_EPS));
        OGK_ASSERT_NEAR(out.beta_rad, beta, OGK_TEST_TOL(1e-13, CMD_EPS));
        OGK_ASSERT_NEAR(out.u[0], dot(u_i, r), OGK_TEST_TOL(1e-15, CMD_EPS));
        OGK_ASSERT_NEAR(out.u[1], dot(u_i, t), OGK_TEST_TOL(1e-15, CMD_EPS));
        OGK_ASSERT_NEAR(out.u[2], dot(u_i, n), OGK_TEST_TOL(1e-15, CMD_EPS));
        OGK_ASSERT_NEAR(out.t_s, 3.0, 0.0);
        OGK_ASSERT_NEAR(out.throttle, 0.5, 0.0);
        assert_int_equal(out.flags, OGK_THRUST_FLAG_ENGINE_ON);
        assert_int_equal(out.law_flags, 0x3u);
        /* and back: the r-t-n vector maps to the inertial one */
        u_rtn[0] = out.u[0];
        u_rtn[1] = out.u[1];
        u_rtn[2] = out.u[2];
        for (k = 0u; k < 3u; ++k) {
            OGK_ASSERT_NEAR((u_rtn[0] * r[k]) + (u_rtn[1] * t[k]) + (u_rtn[2] * n[k]), u_i[k], OGK_TEST_TOL(1e-15, CMD_EPS));
        }
        /* in place */
        OGK_ASSERT_STATUS(ogk_thrust_cmd_to_rtn(&in, &nav, &in), OGK_OK);
        assert_true(memcmp(&in, &out, sizeof in) == 0);
    }
}

/* req: OGK-CORE-019 */
static void test_to_rtn_frames_and_rejections(void **state)
{
    ogk_thrust_cmd_t in;
    ogk_thrust_cmd_t out;
    ogk_thrust_cmd_t keep;
    ogk_nav_state_t nav;
    const ogk_real_t u_sy[3] = {0.0, 1.0, 0.0};
    (void)state;
    (void)memset(&nav, 0, sizeof nav);
    nav.xi_rad = 0.4;
    nav.phi_rad = 0.1;
    /* r-t-n set the old way (memset, then the angles): the angles are the command */
    (void)memset(&in, 0, sizeof in);
    in.t_s = 5.0;
    in.alpha_rad = 0.7;
    in.beta_rad = 0.2;
    in.flags = OGK_THRUST_FLAG_ENGINE_ON;
    OGK_ASSERT_STATUS(ogk_thrust_cmd_to_rtn(&in, &nav, &out), OGK_OK);
    OGK_ASSERT_NEAR(out.alpha_rad, (ogk_real_t)0.7, 0.0);
    OGK_ASSERT_NEAR(out.beta_rad, (ogk_real_t)0.2, 0.0);
    OGK_ASSERT_NEAR(out.u[0], cos(0.2) * sin(0.7), OGK_TEST_TOL(1e-16, CMD_EPS)); /* u filled in */
    OGK_ASSERT_NEAR(out.u[2], sin(0.2), OGK_TEST_TOL(1e-16, CMD_EPS));
    OGK_ASSERT_NEAR(out.throttle, 0.0, 0.0);
    /* r-t-n needs no position: a navigation state with NaN angles does not matter */
    nav.xi_rad = NAN;
    OGK_ASSERT_STATUS(ogk_thrust_cmd_to_rtn(&in, &nav, &out), OGK_OK);
    nav.xi_rad = 0.4;
    /* synodic and unknown frames: OGK_E_FRAME, out untouched */
    keep = out;
    OGK_ASSERT_STATUS(ogk_thrust_cmd_from_unit(5.0, OGK_FRAME_SYNODIC, u_sy, 1.0,
                                               OGK_THRUST_FLAG_ENGINE_ON, 0u, &in), OGK_OK);
    OGK_ASSERT_STATUS(ogk_thrust_cmd_to_rtn(&in, &nav, &out), OGK_E_FRAME);
    in.frame = (ogk_frame_t)9;
    OGK_ASSERT_STATUS(ogk_thrust_cmd_to_rtn(&in, &nav, &out), OGK_E_FRAME);
    assert_true(memcmp(&out, &keep, sizeof out) == 0);
    /* NULLs */
    OGK_ASSERT_STATUS(ogk_thrust_cmd_to_rtn(NULL, &nav, &out), OGK_E_NULL);
    OGK_ASSERT_STATUS(ogk_thrust_cmd_to_rtn(&in, NULL, &out), OGK_E_NULL);
    OGK_ASSERT_STATUS(ogk_thrust_cmd_to_rtn(&in, &nav, NULL), OGK_E_NULL);
    /* r-t-n: non-finite angles, time, throttle; throttle out of range */
    OGK_ASSERT_STATUS(ogk_thrust_cmd_from_angles(5.0, 0.7, 0.2, 1.0, OGK_THRUST_FLAG_ENGINE_ON, 0u, &in),
                      OGK_OK);
    in.beta_rad = NAN;
    OGK_ASSERT_STATUS(ogk_thrust_cmd_to_rtn(&in, &nav, &out), OGK_E_NONFINITE);
    in.beta_rad = 0.2;
    in.alpha_rad = INFINITY;
    OGK_ASSERT_STATUS(ogk_thrust_cmd_to_rtn(&in, &nav, &out), OGK_E_NONFINITE);
    in.alpha_rad = 0.7;
    in.t_s = NAN;
    OGK_ASSERT_STATUS(ogk_thrust_cmd_to_rtn(&in, &nav, &out), OGK_E_NONFINITE);
    in.t_s = 5.0;
    in.throttle = NAN;
    OGK_ASSERT_STATUS(ogk_thrust_cmd_to_rtn(&in, &nav, &out), OGK_E_NONFINITE);
    in.throttle = 1.01;
    OGK_ASSERT_STATUS(ogk_thrust_cmd_to_rtn(&in, &nav, &out), OGK_E_RANGE);
    assert_true(memcmp(&out, &keep, sizeof out) == 0);
    /* inertial: a bad vector, a bad position */
    OGK_ASSERT_STATUS(ogk_thrust_cmd_from_unit(5.0, OGK_FRAME_INERTIAL, u_sy, 1.0,
                                               OGK_THRUST_FLAG_ENGINE_ON, 0u, &in), OGK_OK);
    in.u[1] = 2.0;
    OGK_ASSERT_STATUS(ogk_thrust_cmd_to_rtn(&in, &nav, &out), OGK_E_RANGE);
    in.u[1] = NAN;
    OGK_ASSERT_STATUS(ogk_thrust_cmd_to_rtn(&in, &nav, &out), OGK_E_NONFINITE);
    in.u[1] = 1.0;
    nav.phi_rad = NAN;
    OGK_ASSERT_STATUS(ogk_thrust_cmd_to_rtn(&in, &nav, &out), OGK_E_NONFINITE);
    nav.phi_rad = 0.1;
    nav.xi_rad = INFINITY;
    OGK_ASSERT_STATUS(ogk_thrust_cmd_to_rtn(&in, &nav, &out), OGK_E_NONFINITE);
    nav.xi_rad = 2.0 * OGK_ANGLE_LIMIT;
    OGK_ASSERT_STATUS(ogk_thrust_cmd_to_rtn(&in, &nav, &out), OGK_E_RANGE);
    nav.xi_rad = 0.4;
    nav.phi_rad = -2.0 * OGK_ANGLE_LIMIT;
    OGK_ASSERT_STATUS(ogk_thrust_cmd_to_rtn(&in, &nav, &out), OGK_E_RANGE);
    assert_true(memcmp(&out, &keep, sizeof out) == 0);
}

/* Synodic -> inertial against R3(-angle) written out, then on to CPD. */
/* req: OGK-CORE-019 OGK-CPD-010 */
static void test_synodic_to_inertial_and_cpd(void **state)
{
    static const double angles[5] = {0.0, 0.5 * PI, -2.0, 3.0, 7.5};
    const ogk_real_t u_s[3] = {0.48, -0.64, 0.6};
    ogk_thrust_cmd_t syn;
    ogk_thrust_cmd_t in;
    ogk_thrust_cmd_t keep;
    ogk_thrust_cmd_t rtn;
    ogk_cpd_input_t cpd_a;
    ogk_cpd_input_t cpd_b;
    ogk_nav_state_t nav;
    size_t i;
    (void)state;
    (void)memset(&nav, 0, sizeof nav);
    nav.xi_rad = 1.1;
    nav.phi_rad = -0.2;
    OGK_ASSERT_STATUS(ogk_thrust_cmd_from_unit(0.75, OGK_FRAME_SYNODIC, u_s, 1.0,
                                               OGK_THRUST_FLAG_ENGINE_ON, 0x20u, &syn), OGK_OK);
    for (i = 0u; i < 5u; ++i) {
        const double a = angles[i];
        const double x_s[3] = {cos(a), sin(a), 0.0};  /* the synodic axes in I */
        const double y_s[3] = {-sin(a), cos(a), 0.0};
        size_t k;
        OGK_ASSERT_STATUS(ogk_thrust_cmd_synodic_to_inertial(&syn, a, &in), OGK_OK);
        assert_int_equal((int)in.frame, (int)OGK_FRAME_INERTIAL);
        for (k = 0u; k < 2u; ++k) {
            OGK_ASSERT_NEAR(in.u[k], (u_s[0] * x_s[k]) + (u_s[1] * y_s[k]), OGK_TEST_TOL(1e-15, CMD_EPS));
        }
        OGK_ASSERT_NEAR(in.u[2], u_s[2], 0.0);
        OGK_ASSERT_NEAR(in.t_s, 0.75, 0.0);
        OGK_ASSERT_NEAR(in.throttle, 1.0, 0.0);
        assert_int_equal(in.law_flags, 0x20u);
        /* CPD: the inertial command equals CPD fed its r-t-n angles; the synodic one is refused */
        (void)memset(&cpd_a, 0, sizeof cpd_a);
        (void)memset(&cpd_b, 0, sizeof cpd_b);
        OGK_ASSERT_STATUS(ogk_cpd_input_from_thrust_cmd(&cpd_a, &in, &nav), OGK_OK);
        OGK_ASSERT_STATUS(ogk_thrust_cmd_to_rtn(&in, &nav, &rtn), OGK_OK);
        OGK_ASSERT_STATUS(ogk_cpd_input_from_thrust_cmd(&cpd_b, &rtn, &nav), OGK_OK);
        OGK_ASSERT_NEAR(cpd_a.alpha_c, cpd_b.alpha_c, 0.0);
        OGK_ASSERT_NEAR(cpd_a.beta_c, cpd_b.beta_c, 0.0);
        OGK_ASSERT_NEAR(cpd_a.xi, (ogk_real_t)1.1, 0.0);
        OGK_ASSERT_NEAR(cpd_a.phi, (ogk_real_t)-0.2, 0.0);
        {
            /* the direction CPD gets is the inertial one (r-t-n axes built here) */
            ogk_real_t r[3];
            ogk_real_t t[3];
            ogk_real_t n[3];
            ogk_real_t d[3];
            rtn_axes(nav.xi_rad, nav.phi_rad, r, t, n);
            for (k = 0u; k < 3u; ++k) {
                d[k] = (cos(cpd_a.beta_c) * sin(cpd_a.alpha_c) * r[k]) +
                       (cos(cpd_a.beta_c) * cos(cpd_a.alpha_c) * t[k]) + (sin(cpd_a.beta_c) * n[k]);
            }
            OGK_ASSERT_NEAR(angle_between(d, in.u), 0.0, OGK_TEST_TOL(1e-14, CMD_EPS));
        }
        OGK_ASSERT_STATUS(ogk_cpd_input_from_thrust_cmd(&cpd_b, &syn, &nav), OGK_E_FRAME);
        OGK_ASSERT_NEAR(cpd_b.alpha_c, cpd_a.alpha_c, 0.0); /* untouched */
    }
    /* in place, and the rejections (out untouched) */
    in = syn;
    OGK_ASSERT_STATUS(ogk_thrust_cmd_synodic_to_inertial(&in, 0.3, &in), OGK_OK);
    assert_int_equal((int)in.frame, (int)OGK_FRAME_INERTIAL);
    keep = in;
    OGK_ASSERT_STATUS(ogk_thrust_cmd_synodic_to_inertial(NULL, 0.3, &in), OGK_E_NULL);
    OGK_ASSERT_STATUS(ogk_thrust_cmd_synodic_to_inertial(&syn, 0.3, NULL), OGK_E_NULL);
    OGK_ASSERT_STATUS(ogk_thrust_cmd_synodic_to_inertial(&keep, 0.3, &in), OGK_E_FRAME);
    OGK_ASSERT_STATUS(ogk_thrust_cmd_synodic_to_inertial(&syn, NAN, &in), OGK_E_NONFINITE);
    OGK_ASSERT_STATUS(ogk_thrust_cmd_synodic_to_inertial(&syn, 1e5, &in), OGK_E_RANGE);
    syn.u[0] = 3.0;
    OGK_ASSERT_STATUS(ogk_thrust_cmd_synodic_to_inertial(&syn, 0.3, &in), OGK_E_RANGE);
    syn.u[0] = 0.48;
    syn.throttle = -1.0;
    OGK_ASSERT_STATUS(ogk_thrust_cmd_synodic_to_inertial(&syn, 0.3, &in), OGK_E_RANGE);
    assert_true(memcmp(&in, &keep, sizeof in) == 0);
}

/* CPD from any law: the r-t-n and inertial forms of one direction give the same CPD output. */
/* req: OGK-CPD-010 */
static void test_cpd_same_output_from_either_frame(void **state)
{
    ogk_cpd_config_t cfg;
    ogk_cpd_t ctx_a;
    ogk_cpd_t ctx_b;
    ogk_cpd_output_t out_a;
    ogk_cpd_output_t out_b;
    ogk_cpd_input_t in_a;
    ogk_cpd_input_t in_b;
    ogk_thrust_cmd_t rtn;
    ogk_thrust_cmd_t inert;
    ogk_nav_state_t nav;
    ogk_real_t r[3];
    ogk_real_t t[3];
    ogk_real_t n[3];
    ogk_real_t u_i[3];
    size_t k;
    (void)state;
    OGK_ASSERT_STATUS(ogk_cpd_config_default(&cfg), OGK_OK);
    OGK_ASSERT_STATUS(ogk_cpd_init(&ctx_a, &cfg), OGK_OK);
    OGK_ASSERT_STATUS(ogk_cpd_init(&ctx_b, &cfg), OGK_OK);
    (void)memset(&nav, 0, sizeof nav);
    nav.xi_rad = 0.9;
    nav.phi_rad = 0.05;
    OGK_ASSERT_STATUS(ogk_thrust_cmd_from_angles(1.0, 0.25, -0.1, 1.0, OGK_THRUST_FLAG_ENGINE_ON, 0u, &rtn),
                      OGK_OK);
    rtn_axes(nav.xi_rad, nav.phi_rad, r, t, n);
    for (k = 0u; k < 3u; ++k) {
        u_i[k] = (rtn.u[0] * r[k]) + (rtn.u[1] * t[k]) + (rtn.u[2] * n[k]);
    }
    OGK_ASSERT_STATUS(ogk_thrust_cmd_from_unit(1.0, OGK_FRAME_INERTIAL, u_i, 1.0, OGK_THRUST_FLAG_ENGINE_ON,
                                               0u, &inert), OGK_OK);
    (void)memset(&in_a, 0, sizeof in_a);
    in_a.theta = 0.3;
    in_a.psi = -0.2;
    in_a.rate_q = 0.01;
    in_b = in_a;
    OGK_ASSERT_STATUS(ogk_cpd_input_from_thrust_cmd(&in_a, &rtn, &nav), OGK_OK);
    OGK_ASSERT_STATUS(ogk_cpd_input_from_thrust_cmd(&in_b, &inert, &nav), OGK_OK);
    OGK_ASSERT_NEAR(in_b.alpha_c, 0.25, OGK_TEST_TOL(1e-14, CMD_EPS));
    OGK_ASSERT_NEAR(in_b.beta_c, -0.1, OGK_TEST_TOL(1e-14, CMD_EPS));
    OGK_ASSERT_STATUS(ogk_cpd_step(&ctx_a, &in_a, &out_a), OGK_OK);
    OGK_ASSERT_STATUS(ogk_cpd_step(&ctx_b, &in_b, &out_b), OGK_OK);
    OGK_ASSERT_NEAR(out_b.delta_yc, out_a.delta_yc, 1e-12);
    OGK_ASSERT_NEAR(out_b.delta_zc, out_a.delta_zc, 1e-12);
    OGK_ASSERT_NEAR(out_b.theta_c, out_a.theta_c, OGK_TEST_TOL(1e-13, CMD_EPS));
    OGK_ASSERT_NEAR(out_b.psi_c, out_a.psi_c, OGK_TEST_TOL(1e-13, CMD_EPS));
    /* the rejections CPD adds: a NaN position with an r-t-n command; a non-unit inertial u */
    nav.phi_rad = NAN;
    OGK_ASSERT_STATUS(ogk_cpd_input_from_thrust_cmd(&in_a, &rtn, &nav), OGK_E_NONFINITE);
    nav.phi_rad = 0.05;
    nav.xi_rad = INFINITY;
    OGK_ASSERT_STATUS(ogk_cpd_input_from_thrust_cmd(&in_a, &rtn, &nav), OGK_E_NONFINITE);
    nav.xi_rad = 0.9;
    OGK_ASSERT_NEAR(in_a.alpha_c, 0.25, 0.0); /* untouched */
    inert.u[2] += 0.1;
    OGK_ASSERT_STATUS(ogk_cpd_input_from_thrust_cmd(&in_b, &inert, &nav), OGK_E_RANGE);
    OGK_ASSERT_NEAR(in_b.beta_c, -0.1, OGK_TEST_TOL(1e-14, CMD_EPS)); /* untouched */
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_angles_and_unit_vectors),
        cmocka_unit_test(test_angle_and_vector_rejections),
        cmocka_unit_test(test_builders),
        cmocka_unit_test(test_inertial_to_rtn),
        cmocka_unit_test(test_to_rtn_frames_and_rejections),
        cmocka_unit_test(test_synodic_to_inertial_and_cpd),
        cmocka_unit_test(test_cpd_same_output_from_either_frame),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
