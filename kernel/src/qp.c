/* qp.c -- dense strictly convex QP by the dual active-set method of
 * Goldfarb & Idnani, "A numerically stable dual method for solving strictly
 * convex quadratic programs", Math. Programming 27 (1983) 1-33, in the form of
 * Powell's and Turlach's implementations (quadprog "qpgen2"):
 *
 *   H = L L^T (Cholesky), unconstrained start x = -H^-1 g, J = L^-T;
 *   with the active normals N = [n_1 .. n_q]: L^-1 N = Q [R; 0], J = L^-T Q,
 *   d = J^T n+, z = J2 d2 (primal direction), r = R^-1 d1 (dual direction);
 *   a constraint is added by Givens rotations of the columns of J that zero
 *   d(q+1..n-1) (R gains the column d(0..q)); a constraint is dropped by
 *   removing its column of R and restoring the triangle by Givens rotations
 *   of rows of R (and the same columns of J).
 * J is stored transposed (ws->j row k = column k of J), so that J^T n, J2 d2
 * and every rotation run along contiguous rows; L lives in ws->r until the
 * first constraint is added.
 *
 * Equality rows are made active first, in order, and never dropped; then each
 * iteration adds the most violated inequality row or bound (violation
 * normalised by the row's 2-norm), with the partial/full step rule: a partial
 * step drops the active inequality whose multiplier reaches zero first.
 * Bounds are unit rows e_i (lower) and -e_i (upper) and never stored densely.
 * Design, tolerances and measured cost: docs/qp.md. */
#include "ogk/qp.h"

#include <float.h>
#include <math.h>
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>

#include "ogk_checks.h"

/* "No constraint" (a constraint number or an active-set position). */
#define QP_NONE SIZE_MAX

/* State of one solve, on the caller's stack (pointers and counters only). */
typedef struct {
    ogk_qp_workspace_t *ws;
    const ogk_qp_problem_t *p;
    size_t n;      /* variables */
    size_t k_in;   /* number of the first inequality row (m_eq) */
    size_t k_lb;   /* number of the first lower bound (m_eq + m_in) */
    size_t k_ub;   /* number of the first upper bound (m_eq + m_in + n) */
    size_t q;      /* active constraints */
    size_t iter;   /* active-set changes */
} qp_state_t;

/* Result of the step computation for one constraint. */
typedef struct {
    double ztn;    /* z^T n+ = |d2|^2 */
    bool dep;      /* n+ linearly dependent on the active normals (z = 0) */
} qp_dir_t;

/* ------------------------------------------------------------------ checks */

static bool qp_dim_ok(const ogk_qp_problem_t *p)
{
    return (p->n > 0u) && (p->n <= OGK_QP_MAX_N) && (p->m_eq <= OGK_QP_MAX_EQ) &&
           (p->m_eq <= p->n) && (p->m_in <= OGK_QP_MAX_IN);
}

static bool qp_pointers_ok(const ogk_qp_problem_t *p)
{
    bool ok = (p->H != NULL) && (p->g != NULL);
    if ((p->m_eq > 0u) && ((p->A_eq == NULL) || (p->b_eq == NULL))) {
        ok = false;
    }
    if ((p->m_in > 0u) && ((p->A_in == NULL) || (p->b_in == NULL))) {
        ok = false;
    }
    return ok;
}

/* True when v[0..n-1] has no NaN (infinities allowed: bounds). */
static bool qp_no_nan(const double *v, size_t n)
{
    bool ok = true;
    size_t i;
    for (i = 0u; (i < n) && ok; ++i) {
        if (isnan(v[i]) != 0) {
            ok = false;
        }
    }
    return ok;
}

static bool qp_has_lb(const ogk_qp_problem_t *p, size_t i)
{
    return (p->lb != NULL) && (fabs(p->lb[i]) < OGK_QP_INF);
}

static bool qp_has_ub(const ogk_qp_problem_t *p, size_t i)
{
    return (p->ub != NULL) && (fabs(p->ub[i]) < OGK_QP_INF);
}

