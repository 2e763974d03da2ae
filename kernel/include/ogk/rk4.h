/* ogk/rk4.h -- fixed-step classical RK4 with switching-function detection.
 *
 * The integrator advances x' = f(t, x, mode) on the grid t0 + k h (the last
 * step shortened to land on tf). An optional switching function S(t, x, mode)
 * is evaluated at every grid point; when its sign changes inside a step, the
 * switching time t_s is located by bisection on the sub-step [t, t + dt]
 * (each trial point is one RK4 sub-step of length dt from t) until
 * |S(t_s)| <= s_tol, or the bracket is narrower than t_tol (then the event is
 * flagged OGK_SWITCH_BY_TIME_TOL). The step is split at t_s, the control mode
 * flips (mode := 1 - mode), and integration continues to the grid point.
 * Mode is 0 or 1 (for example thrust off / on). */
#ifndef OGK_RK4_H
#define OGK_RK4_H

#include <stddef.h>
#include <stdint.h>
#include "ogk/config.h"
#include "ogk/status.h"
#include "ogk/real.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Right-hand side: writes xdot[0..n-1] = f(t, x, mode). Any status other than
 * OGK_OK stops the propagation with OGK_E_CALLBACK. */
typedef ogk_status (*ogk_rhs_fn)(void *user, ogk_real_t t, const ogk_real_t *x,
                                 int mode, ogk_real_t *xdot);

/* Switching function: writes *s = S(t, x, mode). */
typedef ogk_status (*ogk_switch_fn)(void *user, ogk_real_t t, const ogk_real_t *x,
                                    int mode, ogk_real_t *s);

typedef struct {
    size_t n;             /* [-] state size, 1..OGK_RK4_MAX_STATE */
    ogk_real_t h;             /* [s or normalised time] fixed step, > 0 */
    ogk_rhs_fn rhs;       /* right-hand side, required */
    ogk_switch_fn sw;     /* switching function, NULL for none */
    void *user;           /* passed unchanged to rhs and sw */
    ogk_real_t s_tol;         /* [units of S] |S(t_s)| accepted as a root, e.g. 1e-12 */
    ogk_real_t t_tol;         /* [units of t] bracket width at which bisection stops, > 0 */
} ogk_rk4_problem_t;

/* How a switch time was accepted. */
#define OGK_SWITCH_BY_S_TOL 0u     /* |S(t_s)| <= s_tol */
#define OGK_SWITCH_BY_TIME_TOL 1u  /* bracket below t_tol first: reported, t_s is the bracket's far end */

typedef struct {
    ogk_real_t t;          /* [units of t] switching time */
    ogk_real_t s;          /* [units of S] S at the accepted point */
    int mode_after;    /* [-] control mode from t on */
    uint8_t how;       /* OGK_SWITCH_BY_S_TOL or OGK_SWITCH_BY_TIME_TOL */
    uint16_t bisections; /* [-] bisection iterations used */
    size_t dense_index;  /* [-] node of the dense output at t (0 when no dense output) */
} ogk_switch_event_t;

typedef struct {
    ogk_switch_event_t sw[OGK_RK4_MAX_SWITCHES]; /* located switches, in time order */
    size_t n_switches;   /* [-] entries of sw in use */
    size_t n_steps;      /* [-] RK4 (sub-)steps taken, split steps counted per piece */
    size_t n_rhs;        /* [-] right-hand-side evaluations (including bisection) */
    int mode_final;      /* [-] control mode at tf */
    ogk_real_t t_reached;    /* [units of t] last time integrated to (tf on success) */
} ogk_rk4_result_t;

/* Optional dense output: caller-owned buffers receiving every node of the
 * integration grid, t0 and tf included, each switching point once. Node k to
 * node k + 1 is one RK4 step of length t[k+1] - t[k] taken in mode[k]. */
typedef struct {
    ogk_real_t *t;        /* [units of t] capacity entries */
    ogk_real_t *x;        /* [units of x] capacity * n entries, row k is the state at t[k] */
    uint8_t *mode;    /* [-] capacity entries, mode of the step from node k to k + 1 (mode at tf for the last) */
    size_t capacity;  /* [-] nodes the buffers hold */
    size_t count;     /* [-] nodes written (output) */
} ogk_rk4_dense_t;

/* One RK4 step of length dt (any sign, nonzero) from (t, x) in mode.
 * x_next may alias x. */
ogk_status ogk_rk4_step(const ogk_rk4_problem_t *p, ogk_real_t t, const ogk_real_t *x,
                        ogk_real_t dt, int mode, ogk_real_t *x_next);

/* Propagates from (t0, x0, mode0) to tf > t0. xf receives the state at
 * t_reached. On OGK_E_SWITCH_OVERFLOW integration stops at the switch that
 * did not fit (its time is res->t_reached, the state there is in xf). dense
 * may be NULL; OGK_E_DIM if it runs out of capacity. */
ogk_status ogk_rk4_propagate(const ogk_rk4_problem_t *p, ogk_real_t t0,
                             const ogk_real_t *x0, int mode0, ogk_real_t tf,
                             ogk_rk4_result_t *res, ogk_real_t *xf,
                             ogk_rk4_dense_t *dense);

#ifdef __cplusplus
}
#endif

#endif /* OGK_RK4_H */
