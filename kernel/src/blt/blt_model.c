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
static void body_gravity(double mu_b, double ref_radius, double c20, double c22, const double rho[3], /* NOLINT(bugprone-easily-swappable-parameters): eq. (7)'s order */
                         double acc[3], double *hess) /* NOLINT(bugprone-easily-swappable-parameters): acceleration, then its gradient */
{
    const double s2 = (rho[0] * rho[0]) + (rho[1] * rho[1]) + (rho[2] * rho[2]);
    const double s = sqrt(s2);
    const double inv_s2 = 1.0 / s2;
    const double inv_s3 = inv_s2 / s;
    const double k2 = mu_b * ref_radius * ref_radius;
    const double q[3] = {(-0.5 * c20) + (3.0 * c22), (-0.5 * c20) - (3.0 * c22), c20};
    const double inv_s5 = inv_s3 * inv_s2;
    const double inv_s7 = inv_s5 * inv_s2;
    double qrho[3];
    double p = 0.0;
    size_t i;

    for (i = 0u; i < 3u; ++i) {
        qrho[i] = q[i] * rho[i];
        p += qrho[i] * rho[i];
    }
    for (i = 0u; i < 3u; ++i) {
        acc[i] += (-mu_b * rho[i] * inv_s3) + (k2 * ((2.0 * qrho[i] * inv_s5) - (5.0 * p * inv_s7 * rho[i])));
    }
    if (hess != NULL) {
        /* H_ij = a rho_i rho_j + b (qrho_i rho_j + rho_i qrho_j) + delta_ij d_i, symmetric: 6 entries */
        const double inv_s9 = inv_s7 * inv_s2;
        const double a = (3.0 * mu_b * inv_s5) + (35.0 * k2 * p * inv_s9);
        const double b = -10.0 * k2 * inv_s7;
        const double d0 = (-mu_b * inv_s3) - (5.0 * k2 * p * inv_s7);
        size_t j;
        for (i = 0u; i < 3u; ++i) {
            for (j = i; j < 3u; ++j) {
                double h = (a * rho[i] * rho[j]) + (b * ((qrho[i] * rho[j]) + (rho[i] * qrho[j])));
                if (i == j) {
                    h += d0 + (2.0 * k2 * q[i] * inv_s5);
                    hess[(i * 3u) + i] += h;
                } else {
                    hess[(i * 3u) + j] += h;
                    hess[(j * 3u) + i] += h;
                }
            }
        }
    }
}

bool ogk_i_blt_rhs(const ogk_blt_model_t *m, const ogk_i_blt_seg_t *seg, double tau, const double x[OGK_BLT_NX],
             double dx[OGK_BLT_NX], ogk_i_blt_rhs_parts_t *parts)
{
    const double t = seg->t_start + tau;
    const double phi = m->sun_angle0 + (m->sun_rate * t);
    const double s_hat[3] = {cos(phi), sin(phi), 0.0};
    const double mass = seg->burn ? (seg->m_start - (m->mass_flow * tau)) : seg->m_start;
    const double body_x[2] = {-m->mu, 1.0 - m->mu};
    const double body_mu[2] = {1.0 - m->mu, m->mu};
    double acc[3] = {0.0, 0.0, 0.0};
    double *hess = NULL;
    double s_dot_r;
    bool ok = mass > 0.0;
    size_t b;

    if (parts != NULL) {
        (void)memset(parts, 0, sizeof(*parts));
        hess = parts->grad;
    }
    for (b = 0u; b < 2u; ++b) {
        const double rho[3] = {x[0] - body_x[b], x[1], x[2]};
        body_gravity(body_mu[b], m->ref_radius[b], m->c20[b], m->c22[b], rho, acc, hess);
    }
    /* eq. (4): Coriolis and centrifugal terms, omega = 1 */
    acc[0] += (2.0 * x[4]) + x[0];
    acc[1] += (-2.0 * x[3]) + x[1];
    /* eq. (10), first-order tide: sun_tidal (3 s (s . r) - r) */
    s_dot_r = (s_hat[0] * x[0]) + (s_hat[1] * x[1]);
    acc[0] += m->sun_tidal * ((3.0 * s_hat[0] * s_dot_r) - x[0]);
    acc[1] += m->sun_tidal * ((3.0 * s_hat[1] * s_dot_r) - x[1]);
    acc[2] -= m->sun_tidal * x[2];
    if (ok) {
        /* eq. (9) / m: pushes away from the Sun */
        const double srp = m->srp_accel / mass;
        acc[0] -= srp * s_hat[0];
        acc[1] -= srp * s_hat[1];
        if (parts != NULL) {
            parts->srp = srp;
        }
    }
    if (ok && seg->burn) {
        double w[3];
        double wn;
        size_t i;
        for (i = 0u; i < 3u; ++i) {
            w[i] = seg->a[i] + (seg->b[i] * tau); /* eq. (21) */
        }
        wn = sqrt((w[0] * w[0]) + (w[1] * w[1]) + (w[2] * w[2]));
        if (wn > 0.0) {
            const double thrust = m->thrust_accel / mass;
            for (i = 0u; i < 3u; ++i) {
                const double u = w[i] / wn; /* eq. (22) */
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
        const double tide = m->sun_tidal;
        size_t i;
        size_t j;
        parts->grad[0] += 1.0; /* centrifugal */
        parts->grad[4] += 1.0;
        for (i = 0u; i < 3u; ++i) {
            for (j = 0u; j < 3u; ++j) {
                parts->grad[(i * 3u) + j] += tide * ((3.0 * s_hat[i] * s_hat[j]) - ((i == j) ? 1.0 : 0.0));
            }
        }
        for (i = 0u; i < 3u; ++i) {
            parts->s_hat[i] = s_hat[i];
        }
        parts->ds_hat[0] = -m->sun_rate * s_hat[1];
        parts->ds_hat[1] = m->sun_rate * s_hat[0];
        parts->ds_hat[2] = 0.0;
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

static double segment_start_time(const ogk_blt_config_t *cfg, const ogk_blt_transfer_t *tr, uint32_t k)
{
    double t = tr->t0;
    /* k clamped once to n_segments (every caller passes k < n_segments): one condition */
    const uint32_t k_b = (k < cfg->n_segments) ? k : cfg->n_segments;
    uint32_t j;
    for (j = 0u; j < k_b; ++j) {
        t += tr->seg[j][6];
    }
    return t;
}

static double segment_start_mass(const ogk_blt_config_t *cfg, const ogk_blt_transfer_t *tr, uint32_t k)
{
    double burned = 0.0;
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
