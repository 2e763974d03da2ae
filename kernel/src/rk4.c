/* rk4.c -- fixed-step classical RK4 with switching detection by bisection. */
#include "ogk/rk4.h"

#include <stdbool.h>
#include <math.h>
#include <string.h>

/* A step count within this relative slop of an integer is that integer:
 * (tf - t0) / h = 1000.0000000001 is 1000 steps, not 1001 with a sliver. */
#define OGK_RK4_STEP_SLOP 1.0e-9

typedef struct {
    const ogk_rk4_problem_t *p;
    size_t n_rhs;
} stepper_t;

static bool all_finite(const double *x, size_t n)
{
    size_t i;
    for (i = 0u; i < n; ++i) {
        if (!isfinite(x[i])) {
            return false;
        }
    }
    return true;
}

static ogk_status check_problem(const ogk_rk4_problem_t *p)
{
    if ((p == NULL) || (p->rhs == NULL)) {
        return OGK_E_NULL;
    }
    if ((p->n == 0u) || (p->n > OGK_RK4_MAX_STATE)) {
        return OGK_E_DIM;
    }
    if (!isfinite(p->h) || !(p->h > 0.0)) {
        return OGK_E_RANGE;
    }
    if (p->sw != NULL) {
        if ((!isfinite(p->s_tol)) || (p->s_tol < 0.0) || (!isfinite(p->t_tol)) || (!(p->t_tol > 0.0))) {
            return OGK_E_RANGE;
        }
    }
    return OGK_OK;
}

/* One RK4 step; x_next may alias x. */
static ogk_status step_raw(stepper_t *s, double t, const double *x, double dt,
                           int mode, double *x_next)
{
    double k1[OGK_RK4_MAX_STATE];
    double k2[OGK_RK4_MAX_STATE];
    double k3[OGK_RK4_MAX_STATE];
    double k4[OGK_RK4_MAX_STATE];
    double xs[OGK_RK4_MAX_STATE];
    const size_t n = s->p->n;
    const double half = 0.5 * dt;
    size_t i;

    s->n_rhs += 4u;
    if (s->p->rhs(s->p->user, t, x, mode, k1) != OGK_OK) {
        return OGK_E_CALLBACK;
    }
    for (i = 0u; i < n; ++i) {
        xs[i] = x[i] + (half * k1[i]);
    }
    if (s->p->rhs(s->p->user, t + half, xs, mode, k2) != OGK_OK) {
        return OGK_E_CALLBACK;
    }
    for (i = 0u; i < n; ++i) {
        xs[i] = x[i] + (half * k2[i]);
    }
    if (s->p->rhs(s->p->user, t + half, xs, mode, k3) != OGK_OK) {
        return OGK_E_CALLBACK;
    }
    for (i = 0u; i < n; ++i) {
        xs[i] = x[i] + (dt * k3[i]);
    }
    if (s->p->rhs(s->p->user, t + dt, xs, mode, k4) != OGK_OK) {
        return OGK_E_CALLBACK;
    }
    for (i = 0u; i < n; ++i) {
        x_next[i] = x[i] + ((dt / 6.0) * (k1[i] + (2.0 * (k2[i] + k3[i])) + k4[i]));
    }
    return all_finite(x_next, n) ? OGK_OK : OGK_E_NONFINITE;
}

ogk_status ogk_rk4_step(const ogk_rk4_problem_t *p, double t, const double *x,
                        double dt, int mode, double *x_next)
{
    stepper_t s;
    ogk_status st = check_problem(p);

    if (st != OGK_OK) {
        return st;
    }
    if ((x == NULL) || (x_next == NULL)) {
        return OGK_E_NULL;
    }
    if (!isfinite(t) || !isfinite(dt) || !all_finite(x, p->n)) {
        return OGK_E_NONFINITE;
    }
    if (dt == 0.0) {
        return OGK_E_RANGE;
    }
    s.p = p;
    s.n_rhs = 0u;
    return step_raw(&s, t, x, dt, mode, x_next);
}

