/* bench_core.c -- cost of the kernel core's hot paths on the host.
 *
 *   bench_core time CASE      ns per call (median of 7 batches)
 *   bench_core once CASE      one call, for valgrind callgrind with
 *                             --toggle-collect=bench_CASE_once
 * CASE: rk4_step    one RK4 step of the two-body problem (6 states)
 *       switch      one bisection switch location: one two-body RK4 step
 *                   over which S = y - 0.3 changes sign, the switch located
 *                   to |S| <= 1e-12 and the step finished in the new mode
 *                   (all RK4 trial steps, S evaluations and the split) */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <math.h>

#include "ogk/rk4.h"
#include "ogk_port.h"
#include "bench_timer.h"

static ogk_status two_body(void *user, double t, const double *x, int mode, double *xdot)
{
    const double r2 = x[0] * x[0] + x[1] * x[1] + x[2] * x[2];
    const double inv_r3 = 1.0 / (r2 * sqrt(r2));
    (void)user;
    (void)t;
    (void)mode;
    xdot[0] = x[3];
    xdot[1] = x[4];
    xdot[2] = x[5];
    xdot[3] = -x[0] * inv_r3;
    xdot[4] = -x[1] * inv_r3;
    xdot[5] = -x[2] * inv_r3;
    return OGK_OK;
}

/* S = y - 0.3: the e = 0.1 orbit below crosses it at t ~ 0.28, inside the step. */
static ogk_status plane_switch(void *user, double t, const double *x, int mode, double *s)
{
    (void)user;
    (void)t;
    (void)mode;
    *s = x[1] - 0.3;
    return OGK_OK;
}

static const double x_peri[6] = {0.9, 0.0, 0.0, 0.0, 1.1055415967851332, 0.0};
static volatile double sink;

__attribute__((noinline)) static int bench_rk4_step_once(void)
{
    ogk_rk4_problem_t p = {6u, 0.01, two_body, NULL, NULL, 0.0, 0.0};
    double x[6];
    int st = (int)ogk_rk4_step(&p, 0.0, x_peri, 0.01, 1, x);
    sink = x[0];
    return st;
}

__attribute__((noinline)) static int bench_switch_once(void)
{
    /* One 0.5-long step from periapsis; y passes 0.3 at t ~ 0.28. */
    ogk_rk4_problem_t p = {6u, 0.5, two_body, plane_switch, NULL, 1e-12, 1e-14};
    ogk_rk4_result_t res;
    double xf[6];
    int st = (int)ogk_rk4_propagate(&p, 0.0, x_peri, 1, 0.5, &res, xf, NULL);
    if (st == 0 && res.n_switches != 1u) {
        st = -1;
    }
    sink = xf[0] + (double)res.sw[0].bisections;
    return st;
}

int main(int argc, char **argv)
{
    (void)ogk_port_counter_init();
    if (argc != 3) {
        fprintf(stderr, "usage: %s time|once rk4_step|switch\n", argv[0]);
        return 2;
    }
    if (strcmp(argv[1], "once") == 0) {
        if (strcmp(argv[2], "rk4_step") == 0) {
            return bench_rk4_step_once();
        }
        if (strcmp(argv[2], "switch") == 0) {
            return bench_switch_once();
        }
    } else if (strcmp(argv[1], "time") == 0) {
        if (strcmp(argv[2], "rk4_step") == 0) {
            return bench_time_case(bench_rk4_step_once, 200000L, "rk4_step");
        }
        if (strcmp(argv[2], "switch") == 0) {
            return bench_time_case(bench_switch_once, 5000L, "switch");
        }
    }
    fprintf(stderr, "unknown arguments\n");
    return 2;
}
