/* nmpc_model.c -- the NMPC's predictive model, eqs. (11)-(14) of Starek &
 * Kolmanovsky (2012), with optional third bodies derived from vectors (the
 * printed eqs. 15-18 are wrong: docs/design/nmpc.md), its Jacobians and the
 * Hessian of a weighted sum of its components (the exact SQP Hessian). */
#include "nmpc_internal.h"

#include <math.h>
#include <string.h>

#include "../ogk_checks.h"

/* T_max(r) and mdot_max(r) with their derivatives in r. */
typedef struct {
    ogk_real_t thrust;    /* [MU LU/TU^2] T_max(r) */
    ogk_real_t thrust_dr; /* [MU/TU^2] dT_max/dr */
    ogk_real_t flow;      /* [MU/TU] mdot_max(r) */
    ogk_real_t flow_dr;   /* [MU/(LU TU)] dmdot_max/dr */
} engine_limits_t;

static void engine_limits(const ogk_nmpc_config_t *cfg, ogk_real_t r, engine_limits_t *lim)
{
    if (cfg->power == OGK_NMPC_POWER_SOLAR) {
        /* eq. (14): p(s) = (a1 s^2 + a2 s + a3) / (s^4 (1 + a4 s)), s = r / unit */
        const ogk_real_t s = r / cfg->solar_length_unit;
        const ogk_real_t num = (((cfg->solar_a[0] * s) + cfg->solar_a[1]) * s) + cfg->solar_a[2];
        const ogk_real_t num_ds = (OGK_R(2.0) * cfg->solar_a[0] * s) + cfg->solar_a[1];
        const ogk_real_t s4 = s * s * s * s;
        const ogk_real_t den = s4 * (OGK_R(1.0) + (cfg->solar_a[3] * s));
        const ogk_real_t den_ds = (OGK_R(4.0) * s * s * s * (OGK_R(1.0) + (cfg->solar_a[3] * s))) + (cfg->solar_a[3] * s4);
        const ogk_real_t p = num / den;
        const ogk_real_t p_dr = ((num_ds * den) - (num * den_ds)) / (den * den * cfg->solar_length_unit);
        lim->thrust = cfg->solar_thrust[0] + (cfg->solar_thrust[1] * p);
        lim->thrust_dr = cfg->solar_thrust[1] * p_dr;
        lim->flow = cfg->solar_flow[0] + (cfg->solar_flow[1] * p);
        lim->flow_dr = cfg->solar_flow[1] * p_dr;
    } else {
        lim->thrust = cfg->thrust_max;
        lim->thrust_dr = OGK_R(0.0);
        lim->flow = cfg->mass_flow_max;
        lim->flow_dr = OGK_R(0.0);
    }
}

/* Third body b seen from the spacecraft at (r, theta) and time t: D =
 * phi_b(t) - theta, d = r_sc - r_b in the spacecraft's axes = (r - R cos D,
 * -R sin D), and |d|^2 + eps^2 (eps the softening length). Shared by the
 * acceleration and its Hessian so that both see the same body. */
typedef struct {
    ogk_real_t mu;   /* [LU^3/TU^2] */
    ogk_real_t big_r; /* [LU] the body's orbit radius R */
    ogk_real_t cd;   /* cos D */
    ogk_real_t sd;   /* sin D */
    ogk_real_t d_r;  /* [LU] */
    ogk_real_t d_t;  /* [LU] */
    ogk_real_t d2;   /* [LU^2] |d|^2 + eps^2 */
} body_geom_t;

static void body_geometry(const ogk_nmpc_config_t *cfg, uint32_t b, ogk_real_t t, ogk_real_t r, ogk_real_t theta, /* NOLINT(bugprone-easily-swappable-parameters): internal helper, (t, r, theta) in the model's order; its callers are body_accel and body_hess */
                          body_geom_t *g)
{
    const ogk_real_t delta = (cfg->body_phase0[b] + (cfg->body_rate[b] * t)) - theta;
    const ogk_real_t eps = cfg->body_softening[b];
    g->mu = cfg->body_mu[b];
    g->big_r = cfg->body_radius[b];
    g->cd = OGK_COS(delta);
    g->sd = OGK_SIN(delta);
    g->d_r = r - (g->big_r * g->cd);
    g->d_t = -g->big_r * g->sd;
    g->d2 = (g->d_r * g->d_r) + (g->d_t * g->d_t) + (eps * eps);
}