static int sign_of(double v)
{
    return (v > 0.0) ? 1 : ((v < 0.0) ? -1 : 0);
}

static ogk_status eval_switch(const ogk_rk4_problem_t *p, double t,
                              const double *x, int mode, double *sv)
{
    if (p->sw(p->user, t, x, mode, sv) != OGK_OK) {
        return OGK_E_CALLBACK;
    }
    return isfinite(*sv) ? OGK_OK : OGK_E_NONFINITE;
}

static ogk_status dense_push(ogk_rk4_dense_t *d, size_t n, double t, /* NOLINT(bugprone-easily-swappable-parameters): internal helper, order of the RK4 step state; unit-tested */
                             const double *x, int mode)
{
    if (d == NULL) {
        return OGK_OK;
    }
    if (d->count >= d->capacity) {
        return OGK_E_DIM;
    }
    d->t[d->count] = t;
    memcpy(&d->x[d->count * n], x, n * sizeof x[0]);
    d->mode[d->count] = (uint8_t)mode;
    d->count += 1u;
    return OGK_OK;
}

/* Locates the switch inside the sub-step [t, t + dt] whose end has S of sign
 * -side: bisection on the sub-step length, each trial one RK4 step from t.
 * On return *dt_s is the accepted sub-step, x_s the state there. */
