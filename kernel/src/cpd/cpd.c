/* cpd.c -- constrained PD attitude control (Pontani & Celani 2021, sec. 5).
 *
 * Rotations are built literally as the paper writes them (products of the
 * elementary frame rotations R1, R2, R3 and R_A); the unit tests check them
 * against an independent vector construction of the same frames. */
#include "ogk/cpd.h"

#include <math.h>
#include <stdbool.h>
#include <stddef.h>
#include <string.h>

#include "../ogk_checks.h"
#include "../thrust_cmd_internal.h"

#define CPD_PI OGK_I_PI

/* Below this horizontal component (in a1-a2) of a unit vector its yaw is
 * undefined (the vector is along +-a3 to within 1e-12 rad). */
#define CPD_YAW_EPS OGK_R(1.0e-12)

/* Below this lateral component of the commanded direction in body axes the
 * pointing error's axis is undefined (pointing_error_body): 1e-300 rad
 * (float build: 1e-30 rad; ogk/real.h) is zero for every purpose, and it keeps
 * angle / lateral far from overflow. */
#define CPD_LATERAL_MIN OGK_REAL_TINY

/* Row-major 3x3 matrix (a struct, so const pointers to it are plain C99). */
typedef struct {
    ogk_real_t m[3][3];
} mat3_t;

/* ---------------------------------------------------------------- rotations */

/* Elementary frame rotations (counterclockwise about axis 1, 2, 3):
 * [new]^T = R_i(t) [old]^T, so components transform as v_new = R_i(t) v_old. */
static void rot1(ogk_real_t t, mat3_t *r)
{
    const ogk_real_t c = OGK_COS(t);
    const ogk_real_t s = OGK_SIN(t);
    r->m[0][0] = OGK_R(1.0); r->m[0][1] = OGK_R(0.0); r->m[0][2] = OGK_R(0.0);
    r->m[1][0] = OGK_R(0.0); r->m[1][1] = c;   r->m[1][2] = s;
    r->m[2][0] = OGK_R(0.0); r->m[2][1] = -s;  r->m[2][2] = c;
}

static void rot2(ogk_real_t t, mat3_t *r)
{
    const ogk_real_t c = OGK_COS(t);
    const ogk_real_t s = OGK_SIN(t);
    r->m[0][0] = c;   r->m[0][1] = OGK_R(0.0); r->m[0][2] = -s;
    r->m[1][0] = OGK_R(0.0); r->m[1][1] = OGK_R(1.0); r->m[1][2] = OGK_R(0.0);
    r->m[2][0] = s;   r->m[2][1] = OGK_R(0.0); r->m[2][2] = c;
}

static void rot3(ogk_real_t t, mat3_t *r)
{
    const ogk_real_t c = OGK_COS(t);
    const ogk_real_t s = OGK_SIN(t);
    r->m[0][0] = c;   r->m[0][1] = s;   r->m[0][2] = OGK_R(0.0);
    r->m[1][0] = -s;  r->m[1][1] = c;   r->m[1][2] = OGK_R(0.0);
    r->m[2][0] = OGK_R(0.0); r->m[2][1] = OGK_R(0.0); r->m[2][2] = OGK_R(1.0);
}

/* out = a b (out must not alias a or b). */
static void mat_mul(const mat3_t *a, const mat3_t *b, mat3_t *out)
{
    size_t i;
    size_t j;
    for (i = 0u; i < 3u; ++i) {
        for (j = 0u; j < 3u; ++j) {
            out->m[i][j] = (a->m[i][0] * b->m[0][j]) + (a->m[i][1] * b->m[1][j]) +
                           (a->m[i][2] * b->m[2][j]);
        }
    }
}

/* out = m v */
static void mat_vec(const mat3_t *a, const ogk_real_t v[3], ogk_real_t out[3])
{
    size_t i;
    for (i = 0u; i < 3u; ++i) {
        out[i] = (a->m[i][0] * v[0]) + (a->m[i][1] * v[1]) + (a->m[i][2] * v[2]);
    }
}