/* Acceleration of third body b in the spacecraft's (radial, circumferential)
 * axes: direct -mu d / |d|^3 with d = r_sc - r_b, and indirect -mu r_b / R^3
 * (the Sun-centred frame accelerates towards the body), |d|^2 + eps^2 in
 * place of |d|^2 with a softening length eps. d in the spacecraft's
 * axes: (r - R cos D, -R sin D), D = phi_b(t) - theta. Adds the acceleration
 * to acc[2] and, when jac is not NULL, its derivatives in (r, theta, t) to
 * jac[2][3]. */
static ogk_status body_accel(const ogk_nmpc_config_t *cfg, uint32_t b, ogk_real_t t, /* NOLINT(bugprone-easily-swappable-parameters): internal helper, (t, r, theta) in the model's order; its only caller is ogk_i_nmpc_rhs, checked against a Cartesian computation and by central differences (test_nmpc.c) */
                             ogk_real_t r, ogk_real_t theta, ogk_real_t *acc, ogk_real_t jac[2][3])
{
    ogk_status st = OGK_OK;
    body_geom_t geo;
    body_geometry(cfg, b, t, r, theta, &geo);
    const ogk_real_t mu_b = geo.mu;
    const ogk_real_t big_r = geo.big_r;
    const ogk_real_t cd = geo.cd;
    const ogk_real_t sd = geo.sd;
    const ogk_real_t d_r = geo.d_r;
    const ogk_real_t d_t = geo.d_t;
    const ogk_real_t d2 = geo.d2;
    const ogk_real_t ind = mu_b / (big_r * big_r);

    if (!(d2 > OGK_R(1.0e-30))) {
        st = OGK_E_NONFINITE; /* the spacecraft is at the body's centre */
    } else {
        const ogk_real_t d1 = OGK_SQRT(d2);
        const ogk_real_t k3 = mu_b / (d2 * d1);
        acc[0] += (-k3 * d_r) - (ind * cd);
        acc[1] += (-k3 * d_t) - (ind * sd);
        if (jac != NULL) {
            /* dA/dd = -mu (I / D^3 - 3 d d^T / D^5) */
            const ogk_real_t k5 = OGK_R(3.0) * k3 / d2;
            const ogk_real_t g_rr = -k3 + (k5 * d_r * d_r);
            const ogk_real_t g_rt = k5 * d_r * d_t;
            const ogk_real_t g_tt = -k3 + (k5 * d_t * d_t);
            /* dd/dr = (1, 0); dd/dD = (R sin D, -R cos D); dD/dtheta = -1, dD/dt = rate */
            const ogk_real_t dd_r_dD = big_r * sd;
            const ogk_real_t dd_t_dD = -big_r * cd;
            /* indirect term: d/dD of -ind (cos D, sin D) = ind (sin D, -cos D) */
            const ogk_real_t a_r_dD = (g_rr * dd_r_dD) + (g_rt * dd_t_dD) + (ind * sd);
            const ogk_real_t a_t_dD = (g_rt * dd_r_dD) + (g_tt * dd_t_dD) - (ind * cd);
            jac[0][0] += g_rr;
            jac[1][0] += g_rt;
            jac[0][1] -= a_r_dD;
            jac[1][1] -= a_t_dD;
            jac[0][2] += a_r_dD * cfg->body_rate[b];
            jac[1][2] += a_t_dD * cfg->body_rate[b];
        }
    }
    return st;
}

