/* test_cpd.c -- CPD attitude control (Pontani & Celani 2021, sec. 5) against
 * independent references.
 *
 * The kernel builds its frames from the paper's matrix products (R1, R2, R3,
 * R_A). Here every frame is built from vectors instead: r-t-n from the
 * right ascension / declination formulas, the a frame from a1 = c2,
 * a2 = -c3, a3 = -c1, and the body axes by turning the a axes with Rodrigues'
 * formula about the current 3rd, 2nd, then 1st axis (yaw, pitch, roll). The
 * dynamics used in the closed-loop checks are eqs. (10)-(18) / (42)-(44),
 * integrated here with a local RK4.
 *
 * Both precisions (ogk_test.h): the random angles are drawn as the kernel
 * has them (ogk_real_t), so the double references measure the kernel alone.
 * In float, a unit vector or an angle made of sines and cosines of float
 * angles carries a few eps each: CPD_EPS = 16 eps (an angle near pi: times
 * pi); an error of size s, 16 eps s. Where a float input cannot stand
 * exactly on a singular direction (pi, pi/2 are not floats) the test says
 * what the kernel does there. Gains and rates near the type's overflow are
 * float's (1e30, 1e38). */
#include "ogk_test.h"

#include <string.h>

#include "ogk/cpd.h"

#define PI 3.14159265358979323846
#define DEG (PI / 180.0)
#define PI_R ((ogk_real_t)PI) /* pi as the build has it: the ends of the range (-pi, pi] */
#define CPD_EPS (16.0 * FLT_EPSILON)

/* LEO-to-GEO vehicle (sec. 6, Tables 1-2) at ignition; T = n0 m0 with
 * n0 = 1.112 g0. */
#define THRUST_N (1.112 * 9.80665 * 2400.0)
#define ARM_M 0.25
#define IX_KG_M2 1200.0
#define IY_KG_M2 800.0
#define IZ_KG_M2 800.0
#define TAU_S 0.1
#define MXC_MAX_N_M 30.0
#define DELTA_C_MAX_RAD (0.65 * DEG)
#define MX_MAX_N_M 60.0
#define DELTA_MAX_RAD (3.0 * DEG)

/* ---------------------------------------------------------------- vectors */
typedef struct {
    double v[3];
} vec3;

static vec3 v3(double x, double y, double z)
{
    vec3 r;
    r.v[0] = x;
    r.v[1] = y;
    r.v[2] = z;
    return r;
}

static double dot(vec3 a, vec3 b)
{
    return a.v[0] * b.v[0] + a.v[1] * b.v[1] + a.v[2] * b.v[2];
}

static vec3 cross(vec3 a, vec3 b)
{
    return v3(a.v[1] * b.v[2] - a.v[2] * b.v[1], a.v[2] * b.v[0] - a.v[0] * b.v[2],
              a.v[0] * b.v[1] - a.v[1] * b.v[0]);
}

static vec3 add(vec3 a, vec3 b)
{
    return v3(a.v[0] + b.v[0], a.v[1] + b.v[1], a.v[2] + b.v[2]);
}

static vec3 scale(vec3 a, double s)
{
    return v3(s * a.v[0], s * a.v[1], s * a.v[2]);
}

static double norm(vec3 a)
{
    return sqrt(dot(a, a));
}

/* Rodrigues: v turned by angle (right hand) about the unit axis k. */
static vec3 rodrigues(vec3 v, vec3 k, double angle)
{
    return add(add(scale(v, cos(angle)), scale(cross(k, v), sin(angle))),
               scale(k, dot(k, v) * (1.0 - cos(angle))));
}

static void assert_vec_near(vec3 a, vec3 b, double tol)
{
    OGK_ASSERT_NEAR(a.v[0], b.v[0], tol);
    OGK_ASSERT_NEAR(a.v[1], b.v[1], tol);
    OGK_ASSERT_NEAR(a.v[2], b.v[2], tol);
}

/* ---------------------------------------------------------------- frames (c components) */
typedef struct {
    vec3 x, y, z;
} triad;

static triad a_frame(void)
{
    triad a;
    a.x = v3(0.0, 1.0, 0.0);  /* a1 = c2 */
    a.y = v3(0.0, 0.0, -1.0); /* a2 = -c3 */
    a.z = v3(-1.0, 0.0, 0.0); /* a3 = -c1 */
    return a;
}

/* Body axes: yaw about a3, pitch about the new 2nd axis, roll about the new
 * 1st axis, each a counterclockwise frame rotation (eq. 9). */
static triad body_frame(double psi, double theta, double phi_roll)
{
    triad b = a_frame();
    b.x = rodrigues(b.x, b.z, psi);
    b.y = rodrigues(b.y, b.z, psi);
    b.x = rodrigues(b.x, b.y, theta);
    b.z = rodrigues(b.z, b.y, theta);
    b.y = rodrigues(b.y, b.x, phi_roll);
    b.z = rodrigues(b.z, b.x, phi_roll);
    return b;
}

static triad rtn_frame(double xi, double phi)
{
    triad f;
    f.x = v3(cos(phi) * cos(xi), cos(phi) * sin(xi), sin(phi)); /* r */
    f.y = v3(-sin(xi), cos(xi), 0.0);                          /* t */
    f.z = cross(f.x, f.y);                                     /* n = r x t */
    return f;
}

static vec3 thrust_dir(double alpha, double beta, double xi, double phi)
{
    const triad f = rtn_frame(xi, phi);
    return add(add(scale(f.x, cos(beta) * sin(alpha)), scale(f.y, cos(beta) * cos(alpha))),
               scale(f.z, sin(beta)));
}

/* ---------------------------------------------------------------- random numbers (LCG) */
static double uniform(uint64_t *s, double lo, double hi)
{
    *s = *s * 6364136223846793005ull + 1442695040888963407ull;
    return lo + (hi - lo) * ((double)(*s >> 11) / 9007199254740992.0);
}

/* ---------------------------------------------------------------- configurations */
/* Sec. 5.3 gains re-derived with G_y = T l0 / I_y0 = 8.18 s^-2 (docs/design/cpd.md). */
static ogk_cpd_config_t rederived_config(ogk_cpd_pointing_t mode)
{
    const double wn = 4.24;
    const double zeta = 0.707;
    const double g_y = THRUST_N * ARM_M / IY_KG_M2;
    const double g_x = 1.0 / IX_KG_M2;
    ogk_cpd_config_t c;
    memset(&c, 0, sizeof(c));
    c.k_px = wn * wn / g_x;
    c.k_dx = 2.0 * zeta * wn / g_x;
    c.k_py = wn * wn / g_y;
    c.k_dy = 2.0 * zeta * wn / g_y;
    c.k_pz = c.k_py;
    c.k_dz = c.k_dy;
    c.m_xc_max = MXC_MAX_N_M;
    c.delta_yc_max = DELTA_C_MAX_RAD;
    c.delta_zc_max = DELTA_C_MAX_RAD;
    c.tau_x = TAU_S;
    c.tau_y = TAU_S;
    c.tau_z = TAU_S;
    c.phi_c = 0.0;
    c.pointing = mode;
    return c;
}

/* Gains as printed after eq. (54). */
static ogk_cpd_config_t printed_config(ogk_cpd_pointing_t mode)
{
    ogk_cpd_config_t c = rederived_config(mode);
    c.k_px = 21.6e3;
    c.k_dx = 7.2e3;
    c.k_py = 21.6;
    c.k_dy = 7.20;
    c.k_pz = 21.6;
    c.k_dz = 7.20;
    return c;
}

static ogk_cpd_input_t zero_input(void)
{
    ogk_cpd_input_t in;
    memset(&in, 0, sizeof(in));
    return in;
}

/* ================================================================ geometry */

/* Eqs. (38)-(39): x_b along the commanded direction, for any roll. */
/* req: OGK-CPD-002 */
static void test_commanded_attitude_points_x_body(void **state)
{
    uint64_t seed = 12345u;
    int k;
    (void)state;
    for (k = 0; k < 500; ++k) {
        const ogk_real_t alpha = uniform(&seed, -PI, PI);
        const ogk_real_t beta = uniform(&seed, -0.49 * PI, 0.49 * PI);
        const ogk_real_t xi = uniform(&seed, -PI, PI);
        const ogk_real_t phi = uniform(&seed, -0.49 * PI, 0.49 * PI);
        const ogk_real_t roll = uniform(&seed, -PI, PI);
        ogk_real_t psi_c = 99.0;
        ogk_real_t theta_c = 99.0;
        triad b;
        OGK_ASSERT_STATUS(ogk_cpd_commanded_attitude(alpha, beta, xi, phi, &psi_c, &theta_c),
                          OGK_OK);
        assert_true(psi_c > -PI_R && psi_c <= PI_R);
        assert_true(theta_c >= -0.5 * PI_R && theta_c <= 0.5 * PI_R);
        b = body_frame(psi_c, theta_c, roll);
        assert_vec_near(b.x, thrust_dir(alpha, beta, xi, phi), OGK_TEST_TOL(1e-13, CPD_EPS));
    }
}

/* The paper's nominal geometry: at xi = phi = 0, alpha_c turns the vehicle in
 * pitch and beta_c in yaw (a1 = c2 = t). */
/* req: OGK-CPD-002 */
static void test_commanded_attitude_known_values(void **state)
{
    ogk_real_t psi_c;
    ogk_real_t theta_c;
    (void)state;
    OGK_ASSERT_STATUS(ogk_cpd_commanded_attitude(0.0, 0.0, 0.0, 0.0, &psi_c, &theta_c), OGK_OK);
    OGK_ASSERT_NEAR(psi_c, 0.0, OGK_TEST_TOL(1e-15, CPD_EPS));
    OGK_ASSERT_NEAR(theta_c, 0.0, OGK_TEST_TOL(1e-15, CPD_EPS));
    /* T = sin a c1 + cos a c2 = cos a a1 - sin a a3: pitch up by alpha */
    OGK_ASSERT_STATUS(ogk_cpd_commanded_attitude(0.3, 0.0, 0.0, 0.0, &psi_c, &theta_c), OGK_OK);
    OGK_ASSERT_NEAR(psi_c, 0.0, OGK_TEST_TOL(1e-15, CPD_EPS));
    OGK_ASSERT_NEAR(theta_c, 0.3, OGK_TEST_TOL(1e-15, CPD_EPS));
    /* T = cos b c2 + sin b c3 = cos b a1 - sin b a2: yaw by -beta */
    OGK_ASSERT_STATUS(ogk_cpd_commanded_attitude(0.0, 0.2, 0.0, 0.0, &psi_c, &theta_c), OGK_OK);
    OGK_ASSERT_NEAR(psi_c, -0.2, OGK_TEST_TOL(1e-15, CPD_EPS));
    OGK_ASSERT_NEAR(theta_c, 0.0, OGK_TEST_TOL(1e-15, CPD_EPS));
    /* along t at right ascension xi: t = (-sin xi, cos xi, 0) = cos xi a1 + sin xi a3,
     * i.e. pitch -xi (eq. 38) */
    OGK_ASSERT_STATUS(ogk_cpd_commanded_attitude(0.0, 0.0, 0.4, 0.0, &psi_c, &theta_c), OGK_OK);
    OGK_ASSERT_NEAR(psi_c, 0.0, OGK_TEST_TOL(1e-15, CPD_EPS));
    OGK_ASSERT_NEAR(theta_c, -0.4, OGK_TEST_TOL(1e-15, CPD_EPS));
    /* along a3 = -c1 (alpha = -90 deg at xi = phi = 0): yaw undefined -> 0 */
    OGK_ASSERT_STATUS(ogk_cpd_commanded_attitude(-0.5 * PI, 0.0, 0.0, 0.0, &psi_c, &theta_c),
                      OGK_OK);
#if OGK_REAL_SINGLE
    /* In float -pi/2 is not a float: the direction lies 4.4e-8 rad off a3,
     * beyond the yaw-undefined threshold (CPD_YAW_EPS, 1e-12 rad in both
     * builds), so the yaw is defined there and any value of it points x_b
     * along the same direction: theta_c is -pi/2 to float's resolution and the
     * body axis lands on the commanded direction. */
    OGK_ASSERT_NEAR(theta_c, -0.5 * PI, OGK_TEST_TOL(1e-15, CPD_EPS));
    assert_vec_near(body_frame(psi_c, theta_c, 0.0).x, thrust_dir(-0.5 * PI_R, 0.0, 0.0, 0.0), CPD_EPS);
#else
    OGK_ASSERT_NEAR(psi_c, 0.0, 0.0);
    OGK_ASSERT_NEAR(theta_c, -0.5 * PI, 1e-15);
#endif
}