/* out = m^T v */
static void mat_t_vec(const mat3_t *a, const ogk_real_t v[3], ogk_real_t out[3])
{
    size_t i;
    for (i = 0u; i < 3u; ++i) {
        out[i] = (a->m[0][i] * v[0]) + (a->m[1][i] * v[1]) + (a->m[2][i] * v[2]);
    }
}

/* N = R_A R3(-xi) R2(phi): [a]^T = N [r t n]^T (sec. 5.4), so a vector with
 * r-t-n components u has a components N u. R_A: a1 = c2, a2 = -c3, a3 = -c1. */
static void a_from_rtn(ogk_real_t xi, ogk_real_t phi, mat3_t *n_out) /* NOLINT(bugprone-easily-swappable-parameters): internal helper, argument order of the equation it implements; every caller is in this file and unit-tested */
{
    static const mat3_t r_a = {{{OGK_R(0.0), OGK_R(1.0), OGK_R(0.0)}, {OGK_R(0.0), OGK_R(0.0), -OGK_R(1.0)}, {-OGK_R(1.0), OGK_R(0.0), OGK_R(0.0)}}};
    mat3_t r3;
    mat3_t r2;
    mat3_t c_from_rtn;
    rot3(-xi, &r3);
    rot2(phi, &r2);
    mat_mul(&r3, &r2, &c_from_rtn);
    mat_mul(&r_a, &c_from_rtn, n_out);
}

/* C = R1(Phi) R2(Theta) R3(Psi): body components = C a components (eq. 9). */
static void body_from_a(ogk_real_t psi, ogk_real_t theta, ogk_real_t phi_roll, mat3_t *c_out) /* NOLINT(bugprone-easily-swappable-parameters): internal helper, argument order of the equation it implements; every caller is in this file and unit-tested */
{
    mat3_t r1;
    mat3_t r2;
    mat3_t r3;
    mat3_t r2r3;
    rot1(phi_roll, &r1);
    rot2(theta, &r2);
    rot3(psi, &r3);
    mat_mul(&r2, &r3, &r2r3);
    mat_mul(&r1, &r2r3, c_out);
}

/* Unit thrust direction in r-t-n from its angles (eqs. 39, 52). */
static void rtn_direction(ogk_real_t alpha, ogk_real_t beta, ogk_real_t u[3])
{
    const ogk_real_t cb = OGK_COS(beta);
    u[0] = cb * OGK_SIN(alpha);
    u[1] = cb * OGK_COS(alpha);
    u[2] = OGK_SIN(beta);
}

/* ---------------------------------------------------------------- checks */

static ogk_status check_angle(ogk_real_t angle)
{
    ogk_status st = OGK_OK;

    if (!isfinite(angle)) {
        st = OGK_E_NONFINITE;
    } else if (OGK_FABS(angle) > OGK_CPD_ANGLE_LIMIT) {
        st = OGK_E_RANGE;
    } else {
        /* finite and inside the limit */
    }
    return st;
}

/* First non-OK status of check_angle over n values (NONFINITE before RANGE:
 * the scan stops at the first non-finite value). */
static ogk_status check_angles(const ogk_real_t *angles, size_t n)
{
    ogk_status st = OGK_OK;
    size_t i;
    for (i = 0u; (i < n) && (st != OGK_E_NONFINITE); ++i) {
        const ogk_status si = check_angle(angles[i]);
        if (si != OGK_OK) {
            st = si;
        }
    }
    return st;
}

static ogk_real_t saturate(ogk_real_t value, ogk_real_t limit, uint32_t flag, uint32_t *flags) /* NOLINT(bugprone-easily-swappable-parameters): internal helper, argument order of the equation it implements; every caller is in this file and unit-tested */
{
    ogk_real_t sat = value;

    if (value > limit) {
        *flags |= flag;
        sat = limit;
    } else if (value < -limit) {
        *flags |= flag;
        sat = -limit;
    } else {
        /* inside the limit: unchanged */
    }
    return sat;
}

