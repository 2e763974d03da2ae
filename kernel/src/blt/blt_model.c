/* blt_model.c -- the right-hand side of docs/design/blt.md sec. 1: the synodic-frame equations of
 * motion (eq. 4) with degree-2 gravity of both bodies (eq. 7 truncated), cannonball SRP (eq. 9,
 * divided by the mass), the solar tide (eq. 10, first order) and BLT thrust (eq. 22); the
 * gravity gradient for the variational equations; the segments' start times and masses. */
#include "blt_internal.h"

#include <math.h>
#include <string.h>

/* Gravity of one body at rho = r - r_body: acc += grad U, hess += d(grad U)/d rho (when non-NULL).
 * U = mu / s + mu R^2 P(rho) / s^5 with P = rho^T Q rho, Q = diag(-C20/2 + 3 C22,
 * -C20/2 - 3 C22, C20): the Cartesian form of eq. (7)'s degree-2 terms. */
static void body_gravity(ogk_real_t mu_b, ogk_real_t ref_radius, ogk_real_t c20, ogk_real_t c22, const ogk_real_t rho[3], /* NOLINT(bugprone-easily-swappable-parameters): eq. (7)'s order */
                         ogk_real_t acc[3], ogk_real_t *hess) /* NOLINT(bugprone-easily-swappable-parameters): acceleration, then its gradient */
{
    const ogk_real_t s2 = (rho[0] * rho[0]) + (rho[1] * rho[1]) + (rho[2] * rho[2]);
    const ogk_real_t s = OGK_SQRT(s2);
    const ogk_real_t inv_s2 = OGK_R(1.0) / s2;
    const ogk_real_t inv_s3 = inv_s2 / s;
    const ogk_real_t k2 = mu_b * ref_radius * ref_radius;
    const ogk_real_t q[3] = {(-OGK_R(0.5) * c20) + (OGK_R(3.0) * c22), (-OGK_R(0.5) * c20) - (OGK_R(3.0) * c22), c20};
    const ogk_real_t inv_s5 = inv_s3 * inv_s2;
    const ogk_real_t inv_s7 = inv_s5 * inv_s2;
    ogk_real_t qrho[3];
    ogk_real_t p = OGK_R(0.0);
    size_t i;

    for (i = 0u; i < 3u; ++i) {
        qrho[i] = q[i] * rho[i];
        p += qrho[i] * rho[i];
    }
    for (i = 0u; i < 3u; ++i) {
        acc[i] += (-mu_b * rho[i] * inv_s3) + (k2 * ((OGK_R(2.0) * qrho[i] * inv_s5) - (OGK_R(5.0) * p * inv_s7 * rho[i])));
    }
    if (hess != NULL) {
        /* H_ij = a rho_i rho_j + b (qrho_i rho_j + rho_i qrho_j) + delta_ij d_i, symmetric: 6 entries */
        const ogk_real_t inv_s9 = inv_s7 * inv_s2;
        const ogk_real_t a = (OGK_R(3.0) * mu_b * inv_s5) + (OGK_R(35.0) * k2 * p * inv_s9);
        const ogk_real_t b = -OGK_R(10.0) * k2 * inv_s7;
        const ogk_real_t d0 = (-mu_b * inv_s3) - (OGK_R(5.0) * k2 * p * inv_s7);
        size_t j;
        for (i = 0u; i < 3u; ++i) {
            for (j = i; j < 3u; ++j) {
                ogk_real_t h = (a * rho[i] * rho[j]) + (b * ((qrho[i] * rho[j]) + (rho[i] * qrho[j])));
                if (i == j) {
                    h += d0 + (OGK_R(2.0) * k2 * q[i] * inv_s5);
                    hess[(i * 3u) + i] += h;
                } else {
                    hess[(i * 3u) + j] += h;
                    hess[(j * 3u) + i] += h;
                }
            }
        }
    }
}