/* Eqs. (49)-(52): zero deflection at the commanded attitude gives back the
 * commanded angles; any deflection gives the direction of eq. (50) built from
 * the independent body axes. */
/* req: OGK-CPD-003 */
static void test_thrust_angles_round_trip_and_deflection(void **state)
{
    uint64_t seed = 777u;
    int k;
    (void)state;
    for (k = 0; k < 300; ++k) {
        const ogk_real_t alpha = uniform(&seed, -0.99 * PI, 0.99 * PI);
        const ogk_real_t beta = uniform(&seed, -0.45 * PI, 0.45 * PI);
        const ogk_real_t xi = uniform(&seed, -PI, PI);
        const ogk_real_t phi = uniform(&seed, -0.45 * PI, 0.45 * PI);
        const ogk_real_t roll = uniform(&seed, -PI, PI);
        const ogk_real_t dy = uniform(&seed, -0.3, 0.3);
        const ogk_real_t dz = uniform(&seed, -0.3, 0.3);
        ogk_real_t psi_c;
        ogk_real_t theta_c;
        ogk_real_t alpha_a;
        ogk_real_t beta_a;
        triad b;
        vec3 d;
        OGK_ASSERT_STATUS(ogk_cpd_commanded_attitude(alpha, beta, xi, phi, &psi_c, &theta_c),
                          OGK_OK);
        OGK_ASSERT_STATUS(ogk_cpd_thrust_angles(psi_c, theta_c, roll, xi, phi, 0.0, 0.0,
                                                &alpha_a, &beta_a),
                          OGK_OK);
        /* float: CPD_EPS, alpha divided by cos(beta) (>= 0.16 here) */
        OGK_ASSERT_NEAR(alpha_a, alpha, OGK_TEST_TOL(1e-12, CPD_EPS / cos(beta)));
        OGK_ASSERT_NEAR(beta_a, beta, OGK_TEST_TOL(1e-12, CPD_EPS));

        /* large deflection: compare directions, built independently */
        OGK_ASSERT_STATUS(ogk_cpd_thrust_angles(psi_c, theta_c, roll, xi, phi, dy, dz,
                                                &alpha_a, &beta_a),
                          OGK_OK);
        b = body_frame(psi_c, theta_c, roll);
        d = add(add(scale(b.x, cos(dz) * cos(dy)), scale(b.y, sin(dz))),
                scale(b.z, cos(dz) * sin(dy)));
        assert_vec_near(thrust_dir(alpha_a, beta_a, xi, phi), d, OGK_TEST_TOL(1e-13, CPD_EPS));
        assert_true(alpha_a > -PI_R && alpha_a <= PI_R);
        assert_true(beta_a >= -0.5 * PI_R && beta_a <= 0.5 * PI_R);
    }
}

/* The branch cut of the documented ranges psi_c, alpha_a in (-pi, pi]: a
 * direction straight behind (along -a1, or -t) has yaw / in-plane angle +pi,
 * also when rounding hands atan2 a -0 or a -1e-16 that makes it return -pi.
 * Commanded: (alpha, beta) = (0, pi) at xi = phi = 0 is -t = -c2 = -a1 (its
 * n-component sin(pi) = 1.2e-16 is the rounding), so psi_c = pi, theta_c = 0.
 * Actual: zero attitude puts x_b on a1 = c2, which at xi = -pi is -t(xi), so
 * alpha_a = pi, beta_a = 0 (the same as at xi = +pi). In float pi is not a
 * float (PI_R = pi + 8.7e-8): the commanded direction's rounding leak is
 * 8.7e-8 rad, and at xi = +PI_R the actual direction lies 8.7e-8 rad past
 * the cut, where -pi + 8.7e-8 is its in-plane angle; both ends are within
 * CPD_EPS pi of pi in magnitude. */
/* req: OGK-CPD-003 */
static void test_thrust_angles_branch_cut(void **state)
{
    ogk_real_t psi_c;
    ogk_real_t theta_c;
    ogk_real_t alpha_a;
    ogk_real_t beta_a;
    (void)state;
    OGK_ASSERT_STATUS(ogk_cpd_commanded_attitude(0.0, PI, 0.0, 0.0, &psi_c, &theta_c), OGK_OK);
    OGK_ASSERT_NEAR(psi_c, PI, OGK_TEST_TOL(1e-15, CPD_EPS * PI));
    OGK_ASSERT_NEAR(theta_c, 0.0, OGK_TEST_TOL(1e-15, CPD_EPS));
    OGK_ASSERT_STATUS(ogk_cpd_commanded_attitude(PI, 0.0, 0.0, 0.0, &psi_c, &theta_c), OGK_OK);
    OGK_ASSERT_NEAR(psi_c, PI, OGK_TEST_TOL(1e-15, CPD_EPS * PI));
    OGK_ASSERT_NEAR(theta_c, 0.0, OGK_TEST_TOL(1e-15, CPD_EPS));
    OGK_ASSERT_STATUS(ogk_cpd_thrust_angles(0.0, 0.0, 0.0, -PI, 0.0, 0.0, 0.0, &alpha_a, &beta_a),
                      OGK_OK);
    OGK_ASSERT_NEAR(alpha_a, PI, OGK_TEST_TOL(1e-15, CPD_EPS * PI));
    OGK_ASSERT_NEAR(beta_a, 0.0, OGK_TEST_TOL(1e-15, CPD_EPS));
    assert_vec_near(thrust_dir(alpha_a, beta_a, -PI_R, 0.0), a_frame().x, OGK_TEST_TOL(1e-15, CPD_EPS));
    OGK_ASSERT_STATUS(ogk_cpd_thrust_angles(0.0, 0.0, 0.0, PI, 0.0, 0.0, 0.0, &alpha_a, &beta_a),
                      OGK_OK);
#if OGK_REAL_SINGLE
    OGK_ASSERT_NEAR(fabs(alpha_a), PI, CPD_EPS * PI);
#else
    OGK_ASSERT_NEAR(alpha_a, PI, 1e-15);
#endif
    OGK_ASSERT_NEAR(beta_a, 0.0, OGK_TEST_TOL(1e-15, CPD_EPS));
}

/* Small deflections: d alpha, d beta from the first-order expansion of eq. (52)
 * with dT = Dz y_b + Dy z_b. Float: d = 1e-3 (1e-6 is four ulps of an angle
 * near pi there): the second-order terms, d^2 / cos^2 beta, and the angles'
 * rounding bound the expansion's error (below). */
/* req: OGK-CPD-003 */
static void test_thrust_angles_small_deflection(void **state)
{
    const double d = OGK_TEST_PICK(1.0e-6, 1.0e-3);
    uint64_t seed = 4242u;
    int k;
    ogk_real_t alpha_a;
    ogk_real_t beta_a;
    (void)state;
    /* nominal geometry: x_b = t, y_b = -n, z_b = -r -> d alpha = -Dy, d beta = -Dz */
    OGK_ASSERT_STATUS(ogk_cpd_thrust_angles(0.0, 0.0, 0.0, 0.0, 0.0, d, 0.0, &alpha_a, &beta_a),
                      OGK_OK);
    /* a pure rotation here: exact but for rounding (float: 16 eps of d) */
    OGK_ASSERT_NEAR(alpha_a, -d, OGK_TEST_TOL(1e-18, CPD_EPS * d));
    OGK_ASSERT_NEAR(beta_a, 0.0, OGK_TEST_TOL(1e-18, CPD_EPS * d));
    OGK_ASSERT_STATUS(ogk_cpd_thrust_angles(0.0, 0.0, 0.0, 0.0, 0.0, 0.0, d, &alpha_a, &beta_a),
                      OGK_OK);
    OGK_ASSERT_NEAR(alpha_a, 0.0, OGK_TEST_TOL(1e-18, CPD_EPS * d));
    OGK_ASSERT_NEAR(beta_a, -d, OGK_TEST_TOL(1e-18, CPD_EPS * d));
    /* 90 deg of roll swaps the roles: y_b = -r, z_b = +n */
    OGK_ASSERT_STATUS(ogk_cpd_thrust_angles(0.0, 0.0, 0.5 * PI, 0.0, 0.0, d, 0.0, &alpha_a,
                                            &beta_a),
                      OGK_OK);
    /* float: the roll pi/2 is not a float either (cos = 4.4e-8): CPD_EPS d */
    OGK_ASSERT_NEAR(alpha_a, 0.0, OGK_TEST_TOL(1e-17, CPD_EPS * d));
    OGK_ASSERT_NEAR(beta_a, d, OGK_TEST_TOL(1e-17, CPD_EPS * d));

    for (k = 0; k < 100; ++k) {
        const ogk_real_t alpha = uniform(&seed, -PI, PI);
        const ogk_real_t beta = uniform(&seed, -1.2, 1.2);
        const ogk_real_t xi = uniform(&seed, -PI, PI);
        const ogk_real_t phi = uniform(&seed, -1.2, 1.2);
        const ogk_real_t roll = uniform(&seed, -PI, PI);
        const ogk_real_t dy = uniform(&seed, -d, d);
        const ogk_real_t dz = uniform(&seed, -d, d);
        const triad f = rtn_frame(xi, phi);
        ogk_real_t psi_c;
        ogk_real_t theta_c;
        triad b;
        vec3 dt;
        vec3 du_dalpha;
        vec3 du_dbeta;
        double exp_da;
        double exp_db;
        OGK_ASSERT_STATUS(ogk_cpd_commanded_attitude(alpha, beta, xi, phi, &psi_c, &theta_c),
                          OGK_OK);
        OGK_ASSERT_STATUS(ogk_cpd_thrust_angles(psi_c, theta_c, roll, xi, phi, dy, dz,
                                                &alpha_a, &beta_a),
                          OGK_OK);
        b = body_frame(psi_c, theta_c, roll);
        dt = add(scale(b.y, dz), scale(b.z, dy));
        /* du/dalpha = cos b (cos a r - sin a t), |.| = cos b; du/dbeta unit */
        du_dalpha = scale(add(scale(f.x, cos(alpha)), scale(f.y, -sin(alpha))), cos(beta));
        du_dbeta = add(add(scale(f.x, -sin(beta) * sin(alpha)),
                           scale(f.y, -sin(beta) * cos(alpha))),
                       scale(f.z, cos(beta)));
        exp_da = dot(dt, du_dalpha) / (cos(beta) * cos(beta));
        exp_db = dot(dt, du_dbeta);
        /* float: the second order, d^2 / cos^2 beta (x 10), and the rounding
         * of the two angles near pi, CPD_EPS pi / cos beta */
        OGK_ASSERT_NEAR(alpha_a - alpha, exp_da,
                        OGK_TEST_TOL(1e-11, ((10.0 * d * d) + (CPD_EPS * PI)) / (cos(beta) * cos(beta))));
        OGK_ASSERT_NEAR(beta_a - beta, exp_db,
                        OGK_TEST_TOL(1e-11, ((10.0 * d * d) + (CPD_EPS * PI)) / (cos(beta) * cos(beta))));
        /* and the change is really first order (not zero by accident) */
        assert_true(fabs(alpha_a - alpha) + fabs(beta_a - beta) > 1e-3 * d);
    }
}

