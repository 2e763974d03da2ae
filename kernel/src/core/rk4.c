/* rk4.c -- fixed-step classical RK4 with switching detection by bisection. */
#include "ogk/rk4.h"
#include "../ogk_checks.h"
#include "../rk4_internal.h"

#include <stdbool.h>
#include <math.h>
#include <string.h>

/* A step count within this relative slop of an integer is that integer:
 * (tf - t0) / h = 1000.0000000001 is 1000 steps, not 1001 with a sliver. */
#define OGK_RK4_STEP_SLOP OGK_R(1.0e-9)

typedef struct {
    const ogk_rk4_problem_t *p;
    size_t n_rhs;
} stepper_t;

static ogk_status check_problem(const ogk_rk4_problem_t *p)
{
    ogk_status st;
    if ((p == NULL) || (p->rhs == NULL)) {
        st = OGK_E_NULL;
    } else if ((p->n == 0u) || (p->n > OGK_RK4_MAX_STATE)) {
        st = OGK_E_DIM;
    } else if ((!isfinite(p->h)) || (!(p->h > OGK_R(0.0))) ||
               ((p->sw != NULL) &&
                ((!isfinite(p->s_tol)) || (p->s_tol < OGK_R(0.0)) || (!isfinite(p->t_tol)) || (!(p->t_tol > OGK_R(0.0)))))) {
        st = OGK_E_RANGE;
    } else {
        st = OGK_OK;
    }
    return st;
}

/* One RK4 step; x_next may alias x (written only once all four stages
 * succeeded). */
static ogk_status step_raw(stepper_t *s, ogk_real_t t, const ogk_real_t *x, ogk_real_t dt,
                           int mode, ogk_real_t *x_next)
{
    ogk_real_t k1[OGK_RK4_MAX_STATE];
    ogk_real_t k2[OGK_RK4_MAX_STATE];
    ogk_real_t k3[OGK_RK4_MAX_STATE];
    ogk_real_t k4[OGK_RK4_MAX_STATE];
    ogk_real_t xs[OGK_RK4_MAX_STATE];
    const size_t n = s->p->n;
    const ogk_real_t half = OGK_R(0.5) * dt;
    ogk_status st = OGK_OK;

    s->n_rhs += 4u;
    if (s->p->rhs(s->p->user, t, x, mode, k1) != OGK_OK) {
        st = OGK_E_CALLBACK;
    }
    if (st == OGK_OK) {
        ogk_i_rk4_stage_state(x, half, k1, n, xs);
        if (s->p->rhs(s->p->user, t + half, xs, mode, k2) != OGK_OK) {
            st = OGK_E_CALLBACK;
        }
    }
    if (st == OGK_OK) {
        ogk_i_rk4_stage_state(x, half, k2, n, xs);
        if (s->p->rhs(s->p->user, t + half, xs, mode, k3) != OGK_OK) {
            st = OGK_E_CALLBACK;
        }
    }
    if (st == OGK_OK) {
        ogk_i_rk4_stage_state(x, dt, k3, n, xs);
        if (s->p->rhs(s->p->user, t + dt, xs, mode, k4) != OGK_OK) {
            st = OGK_E_CALLBACK;
        }
    }
    if (st == OGK_OK) {
        ogk_i_rk4_next_grouped(x, k1, k2, k3, k4, dt, n, x_next);
        st = ogk_i_all_finite(x_next, n) ? OGK_OK : OGK_E_NONFINITE;
    }
    return st;
}

ogk_status ogk_rk4_step(const ogk_rk4_problem_t *p, ogk_real_t t, const ogk_real_t *x,
                        ogk_real_t dt, int mode, ogk_real_t *x_next)
{
    ogk_status st = check_problem(p);

    if (st == OGK_OK) {
        if ((x == NULL) || (x_next == NULL)) {
            st = OGK_E_NULL;
        } else if (!isfinite(t) || !isfinite(dt) || !ogk_i_all_finite(x, p->n)) {
            st = OGK_E_NONFINITE;
        } else if (dt == OGK_R(0.0)) {
            st = OGK_E_RANGE;
        } else {
            stepper_t s;
            s.p = p;
            s.n_rhs = 0u;
            st = step_raw(&s, t, x, dt, mode, x_next);
        }
    }
    return st;
}

/* Sign of the switching function: +1, -1, or 0 at an exact zero. */
static int switch_sign(ogk_real_t v)
{
    return (v > OGK_R(0.0)) ? 1 : ((v < OGK_R(0.0)) ? -1 : 0);
}

static ogk_status eval_switch(const ogk_rk4_problem_t *p, ogk_real_t t,
                              const ogk_real_t *x, int mode, ogk_real_t *sv)
{
    ogk_status st;
    if (p->sw(p->user, t, x, mode, sv) != OGK_OK) {
        st = OGK_E_CALLBACK;
    } else {
        st = isfinite(*sv) ? OGK_OK : OGK_E_NONFINITE;
    }
    return st;
}

