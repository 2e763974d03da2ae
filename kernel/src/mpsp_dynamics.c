/* mpsp_dynamics.c -- MPSP dynamics: Fourier control (eqs. 36-37, C.1),
 * eq. (16), the switching function (eq. 10) and their partial derivatives
 * (Appendix A, dF/dU re-derived: docs/mpsp.md). */
#include "mpsp_internal.h"

#include <float.h>
#include <math.h>
#include <string.h>

void mpsp_dyn_setup(mpsp_dyn_t *dyn, const ogk_mpsp_t *ctx, const double *weights,
                    double thrust)
{
    dyn->mu = ctx->cfg.mu;
    dyn->thrust = thrust;
    dyn->c_exhaust = ctx->cfg.c_exhaust;
    dyn->mdot_thrust = -thrust / ctx->cfg.c_exhaust;
    dyn->w = weights;
    dyn->n_basis = ctx->n_basis;
    dyn->kind = ctx->cfg.fourier_kind;
    dyn->omega = ctx->omega;
    dyn->t_ref = ctx->cfg.fourier_t_ref;
    dyn->cache_t = 0.0;
    dyn->cache_u[0] = 0.0;
    dyn->cache_u[1] = 0.0;
    dyn->cache_u[2] = 0.0;
    dyn->cache_ok = false;
    dyn->anchor_t = 0.0;
    dyn->anchor_c = 1.0;
    dyn->anchor_s = 0.0;
    dyn->anchor_ok = false;
}

/* Largest phase step |omega (t - anchor_t)| taken by rotation in mpsp_phase:
 * the Taylor series below (to delta^8 and delta^9) then leave remainders
 * under delta^10/10! = 3e-20 and delta^11/11! = 1e-22, so the rotated cos and
 * sin are within a few ulp of cos() and sin(). With the Apophis grid
 * (omega h_max = pi/2000) one anchor serves 32 steps. */
#define MPSP_PHASE_REACH 0.05

void mpsp_phase(mpsp_dyn_t *dyn, double t, double *c1, double *s1)
{
    const double delta = dyn->omega * (t - dyn->anchor_t);

    if (dyn->anchor_ok && (fabs(delta) <= MPSP_PHASE_REACH)) {
        /* cos(a + d) = cos a cos d - sin a sin d, sin(a + d) = sin a cos d + cos a sin d */
        const double d2 = delta * delta;
        const double cd = 1.0 - (d2 * (0.5 - (d2 * ((1.0 / 24.0) -
                          (d2 * ((1.0 / 720.0) - (d2 * (1.0 / 40320.0))))))));
        const double sd = delta * (1.0 - (d2 * ((1.0 / 6.0) - (d2 * ((1.0 / 120.0) -
                          (d2 * ((1.0 / 5040.0) - (d2 * (1.0 / 362880.0)))))))));
        *c1 = (dyn->anchor_c * cd) - (dyn->anchor_s * sd);
        *s1 = (dyn->anchor_s * cd) + (dyn->anchor_c * sd);
    } else {
        const double theta = dyn->omega * (t - dyn->t_ref);
        dyn->anchor_t = t;
        dyn->anchor_c = cos(theta);
        dyn->anchor_s = sin(theta);
        dyn->anchor_ok = true;
        *c1 = dyn->anchor_c;
        *s1 = dyn->anchor_s;
    }
}

/* h = [1/2, cos th, sin th, ..., cos n th, sin n th] (eq. C.1 with
 * th = omega (t - t_ref)), or [1/2, cos th, ..., cos 2n th] for the cosine
 * kind; the harmonics by the angle-addition recurrence (two trigonometric
 * calls per time, error growth ~k eps). */