/* ================================================================ pointing error */

/* Body-mode error: magnitude = true angle between x_b and T_c; rotating x_b
 * about the error vector by its magnitude lands on T_c; same magnitude for
 * every roll, and the vector turns with roll as a body-fixed vector must. */
/* req: OGK-CPD-004 */
static void test_body_pointing_error_geometry(void **state)
{
    uint64_t seed = 99u;
    const double rolls[6] = {0.0, 30.0 * DEG, 90.0 * DEG, 135.0 * DEG, PI, -120.0 * DEG};
    int k;
    size_t j;
    (void)state;
    for (k = 0; k < 200; ++k) {
        const ogk_real_t alpha = uniform(&seed, -PI, PI);
        const ogk_real_t beta = uniform(&seed, -1.4, 1.4);
        const ogk_real_t xi = uniform(&seed, -PI, PI);
        const ogk_real_t phi = uniform(&seed, -1.4, 1.4);
        const ogk_real_t psi = uniform(&seed, -PI, PI);
        const ogk_real_t theta = uniform(&seed, -1.4, 1.4);
        const vec3 tc = thrust_dir(alpha, beta, xi, phi);
        double ey0 = 0.0;
        double ez0 = 0.0;
        for (j = 0u; j < 6u; ++j) {
            const triad b = body_frame(psi, theta, rolls[j]);
            const double true_angle = atan2(norm(cross(b.x, tc)), dot(b.x, tc));
            ogk_real_t ey;
            ogk_real_t ez;
            double mag;
            OGK_ASSERT_STATUS(ogk_cpd_pointing_error_body(psi, theta, rolls[j], alpha, beta, xi,
                                                          phi, &ey, &ez),
                              OGK_OK);
            mag = hypot(ey, ez);
            OGK_ASSERT_NEAR(mag, true_angle, OGK_TEST_TOL(1e-12, CPD_EPS * PI));
            if (mag > 1e-9) {
                const vec3 axis = scale(add(scale(b.y, ey), scale(b.z, ez)), 1.0 / mag);
                assert_vec_near(rodrigues(b.x, axis, mag), tc, OGK_TEST_TOL(1e-12, CPD_EPS * PI));
            }
            if (j == 0u) {
                ey0 = ey;
                ez0 = ez;
            } else {
                /* a vector fixed in space seen from axes rolled by Phi */
                const double c = cos(rolls[j]);
                const double s = sin(rolls[j]);
                OGK_ASSERT_NEAR(ey, c * ey0 + s * ez0, OGK_TEST_TOL(1e-11, CPD_EPS * PI));
                OGK_ASSERT_NEAR(ez, -s * ey0 + c * ez0, OGK_TEST_TOL(1e-11, CPD_EPS * PI));
            }
        }
    }
}

/* Small errors at zero roll: body mode = Euler differences (the signs of eq. 46). */
/* req: OGK-CPD-004 */
static void test_body_error_matches_euler_near_zero_roll(void **state)
{
    ogk_real_t psi_c;
    ogk_real_t theta_c;
    ogk_real_t ey;
    ogk_real_t ez;
    (void)state;
    OGK_ASSERT_STATUS(ogk_cpd_commanded_attitude(0.2, -0.1, 0.3, 0.05, &psi_c, &theta_c), OGK_OK);
    /* pure pitch offset: exact */
    OGK_ASSERT_STATUS(ogk_cpd_pointing_error_body(psi_c, theta_c - 0.7, 0.0, 0.2, -0.1, 0.3,
                                                  0.05, &ey, &ez),
                      OGK_OK);
    OGK_ASSERT_NEAR(ey, 0.7, OGK_TEST_TOL(1e-14, CPD_EPS));
    OGK_ASSERT_NEAR(ez, 0.0, OGK_TEST_TOL(1e-14, CPD_EPS));
    /* pure yaw offset at zero pitch: exact */
    OGK_ASSERT_STATUS(ogk_cpd_pointing_error_body(-0.8, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, &ey, &ez),
                      OGK_OK);
    OGK_ASSERT_NEAR(ey, 0.0, OGK_TEST_TOL(1e-15, CPD_EPS));
    OGK_ASSERT_NEAR(ez, 0.8, OGK_TEST_TOL(1e-15, CPD_EPS));
    /* small mixed offset: first order */
    OGK_ASSERT_STATUS(ogk_cpd_pointing_error_body(psi_c - 1e-5, theta_c + 2e-5, 0.0, 0.2, -0.1,
                                                  0.3, 0.05, &ey, &ez),
                      OGK_OK);
    /* float: the offsets are rounded at the angles' ulp (3e-8 at 0.3): 4 of them */
    OGK_ASSERT_NEAR(ey, -2e-5, OGK_TEST_TOL(1e-9, 4.0 * FLT_EPSILON * 0.3));
    OGK_ASSERT_NEAR(ez, 1e-5 * cos(theta_c), OGK_TEST_TOL(1e-9, 4.0 * FLT_EPSILON * 0.3));
    /* at 180 deg of roll both signs flip: the Euler differences do not */
    OGK_ASSERT_STATUS(ogk_cpd_pointing_error_body(psi_c, theta_c - 0.01, PI, 0.2, -0.1, 0.3,
                                                  0.05, &ey, &ez),
                      OGK_OK);
    /* float: the roll pi leaks sin(PI_R) = 8.7e-8 of the error into the other axis */
    OGK_ASSERT_NEAR(ey, -0.01, OGK_TEST_TOL(1e-14, CPD_EPS * 0.01));
    OGK_ASSERT_NEAR(ez, 0.0, OGK_TEST_TOL(1e-14, CPD_EPS * 0.01));
}

/* req: OGK-CPD-004 */
/* Found by Frama-C EVA (docs/evidence/eva.md): a commanded direction behind x_b to
 * within a subnormal lateral component. xi = pi turns r-t-n half-way round
 * (cos = -1, sin(pi) = s = 1.22e-16); alpha = -s cancels the s leak exactly
 * (cb s - s cb = 0) and beta = 1e-310 leaves t_b = (-1, -1e-310, -0), so
 * hypot = 1e-310 and the rotation angle is pi: angle / lateral overflowed to
 * inf and the error came back (NaN, -inf) with OGK_OK. The true error is a
 * half turn about an axis normal to x_b: magnitude pi, finite. Float: the
 * float sine of PI_R (-8.7e-8) and a float subnormal beta (1e-40). */
static void test_body_error_behind_subnormal_lateral(void **state)
{
    const double s = OGK_TEST_PICK(sin(PI), (double)sinf(PI_R));
    ogk_real_t ey = 0.0;
    ogk_real_t ez = 0.0;
    (void)state;
    OGK_ASSERT_STATUS(ogk_cpd_pointing_error_body(0.0, 0.0, 0.0, -s, OGK_TEST_PICK(1e-310, 1e-40), PI, 0.0,
                                                  &ey, &ez),
                      OGK_OK);
    assert_true(isfinite(ey) && isfinite(ez));
    OGK_ASSERT_NEAR(hypot(ey, ez), PI, OGK_TEST_TOL(1e-15, CPD_EPS * PI));
}

/* Commanded direction behind the vehicle: error magnitude near pi, flagged,
 * deflections saturated; exactly behind -> (pi, 0). */
/* req: OGK-CPD-004 */
static void test_body_error_behind(void **state)
{
    ogk_cpd_t ctx;
    ogk_cpd_config_t cfg = rederived_config(OGK_CPD_POINTING_BODY);
    ogk_cpd_input_t in = zero_input();
    ogk_cpd_output_t out;
    ogk_real_t ey;
    ogk_real_t ez;
    (void)state;
    /* x_b = a1 = t; T_c = -t (alpha = 180 deg) */
    OGK_ASSERT_STATUS(ogk_cpd_pointing_error_body(0.0, 0.0, 0.0, PI, 0.0, 0.0, 0.0, &ey, &ez),
                      OGK_OK);
#if OGK_REAL_SINGLE
    /* PI_R is 8.7e-8 past pi: a half turn either way about y_b */
    OGK_ASSERT_NEAR(fabs(ey), PI, CPD_EPS * PI);
#else
    OGK_ASSERT_NEAR(ey, PI, 1e-15);
#endif
    OGK_ASSERT_NEAR(ez, 0.0, OGK_TEST_TOL(1e-15, CPD_EPS));
    /* 170 deg away in a skew direction */
    OGK_ASSERT_STATUS(ogk_cpd_pointing_error_body(0.3, 0.2, 1.0, 0.3 + PI - 0.1, 0.1, 0.0, 0.0,
                                                  &ey, &ez),
                      OGK_OK);
    assert_true(hypot(ey, ez) > 2.5);

    OGK_ASSERT_STATUS(ogk_cpd_init(&ctx, &cfg), OGK_OK);
    in.alpha_c = PI - 0.2;
    OGK_ASSERT_STATUS(ogk_cpd_step(&ctx, &in, &out), OGK_OK);
    assert_true((out.flags & OGK_CPD_FLAG_BEHIND) != 0u);
    assert_true((out.flags & OGK_CPD_FLAG_SAT_Y) != 0u);
    OGK_ASSERT_NEAR(out.delta_yc, cfg.delta_yc_max, 0.0);
    OGK_ASSERT_NEAR(out.err_y, PI - 0.2, OGK_TEST_TOL(1e-14, CPD_EPS * PI));
    in.alpha_c = 0.2;
    OGK_ASSERT_STATUS(ogk_cpd_step(&ctx, &in, &out), OGK_OK);
    assert_true((out.flags & OGK_CPD_FLAG_BEHIND) == 0u);
    /* along a3: yaw undefined flag. Float: -pi/2 is not a float, the
     * direction lies 4.4e-8 rad off a3, beyond CPD_YAW_EPS (1e-12 rad): the
     * yaw is defined and not flagged (test_commanded_attitude_known_values) */
    in.alpha_c = -0.5 * PI;
    OGK_ASSERT_STATUS(ogk_cpd_step(&ctx, &in, &out), OGK_OK);
#if OGK_REAL_SINGLE
    assert_true((out.flags & OGK_CPD_FLAG_YAW_UNDEFINED) == 0u);
    assert_true(isfinite(out.psi_c));
#else
    assert_true((out.flags & OGK_CPD_FLAG_YAW_UNDEFINED) != 0u);
    OGK_ASSERT_NEAR(out.psi_c, 0.0, 0.0);
#endif
}

/* ================================================================ control law */

/* Linear region: outputs equal eqs. (45)-(46); each channel saturates alone at
 * +-limit with its own flag. */
