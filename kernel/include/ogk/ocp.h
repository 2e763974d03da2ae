/* ogk/ocp.h -- an optimal control problem for the NMPC's solver: the
 * problem as a table of callbacks and the caller's data, apart from the SQP
 * that solves it (ogk/nmpc.h: its settings, workspace and strategies).
 *
 * The class of problems (docs/design/nmpc-problem.md). A planar low-thrust vehicle:
 *  - the state x (OGK_OCP_NX = 5): two position coordinates, two velocity
 *    coordinates, the mass (index 4), in the problem's normalised units;
 *  - the controls u (nu = 1 or 2 per node, linear over each subinterval):
 *    u[0] a thrust angle [rad], u[1] the throttle in [0, 1] when nu = 2;
 *  - the objective: the horizon T (minimum time) or m_0 - m_N + w T
 *    (minimum fuel), the solver's settings;
 *  - the terminal set: the first OGK_OCP_NC state components equal a target
 *    state x_T(t_f) (a moving target: its rate enters the linearisation);
 *  - path constraints: keep-out discs, d_j(x_0, x_1, t) >= R_j at the nodes
 *    and at every RK4 step end within three radii, d_j the distance from
 *    disc j's centre (which may move with t);
 *  - the dynamics' structure the solver's sweeps use (the Jacobian's and the
 *    weighted Hessian's structural nonzeros, nmpc_shoot.c and
 *    nmpc_shoot_hess.c), checked by each problem's tests:
 *      x_0' = x_2 exactly; x_1' depends on x_0 and x_3; x_2', x_3' on every
 *      state and on u; x_4' on x_0 and u; only x_2', x_3' on t;
 *      the Hessian of kappa . f in z = (x, u, t) has its nonzeros among
 *      (x_0, x_0), (x_0, x_2), (x_0, x_3), (x_2, x_3), (x_3, x_3),
 *      (x_0 or x_4, x_4 or u), (u, u), and in x_1 and t only for a
 *      time-varying problem (OGK_OCP_TIME_VARYING).
 * The heliocentric rendezvous of Starek & Kolmanovsky (ogk/nmpc.h) and the
 * Clohessy-Wiltshire proximity approach (ogk/proximity.h) are two users. */
#ifndef OGK_OCP_H
#define OGK_OCP_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>
#include "ogk/status.h"
#include "ogk/real.h"

#ifdef __cplusplus
extern "C" {
#endif

#define OGK_OCP_NX 5u           /* state: 2 positions, 2 velocities, mass */
#define OGK_OCP_NC 4u           /* terminal conditions: x_0..x_3 = x_T(t_f) */
#define OGK_OCP_MAX_NU 2u       /* controls per node: the thrust angle, the throttle */
#define OGK_OCP_MAX_KEEPOUT 2u  /* keep-out discs */
#define OGK_OCP_MODEL_KEY 26u   /* doubles that identify a model (the sensitivity cache) */
/* Arguments of the weighted Hessian: z = (x (5), u (nu), t), this stride. */
#define OGK_OCP_NZ (OGK_OCP_NX + OGK_OCP_MAX_NU + 1u)

/* Structure flags (ogk_ocp_problem_t.structure). */
#define OGK_OCP_TIME_VARYING 0x01u   /* f depends on t (its t-column is propagated) */
#define OGK_OCP_FLOW_FIXED 0x02u     /* with nu = 1, x_4' depends on neither x nor u nor t */

typedef struct {
    /* OGK_OCP_* structure flags of the model as it is now (data may change
     * at `update`). */
    uint32_t (*structure)(const void *data, uint32_t nu);
    /* xdot = f(t, x, u) and, when jx is not NULL, the Jacobians jx (5 x 5,
     * row-major), ju (5 x nu), jt (5): only the structural nonzeros written
     * (the caller zeroes the arrays once). trig: cos and sin of u[0], or NULL
     * (computed here). OGK_E_NONFINITE outside the model's domain or for a
     * value that is not finite. */
    ogk_status (*dynamics)(const void *data, uint32_t nu, ogk_real_t t, const ogk_real_t *x, const ogk_real_t *u,
                           const ogk_real_t *trig, ogk_real_t *xdot, ogk_real_t *jx, ogk_real_t *ju, ogk_real_t *jt);
    /* hz (OGK_OCP_NZ square, z = (x, u, t), t at index 5 + nu) = the upper
     * triangle (row <= column) of the Hessian of kappa . f: only its
     * structural nonzeros written (the caller zeroes hz before every call);
     * called after `dynamics` at the same point succeeded. */
    void (*dynamics_hess)(const void *data, uint32_t nu, ogk_real_t t, const ogk_real_t *x, const ogk_real_t *u,
                          const ogk_real_t *trig, const ogk_real_t *kappa, ogk_real_t *hz);
    /* The target state x_T(t_f) (OGK_OCP_NC) and its rate dx_T/dt_f. */
    void (*target)(const void *data, ogk_real_t t_f, ogk_real_t *x_target, ogk_real_t *x_target_rate);
    /* Radius R_j of keep-out disc j < OGK_OCP_MAX_KEEPOUT (0: none). */
    ogk_real_t (*keepout_radius)(const void *data, size_t j);
    /* Distance d_j of (x_0, x_1) at time t from disc j's centre, and its
     * derivatives in x_0, x_1 and t. */
    ogk_real_t (*keepout_distance)(const void *data, size_t j, const ogk_real_t *x, ogk_real_t t, ogk_real_t *d_x0,
                               ogk_real_t *d_x1, ogk_real_t *d_t);
    /* key (OGK_OCP_MODEL_KEY doubles, every one written: 0 where unused) =
     * the doubles that define the dynamics: sensitivities computed under
     * another key are not reused. */
    void (*model_key)(const void *data, ogk_real_t *key);
    /* True when the n states x[0 .. n) (stride OGK_OCP_NX: a measured state,
     * or a plan's nodes) are inside the model's domain (e.g. mass > 0). */
    bool (*state_valid)(const void *data, const ogk_real_t *x, size_t n);
    /* Optional (NULL: none): the problem's own update at each solve or
     * replan from the measured state (t, x), before the SQP; returns the
     * OGK_NMPC_FLAG_* it reports (e.g. a body released). */
    uint32_t (*update)(void *data, ogk_real_t t, const ogk_real_t *x);
} ogk_ocp_problem_t;

#ifdef __cplusplus
}
#endif

#endif /* OGK_OCP_H */