/* ---------------------------------------------------------------- geometry */

/* Eqs. (38)-(39): yaw and pitch of a unit vector with a components t_a. */
static void attitude_of_direction(const ogk_real_t t_a[3], ogk_real_t *psi_c, /* NOLINT(bugprone-easily-swappable-parameters): internal helper, argument order of the equation it implements; every caller is in this file and unit-tested */
                                  ogk_real_t *theta_c, bool *yaw_undefined)
{
    const ogk_real_t horiz = OGK_HYPOT(t_a[0], t_a[1]);
    /* eq. (38): t_a = (cos Th cos Ps, cos Th sin Ps, -sin Th) */
    *theta_c = OGK_ATAN2(-t_a[2], horiz);
    if (horiz < CPD_YAW_EPS) {
        *psi_c = OGK_R(0.0);
        *yaw_undefined = true;
    } else {
        *psi_c = OGK_ATAN2(t_a[1], t_a[0]);
        if (*psi_c <= -CPD_PI) {
            *psi_c = CPD_PI;
        }
        *yaw_undefined = false;
    }
}

/* Rotation vector taking x_b = (1, 0, 0) onto the unit vector t_b (body
 * components): axis x_b x t_b = (0, -t_z, t_y) normalised, angle
 * atan2(|(t_y, t_z)|, t_x) in [0, pi]. Its y and z components are the pitch
 * and yaw pointing errors. Near zero error they reduce to (-t_z, t_y), i.e.
 * (Theta_c - Theta, Psi_c - Psi) at zero roll; they never change sign with
 * the size of the error, and their magnitude is the true pointing angle. */
static void pointing_error_body(const ogk_real_t t_b[3], ogk_real_t *err_y, ogk_real_t *err_z)
{
    const ogk_real_t lateral = OGK_HYPOT(t_b[1], t_b[2]);
    const ogk_real_t angle = OGK_ATAN2(lateral, t_b[0]);
    /* A subnormal lateral (direction behind to within 1e-308 rad) made
     * angle / lateral overflow (pi / 1e-310 = inf). Below CPD_LATERAL_MIN the
     * axis is as undefined as at zero; above it |t_b[i]| * angle / lateral
     * <= 3 pi 1e300 is finite even for EVA, which bounds each component of
     * the unit vector t_b only by 3 (docs/evidence/eva.md). */
    if (lateral >= CPD_LATERAL_MIN) {
        const ogk_real_t scale = angle / lateral; /* -> 1 as the error -> 0 */
        /* |t_b[i]| <= lateral, so each is within the angle <= pi: the clamp
         * only catches rounding, and tells EVA so. */
        *err_y = OGK_FMIN(OGK_FMAX(-t_b[2] * scale, -CPD_PI), CPD_PI);
        *err_z = OGK_FMIN(OGK_FMAX(t_b[1] * scale, -CPD_PI), CPD_PI);
    } else if (t_b[0] >= OGK_R(0.0)) {
        *err_y = OGK_R(0.0);
        *err_z = OGK_R(0.0);
    } else {
        /* exactly behind: any axis normal to x_b turns the vehicle around;
         * pitch is chosen so the command is deterministic */
        *err_y = CPD_PI;
        *err_z = OGK_R(0.0);
    }
}

/* Commanded direction in a and body components. */
static void commanded_direction(ogk_real_t psi, ogk_real_t theta, ogk_real_t phi_roll, /* NOLINT(bugprone-easily-swappable-parameters): internal helper, argument order of the equation it implements; every caller is in this file and unit-tested */
                                ogk_real_t alpha_c, ogk_real_t beta_c, ogk_real_t xi, /* NOLINT(bugprone-easily-swappable-parameters): internal helper, argument order of the equation it implements; every caller is in this file and unit-tested */
                                ogk_real_t phi, ogk_real_t t_a[3], ogk_real_t t_b[3])
{
    mat3_t n_a_rtn;
    mat3_t c_b_a;
    ogk_real_t u_rtn[3];
    rtn_direction(alpha_c, beta_c, u_rtn);
    a_from_rtn(xi, phi, &n_a_rtn);
    mat_vec(&n_a_rtn, u_rtn, t_a);
    body_from_a(psi, theta, phi_roll, &c_b_a);
    mat_vec(&c_b_a, t_a, t_b);
}