/* req: OGK-CPD-001 */
static void test_control_law_and_saturation(void **state)
{
    const ogk_cpd_pointing_t modes[2] = {OGK_CPD_POINTING_BODY, OGK_CPD_POINTING_EULER};
    size_t m;
    (void)state;
    for (m = 0u; m < 2u; ++m) {
        ogk_cpd_config_t cfg = rederived_config(modes[m]);
        ogk_cpd_t ctx;
        ogk_cpd_input_t in = zero_input();
        ogk_cpd_output_t out;
        int sign;
        OGK_ASSERT_STATUS(ogk_cpd_init(&ctx, &cfg), OGK_OK);
        /* commanded pitch 0.3 (alpha_c = 0.3 at xi = phi = 0), small errors */
        in.alpha_c = 0.3;
        in.theta = 0.3 - 1e-4;
        in.psi = 2e-4;
        in.phi_roll = 1e-6;
        in.rate_p = 1e-6;
        in.rate_q = 2e-4;
        in.rate_r = -1e-4;
        OGK_ASSERT_STATUS(ogk_cpd_step(&ctx, &in, &out), OGK_OK);
        assert_int_equal(out.flags, 0);
        /* float: angles CPD_EPS (of their size); the errors are differences of
         * angles near 0.3 (ulp 3e-8), 4 of those; the commands 16 eps of their
         * size (below 1e-3) */
        OGK_ASSERT_NEAR(out.theta_c, 0.3, OGK_TEST_TOL(1e-15, CPD_EPS * 0.3));
        OGK_ASSERT_NEAR(out.psi_c, 0.0, OGK_TEST_TOL(1e-15, CPD_EPS * 0.3));
        OGK_ASSERT_NEAR(out.err_x, -1e-6, OGK_TEST_TOL(1e-15, CPD_EPS * 1e-6));
        OGK_ASSERT_NEAR(out.m_xc, cfg.k_px * -1e-6 - cfg.k_dx * 1e-6,
                        OGK_TEST_TOL(5e-11, cfg.k_px * CPD_EPS * 1e-6)); /* k_px * 1e-15 */
        /* Euler: e_y = 1e-4 exactly, e_z = -2e-4; body: first order */
        OGK_ASSERT_NEAR(out.err_y, 1e-4,
                        OGK_TEST_TOL(modes[m] == OGK_CPD_POINTING_EULER ? 1e-16 : 1e-8, 4.0 * FLT_EPSILON * 0.3));
        OGK_ASSERT_NEAR(out.err_z, -2e-4 * (modes[m] == OGK_CPD_POINTING_EULER ? 1.0 : cos(0.3)),
                        OGK_TEST_TOL(modes[m] == OGK_CPD_POINTING_EULER ? 1e-16 : 1e-8, 4.0 * FLT_EPSILON * 0.3));
        OGK_ASSERT_NEAR(out.delta_yc, cfg.k_py * out.err_y - cfg.k_dy * 2e-4, OGK_TEST_TOL(1e-15, CPD_EPS * 1e-3));
        OGK_ASSERT_NEAR(out.delta_zc, -cfg.k_pz * out.err_z + cfg.k_dz * -1e-4, OGK_TEST_TOL(1e-15, CPD_EPS * 1e-3));
        assert_true(fabs(out.delta_yc) < cfg.delta_yc_max);
        assert_true(fabs(out.delta_zc) < cfg.delta_zc_max);
        /* the context keeps the last command */
        OGK_ASSERT_NEAR(ctx.last.delta_yc, out.delta_yc, 0.0);

        for (sign = -1; sign <= 1; sign += 2) {
            ogk_cpd_input_t s = in;
            s.rate_p = -sign * 1.0; /* roll channel only */
            OGK_ASSERT_STATUS(ogk_cpd_step(&ctx, &s, &out), OGK_OK);
            assert_int_equal(out.flags, OGK_CPD_FLAG_SAT_X);
            OGK_ASSERT_NEAR(out.m_xc, sign * cfg.m_xc_max, 0.0);
            s = in;
            s.rate_q = -sign * 1.0; /* pitch channel only */
            OGK_ASSERT_STATUS(ogk_cpd_step(&ctx, &s, &out), OGK_OK);
            assert_int_equal(out.flags, OGK_CPD_FLAG_SAT_Y);
            OGK_ASSERT_NEAR(out.delta_yc, sign * cfg.delta_yc_max, 0.0);
            s = in;
            s.rate_r = sign * 1.0; /* yaw channel only */
            OGK_ASSERT_STATUS(ogk_cpd_step(&ctx, &s, &out), OGK_OK);
            assert_int_equal(out.flags, OGK_CPD_FLAG_SAT_Z);
            OGK_ASSERT_NEAR(out.delta_zc, sign * cfg.delta_zc_max, 0.0);
            /* attitude errors saturate too (10 deg) */
            s = in;
            s.theta = 0.3 - sign * 10.0 * DEG;
            s.phi_roll = -sign * 10.0 * DEG;
            s.psi = -sign * 10.0 * DEG; /* yaw error +sign*10 deg -> delta_zc = -sign*max */
            OGK_ASSERT_STATUS(ogk_cpd_step(&ctx, &s, &out), OGK_OK);
            assert_int_equal(out.flags,
                             OGK_CPD_FLAG_SAT_X | OGK_CPD_FLAG_SAT_Y | OGK_CPD_FLAG_SAT_Z);
            OGK_ASSERT_NEAR(out.m_xc, sign * cfg.m_xc_max, 0.0);
            OGK_ASSERT_NEAR(out.delta_yc, sign * cfg.delta_yc_max, 0.0);
            OGK_ASSERT_NEAR(out.delta_zc, -sign * cfg.delta_zc_max, 0.0);
        }
        /* huge finite rates: saturated, no overflow to NaN (float: 1e38) */
        in.rate_p = OGK_TEST_PICK(1e308, 1e38);
        in.rate_q = -OGK_TEST_PICK(1e308, 1e38);
        in.rate_r = OGK_TEST_PICK(1e308, 1e38);
        OGK_ASSERT_STATUS(ogk_cpd_step(&ctx, &in, &out), OGK_OK);
        OGK_ASSERT_NEAR(out.m_xc, -cfg.m_xc_max, 0.0);
        OGK_ASSERT_NEAR(out.delta_yc, cfg.delta_yc_max, 0.0);
        OGK_ASSERT_NEAR(out.delta_zc, cfg.delta_zc_max, 0.0);
    }
}

/* Euler mode wraps the roll and yaw errors: 350 deg of yaw error is -10 deg. */
/* req: OGK-CPD-004 OGK-CORE-020 */
static void test_euler_mode_wraps_errors(void **state)
{
    ogk_cpd_config_t cfg = rederived_config(OGK_CPD_POINTING_EULER);
    ogk_cpd_t ctx;
    ogk_cpd_input_t in = zero_input();
    ogk_cpd_output_t out;
    (void)state;
    cfg.phi_c = 170.0 * DEG;
    OGK_ASSERT_STATUS(ogk_cpd_init(&ctx, &cfg), OGK_OK);
    in.phi_roll = -170.0 * DEG; /* raw error 340 deg -> -20 deg */
    in.psi = -350.0 * DEG;      /* psi_c = 0: raw error 350 deg -> -10 deg */
    OGK_ASSERT_STATUS(ogk_cpd_step(&ctx, &in, &out), OGK_OK);
    OGK_ASSERT_NEAR(out.err_x, -20.0 * DEG, OGK_TEST_TOL(1e-13, CPD_EPS * PI));
    OGK_ASSERT_NEAR(out.err_z, -10.0 * DEG, OGK_TEST_TOL(1e-13, CPD_EPS * PI));
    OGK_ASSERT_NEAR(out.m_xc, -cfg.m_xc_max, 0.0);
    OGK_ASSERT_NEAR(out.delta_zc, cfg.delta_zc_max, 0.0);
    OGK_ASSERT_NEAR(out.phi_c, (ogk_real_t)(170.0 * DEG), 0.0); /* the configured value, as stored */
}

/* req: OGK-CORE-020 */
static void test_wrap_pi(void **state)
{
    const double cases[][2] = {
        {0.0, 0.0},          {PI, PI},           {-PI, PI},
        {3.0 * PI, PI},      {-3.0 * PI, PI},    {2.0 * PI, 0.0},
        {-2.0 * PI, 0.0},    {7.5, 7.5 - 2.0 * PI}, {-7.5, -7.5 + 2.0 * PI},
        {1.0, 1.0},          {-1.0, -1.0},       {PI + 1e-9, -PI + 1e-9},
        {-PI + 1e-9, -PI + 1e-9}};
    size_t i;
    ogk_real_t w;
    uint64_t seed = 5u;
    (void)state;
    /* Float: an odd multiple of pi rounded to float lies an ulp or so to one
     * side of the cut, so its wrap is +pi or -pi (both within rounding of the
     * input): the cases are compared as angles, by the distance modulo 2 pi;
     * the wrap's own error is that of subtracting multiples of 2 PI_R from a
     * float of up to OGK_CPD_ANGLE_LIMIT: a few ulps of it (CPD_EPS of the
     * input's size). */
    for (i = 0u; i < sizeof(cases) / sizeof(cases[0]); ++i) {
        OGK_ASSERT_STATUS(ogk_wrap_pi(cases[i][0], &w), OGK_OK);
#if OGK_REAL_SINGLE
        OGK_ASSERT_NEAR(remainder(w - cases[i][1], 2.0 * PI), 0.0, CPD_EPS * fmax(PI, fabs(cases[i][0])));
#else
        OGK_ASSERT_NEAR(w, cases[i][1], 1e-12);
#endif
    }
    for (i = 0u; i < 1000u; ++i) {
        const ogk_real_t a = uniform(&seed, -OGK_CPD_ANGLE_LIMIT, OGK_CPD_ANGLE_LIMIT);
        OGK_ASSERT_STATUS(ogk_wrap_pi(a, &w), OGK_OK);
        assert_true(w > -PI_R && w <= PI_R);
        OGK_ASSERT_NEAR(sin(w), sin(a), OGK_TEST_TOL(1e-11, CPD_EPS * fabs(a)));
        OGK_ASSERT_NEAR(cos(w), cos(a), OGK_TEST_TOL(1e-11, CPD_EPS * fabs(a)));
    }
    /* exact on the principal range (one wrap for every law, ogk/mathutil.h) */
    for (i = 0u; i < 1000u; ++i) {
        const ogk_real_t a = uniform(&seed, -PI, PI);
        OGK_ASSERT_STATUS(ogk_wrap_pi(a, &w), OGK_OK);
        assert_true(w == a || (a == -PI_R && w == PI_R));
    }
    /* one ulp past +-pi: still in (-pi, pi] */
    OGK_ASSERT_STATUS(ogk_wrap_pi(OGK_TEST_NEXTAFTER(PI, 4.0), &w), OGK_OK);
    assert_true(w > -PI_R && w <= PI_R);
    OGK_ASSERT_NEAR(fabs(w), PI, OGK_TEST_TOL(1e-15, CPD_EPS * PI));
    OGK_ASSERT_STATUS(ogk_wrap_pi(OGK_TEST_NEXTAFTER(-PI, -4.0), &w), OGK_OK);
    assert_true(w > -PI_R && w <= PI_R);
    OGK_ASSERT_NEAR(fabs(w), PI, OGK_TEST_TOL(1e-15, CPD_EPS * PI));
}

/* ================================================================ actuator rate bound */

/* Eq. (47): whatever the inputs, the commands are bounded, so the first-order
 * actuators of eqs. (16)-(18) (integrated here) move no faster than
 * 2 limit / tau. Worst case: saturated commands alternating sign. */
