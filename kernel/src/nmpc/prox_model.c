/* prox_model.c -- the planar proximity approach as an ogk/ocp.h problem:
 * the Clohessy-Wiltshire equations in the target's Hill frame with a
 * throttled engine (ogk/proximity.h), their Jacobians, the Hessian of a
 * weighted sum of their components, the hold point and the keep-out discs,
 * over an ogk_prox_model_t (docs/design/nmpc-problem.md, "The second problem").
 *
 * The sweeps of the solver (nmpc_shoot.c jx_column and stage_k,
 * nmpc_shoot_hess.c stage_m_column and add_stage_curvature) read only the
 * structural nonzeros ogk/ocp.h lists; this model's are a subset of them:
 *   jx: x_0' = x_2 (jx[2] = 1), x_1' = x_3 (jx[8] = 1, jx[5] = 0),
 *       v_x' in x_0, x_3, m (jx[10], jx[13], jx[14]),
 *       v_y' in x_2, m (jx[17], jx[19]); m' in none of the states;
 *   ju: rows 2, 3 (alpha, w) and row 4 (w); jt: 0 (time-invariant);
 *   hz: the thrust term only, pairs (m, m), (m, alpha), (alpha, alpha),
 *       (m, w), (alpha, w) (the CW terms are linear, the flow linear in w).
 * test_proximity.c checks every other entry is exactly 0. */
#include "ogk/proximity.h"

#include <math.h>
#include <string.h>

#include "../ogk_checks.h"

#define NX ((size_t)OGK_OCP_NX)
/* OGK_OCP_NZ from its atoms, as a size_t (no composite expression cast) */
#define NZ (((size_t)OGK_OCP_NX + (size_t)OGK_OCP_MAX_NU) + 1u)
#if OGK_OCP_NZ != (OGK_OCP_NX + OGK_OCP_MAX_NU + 1u)
#error "NZ is no longer ogk/ocp.h's OGK_OCP_NZ: hz's stride would differ from the solver's"
#endif

#if OGK_PROX_MAX_KEEPOUT > OGK_OCP_MAX_KEEPOUT
#error "OGK_PROX_MAX_KEEPOUT exceeds the solver's OGK_OCP_MAX_KEEPOUT (ogk/ocp.h)"
#endif

/* The problem's data: ogk_nmpc_init_problem stores the ogk_prox_model_t
 * pointer it is given as `data`, and the solver hands it back unchanged to
 * every callback of ogk_prox_problem (docs/evidence/misra-deviations.md, D10). */
static const ogk_prox_model_t *prox_model(const void *data)
{
    return (const ogk_prox_model_t *)data;
}

static uint32_t prox_structure(const void *data, uint32_t nu)
{
    (void)data;
    (void)nu;
    /* autonomous (no t column); with nu = 2 the flow -w mdot_max depends on
     * u, so not OGK_OCP_FLOW_FIXED (with nu = 1 the throttle is 1 and the
     * flow fixed, but the wrapper always flies the throttled engine) */
    return 0u;
}

