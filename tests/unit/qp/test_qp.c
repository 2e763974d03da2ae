/* test_qp.c -- unit tests of kernel/src/qp/qp.c (ogk_qp_solve, Goldfarb-Idnani).
 *
 * Truths used, none of them the solver itself:
 *   - every bad-input code of ogk/qp.h, with x and the multipliers zeroed;
 *   - unconstrained and equality-only QPs against their linear KKT systems
 *     solved here by Gaussian elimination with partial pivoting;
 *   - Nocedal & Wright's example 16.4 worked by hand (comment at the test);
 *   - random feasible QPs (fixed-seed LCG): the KKT conditions of the returned
 *     (x, y, z), and for n <= 6 the optimum of a brute-force solver that
 *     enumerates every subset of active inequalities/bounds (KKT solve of each
 *     subset, feasible with non-negative multipliers, least objective);
 *   - degenerate cases (redundant constraints active at the optimum, dependent
 *     consistent and inconsistent equality rows, a fixed variable).
 * Large structs are static (Cortex-M7 target stack).
 *
 * Both precisions (ogk_test.h): the problems are ogk_real_t, the reference
 * solvers (Gaussian elimination, the brute force, the objective) work in
 * double on the same data. Float tolerances of the hand-worked cases are
 * the double ones' multiples of the unit round-off (1e-15 is 4.5 eps, 1e-14
 * 45); those of the random problems ten times the worst measured (make
 * unit-errors). Row scalings and overflows at float's magnitudes. */
#include "ogk_test.h"

#include <float.h>
#include <stdbool.h>
#include <string.h>

#include "ogk/qp.h"

static ogk_qp_workspace_t ws;
static ogk_qp_solution_t sol;

/* Float tolerances of the random problems (H = M M^T + 0.1 I: condition up to
 * about 1e3), relative to the data and solution sizes as the double ones are:
 * ten times the worst measured on host and M4F (make unit-errors). */
#define QP_KKT_TOL_F 1e-5      /* KKT residuals; measured worst 1.5e-6 on M4F and host (primal feasibility) */
#define QP_SOL_TOL_F 5e-5      /* x, y against the KKT / brute-force references; measured worst 9.8e-6 on M4F and host */

/* ------------------------------------------------------------------ helpers */

/* Knuth MMIX LCG; the top 53 bits give a uniform double in [-1, 1). */
static double lcg_uniform(uint64_t *state)
{
    *state = *state * 6364136223846793005ull + 1442695040888963407ull;
    return (double)(*state >> 11) * (2.0 / 9007199254740992.0) - 1.0;
}

/* Uniform integer in [0, k). */
static size_t lcg_int(uint64_t *state, size_t k)
{
    const double u = 0.5 * (lcg_uniform(state) + 1.0);
    size_t v = (size_t)(u * (double)k);
    return (v >= k) ? k - 1u : v;
}

/* Solves the dim x dim system M y = rhs in place (M destroyed, y = rhs on
 * return) by Gaussian elimination with partial pivoting. false when a pivot is
 * below 1e-11 times the largest entry of M (singular for our purposes). */
#define GE_MAX 40
static bool ge_solve(double *M, double *rhs, size_t dim)
{
    double scale = 0.0;
    size_t c, i, k;
    for (i = 0; i < dim * dim; ++i) {
        scale = fmax(scale, fabs(M[i]));
    }
    for (c = 0; c < dim; ++c) {
        size_t piv = c;
        for (i = c + 1; i < dim; ++i) {
            if (fabs(M[i * dim + c]) > fabs(M[piv * dim + c])) {
                piv = i;
            }
        }
        if (!(fabs(M[piv * dim + c]) > 1e-11 * scale)) {
            return false;
        }
        if (piv != c) {
            double t;
            for (k = 0; k < dim; ++k) {
                t = M[c * dim + k];
                M[c * dim + k] = M[piv * dim + k];
                M[piv * dim + k] = t;
            }
            t = rhs[c];
            rhs[c] = rhs[piv];
            rhs[piv] = t;
        }
        for (i = c + 1; i < dim; ++i) {
            const double f = M[i * dim + c] / M[c * dim + c];
            if (f != 0.0) {
                for (k = c; k < dim; ++k) {
                    M[i * dim + k] -= f * M[c * dim + k];
                }
                rhs[i] -= f * rhs[c];
            }
        }
    }
    for (i = dim; i-- > 0;) {
        double s = rhs[i];
        for (k = i + 1; k < dim; ++k) {
            s -= M[i * dim + k] * rhs[k];
        }
        rhs[i] = s / M[i * dim + i];
    }
    return true;
}

/* A problem with its own storage (sizes of the random tests). */
#define TP_N 48
#define TP_EQ 4
#define TP_IN 16
typedef struct {
    size_t n, m_eq, m_in;
    ogk_real_t H[TP_N * TP_N];
    ogk_real_t g[TP_N];
    ogk_real_t A_eq[TP_EQ * TP_N];
    ogk_real_t b_eq[TP_EQ];
    ogk_real_t A_in[TP_IN * TP_N];
    ogk_real_t b_in[TP_IN];
    ogk_real_t lb[TP_N];
    ogk_real_t ub[TP_N];
    bool bounds;
} test_problem_t;

static test_problem_t tp;

static ogk_qp_problem_t view(const test_problem_t *t)
{
    ogk_qp_problem_t p;
    p.n = t->n;
    p.m_eq = t->m_eq;
    p.m_in = t->m_in;
    p.H = t->H;
    p.g = t->g;
    p.A_eq = (t->m_eq > 0) ? t->A_eq : NULL;
    p.b_eq = (t->m_eq > 0) ? t->b_eq : NULL;
    p.A_in = (t->m_in > 0) ? t->A_in : NULL;
    p.b_in = (t->m_in > 0) ? t->b_in : NULL;
    p.lb = t->bounds ? t->lb : NULL;
    p.ub = t->bounds ? t->ub : NULL;
    return p;
}

/* max_i |v[i]| of a double reference array (ogk_test_max_abs reads the kernel's ogk_real_t). */
static double max_abs_d(const double *v, size_t count)
{
    double m = 0.0;
    size_t i;
    for (i = 0; i < count; ++i) {
        m = fmax(m, fabs(v[i]));
    }
    return m;
}