ogk_status ogk_i_nmpc_rhs(const void *data, uint32_t nu, ogk_real_t t, /* NOLINT(bugprone-easily-swappable-parameters): internal, the order of ogk/ocp.h's dynamics (model f(t, x, u) and its Jacobians); checked against eq. (11) and by central differences (test_nmpc.c) */
                          const ogk_real_t *x, const ogk_real_t *u, const ogk_real_t *trig, /* NOLINT(bugprone-easily-swappable-parameters): as above */
                          ogk_real_t *xdot, ogk_real_t *jx, ogk_real_t *ju, ogk_real_t *jt) /* NOLINT(bugprone-easily-swappable-parameters): as above */
{
    /* the heliocentric problem's data is its configuration (nmpc_helio.c) */
    const ogk_nmpc_config_t *cfg = (const ogk_nmpc_config_t *)data;
    ogk_status st = OGK_OK;
    const ogk_real_t r = x[0];
    const ogk_real_t v_r = x[2];
    const ogk_real_t v_t = x[3];
    const ogk_real_t m = x[4];

    /* the callers pass finite x and u (the API checks its inputs, every SQP
     * iterate passed a finite violation test); r and m are checked here (a
     * NaN fails them too) and xdot below, which catches an overflow */
    if (!(r > OGK_R(0.0)) || !(m > OGK_R(0.0))) {
        st = OGK_E_NONFINITE;
    } else {
        const ogk_real_t throttle = (nu > 1u) ? u[1] : OGK_R(1.0);
        const ogk_real_t ca = (trig != NULL) ? trig[0] : OGK_COS(u[0]);
        const ogk_real_t sa = (trig != NULL) ? trig[1] : OGK_SIN(u[0]);
        engine_limits_t lim;
        ogk_real_t pert[2] = { OGK_R(0.0), OGK_R(0.0) };
        ogk_real_t pert_jac[2][3] = { { OGK_R(0.0), OGK_R(0.0), OGK_R(0.0) }, { OGK_R(0.0), OGK_R(0.0), OGK_R(0.0) } };
        /* n_bodies <= OGK_NMPC_MAX_BODIES (ogk_nmpc_init): clamped once, a fixed bound */
        const uint32_t n_bodies = ogk_i_min_u32(cfg->n_bodies, OGK_NMPC_MAX_BODIES);
        uint32_t b;

        engine_limits(cfg, r, &lim);
        for (b = 0u; (b < n_bodies) && (st == OGK_OK); ++b) {
            if (cfg->body_mu[b] > OGK_R(0.0)) { /* mu = 0: an ephemeris for the keep-out only */
                st = body_accel(cfg, b, t, r, x[1], pert, (jx != NULL) ? pert_jac : NULL);
            }
        }
        if (st == OGK_OK) {
            const ogk_real_t inv_r = OGK_R(1.0) / r;
            const ogk_real_t acc = throttle * lim.thrust / m;
            /* eq. (11) and (13) */
            xdot[0] = v_r;
            xdot[1] = v_t * inv_r;
            xdot[2] = (v_t * v_t * inv_r) - (cfg->mu * inv_r * inv_r) + (acc * ca) + pert[0];
            xdot[3] = (-v_t * v_r * inv_r) + (acc * sa) + pert[1];
            xdot[4] = -throttle * lim.flow;
            if (!ogk_i_all_finite(xdot, OGK_NMPC_NX)) {
                st = OGK_E_NONFINITE;
            }
            if ((st == OGK_OK) && (jx != NULL)) {
                const ogk_real_t acc_dr = throttle * lim.thrust_dr / m;
                jx[(0u * OGK_NMPC_NX) + 2u] = OGK_R(1.0);
                jx[(1u * OGK_NMPC_NX) + 0u] = -v_t * inv_r * inv_r;
                jx[(1u * OGK_NMPC_NX) + 3u] = inv_r;
                jx[(2u * OGK_NMPC_NX) + 0u] = (-v_t * v_t * inv_r * inv_r)
                    + (OGK_R(2.0) * cfg->mu * inv_r * inv_r * inv_r) + (acc_dr * ca) + pert_jac[0][0];
                jx[(2u * OGK_NMPC_NX) + 1u] = pert_jac[0][1];
                jx[(2u * OGK_NMPC_NX) + 3u] = OGK_R(2.0) * v_t * inv_r;
                jx[(2u * OGK_NMPC_NX) + 4u] = -acc * ca / m;
                jx[(3u * OGK_NMPC_NX) + 0u] = (v_t * v_r * inv_r * inv_r) + (acc_dr * sa) + pert_jac[1][0];
                jx[(3u * OGK_NMPC_NX) + 1u] = pert_jac[1][1];
                jx[(3u * OGK_NMPC_NX) + 2u] = -v_t * inv_r;
                jx[(3u * OGK_NMPC_NX) + 3u] = -v_r * inv_r;
                jx[(3u * OGK_NMPC_NX) + 4u] = -acc * sa / m;
                jx[(4u * OGK_NMPC_NX) + 0u] = -throttle * lim.flow_dr;
                if (ju != NULL) {
                    ju[(2u * nu) + 0u] = -acc * sa;
                    ju[(3u * nu) + 0u] = acc * ca;
                    if (nu > 1u) {
                        ju[(2u * nu) + 1u] = lim.thrust * ca / m;
                        ju[(3u * nu) + 1u] = lim.thrust * sa / m;
                        ju[(4u * nu) + 1u] = -lim.flow;
                    }
                }
                if (jt != NULL) {
                    jt[0] = OGK_R(0.0);
                    jt[1] = OGK_R(0.0);
                    jt[2] = pert_jac[0][2];
                    jt[3] = pert_jac[1][2];
                    jt[4] = OGK_R(0.0);
                }
            }
        }
    }
    return st;
}

