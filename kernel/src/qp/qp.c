/* qp.c -- dense strictly convex QP by the dual active-set method of
 * Goldfarb & Idnani, "A numerically stable dual method for solving strictly
 * convex quadratic programs", Math. Programming 27 (1983) 1-33:
 *
 *   H = L L^T (Cholesky, computed as U = L^T), unconstrained start
 *   x = -H^-1 g, J = L^-T;
 *   with the active normals N = [n_1 .. n_q]: L^-1 N = Q [R; 0], J = L^-T Q,
 *   d = J^T n+, z = J2 d2 (primal direction), r = R^-1 d1 (dual direction);
 *   a constraint is added by one Householder reflection of the columns
 *   q..n-1 of J that maps d2 onto |d2| e_1 (R gains the column d(0..q)); a
 *   constraint is dropped by removing its column of R and restoring the
 *   triangle by Givens rotations of rows of R (and the same columns of J).
 * J is stored transposed (ws->j row k = column k of J), so that J^T n, J2 d2,
 * the reflection and every rotation run along contiguous rows; U lives in
 * ws->r until the first constraint is added. Until then J^T = L^-1 is lower
 * triangular and its products skip the zeros. The dense loops are in
 * qp_blas.c.
 *
 * Equality rows are made active first, in order, and never dropped; then each
 * iteration adds the most violated inequality row or bound (violation
 * normalised by the row's 2-norm), with the partial/full step rule: a partial
 * step drops the active inequality whose multiplier reaches zero first.
 * Bounds are unit rows e_i (lower) and -e_i (upper) and never stored densely.
 * Design, tolerances and measured cost: docs/design/qp.md. */
#include "ogk/qp.h"

#include <float.h>
#include <math.h>
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>

#include "../ogk_checks.h"
#include "qp_internal.h"

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
    ogk_real_t ztn;    /* z^T n+ = |d2|^2 */
    ogk_real_t d2;     /* |d2|_2, d2 = d(q..n-1) */
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
static bool qp_no_nan(const ogk_real_t *v, size_t n)
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

/* True when v[0..n-1] is all finite: v_i * 0 is 0 for a finite v_i and NaN
 * for +-Inf or NaN, and a NaN stays in the sums. Two independent sums and no
 * branch per element (the input check reads all of H). */
static bool qp_all_finite(const ogk_real_t *v, size_t n)
{
    ogk_real_t acc0 = OGK_R(0.0);
    ogk_real_t acc1 = OGK_R(0.0);
    size_t i = 0u;
    for (; (i + 2u) <= n; i += 2u) {
        acc0 += v[i] * OGK_R(0.0);
        acc1 += v[i + 1u] * OGK_R(0.0);
    }
    if (i < n) {
        acc0 += v[i] * OGK_R(0.0);
    }
    return (acc0 + acc1) == OGK_R(0.0);
}

static bool qp_has_lb(const ogk_qp_problem_t *p, size_t i)
{
    return (p->lb != NULL) && (OGK_FABS(p->lb[i]) < OGK_QP_INF);
}

static bool qp_has_ub(const ogk_qp_problem_t *p, size_t i)
{
    return (p->ub != NULL) && (OGK_FABS(p->ub[i]) < OGK_QP_INF);
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
    } else if (!qp_all_finite(p->H, p->n * p->n) || !qp_all_finite(p->g, p->n) ||
               ((p->m_eq > 0u) && (!qp_all_finite(p->A_eq, p->m_eq * p->n) ||
                                   !qp_all_finite(p->b_eq, p->m_eq))) ||
               ((p->m_in > 0u) && (!qp_all_finite(p->A_in, p->m_in * p->n) ||
                                   !qp_all_finite(p->b_in, p->m_in)))) {
        st = OGK_E_NONFINITE;
    } else {
        st = qp_bounds_check(p);
    }
    return st;
}

/* ------------------------------------------------------------------ setup */

/* Sum of squares below which the unscaled 2-norm may have lost accuracy to
 * underflow (DBL_MIN / DBL_EPSILON). */
#define QP_SSQ_SAFE_MIN (OGK_REAL_MIN / OGK_REAL_EPSILON)

/* 2-norm of v[0..n-1]: the plain sum of squares, or, when it overflowed or
 * may have underflowed, the sum rescaled by the largest magnitude. */
