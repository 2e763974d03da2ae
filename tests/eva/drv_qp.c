/* tests/eva/drv_qp.c -- EVA driver of ogk_qp_solve (ogk/qp.h), n = 3: a
 * diagonal H with entries in [1, 10] plus off-diagonal terms in +-0.1
 * (symmetric positive definite), g and the bounds' data in +-10, one
 * equality row and two inequality rows with entries in +-1, box bounds
 * [-10, -1] / [1, 10]. Not gated at zero: docs/evidence/eva.md lists the alarms. */
#include "eva_driver.h"
#include "ogk/qp.h"

#define N 3u

void eva_qp(void)
{
    static ogk_qp_workspace_t ws;
    static ogk_qp_solution_t sol;
    double H[N * N];
    double g[N];
    double a_eq[N];
    double b_eq[1];
    double a_in[2u * N];
    double b_in[2];
    double lb[N];
    double ub[N];
    ogk_qp_problem_t p;
    size_t i;
    size_t j;

    for (i = 0u; i < N; ++i) {
        for (j = 0u; j < N; ++j) {
            H[(i * N) + j] = (i == j) ? eva_in(1.0, 10.0) : 0.0;
        }
        g[i] = eva_in(-10.0, 10.0);
        a_eq[i] = eva_in(-1.0, 1.0);
        a_in[i] = eva_in(-1.0, 1.0);
        a_in[N + i] = eva_in(-1.0, 1.0);
        lb[i] = eva_in(-10.0, -1.0);
        ub[i] = eva_in(1.0, 10.0);
    }
    H[1] = eva_in(-0.1, 0.1);
    H[3] = H[1];
    b_eq[0] = eva_in(-1.0, 1.0);
    b_in[0] = eva_in(-1.0, 1.0);
    b_in[1] = eva_in(-1.0, 1.0);
    p.n = N;
    p.m_eq = 1u;
    p.m_in = 2u;
    p.H = H;
    p.g = g;
    p.A_eq = a_eq;
    p.b_eq = b_eq;
    p.A_in = a_in;
    p.b_in = b_in;
    p.lb = lb;
    p.ub = ub;
    (void)ogk_qp_solve(&ws, &p, &sol);
    (void)ogk_qp_solve(&ws, NULL, &sol);
}