/* OGK_E_NONFINITE for a NaN bound, OGK_E_RANGE for lb > ub (both bounds set). */
static ogk_status qp_bounds_check(const ogk_qp_problem_t *p)
{
    ogk_status st = OGK_OK;
    size_t i;
    if (((p->lb != NULL) && !qp_no_nan(p->lb, p->n)) ||
        ((p->ub != NULL) && !qp_no_nan(p->ub, p->n))) {
        st = OGK_E_NONFINITE;
    }
    for (i = 0u; (i < p->n) && (st == OGK_OK); ++i) {
        if (qp_has_lb(p, i) && qp_has_ub(p, i) && (p->lb[i] > p->ub[i])) {
            st = OGK_E_RANGE;
        }
    }
    return st;
}

static ogk_status qp_input_check(const ogk_qp_workspace_t *ws, const ogk_qp_problem_t *p,
                                 const ogk_qp_solution_t *sol)
{
    ogk_status st;
    if ((ws == NULL) || (p == NULL) || (sol == NULL) || !qp_pointers_ok(p)) {
        st = OGK_E_NULL;
    } else if (!qp_dim_ok(p)) {
        st = OGK_E_DIM;
    } else if (!ogk_i_all_finite(p->H, p->n * p->n) || !ogk_i_all_finite(p->g, p->n) ||
               ((p->m_eq > 0u) && (!ogk_i_all_finite(p->A_eq, p->m_eq * p->n) ||
                                   !ogk_i_all_finite(p->b_eq, p->m_eq))) ||
               ((p->m_in > 0u) && (!ogk_i_all_finite(p->A_in, p->m_in * p->n) ||
                                   !ogk_i_all_finite(p->b_in, p->m_in)))) {
        st = OGK_E_NONFINITE;
    } else {
        st = qp_bounds_check(p);
    }
    return st;
}

/* ------------------------------------------------------------------ setup */

/* Sum of squares below which the unscaled 2-norm may have lost accuracy to
 * underflow (DBL_MIN / DBL_EPSILON). */
#define QP_SSQ_SAFE_MIN (DBL_MIN / DBL_EPSILON)

/* 2-norm of v[0..n-1]: the plain sum of squares, or, when it overflowed or
 * may have underflowed, the sum rescaled by the largest magnitude. */
static double qp_norm2(const double *v, size_t n)
{
    double ssq = 0.0;
    double norm;
    size_t i;
    for (i = 0u; i < n; ++i) {
        ssq += v[i] * v[i];
    }
    if ((ssq <= DBL_MAX) && (ssq >= QP_SSQ_SAFE_MIN)) {
        norm = sqrt(ssq);
    } else {
        double scale = 0.0;
        for (i = 0u; i < n; ++i) {
            if (fabs(v[i]) > scale) {
                scale = fabs(v[i]);
            }
        }
        ssq = 0.0;
        if (scale > 0.0) {
            for (i = 0u; i < n; ++i) {
                const double t = v[i] / scale;
                ssq += t * t;
            }
        }
        norm = scale * sqrt(ssq);
    }
    return norm;
}

/* OGK_E_NOT_POSDEF when H is not symmetric to OGK_QP_SYM_TOL max |H|. */
static ogk_status qp_symmetry_check(const double *H, size_t n)
{
    ogk_status st = OGK_OK;
    double hmax = 0.0;
    size_t i;
    size_t k;
    for (i = 0u; i < (n * n); ++i) {
        if (fabs(H[i]) > hmax) {
            hmax = fabs(H[i]);
        }
    }
    for (i = 0u; (i < n) && (st == OGK_OK); ++i) {
        for (k = 0u; (k < i) && (st == OGK_OK); ++k) {
            if (fabs(H[(i * n) + k] - H[(k * n) + i]) > (OGK_QP_SYM_TOL * hmax)) {
                st = OGK_E_NOT_POSDEF;
            }
        }
    }
    return st;
}

/* ws->r = L, (H + H^T)/2 = L L^T (row-major, zero above the diagonal).
 * OGK_E_NOT_POSDEF when a pivot d^2 <= OGK_QP_PIVOT_TOL H_jj or H_jj <= 0. */