static ogk_status prox_dynamics(const void *data, uint32_t nu, ogk_real_t t, /* NOLINT(bugprone-easily-swappable-parameters): the order of ogk_ocp_problem_t.dynamics (ogk/ocp.h); checked against the closed form and by central differences (test_proximity.c) */
                                const ogk_real_t *x, const ogk_real_t *u, const ogk_real_t *trig, /* NOLINT(bugprone-easily-swappable-parameters): as above */
                                ogk_real_t *xdot, ogk_real_t *jx, ogk_real_t *ju, ogk_real_t *jt) /* NOLINT(bugprone-easily-swappable-parameters): as above */
{
    const ogk_prox_model_t *mdl = prox_model(data);
    ogk_status st = OGK_OK;
    const ogk_real_t m = x[4];
    (void)t;
    /* m > 0 is the model's domain (a NaN fails it too); xdot's finite test
     * below catches any other non-finite input or an overflow */
    if (!(m > OGK_R(0.0))) {
        st = OGK_E_NONFINITE;
    } else {
        const ogk_real_t n = mdl->mean_motion;
        const ogk_real_t throttle = (nu > 1u) ? u[1] : OGK_R(1.0);
        const ogk_real_t ca = (trig != NULL) ? trig[0] : OGK_COS(u[0]);
        const ogk_real_t sa = (trig != NULL) ? trig[1] : OGK_SIN(u[0]);
        const ogk_real_t acc = throttle * mdl->thrust_max / m;
        /* ogk/proximity.h: the CW equations with the thrust T_max w / m along alpha */
        xdot[0] = x[2];
        xdot[1] = x[3];
        xdot[2] = (OGK_R(3.0) * n * n * x[0]) + (OGK_R(2.0) * n * x[3]) + (acc * ca);
        xdot[3] = (-OGK_R(2.0) * n * x[2]) + (acc * sa);
        xdot[4] = -throttle * mdl->mass_flow_max;
        if (!ogk_i_all_finite(xdot, NX)) {
            st = OGK_E_NONFINITE;
        }
        if ((st == OGK_OK) && (jx != NULL)) {
            jx[(0u * NX) + 2u] = OGK_R(1.0);
            jx[(1u * NX) + 0u] = OGK_R(0.0); /* read by the sweep (the heliocentric theta' depends on r) */
            jx[(1u * NX) + 3u] = OGK_R(1.0);
            jx[(2u * NX) + 0u] = OGK_R(3.0) * n * n;
            jx[(2u * NX) + 3u] = OGK_R(2.0) * n;
            jx[(2u * NX) + 4u] = -acc * ca / m;
            jx[(3u * NX) + 2u] = -OGK_R(2.0) * n;
            jx[(3u * NX) + 4u] = -acc * sa / m;
            if (ju != NULL) {
                ju[(2u * nu) + 0u] = -acc * sa;
                ju[(3u * nu) + 0u] = acc * ca;
                if (nu > 1u) {
                    ju[(2u * nu) + 1u] = mdl->thrust_max * ca / m;
                    ju[(3u * nu) + 1u] = mdl->thrust_max * sa / m;
                    ju[(4u * nu) + 1u] = -mdl->mass_flow_max;
                }
            }
            if (jt != NULL) {
                (void)memset(jt, 0, NX * sizeof(ogk_real_t)); /* time-invariant */
            }
        }
    }
    return st;
}

static void prox_dynamics_hess(const void *data, uint32_t nu, ogk_real_t t, /* NOLINT(bugprone-easily-swappable-parameters): the order of ogk_ocp_problem_t.dynamics_hess (ogk/ocp.h); checked by central differences of kappa . jacobian (test_proximity.c) */
                               const ogk_real_t *x, const ogk_real_t *u, const ogk_real_t *trig, /* NOLINT(bugprone-easily-swappable-parameters): as above */
                               const ogk_real_t *kappa, ogk_real_t *hz) /* NOLINT(bugprone-easily-swappable-parameters): as above */
{
    const ogk_prox_model_t *mdl = prox_model(data);
    const size_t i_a = NX;        /* alpha's index in z */
    const size_t i_w = NX + 1u;   /* w's (nu = 2) */
    const ogk_real_t inv_m = OGK_R(1.0) / x[4];
    const ogk_real_t throttle = (nu > 1u) ? u[1] : OGK_R(1.0);
    const ogk_real_t ca = (trig != NULL) ? trig[0] : OGK_COS(u[0]);
    const ogk_real_t sa = (trig != NULL) ? trig[1] : OGK_SIN(u[0]);
    /* kappa . f = (linear CW and flow terms) + (T_max w / m) q(alpha),
     * q = kappa_2 cos(alpha) + kappa_3 sin(alpha), q_alpha = -kappa_2 sin + kappa_3 cos,
     * q_alpha_alpha = -q */
    const ogk_real_t q = (kappa[2] * ca) + (kappa[3] * sa);
    const ogk_real_t q_a = (-kappa[2] * sa) + (kappa[3] * ca);
    const ogk_real_t tw = throttle * mdl->thrust_max;
    (void)t;
    /* ogk/ocp.h: the caller zeroes hz before every call; only the thrust term's nonzeros are written */
    hz[(4u * NZ) + 4u] = OGK_R(2.0) * tw * inv_m * inv_m * inv_m * q;
    hz[(4u * NZ) + i_a] = -tw * inv_m * inv_m * q_a;
    hz[(i_a * NZ) + i_a] = -tw * inv_m * q;
    if (nu > 1u) {
        hz[(4u * NZ) + i_w] = -mdl->thrust_max * inv_m * inv_m * q;
        hz[(i_a * NZ) + i_w] = mdl->thrust_max * inv_m * q_a;
    }
}

