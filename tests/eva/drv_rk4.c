/* tests/eva/drv_rk4.c -- EVA driver of ogk_rk4_* (ogk/rk4.h): a right-hand
 * side whose derivative is any value in [-1e3, 1e3] (a bounded vector
 * field), a switching function in [-1, 1], states in [-1e6, 1e6]. */
#include "eva_driver.h"
#include "ogk/rk4.h"

#define N_STATE 3u

static ogk_status rhs(void *user, double t, const double *x, int mode, double *xdot)
{
    size_t i;
    (void)user;
    (void)t;
    (void)x;
    (void)mode;
    for (i = 0u; i < N_STATE; ++i) {
        xdot[i] = eva_in(-1.0e3, 1.0e3);
    }
    return OGK_OK;
}

static ogk_status sw(void *user, double t, const double *x, int mode, double *s)
{
    (void)user;
    (void)t;
    (void)x;
    (void)mode;
    *s = eva_in(-1.0, 1.0);
    return OGK_OK;
}

void eva_rk4(void)
{
    ogk_rk4_problem_t p;
    ogk_rk4_result_t res;
    double x[N_STATE];
    double xf[N_STATE];
    size_t i;

    for (i = 0u; i < N_STATE; ++i) {
        x[i] = eva_in(-1.0e6, 1.0e6);
    }
    p.n = N_STATE;
    p.h = 0.25;
    p.rhs = rhs;
    p.sw = NULL;
    p.user = NULL;
    p.s_tol = 1e-12;
    p.t_tol = 1e-9;
    (void)ogk_rk4_step(&p, eva_in(-1.0e6, 1.0e6), x, eva_in(-1.0e3, 1.0e3), 0, xf);
    (void)ogk_rk4_step(&p, 0.0, x, 0.1, 0, x);
#ifndef EVA_RK4_NO_PROPAGATE
    (void)ogk_rk4_propagate(&p, 0.0, x, 0, 1.0, &res, xf, NULL);
#endif
#ifdef EVA_RK4_SWITCH
    p.sw = sw;
    (void)ogk_rk4_propagate(&p, 0.0, x, 0, 1.0, &res, xf, NULL);
#endif
    /* rejections */
    (void)ogk_rk4_step(NULL, 0.0, x, 0.1, 0, xf);
    p.n = 0u;
    (void)ogk_rk4_step(&p, 0.0, x, 0.1, 0, xf);
}