static ogk_real_t qp_norm2(const ogk_real_t *v, size_t n)
{
    ogk_real_t ssq = OGK_R(0.0);
    ogk_real_t norm;
    size_t i;
    for (i = 0u; i < n; ++i) {
        ssq += v[i] * v[i];
    }
    if ((ssq <= OGK_REAL_MAX) && (ssq >= QP_SSQ_SAFE_MIN)) {
        norm = OGK_SQRT(ssq);
    } else {
        ogk_real_t scale = OGK_R(0.0);
        for (i = 0u; i < n; ++i) {
            if (OGK_FABS(v[i]) > scale) {
                scale = OGK_FABS(v[i]);
            }
        }
        ssq = OGK_R(0.0);
        if (scale > OGK_R(0.0)) {
            for (i = 0u; i < n; ++i) {
                const ogk_real_t t = v[i] / scale;
                ssq += t * t;
            }
        }
        norm = scale * OGK_SQRT(ssq);
    }
    return norm;
}

/* ------------------------------------------------------------------ constraints */

/* Row of the general constraint number c (equality or inequality row). */
static const ogk_real_t *qp_row(const qp_state_t *s, size_t c)
{
    const ogk_real_t *row;
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
static ogk_real_t qp_rhs(const qp_state_t *s, size_t c, ogk_real_t *sign, size_t *var)
{
    ogk_real_t b;
    *var = QP_NONE;
    if (c < s->k_in) {
        *sign = s->ws->eqsign[c] * s->ws->rowscale[c];
        b = *sign * s->p->b_eq[c];
    } else if (c < s->k_lb) {
        *sign = s->ws->rowscale[c];
        b = *sign * s->p->b_in[c - s->k_in];
    } else if (c < s->k_ub) {
        *sign = OGK_R(1.0);
        *var = c - s->k_lb;
        b = s->p->lb[*var];
    } else {
        *sign = -OGK_R(1.0);
        *var = c - s->k_ub;
        b = -s->p->ub[*var];
    }
    return b;
}

/* n_c^T v for the constraint normal n_c. */
static ogk_real_t qp_dot(const qp_state_t *s, size_t c, const ogk_real_t *v)
{
    ogk_real_t sign;
    size_t var;
    ogk_real_t dot;
    (void)qp_rhs(s, c, &sign, &var); /* only the sign and the variable are needed */
    if (var != QP_NONE) {
        dot = sign * v[var];
    } else {
        const ogk_real_t *row = qp_row(s, c);
        size_t i;
        dot = OGK_R(0.0);
        for (i = 0u; i < s->n; ++i) {
            dot += row[i] * v[i];
        }
        dot *= sign;
    }
    return dot;
}

/* Slack n_c^T x - b_c at ws->x and its violation tolerance in *tol. */
static ogk_real_t qp_slack(const qp_state_t *s, size_t c, ogk_real_t xnorm, ogk_real_t *tol) /* NOLINT(bugprone-easily-swappable-parameters): a constraint number and a norm, every call checked by the KKT and brute-force unit tests */
{
    ogk_real_t sign;
    size_t var;
    const ogk_real_t b = qp_rhs(s, c, &sign, &var);
    (void)var; /* unit normals: |n_c|_2 = 1 (1 / |a| for a zero row a: |n_c| = 0) */
    *tol = OGK_QP_FEAS_TOL * (OGK_FABS(b) + xnorm);
    return qp_dot(s, c, s->ws->x) - b;
}

/* ------------------------------------------------------------------ active-set algebra */

/* d = J^T n_c, z = J2 d2, rdir = R^-1 d1; dependence test of n_c. */
static qp_dir_t qp_direction(const qp_state_t *s, size_t c)
{
    ogk_qp_workspace_t *ws = s->ws;
    const size_t n = s->n;
    const size_t q = s->q;
    /* J^T is L^-1, lower triangular, until the first change of the active set */
    const bool lower = s->iter == 0u;
    ogk_real_t sign;
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
        ogk_i_qp_mat_vec(ws->j, n, n, lower, qp_row(s, c), sign, ws->d);
    }
    /* z = sum over the free columns q..n-1 of J(:, k) d(k) (rows of ws->j) */
    ogk_i_qp_rows_combine(ws->j, n, lower, q, ws->d, ws->z);
    /* rdir = R^-1 d(0..q-1), back substitution */
    for (i = q; i > 0u; --i) {
        const size_t ii = i - 1u;
        ogk_real_t t = ws->d[ii];
        for (k = i; k < q; ++k) {
            t -= ws->r[(ii * n) + k] * ws->rdir[k];
        }
        ws->rdir[ii] = t / ws->r[(ii * n) + ii];
    }
    {
        const ogk_real_t d2 = (q < n) ? qp_norm2(&ws->d[q], n - q) : OGK_R(0.0);
        dir.ztn = d2 * d2;
        dir.d2 = d2;
        dir.dep = (q >= n) || (d2 <= (OGK_QP_DEP_TOL * qp_norm2(ws->d, n))) ||
                  (dir.ztn <= OGK_R(0.0));
    }
    return dir;
}

