/* mpsp_dynamics.c -- MPSP dynamics: eq. (16), the switching function (eq. 10)
 * and their partial derivatives (Appendix A, dF/dU re-derived: docs/design/mpsp.md),
 * the RK4 callbacks; the Fourier control is in mpsp_control.c. */
#include "mpsp_internal.h"

#include <float.h>
#include <math.h>
#include <string.h>

void ogk_i_mpsp_dyn_setup(ogk_i_mpsp_dyn_t *dyn, const ogk_mpsp_t *ctx, const ogk_real_t *weights,
                    ogk_real_t thrust)
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
    dyn->cache_t = OGK_R(0.0);
    dyn->cache_u[0] = OGK_R(0.0);
    dyn->cache_u[1] = OGK_R(0.0);
    dyn->cache_u[2] = OGK_R(0.0);
    dyn->cache_ok = false;
    dyn->anchor_t = OGK_R(0.0);
    dyn->anchor_c = OGK_R(1.0);
    dyn->anchor_s = OGK_R(0.0);
    dyn->anchor_ok = false;
#if defined(__SSE2__)
    {
        size_t i;
        for (i = 0u; i < (3u * ctx->n_basis); ++i) {
            dyn->w2[2u * i] = weights[i];
            dyn->w2[(2u * i) + 1u] = weights[i];
        }
    }
    dyn->grid_t0 = ctx->cfg.t0;
    dyn->grid_h = ctx->cfg.h_max;
    dyn->grid_tf = ctx->cfg.tf;
    dyn->next_t = OGK_R(0.0);
    dyn->next_u[0] = OGK_R(0.0);
    dyn->next_u[1] = OGK_R(0.0);
    dyn->next_u[2] = OGK_R(0.0);
    dyn->next_ok = false;
    dyn->undo_t = OGK_R(0.0);
    dyn->undo_c = OGK_R(1.0);
    dyn->undo_s = OGK_R(0.0);
    dyn->undo_ok = false;
    dyn->pairing = false;
    dyn->keep_scale = OGK_R(2.0) / ctx->cfg.h_max;
    dyn->keep_t = NULL;
    dyn->keep_u = NULL;
#endif
}


static ogk_real_t norm3(const ogk_real_t *a)
{
    return OGK_SQRT((a[0] * a[0]) + (a[1] * a[1]) + (a[2] * a[2]));
}