static ogk_status dense_push(ogk_rk4_dense_t *d, size_t n, ogk_real_t t, /* NOLINT(bugprone-easily-swappable-parameters): internal helper, order of the RK4 step state; unit-tested */
                             const ogk_real_t *x, int mode)
{
    ogk_status st = OGK_OK;
    if (d != NULL) {
        if (d->count >= d->capacity) {
            st = OGK_E_DIM;
        } else {
            d->t[d->count] = t;
            /* memcpy returns its destination: nothing to check (here and below). */
            (void)memcpy(&d->x[d->count * n], x, n * sizeof x[0]);
            d->mode[d->count] = (uint8_t)mode;
            d->count += 1u;
        }
    }
    return st;
}

/* Locates the switch inside the sub-step [t, t + dt] whose end has S of sign
 * -side: bisection on the sub-step length, each trial one RK4 step from t.
 * On return *dt_s is the accepted sub-step, x_s the state there. */
static ogk_status bisect_switch(stepper_t *s, ogk_real_t t, const ogk_real_t *x,
                                ogk_real_t dt, int mode, int side, ogk_real_t *dt_s, /* NOLINT(bugprone-easily-swappable-parameters): internal helper, order of the RK4 step state; unit-tested */
                                ogk_real_t *x_s, ogk_switch_event_t *ev)
{
    ogk_real_t lo = OGK_R(0.0);
    ogk_real_t hi = dt;
    unsigned it;
    bool found = false; /* |S| <= s_tol at a trial point */
    ogk_status st = OGK_OK;

    ev->how = OGK_SWITCH_BY_TIME_TOL;
    for (it = 0u; (it < OGK_RK4_MAX_BISECTIONS) && (st == OGK_OK) && (!found); ++it) {
        const ogk_real_t mid = lo + (OGK_R(0.5) * (hi - lo));
        ogk_real_t s_mid = OGK_R(0.0);
        /* !(mid > lo && mid < hi) written by De Morgan (the same for NaN), so that
         * clang's MC/DC instruments the decision */
        if ((!(mid > lo)) || (!(mid < hi)) || ((hi - lo) <= s->p->t_tol)) {
            break; /* bracket at the time tolerance or at its last bit */
        }
        st = step_raw(s, t, x, mid, mode, x_s);
        if (st == OGK_OK) {
            st = eval_switch(s->p, t + mid, x_s, mode, &s_mid);
        }
        if (st == OGK_OK) {
            ev->bisections = (uint16_t)(it + 1u);
            if (OGK_FABS(s_mid) <= s->p->s_tol) {
                ev->how = OGK_SWITCH_BY_S_TOL;
                ev->s = s_mid;
                *dt_s = mid;
                found = true;
            } else if (switch_sign(s_mid) == side) {
                lo = mid;
            } else {
                hi = mid;
            }
        }
    }
    if ((st == OGK_OK) && (!found)) {
        /* Accept the far end of the bracket, where S already has the new sign. */
        st = step_raw(s, t, x, hi, mode, x_s);
        if (st == OGK_OK) {
            st = eval_switch(s->p, t + hi, x_s, mode, &ev->s);
            *dt_s = hi;
        }
    }
    return st;
}

static void finish(ogk_rk4_result_t *res, const stepper_t *s, ogk_real_t t, /* NOLINT(bugprone-easily-swappable-parameters): internal helper, order of the RK4 step state; unit-tested */
                   int mode, const ogk_real_t *x, ogk_real_t *xf, size_t n)
{
    res->n_rhs = s->n_rhs;
    res->t_reached = t;
    res->mode_final = mode;
    (void)memcpy(xf, x, n * sizeof x[0]);
}

/* The output pointers of ogk_rk4_propagate (dense optional, its buffers
 * required when it is given). */
static ogk_status check_outputs(const ogk_real_t *x0, const ogk_rk4_result_t *res,
                                const ogk_real_t *xf, const ogk_rk4_dense_t *dense)
{
    ogk_status st;
    if ((x0 == NULL) || (res == NULL) || (xf == NULL) ||
        ((dense != NULL) && ((dense->t == NULL) || (dense->x == NULL) || (dense->mode == NULL)))) {
        st = OGK_E_NULL;
    } else {
        st = OGK_OK;
    }
    return st;
}

/* Checks the span and initial state of ogk_rk4_propagate and counts its grid
 * steps into *n_grid. */
static ogk_status grid_steps(const ogk_rk4_problem_t *p, ogk_real_t t0, const ogk_real_t *x0, /* NOLINT(bugprone-easily-swappable-parameters): argument order of ogk_rk4_propagate */
                             int mode0, ogk_real_t tf, size_t *n_grid)
{
    ogk_status st;
    ogk_real_t ratio = OGK_R(0.0);

    if (!isfinite(t0) || !isfinite(tf) || !ogk_i_all_finite(x0, p->n)) {
        st = OGK_E_NONFINITE;
    } else if ((!(tf > t0)) || ((mode0 != 0) && (mode0 != 1))) {
        st = OGK_E_RANGE;
    } else {
        ratio = (tf - t0) / p->h;
        st = (ratio <= (ogk_real_t)OGK_RK4_MAX_STEPS) ? OGK_OK : OGK_E_STEP_LIMIT;
    }
    if (st == OGK_OK) {
        *n_grid = (size_t)OGK_FLOOR(ratio);
        if (((ratio - (ogk_real_t)*n_grid) > (OGK_RK4_STEP_SLOP * OGK_FMAX(OGK_R(1.0), ratio))) || (*n_grid == 0u)) {
            *n_grid += 1u;
        }
    }
    return st;
}