/* Rotates columns a and b of J (rows of ws->j, which holds J^T):
 * (Ja, Jb) <- (c Ja + s Jb, -s Ja + c Jb). */
static void qp_rotate_j(ogk_qp_workspace_t *ws, size_t n, size_t a, size_t b, /* NOLINT(bugprone-easily-swappable-parameters): order, rows, cosine, sine of a Givens rotation; a swapped pair fails the unit tests (docs/design/qp.md, mutants) */
                        ogk_real_t cs, ogk_real_t sn)
{
    ogk_real_t *ja = &ws->j[a * n];
    ogk_real_t *jb = &ws->j[b * n];
    size_t i;
    for (i = 0u; i < n; ++i) {
        const ogk_real_t va = ja[i];
        const ogk_real_t vb = jb[i];
        ja[i] = (cs * va) + (sn * vb);
        jb[i] = (cs * vb) - (sn * va);
    }
}

/* Adds constraint c with multiplier u_c at position q (d = J^T n_c and
 * z = J2 d2 held). One Householder reflection P = I - v v^T / beta of the
 * columns q..n-1 of J maps d2 onto |d2| e_1 (Golub & Van Loan, Matrix
 * Computations, 4th ed., Algorithm 5.1.1): v = d2 + sigma |d2| e_1,
 * sigma = sign(d2(0)) (no cancellation), beta = sigma |d2| v(0) = v^T v / 2,
 * J2 <- J2 P = J2 - w v^T / beta with w = J2 v = z + sigma |d2| J(:, q), so
 * that the product J2 v costs n operations (z is already there). P d2 =
 * -sigma |d2| e_1: column q of J is negated when sigma > 0 (R's diagonal > 0).
 * About 2 n (n - q) operations instead of the 6 n (n - q) of n - q - 1 Givens
 * rotations (docs/design/qp.md, "Adding a constraint"). */
static void qp_add(qp_state_t *s, size_t c, ogk_real_t u_c, ogk_real_t d2norm) /* NOLINT(bugprone-easily-swappable-parameters): a constraint number, its multiplier and |d2| */
{
    ogk_qp_workspace_t *ws = s->ws;
    const size_t n = s->n;
    const size_t q = s->q;
    ogk_real_t *w = ws->rdir; /* R^-1 d1 is not needed after the step: reused for J2 v */
    size_t i;
    if (((q + 1u) < n) && (d2norm > OGK_R(0.0))) {
        size_t k;
        const ogk_real_t *jq = &ws->j[q * n];
        const ogk_real_t sigma = (ws->d[q] < OGK_R(0.0)) ? -OGK_R(1.0) : OGK_R(1.0);
        const ogk_real_t alpha = sigma * d2norm;
        const ogk_real_t v0 = ws->d[q] + alpha;
        const ogk_real_t inv_beta = OGK_R(1.0) / (alpha * v0);
        for (i = 0u; i < n; ++i) {
            w[i] = (ws->z[i] + (alpha * jq[i])) * inv_beta;
        }
        /* the rows q..n-1 of J^T: row k -= v(k - q) w / beta; v(k - q) = d(k) for k > q */
        ws->d[q] = v0;
        ogk_i_qp_rank1_rows(ws->j, n, q, ws->d, w);
        for (k = q + 1u; k < n; ++k) {
            ws->d[k] = OGK_R(0.0);
        }
        /* P d2 = -alpha e_1: negate column q when sigma > 0 so that R(q, q) = |d2| > 0 */
        if (sigma > OGK_R(0.0)) {
            ogk_real_t *jq_new = &ws->j[q * n];
            for (i = 0u; i < n; ++i) {
                jq_new[i] = -jq_new[i];
            }
        }
        ws->d[q] = d2norm;
    } else if (ws->d[q] < OGK_R(0.0)) {
        /* q = n - 1 (nothing to reflect): only the sign of column q */
        for (i = 0u; i < n; ++i) {
            ws->j[(q * n) + i] = -ws->j[(q * n) + i];
        }
        ws->d[q] = -ws->d[q];
    } else {
        /* d(q) >= 0 already */
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
        const ogk_real_t a = ws->r[(k * n) + k];
        const ogk_real_t b = ws->r[((k + 1u) * n) + k];
        const ogk_real_t h = OGK_HYPOT(a, b);
        if (h > OGK_R(0.0)) {
            /* also when b = 0: a < 0 then gives cs = -1, a positive diagonal */
            const ogk_real_t cs = a / h;
            const ogk_real_t sn = b / h;
            for (i = k; (i + 1u) < q; ++i) {
                const ogk_real_t ra = ws->r[(k * n) + i];
                const ogk_real_t rb = ws->r[((k + 1u) * n) + i];
                ws->r[(k * n) + i] = (cs * ra) + (sn * rb);
                ws->r[((k + 1u) * n) + i] = (cs * rb) - (sn * ra);
            }
            qp_rotate_j(ws, n, k, k + 1u, cs, sn);
        }
        ws->r[((k + 1u) * n) + k] = OGK_R(0.0);
    }
    s->q = q - 1u;
    s->iter += 1u;
}