bool ogk_i_blt_rhs(const ogk_blt_model_t *m, const ogk_i_blt_seg_t *seg, ogk_real_t tau, const ogk_real_t x[OGK_BLT_NX],
             ogk_real_t dx[OGK_BLT_NX], ogk_i_blt_rhs_parts_t *parts)
{
    const ogk_real_t t = seg->t_start + tau;
    const ogk_real_t phi = m->sun_angle0 + (m->sun_rate * t);
    const ogk_real_t s_hat[3] = {OGK_COS(phi), OGK_SIN(phi), OGK_R(0.0)};
    const ogk_real_t mass = seg->burn ? (seg->m_start - (m->mass_flow * tau)) : seg->m_start;
    const ogk_real_t body_x[2] = {-m->mu, OGK_R(1.0) - m->mu};
    const ogk_real_t body_mu[2] = {OGK_R(1.0) - m->mu, m->mu};
    ogk_real_t acc[3] = {OGK_R(0.0), OGK_R(0.0), OGK_R(0.0)};
    ogk_real_t *hess = NULL;
    ogk_real_t s_dot_r;
    bool ok = mass > OGK_R(0.0);
    size_t b;

    if (parts != NULL) {
        (void)memset(parts, 0, sizeof(*parts));
        hess = parts->grad;
    }
    for (b = 0u; b < 2u; ++b) {
        const ogk_real_t rho[3] = {x[0] - body_x[b], x[1], x[2]};
        body_gravity(body_mu[b], m->ref_radius[b], m->c20[b], m->c22[b], rho, acc, hess);
    }
    /* eq. (4): Coriolis and centrifugal terms, omega = 1 */
    acc[0] += (OGK_R(2.0) * x[4]) + x[0];
    acc[1] += (-OGK_R(2.0) * x[3]) + x[1];
    /* eq. (10), first-order tide: sun_tidal (3 s (s . r) - r) */
    s_dot_r = (s_hat[0] * x[0]) + (s_hat[1] * x[1]);
    acc[0] += m->sun_tidal * ((OGK_R(3.0) * s_hat[0] * s_dot_r) - x[0]);
    acc[1] += m->sun_tidal * ((OGK_R(3.0) * s_hat[1] * s_dot_r) - x[1]);
    acc[2] -= m->sun_tidal * x[2];
    if (ok) {
        /* eq. (9) / m: pushes away from the Sun */
        const ogk_real_t srp = m->srp_accel / mass;
        acc[0] -= srp * s_hat[0];
        acc[1] -= srp * s_hat[1];
        if (parts != NULL) {
            parts->srp = srp;
        }
    }
    if (ok && seg->burn) {
        ogk_real_t w[3];
        ogk_real_t wn;
        size_t i;
        for (i = 0u; i < 3u; ++i) {
            w[i] = seg->a[i] + (seg->b[i] * tau); /* eq. (21) */
        }
        wn = OGK_SQRT((w[0] * w[0]) + (w[1] * w[1]) + (w[2] * w[2]));
        if (wn > OGK_R(0.0)) {
            const ogk_real_t thrust = m->thrust_accel / mass;
            for (i = 0u; i < 3u; ++i) {
                const ogk_real_t u = w[i] / wn; /* eq. (22) */
                acc[i] += thrust * u;
                if (parts != NULL) {
                    parts->u_hat[i] = u;
                }
            }
            if (parts != NULL) {
                parts->w_norm = wn;
                parts->thrust = thrust;
            }
        } else {
            ok = false;
        }
    }
    if (parts != NULL) {
        const ogk_real_t tide = m->sun_tidal;
        size_t i;
        size_t j;
        parts->grad[0] += OGK_R(1.0); /* centrifugal */
        parts->grad[4] += OGK_R(1.0);
        for (i = 0u; i < 3u; ++i) {
            for (j = 0u; j < 3u; ++j) {
                parts->grad[(i * 3u) + j] += tide * ((OGK_R(3.0) * s_hat[i] * s_hat[j]) - ((i == j) ? OGK_R(1.0) : OGK_R(0.0)));
            }
        }
        for (i = 0u; i < 3u; ++i) {
            parts->s_hat[i] = s_hat[i];
        }
        parts->ds_hat[0] = -m->sun_rate * s_hat[1];
        parts->ds_hat[1] = m->sun_rate * s_hat[0];
        parts->ds_hat[2] = OGK_R(0.0);
        parts->mass = mass;
    }
    dx[0] = x[3];
    dx[1] = x[4];
    dx[2] = x[5];
    dx[3] = acc[0];
    dx[4] = acc[1];
    dx[5] = acc[2];
    return ok;
}

static ogk_real_t segment_start_time(const ogk_blt_config_t *cfg, const ogk_blt_transfer_t *tr, uint32_t k)
{
    ogk_real_t t = tr->t0;
    /* k clamped once to n_segments (every caller passes k < n_segments): one condition */
    const uint32_t k_b = (k < cfg->n_segments) ? k : cfg->n_segments;
    uint32_t j;
    for (j = 0u; j < k_b; ++j) {
        t += tr->seg[j][6];
    }
    return t;
}

static ogk_real_t segment_start_mass(const ogk_blt_config_t *cfg, const ogk_blt_transfer_t *tr, uint32_t k)
{
    ogk_real_t burned = OGK_R(0.0);
    /* k clamped once to n_segments (every caller passes k < n_segments): one condition */
    const uint32_t k_b = (k < cfg->n_segments) ? k : cfg->n_segments;
    uint32_t j;
    for (j = 0u; j < k_b; ++j) {
        if (cfg->segment_kind[j] == OGK_BLT_SEG_BURN) {
            burned += tr->seg[j][6];
        }
    }
    return tr->mass0 - (cfg->model.mass_flow * burned);
}

void ogk_i_blt_segment(const ogk_blt_config_t *cfg, const ogk_blt_transfer_t *tr, uint32_t k, ogk_i_blt_seg_t *seg)
{
    size_t i;
    seg->t_start = segment_start_time(cfg, tr, k);
    seg->m_start = segment_start_mass(cfg, tr, k);
    seg->burn = cfg->segment_kind[k] == OGK_BLT_SEG_BURN;
    for (i = 0u; i < 3u; ++i) {
        seg->a[i] = tr->seg[k][i];
        seg->b[i] = tr->seg[k][3u + i];
    }
}