static double objective(const test_problem_t *t, const double *x)
{
    double f = 0.0;
    size_t i, k;
    for (i = 0; i < t->n; ++i) {
        double hx = 0.0;
        for (k = 0; k < t->n; ++k) {
            hx += t->H[i * t->n + k] * x[k];
        }
        f += 0.5 * x[i] * hx + t->g[i] * x[i];
    }
    return f;
}

/* A value of the constraint data: itself in the double build; in the float
 * build the nearest multiple of 2^-8, so that every b = A x0 - slack is exact
 * in float (products of 17 bits, sums of at most 48 of them below 2^6: 23
 * bits) and the vertices made degenerate on purpose (slack 0, bounds at x0)
 * stay so: rounding independent floats would leave some of these problems
 * infeasible by 1e-7 (measured: 3 of the 300 of test_random_vs_brute_force,
 * infeasible to the double kernel too). */
static double q_data(double v)
{
#if OGK_REAL_SINGLE
    return floor((v * 256.0) + 0.5) / 256.0;
#else
    return v;
#endif
}

/* Random feasible problem: H = M M^T + 0.1 I, A random, b built from a known
 * point x0 (equalities exact, inequalities with slack in [0, 1) and exactly 0
 * for about one row in four), bounds on about `bound_share` of the variables
 * (lower, upper or both, x0 inside, some at x0 exactly). */
static void random_problem(test_problem_t *t, uint64_t *s, size_t n, size_t m_eq, size_t m_in,
                           double bound_share)
{
    double M[TP_N * TP_N];
    double x0[TP_N];
    size_t i, j, k;
    memset(t, 0, sizeof(*t));
    t->n = n;
    t->m_eq = m_eq;
    t->m_in = m_in;
    for (i = 0; i < n * n; ++i) {
        M[i] = lcg_uniform(s);
    }
    for (i = 0; i < n; ++i) {
        for (j = 0; j <= i; ++j) {
            double v = (i == j) ? 0.1 : 0.0;
            for (k = 0; k < n; ++k) {
                v += M[i * n + k] * M[j * n + k];
            }
            t->H[i * n + j] = v;
            t->H[j * n + i] = v;
        }
        t->g[i] = 3.0 * lcg_uniform(s);
        x0[i] = q_data(lcg_uniform(s));
    }
    for (i = 0; i < m_eq; ++i) {
        double b = 0.0;
        for (k = 0; k < n; ++k) {
            t->A_eq[i * n + k] = q_data(lcg_uniform(s));
            b += t->A_eq[i * n + k] * x0[k];
        }
        t->b_eq[i] = b;
    }
    for (i = 0; i < m_in; ++i) {
        double b = 0.0;
        const double slack = (lcg_int(s, 4) == 0) ? 0.0 : q_data(0.5 * (lcg_uniform(s) + 1.0));
        for (k = 0; k < n; ++k) {
            t->A_in[i * n + k] = q_data(lcg_uniform(s));
            b += t->A_in[i * n + k] * x0[k];
        }
        t->b_in[i] = b - slack;
    }
    t->bounds = bound_share > 0.0;
    for (i = 0; i < n; ++i) {
        t->lb[i] = -OGK_QP_INF;
        t->ub[i] = OGK_QP_INF;
        if (0.5 * (lcg_uniform(s) + 1.0) < bound_share) {
            const size_t kind = lcg_int(s, 3);
            const double w = (lcg_int(s, 5) == 0) ? 0.0 : q_data(0.3 * (lcg_uniform(s) + 1.0));
            if (kind != 1) {
                t->lb[i] = x0[i] - w;
            }
            if (kind != 0) {
                t->ub[i] = x0[i] + q_data(0.3 * (lcg_uniform(s) + 1.0));
            }
        }
    }
}

/* Checks the KKT conditions of sol for problem t with tolerance tol (relative
 * to the size of the data and of the solution). */
static void check_kkt(const test_problem_t *t, const ogk_qp_solution_t *s, double tol)
{
    const size_t n = t->n;
    const double xs = fmax(1.0, ogk_test_max_abs(s->x, n));
    const double ys = fmax(1.0, fmax(ogk_test_max_abs(s->y_eq, t->m_eq), ogk_test_max_abs(s->y_in, t->m_in)));
    const double zs = fmax(ogk_test_max_abs(s->z_lb, n), ogk_test_max_abs(s->z_ub, n));
    const double hs = fmax(1.0, ogk_test_max_abs(t->H, n * n));
    const double mult = fmax(ys, zs);
    size_t i, k;
    /* stationarity: H x + g - A_eq^T y_eq - A_in^T y_in - z_lb + z_ub = 0 */
    for (i = 0; i < n; ++i) {
        double r = t->g[i] - s->z_lb[i] + s->z_ub[i];
        for (k = 0; k < n; ++k) {
            r += t->H[i * n + k] * s->x[k];
        }
        for (k = 0; k < t->m_eq; ++k) {
            r -= t->A_eq[k * n + i] * s->y_eq[k];
        }
        for (k = 0; k < t->m_in; ++k) {
            r -= t->A_in[k * n + i] * s->y_in[k];
        }
        OGK_ASSERT_NEAR(r, 0.0, tol * (hs * xs + mult + fmax(1.0, ogk_test_max_abs(t->g, n))));
    }
    /* primal feasibility */
    for (k = 0; k < t->m_eq; ++k) {
        double a = 0.0;
        for (i = 0; i < n; ++i) {
            a += t->A_eq[k * n + i] * s->x[i];
        }
        OGK_ASSERT_NEAR(a, t->b_eq[k], tol * xs * 4.0);
    }
    for (k = 0; k < t->m_in; ++k) {
        double a = 0.0;
        for (i = 0; i < n; ++i) {
            a += t->A_in[k * n + i] * s->x[i];
        }
        assert_true(a - t->b_in[k] >= -tol * xs * 4.0);
        /* dual sign, complementarity */
        assert_true(s->y_in[k] >= 0.0);
        OGK_ASSERT_NEAR(s->y_in[k] * (a - t->b_in[k]), 0.0, tol * mult * xs * 4.0);
    }
    for (i = 0; i < n; ++i) {
        assert_true(s->z_lb[i] >= 0.0);
        assert_true(s->z_ub[i] >= 0.0);
        if (t->bounds) {
            if (t->lb[i] > -OGK_QP_INF) {
                assert_true(s->x[i] - t->lb[i] >= -tol * xs);
                OGK_ASSERT_NEAR(s->z_lb[i] * (s->x[i] - t->lb[i]), 0.0, tol * mult * xs);
            } else {
                assert_true(s->z_lb[i] == 0.0);
            }
            if (t->ub[i] < OGK_QP_INF) {
                assert_true(t->ub[i] - s->x[i] >= -tol * xs);
                OGK_ASSERT_NEAR(s->z_ub[i] * (t->ub[i] - s->x[i]), 0.0, tol * mult * xs);
            } else {
                assert_true(s->z_ub[i] == 0.0);
            }
        } else {
            assert_true(s->z_lb[i] == 0.0);
            assert_true(s->z_ub[i] == 0.0);
        }
    }
    {
        double xd[TP_N];
        for (i = 0; i < n; ++i) {
            xd[i] = s->x[i];
        }
        OGK_ASSERT_REL(s->objective, objective(t, xd), OGK_TEST_TOL(1e-12, tol), 1.0);
    }
}