/* x += t z, u(0..q-1) -= t rdir; inequality multipliers kept >= 0 (rounding). */
static void qp_take_step(const qp_state_t *s, ogk_real_t t)
{
    ogk_qp_workspace_t *ws = s->ws;
    size_t k;
    for (k = 0u; k < s->n; ++k) {
        ws->x[k] += t * ws->z[k];
    }
    for (k = 0u; k < s->q; ++k) {
        ws->u[k] -= t * ws->rdir[k];
        if ((ws->active[k] >= s->k_in) && (ws->u[k] < OGK_R(0.0))) {
            ws->u[k] = OGK_R(0.0);
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
        const ogk_real_t xnorm = qp_norm2(ws->x, s->n);
        ogk_real_t tol;
        ogk_real_t slack;
        qp_dir_t dir;
        ws->eqsign[c] = OGK_R(1.0);
        slack = qp_slack(s, c, xnorm, &tol);
        if (slack > OGK_R(0.0)) {
            ws->eqsign[c] = -OGK_R(1.0);
            slack = -slack;
        }
        dir = qp_direction(s, c);
        if (dir.dep) {
            if (slack < -tol) {
                st = OGK_E_INFEASIBLE;
            }
        } else {
            const ogk_real_t t = -slack / dir.ztn;
            qp_take_step(s, t);
            qp_add(s, c, t, dir.d2);
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
    const ogk_real_t xnorm = qp_norm2(ws->x, s->n);
    size_t best = QP_NONE;
    ogk_real_t worst = OGK_R(0.0);
    size_t k;
    /* the rows: A_in x four rows per pass, then qp_slack's arithmetic on the
     * unit normals (factor 1 / |a|_2) */
    if (m_in > 0u) {
        ogk_i_qp_mat_vec(s->p->A_in, m_in, s->n, false, ws->x, OGK_R(1.0), ws->slack);
    }
    for (k = 0u; k < m_in; ++k) {
        const ogk_real_t scale = ws->rowscale[s->k_in + k];
        const ogk_real_t b = scale * s->p->b_in[k];
        const ogk_real_t slack = (scale * ws->slack[k]) - b;
        ws->slack[k] = (slack >= -(OGK_QP_FEAS_TOL * (OGK_FABS(b) + xnorm))) ? OGK_R(0.0) : slack;
    }
    /* bounds in one pass each, the arithmetic of qp_slack without its
     * dispatch: x_i - lb_i, and (-x_i) - (-ub_i) = ub_i - x_i exactly */
    for (k = 0u; k < s->n; ++k) {
        ogk_real_t lo = OGK_R(0.0);
        ogk_real_t hi = OGK_R(0.0);
        if (qp_has_lb(s->p, k)) {
            const ogk_real_t slack = ws->x[k] - s->p->lb[k];
            lo = (slack >= -(OGK_QP_FEAS_TOL * (OGK_FABS(s->p->lb[k]) + xnorm))) ? OGK_R(0.0) : slack;
        }
        if (qp_has_ub(s->p, k)) {
            const ogk_real_t slack = s->p->ub[k] - ws->x[k];
            hi = (slack >= -(OGK_QP_FEAS_TOL * (OGK_FABS(s->p->ub[k]) + xnorm))) ? OGK_R(0.0) : slack;
        }
        ws->slack[m_in + k] = lo;
        ws->slack[m_in + s->n + k] = hi;
    }
    for (k = 0u; k < s->q; ++k) {
        if (ws->active[k] >= s->k_in) {
            ws->slack[ws->active[k] - s->k_in] = OGK_R(0.0);
        }
    }
    /* the most negative slack, the first on ties (worst starts at 0: only
     * violated constraints qualify); selects instead of branches */
    for (k = 0u; k < total; ++k) {
        const bool better = ws->slack[k] < worst;
        worst = better ? ws->slack[k] : worst;
        best = better ? (s->k_in + k) : best;
    }
    return best;
}

/* One change of the active set for the violated constraint c whose
 * multiplier is *u_c: a full step adds c (*added = true); a partial step, or a
 * dual step when n_c depends on the active set, drops the active inequality
 * whose multiplier reaches zero first. OGK_E_INFEASIBLE when neither exists. */
static ogk_status qp_iterate(qp_state_t *s, size_t c, ogk_real_t *u_c, bool *added)
{
    ogk_qp_workspace_t *ws = s->ws;
    ogk_status st = OGK_OK;
    const qp_dir_t dir = qp_direction(s, c);
    ogk_real_t tol;
    const ogk_real_t slack = qp_slack(s, c, qp_norm2(ws->x, s->n), &tol);
    ogk_real_t t1 = OGK_R(0.0);
    size_t drop = QP_NONE;
    size_t k;
    *added = false;
    for (k = 0u; k < s->q; ++k) {
        if ((ws->active[k] >= s->k_in) && (ws->rdir[k] > OGK_R(0.0))) {
            const ogk_real_t ratio = ws->u[k] / ws->rdir[k];
            if ((drop == QP_NONE) || (ratio < t1)) {
                t1 = ratio;
                drop = k;
            }
        }
    }
    if (dir.dep && (drop == QP_NONE)) {
        st = OGK_E_INFEASIBLE;
    } else if (!dir.dep && ((drop == QP_NONE) || ((-slack / dir.ztn) <= t1))) {
        const ogk_real_t t2 = -slack / dir.ztn;
        qp_take_step(s, t2);
        *u_c += t2;
        qp_add(s, c, *u_c, dir.d2);
        *added = true;
    } else {
        if (dir.dep) {
            (void)memset(ws->z, 0, s->n * sizeof(ogk_real_t)); /* result unused: dual step only */
        }
        qp_take_step(s, t1);
        *u_c += t1;
        ws->u[drop] = OGK_R(0.0);
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
    ogk_real_t u_c = OGK_R(0.0);
    size_t pass;
    for (pass = 0u; (pass <= OGK_QP_MAX_ITER) && running; ++pass) {
        if (c == QP_NONE) {
            c = qp_select(s);
            u_c = OGK_R(0.0);
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
    ogk_qp_workspace_t *ws = s->ws;
    ogk_real_t *hx = ws->d; /* scratch: d is not needed after the last step */
    const ogk_real_t *H = s->p->H;
    const size_t n = s->n;
    ogk_real_t quad = OGK_R(0.0);
    ogk_real_t lin = OGK_R(0.0);
    size_t i;
    size_t k;
    ogk_i_qp_mat_vec(H, n, n, false, ws->x, OGK_R(1.0), hx); /* H x, four rows per pass */
    for (i = 0u; i < n; ++i) {
        quad += ws->x[i] * hx[i];
        lin += s->p->g[i] * ws->x[i];
        sol->x[i] = ws->x[i];
    }
    sol->objective = (OGK_R(0.5) * quad) + lin;
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
        const ogk_real_t norm = qp_norm2(qp_row(s, c), s->n);
        ogk_real_t scale = OGK_R(1.0);
        if (norm > OGK_R(0.0)) {
            scale = OGK_R(1.0) / norm;
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
        /* symmetry (OGK_QP_SYM_TOL) checked in the same pass: OGK_E_NOT_POSDEF too */
        st = ogk_i_qp_cholesky(p->H, p->n, ws->r); /* U = L^T in ws->r until the first add */
    }
    if (st == OGK_OK) {
        ogk_i_qp_inverse_lower(ws->r, p->n, ws->j); /* J^T = L^-1 */
        /* unconstrained start x = -H^-1 g = L^-T (-L^-1 g), by the rows of L^-1 */
        ogk_i_qp_mat_vec(ws->j, p->n, p->n, true, p->g, -OGK_R(1.0), ws->d);
        ogk_i_qp_rows_combine(ws->j, p->n, true, 0u, ws->d, ws->x);
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