/* req: OGK-CPD-005 */
static void test_actuator_rate_bound(void **state)
{
    const double dt = 0.01;  /* [s] control sample */
    const int sub = 20;      /* RK4 sub-steps per sample */
    ogk_cpd_config_t cfg = rederived_config(OGK_CPD_POINTING_BODY);
    ogk_cpd_t ctx;
    double act[3] = {0.0, 0.0, 0.0};     /* Mx [N m], Dy, Dz [rad] */
    const double tau[3] = {TAU_S, TAU_S, TAU_S};
    double bound[3];
    double max_rate[3] = {0.0, 0.0, 0.0};
    uint64_t seed = 31337u;
    int k;
    (void)state;
    OGK_ASSERT_STATUS(ogk_cpd_init(&ctx, &cfg), OGK_OK);
    bound[0] = 2.0 * cfg.m_xc_max / cfg.tau_x;
    bound[1] = 2.0 * cfg.delta_yc_max / cfg.tau_y;
    bound[2] = 2.0 * cfg.delta_zc_max / cfg.tau_z;
    for (k = 0; k < 3000; ++k) {
        ogk_cpd_input_t in = zero_input();
        ogk_cpd_output_t out;
        double cmd[3];
        int i;
        int s;
        if (k < 1500) {
            /* bang-bang: sign flips every 50 samples (5 tau: settled) */
            const double sgn = ((k / 50) % 2 == 0) ? 1.0 : -1.0;
            in.rate_p = -sgn;
            in.rate_q = -sgn;
            in.rate_r = sgn;
        } else {
            /* random attitude, rates and command */
            in.psi = uniform(&seed, -PI, PI);
            in.theta = uniform(&seed, -1.5, 1.5);
            in.phi_roll = uniform(&seed, -PI, PI);
            in.rate_p = uniform(&seed, -1.0, 1.0);
            in.rate_q = uniform(&seed, -1.0, 1.0);
            in.rate_r = uniform(&seed, -1.0, 1.0);
            in.alpha_c = uniform(&seed, -PI, PI);
            in.beta_c = uniform(&seed, -1.5, 1.5);
        }
        OGK_ASSERT_STATUS(ogk_cpd_step(&ctx, &in, &out), OGK_OK);
        cmd[0] = out.m_xc;
        cmd[1] = out.delta_yc;
        cmd[2] = out.delta_zc;
        for (i = 0; i < 3; ++i) {
            const double h = dt / sub;
            for (s = 0; s < sub; ++s) {
                /* RK4 on x' = (c - x) / tau, rate checked at every node */
                const double k1 = (cmd[i] - act[i]) / tau[i];
                const double k2 = (cmd[i] - (act[i] + 0.5 * h * k1)) / tau[i];
                const double k3 = (cmd[i] - (act[i] + 0.5 * h * k2)) / tau[i];
                const double k4 = (cmd[i] - (act[i] + h * k3)) / tau[i];
                max_rate[i] = fmax(max_rate[i], fabs(k1));
                act[i] += h * (k1 + 2.0 * k2 + 2.0 * k3 + k4) / 6.0;
            }
        }
        /* eq. (17): the actuator states never reach the hardware limits */
        assert_true(fabs(act[0]) <= cfg.m_xc_max * (1.0 + 1e-12) && cfg.m_xc_max < MX_MAX_N_M);
        assert_true(fabs(act[1]) <= cfg.delta_yc_max * (1.0 + 1e-12) &&
                    cfg.delta_yc_max < DELTA_MAX_RAD);
        assert_true(fabs(act[2]) <= cfg.delta_zc_max * (1.0 + 1e-12));
    }
    for (k = 0; k < 3; ++k) {
        assert_true(max_rate[k] <= bound[k] * (1.0 + 1e-12));
        assert_true(max_rate[k] >= 0.99 * bound[k]); /* the bound is reached: tight */
    }
    /* paper, sec. 6: 600 N m/s and 13 deg/s */
    /* float: the limits and tau as stored (a rounding each) */
    OGK_ASSERT_NEAR(bound[0], 600.0, OGK_TEST_TOL(1e-9, 2.0 * FLT_EPSILON * 600.0));
    OGK_ASSERT_NEAR(bound[1] / DEG, 13.0, OGK_TEST_TOL(1e-9, 2.0 * FLT_EPSILON * 13.0));
}

/* ================================================================ closed loops */

/* One axis of eqs. (42)-(44): angle' = rate, rate' = gain u, u' = (u_c - u)/tau,
 * u saturated at u_max (eq. 17). gain: T l / I for pitch, -T l / I for yaw,
 * 1 / I_x for roll. */
typedef struct {
    double angle, rate, act;
} axis_state;

static axis_state axis_deriv(axis_state x, double gain, double u_c, double tau, double u_max)
{
    axis_state d;
    const double u = fmax(-u_max, fmin(u_max, x.act));
    d.angle = x.rate;
    d.rate = gain * u;
    d.act = (u_c - x.act) / tau;
    return d;
}

static axis_state axis_add(axis_state x, axis_state d, double h)
{
    axis_state r;
    r.angle = x.angle + h * d.angle;
    r.rate = x.rate + h * d.rate;
    r.act = x.act + h * d.act;
    return r;
}

typedef enum { AXIS_ROLL, AXIS_PITCH, AXIS_YAW } axis_id;

/* Commanded angle of each axis in simulate_axis [rad]. */
static double axis_target(axis_id axis)
{
    return (axis == AXIS_ROLL) ? 0.2 : ((axis == AXIS_PITCH) ? 0.3 : 0.25);
}

/* Simulates one axis for t_end seconds with the kernel in the loop (100 Hz,
 * zero-order hold, RK4 at 1 ms); returns the final state. Commanded angle:
 * roll 0.2 rad (phi_c), pitch 0.3 rad (alpha_c), yaw -0.25 rad (beta_c). */
static axis_state simulate_axis(const ogk_cpd_config_t *cfg0, axis_id axis, double g_tvc,
                                double angle0, double rate0, double t_end, double *target,
                                int *n_sat)
{
    ogk_cpd_config_t cfg = *cfg0;
    ogk_cpd_t ctx;
    axis_state x;
    const int n_samples = (int)(t_end / 0.01 + 0.5);
    const double h = 0.001;
    double gain;
    double u_max;
    double tau;
    int k;
    int s;
    cfg.phi_c = (axis == AXIS_ROLL) ? 0.2 : 0.0;
    OGK_ASSERT_STATUS(ogk_cpd_init(&ctx, &cfg), OGK_OK);
    *target = axis_target(axis);
    gain = (axis == AXIS_ROLL) ? 1.0 / IX_KG_M2 : ((axis == AXIS_PITCH) ? g_tvc : -g_tvc);
    u_max = (axis == AXIS_ROLL) ? MX_MAX_N_M : DELTA_MAX_RAD;
    tau = (axis == AXIS_ROLL) ? cfg.tau_x : ((axis == AXIS_PITCH) ? cfg.tau_y : cfg.tau_z);
    x.angle = angle0;
    x.rate = rate0;
    x.act = 0.0;
    *n_sat = 0;
    for (k = 0; k < n_samples; ++k) {
        ogk_cpd_input_t in = zero_input();
        ogk_cpd_output_t out;
        double u_c;
        if (axis == AXIS_ROLL) {
            in.phi_roll = x.angle;
            in.rate_p = x.rate;
        } else if (axis == AXIS_PITCH) {
            in.alpha_c = 0.3; /* theta_c = 0.3, psi_c = 0 */
            in.theta = x.angle;
            in.rate_q = x.rate;
        } else {
            in.beta_c = -0.25; /* psi_c = 0.25, theta_c = 0 */
            in.psi = x.angle;
            in.rate_r = x.rate;
        }
        OGK_ASSERT_STATUS(ogk_cpd_step(&ctx, &in, &out), OGK_OK);
        u_c = (axis == AXIS_ROLL) ? out.m_xc : ((axis == AXIS_PITCH) ? out.delta_yc : out.delta_zc);
        if ((out.flags & (OGK_CPD_FLAG_SAT_X | OGK_CPD_FLAG_SAT_Y | OGK_CPD_FLAG_SAT_Z)) != 0u) {
            ++*n_sat;
        }
        for (s = 0; s < 10; ++s) {
            const axis_state k1 = axis_deriv(x, gain, u_c, tau, u_max);
            const axis_state k2 = axis_deriv(axis_add(x, k1, 0.5 * h), gain, u_c, tau, u_max);
            const axis_state k3 = axis_deriv(axis_add(x, k2, 0.5 * h), gain, u_c, tau, u_max);
            const axis_state k4 = axis_deriv(axis_add(x, k3, h), gain, u_c, tau, u_max);
            x.angle += h * (k1.angle + 2.0 * k2.angle + 2.0 * k3.angle + k4.angle) / 6.0;
            x.rate += h * (k1.rate + 2.0 * k2.rate + 2.0 * k3.rate + k4.rate) / 6.0;
            x.act += h * (k1.act + 2.0 * k2.act + 2.0 * k3.act + k4.act) / 6.0;
        }
    }
    return x;
}

/* Linearised single axes (eqs. 42-44) converge with the paper's gains: the
 * printed ones on the paper's G = 0.83 s^-2, the re-derived ones on the true
 * G = T l0 / I_y0 = 8.18 s^-2; from a small error (linear CPD) and from the
 * Table 4 1-sigma dispersion (10 deg, 10 deg/s: saturated CPD). */
/* req: OGK-CPD-012 */
static void test_single_axis_closed_loop_converges(void **state)
{
    const ogk_cpd_pointing_t modes[2] = {OGK_CPD_POINTING_BODY, OGK_CPD_POINTING_EULER};
    const axis_id axes[3] = {AXIS_ROLL, AXIS_PITCH, AXIS_YAW};
    const double g_true = THRUST_N * ARM_M / IY_KG_M2;
    size_t m;
    size_t a;
    (void)state;
    for (m = 0u; m < 2u; ++m) {
        const ogk_cpd_config_t printed = printed_config(modes[m]);
        const ogk_cpd_config_t rederived = rederived_config(modes[m]);
        for (a = 0u; a < 3u; ++a) {
            double target;
            int n_sat;
            axis_state x;
            /* printed gains, paper's G, 0.01 deg error: stays linear */
            target = axis_target(axes[a]);
            x = simulate_axis(&printed, axes[a], 0.83, target - 0.01 * DEG, 0.0, 20.0, &target,
                              &n_sat);
            assert_int_equal(n_sat, 0);
            /* float: the loop settles within the resolution of the attitude it is
             * handed (ulp of 0.83: 6e-8), 4 ulps */
            OGK_ASSERT_NEAR(x.angle, target, OGK_TEST_TOL(1e-9, 4.0 * FLT_EPSILON * 0.83));
            OGK_ASSERT_NEAR(x.rate, 0.0, 1e-9);
            /* printed gains, paper's G, 1 deg error: saturated, converges */
            x = simulate_axis(&printed, axes[a], 0.83, target - 1.0 * DEG, 0.0, 40.0, &target,
                              &n_sat);
            assert_true(n_sat > 0);
            OGK_ASSERT_NEAR(x.angle, target, 1e-6);
            OGK_ASSERT_NEAR(x.rate, 0.0, 1e-6);
            /* re-derived gains on the true G: 10 deg and 10 deg/s. Pitch/yaw
             * settle in ~16 s. Roll: the saturated PD overshoots (the linear
             * band is 0.08 deg wide, 30 N m on 1200 kg m^2 gives 1.4 deg/s^2)
             * and rings down from 39 deg in ~130 s (docs/design/cpd.md). */
            x = simulate_axis(&rederived, axes[a], g_true, target - 10.0 * DEG, 10.0 * DEG,
                              (axes[a] == AXIS_ROLL) ? 160.0 : 25.0, &target, &n_sat);
            assert_true(n_sat > 0);
            OGK_ASSERT_NEAR(x.angle, target, 1e-6);
            OGK_ASSERT_NEAR(x.rate, 0.0, 1e-6);
        }
    }
}

/* ---------------------------------------------------------------- nonlinear rigid body */
/* x = [Phi, Theta, Psi, P, Q, R, Mx~, Dy~, Dz~] (eqs. 10-18, constant T, l, I). */
typedef struct {
    double s[9];
} rb_state;

