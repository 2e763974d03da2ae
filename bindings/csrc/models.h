/* models.h -- C right-hand sides and switching functions for the SIL harness's
 * tests and demos. NOT flight code: these are the "plant" side, called by the
 * kernel's RK4 through ogk_rk4_problem_t (signatures of ogk/rk4.h). */
#ifndef OGK_HARNESS_MODELS_H
#define OGK_HARNESS_MODELS_H

#include "ogk/real.h"
#include "ogk/status.h"

#ifdef __cplusplus
extern "C" {
#endif

/* ---------------------------------------------------------------- two-body
 * x = [r(3), v(3)] in an inertial frame; xdot = [v, -mu r / |r|^3].
 * mode is ignored. OGK_E_RANGE at r = 0. */
typedef struct {
    ogk_real_t mu; /* [length^3/time^2] gravitational parameter */
} ogk_model_two_body_t;

ogk_status ogk_model_two_body_rhs(void *user, ogk_real_t t, const ogk_real_t *x,
                                  int mode, ogk_real_t *xdot);

/* ---------------------------------------------------------------- min-fuel double integrator
 * Minimum-fuel control of r'' = u, |u| <= u_max (cost = integral of |u|),
 * integrated together with its costates (Pontryagin):
 *   x = [r, v, lambda_r, lambda_v],
 *   H = |u| + lambda_r v + lambda_v u,
 *   lambda_r' = -dH/dr = 0,  lambda_v' = -dH/dv = -lambda_r,
 *   u = -u_max sign(lambda_v) when |lambda_v| > 1 (mode 1, thrust on),
 *   u = 0                     when |lambda_v| < 1 (mode 0, coast).
 * Switching function S = |lambda_v| - 1: piecewise linear in the state and,
 * since lambda_v is linear in t, crossing zero at closed-form times. A
 * rest-to-rest transfer of distance D in time T is bang-off-bang:
 *   t1 = (T - sqrt(T^2 - 4 D / u_max)) / 2,  t2 = T - t1,
 *   lambda_v(0) = -T / (T - 2 t1),  lambda_r = -2 / (T - 2 t1). */
#define OGK_MODEL_MIN_FUEL_DI_N 4u

typedef struct {
    ogk_real_t u_max; /* [length/time^2] acceleration magnitude when thrust is on, > 0 */
} ogk_model_min_fuel_di_t;

ogk_status ogk_model_min_fuel_di_rhs(void *user, ogk_real_t t, const ogk_real_t *x,
                                     int mode, ogk_real_t *xdot);
ogk_status ogk_model_min_fuel_di_switch(void *user, ogk_real_t t, const ogk_real_t *x,
                                        int mode, ogk_real_t *s);

/* ---------------------------------------------------------------- decay
 * Scalar x' = -rate x (exact solution x0 exp(-rate t)); returns OGK_E_RANGE
 * for t > t_fail, so tests can provoke OGK_E_CALLBACK. mode is ignored. */
typedef struct {
    ogk_real_t rate;   /* [1/time] decay rate */
    ogk_real_t t_fail; /* [time] the rhs fails beyond this time */
} ogk_model_decay_t;

ogk_status ogk_model_decay_rhs(void *user, ogk_real_t t, const ogk_real_t *x,
                               int mode, ogk_real_t *xdot);

/* ---------------------------------------------------------------- oscillator
 * x = [q, q'], q'' = -omega^2 q; switching function S = q, so with x0 = [1, 0]
 * the k-th switch (k = 0, 1, ...) is at t = (k + 1/2) pi / omega. mode is
 * ignored by the rhs: the model exercises event location on smooth,
 * non-polynomial motion and the switch-count limit. */
typedef struct {
    ogk_real_t omega; /* [rad/time] angular frequency */
} ogk_model_oscillator_t;

ogk_status ogk_model_oscillator_rhs(void *user, ogk_real_t t, const ogk_real_t *x,
                                    int mode, ogk_real_t *xdot);
ogk_status ogk_model_oscillator_switch(void *user, ogk_real_t t, const ogk_real_t *x,
                                       int mode, ogk_real_t *s);

#ifdef __cplusplus
}
#endif

#endif /* OGK_HARNESS_MODELS_H */