/* Eq. (16). */
ogk_status ogk_i_mpsp_rhs(const ogk_i_mpsp_dyn_t *dyn, const ogk_real_t *x, const ogk_real_t *u, int mode, /* NOLINT(bugprone-easily-swappable-parameters): eq. (16) order x, u; FD-checked by the unit tests */
                    ogk_real_t *xdot)
{
    const ogk_real_t m = x[6];
    ogk_real_t gx = OGK_R(0.0);
    ogk_real_t gy = OGK_R(0.0);
    ogk_real_t gz = OGK_R(0.0);
    ogk_status st = OGK_OK;

    if (!(m > OGK_R(0.0))) {
        st = OGK_E_CALLBACK; /* mass depleted: eq. (16) undefined */
    } else if (dyn->mu != OGK_R(0.0)) {
        const ogk_real_t r2 = (x[0] * x[0]) + (x[1] * x[1]) + (x[2] * x[2]);
        const ogk_real_t k = -dyn->mu / (r2 * OGK_SQRT(r2));
        if (!(r2 > OGK_R(0.0))) {
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
            const ogk_real_t lam = norm3(u);
            if (!(lam > OGK_R(0.0))) {
                st = OGK_E_CALLBACK; /* thrust direction undefined (eq. 8) */
            } else {
                const ogk_real_t a = dyn->thrust / (m * lam);
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
            xdot[6] = OGK_R(0.0);
            xdot[7] = OGK_R(0.0);
        }
    }
    return st;
}

/* Eq. (10): S = 1 - lambda_m - |lambda_v| c / m. */
ogk_real_t ogk_i_mpsp_switch_value(const ogk_i_mpsp_dyn_t *dyn, const ogk_real_t *x, const ogk_real_t *u)
{
    return OGK_R(1.0) - x[7] - norm3(u) * dyn->c_exhaust / x[6];
}

/* v into entry i of a stage partial held MPSP_SL times (ogk_i_mpsp_stage_t). */
static void put_sl(ogk_real_t *a, size_t i, ogk_real_t v)
{
    size_t l;
    for (l = 0u; l < MPSP_SL; ++l) {
        a[(i * MPSP_SL) + l] = v;
    }
}

/* G = mu/r^3 (3 r r^T / r^2 - I), upper triangle (held as ogk_i_mpsp_stage_t.g),
 * and *kg = -mu/r^3 (0 and G = 0 without a central body): one square root
 * and one division. OGK_E_CALLBACK at r = 0. */
static ogk_status gravity_gradient(const ogk_i_mpsp_dyn_t *dyn, const ogk_real_t *x, ogk_real_t *kg,
                                   ogk_real_t *g)
{
    ogk_status st = OGK_OK;

    if (dyn->mu != OGK_R(0.0)) {
        const ogk_real_t r2 = (x[0] * x[0]) + (x[1] * x[1]) + (x[2] * x[2]);
        if (!(r2 > OGK_R(0.0))) {
            st = OGK_E_CALLBACK;
        } else {
            const ogk_real_t inv_r = OGK_R(1.0) / OGK_SQRT(r2);
            const ogk_real_t inv_r2 = inv_r * inv_r;
            const ogk_real_t k = dyn->mu * inv_r2 * inv_r;
            const ogk_real_t k3 = OGK_R(3.0) * k * inv_r2;
            *kg = -k;
            put_sl(g, 0u, (k3 * x[0] * x[0]) - k);
            put_sl(g, 1u, k3 * x[0] * x[1]);
            put_sl(g, 2u, k3 * x[0] * x[2]);
            put_sl(g, 3u, (k3 * x[1] * x[1]) - k);
            put_sl(g, 4u, k3 * x[1] * x[2]);
            put_sl(g, 5u, (k3 * x[2] * x[2]) - k);
        }
    } else {
        size_t i;
        *kg = OGK_R(0.0);
        for (i = 0u; i < (6u * MPSP_SL); ++i) {
            g[i] = OGK_R(0.0);
        }
    }
    return st;
}

/* The stage states need only be those of ogk_rk4_step to rounding (the
 * partials taken there agree with finite differences to 1e-8, docs/design/mpsp.md):
 * reciprocals replace the divisions of ogk_i_mpsp_rhs (7 per stage to 3). */
ogk_status ogk_i_mpsp_stage_eval(const ogk_i_mpsp_dyn_t *dyn, const ogk_real_t *x, const ogk_i_mpsp_uval_t *uv, /* NOLINT(bugprone-easily-swappable-parameters): eq. (16) order x, u; FD-checked by the unit tests */
                           int mode, ogk_real_t *xdot, ogk_i_mpsp_stage_t *sd)
{
    const ogk_real_t m = x[6];
    ogk_real_t kg = OGK_R(0.0);
    ogk_status st = OGK_OK;

    if (!(m > OGK_R(0.0))) {
        st = OGK_E_CALLBACK; /* mass depleted: eq. (16) undefined */
    } else {
        st = gravity_gradient(dyn, x, &kg, sd->g);
    }
    if ((st == OGK_OK) && (mode == 1) && !(uv->lam > OGK_R(0.0))) {
        st = OGK_E_CALLBACK; /* thrust direction undefined (eq. 8) */
    }
    if (st == OGK_OK) {
        if (mode == 1) {
            const ogk_real_t lam = uv->lam;
            const ogk_real_t inv_lam = OGK_R(1.0) / lam;
            const ogk_real_t t_m = dyn->thrust / m;
            const ogk_real_t t_m2 = t_m / m;
            const ogk_real_t a = t_m * inv_lam; /* T/(m |U|) */
            put_sl(sd->e, 0u, uv->u[0] * inv_lam);
            put_sl(sd->e, 1u, uv->u[1] * inv_lam);
            put_sl(sd->e, 2u, uv->u[2] * inv_lam);
            put_sl(sd->a_vm, 0u, t_m2);
            put_sl(sd->a_lm, 0u, OGK_R(2.0) * t_m2 * lam / m);
            put_sl(sd->d_v, 0u, -a);
            put_sl(sd->d_l, 0u, -t_m2);
            if (xdot != NULL) { /* eq. (16), thrust */
                xdot[3] = (kg * x[0]) - (a * uv->u[0]);
                xdot[4] = (kg * x[1]) - (a * uv->u[1]);
                xdot[5] = (kg * x[2]) - (a * uv->u[2]);
                xdot[6] = dyn->mdot_thrust;
                xdot[7] = -t_m2 * lam;
            }
        } else {
            (void)memset(sd->e, 0, sizeof sd->e);
            (void)memset(sd->a_vm, 0, sizeof sd->a_vm);
            (void)memset(sd->a_lm, 0, sizeof sd->a_lm);
            (void)memset(sd->d_v, 0, sizeof sd->d_v);
            (void)memset(sd->d_l, 0, sizeof sd->d_l);
            if (xdot != NULL) { /* eq. (16), coast */
                xdot[3] = kg * x[0];
                xdot[4] = kg * x[1];
                xdot[5] = kg * x[2];
                xdot[6] = OGK_R(0.0);
                xdot[7] = OGK_R(0.0);
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

/* RK4 callbacks of ogk_i_mpsp_rk4_problem: user is the ogk_i_mpsp_dyn_t it was given. */
static ogk_status mpsp_rhs_cb(void *user, ogk_real_t t, const ogk_real_t *x, int mode, ogk_real_t *xdot)
{
    ogk_i_mpsp_dyn_t *dyn = (ogk_i_mpsp_dyn_t *)user;
    ogk_real_t u[3] = {OGK_R(0.0), OGK_R(0.0), OGK_R(0.0)};
    if (mode == 1) {
        ogk_i_mpsp_control_at(dyn, t, u); /* coast needs no control */
    }
    return ogk_i_mpsp_rhs(dyn, x, u, mode, xdot);
}

static ogk_status mpsp_switch_cb(void *user, ogk_real_t t, const ogk_real_t *x, int mode, ogk_real_t *s)
{
    ogk_i_mpsp_dyn_t *dyn = (ogk_i_mpsp_dyn_t *)user;
    ogk_status st = OGK_OK;
    (void)mode;
    if (!(x[6] > OGK_R(0.0))) {
        st = OGK_E_CALLBACK;
    } else {
        ogk_real_t u[3];
        ogk_i_mpsp_control_at(dyn, t, u);
        *s = ogk_i_mpsp_switch_value(dyn, x, u);
    }
    return st;
}

void ogk_i_mpsp_rk4_problem(ogk_rk4_problem_t *p, const ogk_mpsp_t *ctx, ogk_i_mpsp_dyn_t *dyn)
{
    p->n = OGK_MPSP_NX;
    p->h = ctx->cfg.h_max;
    p->rhs = mpsp_rhs_cb;
    p->sw = mpsp_switch_cb;
    p->user = dyn;
    p->s_tol = ctx->cfg.s_tol;
    /* Bisection stops at the last representable bits of t if |S| <= s_tol
     * is not reached first. */
    p->t_tol = OGK_R(4.0) * OGK_REAL_EPSILON * (OGK_FABS(ctx->cfg.t0) + OGK_FABS(ctx->cfg.tf));
}