static rb_state rb_deriv(const rb_state *x, const double cmd[3])
{
    rb_state d;
    const double phi_r = x->s[0];
    const double theta = x->s[1];
    const double p = x->s[3];
    const double q = x->s[4];
    const double r = x->s[5];
    const double mx = fmax(-MX_MAX_N_M, fmin(MX_MAX_N_M, x->s[6]));
    const double dy = fmax(-DELTA_MAX_RAD, fmin(DELTA_MAX_RAD, x->s[7]));
    const double dz = fmax(-DELTA_MAX_RAD, fmin(DELTA_MAX_RAD, x->s[8]));
    d.s[0] = p + (q * sin(phi_r) + r * cos(phi_r)) * tan(theta);  /* eq. (10) */
    d.s[1] = q * cos(phi_r) - r * sin(phi_r);                     /* eq. (11) */
    d.s[2] = (q * sin(phi_r) + r * cos(phi_r)) / cos(theta);      /* eq. (12) */
    d.s[3] = (IY_KG_M2 - IZ_KG_M2) / IX_KG_M2 * q * r + mx / IX_KG_M2;               /* (13) */
    d.s[4] = (IZ_KG_M2 - IX_KG_M2) / IY_KG_M2 * p * r +
             THRUST_N * ARM_M * cos(dz) * sin(dy) / IY_KG_M2;                       /* (14) */
    d.s[5] = (IX_KG_M2 - IY_KG_M2) / IZ_KG_M2 * p * q -
             THRUST_N * ARM_M * sin(dz) / IZ_KG_M2;                                 /* (15) */
    d.s[6] = (cmd[0] - x->s[6]) / TAU_S;                          /* eq. (18) */
    d.s[7] = (cmd[1] - x->s[7]) / TAU_S;                          /* eq. (16) */
    d.s[8] = (cmd[2] - x->s[8]) / TAU_S;
    return d;
}

static rb_state rb_axpy(const rb_state *x, const rb_state *d, double h)
{
    rb_state r;
    int i;
    for (i = 0; i < 9; ++i) {
        r.s[i] = x->s[i] + h * d->s[i];
    }
    return r;
}

/* Holds the vehicle at a roll of 120 deg (phi_c = 120 deg) with a 5 deg pitch
 * and 3 deg yaw offset; returns the largest and the final pointing angle
 * between x_b and the commanded direction. */
static void simulate_rigid_body(ogk_cpd_pointing_t mode, double *max_err, double *final_err)
{
    ogk_cpd_config_t cfg = rederived_config(mode);
    ogk_cpd_t ctx;
    rb_state x;
    const double alpha_c = 0.1;
    const double beta_c = 0.02;
    const double h = 0.001;
    ogk_real_t psi_c;
    ogk_real_t theta_c;
    int k;
    int s;
    int i;
    cfg.phi_c = 120.0 * DEG;
    OGK_ASSERT_STATUS(ogk_cpd_init(&ctx, &cfg), OGK_OK);
    OGK_ASSERT_STATUS(ogk_cpd_commanded_attitude(alpha_c, beta_c, 0.0, 0.0, &psi_c, &theta_c),
                      OGK_OK);
    memset(&x, 0, sizeof(x));
    x.s[0] = 120.0 * DEG;
    x.s[1] = theta_c - 5.0 * DEG;
    x.s[2] = psi_c + 3.0 * DEG;
    *max_err = 0.0;
    *final_err = 0.0;
    for (k = 0; k < 1500; ++k) { /* 15 s at 100 Hz */
        ogk_cpd_input_t in = zero_input();
        ogk_cpd_output_t out;
        double cmd[3];
        triad b;
        in.phi_roll = x.s[0];
        in.theta = x.s[1];
        in.psi = x.s[2];
        in.rate_p = x.s[3];
        in.rate_q = x.s[4];
        in.rate_r = x.s[5];
        in.alpha_c = alpha_c;
        in.beta_c = beta_c;
        b = body_frame(x.s[2], x.s[1], x.s[0]);
        *final_err = acos(fmin(1.0, dot(b.x, thrust_dir(alpha_c, beta_c, 0.0, 0.0))));
        *max_err = fmax(*max_err, *final_err);
        if (*final_err > 60.0 * DEG || fabs(x.s[1]) > 80.0 * DEG) {
            return; /* lost (and near the Euler singularity of eqs. 10-12) */
        }
        OGK_ASSERT_STATUS(ogk_cpd_step(&ctx, &in, &out), OGK_OK);
        cmd[0] = out.m_xc;
        cmd[1] = out.delta_yc;
        cmd[2] = out.delta_zc;
        for (s = 0; s < 10; ++s) {
            const rb_state k1 = rb_deriv(&x, cmd);
            const rb_state x2 = rb_axpy(&x, &k1, 0.5 * h);
            const rb_state k2 = rb_deriv(&x2, cmd);
            const rb_state x3 = rb_axpy(&x, &k2, 0.5 * h);
            const rb_state k3 = rb_deriv(&x3, cmd);
            const rb_state x4 = rb_axpy(&x, &k3, h);
            const rb_state k4 = rb_deriv(&x4, cmd);
            for (i = 0; i < 9; ++i) {
                x.s[i] += h * (k1.s[i] + 2.0 * k2.s[i] + 2.0 * k3.s[i] + k4.s[i]) / 6.0;
            }
        }
    }
}

/* The errata's point, on the full nonlinear attitude dynamics: at 120 deg of
 * roll the literal Euler-error law (eq. 46) drives the pointing error away,
 * the body-axis pointing error brings it to zero. */
/* req: OGK-CPD-012 OGK-CPD-004 */
static void test_rigid_body_at_large_roll(void **state)
{
    double max_err;
    double final_err;
    (void)state;
    simulate_rigid_body(OGK_CPD_POINTING_BODY, &max_err, &final_err);
    assert_true(max_err < 6.5 * DEG);
    assert_true(final_err < 1e-4 * DEG);
    simulate_rigid_body(OGK_CPD_POINTING_EULER, &max_err, &final_err);
    assert_true(max_err > 30.0 * DEG);
}

/* ================================================================ errors */

/* req: OGK-CPD-006 */
static void test_init_rejects_bad_config(void **state)
{
    const ogk_cpd_config_t good = rederived_config(OGK_CPD_POINTING_BODY);
    ogk_cpd_config_t c;
    ogk_cpd_t ctx;
    ogk_cpd_input_t in = zero_input();
    ogk_cpd_output_t out;
    ogk_real_t *fields[13];
    size_t i;
    (void)state;

    OGK_ASSERT_STATUS(ogk_cpd_init(NULL, &good), OGK_E_NULL);
    memset(&ctx, 0xA5, sizeof(ctx));
    OGK_ASSERT_STATUS(ogk_cpd_init(&ctx, NULL), OGK_E_NULL);
    OGK_ASSERT_STATUS(ogk_cpd_step(&ctx, &in, &out), OGK_E_NOT_INIT);

    c = good;
    fields[0] = &c.k_px;
    fields[1] = &c.k_dx;
    fields[2] = &c.k_py;
    fields[3] = &c.k_dy;
    fields[4] = &c.k_pz;
    fields[5] = &c.k_dz;
    fields[6] = &c.m_xc_max;
    fields[7] = &c.delta_yc_max;
    fields[8] = &c.delta_zc_max;
    fields[9] = &c.tau_x;
    fields[10] = &c.tau_y;
    fields[11] = &c.tau_z;
    fields[12] = &c.phi_c;
    for (i = 0u; i < 13u; ++i) {
        const ogk_real_t keep = *fields[i];
        *fields[i] = NAN;
        OGK_ASSERT_STATUS(ogk_cpd_init(&ctx, &c), OGK_E_NONFINITE);
        OGK_ASSERT_STATUS(ogk_cpd_step(&ctx, &in, &out), OGK_E_NOT_INIT);
        *fields[i] = INFINITY;
        OGK_ASSERT_STATUS(ogk_cpd_init(&ctx, &c), OGK_E_NONFINITE);
        if (i < 12u) { /* gains, limits, time constants must be > 0 */
            *fields[i] = 0.0;
            OGK_ASSERT_STATUS(ogk_cpd_init(&ctx, &c), OGK_E_CONFIG);
            *fields[i] = -keep;
            OGK_ASSERT_STATUS(ogk_cpd_init(&ctx, &c), OGK_E_CONFIG);
            OGK_ASSERT_STATUS(ogk_cpd_step(&ctx, &in, &out), OGK_E_NOT_INIT);
        }
        *fields[i] = keep;
        OGK_ASSERT_STATUS(ogk_cpd_init(&ctx, &c), OGK_OK);
    }
    /* convergence condition k_d > k_p tau (sec. 5.2), each axis */
    for (i = 0u; i < 3u; ++i) {
        ogk_real_t *kp = fields[2u * i];
        ogk_real_t *kd = fields[2u * i + 1u];
        ogk_real_t *tau = fields[9u + i];
        const double keep = *kd;
        *kd = *kp * *tau;
        OGK_ASSERT_STATUS(ogk_cpd_init(&ctx, &c), OGK_E_CONFIG);
        *kd = *kp * *tau * (1.0 + OGK_TEST_TOL(1e-9, 4.0 * FLT_EPSILON)); /* just above */
        OGK_ASSERT_STATUS(ogk_cpd_init(&ctx, &c), OGK_OK);
        *kd = keep;
    }
    c.phi_c = PI + OGK_TEST_PICK(1e-9, 1e-6); /* float: beyond PI_R */
    OGK_ASSERT_STATUS(ogk_cpd_init(&ctx, &c), OGK_E_CONFIG);
    c.phi_c = -PI;
    OGK_ASSERT_STATUS(ogk_cpd_init(&ctx, &c), OGK_OK);
    c = good;
    c.pointing = (ogk_cpd_pointing_t)7;
    OGK_ASSERT_STATUS(ogk_cpd_init(&ctx, &c), OGK_E_CONFIG);
    OGK_ASSERT_STATUS(ogk_cpd_step(&ctx, &in, &out), OGK_E_NOT_INIT);
    assert_true(out.flags == OGK_CPD_FLAG_SAFE);
    c.pointing = OGK_CPD_POINTING_EULER;
    OGK_ASSERT_STATUS(ogk_cpd_init(&ctx, &c), OGK_OK);
    OGK_ASSERT_STATUS(ogk_cpd_step(&ctx, &in, &out), OGK_OK);
}

static void assert_safe(const ogk_cpd_output_t *out)
{
    OGK_ASSERT_NEAR(out->m_xc, 0.0, 0.0);
    OGK_ASSERT_NEAR(out->delta_yc, 0.0, 0.0);
    OGK_ASSERT_NEAR(out->delta_zc, 0.0, 0.0);
    OGK_ASSERT_NEAR(out->err_y, 0.0, 0.0);
    assert_int_equal(out->flags, OGK_CPD_FLAG_SAFE);
}

/* NaN/Inf or out-of-range inputs: defined safe command, flagged; the context
 * stays usable. NULL arguments. */