ogk_real_t ogk_i_nmpc_objective(const ogk_nmpc_config_t *cfg,
                            const ogk_nmpc_plan_t *p)
{
    ogk_real_t j;
    if (cfg->objective == OGK_NMPC_MIN_FUEL) {
        j = (p->x[(0u * OGK_NMPC_NX) + 4u] - p->x[(p->nodes * OGK_NMPC_NX) + 4u])
            + (cfg->time_weight * p->horizon);
    } else {
        j = p->horizon;
    }
    return j;
}

/* d2T_max/dr2 and d2mdot_max/dr2 (0 for constant power): eq. (14)'s
 * p den = num differentiated twice, p'' den + 2 p' den' + p den'' = num''. */
static void engine_curvature(const ogk_nmpc_config_t *cfg, ogk_real_t r, ogk_real_t *thrust_drr, ogk_real_t *flow_drr) /* NOLINT(bugprone-easily-swappable-parameters): internal helper, outputs in engine_limits_t's order */
{
    if (cfg->power == OGK_NMPC_POWER_SOLAR) {
        const ogk_real_t s = r / cfg->solar_length_unit;
        const ogk_real_t num = (((cfg->solar_a[0] * s) + cfg->solar_a[1]) * s) + cfg->solar_a[2];
        const ogk_real_t num_ds = (OGK_R(2.0) * cfg->solar_a[0] * s) + cfg->solar_a[1];
        const ogk_real_t s4 = s * s * s * s;
        const ogk_real_t den = s4 * (OGK_R(1.0) + (cfg->solar_a[3] * s));
        const ogk_real_t den_ds = (OGK_R(4.0) * s * s * s * (OGK_R(1.0) + (cfg->solar_a[3] * s))) + (cfg->solar_a[3] * s4);
        const ogk_real_t den_dss = (OGK_R(12.0) * s * s) + (OGK_R(20.0) * cfg->solar_a[3] * s * s * s);
        const ogk_real_t p = num / den;
        const ogk_real_t p_ds = ((num_ds * den) - (num * den_ds)) / (den * den);
        const ogk_real_t p_dss = ((OGK_R(2.0) * cfg->solar_a[0]) - (OGK_R(2.0) * p_ds * den_ds) - (p * den_dss)) / den;
        const ogk_real_t p_drr = p_dss / (cfg->solar_length_unit * cfg->solar_length_unit);
        *thrust_drr = cfg->solar_thrust[1] * p_drr;
        *flow_drr = cfg->solar_flow[1] * p_drr;
    } else {
        *thrust_drr = OGK_R(0.0);
        *flow_drr = OGK_R(0.0);
    }
}

/* Hessian in (r, D) of kappa . A_b for third body b, A_b its acceleration in
 * the spacecraft's axes (body_accel), D = phi_b(t) - theta: out[0] = d2/dr2,
 * out[1] = d2/dr dD, out[2] = d2/dD2. With d = (r - R cos D, -R sin D) and
 * rho^2 = |d|^2 + eps^2, the direct term -mu d / rho^3 has the d-Hessian
 * 3 mu ((kappa d^T + d kappa^T) + (kappa . d) I) / rho^5
 * - 15 mu (kappa . d) d d^T / rho^7, chained through dd/dr = (1, 0),
 * dd/dD = (R sin D, -R cos D), d2d/dD2 = (R cos D, R sin D); the indirect
 * term -ind (cos D, sin D) adds ind (kappa . (cos D, sin D)) to d2/dD2. */