/* ------------------------------------------------------------------ brute force */

/* Constraint list of the brute-force solver: normal . x >= rhs (= for equalities). */
#define BF_MAX_N 6
#define BF_MAX_C 20
typedef struct {
    size_t count, n_eq;
    double normal[BF_MAX_C][BF_MAX_N];
    double rhs[BF_MAX_C];
} bf_constraints_t;

static void bf_list(const test_problem_t *t, bf_constraints_t *c)
{
    size_t i, k;
    memset(c, 0, sizeof(*c));
    for (k = 0; k < t->m_eq; ++k, ++c->count) {
        for (i = 0; i < t->n; ++i) {
            c->normal[c->count][i] = t->A_eq[k * t->n + i];
        }
        c->rhs[c->count] = t->b_eq[k];
    }
    c->n_eq = c->count;
    for (k = 0; k < t->m_in; ++k, ++c->count) {
        for (i = 0; i < t->n; ++i) {
            c->normal[c->count][i] = t->A_in[k * t->n + i];
        }
        c->rhs[c->count] = t->b_in[k];
    }
    for (i = 0; t->bounds && i < t->n; ++i) {
        if (t->lb[i] > -OGK_QP_INF) {
            c->normal[c->count][i] = 1.0;
            c->rhs[c->count++] = t->lb[i];
        }
        if (t->ub[i] < OGK_QP_INF) {
            c->normal[c->count][i] = -1.0;
            c->rhs[c->count++] = -t->ub[i];
        }
    }
}

/* Minimiser by enumeration of the active inequality subsets; false when no
 * subset gives a feasible point with non-negative multipliers. */
static bool brute_force(const test_problem_t *t, double *x_best, double *f_best)
{
    static bf_constraints_t c;
    const size_t n = t->n;
    size_t n_ineq;
    unsigned long mask;
    bool found = false;
    bf_list(t, &c);
    n_ineq = c.count - c.n_eq;
    assert_true(c.count <= BF_MAX_C && n <= BF_MAX_N);
    for (mask = 0; mask < (1ul << n_ineq); ++mask) {
        double M[GE_MAX * GE_MAX];
        double y[GE_MAX];
        size_t act[BF_MAX_C];
        size_t na = 0, dim, i, k, j;
        bool ok = true;
        for (k = 0; k < c.n_eq; ++k) {
            act[na++] = k;
        }
        for (k = 0; k < n_ineq; ++k) {
            if (mask & (1ul << k)) {
                act[na++] = c.n_eq + k;
            }
        }
        if (na > n) {
            continue;
        }
        /* [H  -C^T] [x]   [-g]
         * [C   0  ] [l] = [ b] */
        dim = n + na;
        memset(M, 0, sizeof(M));
        for (i = 0; i < n; ++i) {
            for (k = 0; k < n; ++k) {
                M[i * dim + k] = t->H[i * n + k];
            }
            for (j = 0; j < na; ++j) {
                M[i * dim + n + j] = -c.normal[act[j]][i];
                M[(n + j) * dim + i] = c.normal[act[j]][i];
            }
            y[i] = -t->g[i];
        }
        for (j = 0; j < na; ++j) {
            y[n + j] = c.rhs[act[j]];
        }
        if (!ge_solve(M, y, dim)) {
            continue; /* dependent active normals: another subset covers it */
        }
        for (j = 0; j < na && ok; ++j) {
            /* float data: the constraints through x0, rounded to float one by one,
             * agree only to the KKT tolerance (so does the kernel's answer) */
            if (act[j] >= c.n_eq && y[n + j] < -OGK_TEST_TOL(1e-9, QP_KKT_TOL_F)) {
                ok = false;
            }
        }
        for (k = c.n_eq; k < c.count && ok; ++k) {
            double a = 0.0;
            for (i = 0; i < n; ++i) {
                a += c.normal[k][i] * y[i];
            }
            if (a - c.rhs[k] < -OGK_TEST_TOL(1e-9, QP_KKT_TOL_F) * fmax(1.0, fabs(c.rhs[k]))) {
                ok = false;
            }
        }
        if (ok) {
            const double f = objective(t, y);
            if (!found || f < *f_best) {
                found = true;
                *f_best = f;
                memcpy(x_best, y, n * sizeof(double));
            }
        }
    }
    return found;
}

/* ------------------------------------------------------------------ bad input */

static void assert_zeroed(void)
{
    size_t i;
    for (i = 0; i < OGK_QP_MAX_N; ++i) {
        assert_true(sol.x[i] == 0.0 && sol.z_lb[i] == 0.0 && sol.z_ub[i] == 0.0);
    }
    for (i = 0; i < OGK_QP_MAX_EQ; ++i) {
        assert_true(sol.y_eq[i] == 0.0);
    }
    for (i = 0; i < OGK_QP_MAX_IN; ++i) {
        assert_true(sol.y_in[i] == 0.0);
    }
    assert_true(sol.objective == 0.0);
}

/* Solve expecting `code`, with the solution pre-filled with garbage. */
static void expect_status(const ogk_qp_problem_t *p, ogk_status code)
{
    memset(&sol, 0x5a, sizeof(sol));
    OGK_ASSERT_STATUS(ogk_qp_solve(&ws, p, &sol), code);
    if (code != OGK_OK) {
        assert_zeroed();
    }
}