void mpsp_basis(const mpsp_dyn_t *dyn, double t, double *h, double *hdot) /* NOLINT(bugprone-easily-swappable-parameters): eq. (16) order x, u; FD-checked by the unit tests */
{
    const double theta = dyn->omega * (t - dyn->t_ref);
    const double c1 = cos(theta);
    const double s1 = sin(theta);
    const size_t last = dyn->n_basis - 1u; /* 2n */
    const bool cosine = (dyn->kind == OGK_MPSP_BASIS_COSINE);
    double cn = c1;
    double sn = s1;
    size_t k;

    h[0] = 0.5;
    if (hdot != NULL) {
        hdot[0] = 0.0;
    }
    for (k = 1u; (cosine ? k : (2u * k)) <= last; ++k) { /* k <= n harmonics */
        const double kw = (double)k * dyn->omega;
        if (cosine) {
            h[k] = cn;
            if (hdot != NULL) {
                hdot[k] = -kw * sn;
            }
        } else {
            h[(2u * k) - 1u] = cn;
            h[2u * k] = sn;
            if (hdot != NULL) {
                hdot[(2u * k) - 1u] = -kw * sn;
                hdot[2u * k] = kw * cn;
            }
        }
        {
            const double c_next = (cn * c1) - (sn * s1);
            sn = (sn * c1) + (cn * s1);
            cn = c_next;
        }
    }
    /* Every one of the n_basis entries is written: an even n_basis (never made by
     * ogk_mpsp_init, which sets 2 n + 1) leaves a last entry the harmonics do not
     * reach; it is zeroed instead of left indeterminate (clang-analyzer
     * core.UndefinedBinaryOperatorResult in mpsp_control_from_basis). */
    if (!cosine && (last % 2u) != 0u) {
        h[last] = 0.0;
        if (hdot != NULL) {
            hdot[last] = 0.0;
        }
    }
}

/* One pass over the basis for the three components (each sum in the order
 * q = 0, 1, ..., as control_cs and mpsp_basis_control). */
void mpsp_control_from_basis(const mpsp_dyn_t *dyn, const double *h, double *u)
{
    const size_t nb = dyn->n_basis;
    const double *w = dyn->w;
    double u0 = 0.0;
    double u1 = 0.0;
    double u2 = 0.0;
    size_t q;
    for (q = 0u; q < nb; ++q) {
        const double hq = h[q];
        u0 += hq * w[q];
        u1 += hq * w[nb + q];
        u2 += hq * w[(2u * nb) + q];
    }
    u[0] = u0;
    u[1] = u1;
    u[2] = u2;
}

/* U = P(t) W from the phase (c1, s1): the harmonics of mpsp_basis (same
 * recurrence) summed as they are made, in the order of
 * mpsp_control_from_basis; the propagation needs U, not h (eqs. 36-37). */
static void control_cs(const mpsp_dyn_t *dyn, double c1, double s1, double *u)
{
    const size_t nb = dyn->n_basis;
    const size_t last = nb - 1u; /* 2n */
    const double *w = dyn->w;
    double cn = c1;
    double sn = s1;
    double u0 = 0.0;
    double u1 = 0.0;
    double u2 = 0.0;
    size_t k;

    u0 += 0.5 * w[0];
    u1 += 0.5 * w[nb];
    u2 += 0.5 * w[2u * nb];
    if (dyn->kind == OGK_MPSP_BASIS_COSINE) {
        for (k = 1u; k < last; k += 2u) { /* cos k theta, k = 1..2n, two per pass */
            double c2;
            double s2;
            u0 += cn * w[k];
            u1 += cn * w[nb + k];
            u2 += cn * w[(2u * nb) + k];
            c2 = (cn * c1) - (sn * s1);
            s2 = (sn * c1) + (cn * s1);
            u0 += c2 * w[k + 1u];
            u1 += c2 * w[nb + k + 1u];
            u2 += c2 * w[(2u * nb) + k + 1u];
            cn = (c2 * c1) - (s2 * s1);
            sn = (s2 * c1) + (c2 * s1);
        }
        if (k == last) { /* an odd 2n (never made by ogk_mpsp_init) */
            u0 += cn * w[k];
            u1 += cn * w[nb + k];
            u2 += cn * w[(2u * nb) + k];
        }
    } else {
        /* cos k theta, sin k theta, k = 1..n, two harmonics per pass (the
         * recurrence then needs no register copies) */
        for (k = 1u; ((2u * k) + 2u) <= last; k += 2u) {
            const size_t ic = (2u * k) - 1u;
            double c2;
            double s2;
            u0 += cn * w[ic];
            u0 += sn * w[ic + 1u];
            u1 += cn * w[nb + ic];
            u1 += sn * w[nb + ic + 1u];
            u2 += cn * w[(2u * nb) + ic];
            u2 += sn * w[(2u * nb) + ic + 1u];
            c2 = (cn * c1) - (sn * s1);
            s2 = (sn * c1) + (cn * s1);
            u0 += c2 * w[ic + 2u];
            u0 += s2 * w[ic + 3u];
            u1 += c2 * w[nb + ic + 2u];
            u1 += s2 * w[nb + ic + 3u];
            u2 += c2 * w[(2u * nb) + ic + 2u];
            u2 += s2 * w[(2u * nb) + ic + 3u];
            cn = (c2 * c1) - (s2 * s1);
            sn = (s2 * c1) + (c2 * s1);
        }
        if ((2u * k) <= last) { /* n odd: the last harmonic */
            const size_t ic = (2u * k) - 1u;
            u0 += cn * w[ic];
            u0 += sn * w[ic + 1u];
            u1 += cn * w[nb + ic];
            u1 += sn * w[nb + ic + 1u];
            u2 += cn * w[(2u * nb) + ic];
            u2 += sn * w[(2u * nb) + ic + 1u];
        }
    }
    u[0] = u0;
    u[1] = u1;
    u[2] = u2;
}