static void body_hess(const ogk_nmpc_config_t *cfg, uint32_t b, ogk_real_t t, ogk_real_t r, ogk_real_t theta, /* NOLINT(bugprone-easily-swappable-parameters): internal helper, (t, r, theta) in body_accel's order; checked by central differences of the interval's gradient (test_nmpc.c) */
                      const ogk_real_t *kappa, ogk_real_t *out)
{
    body_geom_t geo;
    body_geometry(cfg, b, t, r, theta, &geo);
    const ogk_real_t mu_b = geo.mu;
    const ogk_real_t big_r = geo.big_r;
    const ogk_real_t cd = geo.cd;
    const ogk_real_t sd = geo.sd;
    const ogk_real_t d_r = geo.d_r;
    const ogk_real_t d_t = geo.d_t;
    const ogk_real_t rho2 = geo.d2;
    const ogk_real_t rho = OGK_SQRT(rho2);
    const ogk_real_t k3 = mu_b / (rho2 * rho);
    const ogk_real_t k5 = OGK_R(3.0) * k3 / rho2;
    const ogk_real_t k7 = OGK_R(5.0) * k5 / rho2;
    const ogk_real_t kd = (kappa[0] * d_r) + (kappa[1] * d_t);
    const ogk_real_t ind = mu_b / (big_r * big_r);
    /* d-Hessian of kappa . A_direct (symmetric 2 x 2) and its gradient */
    const ogk_real_t h_rr = (OGK_R(2.0) * k5 * kappa[0] * d_r) + (k5 * kd) - (k7 * kd * d_r * d_r);
    const ogk_real_t h_rt = (k5 * ((kappa[0] * d_t) + (kappa[1] * d_r))) - (k7 * kd * d_r * d_t);
    const ogk_real_t h_tt = (OGK_R(2.0) * k5 * kappa[1] * d_t) + (k5 * kd) - (k7 * kd * d_t * d_t);
    const ogk_real_t g_r = (-k3 * kappa[0]) + (k5 * kd * d_r);
    const ogk_real_t g_t = (-k3 * kappa[1]) + (k5 * kd * d_t);
    const ogk_real_t e_r = big_r * sd;  /* dd/dD */
    const ogk_real_t e_t = -big_r * cd;
    out[0] = h_rr;
    out[1] = (h_rr * e_r) + (h_rt * e_t);
    out[2] = (e_r * ((h_rr * e_r) + (h_rt * e_t))) + (e_t * ((h_rt * e_r) + (h_tt * e_t)))
        + (g_r * big_r * cd) + (g_t * big_r * sd)
        + (ind * ((kappa[0] * cd) + (kappa[1] * sd)));
}