static ogk_status qp_cholesky(ogk_qp_workspace_t *ws, const double *H, size_t n)
{
    ogk_status st = OGK_OK;
    double *L = ws->r;
    size_t i;
    size_t jj;
    size_t k;
    (void)memset(L, 0, n * n * sizeof(double)); /* result unused: returns L */
    for (jj = 0u; (jj < n) && (st == OGK_OK); ++jj) {
        const double hjj = H[(jj * n) + jj];
        double piv = hjj;
        for (k = 0u; k < jj; ++k) {
            piv -= L[(jj * n) + k] * L[(jj * n) + k];
        }
        if ((hjj <= 0.0) || (piv <= (OGK_QP_PIVOT_TOL * hjj))) {
            st = OGK_E_NOT_POSDEF;
        } else {
            const double ljj = sqrt(piv);
            L[(jj * n) + jj] = ljj;
            for (i = jj + 1u; i < n; ++i) {
                double s = 0.5 * (H[(i * n) + jj] + H[(jj * n) + i]);
                for (k = 0u; k < jj; ++k) {
                    s -= L[(i * n) + k] * L[(jj * n) + k];
                }
                L[(i * n) + jj] = s / ljj;
            }
        }
    }
    return st;
}

/* ws->x = -H^-1 g from L (forward then back substitution). */
static void qp_unconstrained(ogk_qp_workspace_t *ws, const double *g, size_t n)
{
    const double *L = ws->r;
    double *x = ws->x;
    size_t i;
    size_t k;
    for (i = 0u; i < n; ++i) {
        double s = -g[i];
        for (k = 0u; k < i; ++k) {
            s -= L[(i * n) + k] * x[k];
        }
        x[i] = s / L[(i * n) + i];
    }
    for (i = n; i > 0u; --i) {
        const size_t ii = i - 1u;
        double s = x[ii];
        for (k = i; k < n; ++k) {
            s -= L[(k * n) + ii] * x[k];
        }
        x[ii] = s / L[(ii * n) + ii];
    }
}

/* ws->j = J^T = L^-1 (lower triangular), row by row from L in ws->r:
 * L(i,i) Li(i,:) = e_i - sum_{k<i} L(i,k) Li(k,:). */
static void qp_initial_j(ogk_qp_workspace_t *ws, size_t n)
{
    const double *L = ws->r;
    double *Li = ws->j;
    size_t c;
    size_t i;
    size_t k;
    (void)memset(Li, 0, n * n * sizeof(double)); /* result unused: returns Li */
    for (i = 0u; i < n; ++i) {
        double *row = &Li[i * n];
        const double inv = 1.0 / L[(i * n) + i];
        for (k = 0u; k < i; ++k) {
            const double lik = L[(i * n) + k];
            const double *rk = &Li[k * n];
            for (c = 0u; c <= k; ++c) {
                row[c] -= lik * rk[c];
            }
        }
        row[i] = 1.0;
        for (c = 0u; c <= i; ++c) {
            row[c] *= inv;
        }
    }
}

/* ------------------------------------------------------------------ constraints */

/* Row of the general constraint number c (equality or inequality row). */
static const double *qp_row(const qp_state_t *s, size_t c)
{
    const double *row;
    if (c < s->k_in) {
        row = &s->p->A_eq[c * s->n];
    } else {
        row = &s->p->A_in[(c - s->k_in) * s->n];
    }
    return row;
}

/* Factor and right-hand side of constraint c as n_c^T x >= b_c, n_c = factor
 * times the row: 1 / |a|_2 for the general rows (unit normals), times the
 * sign an equality was made active with; +-1 for the bounds, whose variable
 * goes to *var (QP_NONE for a general row). */
static double qp_rhs(const qp_state_t *s, size_t c, double *sign, size_t *var)
{
    double b;
    *var = QP_NONE;
    if (c < s->k_in) {
        *sign = s->ws->eqsign[c] * s->ws->rowscale[c];
        b = *sign * s->p->b_eq[c];
    } else if (c < s->k_lb) {
        *sign = s->ws->rowscale[c];
        b = *sign * s->p->b_in[c - s->k_in];
    } else if (c < s->k_ub) {
        *sign = 1.0;
        *var = c - s->k_lb;
        b = s->p->lb[*var];
    } else {
        *sign = -1.0;
        *var = c - s->k_ub;
        b = -s->p->ub[*var];
    }
    return b;
}