void mpsp_basis_control(mpsp_dyn_t *dyn, double t, double *h, mpsp_uval_t *uv)
{
    const size_t nb = dyn->n_basis;
    const size_t last = nb - 1u; /* 2n */
    const double *w = dyn->w;
    double c1;
    double s1;
    double cn;
    double sn;
    double u0;
    double u1;
    double u2;
    size_t k;

    mpsp_phase(dyn, t, &c1, &s1);
    cn = c1;
    sn = s1;
    h[0] = 0.5;
    u0 = 0.5 * w[0];
    u1 = 0.5 * w[nb];
    u2 = 0.5 * w[2u * nb];
    if (dyn->kind == OGK_MPSP_BASIS_COSINE) {
        for (k = 1u; k < last; k += 2u) { /* two per pass */
            double c2;
            double s2;
            h[k] = cn;
            u0 += cn * w[k];
            u1 += cn * w[nb + k];
            u2 += cn * w[(2u * nb) + k];
            c2 = (cn * c1) - (sn * s1);
            s2 = (sn * c1) + (cn * s1);
            h[k + 1u] = c2;
            u0 += c2 * w[k + 1u];
            u1 += c2 * w[nb + k + 1u];
            u2 += c2 * w[(2u * nb) + k + 1u];
            cn = (c2 * c1) - (s2 * s1);
            sn = (s2 * c1) + (c2 * s1);
        }
        if (k == last) { /* an odd 2n (never made by ogk_mpsp_init) */
            h[k] = cn;
            u0 += cn * w[k];
            u1 += cn * w[nb + k];
            u2 += cn * w[(2u * nb) + k];
        }
    } else {
        for (k = 1u; ((2u * k) + 2u) <= last; k += 2u) { /* two harmonics per pass */
            const size_t ic = (2u * k) - 1u;
            double c2;
            double s2;
            h[ic] = cn;
            h[ic + 1u] = sn;
            u0 += cn * w[ic];
            u0 += sn * w[ic + 1u];
            u1 += cn * w[nb + ic];
            u1 += sn * w[nb + ic + 1u];
            u2 += cn * w[(2u * nb) + ic];
            u2 += sn * w[(2u * nb) + ic + 1u];
            c2 = (cn * c1) - (sn * s1);
            s2 = (sn * c1) + (cn * s1);
            h[ic + 2u] = c2;
            h[ic + 3u] = s2;
            u0 += c2 * w[ic + 2u];
            u0 += s2 * w[ic + 3u];
            u1 += c2 * w[nb + ic + 2u];
            u1 += s2 * w[nb + ic + 3u];
            u2 += c2 * w[(2u * nb) + ic + 2u];
            u2 += s2 * w[(2u * nb) + ic + 3u];
            cn = (c2 * c1) - (s2 * s1);
            sn = (s2 * c1) + (c2 * s1);
        }
        if ((2u * k) <= last) { /* n odd: the last harmonic */
            const size_t ic = (2u * k) - 1u;
            h[ic] = cn;
            h[ic + 1u] = sn;
            u0 += cn * w[ic];
            u0 += sn * w[ic + 1u];
            u1 += cn * w[nb + ic];
            u1 += sn * w[nb + ic + 1u];
            u2 += cn * w[(2u * nb) + ic];
            u2 += sn * w[(2u * nb) + ic + 1u];
        }
        if ((last % 2u) != 0u) {
            h[last] = 0.0; /* an even n_basis, as in mpsp_basis */
        }
    }
    uv->u[0] = u0;
    uv->u[1] = u1;
    uv->u[2] = u2;
    uv->lam = sqrt((u0 * u0) + (u1 * u1) + (u2 * u2));
}