/* 2 variables, H = diag(2, 2), g = (-2, -5): the Nocedal & Wright problem. */
static const ogk_real_t H2[4] = {2.0, 0.0, 0.0, 2.0};
static const ogk_real_t g2[2] = {-2.0, -5.0};

static ogk_qp_problem_t small_problem(void)
{
    ogk_qp_problem_t p;
    memset(&p, 0, sizeof(p));
    p.n = 2;
    p.H = H2;
    p.g = g2;
    return p;
}

/* req: OGK-CORE-018 */
static void test_null_and_dims(void **state)
{
    ogk_qp_problem_t p = small_problem();
    static const ogk_real_t a[2] = {1.0, 1.0};
    static const ogk_real_t b[1] = {1.0};
    (void)state;
    OGK_ASSERT_STATUS(ogk_qp_solve(NULL, &p, &sol), OGK_E_NULL);
    OGK_ASSERT_STATUS(ogk_qp_solve(&ws, NULL, &sol), OGK_E_NULL);
    OGK_ASSERT_STATUS(ogk_qp_solve(&ws, &p, NULL), OGK_E_NULL);
    p.H = NULL;
    expect_status(&p, OGK_E_NULL);
    p = small_problem();
    p.g = NULL;
    expect_status(&p, OGK_E_NULL);
    p = small_problem();
    p.m_eq = 1; /* A_eq, b_eq NULL */
    expect_status(&p, OGK_E_NULL);
    p.A_eq = a;
    expect_status(&p, OGK_E_NULL);
    p = small_problem();
    p.m_in = 1;
    p.b_in = b;
    expect_status(&p, OGK_E_NULL);
    p = small_problem();
    p.n = 0;
    expect_status(&p, OGK_E_DIM);
    p.n = OGK_QP_MAX_N + 1u;
    expect_status(&p, OGK_E_DIM);
    p = small_problem();
    p.m_eq = 3; /* > n */
    p.A_eq = a;
    p.b_eq = b;
    expect_status(&p, OGK_E_DIM);
    p.m_eq = OGK_QP_MAX_EQ + 1u;
    expect_status(&p, OGK_E_DIM);
    p = small_problem();
    p.m_in = OGK_QP_MAX_IN + 1u;
    p.A_in = a;
    p.b_in = b;
    expect_status(&p, OGK_E_DIM);
    /* and the workspace still works */
    p = small_problem();
    expect_status(&p, OGK_OK);
    OGK_ASSERT_NEAR(sol.x[0], 1.0, OGK_TEST_TOL(1e-15, 4.5 * FLT_EPSILON));
    OGK_ASSERT_NEAR(sol.x[1], 2.5, OGK_TEST_TOL(1e-15, 4.5 * FLT_EPSILON));
}

/* req: OGK-CORE-018 */
static void test_nonfinite_and_range(void **state)
{
    ogk_qp_problem_t p = small_problem();
    ogk_real_t H[4] = {2.0, 0.0, 0.0, 2.0};
    ogk_real_t g[2] = {-2.0, -5.0};
    ogk_real_t a[2] = {1.0, 1.0};
    ogk_real_t b[1] = {1.0};
    ogk_real_t lb[2] = {0.0, -INFINITY};
    ogk_real_t ub[2] = {1.0, INFINITY};
    (void)state;
    p.H = H;
    p.g = g;
    H[1] = NAN;
    expect_status(&p, OGK_E_NONFINITE);
    H[1] = 0.0;
    H[3] = INFINITY;
    expect_status(&p, OGK_E_NONFINITE);
    H[3] = 2.0;
    g[1] = NAN;
    expect_status(&p, OGK_E_NONFINITE);
    g[1] = -5.0;
    p.m_eq = 1;
    p.A_eq = a;
    p.b_eq = b;
    a[1] = NAN;
    expect_status(&p, OGK_E_NONFINITE);
    a[1] = 1.0;
    b[0] = -INFINITY;
    expect_status(&p, OGK_E_NONFINITE);
    b[0] = 1.0;
    p.m_eq = 0;
    p.m_in = 1;
    p.A_in = a;
    p.b_in = b;
    a[0] = INFINITY;
    expect_status(&p, OGK_E_NONFINITE);
    a[0] = 1.0;
    b[0] = NAN;
    expect_status(&p, OGK_E_NONFINITE);
    b[0] = 1.0;
    p.m_in = 0;
    /* bounds: infinities mean "no bound", NaN is rejected, lb > ub too */
    p.lb = lb;
    p.ub = ub;
    expect_status(&p, OGK_OK);
    OGK_ASSERT_NEAR(sol.x[0], 1.0, OGK_TEST_TOL(1e-15, 4.5 * FLT_EPSILON));
    OGK_ASSERT_NEAR(sol.x[1], 2.5, OGK_TEST_TOL(1e-15, 4.5 * FLT_EPSILON));
    lb[1] = NAN;
    expect_status(&p, OGK_E_NONFINITE);
    lb[1] = -INFINITY;
    ub[0] = NAN;
    expect_status(&p, OGK_E_NONFINITE);
    ub[0] = -0.5;
    expect_status(&p, OGK_E_RANGE);
    ub[0] = 0.0; /* lb == ub: a fixed variable */
    expect_status(&p, OGK_OK);
    OGK_ASSERT_NEAR(sol.x[0], 0.0, OGK_TEST_TOL(1e-15, 4.5 * FLT_EPSILON));
    OGK_ASSERT_NEAR(sol.x[1], 2.5, OGK_TEST_TOL(1e-15, 4.5 * FLT_EPSILON));
    /* stationarity in x0: 2*0 - 2 = z_lb - z_ub, so z_ub = 2 */
    OGK_ASSERT_NEAR(sol.z_ub[0] - sol.z_lb[0], 2.0, OGK_TEST_TOL(1e-14, 45.0 * FLT_EPSILON));
}