/* n_c^T v for the constraint normal n_c. */
static double qp_dot(const qp_state_t *s, size_t c, const double *v)
{
    double sign;
    size_t var;
    double dot;
    (void)qp_rhs(s, c, &sign, &var); /* only the sign and the variable are needed */
    if (var != QP_NONE) {
        dot = sign * v[var];
    } else {
        const double *row = qp_row(s, c);
        size_t i;
        dot = 0.0;
        for (i = 0u; i < s->n; ++i) {
            dot += row[i] * v[i];
        }
        dot *= sign;
    }
    return dot;
}

/* Slack n_c^T x - b_c at ws->x and its violation tolerance in *tol. */
static double qp_slack(const qp_state_t *s, size_t c, double xnorm, double *tol) /* NOLINT(bugprone-easily-swappable-parameters): a constraint number and a norm, every call checked by the KKT and brute-force unit tests */
{
    double sign;
    size_t var;
    const double b = qp_rhs(s, c, &sign, &var);
    (void)var; /* unit normals: |n_c|_2 = 1 (1 / |a| for a zero row a: |n_c| = 0) */
    *tol = OGK_QP_FEAS_TOL * (fabs(b) + xnorm);
    return qp_dot(s, c, s->ws->x) - b;
}

/* ------------------------------------------------------------------ active-set algebra */

/* d = J^T n_c, z = J2 d2, rdir = R^-1 d1; dependence test of n_c. */
static qp_dir_t qp_direction(const qp_state_t *s, size_t c)
{
    ogk_qp_workspace_t *ws = s->ws;
    const size_t n = s->n;
    const size_t q = s->q;
    double sign;
    size_t var;
    qp_dir_t dir;
    size_t i;
    size_t k;

    (void)qp_rhs(s, c, &sign, &var); /* only the sign and the variable are needed */
    if (var != QP_NONE) {
        for (k = 0u; k < n; ++k) {
            ws->d[k] = sign * ws->j[(k * n) + var];
        }
    } else {
        const double *row = qp_row(s, c);
        for (k = 0u; k < n; ++k) {
            const double *jk = &ws->j[k * n];
            double dk = 0.0;
            for (i = 0u; i < n; ++i) {
                dk += jk[i] * row[i];
            }
            ws->d[k] = sign * dk;
        }
    }
    /* z = sum over the free columns q..n-1 of J(:, k) d(k) (rows of ws->j) */
    (void)memset(ws->z, 0, n * sizeof(double)); /* result unused: returns z */
    for (k = q; k < n; ++k) {
        const double *jk = &ws->j[k * n];
        const double dk = ws->d[k];
        for (i = 0u; i < n; ++i) {
            ws->z[i] += jk[i] * dk;
        }
    }
    /* rdir = R^-1 d(0..q-1), back substitution */
    for (i = q; i > 0u; --i) {
        const size_t ii = i - 1u;
        double t = ws->d[ii];
        for (k = i; k < q; ++k) {
            t -= ws->r[(ii * n) + k] * ws->rdir[k];
        }
        ws->rdir[ii] = t / ws->r[(ii * n) + ii];
    }
    {
        const double d2 = (q < n) ? qp_norm2(&ws->d[q], n - q) : 0.0;
        dir.ztn = d2 * d2;
        dir.dep = (q >= n) || (d2 <= (OGK_QP_DEP_TOL * qp_norm2(ws->d, n))) ||
                  (dir.ztn <= 0.0);
    }
    return dir;
}

/* Rotates columns a and b of J (rows of ws->j, which holds J^T):
 * (Ja, Jb) <- (c Ja + s Jb, -s Ja + c Jb). */
static void qp_rotate_j(ogk_qp_workspace_t *ws, size_t n, size_t a, size_t b, /* NOLINT(bugprone-easily-swappable-parameters): order, rows, cosine, sine of a Givens rotation; a swapped pair fails the unit tests (docs/qp.md, mutants) */
                        double cs, double sn)
{
    double *ja = &ws->j[a * n];
    double *jb = &ws->j[b * n];
    size_t i;
    for (i = 0u; i < n; ++i) {
        const double va = ja[i];
        const double vb = jb[i];
        ja[i] = (cs * va) + (sn * vb);
        jb[i] = (cs * vb) - (sn * va);
    }
}