void mpsp_control_at(mpsp_dyn_t *dyn, double t, double *u)
{
    if ((!dyn->cache_ok) || (dyn->cache_t != t)) {
        double c1;
        double s1;
        mpsp_phase(dyn, t, &c1, &s1);
        control_cs(dyn, c1, s1, dyn->cache_u);
        dyn->cache_t = t;
        dyn->cache_ok = true;
    }
    u[0] = dyn->cache_u[0];
    u[1] = dyn->cache_u[1];
    u[2] = dyn->cache_u[2];
}

static double norm3(const double *a)
{
    return sqrt((a[0] * a[0]) + (a[1] * a[1]) + (a[2] * a[2]));
}

/* Eq. (16). */
ogk_status mpsp_rhs(const mpsp_dyn_t *dyn, const double *x, const double *u, int mode, /* NOLINT(bugprone-easily-swappable-parameters): eq. (16) order x, u; FD-checked by the unit tests */
                    double *xdot)
{
    const double m = x[6];
    double gx = 0.0;
    double gy = 0.0;
    double gz = 0.0;
    ogk_status st = OGK_OK;

    if (!(m > 0.0)) {
        st = OGK_E_CALLBACK; /* mass depleted: eq. (16) undefined */
    } else if (dyn->mu != 0.0) {
        const double r2 = (x[0] * x[0]) + (x[1] * x[1]) + (x[2] * x[2]);
        const double k = -dyn->mu / (r2 * sqrt(r2));
        if (!(r2 > 0.0)) {
            st = OGK_E_CALLBACK;
        } else {
            gx = k * x[0];
            gy = k * x[1];
            gz = k * x[2];
        }
    } else {
        /* no central body (mu = 0): no gravity */
    }
    if (st == OGK_OK) {
        xdot[0] = x[3];
        xdot[1] = x[4];
        xdot[2] = x[5];
        if (mode == 1) {
            const double lam = norm3(u);
            if (!(lam > 0.0)) {
                st = OGK_E_CALLBACK; /* thrust direction undefined (eq. 8) */
            } else {
                const double a = dyn->thrust / (m * lam);
                xdot[3] = gx - (a * u[0]);
                xdot[4] = gy - (a * u[1]);
                xdot[5] = gz - (a * u[2]);
                xdot[6] = dyn->mdot_thrust;
                xdot[7] = -dyn->thrust * lam / (m * m);
            }
        } else {
            xdot[3] = gx;
            xdot[4] = gy;
            xdot[5] = gz;
            xdot[6] = 0.0;
            xdot[7] = 0.0;
        }
    }
    return st;
}

/* Eq. (10): S = 1 - lambda_m - |lambda_v| c / m. */
double mpsp_switch_value(const mpsp_dyn_t *dyn, const double *x, const double *u)
{
    return 1.0 - x[7] - norm3(u) * dyn->c_exhaust / x[6];
}

/* G = mu/r^3 (3 r r^T / r^2 - I), upper triangle; *kg = -mu/r^3 as in
 * mpsp_rhs (0 and G = 0 without a central body). OGK_E_CALLBACK at r = 0. */
/* G = mu/r^3 (3 r r^T / r^2 - I), upper triangle, and *kg = -mu/r^3 (0 and
 * G = 0 without a central body): one square root and one division.
 * OGK_E_CALLBACK at r = 0. */
static ogk_status gravity_gradient(const mpsp_dyn_t *dyn, const double *x, double *kg,
                                   double *g)
{
    ogk_status st = OGK_OK;

    if (dyn->mu != 0.0) {
        const double r2 = (x[0] * x[0]) + (x[1] * x[1]) + (x[2] * x[2]);
        if (!(r2 > 0.0)) {
            st = OGK_E_CALLBACK;
        } else {
            const double inv_r = 1.0 / sqrt(r2);
            const double inv_r2 = inv_r * inv_r;
            const double k = dyn->mu * inv_r2 * inv_r;
            const double k3 = 3.0 * k * inv_r2;
            *kg = -k;
            g[0] = (k3 * x[0] * x[0]) - k;
            g[1] = k3 * x[0] * x[1];
            g[2] = k3 * x[0] * x[2];
            g[3] = (k3 * x[1] * x[1]) - k;
            g[4] = k3 * x[1] * x[2];
            g[5] = (k3 * x[2] * x[2]) - k;
        }
    } else {
        size_t i;
        *kg = 0.0;
        for (i = 0u; i < 6u; ++i) {
            g[i] = 0.0;
        }
    }
    return st;
}

