/* nmpc_helio.c -- the heliocentric rendezvous of Starek & Kolmanovsky
 * (2012) as a problem of the NMPC's solver (ogk/ocp.h): its data is the
 * context's ogk_nmpc_config_t; the model is nmpc_model.c (eqs. 11-14 with
 * the third bodies), the terminal set eq. (5) with the target on its
 * circular orbit (eq. 6), the keep-out discs the planets' (docs/design/nmpc-flight.md,
 * "Robustness"), the update the release of a departure planet's gravity
 * (body_release). */
#include "nmpc_internal.h"

#include <math.h>
#include <string.h>

#include "../ogk_checks.h"

static const ogk_nmpc_config_t *helio_cfg(const void *data)
{
    return (const ogk_nmpc_config_t *)data;
}

/* A third body pulls (mu > 0): the model then depends on time. A body with
 * mu = 0 is an ephemeris for the keep-out only. Constant power: the mass
 * flow of the constant engine is fixed. */
static uint32_t helio_structure(const void *data, uint32_t nu)
{
    const ogk_nmpc_config_t *cfg = helio_cfg(data);
    /* n_bodies <= OGK_NMPC_MAX_BODIES (ogk_nmpc_init): clamped once, a fixed bound */
    const uint32_t n_bodies = ogk_i_min_u32(cfg->n_bodies, OGK_NMPC_MAX_BODIES);
    uint32_t flags = 0u;
    uint32_t b;
    for (b = 0u; b < n_bodies; ++b) {
        if (cfg->body_mu[b] > OGK_R(0.0)) {
            flags |= OGK_OCP_TIME_VARYING;
        }
    }
    if (cfg->power != OGK_NMPC_POWER_SOLAR) {
        flags |= OGK_OCP_FLOW_FIXED;
    }
    (void)nu;
    return flags;
}

/* eq. (5) with eq. (6): the target on its circular orbit at t_f, at rest in
 * its radial velocity and at the circular speed. */
static void helio_target(const void *data, ogk_real_t t_f, ogk_real_t *x_target, ogk_real_t *x_target_rate) /* NOLINT(bugprone-easily-swappable-parameters): the order of ogk/ocp.h's target (state, then its rate); checked by the records and test_nmpc.c */
{
    const ogk_nmpc_config_t *cfg = helio_cfg(data);
    x_target[0] = cfg->target_radius;
    x_target[1] = cfg->target_phase0 + (cfg->target_rate * t_f);
    x_target[2] = OGK_R(0.0);
    x_target[3] = OGK_SQRT(cfg->mu / cfg->target_radius);
    x_target_rate[0] = OGK_R(0.0);
    x_target_rate[1] = cfg->target_rate;
    x_target_rate[2] = OGK_R(0.0);
    x_target_rate[3] = OGK_R(0.0);
}

static ogk_real_t helio_keepout_radius(const void *data, size_t j)
{
    const ogk_nmpc_config_t *cfg = helio_cfg(data);
    return (j < (size_t)cfg->n_bodies) ? cfg->keepout_radius[j] : OGK_R(0.0);
}

/* Distance of state x at time t from body b's centre and its derivatives in
 * r, theta and t (d^2 = r^2 + R^2 - 2 r R cos(theta - phi)). */
static ogk_real_t helio_keepout_distance(const void *data, size_t j, const ogk_real_t *x, ogk_real_t t, /* NOLINT(bugprone-easily-swappable-parameters): the order of ogk/ocp.h's keepout_distance, checked by test_keepout_detour */
                                     ogk_real_t *d_x0, ogk_real_t *d_x1, ogk_real_t *d_t)
{
    const ogk_nmpc_config_t *cfg = helio_cfg(data);
    const size_t b = (j < OGK_NMPC_MAX_BODIES) ? j : 0u;
    const ogk_real_t big_r = cfg->body_radius[b];
    const ogk_real_t phi = cfg->body_phase0[b] + (cfg->body_rate[b] * t);
    const ogk_real_t cd = OGK_COS(x[1] - phi);
    const ogk_real_t sd = OGK_SIN(x[1] - phi);
    const ogk_real_t d2 = ((x[0] * x[0]) + (big_r * big_r)) - (OGK_R(2.0) * x[0] * big_r * cd);
    ogk_real_t d = OGK_R(0.0);
    ogk_real_t inv = OGK_R(0.0);
    if (d2 > OGK_R(0.0)) {
        d = OGK_SQRT(d2);
    }
    if (d > OGK_REAL_TINY) {
        inv = OGK_R(1.0) / d;
    }
    *d_x0 = (x[0] - (big_r * cd)) * inv;
    *d_x1 = x[0] * big_r * sd * inv;
    *d_t = -(*d_x1) * cfg->body_rate[b];
    return d;
}

