/* bench_qp_peers.c -- ogk_qp_solve against DAQP (Arnstrom, Bemporad & Axehill
 * 2022; its C sources from the PyPI sdist, compiled with the same compiler and
 * flags as the kernel), both called from C on the same pre-built arrays.
 *
 *   bench_qp_peers time FILE REPS   per QP of FILE: median CPU time of REPS
 *                                   solves (CLOCK_PROCESS_CPUTIME_ID, each
 *                                   solve timed alone) of the kernel and of
 *                                   daqp_quadprog (one-shot: setup, solve and
 *                                   its own malloc/free, as daqp.solve does);
 *                                   one line per QP: index n m_eq m_in status
 *                                   t_ogk_ns t_daqp_ns f_ogk f_daqp exitflag
 *   bench_qp_peers once FILE        every QP of FILE solved once by the kernel
 *                                   in bench_qp_set_once (for callgrind's
 *                                   --toggle-collect)
 *   bench_qp_peers once-daqp FILE   the same for DAQP in bench_daqp_set_once
 *                                   (its cases built before, outside)
 *
 * FILE (written by tests/bench/bench_qp_peers.py and by the NMPC recorder
 * bench_qp_record.c): per QP, int32 n, m_eq, m_in, then doubles H (n x n,
 * row-major), g, A_eq, b_eq, A_in, b_in, lb, ub (+-1e20 or beyond: none). */
#define _POSIX_C_SOURCE 199309L
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "ogk/qp.h"
#include "api.h"

typedef struct {
    int32_t n, m_eq, m_in;
    double *H, *g, *A_eq, *b_eq, *A_in, *b_in, *lb, *ub;
} qp_rec_t;

static ogk_qp_workspace_t ws;
static ogk_qp_solution_t sol;

static double *read_doubles(FILE *f, size_t k)
{
    double *v = malloc((k > 0 ? k : 1) * sizeof(double));
    if (v == NULL || fread(v, sizeof(double), k, f) != k) {
        fprintf(stderr, "bench_qp_peers: short file\n");
        exit(2);
    }
    return v;
}

static size_t read_set(const char *path, qp_rec_t **out)
{
    FILE *f = fopen(path, "rb");
    size_t cap = 16, cnt = 0;
    qp_rec_t *v = malloc(cap * sizeof(*v));
    int32_t hdr[3];
    if (f == NULL) {
        fprintf(stderr, "bench_qp_peers: cannot open %s\n", path);
        exit(2);
    }
    while (fread(hdr, sizeof(int32_t), 3, f) == 3) {
        qp_rec_t *q;
        size_t n = (size_t)hdr[0], me = (size_t)hdr[1], mi = (size_t)hdr[2];
        if (cnt == cap) {
            cap *= 2;
            v = realloc(v, cap * sizeof(*v));
        }
        q = &v[cnt++];
        q->n = hdr[0];
        q->m_eq = hdr[1];
        q->m_in = hdr[2];
        q->H = read_doubles(f, n * n);
        q->g = read_doubles(f, n);
        q->A_eq = read_doubles(f, me * n);
        q->b_eq = read_doubles(f, me);
        q->A_in = read_doubles(f, mi * n);
        q->b_in = read_doubles(f, mi);
        q->lb = read_doubles(f, n);
        q->ub = read_doubles(f, n);
    }
    fclose(f);
    *out = v;
    return cnt;
}

static void ogk_problem(const qp_rec_t *q, ogk_qp_problem_t *p)
{
    memset(p, 0, sizeof(*p));
    p->n = (size_t)q->n;
    p->m_eq = (size_t)q->m_eq;
    p->m_in = (size_t)q->m_in;
    p->H = q->H;
    p->g = q->g;
    p->A_eq = q->m_eq > 0 ? q->A_eq : NULL;
    p->b_eq = q->m_eq > 0 ? q->b_eq : NULL;
    p->A_in = q->m_in > 0 ? q->A_in : NULL;
    p->b_in = q->m_in > 0 ? q->b_in : NULL;
    p->lb = q->lb;
    p->ub = q->ub;
}

/* DAQP's form: blower <= [x; A_eq x; A_in x] <= bupper, the equality rows with
 * sense 5 (DAQP's "equality"), bounds as its simple bounds (ms = n). */
typedef struct {
    DAQPProblem p;
    double *A, *bu, *bl, *x, *lam;
    int *sense;
} daqp_case_t;