/* req: OGK-CORE-018 */
static void test_not_posdef(void **state)
{
    ogk_qp_problem_t p = small_problem();
    const ogk_real_t indefinite[4] = {1.0, 2.0, 2.0, 1.0};
    const ogk_real_t semidefinite[4] = {1.0, 1.0, 1.0, 1.0};
    const ogk_real_t negative_diag[4] = {-1.0, 0.0, 0.0, 1.0};
    const ogk_real_t unsymmetric[4] = {2.0, 1.0, 0.0, 2.0};
    const ogk_real_t tiny_asym[4] = {2.0, 1.0, 1.0 + 1e-14, 2.0};
    /* pivots 2^-46 ~ 1.4e-14 and 2^-33 ~ 1.2e-10 relative to H_22 = 1 (exact
     * in binary): below and above OGK_QP_PIVOT_TOL = 1e-12. Float: OGK_QP_PIVOT_TOL
     * is 64 eps = 2^-17 ~ 7.6e-6 (ogk/qp.h), and the pivots are 2^-20 ~ 9.5e-7 and
     * 2^-14 ~ 6.1e-5, below and above it (exact in float too). */
    const ogk_real_t near_singular[4] = {1.0, 1.0, 1.0, 1.0 + OGK_TEST_PICK(0x1p-46, 0x1p-20)};
    const ogk_real_t barely_pd[4] = {1.0, 1.0, 1.0, 1.0 + OGK_TEST_PICK(0x1p-33, 0x1p-14)};
    (void)state;
    p.H = indefinite;
    expect_status(&p, OGK_E_NOT_POSDEF);
    p.H = semidefinite;
    expect_status(&p, OGK_E_NOT_POSDEF);
    p.H = negative_diag;
    expect_status(&p, OGK_E_NOT_POSDEF);
    p.H = unsymmetric;
    expect_status(&p, OGK_E_NOT_POSDEF);
    p.H = tiny_asym; /* within OGK_QP_SYM_TOL: accepted */
    expect_status(&p, OGK_OK);
    p.H = near_singular;
    expect_status(&p, OGK_E_NOT_POSDEF);
    p.H = barely_pd;
    expect_status(&p, OGK_OK);
}

/* Infeasible: x1 + x2 = 5 with 0 <= x <= 2; x1 >= 1 with x1 <= 0 (rows);
 * inconsistent dependent equality rows. */
/* req: OGK-CORE-018 */
static void test_infeasible(void **state)
{
    ogk_qp_problem_t p = small_problem();
    const ogk_real_t a_eq[2] = {1.0, 1.0};
    const ogk_real_t b_eq[1] = {5.0};
    const ogk_real_t lb[2] = {0.0, 0.0};
    const ogk_real_t ub[2] = {2.0, 2.0};
    const ogk_real_t a_in[4] = {1.0, 0.0, -1.0, 0.0};
    const ogk_real_t b_in[2] = {1.0, 0.0};
    const ogk_real_t a_eq2[4] = {1.0, 1.0, 2.0, 2.0};
    const ogk_real_t b_eq2[2] = {1.0, 3.0};
    const ogk_real_t a_in3[6] = {1.0, 1.0, 1.0, -3.0, -3.0, -3.0};
    const ogk_real_t b_in3[2] = {1.0, 0.0};
    (void)state;
    p.m_eq = 1;
    p.A_eq = a_eq;
    p.b_eq = b_eq;
    p.lb = lb;
    p.ub = ub;
    expect_status(&p, OGK_E_INFEASIBLE);
    p = small_problem();
    p.m_in = 2;
    p.A_in = a_in;
    p.b_in = b_in;
    expect_status(&p, OGK_E_INFEASIBLE);
    p = small_problem();
    p.m_eq = 2;
    p.A_eq = a_eq2;
    p.b_eq = b_eq2;
    expect_status(&p, OGK_E_INFEASIBLE);
    /* 3 variables: x1 + x2 + x3 >= 1 and x1 + x2 + x3 <= 0 (scaled differently),
     * with H = I: the second row can only be added by dropping the first. */
    {
        static const ogk_real_t H3[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};
        static const ogk_real_t g3[3] = {0.5, -0.2, 0.1};
        p = small_problem();
        p.n = 3;
        p.H = H3;
        p.g = g3;
        p.m_in = 2;
        p.A_in = a_in3;
        p.b_in = b_in3;
        expect_status(&p, OGK_E_INFEASIBLE);
    }
    /* and a feasible problem afterwards solves normally */
    p = small_problem();
    expect_status(&p, OGK_OK);
    OGK_ASSERT_NEAR(sol.x[1], 2.5, OGK_TEST_TOL(1e-15, 4.5 * FLT_EPSILON));
}

/* ------------------------------------------------------------------ closed forms */

/* req: OGK-CORE-018 */
static void test_unconstrained(void **state)
{
    uint64_t s = 11u;
    size_t n, i, k;
    (void)state;
    for (n = 1; n <= 30; n += 7) {
        double M[GE_MAX * GE_MAX];
        double y[GE_MAX];
        ogk_qp_problem_t p;
        random_problem(&tp, &s, n, 0, 0, 0.0);
        p = view(&tp);
        expect_status(&p, OGK_OK);
        for (i = 0; i < n; ++i) {
            for (k = 0; k < n; ++k) {
                M[i * n + k] = tp.H[i * n + k];
            }
            y[i] = -tp.g[i];
        }
        assert_true(ge_solve(M, y, n));
        for (i = 0; i < n; ++i) {
            OGK_ASSERT_NEAR(sol.x[i], y[i], OGK_TEST_TOL(1e-9, QP_SOL_TOL_F) * fmax(1.0, max_abs_d(y, n)));
        }
        assert_int_equal((int)sol.n_active, 0);
        assert_int_equal((int)sol.iterations, 0);
        OGK_ASSERT_REL(sol.objective, objective(&tp, y), OGK_TEST_TOL(1e-11, QP_SOL_TOL_F), 1.0);
    }
}