/* Body-axis rate [rad/s] of the commanded direction between two steps,
 * (d_prev x d_now) / period in a components, rotated to body axes; only the
 * y and z components (the pointing loops) are returned, clipped in norm. */
static void feedforward_rate(const ogk_cpd_t *ctx, const ogk_real_t t_a[3], ogk_real_t psi,
                             ogk_real_t theta, ogk_real_t phi_roll, ogk_real_t *w_y, ogk_real_t *w_z)
{
    const ogk_cpd_config_t *cfg = &ctx->cfg;
    const ogk_real_t *p = ctx->dir_prev_a;

    *w_y = OGK_R(0.0);
    *w_z = OGK_R(0.0);
    /* Zero without a period or a previous direction. */
    if ((cfg->ff_period_s > OGK_R(0.0)) && (ctx->has_prev != 0u)) {
        ogk_real_t w_a[3];
        ogk_real_t w_b[3];
        ogk_real_t norm;
        mat3_t c_b_a;
        w_a[0] = ((p[1] * t_a[2]) - (p[2] * t_a[1])) / cfg->ff_period_s;
        w_a[1] = ((p[2] * t_a[0]) - (p[0] * t_a[2])) / cfg->ff_period_s;
        w_a[2] = ((p[0] * t_a[1]) - (p[1] * t_a[0])) / cfg->ff_period_s;
        body_from_a(psi, theta, phi_roll, &c_b_a);
        mat_vec(&c_b_a, w_a, w_b);
        norm = OGK_HYPOT(w_b[1], w_b[2]);
        if (norm > cfg->ff_rate_max) {
            const ogk_real_t scale = (norm > OGK_R(0.0)) ? (cfg->ff_rate_max / norm) : OGK_R(0.0);
            w_b[1] *= scale;
            w_b[2] *= scale;
        }
        *w_y = w_b[1];
        *w_z = w_b[2];
    }
}

/* ---------------------------------------------------------------- public */

ogk_status ogk_cpd_commanded_attitude(ogk_real_t alpha_c, ogk_real_t beta_c, ogk_real_t xi,
                                      ogk_real_t phi, ogk_real_t *psi_c,
                                      ogk_real_t *theta_c)
{
    const ogk_real_t angles[4] = {alpha_c, beta_c, xi, phi};
    ogk_status st;

    if ((psi_c == NULL) || (theta_c == NULL)) {
        st = OGK_E_NULL;
    } else {
        st = check_angles(angles, 4u);
    }
    if (st == OGK_OK) {
        mat3_t n_a_rtn;
        ogk_real_t u_rtn[3];
        ogk_real_t t_a[3];
        bool yaw_undefined;
        rtn_direction(alpha_c, beta_c, u_rtn);
        a_from_rtn(xi, phi, &n_a_rtn);
        mat_vec(&n_a_rtn, u_rtn, t_a);
        attitude_of_direction(t_a, psi_c, theta_c, &yaw_undefined);
    }
    return st;
}