static void daqp_problem(const qp_rec_t *q, daqp_case_t *c)
{
    size_t n = (size_t)q->n, me = (size_t)q->m_eq, mi = (size_t)q->m_in, m = n + me + mi, i;
    c->A = malloc((me + mi + 1) * n * sizeof(double));
    c->bu = malloc(m * sizeof(double));
    c->bl = malloc(m * sizeof(double));
    c->x = malloc(n * sizeof(double));
    c->lam = malloc(m * sizeof(double));
    c->sense = calloc(m, sizeof(int));
    memcpy(c->A, q->A_eq, me * n * sizeof(double));
    memcpy(c->A + me * n, q->A_in, mi * n * sizeof(double));
    for (i = 0; i < n; ++i) {
        c->bl[i] = q->lb[i] <= -OGK_QP_INF ? -DAQP_INF : q->lb[i];
        c->bu[i] = q->ub[i] >= OGK_QP_INF ? DAQP_INF : q->ub[i];
    }
    for (i = 0; i < me; ++i) {
        c->bl[n + i] = q->b_eq[i];
        c->bu[n + i] = q->b_eq[i];
        c->sense[n + i] = 5;
    }
    for (i = 0; i < mi; ++i) {
        c->bl[n + me + i] = q->b_in[i];
        c->bu[n + me + i] = DAQP_INF;
    }
    memset(&c->p, 0, sizeof(c->p));
    c->p.n = (int)n;
    c->p.m = (int)m;
    c->p.ms = (int)n;
    c->p.H = q->H;
    c->p.f = q->g;
    c->p.A = c->A;
    c->p.bupper = c->bu;
    c->p.blower = c->bl;
    c->p.sense = c->sense;
}

static int daqp_run(daqp_case_t *c, double *fval)
{
    DAQPResult res;
    memset(&res, 0, sizeof(res));
    res.x = c->x;
    res.lam = c->lam;
    daqp_quadprog(&res, &c->p, NULL);
    *fval = res.fval;
    return res.exitflag;
}

static double cpu_ns(void)
{
    struct timespec t;
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
    return (double)t.tv_sec * 1e9 + (double)t.tv_nsec;
}

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

static double median(double *v, int k)
{
    qsort(v, (size_t)k, sizeof(double), cmp_double);
    return (k % 2) ? v[k / 2] : 0.5 * (v[k / 2 - 1] + v[k / 2]);
}

/* objective 1/2 x^T H x + g^T x of the original problem (DAQP's fval is of its own form) */
static double objective(const qp_rec_t *q, const double *x)
{
    size_t n = (size_t)q->n, i, k;
    double f = 0.0;
    for (i = 0; i < n; ++i) {
        double hx = 0.0;
        for (k = 0; k < n; ++k) hx += q->H[i * n + k] * x[k];
        f += x[i] * (0.5 * hx + q->g[i]);
    }
    return f;
}

__attribute__((noinline)) static int bench_qp_set_once(const qp_rec_t *v, size_t cnt)
{
    int bad = 0;
    size_t i;
    for (i = 0; i < cnt; ++i) {
        ogk_qp_problem_t p;
        ogk_problem(&v[i], &p);
        bad += (int)(ogk_qp_solve(&ws, &p, &sol) != OGK_OK);
    }
    return bad;
}

__attribute__((noinline)) static int bench_daqp_set_once(daqp_case_t *c, size_t cnt)
{
    int bad = 0;
    size_t i;
    double fd = 0.0;
    for (i = 0; i < cnt; ++i) {
        bad += (int)(daqp_run(&c[i], &fd) != 1);
    }
    return bad;
}

int main(int argc, char **argv)
{
    qp_rec_t *v;
    size_t cnt, i;
    if (argc < 3) {
        fprintf(stderr, "usage: bench_qp_peers time FILE REPS | once FILE | once-daqp FILE\n");
        return 2;
    }
    cnt = read_set(argv[2], &v);
    if (strcmp(argv[1], "once") == 0) {
        int bad = bench_qp_set_once(v, cnt);
        printf("qps %zu failed %d\n", cnt, bad);
        return 0;
    }
    if (strcmp(argv[1], "once-daqp") == 0) {
        daqp_case_t *c = malloc(cnt * sizeof(daqp_case_t));
        int bad;
        for (i = 0; i < cnt; ++i) {
            daqp_problem(&v[i], &c[i]);
        }
        bad = bench_daqp_set_once(c, cnt);
        printf("qps %zu failed %d\n", cnt, bad);
        return 0;
    }
    {
        int reps = argc > 3 ? atoi(argv[3]) : 31, r;
        double *to = malloc((size_t)reps * sizeof(double)), *td = malloc((size_t)reps * sizeof(double));
        for (i = 0; i < cnt; ++i) {
            ogk_qp_problem_t p;
            daqp_case_t c;
            int st = 0, ef = 0;
            double fd = 0.0;
            ogk_problem(&v[i], &p);
            daqp_problem(&v[i], &c);
            /* alternate the two solvers so that a change of the machine's load hits both */
            for (r = 0; r < reps; ++r) {
                double t0 = cpu_ns();
                st = (int)ogk_qp_solve(&ws, &p, &sol);
                double t1 = cpu_ns();
                ef = daqp_run(&c, &fd);
                double t2 = cpu_ns();
                to[r] = t1 - t0;
                td[r] = t2 - t1;
            }
            printf("%zu %d %d %d %d %.1f %.1f %.17g %.17g %d\n", i, v[i].n, v[i].m_eq, v[i].m_in, st,
                   median(to, reps), median(td, reps), sol.objective, objective(&v[i], c.x), ef);
            free(c.A); free(c.bu); free(c.bl); free(c.x); free(c.lam); free(c.sense);
        }
    }
    return 0;
}