static ogk_status bisect_switch(stepper_t *s, double t, const double *x,
                                double dt, int mode, int side, double *dt_s, /* NOLINT(bugprone-easily-swappable-parameters): internal helper, order of the RK4 step state; unit-tested */
                                double *x_s, ogk_switch_event_t *ev)
{
    double lo = 0.0;
    double hi = dt;
    unsigned it;
    ogk_status st;

    ev->how = OGK_SWITCH_BY_TIME_TOL;
    for (it = 0u; it < OGK_RK4_MAX_BISECTIONS; ++it) {
        const double mid = lo + (0.5 * (hi - lo));
        double s_mid;
        if ((!((mid > lo) && (mid < hi))) || ((hi - lo) <= s->p->t_tol)) {
            break; /* bracket at the time tolerance or at its last bit */
        }
        st = step_raw(s, t, x, mid, mode, x_s);
        if (st != OGK_OK) {
            return st;
        }
        st = eval_switch(s->p, t + mid, x_s, mode, &s_mid);
        if (st != OGK_OK) {
            return st;
        }
        ev->bisections = (uint16_t)(it + 1u);
        if (fabs(s_mid) <= s->p->s_tol) {
            ev->how = OGK_SWITCH_BY_S_TOL;
            ev->s = s_mid;
            *dt_s = mid;
            return OGK_OK;
        }
        if (sign_of(s_mid) == side) {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    /* Accept the far end of the bracket, where S already has the new sign. */
    st = step_raw(s, t, x, hi, mode, x_s);
    if (st != OGK_OK) {
        return st;
    }
    st = eval_switch(s->p, t + hi, x_s, mode, &ev->s);
    *dt_s = hi;
    return st;
}

static void finish(ogk_rk4_result_t *res, const stepper_t *s, double t, /* NOLINT(bugprone-easily-swappable-parameters): internal helper, order of the RK4 step state; unit-tested */
                   int mode, const double *x, double *xf, size_t n)
{
    res->n_rhs = s->n_rhs;
    res->t_reached = t;
    res->mode_final = mode;
    memcpy(xf, x, n * sizeof x[0]);
}

ogk_status ogk_rk4_propagate(const ogk_rk4_problem_t *p, double t0,
                             const double *x0, int mode0, double tf,
                             ogk_rk4_result_t *res, double *xf,
                             ogk_rk4_dense_t *dense)
{
    double x[OGK_RK4_MAX_STATE];
    double x_end[OGK_RK4_MAX_STATE];
    double ratio;
    double t;
    size_t n_grid;
    size_t k;
    int mode = mode0;
    int side = 0;
    stepper_t s;
    ogk_status st = check_problem(p);

    if (st != OGK_OK) {
        return st;
    }
    if ((x0 == NULL) || (res == NULL) || (xf == NULL)) {
        return OGK_E_NULL;
    }
    if ((dense != NULL) && ((dense->t == NULL) || (dense->x == NULL) || (dense->mode == NULL))) {
        return OGK_E_NULL;
    }
    memset(res, 0, sizeof *res);
    if (dense != NULL) {
        dense->count = 0u;
    }
    if (!isfinite(t0) || !isfinite(tf) || !all_finite(x0, p->n)) {
        return OGK_E_NONFINITE;
    }
    if ((!(tf > t0)) || ((mode0 != 0) && (mode0 != 1))) {
        return OGK_E_RANGE;
    }
    ratio = (tf - t0) / p->h;
    if (!(ratio <= (double)OGK_RK4_MAX_STEPS)) {
        return OGK_E_STEP_LIMIT;
    }
    n_grid = (size_t)floor(ratio);
    if (((ratio - (double)n_grid) > (OGK_RK4_STEP_SLOP * fmax(1.0, ratio))) || (n_grid == 0u)) {
        n_grid += 1u;
    }

    s.p = p;
    s.n_rhs = 0u;
    t = t0;
    memcpy(x, x0, p->n * sizeof x[0]);
    if (p->sw != NULL) {
        double s0;
        st = eval_switch(p, t, x, mode, &s0);
        if (st != OGK_OK) {
            finish(res, &s, t, mode, x, xf, p->n);
            return st;
        }
        side = sign_of(s0);
    }
    st = dense_push(dense, p->n, t, x, mode);

    for (k = 0u; (k < n_grid) && (st == OGK_OK); ++k) {
        const double t_target = (k + 1u == n_grid) ? tf : t0 + (double)(k + 1u) * p->h;
        size_t piece;
        /* One piece per located switch plus the last one: fixed bound. */
        for (piece = 0u; piece <= OGK_RK4_MAX_SWITCHES; ++piece) {
            double s_end = 0.0;
            st = step_raw(&s, t, x, t_target - t, mode, x_end);
            if ((st == OGK_OK) && (p->sw != NULL)) {
                st = eval_switch(p, t_target, x_end, mode, &s_end);
            }
            if (st != OGK_OK) {
                break;
            }
            if (side == 0) {
                side = sign_of(s_end); /* S started exactly at zero: no event */
            }
            if ((p->sw == NULL) || (side == 0) || (sign_of(s_end) != -side)) {
                memcpy(x, x_end, p->n * sizeof x[0]);
                t = t_target;
                res->n_steps += 1u;
                st = dense_push(dense, p->n, t, x, mode);
                break;
            }
            {
                ogk_switch_event_t ev;
                double dt_s = 0.0;
                memset(&ev, 0, sizeof ev);
                st = bisect_switch(&s, t, x, t_target - t, mode, side, &dt_s, x_end, &ev);
                if (st != OGK_OK) {
                    break;
                }
                t += dt_s;
                memcpy(x, x_end, p->n * sizeof x[0]);
                res->n_steps += 1u;
                if (res->n_switches >= OGK_RK4_MAX_SWITCHES) {
                    st = OGK_E_SWITCH_OVERFLOW;
                    break;
                }
                mode = 1 - mode;
                side = -side;
                ev.t = t;
                ev.mode_after = mode;
                ev.dense_index = (dense != NULL) ? dense->count : 0u;
                res->sw[res->n_switches] = ev;
                res->n_switches += 1u;
                st = dense_push(dense, p->n, t, x, mode);
                if ((st != OGK_OK) || (!(t < t_target))) {
                    break;
                }
            }
        }
    }
    finish(res, &s, t, mode, x, xf, p->n);
    return st;
}