ogk_status ogk_cpd_thrust_angles(ogk_real_t psi, ogk_real_t theta, ogk_real_t phi_roll,
                                 ogk_real_t xi, ogk_real_t phi, ogk_real_t delta_y,
                                 ogk_real_t delta_z, ogk_real_t *alpha_a,
                                 ogk_real_t *beta_a)
{
    const ogk_real_t angles[7] = {psi, theta, phi_roll, xi, phi, delta_y, delta_z};
    ogk_status st;

    if ((alpha_a == NULL) || (beta_a == NULL)) {
        st = OGK_E_NULL;
    } else {
        st = check_angles(angles, 7u);
    }
    if (st == OGK_OK) {
        mat3_t n_a_rtn;
        mat3_t c_b_a;
        mat3_t c_b_rtn;
        ogk_real_t d_b[3];
        ogk_real_t t_rtn[3];
        /* eq. (50): deflected thrust direction in body axes */
        d_b[0] = OGK_COS(delta_z) * OGK_COS(delta_y);
        d_b[1] = OGK_SIN(delta_z);
        d_b[2] = OGK_COS(delta_z) * OGK_SIN(delta_y);
        /* eqs. (49), (51): body components = C N (r-t-n components) */
        a_from_rtn(xi, phi, &n_a_rtn);
        body_from_a(psi, theta, phi_roll, &c_b_a);
        mat_mul(&c_b_a, &n_a_rtn, &c_b_rtn);
        mat_t_vec(&c_b_rtn, d_b, t_rtn);
        /* eq. (52): t_rtn = (cos b sin a, cos b cos a, sin b) */
        *alpha_a = OGK_ATAN2(t_rtn[0], t_rtn[1]);
        if (*alpha_a <= -CPD_PI) {
            *alpha_a = CPD_PI;
        }
        *beta_a = OGK_ATAN2(t_rtn[2], OGK_HYPOT(t_rtn[0], t_rtn[1]));
    }
    return st;
}

ogk_status ogk_cpd_pointing_error_body(ogk_real_t psi, ogk_real_t theta, ogk_real_t phi_roll,
                                       ogk_real_t alpha_c, ogk_real_t beta_c, ogk_real_t xi,
                                       ogk_real_t phi, ogk_real_t *err_y, ogk_real_t *err_z)
{
    const ogk_real_t angles[7] = {psi, theta, phi_roll, alpha_c, beta_c, xi, phi};
    ogk_status st;

    if ((err_y == NULL) || (err_z == NULL)) {
        st = OGK_E_NULL;
    } else {
        st = check_angles(angles, 7u);
    }
    if (st == OGK_OK) {
        ogk_real_t t_a[3];
        ogk_real_t t_b[3];
        commanded_direction(psi, theta, phi_roll, alpha_c, beta_c, xi, phi, t_a, t_b);
        pointing_error_body(t_b, err_y, err_z);
    }
    return st;
}

static bool config_finite(const ogk_cpd_config_t *cfg)
{
    const ogk_real_t v[18] = {cfg->k_px, cfg->k_dx, cfg->k_py, cfg->k_dy, cfg->k_pz,
                          cfg->k_dz, cfg->m_xc_max, cfg->delta_yc_max,
                          cfg->delta_zc_max, cfg->tau_x, cfg->tau_y, cfg->tau_z,
                          cfg->phi_c, cfg->approach_accel_x, cfg->approach_accel_y,
                          cfg->approach_accel_z, cfg->ff_period_s, cfg->ff_rate_max};
    return ogk_i_all_finite(v, sizeof(v) / sizeof(v[0]));
}

/* The PD term of one axis, k_p e - k_d w, with the braking-curve cap of the
 * rate command k_p e / k_d when a > 0 (see ogk_cpd_config_t). */
static ogk_real_t pd_term(ogk_real_t k_p, ogk_real_t k_d, ogk_real_t a, ogk_real_t err, ogk_real_t rate) /* NOLINT(bugprone-easily-swappable-parameters): internal helper, argument order of the equation it implements; every caller is in this file and unit-tested */
{
    ogk_real_t rate_cmd = k_p * err / k_d;
    if (a > OGK_R(0.0)) {
        const ogk_real_t braking = OGK_SQRT(OGK_R(2.0) * a * OGK_FABS(err));
        if (OGK_FABS(rate_cmd) > braking) {
            rate_cmd = OGK_COPYSIGN(braking, err);
        }
    }
    return k_d * (rate_cmd - rate);
}

/* Sec. 5.2: the linearised loop with a first-order actuator converges iff
 * k_d > k_p tau > 0 (Routh on tau s^3 + s^2 + G k_d s + G k_p). */
