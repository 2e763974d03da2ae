/* bench_qp_record.c -- records the QPs that the NMPC bench hands to
 * ogk_qp_solve, for tests/bench/bench_qp_peers.py. Linked into a build of
 * tests/bench/bench_nmpc.c with -Wl,--wrap=ogk_qp_solve (no hook in kernel/):
 * every QP of `bench_nmpc once` (the open loop, then the one re-solve) is
 * appended to the file named by OGK_QP_RECORD in the format of
 * bench_qp_peers.c (int32 n, m_eq, m_in; doubles H, g, A_eq, b_eq, A_in,
 * b_in, lb, ub; absent bounds as -+1e20), then solved by the real
 * ogk_qp_solve. */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>

#include "ogk/qp.h"

ogk_status __real_ogk_qp_solve(ogk_qp_workspace_t *ws, const ogk_qp_problem_t *p, ogk_qp_solution_t *sol);
ogk_status __wrap_ogk_qp_solve(ogk_qp_workspace_t *ws, const ogk_qp_problem_t *p, ogk_qp_solution_t *sol);

static void put(FILE *f, const double *v, size_t k)
{
    if (k > 0u && fwrite(v, sizeof(double), k, f) != k) {
        fprintf(stderr, "bench_qp_record: write failed\n");
        exit(2);
    }
}

static void put_bounds(FILE *f, const double *v, size_t n, double none)
{
    size_t i;
    for (i = 0u; i < n; ++i) {
        const double b = (v != NULL) ? v[i] : none;
        put(f, &b, 1u);
    }
}

ogk_status __wrap_ogk_qp_solve(ogk_qp_workspace_t *ws, const ogk_qp_problem_t *p, ogk_qp_solution_t *sol)
{
    const char *path = getenv("OGK_QP_RECORD");
    if (path != NULL && p != NULL) {
        FILE *f = fopen(path, "ab");
        int32_t hdr[3];
        if (f == NULL) {
            fprintf(stderr, "bench_qp_record: cannot open %s\n", path);
            exit(2);
        }
        hdr[0] = (int32_t)p->n;
        hdr[1] = (int32_t)p->m_eq;
        hdr[2] = (int32_t)p->m_in;
        if (fwrite(hdr, sizeof(int32_t), 3u, f) != 3u) {
            exit(2);
        }
        put(f, p->H, p->n * p->n);
        put(f, p->g, p->n);
        put(f, p->A_eq, p->m_eq * p->n);
        put(f, p->b_eq, p->m_eq);
        put(f, p->A_in, p->m_in * p->n);
        put(f, p->b_in, p->m_in);
        put_bounds(f, p->lb, p->n, -OGK_QP_INF);
        put_bounds(f, p->ub, p->n, OGK_QP_INF);
        fclose(f);
    }
    return __real_ogk_qp_solve(ws, p, sol);
}