/* The integration of ogk_rk4_propagate over its n_grid grid steps, inputs
 * checked and res zeroed. */
static ogk_status integrate(const ogk_rk4_problem_t *p, ogk_real_t t0,
                            const ogk_real_t *x0, int mode0, ogk_real_t tf, size_t n_grid, /* NOLINT(bugprone-easily-swappable-parameters): argument order of ogk_rk4_propagate */
                            ogk_rk4_result_t *res, ogk_real_t *xf, ogk_rk4_dense_t *dense)
{
    ogk_real_t x[OGK_RK4_MAX_STATE];
    ogk_real_t x_end[OGK_RK4_MAX_STATE];
    ogk_real_t t = t0;
    size_t k;
    int mode = mode0;
    int side = 0;
    stepper_t s;
    ogk_status st = OGK_OK;

    s.p = p;
    s.n_rhs = 0u;
    (void)memcpy(x, x0, p->n * sizeof x[0]);
    if (p->sw != NULL) {
        ogk_real_t s0 = OGK_R(0.0);
        st = eval_switch(p, t, x, mode, &s0);
        if (st == OGK_OK) {
            side = switch_sign(s0);
        }
    }
    if (st == OGK_OK) {
        st = dense_push(dense, p->n, t, x, mode);
    }

    for (k = 0u; (k < n_grid) && (st == OGK_OK); ++k) {
        const size_t k_next = k + 1u;
        const ogk_real_t t_target = (k_next == n_grid) ? tf : (t0 + ((ogk_real_t)k_next * p->h));
        bool done = false; /* t_target reached, or stopped on an error */
        size_t piece;
        /* One piece per located switch plus the last one: fixed bound. */
        for (piece = 0u; (piece <= OGK_RK4_MAX_SWITCHES) && (!done); ++piece) {
            ogk_real_t s_end = OGK_R(0.0);
            st = step_raw(&s, t, x, t_target - t, mode, x_end);
            if ((st == OGK_OK) && (p->sw != NULL)) {
                st = eval_switch(p, t_target, x_end, mode, &s_end);
            }
            if ((st == OGK_OK) && (side == 0)) {
                side = switch_sign(s_end); /* S started exactly at zero: no event */
            }
            if (st != OGK_OK) {
                done = true;
            } else if ((p->sw == NULL) || (side == 0) || (switch_sign(s_end) != -side)) {
                (void)memcpy(x, x_end, p->n * sizeof x[0]);
                t = t_target;
                res->n_steps += 1u;
                st = dense_push(dense, p->n, t, x, mode);
                done = true;
            } else {
                ogk_switch_event_t ev;
                ogk_real_t dt_s = OGK_R(0.0);
                (void)memset(&ev, 0, sizeof ev); /* returns its destination */
                st = bisect_switch(&s, t, x, t_target - t, mode, side, &dt_s, x_end, &ev);
                if (st == OGK_OK) {
                    t += dt_s;
                    (void)memcpy(x, x_end, p->n * sizeof x[0]);
                    res->n_steps += 1u;
                    if (res->n_switches >= OGK_RK4_MAX_SWITCHES) {
                        st = OGK_E_SWITCH_OVERFLOW;
                    } else {
                        mode = 1 - mode;
                        side = -side;
                        ev.t = t;
                        ev.mode_after = mode;
                        ev.dense_index = (dense != NULL) ? dense->count : 0u;
                        res->sw[res->n_switches] = ev;
                        res->n_switches += 1u;
                        st = dense_push(dense, p->n, t, x, mode);
                    }
                }
                done = (st != OGK_OK) || (!(t < t_target));
            }
        }
    }
    finish(res, &s, t, mode, x, xf, p->n);
    return st;
}

ogk_status ogk_rk4_propagate(const ogk_rk4_problem_t *p, ogk_real_t t0,
                             const ogk_real_t *x0, int mode0, ogk_real_t tf,
                             ogk_rk4_result_t *res, ogk_real_t *xf,
                             ogk_rk4_dense_t *dense)
{
    size_t n_grid = 0u;
    ogk_status st = check_problem(p);

    if (st == OGK_OK) {
        st = check_outputs(x0, res, xf, dense);
    }
    if (st == OGK_OK) {
        (void)memset(res, 0, sizeof *res); /* returns its destination */
        if (dense != NULL) {
            dense->count = 0u;
        }
        st = grid_steps(p, t0, x0, mode0, tf, &n_grid);
    }
    if (st == OGK_OK) {
        st = integrate(p, t0, x0, mode0, tf, n_grid, res, xf, dense);
    }
    return st;
}