/* req: OGK-CPD-007 */
static void test_step_bad_inputs_give_safe_command(void **state)
{
    const ogk_cpd_config_t cfg = rederived_config(OGK_CPD_POINTING_BODY);
    ogk_cpd_t ctx;
    ogk_cpd_input_t good = zero_input();
    ogk_cpd_output_t out;
    ogk_real_t *fields[10];
    size_t i;
    (void)state;
    OGK_ASSERT_STATUS(ogk_cpd_init(&ctx, &cfg), OGK_OK);
    good.theta = 0.3; /* 0.3 rad pitch error: saturated command when good */
    for (i = 0u; i < 10u; ++i) {
        ogk_cpd_input_t in = good;
        fields[0] = &in.psi;
        fields[1] = &in.theta;
        fields[2] = &in.phi_roll;
        fields[3] = &in.rate_p;
        fields[4] = &in.rate_q;
        fields[5] = &in.rate_r;
        fields[6] = &in.alpha_c;
        fields[7] = &in.beta_c;
        fields[8] = &in.xi;
        fields[9] = &in.phi;
        *fields[i] = NAN;
        OGK_ASSERT_STATUS(ogk_cpd_step(&ctx, &in, &out), OGK_E_NONFINITE);
        assert_safe(&out);
        assert_safe(&ctx.last);
        *fields[i] = -INFINITY;
        OGK_ASSERT_STATUS(ogk_cpd_step(&ctx, &in, &out), OGK_E_NONFINITE);
        assert_safe(&out);
        *fields[i] = 2.0 * OGK_CPD_ANGLE_LIMIT;
        /* angles: range; rates: any finite value is accepted */
        OGK_ASSERT_STATUS(ogk_cpd_step(&ctx, &in, &out),
                          (i >= 3u && i <= 5u) ? OGK_OK : OGK_E_RANGE);
        if (i < 3u || i > 5u) {
            assert_safe(&out);
        }
        /* still usable */
        OGK_ASSERT_STATUS(ogk_cpd_step(&ctx, &good, &out), OGK_OK);
        assert_true((out.flags & OGK_CPD_FLAG_SAFE) == 0u);
        OGK_ASSERT_NEAR(out.delta_yc, -cfg.delta_yc_max, 0.0);
    }
    OGK_ASSERT_STATUS(ogk_cpd_step(NULL, &good, &out), OGK_E_NULL);
    assert_safe(&out);
    OGK_ASSERT_STATUS(ogk_cpd_step(&ctx, NULL, &out), OGK_E_NULL);
    assert_safe(&out);
    OGK_ASSERT_STATUS(ogk_cpd_step(&ctx, &good, NULL), OGK_E_NULL);
    assert_safe(&ctx.last);
    OGK_ASSERT_STATUS(ogk_cpd_step(&ctx, &good, &out), OGK_OK);
}

/* req: OGK-CPD-007 */
static void test_geometry_functions_bad_inputs(void **state)
{
    ogk_real_t a;
    ogk_real_t b;
    (void)state;
    OGK_ASSERT_STATUS(ogk_cpd_commanded_attitude(0.0, 0.0, 0.0, 0.0, NULL, &b), OGK_E_NULL);
    OGK_ASSERT_STATUS(ogk_cpd_commanded_attitude(0.0, 0.0, 0.0, 0.0, &a, NULL), OGK_E_NULL);
    OGK_ASSERT_STATUS(ogk_cpd_commanded_attitude(NAN, 0.0, 0.0, 0.0, &a, &b), OGK_E_NONFINITE);
    OGK_ASSERT_STATUS(ogk_cpd_commanded_attitude(0.0, 0.0, 0.0, INFINITY, &a, &b),
                      OGK_E_NONFINITE);
    OGK_ASSERT_STATUS(ogk_cpd_commanded_attitude(0.0, 2e4, 0.0, 0.0, &a, &b), OGK_E_RANGE);
    /* NaN wins over range, wherever it is */
    OGK_ASSERT_STATUS(ogk_cpd_commanded_attitude(2e4, 0.0, 0.0, NAN, &a, &b), OGK_E_NONFINITE);

    OGK_ASSERT_STATUS(ogk_cpd_thrust_angles(0, 0, 0, 0, 0, 0, 0, NULL, &b), OGK_E_NULL);
    OGK_ASSERT_STATUS(ogk_cpd_thrust_angles(0, 0, 0, 0, 0, 0, 0, &a, NULL), OGK_E_NULL);
    OGK_ASSERT_STATUS(ogk_cpd_thrust_angles(0, 0, 0, 0, 0, 0, NAN, &a, &b), OGK_E_NONFINITE);
    OGK_ASSERT_STATUS(ogk_cpd_thrust_angles(0, -2e4, 0, 0, 0, 0, 0, &a, &b), OGK_E_RANGE);

    OGK_ASSERT_STATUS(ogk_cpd_pointing_error_body(0, 0, 0, 0, 0, 0, 0, NULL, &b), OGK_E_NULL);
    OGK_ASSERT_STATUS(ogk_cpd_pointing_error_body(0, 0, 0, 0, 0, 0, 0, &a, NULL), OGK_E_NULL);
    OGK_ASSERT_STATUS(ogk_cpd_pointing_error_body(0, 0, NAN, 0, 0, 0, 0, &a, &b),
                      OGK_E_NONFINITE);
    OGK_ASSERT_STATUS(ogk_cpd_pointing_error_body(0, 0, 0, 0, 0, 2e4, 0, &a, &b), OGK_E_RANGE);

    OGK_ASSERT_STATUS(ogk_wrap_pi(0.0, NULL), OGK_E_NULL);
    OGK_ASSERT_STATUS(ogk_wrap_pi(NAN, &a), OGK_E_NONFINITE);
    OGK_ASSERT_STATUS(ogk_wrap_pi(-INFINITY, &a), OGK_E_NONFINITE);
    OGK_ASSERT_STATUS(ogk_wrap_pi(1.5e4, &a), OGK_E_RANGE);
}

/* Braking-curve cap (ogk_cpd_config_t.approach_accel_*): in the linear band it
 * is the paper's law; for a large error the rate command is sqrt(2 a |e|). */
/* req: OGK-CPD-008 */
static void test_braking_cap_formula(void **state)
{
    ogk_cpd_config_t paper = rederived_config(OGK_CPD_POINTING_EULER);
    ogk_cpd_config_t capped = paper;
    ogk_cpd_t ctx_paper;
    ogk_cpd_t ctx_capped;
    ogk_cpd_input_t in = zero_input();
    ogk_cpd_output_t o_paper;
    ogk_cpd_output_t o_capped;
    const double a = 0.05;
    const double e = 0.5;
    const double w_brake = sqrt(2.0 * a * e);
    (void)state;
    capped.approach_accel_x = a;
    capped.approach_accel_y = a;
    capped.approach_accel_z = a;
    OGK_ASSERT_STATUS(ogk_cpd_init(&ctx_paper, &paper), OGK_OK);
    OGK_ASSERT_STATUS(ogk_cpd_init(&ctx_capped, &capped), OGK_OK);
    /* Linear band: 0.1 deg pitch error, small rate: identical commands. */
    in.alpha_c = 0.3;
    in.theta = 0.3 - 0.1 * DEG;
    in.rate_q = 0.001;
    OGK_ASSERT_STATUS(ogk_cpd_step(&ctx_paper, &in, &o_paper), OGK_OK);
    OGK_ASSERT_STATUS(ogk_cpd_step(&ctx_capped, &in, &o_capped), OGK_OK);
    OGK_ASSERT_NEAR(o_capped.delta_yc, o_paper.delta_yc, OGK_TEST_TOL(1e-15, CPD_EPS * DELTA_C_MAX_RAD));
    /* Pitch error 0.5 rad flown at exactly the braking rate: zero command. */
    in.theta = 0.3 - e;
    in.rate_q = w_brake;
    OGK_ASSERT_STATUS(ogk_cpd_step(&ctx_capped, &in, &o_capped), OGK_OK);
    OGK_ASSERT_NEAR(o_capped.err_y, e, 1e-12);
    OGK_ASSERT_NEAR(o_capped.delta_yc, 0.0, OGK_TEST_TOL(1e-12, CPD_EPS * DELTA_C_MAX_RAD));
    /* Slightly faster than the braking curve: brake (negative deflection),
     * while the paper's law still accelerates (saturated positive). */
    in.rate_q = w_brake + 0.005;
    OGK_ASSERT_STATUS(ogk_cpd_step(&ctx_capped, &in, &o_capped), OGK_OK);
    OGK_ASSERT_NEAR(o_capped.delta_yc, -capped.k_dy * 0.005, OGK_TEST_TOL(1e-12, CPD_EPS * DELTA_C_MAX_RAD));
    OGK_ASSERT_STATUS(ogk_cpd_step(&ctx_paper, &in, &o_paper), OGK_OK);
    OGK_ASSERT_NEAR(o_paper.delta_yc, paper.delta_yc_max, 0.0);
    /* Yaw: error +0.5 rad about z_b approached at +w_brake (R > 0): zero command. */
    in = zero_input();
    in.beta_c = -0.25; /* psi_c = 0.25 */
    in.psi = 0.25 - e;
    in.rate_r = w_brake;
    OGK_ASSERT_STATUS(ogk_cpd_step(&ctx_capped, &in, &o_capped), OGK_OK);
    OGK_ASSERT_NEAR(o_capped.err_z, e, 1e-12);
    OGK_ASSERT_NEAR(o_capped.delta_zc, 0.0, 1e-12);
    /* Roll the same way. */
    in = zero_input();
    in.phi_roll = -e;
    in.rate_p = w_brake;
    OGK_ASSERT_STATUS(ogk_cpd_step(&ctx_capped, &in, &o_capped), OGK_OK);
    OGK_ASSERT_NEAR(o_capped.m_xc, 0.0, 1e-9);
    /* A negative braking acceleration is rejected. */
    capped.approach_accel_z = -1e-3;
    OGK_ASSERT_STATUS(ogk_cpd_init(&ctx_capped, &capped), OGK_E_CONFIG);
}

/* A 2.5-sigma pitch rate (25 deg/s, as in the worst Table 4 draws) on the
 * single pitch axis at the start of the burn (G = 8.18 s^-2): with the cap
 * (margin 0.5 on the saturated acceleration) the error is captured to 0.5 deg
 * within 16 s (stopping alone takes w0 / a_sat = 4.7 s and 59 deg), and the
 * excursion stays below the ballistic stopping angle w0^2 / (2 a_sat) plus 20 %. */
/* req: OGK-CPD-008 */
static void test_braking_cap_captures_large_rate(void **state)
{
    const double g_true = THRUST_N * ARM_M / IY_KG_M2;
    const double a_sat = g_true * sin(DELTA_C_MAX_RAD);
    const double w0 = 25.0 * DEG;
    ogk_cpd_config_t cfg = rederived_config(OGK_CPD_POINTING_EULER);
    double target;
    int n_sat;
    axis_state x;
    (void)state;
    cfg.approach_accel_y = 0.5 * a_sat;
    x = simulate_axis(&cfg, AXIS_PITCH, g_true, axis_target(AXIS_PITCH), w0, 16.0, &target,
                      &n_sat);
    assert_true(fabs(x.angle - target) < 0.5 * DEG);
    assert_true(fabs(x.rate) < 0.5 * DEG);
    assert_true(n_sat > 0);
    x = simulate_axis(&cfg, AXIS_PITCH, g_true, axis_target(AXIS_PITCH), w0, 4.0, &target,
                      &n_sat);
    assert_true(x.angle - target < 1.2 * w0 * w0 / (2.0 * a_sat));
}

/* Feed-forward of the commanded turn rate: for a command turning at omega
 * (alpha_c stepping by omega dt between steps, vehicle on the commanded
 * attitude with zero rates), the pitch/yaw commands differ from the
 * feed-forward-free law by k_d times a body rate of magnitude omega; the
 * first step (no previous direction) and a command step beyond the clip are
 * handled as documented. */