/* The fields ogk_i_nmpc_shoot reads, as doubles (the integers exactly). */
static void helio_model_key(const void *data, ogk_real_t *key)
{
    const ogk_nmpc_config_t *cfg = helio_cfg(data);
    size_t b;
    key[0] = cfg->mu;
    key[1] = (ogk_real_t)cfg->engine;
    key[2] = (ogk_real_t)cfg->power;
    key[3] = cfg->thrust_max;
    key[4] = cfg->mass_flow_max;
    key[5] = cfg->solar_length_unit;
    key[6] = (ogk_real_t)cfg->n_bodies;
    key[7] = (ogk_real_t)cfg->rk4_steps;
    (void)memcpy(&key[8], cfg->solar_a, sizeof(cfg->solar_a));
    (void)memcpy(&key[12], cfg->solar_thrust, sizeof(cfg->solar_thrust));
    (void)memcpy(&key[14], cfg->solar_flow, sizeof(cfg->solar_flow));
    for (b = 0u; b < (size_t)OGK_NMPC_MAX_BODIES; ++b) {
        ogk_real_t *body = &key[16u + (5u * b)];
        body[0] = cfg->body_mu[b];
        body[1] = cfg->body_radius[b];
        body[2] = cfg->body_phase0[b];
        body[3] = cfg->body_rate[b];
        body[4] = cfg->body_softening[b];
    }
}

/* r > 0 and m > 0 (a NaN fails both) in every state. */
static bool helio_state_valid(const void *data, const ogk_real_t *x, size_t n)
{
    /* n <= OGK_NMPC_MAX_NODES + 1 (the callers' plans): clamped, a fixed bound */
    const size_t n_b = ogk_i_min_size(n, (size_t)OGK_NMPC_MAX_NODES + 1u);
    bool ok = true;
    size_t k;
    (void)data;
    for (k = 0u; (k < n_b) && ok; ++k) {
        ok = (x[(k * OGK_NMPC_NX) + 0u] > OGK_R(0.0)) && (x[(k * OGK_NMPC_NX) + 4u] > OGK_R(0.0));
    }
    return ok;
}

/* Two-body energy of state x at time t relative to body b, |v - v_b|^2 / 2
 * - mu_b / |r - r_b| [LU^2/TU^2] (>= 0: on an escape orbit from b). */
static ogk_real_t body_energy(const ogk_nmpc_config_t *cfg, size_t b, const ogk_real_t *x, ogk_real_t t, ogk_real_t d) /* NOLINT(bugprone-easily-swappable-parameters): internal helper, (t, then the distance at t); its only caller is helio_update */
{
    const ogk_real_t phi = cfg->body_phase0[b] + (cfg->body_rate[b] * t);
    const ogk_real_t ct = OGK_COS(x[1]);
    const ogk_real_t st = OGK_SIN(x[1]);
    const ogk_real_t cp = OGK_COS(phi);
    const ogk_real_t sp = OGK_SIN(phi);
    const ogk_real_t vb = cfg->body_radius[b] * cfg->body_rate[b];
    /* Cartesian velocities: the spacecraft's (v_r, v_theta) rotated by theta, the body's R phi' e_phi */
    const ogk_real_t dvx = ((x[2] * ct) - (x[3] * st)) + (vb * sp);
    const ogk_real_t dvy = ((x[2] * st) + (x[3] * ct)) - (vb * cp);
    const ogk_real_t pot = (d > OGK_REAL_TINY) ? (cfg->body_mu[b] / d) : OGK_R(0.0);
    return (OGK_R(0.5) * ((dvx * dvx) + (dvy * dvy))) - pot;
}

/* A body whose release radius the measured state is beyond, on an escape
 * orbit from it (two-body energy >= 0: it does not fall back), leaves the
 * predictive model for good (body_release): OGK_NMPC_FLAG_RELEASED. */
static uint32_t helio_update(void *data, ogk_real_t t, const ogk_real_t *x)
{
    ogk_nmpc_config_t *cfg = (ogk_nmpc_config_t *)data;
    /* n_bodies <= OGK_NMPC_MAX_BODIES (ogk_nmpc_init): clamped once, a fixed bound */
    const size_t n_bodies = ogk_i_min_size(cfg->n_bodies, OGK_NMPC_MAX_BODIES);
    uint32_t flags = 0u;
    size_t b;
    for (b = 0u; b < n_bodies; ++b) {
        if ((cfg->body_release[b] > OGK_R(0.0)) && (cfg->body_mu[b] > OGK_R(0.0))) {
            ogk_real_t d_x0;
            ogk_real_t d_x1;
            ogk_real_t d_t;
            const ogk_real_t d = helio_keepout_distance(data, b, x, t, &d_x0, &d_x1, &d_t);
            if ((d > cfg->body_release[b]) && (body_energy(cfg, b, x, t, d) >= OGK_R(0.0))) {
                cfg->body_mu[b] = OGK_R(0.0);
                flags |= OGK_NMPC_FLAG_RELEASED;
            }
        }
    }
    return flags;
}

const ogk_ocp_problem_t ogk_i_nmpc_helio_problem = {
    helio_structure,
    ogk_i_nmpc_rhs,
    ogk_i_nmpc_rhs_hess,
    helio_target,
    helio_keepout_radius,
    helio_keepout_distance,
    helio_model_key,
    helio_state_valid,
    helio_update
};