/* The stage states need only be those of ogk_rk4_step to rounding (the
 * partials taken there agree with finite differences to 1e-8, docs/mpsp.md):
 * reciprocals replace the divisions of mpsp_rhs (7 per stage to 3). */
ogk_status mpsp_stage_eval(const mpsp_dyn_t *dyn, const double *x, const mpsp_uval_t *uv, /* NOLINT(bugprone-easily-swappable-parameters): eq. (16) order x, u; FD-checked by the unit tests */
                           int mode, double *xdot, mpsp_stage_t *sd)
{
    const double m = x[6];
    double kg = 0.0;
    ogk_status st = OGK_OK;

    if (!(m > 0.0)) {
        st = OGK_E_CALLBACK; /* mass depleted: eq. (16) undefined */
    } else {
        st = gravity_gradient(dyn, x, &kg, sd->g);
    }
    if ((st == OGK_OK) && (mode == 1) && !(uv->lam > 0.0)) {
        st = OGK_E_CALLBACK; /* thrust direction undefined (eq. 8) */
    }
    if (st == OGK_OK) {
        if (mode == 1) {
            const double lam = uv->lam;
            const double inv_lam = 1.0 / lam;
            const double t_m = dyn->thrust / m;
            const double t_m2 = t_m / m;
            const double a = t_m * inv_lam; /* T/(m |U|) */
            sd->e[0] = uv->u[0] * inv_lam;
            sd->e[1] = uv->u[1] * inv_lam;
            sd->e[2] = uv->u[2] * inv_lam;
            sd->a_vm = t_m2;
            sd->a_lm = 2.0 * t_m2 * lam / m;
            sd->d_v = -a;
            sd->d_l = -t_m2;
            if (xdot != NULL) { /* eq. (16), thrust */
                xdot[3] = (kg * x[0]) - (a * uv->u[0]);
                xdot[4] = (kg * x[1]) - (a * uv->u[1]);
                xdot[5] = (kg * x[2]) - (a * uv->u[2]);
                xdot[6] = dyn->mdot_thrust;
                xdot[7] = -t_m2 * lam;
            }
        } else {
            sd->e[0] = 0.0;
            sd->e[1] = 0.0;
            sd->e[2] = 0.0;
            sd->a_vm = 0.0;
            sd->a_lm = 0.0;
            sd->d_v = 0.0;
            sd->d_l = 0.0;
            if (xdot != NULL) { /* eq. (16), coast */
                xdot[3] = kg * x[0];
                xdot[4] = kg * x[1];
                xdot[5] = kg * x[2];
                xdot[6] = 0.0;
                xdot[7] = 0.0;
            }
        }
        if (xdot != NULL) {
            xdot[0] = x[3];
            xdot[1] = x[4];
            xdot[2] = x[5];
        }
    }
    return st;
}

/* RK4 callbacks of mpsp_rk4_problem: user is the mpsp_dyn_t it was given. */
static ogk_status mpsp_rhs_cb(void *user, double t, const double *x, int mode, double *xdot)
{
    mpsp_dyn_t *dyn = (mpsp_dyn_t *)user;
    double u[3] = {0.0, 0.0, 0.0};
    if (mode == 1) {
        mpsp_control_at(dyn, t, u); /* coast needs no control */
    }
    return mpsp_rhs(dyn, x, u, mode, xdot);
}

static ogk_status mpsp_switch_cb(void *user, double t, const double *x, int mode, double *s)
{
    mpsp_dyn_t *dyn = (mpsp_dyn_t *)user;
    ogk_status st = OGK_OK;
    (void)mode;
    if (!(x[6] > 0.0)) {
        st = OGK_E_CALLBACK;
    } else {
        double u[3];
        mpsp_control_at(dyn, t, u);
        *s = mpsp_switch_value(dyn, x, u);
    }
    return st;
}

void mpsp_rk4_problem(ogk_rk4_problem_t *p, const ogk_mpsp_t *ctx, mpsp_dyn_t *dyn)
{
    p->n = OGK_MPSP_NX;
    p->h = ctx->cfg.h_max;
    p->rhs = mpsp_rhs_cb;
    p->sw = mpsp_switch_cb;
    p->user = dyn;
    p->s_tol = ctx->cfg.s_tol;
    /* Bisection stops at the last representable bits of t if |S| <= s_tol
     * is not reached first. */
    p->t_tol = 4.0 * DBL_EPSILON * (fabs(ctx->cfg.t0) + fabs(ctx->cfg.tf));
}
