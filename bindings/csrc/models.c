/* models.c -- harness models (see models.h). Not flight code. */
#include "models.h"

#include <math.h>
#include <stddef.h>

ogk_status ogk_model_two_body_rhs(void *user, double t, const double *x,
                                  int mode, double *xdot)
{
    const ogk_model_two_body_t *p = (const ogk_model_two_body_t *)user;
    double r2;
    double r3;
    double k;
    (void)t;
    (void)mode;
    if (p == NULL || x == NULL || xdot == NULL) {
        return OGK_E_NULL;
    }
    r2 = x[0] * x[0] + x[1] * x[1] + x[2] * x[2];
    if (!(r2 > 0.0)) {
        return OGK_E_RANGE;
    }
    r3 = r2 * sqrt(r2);
    k = -p->mu / r3;
    xdot[0] = x[3];
    xdot[1] = x[4];
    xdot[2] = x[5];
    xdot[3] = k * x[0];
    xdot[4] = k * x[1];
    xdot[5] = k * x[2];
    return OGK_OK;
}

ogk_status ogk_model_min_fuel_di_rhs(void *user, double t, const double *x,
                                     int mode, double *xdot)
{
    const ogk_model_min_fuel_di_t *p = (const ogk_model_min_fuel_di_t *)user;
    double u = 0.0;
    (void)t;
    if (p == NULL || x == NULL || xdot == NULL) {
        return OGK_E_NULL;
    }
    if (mode == 1) {
        /* Thrust opposite to the velocity costate (minimises lambda_v u). */
        u = (x[3] > 0.0) ? -p->u_max : p->u_max;
    } else if (mode != 0) {
        return OGK_E_RANGE;
    }
    xdot[0] = x[1];
    xdot[1] = u;
    xdot[2] = 0.0;
    xdot[3] = -x[2];
    return OGK_OK;
}

ogk_status ogk_model_min_fuel_di_switch(void *user, double t, const double *x,
                                        int mode, double *s)
{
    (void)user;
    (void)t;
    (void)mode;
    if (x == NULL || s == NULL) {
        return OGK_E_NULL;
    }
    *s = fabs(x[3]) - 1.0;
    return OGK_OK;
}

ogk_status ogk_model_decay_rhs(void *user, double t, const double *x,
                               int mode, double *xdot)
{
    const ogk_model_decay_t *p = (const ogk_model_decay_t *)user;
    (void)mode;
    if (p == NULL || x == NULL || xdot == NULL) {
        return OGK_E_NULL;
    }
    if (t > p->t_fail) {
        return OGK_E_RANGE;
    }
    xdot[0] = -p->rate * x[0];
    return OGK_OK;
}

ogk_status ogk_model_oscillator_rhs(void *user, double t, const double *x,
                                    int mode, double *xdot)
{
    const ogk_model_oscillator_t *p = (const ogk_model_oscillator_t *)user;
    (void)t;
    (void)mode;
    if (p == NULL || x == NULL || xdot == NULL) {
        return OGK_E_NULL;
    }
    xdot[0] = x[1];
    xdot[1] = -p->omega * p->omega * x[0];
    return OGK_OK;
}

ogk_status ogk_model_oscillator_switch(void *user, double t, const double *x,
                                       int mode, double *s)
{
    (void)user;
    (void)t;
    (void)mode;
    if (x == NULL || s == NULL) {
        return OGK_E_NULL;
    }
    *s = x[0];
    return OGK_OK;
}