static bool axis_ok(ogk_real_t k_p, ogk_real_t k_d, ogk_real_t tau, ogk_real_t limit)
{
    return (k_p > OGK_R(0.0)) && (k_d > OGK_R(0.0)) && (tau > OGK_R(0.0)) && (limit > OGK_R(0.0)) &&
           (k_d > (k_p * tau));
}

/* The defaults of ogk_cpd_config_default into a non-NULL cfg. */
static void config_default(ogk_cpd_config_t *cfg)
{
    (void)memset(cfg, 0, sizeof(*cfg));
    /* eq. (54) and sec. 6 as printed (docs/design/cpd.md: pitch/yaw gain erratum) */
    cfg->k_px = OGK_R(21.6e3);
    cfg->k_dx = OGK_R(7.2e3);
    cfg->k_py = OGK_R(21.6);
    cfg->k_dy = OGK_R(7.2);
    cfg->k_pz = OGK_R(21.6);
    cfg->k_dz = OGK_R(7.2);
    cfg->m_xc_max = OGK_R(30.0);
    cfg->delta_yc_max = OGK_R(0.65) * CPD_PI / OGK_R(180.0);
    cfg->delta_zc_max = OGK_R(0.65) * CPD_PI / OGK_R(180.0);
    cfg->tau_x = OGK_R(0.1);
    cfg->tau_y = OGK_R(0.1);
    cfg->tau_z = OGK_R(0.1);
    cfg->phi_c = OGK_R(0.0);
    cfg->pointing = OGK_CPD_POINTING_BODY;
    cfg->approach_accel_x = OGK_R(0.0);
    cfg->approach_accel_y = OGK_R(0.0);
    cfg->approach_accel_z = OGK_R(0.0);
    cfg->ff_period_s = OGK_R(0.0);
    cfg->ff_rate_max = OGK_R(0.0);
}

/* The configuration checks of ogk_cpd_init, in their order. */
static ogk_status cpd_check_config(const ogk_cpd_config_t *cfg)
{
    ogk_status st = OGK_OK;

    if (cfg == NULL) {
        st = OGK_E_NULL;
    } else if (!config_finite(cfg)) {
        st = OGK_E_NONFINITE;
    } else if ((!axis_ok(cfg->k_px, cfg->k_dx, cfg->tau_x, cfg->m_xc_max) ||
                !axis_ok(cfg->k_py, cfg->k_dy, cfg->tau_y, cfg->delta_yc_max) ||
                !axis_ok(cfg->k_pz, cfg->k_dz, cfg->tau_z, cfg->delta_zc_max)) ||
               /* roll command */
               (OGK_FABS(cfg->phi_c) > CPD_PI) ||
               /* braking curves and feed-forward */
               ((cfg->approach_accel_x < OGK_R(0.0)) || (cfg->approach_accel_y < OGK_R(0.0)) ||
                (cfg->approach_accel_z < OGK_R(0.0)) || (cfg->ff_period_s < OGK_R(0.0)) || (cfg->ff_rate_max < OGK_R(0.0))) ||
               /* pointing-error definition */
               ((cfg->pointing != OGK_CPD_POINTING_BODY) &&
                (cfg->pointing != OGK_CPD_POINTING_EULER))) {
        st = OGK_E_CONFIG;
    } else {
        /* a usable configuration */
    }
    return st;
}

ogk_status ogk_cpd_init(ogk_cpd_t *ctx, const ogk_cpd_config_t *cfg)
{
    ogk_status st;

    if (ctx == NULL) {
        st = OGK_E_NULL;
    } else {
        (void)memset(ctx, 0, sizeof(*ctx));
        st = cpd_check_config(cfg);
        if (st == OGK_OK) {
            ctx->cfg = *cfg;
            ctx->last.flags = OGK_CPD_FLAG_SAFE;
            ctx->init_marker = OGK_CPD_INIT_MARKER;
        }
    }
    return st;
}

ogk_status ogk_cpd_config_default(ogk_cpd_config_t *cfg)
{
    ogk_status st = OGK_OK;

    if (cfg == NULL) {
        st = OGK_E_NULL;
    } else {
        config_default(cfg);
    }
    return st;
}