/* Adds constraint c with multiplier u_c at position q (d = J^T n_c held). */
static void qp_add(qp_state_t *s, size_t c, double u_c) /* NOLINT(bugprone-easily-swappable-parameters): a constraint number and its multiplier */
{
    ogk_qp_workspace_t *ws = s->ws;
    const size_t n = s->n;
    const size_t q = s->q;
    size_t k;
    size_t i;
    for (k = n - 1u; k > q; --k) {
        const double a = ws->d[k - 1u];
        const double b = ws->d[k];
        if (b != 0.0) {
            const double h = hypot(a, b);
            qp_rotate_j(ws, n, k - 1u, k, a / h, b / h);
            ws->d[k - 1u] = h;
            ws->d[k] = 0.0;
        }
    }
    if (ws->d[q] < 0.0) {
        for (i = 0u; i < n; ++i) {
            ws->j[(q * n) + i] = -ws->j[(q * n) + i];
        }
        ws->d[q] = -ws->d[q];
    }
    for (i = 0u; i <= q; ++i) {
        ws->r[(i * n) + q] = ws->d[i];
    }
    ws->active[q] = c;
    ws->u[q] = u_c;
    s->q = q + 1u;
    s->iter += 1u;
}

/* Drops the active constraint at position pos: R loses that column and is
 * made triangular again by rotations of its rows (and the same columns of J). */
static void qp_drop(qp_state_t *s, size_t pos)
{
    ogk_qp_workspace_t *ws = s->ws;
    const size_t n = s->n;
    const size_t q = s->q;
    size_t k;
    size_t i;
    for (k = pos; (k + 1u) < q; ++k) {
        for (i = 0u; i <= (k + 1u); ++i) {
            ws->r[(i * n) + k] = ws->r[(i * n) + k + 1u];
        }
        ws->active[k] = ws->active[k + 1u];
        ws->u[k] = ws->u[k + 1u];
    }
    /* R is now upper Hessenberg in columns pos..q-2: zero R(k+1, k). */
    for (k = pos; (k + 1u) < q; ++k) {
        const double a = ws->r[(k * n) + k];
        const double b = ws->r[((k + 1u) * n) + k];
        const double h = hypot(a, b);
        if (h > 0.0) {
            /* also when b = 0: a < 0 then gives cs = -1, a positive diagonal */
            const double cs = a / h;
            const double sn = b / h;
            for (i = k; (i + 1u) < q; ++i) {
                const double ra = ws->r[(k * n) + i];
                const double rb = ws->r[((k + 1u) * n) + i];
                ws->r[(k * n) + i] = (cs * ra) + (sn * rb);
                ws->r[((k + 1u) * n) + i] = (cs * rb) - (sn * ra);
            }
            qp_rotate_j(ws, n, k, k + 1u, cs, sn);
        }
        ws->r[((k + 1u) * n) + k] = 0.0;
    }
    s->q = q - 1u;
    s->iter += 1u;
}

/* x += t z, u(0..q-1) -= t rdir; inequality multipliers kept >= 0 (rounding). */
static void qp_take_step(const qp_state_t *s, double t)
{
    ogk_qp_workspace_t *ws = s->ws;
    size_t k;
    for (k = 0u; k < s->n; ++k) {
        ws->x[k] += t * ws->z[k];
    }
    for (k = 0u; k < s->q; ++k) {
        ws->u[k] -= t * ws->rdir[k];
        if ((ws->active[k] >= s->k_in) && (ws->u[k] < 0.0)) {
            ws->u[k] = 0.0;
        }
    }
}

/* ------------------------------------------------------------------ the method */

/* Equality rows, in order: each made active with a full step. A row dependent
 * on the rows already active is skipped when consistent (|slack| within the
 * feasibility tolerance) and makes the problem infeasible otherwise. */
