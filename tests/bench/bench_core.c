/* bench_core.c -- cost of the kernel core's hot paths on the host.
 *
 *   bench_core time CASE      ns per call (median of 7 batches)
 *   bench_core once CASE      one call, for valgrind callgrind with
 *                             --toggle-collect=bench_CASE_once
 * CASE: rk4_step    one RK4 step of the two-body problem (6 states)
 *       switch      one bisection switch location: one two-body RK4 step
 *                   over which S = y - 0.3 changes sign, the switch located
 *                   to |S| <= 1e-12 and the step finished in the new mode
 *                   (all RK4 trial steps, S evaluations and the split)
 *       qp          one ogk_qp_solve of a fixed random QP of the NMPC's size:
 *                   n = 32, 4 equality rows, lower bounds on 16 variables
 *                   (H = M M^T / n + 0.05 I, b from a known feasible point) */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <math.h>

#include "ogk/qp.h"
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

/* The QP of the qp case, built once by qp_setup (fixed-seed LCG). */
#define QP_N 32u
#define QP_EQ 4u
static double qp_H[QP_N * QP_N], qp_g[QP_N], qp_Aeq[QP_EQ * QP_N], qp_beq[QP_EQ];
static double qp_lb[QP_N], qp_ub[QP_N];
static ogk_qp_problem_t qp_prob;
static ogk_qp_workspace_t qp_ws;
static ogk_qp_solution_t qp_sol;

static double qp_uniform(unsigned long long *s)
{
    *s = *s * 6364136223846793005ull + 1442695040888963407ull;
    return (double)(*s >> 11) * (2.0 / 9007199254740992.0) - 1.0;
}

static void qp_setup(void)
{
    static double M[QP_N * QP_N], x0[QP_N];
    unsigned long long s = 20261202ull;
    size_t i, j, k;
    for (i = 0; i < QP_N * QP_N; ++i) {
        M[i] = qp_uniform(&s);
    }
    for (i = 0; i < QP_N; ++i) {
        x0[i] = qp_uniform(&s);
        qp_g[i] = 3.0 * qp_uniform(&s);
        qp_lb[i] = (i % 2u == 0u) ? x0[i] - 0.1 * (qp_uniform(&s) + 1.0) : -OGK_QP_INF;
        qp_ub[i] = OGK_QP_INF;
        for (j = 0; j < QP_N; ++j) {
            double v = (i == j) ? 0.05 : 0.0;
            for (k = 0; k < QP_N; ++k) {
                v += M[i * QP_N + k] * M[j * QP_N + k] / (double)QP_N;
            }
            qp_H[i * QP_N + j] = v;
        }
    }
    for (i = 0; i < QP_EQ; ++i) {
        qp_beq[i] = 0.0;
        for (k = 0; k < QP_N; ++k) {
            qp_Aeq[i * QP_N + k] = qp_uniform(&s);
            qp_beq[i] += qp_Aeq[i * QP_N + k] * x0[k];
        }
    }
    memset(&qp_prob, 0, sizeof(qp_prob));
    qp_prob.n = QP_N;
    qp_prob.m_eq = QP_EQ;
    qp_prob.H = qp_H;
    qp_prob.g = qp_g;
    qp_prob.A_eq = qp_Aeq;
    qp_prob.b_eq = qp_beq;
    qp_prob.lb = qp_lb;
    qp_prob.ub = qp_ub;
}

__attribute__((noinline)) static int bench_qp_once(void)
{
    int st = (int)ogk_qp_solve(&qp_ws, &qp_prob, &qp_sol);
    sink = qp_sol.x[0] + (double)qp_sol.iterations;
    return st;
}

int main(int argc, char **argv)
{
    (void)ogk_port_counter_init();
    if (argc != 3) {
        fprintf(stderr, "usage: %s time|once rk4_step|switch|qp\n", argv[0]);
        return 2;
    }
    qp_setup();
    if (strcmp(argv[1], "once") == 0) {
        if (strcmp(argv[2], "qp") == 0) {
            return bench_qp_once();
        }
        if (strcmp(argv[2], "rk4_step") == 0) {
            return bench_rk4_step_once();
        }
        if (strcmp(argv[2], "switch") == 0) {
            return bench_switch_once();
        }
    } else if (strcmp(argv[1], "time") == 0) {
        if (strcmp(argv[2], "qp") == 0) {
            return bench_time_case(bench_qp_once, 2000L, "qp");
        }
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