ogk_status ogk_cpd_reset(ogk_cpd_t *ctx)
{
    ogk_status st = OGK_OK;

    if (ctx == NULL) {
        st = OGK_E_NULL;
    } else if (ctx->init_marker != OGK_CPD_INIT_MARKER) {
        st = OGK_E_NOT_INIT;
    } else {
        (void)memset(&ctx->last, 0, sizeof(ctx->last));
        ctx->last.flags = OGK_CPD_FLAG_SAFE;
        ctx->dir_prev_a[0] = OGK_R(0.0);
        ctx->dir_prev_a[1] = OGK_R(0.0);
        ctx->dir_prev_a[2] = OGK_R(0.0);
        ctx->has_prev = 0u;
    }
    return st;
}

ogk_status ogk_cpd_input_from_thrust_cmd(ogk_cpd_input_t *in, const ogk_thrust_cmd_t *cmd,
                                         const ogk_nav_state_t *nav)
{
    ogk_status st;

    if ((in == NULL) || (cmd == NULL) || (nav == NULL)) {
        st = OGK_E_NULL;
    } else {
        ogk_real_t ab[2];
        /* any law's command as r-t-n angles at the vehicle's position (ogk_thrust_cmd_to_rtn's
         * checks; no unit vector built) */
        st = ogk_i_thrust_cmd_rtn_direction(cmd, nav, ab, NULL);
        if ((st == OGK_OK) && (!isfinite(nav->xi_rad) || !isfinite(nav->phi_rad))) {
            st = OGK_E_NONFINITE;
        }
        if (st == OGK_OK) {
            in->alpha_c = ab[0];
            in->beta_c = ab[1];
            in->xi = nav->xi_rad;
            in->phi = nav->phi_rad;
        }
    }
    return st;
}

static void safe_command(ogk_cpd_output_t *out)
{
    out->m_xc = OGK_R(0.0);
    out->delta_yc = OGK_R(0.0);
    out->delta_zc = OGK_R(0.0);
    out->psi_c = OGK_R(0.0);
    out->theta_c = OGK_R(0.0);
    out->phi_c = OGK_R(0.0);
    out->err_x = OGK_R(0.0);
    out->err_y = OGK_R(0.0);
    out->err_z = OGK_R(0.0);
    out->flags = OGK_CPD_FLAG_SAFE;
}

/* Writes the safe command into out (if any) and into the context's last
 * command (if the context is usable). */
static void reject(ogk_cpd_t *ctx, ogk_cpd_output_t *out)
{
    if (out != NULL) {
        safe_command(out);
    }
    if ((ctx != NULL) && (ctx->init_marker == OGK_CPD_INIT_MARKER)) {
        safe_command(&ctx->last);
    }
}

/* The input checks of ogk_cpd_step: rates finite, angles checked. */
static ogk_status cpd_check_input(const ogk_cpd_input_t *in)
{
    const ogk_real_t angles[7] = {in->psi, in->theta, in->phi_roll, in->alpha_c,
                              in->beta_c, in->xi, in->phi};
    ogk_status st;
    /* rates: only finiteness matters (a large rate saturates the command) */
    if (!(isfinite(in->rate_p) && isfinite(in->rate_q) && isfinite(in->rate_r))) {
        st = OGK_E_NONFINITE;
    } else {
        st = check_angles(angles, 7u);
    }
    return st;
}

/* ogk_cpd_step on checked input: the command into out and, when finite,
 * committed to ctx; OGK_E_SAFE_COMMAND (ctx untouched) otherwise. */
