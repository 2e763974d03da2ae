/* models.c -- harness models (see models.h). Not flight code. In the kernel's real type
 * (ogk/real.h), so that the float build's RK4 calls them as it calls its own. */
#include "models.h"

#include <math.h>
#include <stddef.h>

ogk_status ogk_model_two_body_rhs(void *user, ogk_real_t t, const ogk_real_t *x,
                                  int mode, ogk_real_t *xdot)
{
    const ogk_model_two_body_t *p = (const ogk_model_two_body_t *)user;
    ogk_real_t r2;
    ogk_real_t r3;
    ogk_real_t k;
    (void)t;
    (void)mode;
    if (p == NULL || x == NULL || xdot == NULL) {
        return OGK_E_NULL;
    }
    r2 = x[0] * x[0] + x[1] * x[1] + x[2] * x[2];
    if (!(r2 > OGK_R(0.0))) {
        return OGK_E_RANGE;
    }
    r3 = r2 * OGK_SQRT(r2);
    k = -p->mu / r3;
    xdot[0] = x[3];
    xdot[1] = x[4];
    xdot[2] = x[5];
    xdot[3] = k * x[0];
    xdot[4] = k * x[1];
    xdot[5] = k * x[2];
    return OGK_OK;
}

ogk_status ogk_model_min_fuel_di_rhs(void *user, ogk_real_t t, const ogk_real_t *x,
                                     int mode, ogk_real_t *xdot)
{
    const ogk_model_min_fuel_di_t *p = (const ogk_model_min_fuel_di_t *)user;
    ogk_real_t u = OGK_R(0.0);
    (void)t;
    if (p == NULL || x == NULL || xdot == NULL) {
        return OGK_E_NULL;
    }
    if (mode == 1) {
        /* Thrust opposite to the velocity costate (minimises lambda_v u). */
        u = (x[3] > OGK_R(0.0)) ? -p->u_max : p->u_max;
    } else if (mode != 0) {
        return OGK_E_RANGE;
    }
    xdot[0] = x[1];
    xdot[1] = u;
    xdot[2] = OGK_R(0.0);
    xdot[3] = -x[2];
    return OGK_OK;
}

ogk_status ogk_model_min_fuel_di_switch(void *user, ogk_real_t t, const ogk_real_t *x,
                                        int mode, ogk_real_t *s)
{
    (void)user;
    (void)t;
    (void)mode;
    if (x == NULL || s == NULL) {
        return OGK_E_NULL;
    }
    *s = OGK_FABS(x[3]) - OGK_R(1.0);
    return OGK_OK;
}

ogk_status ogk_model_decay_rhs(void *user, ogk_real_t t, const ogk_real_t *x,
                               int mode, ogk_real_t *xdot)
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

ogk_status ogk_model_oscillator_rhs(void *user, ogk_real_t t, const ogk_real_t *x,
                                    int mode, ogk_real_t *xdot)
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

ogk_status ogk_model_oscillator_switch(void *user, ogk_real_t t, const ogk_real_t *x,
                                       int mode, ogk_real_t *s)
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