void ogk_i_nmpc_rhs_hess(const void *data, uint32_t nu, ogk_real_t t, /* NOLINT(bugprone-easily-swappable-parameters): internal, the order of ogk_i_nmpc_rhs; checked by central differences of the interval's gradient (test_nmpc.c) */
                         const ogk_real_t *x, const ogk_real_t *u, const ogk_real_t *trig, /* NOLINT(bugprone-easily-swappable-parameters): as above */
                         const ogk_real_t *kappa, ogk_real_t *hz) /* NOLINT(bugprone-easily-swappable-parameters): as above */
{
    const ogk_nmpc_config_t *cfg = (const ogk_nmpc_config_t *)data;
    /* z = (r, theta, v_r, v_theta, m, alpha[, w], t); g = kappa . f(z) */
    const size_t zs = OGK_I_NMPC_NZ;
    const size_t i_a = OGK_NMPC_NX;
    const size_t i_w = OGK_NMPC_NX + 1u;
    const size_t i_t = OGK_NMPC_NX + (size_t)nu;
    const ogk_real_t r = x[0];
    const ogk_real_t v_r = x[2];
    const ogk_real_t v_t = x[3];
    const ogk_real_t m = x[4];
    const ogk_real_t throttle = (nu > 1u) ? u[1] : OGK_R(1.0);
    const ogk_real_t inv_r = OGK_R(1.0) / r;
    const ogk_real_t inv_r2 = inv_r * inv_r;
    const ogk_real_t inv_r3 = inv_r2 * inv_r;
    const ogk_real_t inv_m = OGK_R(1.0) / m;
    /* q = kappa . (0, 0, cos a, sin a, 0) and its alpha derivative */
    const ogk_real_t q = (kappa[2] * trig[0]) + (kappa[3] * trig[1]);
    const ogk_real_t q_a = (-kappa[2] * trig[1]) + (kappa[3] * trig[0]);
    engine_limits_t lim;
    ogk_real_t thrust_drr;
    ogk_real_t flow_drr;
    /* n_bodies <= OGK_NMPC_MAX_BODIES (ogk_nmpc_init): clamped once, a fixed bound */
    const uint32_t n_bodies = ogk_i_min_u32(cfg->n_bodies, OGK_NMPC_MAX_BODIES);
    uint32_t b;

    engine_limits(cfg, r, &lim);
    engine_curvature(cfg, r, &thrust_drr, &flow_drr);
    /* hz is zeroed by the caller (ogk/ocp.h): only the structural nonzeros are written */
    /* eq. (11): the central body and the transport terms */
    hz[(0u * zs) + 0u] = (kappa[1] * OGK_R(2.0) * v_t * inv_r3)
        + (kappa[2] * ((OGK_R(2.0) * v_t * v_t * inv_r3) - (OGK_R(6.0) * cfg->mu * inv_r2 * inv_r2)))
        - (kappa[3] * OGK_R(2.0) * v_t * v_r * inv_r3)
        + (throttle * thrust_drr * inv_m * q) - (kappa[4] * throttle * flow_drr);
    hz[(0u * zs) + 2u] = kappa[3] * v_t * inv_r2;
    hz[(0u * zs) + 3u] = ((-kappa[1] - (OGK_R(2.0) * kappa[2] * v_t)) + (kappa[3] * v_r)) * inv_r2;
    hz[(2u * zs) + 3u] = -kappa[3] * inv_r;
    hz[(3u * zs) + 3u] = OGK_R(2.0) * kappa[2] * inv_r;
    /* the thrust w T(r) / m (cos a, sin a) and the flow -w mdot(r) */
    hz[(0u * zs) + 4u] = -throttle * lim.thrust_dr * inv_m * inv_m * q;
    hz[(0u * zs) + i_a] = throttle * lim.thrust_dr * inv_m * q_a;
    hz[(4u * zs) + 4u] = OGK_R(2.0) * throttle * lim.thrust * inv_m * inv_m * inv_m * q;
    hz[(4u * zs) + i_a] = -throttle * lim.thrust * inv_m * inv_m * q_a;
    hz[(i_a * zs) + i_a] = -throttle * lim.thrust * inv_m * q;
    if (nu > 1u) {
        hz[(0u * zs) + i_w] = (lim.thrust_dr * inv_m * q) - (kappa[4] * lim.flow_dr);
        hz[(4u * zs) + i_w] = -lim.thrust * inv_m * inv_m * q;
        hz[(i_a * zs) + i_w] = lim.thrust * inv_m * q_a;
    }
    /* third bodies: (r, D) with D = phi_b(t) - theta, dD/dtheta = -1, dD/dt = rate */
    for (b = 0u; b < n_bodies; ++b) {
        if (cfg->body_mu[b] > OGK_R(0.0)) {
            ogk_real_t hb[3];
            const ogk_real_t rate = cfg->body_rate[b];
            body_hess(cfg, b, t, r, x[1], &kappa[2], hb);
            hz[(0u * zs) + 0u] += hb[0];
            hz[(0u * zs) + 1u] -= hb[1];
            hz[(0u * zs) + i_t] += rate * hb[1];
            hz[(1u * zs) + 1u] += hb[2];
            hz[(1u * zs) + i_t] -= rate * hb[2];
            hz[(i_t * zs) + i_t] += rate * rate * hb[2];
        }
    }
}