static ogk_status qp_equalities(qp_state_t *s)
{
    ogk_qp_workspace_t *ws = s->ws;
    ogk_status st = OGK_OK;
    size_t c;
    for (c = 0u; (c < s->k_in) && (st == OGK_OK); ++c) {
        const double xnorm = qp_norm2(ws->x, s->n);
        double tol;
        double slack;
        qp_dir_t dir;
        ws->eqsign[c] = 1.0;
        slack = qp_slack(s, c, xnorm, &tol);
        if (slack > 0.0) {
            ws->eqsign[c] = -1.0;
            slack = -slack;
        }
        dir = qp_direction(s, c);
        if (dir.dep) {
            if (slack < -tol) {
                st = OGK_E_INFEASIBLE;
            }
        } else {
            const double t = -slack / dir.ztn;
            qp_take_step(s, t);
            qp_add(s, c, t);
        }
    }
    return st;
}

/* The most violated inequality row or bound (violation / row norm), or QP_NONE. */
static size_t qp_select(const qp_state_t *s)
{
    ogk_qp_workspace_t *ws = s->ws;
    const size_t m_in = s->k_lb - s->k_in;
    const size_t total = m_in + (2u * s->n);
    const double xnorm = qp_norm2(ws->x, s->n);
    size_t best = QP_NONE;
    double worst = 0.0;
    size_t k;
    for (k = 0u; k < total; ++k) {
        const size_t c = s->k_in + k;
        const bool is_bound = k >= m_in;
        const size_t var = is_bound ? ((k - m_in) % s->n) : 0u;
        const bool present = !is_bound || ((c < s->k_ub) ? qp_has_lb(s->p, var) : qp_has_ub(s->p, var));
        double slack = 0.0;
        if (present) {
            double tol;
            slack = qp_slack(s, c, xnorm, &tol);
            if (slack >= -tol) {
                slack = 0.0;
            }
        }
        ws->slack[k] = slack;
    }
    for (k = 0u; k < s->q; ++k) {
        if (ws->active[k] >= s->k_in) {
            ws->slack[ws->active[k] - s->k_in] = 0.0;
        }
    }
    for (k = 0u; k < total; ++k) {
        if (ws->slack[k] < 0.0) {
            if (ws->slack[k] < worst) {
                worst = ws->slack[k];
                best = s->k_in + k;
            }
        }
    }
    return best;
}

/* One change of the active set for the violated constraint c whose
 * multiplier is *u_c: a full step adds c (*added = true); a partial step, or a
 * dual step when n_c depends on the active set, drops the active inequality
 * whose multiplier reaches zero first. OGK_E_INFEASIBLE when neither exists. */
static ogk_status qp_iterate(qp_state_t *s, size_t c, double *u_c, bool *added)
{
    ogk_qp_workspace_t *ws = s->ws;
    ogk_status st = OGK_OK;
    const qp_dir_t dir = qp_direction(s, c);
    double tol;
    const double slack = qp_slack(s, c, qp_norm2(ws->x, s->n), &tol);
    double t1 = 0.0;
    size_t drop = QP_NONE;
    size_t k;
    *added = false;
    for (k = 0u; k < s->q; ++k) {
        if ((ws->active[k] >= s->k_in) && (ws->rdir[k] > 0.0)) {
            const double ratio = ws->u[k] / ws->rdir[k];
            if ((drop == QP_NONE) || (ratio < t1)) {
                t1 = ratio;
                drop = k;
            }
        }
    }
    if (dir.dep && (drop == QP_NONE)) {
        st = OGK_E_INFEASIBLE;
    } else if (!dir.dep && ((drop == QP_NONE) || ((-slack / dir.ztn) <= t1))) {
        const double t2 = -slack / dir.ztn;
        qp_take_step(s, t2);
        *u_c += t2;
        qp_add(s, c, *u_c);
        *added = true;
    } else {
        if (dir.dep) {
            (void)memset(ws->z, 0, s->n * sizeof(double)); /* result unused: dual step only */
        }
        qp_take_step(s, t1);
        *u_c += t1;
        ws->u[drop] = 0.0;
        qp_drop(s, drop);
    }
    return st;
}