static void prox_target(const void *data, ogk_real_t t_f, ogk_real_t *x_target, ogk_real_t *x_target_rate) /* NOLINT(bugprone-easily-swappable-parameters): the order of ogk_ocp_problem_t.target (ogk/ocp.h) */
{
    const ogk_prox_model_t *mdl = prox_model(data);
    (void)t_f;
    /* the hold point at rest, fixed in the Hill frame */
    x_target[0] = mdl->hold[0];
    x_target[1] = mdl->hold[1];
    x_target[2] = OGK_R(0.0);
    x_target[3] = OGK_R(0.0);
    (void)memset(x_target_rate, 0, (size_t)OGK_OCP_NC * sizeof(ogk_real_t));
}

static ogk_real_t prox_keepout_radius(const void *data, size_t j)
{
    const ogk_prox_model_t *mdl = prox_model(data);
    ogk_real_t r = OGK_R(0.0);
    /* n_keepout <= OGK_PROX_MAX_KEEPOUT (ogk_prox_init): the clamp keeps the read in bounds for a
     * caller of the table with data it has not validated */
    if (j < ogk_i_min_size(mdl->n_keepout, OGK_PROX_MAX_KEEPOUT)) {
        r = mdl->keepout_radius[j];
    }
    return r;
}

static ogk_real_t prox_keepout_distance(const void *data, size_t j, const ogk_real_t *x, ogk_real_t t, /* NOLINT(bugprone-easily-swappable-parameters): the order of ogk_ocp_problem_t.keepout_distance (ogk/ocp.h); checked by central differences (test_proximity.c) */
                                    ogk_real_t *d_x0, ogk_real_t *d_x1, ogk_real_t *d_t) /* NOLINT(bugprone-easily-swappable-parameters): as above */
{
    const ogk_prox_model_t *mdl = prox_model(data);
    ogk_real_t d = OGK_R(0.0);
    ogk_real_t inv = OGK_R(0.0);
    ogk_real_t dx = OGK_R(0.0);
    ogk_real_t dy = OGK_R(0.0);
    (void)t;
    if (j < OGK_PROX_MAX_KEEPOUT) {
        /* the disc's centre is fixed in the Hill frame: d = |(x_0, x_1) - c_j| */
        dx = x[0] - mdl->keepout_centre[2u * j];
        dy = x[1] - mdl->keepout_centre[(2u * j) + 1u];
        d = OGK_SQRT((dx * dx) + (dy * dy));
    }
    if (d > OGK_REAL_TINY) {
        inv = OGK_R(1.0) / d;
    }
    /* at the centre the gradient is undefined: 0 (the keep-out row is then the
     * violation alone, as for the heliocentric bodies) */
    *d_x0 = dx * inv;
    *d_x1 = dy * inv;
    *d_t = OGK_R(0.0);
    return d;
}

static void prox_model_key(const void *data, ogk_real_t *key)
{
    const ogk_prox_model_t *mdl = prox_model(data);
    /* what the dynamics depend on (the discs do not enter the sensitivities;
     * the solver adds its own RK4 step count) */
    (void)memset(key, 0, (size_t)OGK_OCP_MODEL_KEY * sizeof(ogk_real_t));
    key[0] = mdl->mean_motion;
    key[1] = mdl->thrust_max;
    key[2] = mdl->mass_flow_max;
}

static bool prox_state_valid(const void *data, const ogk_real_t *x, size_t n)
{
    /* n <= OGK_NMPC_MAX_NODES + 1 (a plan's nodes, or one measured state): clamped once, a fixed bound */
    const size_t n_b = ogk_i_min_size(n, (size_t)OGK_NMPC_MAX_NODES + 1u);
    bool valid = true;
    size_t k;
    (void)data;
    /* any finite position and velocity in the Hill frame; a positive mass */
    for (k = 0u; (k < n_b) && valid; ++k) {
        valid = ogk_i_all_finite(&x[k * NX], NX) && (x[(k * NX) + 4u] > OGK_R(0.0));
    }
    return valid;
}

const ogk_ocp_problem_t ogk_prox_problem = {
    prox_structure,
    prox_dynamics,
    prox_dynamics_hess,
    prox_target,
    prox_keepout_radius,
    prox_keepout_distance,
    prox_model_key,
    prox_state_valid,
    NULL,
};