static ogk_status control_step(ogk_cpd_t *ctx, const ogk_cpd_input_t *in, ogk_cpd_output_t *out)
{
    const ogk_cpd_config_t *cfg = &ctx->cfg;
    ogk_real_t t_a[3];
    ogk_real_t t_b[3];
    ogk_real_t err_y;
    ogk_real_t err_z;
    ogk_real_t err_x;
    ogk_real_t ff_y;
    ogk_real_t ff_z;
    bool yaw_undefined;
    uint32_t flags = 0u;
    ogk_status st = OGK_OK;

    /* eqs. (38)-(39): commanded attitude; direction in a and body axes */
    commanded_direction(in->psi, in->theta, in->phi_roll, in->alpha_c, in->beta_c,
                        in->xi, in->phi, t_a, t_b);
    attitude_of_direction(t_a, &out->psi_c, &out->theta_c, &yaw_undefined);
    out->phi_c = cfg->phi_c;
    if (yaw_undefined) {
        flags |= OGK_CPD_FLAG_YAW_UNDEFINED;
    }
    if (t_b[0] < OGK_R(0.0)) {
        flags |= OGK_CPD_FLAG_BEHIND;
    }

    /* roll error: eq. (45) with the error wrapped to (-pi, pi] */
    err_x = ogk_i_wrap_pi(cfg->phi_c - in->phi_roll);
    if (cfg->pointing == OGK_CPD_POINTING_EULER) {
        /* eq. (46) literally (valid near zero roll only, see cpd.h) */
        err_y = out->theta_c - in->theta;
        err_z = ogk_i_wrap_pi(out->psi_c - in->psi);
    } else {
        pointing_error_body(t_b, &err_y, &err_z);
    }

    /* eqs. (45)-(46) */
    out->m_xc = saturate(pd_term(cfg->k_px, cfg->k_dx, cfg->approach_accel_x, err_x,
                                 in->rate_p),
                         cfg->m_xc_max, OGK_CPD_FLAG_SAT_X, &flags);
    feedforward_rate(ctx, t_a, in->psi, in->theta, in->phi_roll, &ff_y, &ff_z);
    out->delta_yc = saturate(pd_term(cfg->k_py, cfg->k_dy, cfg->approach_accel_y, err_y,
                                     in->rate_q - ff_y),
                             cfg->delta_yc_max, OGK_CPD_FLAG_SAT_Y, &flags);
    /* yaw: eq. (46), -k_pz e_z + k_dz R = -(k_pz e_z - k_dz R): a negative
     * deflection turns about +z_b (eq. 15) */
    out->delta_zc = saturate(-pd_term(cfg->k_pz, cfg->k_dz, cfg->approach_accel_z, err_z,
                                      in->rate_r - ff_z),
                             cfg->delta_zc_max, OGK_CPD_FLAG_SAT_Z, &flags);
    out->err_x = err_x;
    out->err_y = err_y;
    out->err_z = err_z;
    out->flags = flags;
    {
        /* Finite by construction for the gains met in practice (saturate
         * bounds the commands, atan2 and the wrap bound the angles); absurd
         * but finite gains with huge rates could still meet inf - inf. */
        const ogk_real_t v[9] = {out->m_xc, out->delta_yc, out->delta_zc, out->psi_c,
                             out->theta_c, out->phi_c, out->err_x, out->err_y, out->err_z};
        if (!ogk_i_all_finite(v, 9u)) {
            st = OGK_E_SAFE_COMMAND;
        }
    }
    if (st == OGK_OK) {
        ctx->last = *out;
        ctx->dir_prev_a[0] = t_a[0];
        ctx->dir_prev_a[1] = t_a[1];
        ctx->dir_prev_a[2] = t_a[2];
        ctx->has_prev = 1u;
    }
    return st;
}

ogk_status ogk_cpd_step(ogk_cpd_t *ctx, const ogk_cpd_input_t *in,
                        ogk_cpd_output_t *out)
{
    ogk_status st;

    if ((ctx == NULL) || (in == NULL) || (out == NULL)) {
        st = OGK_E_NULL;
    } else if (ctx->init_marker != OGK_CPD_INIT_MARKER) {
        st = OGK_E_NOT_INIT;
    } else {
        st = cpd_check_input(in);
        if (st == OGK_OK) {
            st = control_step(ctx, in, out);
        }
    }
    if (st != OGK_OK) {
        reject(ctx, out);
    }
    return st;
}