/* Inequality rows and bounds until none is violated. */
static ogk_status qp_inequalities(qp_state_t *s)
{
    ogk_status st = OGK_OK;
    bool running = true;
    size_t c = QP_NONE;
    double u_c = 0.0;
    size_t pass;
    for (pass = 0u; (pass <= OGK_QP_MAX_ITER) && running; ++pass) {
        if (c == QP_NONE) {
            c = qp_select(s);
            u_c = 0.0;
        }
        if (c == QP_NONE) {
            running = false;
        } else if (s->iter >= OGK_QP_MAX_ITER) {
            st = OGK_E_ITER_LIMIT;
            running = false;
        } else {
            bool added;
            st = qp_iterate(s, c, &u_c, &added);
            if (st != OGK_OK) {
                running = false;
            } else if (added) {
                c = QP_NONE;
            } else {
                /* partial step: c stays the constraint to add */
            }
        }
    }
    if (running) {
        st = OGK_E_ITER_LIMIT;
    }
    return st;
}

/* ------------------------------------------------------------------ results */

static void qp_solution(const qp_state_t *s, ogk_qp_solution_t *sol)
{
    const ogk_qp_workspace_t *ws = s->ws;
    const double *H = s->p->H;
    const size_t n = s->n;
    double quad = 0.0;
    double lin = 0.0;
    size_t i;
    size_t k;
    for (i = 0u; i < n; ++i) {
        double hx = 0.0;
        for (k = 0u; k < n; ++k) {
            hx += H[(i * n) + k] * ws->x[k];
        }
        quad += ws->x[i] * hx;
        lin += s->p->g[i] * ws->x[i];
        sol->x[i] = ws->x[i];
    }
    sol->objective = (0.5 * quad) + lin;
    for (k = 0u; k < s->q; ++k) {
        const size_t c = ws->active[k];
        if (c < s->k_in) {
            sol->y_eq[c] = ws->eqsign[c] * ws->rowscale[c] * ws->u[k];
        } else if (c < s->k_lb) {
            sol->y_in[c - s->k_in] = ws->rowscale[c] * ws->u[k];
        } else if (c < s->k_ub) {
            sol->z_lb[c - s->k_lb] = ws->u[k];
        } else {
            sol->z_ub[c - s->k_ub] = ws->u[k];
        }
    }
    sol->n_active = s->q;
}

static void qp_row_norms(const qp_state_t *s)
{
    size_t c;
    for (c = 0u; c < s->k_lb; ++c) {
        const double norm = qp_norm2(qp_row(s, c), s->n);
        double scale = 1.0;
        if (norm > 0.0) {
            scale = 1.0 / norm;
        }
        s->ws->rowscale[c] = scale;
    }
}

ogk_status ogk_qp_solve(ogk_qp_workspace_t *ws, const ogk_qp_problem_t *p,
                        ogk_qp_solution_t *sol)
{
    ogk_status st = qp_input_check(ws, p, sol);
    qp_state_t s = {NULL, NULL, 0u, 0u, 0u, 0u, 0u, 0u};
    if (sol != NULL) {
        (void)memset(sol, 0, sizeof(*sol)); /* result unused: returns sol */
    }
    if (st == OGK_OK) {
        s.ws = ws;
        s.p = p;
        s.n = p->n;
        s.k_in = p->m_eq;
        s.k_lb = p->m_eq + p->m_in;
        s.k_ub = s.k_lb + p->n;
        s.q = 0u;
        s.iter = 0u;
        st = qp_symmetry_check(p->H, p->n);
    }
    if (st == OGK_OK) {
        st = qp_cholesky(ws, p->H, p->n);
    }
    if (st == OGK_OK) {
        qp_unconstrained(ws, p->g, p->n);
        qp_initial_j(ws, p->n);
        qp_row_norms(&s);
        st = qp_equalities(&s);
    }
    if (st == OGK_OK) {
        st = qp_inequalities(&s);
    }
    if ((st == OGK_OK) && !ogk_i_all_finite(ws->x, p->n)) {
        st = OGK_E_NONFINITE;
    }
    if (st == OGK_OK) {
        qp_solution(&s, sol);
    }
    if ((st == OGK_OK) || (st == OGK_E_INFEASIBLE) || (st == OGK_E_ITER_LIMIT)) {
        sol->iterations = s.iter; /* also kept by a failed solve (x and multipliers zero) */
    }
    return st;
}