/* Equality-only QP: [H -A^T; A 0] [x; y] = [-g; b]. */
/* req: OGK-CORE-018 */
static void test_equality_only(void **state)
{
    uint64_t s = 12u;
    size_t n, i, k;
    (void)state;
    for (n = 4; n <= 32; n += 7) {
        const size_t me = (n < 8) ? 2 : 4;
        const size_t dim = n + me;
        double M[GE_MAX * GE_MAX];
        double y[GE_MAX];
        ogk_qp_problem_t p;
        random_problem(&tp, &s, n, me, 0, 0.0);
        p = view(&tp);
        expect_status(&p, OGK_OK);
        memset(M, 0, sizeof(M));
        for (i = 0; i < n; ++i) {
            for (k = 0; k < n; ++k) {
                M[i * dim + k] = tp.H[i * n + k];
            }
            for (k = 0; k < me; ++k) {
                M[i * dim + n + k] = -tp.A_eq[k * n + i];
                M[(n + k) * dim + i] = tp.A_eq[k * n + i];
            }
            y[i] = -tp.g[i];
        }
        for (k = 0; k < me; ++k) {
            y[n + k] = tp.b_eq[k];
        }
        assert_true(ge_solve(M, y, dim));
        for (i = 0; i < n; ++i) {
            OGK_ASSERT_NEAR(sol.x[i], y[i], OGK_TEST_TOL(1e-9, QP_SOL_TOL_F) * fmax(1.0, max_abs_d(y, n)));
        }
        for (k = 0; k < me; ++k) {
            OGK_ASSERT_NEAR(sol.y_eq[k], y[n + k], OGK_TEST_TOL(1e-8, QP_SOL_TOL_F) * fmax(1.0, max_abs_d(&y[n], me)));
        }
        assert_int_equal((int)sol.n_active, (int)me);
        assert_int_equal((int)sol.iterations, (int)me);
        check_kkt(&tp, &sol, OGK_TEST_TOL(1e-11, QP_KKT_TOL_F));
    }
}

/* Nocedal & Wright, Numerical Optimization (2nd ed.), example 16.4:
 *   min (x1 - 1)^2 + (x2 - 2.5)^2  = 1/2 x^T diag(2, 2) x + (-2, -5) x + 7.25
 *   s.t. c1:  x1 - 2 x2 + 2 >= 0     c2: -x1 - 2 x2 + 6 >= 0
 *        c3: -x1 + 2 x2 + 2 >= 0     x1 >= 0, x2 >= 0.
 * The unconstrained minimiser (1, 2.5) violates only c1 (1 - 5 + 2 = -2).
 * With c1 active: x = (1, 2.5) + t (1, -2) / 2 ... by hand: minimise over the
 * line x1 = 2 x2 - 2: d/dx2 [(2 x2 - 3)^2 + (x2 - 2.5)^2] = 0 gives
 * 4 (2 x2 - 3) + 2 (x2 - 2.5) = 0, x2 = 1.7, x1 = 1.4. Stationarity
 * (2.8 - 2, 3.4 - 5) = (0.8, -1.6) = y1 (1, -2): y1 = 0.8 >= 0.
 * c2 = -1.4 - 3.4 + 6 = 1.2 > 0, c3 = -1.4 + 3.4 + 2 = 4 > 0, bounds inactive.
 * Objective 1/2 x^T H x + g^T x = 1.96 + 2.89 - 2.8 - 8.5 = -6.45. */
static const ogk_real_t nw_A[6] = {1.0, -2.0, -1.0, -2.0, -1.0, 2.0};
static const ogk_real_t nw_b[3] = {-2.0, -6.0, -2.0};
static const ogk_real_t nw_lb[2] = {0.0, 0.0};
static const ogk_real_t nw_ub[2] = {OGK_QP_INF, OGK_QP_INF};

/* req: OGK-CORE-018 */
static void test_hand_example(void **state)
{
    ogk_qp_problem_t p = small_problem();
    (void)state;
    p.m_in = 3;
    p.A_in = nw_A;
    p.b_in = nw_b;
    p.lb = nw_lb;
    p.ub = nw_ub;
    expect_status(&p, OGK_OK);
    OGK_ASSERT_NEAR(sol.x[0], 1.4, OGK_TEST_TOL(1e-14, 45.0 * FLT_EPSILON));
    OGK_ASSERT_NEAR(sol.x[1], 1.7, OGK_TEST_TOL(1e-14, 45.0 * FLT_EPSILON));
    OGK_ASSERT_NEAR(sol.y_in[0], 0.8, OGK_TEST_TOL(1e-14, 45.0 * FLT_EPSILON));
    assert_true(sol.y_in[1] == 0.0 && sol.y_in[2] == 0.0);
    assert_true(sol.z_lb[0] == 0.0 && sol.z_lb[1] == 0.0);
    OGK_ASSERT_NEAR(sol.objective, -6.45, OGK_TEST_TOL(1e-14, 45.0 * FLT_EPSILON));
    assert_int_equal((int)sol.n_active, 1);
    assert_int_equal((int)sol.iterations, 1);
    /* the same workspace again: bit-identical */
    {
        ogk_qp_solution_t first = sol;
        expect_status(&p, OGK_OK);
        assert_true(memcmp(&first, &sol, sizeof(sol)) == 0);
    }
}

/* Degenerate: c1 duplicated as 2 x1 - 4 x2 + 4 >= 0 (both active at the
 * optimum, multipliers not unique: y1 + 2 y1' = 0.8); and H = I, g = 0 with
 * x >= 1 (bounds) and x1 + x2 >= 2: optimum (1, 1) with all three active in
 * exact arithmetic, the row redundant. */
