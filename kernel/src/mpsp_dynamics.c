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

void mpsp_control_from_basis(const mpsp_dyn_t *dyn, const double *h, double *u)
{
    const size_t nb = dyn->n_basis;
    size_t i;
    size_t q;
    for (i = 0u; i < 3u; ++i) {
        const double *wi = &dyn->w[i * nb];
        double sum = 0.0;
        for (q = 0u; q < nb; ++q) {
            sum += h[q] * wi[q];
        }
        u[i] = sum;
    }
}

void mpsp_control_at(mpsp_dyn_t *dyn, double t, double *u)
{
    if ((!dyn->cache_ok) || (dyn->cache_t != t)) {
        double h[OGK_MPSP_MAX_BASIS];
        mpsp_basis(dyn, t, h, NULL);
        mpsp_control_from_basis(dyn, h, dyn->cache_u);
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
                xdot[6] = -dyn->thrust / dyn->c_exhaust;
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

ogk_status mpsp_jacobian(const mpsp_dyn_t *dyn, const double *x, const double *u, /* NOLINT(bugprone-easily-swappable-parameters): eq. (16) order x, u; FD-checked by the unit tests */
                         int mode, mpsp_jac_t *jac)
{
    const double m = x[6];
    size_t i;
    ogk_status st = OGK_OK;

    if (!(m > 0.0)) {
        st = OGK_E_CALLBACK;
    } else if (dyn->mu != 0.0) {
        const double r2 = (x[0] * x[0]) + (x[1] * x[1]) + (x[2] * x[2]);
        if (!(r2 > 0.0)) {
            st = OGK_E_CALLBACK;
        } else {
            double k;
            double k3;
            size_t j;
            /* G = mu/r^3 (3 r r^T / r^2 - I) */
            k = dyn->mu / (r2 * sqrt(r2));
            k3 = 3.0 * k / r2;
            for (i = 0u; i < 3u; ++i) {
                for (j = 0u; j < 3u; ++j) {
                    jac->g[(i * 3u) + j] = (k3 * x[i] * x[j]) - ((i == j) ? k : 0.0);
                }
            }
        }
    } else {
        for (i = 0u; i < 9u; ++i) {
            jac->g[i] = 0.0;
        }
    }
    if (st == OGK_OK) {
        jac->thrust = (mode == 1);
        if (jac->thrust) {
            const double lam = norm3(u);
            const double t_m2 = dyn->thrust / (m * m);
            if (!(lam > 0.0)) {
                st = OGK_E_CALLBACK;
            } else {
                for (i = 0u; i < 3u; ++i) {
                    jac->e[i] = u[i] / lam;
                }
                jac->a_vm = t_m2;
                jac->a_lm = 2.0 * t_m2 * lam / m;
                jac->d_v = -dyn->thrust / (m * lam);
                jac->d_l = -t_m2;
            }
        } else {
            jac->e[0] = 0.0;
            jac->e[1] = 0.0;
            jac->e[2] = 0.0;
            jac->a_vm = 0.0;
            jac->a_lm = 0.0;
            jac->d_v = 0.0;
            jac->d_l = 0.0;
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