/* req: OGK-CPD-009 */
static void test_feedforward_turn_rate(void **state)
{
    const double dt = 0.02;
    const double omega = 0.01;        /* rad/s */
    ogk_cpd_config_t off = rederived_config(OGK_CPD_POINTING_BODY);
    ogk_cpd_config_t on = off;
    ogk_cpd_t c_off, c_on;
    ogk_cpd_output_t o_off, o_on;
    ogk_cpd_input_t in = zero_input();
    ogk_real_t psi_c, theta_c, ff_y, ff_z;
    int k;
    (void)state;
    on.ff_period_s = dt;
    on.ff_rate_max = 0.05;
    OGK_ASSERT_STATUS(ogk_cpd_init(&c_off, &off), OGK_OK);
    OGK_ASSERT_STATUS(ogk_cpd_init(&c_on, &on), OGK_OK);
    in.xi = 0.7;
    in.phi = 0.01;
    in.beta_c = 0.05;
    for (k = 0; k < 3; ++k) {
        in.alpha_c = 0.3 + omega * dt * (double)k;
        OGK_ASSERT_STATUS(ogk_cpd_commanded_attitude(in.alpha_c, in.beta_c, in.xi, in.phi,
                                                     &psi_c, &theta_c), OGK_OK);
        in.psi = psi_c;
        in.theta = theta_c;
        in.phi_roll = 0.4;
        OGK_ASSERT_STATUS(ogk_cpd_step(&c_off, &in, &o_off), OGK_OK);
        OGK_ASSERT_STATUS(ogk_cpd_step(&c_on, &in, &o_on), OGK_OK);
        ff_y = (o_on.delta_yc - o_off.delta_yc) / on.k_dy;
        ff_z = -(o_on.delta_zc - o_off.delta_zc) / on.k_dz;
        if (k == 0) {
            OGK_ASSERT_NEAR(hypot(ff_y, ff_z), 0.0, 0.0);
        } else {
            /* beta_c = 0.05: the in-plane turn is omega cos(beta_c) to first order */
            OGK_ASSERT_REL(hypot(ff_y, ff_z), omega * cos(in.beta_c), 1e-3, 1e-12);
        }
    }
    /* A 1-deg step of the command in one period is clipped to ff_rate_max. */
    in.alpha_c += 1.0 * DEG;
    OGK_ASSERT_STATUS(ogk_cpd_step(&c_off, &in, &o_off), OGK_OK);
    OGK_ASSERT_STATUS(ogk_cpd_step(&c_on, &in, &o_on), OGK_OK);
    ff_y = (o_on.delta_yc - o_off.delta_yc) / on.k_dy;
    ff_z = -(o_on.delta_zc - o_off.delta_zc) / on.k_dz;
    assert_true(hypot(ff_y, ff_z) <= on.ff_rate_max * (1.0 + 1e-12));
    on.ff_period_s = -0.02;
    OGK_ASSERT_STATUS(ogk_cpd_init(&c_on, &on), OGK_E_CONFIG);
}

/* ================================================================ contract */

/* req: OGK-CPD-006 OGK-CPD-010 */
static void test_config_default_reset_and_thrust_cmd(void **state)
{
    ogk_cpd_config_t cfg;
    const ogk_cpd_config_t printed = printed_config(OGK_CPD_POINTING_BODY);
    ogk_cpd_t ctx, fresh, zero;
    ogk_cpd_input_t in = zero_input();
    ogk_cpd_output_t out;
    ogk_thrust_cmd_t cmd;
    ogk_nav_state_t nav;
    int k;
    (void)state;
    OGK_ASSERT_STATUS(ogk_cpd_config_default(NULL), OGK_E_NULL);
    memset(&cfg, 0xA5, sizeof(cfg));
    OGK_ASSERT_STATUS(ogk_cpd_config_default(&cfg), OGK_OK);
    /* the paper's printed values (eq. 54, sec. 6); extensions off */
    OGK_ASSERT_NEAR(cfg.k_px, printed.k_px, 0.0);
    OGK_ASSERT_NEAR(cfg.k_dx, printed.k_dx, 0.0);
    OGK_ASSERT_NEAR(cfg.k_py, printed.k_py, 0.0);
    OGK_ASSERT_NEAR(cfg.k_dy, printed.k_dy, 0.0);
    OGK_ASSERT_NEAR(cfg.k_pz, printed.k_pz, 0.0);
    OGK_ASSERT_NEAR(cfg.k_dz, printed.k_dz, 0.0);
    OGK_ASSERT_NEAR(cfg.m_xc_max, printed.m_xc_max, 0.0);
    /* float: the float of 0.65 deg by two roundings: an ulp */
    OGK_ASSERT_NEAR(cfg.delta_yc_max, printed.delta_yc_max, OGK_TEST_TOL(1e-17, FLT_EPSILON * DELTA_C_MAX_RAD));
    OGK_ASSERT_NEAR(cfg.delta_zc_max, printed.delta_zc_max, OGK_TEST_TOL(1e-17, FLT_EPSILON * DELTA_C_MAX_RAD));
    OGK_ASSERT_NEAR(cfg.tau_x, printed.tau_x, 0.0);
    OGK_ASSERT_NEAR(cfg.tau_y, printed.tau_y, 0.0);
    OGK_ASSERT_NEAR(cfg.tau_z, printed.tau_z, 0.0);
    OGK_ASSERT_NEAR(cfg.phi_c + cfg.approach_accel_x + cfg.approach_accel_y +
                    cfg.approach_accel_z + cfg.ff_period_s + cfg.ff_rate_max, 0.0, 0.0);
    assert_int_equal(cfg.pointing, OGK_CPD_POINTING_BODY);
    OGK_ASSERT_STATUS(ogk_cpd_init(&ctx, &cfg), OGK_OK);
    assert_true(ctx.init_marker == OGK_CPD_INIT_MARKER);

    /* reset: back to the just-initialised state, configuration kept */
    cfg.ff_period_s = 0.02;
    cfg.ff_rate_max = 0.05;
    OGK_ASSERT_STATUS(ogk_cpd_init(&ctx, &cfg), OGK_OK);
    OGK_ASSERT_STATUS(ogk_cpd_init(&fresh, &cfg), OGK_OK);
    for (k = 0; k < 3; ++k) {
        in.alpha_c = 0.1 * k;
        OGK_ASSERT_STATUS(ogk_cpd_step(&ctx, &in, &out), OGK_OK);
    }
    assert_int_equal(ctx.has_prev, 1u);
    OGK_ASSERT_STATUS(ogk_cpd_reset(&ctx), OGK_OK);
    assert_true(memcmp(&ctx, &fresh, sizeof(ctx)) == 0);
    OGK_ASSERT_STATUS(ogk_cpd_reset(NULL), OGK_E_NULL);
    memset(&zero, 0, sizeof(zero));
    OGK_ASSERT_STATUS(ogk_cpd_reset(&zero), OGK_E_NOT_INIT);

    /* any law's thrust command feeds CPD */
    memset(&cmd, 0, sizeof(cmd));
    memset(&nav, 0, sizeof(nav));
    cmd.alpha_rad = 0.3;
    cmd.beta_rad = -0.1;
    cmd.flags = OGK_THRUST_FLAG_ENGINE_ON;
    nav.xi_rad = 1.2;
    nav.phi_rad = 0.01;
    in = zero_input();
    in.theta = 0.2;
    OGK_ASSERT_STATUS(ogk_cpd_input_from_thrust_cmd(&in, &cmd, &nav), OGK_OK);
    /* copied: the values as stored (ogk_real_t) */
    OGK_ASSERT_NEAR(in.alpha_c, (ogk_real_t)0.3, 0.0);
    OGK_ASSERT_NEAR(in.beta_c, (ogk_real_t)-0.1, 0.0);
    OGK_ASSERT_NEAR(in.xi, (ogk_real_t)1.2, 0.0);
    OGK_ASSERT_NEAR(in.phi, (ogk_real_t)0.01, 0.0);
    OGK_ASSERT_NEAR(in.theta, (ogk_real_t)0.2, 0.0); /* attitude untouched */
    OGK_ASSERT_STATUS(ogk_cpd_step(&fresh, &in, &out), OGK_OK);
    OGK_ASSERT_STATUS(ogk_cpd_input_from_thrust_cmd(NULL, &cmd, &nav), OGK_E_NULL);
    OGK_ASSERT_STATUS(ogk_cpd_input_from_thrust_cmd(&in, NULL, &nav), OGK_E_NULL);
    OGK_ASSERT_STATUS(ogk_cpd_input_from_thrust_cmd(&in, &cmd, NULL), OGK_E_NULL);
    cmd.beta_rad = NAN;
    OGK_ASSERT_STATUS(ogk_cpd_input_from_thrust_cmd(&in, &cmd, &nav), OGK_E_NONFINITE);
    OGK_ASSERT_NEAR(in.beta_c, (ogk_real_t)-0.1, 0.0); /* untouched on rejection */
}


/* Every output is finite whatever the input's size: absurd but finite gains
 * (1e300, still k_d > k_p tau) and rates of +-1e308 on every axis, both
 * pointing modes (float: 1e30 and 1e38). */
/* req: OGK-CPD-007 */
static void test_outputs_finite_for_absurd_finite_input(void **state)
{
    static const double rates[3] = {OGK_TEST_PICK(1e308, 1e38), -OGK_TEST_PICK(1e308, 1e38), 0.0};
    unsigned mode, i, j, k;
    (void)state;
    for (mode = 0u; mode < 2u; ++mode) {
        ogk_cpd_config_t cfg = rederived_config(mode == 0u ? OGK_CPD_POINTING_BODY
                                                           : OGK_CPD_POINTING_EULER);
        ogk_cpd_t ctx;
        cfg.k_px = cfg.k_py = cfg.k_pz = OGK_TEST_PICK(1e300, 1e30);
        cfg.k_dx = cfg.k_dy = cfg.k_dz = OGK_TEST_PICK(1e300, 1e30);
        OGK_ASSERT_STATUS(ogk_cpd_init(&ctx, &cfg), OGK_OK);
        for (i = 0u; i < 3u; ++i) {
            for (j = 0u; j < 3u; ++j) {
                for (k = 0u; k < 3u; ++k) {
                    ogk_cpd_input_t in = zero_input();
                    ogk_cpd_output_t out;
                    ogk_status st;
                    in.theta = 0.5;
                    in.psi = -0.3;
                    in.alpha_c = 1.0;
                    in.beta_c = -0.2;
                    in.rate_p = rates[i];
                    in.rate_q = rates[j];
                    in.rate_r = rates[k];
                    st = ogk_cpd_step(&ctx, &in, &out);
                    assert_true(st == OGK_OK || st == OGK_E_SAFE_COMMAND);
                    assert_true(isfinite(out.m_xc) && isfinite(out.delta_yc) &&
                                isfinite(out.delta_zc) && isfinite(out.psi_c) &&
                                isfinite(out.theta_c) && isfinite(out.phi_c) &&
                                isfinite(out.err_x) && isfinite(out.err_y) &&
                                isfinite(out.err_z));
                    assert_true(fabs(out.m_xc) <= cfg.m_xc_max &&
                                fabs(out.delta_yc) <= cfg.delta_yc_max &&
                                fabs(out.delta_zc) <= cfg.delta_zc_max);
                }
            }
        }
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_commanded_attitude_points_x_body),
        cmocka_unit_test(test_commanded_attitude_known_values),
        cmocka_unit_test(test_thrust_angles_round_trip_and_deflection),
        cmocka_unit_test(test_thrust_angles_small_deflection),
        cmocka_unit_test(test_thrust_angles_branch_cut),
        cmocka_unit_test(test_body_pointing_error_geometry),
        cmocka_unit_test(test_body_error_matches_euler_near_zero_roll),
        cmocka_unit_test(test_body_error_behind),
        cmocka_unit_test(test_body_error_behind_subnormal_lateral),
        cmocka_unit_test(test_control_law_and_saturation),
        cmocka_unit_test(test_euler_mode_wraps_errors),
        cmocka_unit_test(test_wrap_pi),
        cmocka_unit_test(test_actuator_rate_bound),
        cmocka_unit_test(test_outputs_finite_for_absurd_finite_input),
        cmocka_unit_test(test_single_axis_closed_loop_converges),
        cmocka_unit_test(test_rigid_body_at_large_roll),
        cmocka_unit_test(test_init_rejects_bad_config),
        cmocka_unit_test(test_step_bad_inputs_give_safe_command),
        cmocka_unit_test(test_geometry_functions_bad_inputs),
        cmocka_unit_test(test_braking_cap_formula),
        cmocka_unit_test(test_braking_cap_captures_large_rate),
        cmocka_unit_test(test_feedforward_turn_rate),
        cmocka_unit_test(test_config_default_reset_and_thrust_cmd),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