/* req: OGK-CORE-018 */
static void test_degenerate(void **state)
{
    ogk_qp_problem_t p = small_problem();
    static const ogk_real_t A4[8] = {1.0, -2.0, -1.0, -2.0, -1.0, 2.0, 2.0, -4.0};
    static const ogk_real_t b4[4] = {-2.0, -6.0, -2.0, -4.0};
    static const ogk_real_t I2[4] = {1.0, 0.0, 0.0, 1.0};
    static const ogk_real_t zero2[2] = {0.0, 0.0};
    static const ogk_real_t one2[2] = {1.0, 1.0};
    static const ogk_real_t inf2[2] = {OGK_QP_INF, OGK_QP_INF};
    static const ogk_real_t row[2] = {1.0, 1.0};
    static const ogk_real_t two[1] = {2.0};
    (void)state;
    p.m_in = 4;
    p.A_in = A4;
    p.b_in = b4;
    expect_status(&p, OGK_OK);
    OGK_ASSERT_NEAR(sol.x[0], 1.4, OGK_TEST_TOL(1e-14, 45.0 * FLT_EPSILON));
    OGK_ASSERT_NEAR(sol.x[1], 1.7, OGK_TEST_TOL(1e-14, 45.0 * FLT_EPSILON));
    OGK_ASSERT_NEAR(sol.y_in[0] + 2.0 * sol.y_in[3], 0.8, OGK_TEST_TOL(1e-14, 45.0 * FLT_EPSILON));
    assert_true(sol.y_in[0] >= 0.0 && sol.y_in[3] >= 0.0);
    OGK_ASSERT_NEAR(sol.objective, -6.45, OGK_TEST_TOL(1e-14, 45.0 * FLT_EPSILON));

    p = small_problem();
    p.H = I2;
    p.g = zero2;
    p.m_in = 1;
    p.A_in = row;
    p.b_in = two;
    p.lb = one2;
    p.ub = inf2;
    expect_status(&p, OGK_OK);
    OGK_ASSERT_NEAR(sol.x[0], 1.0, OGK_TEST_TOL(1e-15, 4.5 * FLT_EPSILON));
    OGK_ASSERT_NEAR(sol.x[1], 1.0, OGK_TEST_TOL(1e-15, 4.5 * FLT_EPSILON));
    /* x = y_in (1, 1) + z_lb */
    OGK_ASSERT_NEAR(sol.y_in[0] + sol.z_lb[0], 1.0, OGK_TEST_TOL(1e-15, 4.5 * FLT_EPSILON));
    OGK_ASSERT_NEAR(sol.y_in[0] + sol.z_lb[1], 1.0, OGK_TEST_TOL(1e-15, 4.5 * FLT_EPSILON));
    OGK_ASSERT_NEAR(sol.objective, 1.0, OGK_TEST_TOL(1e-15, 4.5 * FLT_EPSILON));
    /* the most violated constraint first (violation / row norm): the row
     * (-2 / sqrt 2) before the bounds (-1 each), one step to (1, 1) */
    assert_int_equal((int)sol.iterations, 1);
    assert_int_equal((int)sol.n_active, 1);
    OGK_ASSERT_NEAR(sol.y_in[0], 1.0, OGK_TEST_TOL(1e-15, 4.5 * FLT_EPSILON));
}

/* Dependent equality rows: consistent ones solve (the dependent row is
 * skipped, its multiplier 0), inconsistent ones are OGK_E_INFEASIBLE
 * (test_infeasible). */
/* req: OGK-CORE-018 */
static void test_dependent_equalities(void **state)
{
    ogk_qp_problem_t p = small_problem();
    static const ogk_real_t A[4] = {1.0, 1.0, 2.0, 2.0};
    static const ogk_real_t b[2] = {1.0, 2.0};
    /* 3 variables: row 3 = row 1 - 2 row 2, b3 = b1 - 2 b2 */
    static const ogk_real_t H3[9] = {2.0, 0.5, 0.0, 0.5, 1.0, 0.2, 0.0, 0.2, 3.0};
    static const ogk_real_t g3[3] = {1.0, -2.0, 0.5};
    static const ogk_real_t A3[9] = {1.0, 0.0, 1.0, 0.0, 1.0, 1.0, 1.0, -2.0, -1.0};
    static const ogk_real_t b3[3] = {0.7, -0.4, 1.5};
    double M[25];
    double y[5];
    size_t i, k;
    (void)state;
    p.m_eq = 2;
    p.A_eq = A;
    p.b_eq = b;
    expect_status(&p, OGK_OK);
    /* min (x1-1)^2 + (x2-2.5)^2 on x1 + x2 = 1: x = (-0.25, 1.25) */
    OGK_ASSERT_NEAR(sol.x[0], -0.25, OGK_TEST_TOL(1e-14, 45.0 * FLT_EPSILON));
    OGK_ASSERT_NEAR(sol.x[1], 1.25, OGK_TEST_TOL(1e-14, 45.0 * FLT_EPSILON));
    /* H x + g = (-2.5, -2.5) = (1, 1) (y0 + 2 y1) */
    OGK_ASSERT_NEAR(sol.y_eq[0] + 2.0 * sol.y_eq[1], -2.5, OGK_TEST_TOL(1e-14, 45.0 * FLT_EPSILON));
    assert_int_equal((int)sol.n_active, 1);

    p.n = 3;
    p.H = H3;
    p.g = g3;
    p.m_eq = 3;
    p.A_eq = A3;
    p.b_eq = b3;
    expect_status(&p, OGK_OK);
    assert_int_equal((int)sol.n_active, 2);
    /* KKT of the two independent rows: [H -A^T; A 0] [x; y] = [-g; b] */
    memset(M, 0, sizeof(M));
    for (i = 0; i < 3; ++i) {
        for (k = 0; k < 3; ++k) {
            M[i * 5 + k] = H3[i * 3 + k];
        }
        for (k = 0; k < 2; ++k) {
            M[i * 5 + 3 + k] = -A3[k * 3 + i];
            M[(3 + k) * 5 + i] = A3[k * 3 + i];
        }
        y[i] = -g3[i];
    }
    y[3] = b3[0];
    y[4] = b3[1];
    assert_true(ge_solve(M, y, 5));
    for (i = 0; i < 3; ++i) {
        OGK_ASSERT_NEAR(sol.x[i], y[i], OGK_TEST_TOL(1e-14, 45.0 * FLT_EPSILON));
    }
    /* the multipliers of the dependent set: y0 + y2 = Y0, y1 - 2 y2 = Y1 */
    OGK_ASSERT_NEAR(sol.y_eq[0] + sol.y_eq[2], y[3], OGK_TEST_TOL(1e-13, 450.0 * FLT_EPSILON));
    OGK_ASSERT_NEAR(sol.y_eq[1] - 2.0 * sol.y_eq[2], y[4], OGK_TEST_TOL(1e-13, 450.0 * FLT_EPSILON));
}

/* Row scaling: the N&W problem with its rows multiplied by 1e200 and by
 * 1e-200 (squares overflow / underflow) gives the same x, and multipliers
 * divided by the factor; a solution that overflows is OGK_E_NONFINITE.
 * Float: 1e20 and 1e-20, g = 1e30 (x = -1e40). */
/* req: OGK-CORE-018 */
static void test_scaled_rows_and_overflow(void **state)
{
    ogk_qp_problem_t p = small_problem();
    static const double factors[2] = {OGK_TEST_PICK(1e200, 1e20), OGK_TEST_PICK(1e-200, 1e-20)};
    static ogk_real_t A[6];
    static ogk_real_t b[3];
    static const ogk_real_t Hs[4] = {1e-10, 0.0, 0.0, 1e-10};
    static const ogk_real_t gs[2] = {OGK_TEST_PICK(1e300, 1e30), 0.0};
    size_t f, i;
    (void)state;
    for (f = 0; f < 2; ++f) {
        for (i = 0; i < 6; ++i) {
            A[i] = nw_A[i] * factors[f];
        }
        for (i = 0; i < 3; ++i) {
            b[i] = nw_b[i] * factors[f];
        }
        p = small_problem();
        p.m_in = 3;
        p.A_in = A;
        p.b_in = b;
        expect_status(&p, OGK_OK);
        OGK_ASSERT_NEAR(sol.x[0], 1.4, OGK_TEST_TOL(1e-14, 45.0 * FLT_EPSILON));
        OGK_ASSERT_NEAR(sol.x[1], 1.7, OGK_TEST_TOL(1e-14, 45.0 * FLT_EPSILON));
        OGK_ASSERT_REL(sol.y_in[0] * factors[f], 0.8, OGK_TEST_TOL(1e-14, 45.0 * FLT_EPSILON), 0.0);
        /* the same rows as equalities: x1 - 2 x2 = -2 alone */
        p = small_problem();
        p.m_eq = 1;
        p.A_eq = A;
        p.b_eq = b;
        expect_status(&p, OGK_OK);
        OGK_ASSERT_NEAR(sol.x[0], 1.4, OGK_TEST_TOL(1e-14, 45.0 * FLT_EPSILON));
        OGK_ASSERT_REL(sol.y_eq[0] * factors[f], 0.8, OGK_TEST_TOL(1e-14, 45.0 * FLT_EPSILON), 0.0);
    }
    /* x = -H^-1 g = -1e310: overflows */
    p = small_problem();
    p.H = Hs;
    p.g = gs;
    expect_status(&p, OGK_E_NONFINITE);
}

/* ------------------------------------------------------------------ random */

#if OGK_REAL_SINGLE
/* sum of |multipliers| of sol (the float objective's tolerance in test_random_vs_brute_force) */
static double multiplier_sum(size_t n, size_t me, size_t mi)
{
    double sum = 0.0;
    size_t i;
    for (i = 0; i < n; ++i) {
        sum += fabs((double)sol.z_lb[i]) + fabs((double)sol.z_ub[i]);
    }
    for (i = 0; i < me; ++i) {
        sum += fabs((double)sol.y_eq[i]);
    }
    for (i = 0; i < mi; ++i) {
        sum += fabs((double)sol.y_in[i]);
    }
    return sum;
}
#endif

/* n <= 6: the kernel against the brute-force enumeration, plus KKT. */
/* req: OGK-CORE-018 */
static void test_random_vs_brute_force(void **state)
{
    uint64_t s = 20261208u;
    size_t trial;
    size_t with_active = 0;
    (void)state;
    for (trial = 0; trial < 300; ++trial) {
        const size_t n = 1 + lcg_int(&s, 6);
        const size_t me = lcg_int(&s, (n < 3) ? n : 3);
        const size_t mi = lcg_int(&s, 5);
        double xb[BF_MAX_N];
        double fb = 0.0;
        ogk_qp_problem_t p;
        size_t i;
        random_problem(&tp, &s, n, me, mi, 0.4);
        p = view(&tp);
        expect_status(&p, OGK_OK);
        check_kkt(&tp, &sol, OGK_TEST_TOL(1e-11, QP_KKT_TOL_F));
        assert_true(brute_force(&tp, xb, &fb));
        for (i = 0; i < n; ++i) {
            OGK_ASSERT_NEAR(sol.x[i], xb[i], OGK_TEST_TOL(1e-8, QP_SOL_TOL_F) * fmax(1.0, max_abs_d(xb, n)));
        }
#if OGK_REAL_SINGLE
        /* Float: the active rows hold to float's residual (QP_KKT_TOL_F, relative), and the objective
         * moves with them by y^T r: the tolerance adds QP_KKT_TOL_F times the multipliers' sum. Trial
         * 119 (n = 2, an equality and a row nearly parallel, y = -88 and 123): x within 2.5e-5 of the
         * brute force, the equality's residual 1.2e-6 (10 eps), the objective 1.1e-4 below fb. */
        OGK_ASSERT_NEAR(sol.objective, fb,
                        QP_SOL_TOL_F * fmax(fabs(fb), 1.0) + QP_KKT_TOL_F * multiplier_sum(n, me, mi));
#else
        OGK_ASSERT_REL(sol.objective, fb, OGK_TEST_TOL(1e-10, QP_SOL_TOL_F), 1.0);
#endif
        if (sol.n_active > me) {
            ++with_active;
        }
    }
    /* the cases exercise the inequalities (not only unconstrained optima) */
    assert_true(with_active > 150);
}

/* Target size of the SQP: n = 32..48, 4 equalities, bounds on a third of the
 * variables, 8..16 rows: KKT conditions. */
/* req: OGK-CORE-018 */
static void test_random_target_size(void **state)
{
    uint64_t s = 31337u;
    size_t trial;
    (void)state;
    for (trial = 0; trial < 20; ++trial) {
        const size_t n = 32 + lcg_int(&s, 17);
        const size_t mi = 8 + lcg_int(&s, 9);
        ogk_qp_problem_t p;
        random_problem(&tp, &s, n, 4, mi, 0.34);
        p = view(&tp);
        expect_status(&p, OGK_OK);
        check_kkt(&tp, &sol, OGK_TEST_TOL(1e-10, QP_KKT_TOL_F));
        assert_true(sol.iterations <= OGK_QP_MAX_ITER);
        assert_true(sol.n_active >= 4 && sol.n_active <= n);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_null_and_dims),
        cmocka_unit_test(test_nonfinite_and_range),
        cmocka_unit_test(test_not_posdef),
        cmocka_unit_test(test_infeasible),
        cmocka_unit_test(test_unconstrained),
        cmocka_unit_test(test_equality_only),
        cmocka_unit_test(test_hand_example),
        cmocka_unit_test(test_degenerate),
        cmocka_unit_test(test_dependent_equalities),
        cmocka_unit_test(test_scaled_rows_and_overflow),
        cmocka_unit_test(test_random_vs_brute_force),
        cmocka_unit_test(test_random_target_size),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
