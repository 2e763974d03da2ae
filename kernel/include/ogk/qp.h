/* ogk/qp.h -- dense strictly convex quadratic programming (the QP of the
 * NMPC's SQP, ogk/nmpc.h), by the dual active-set method of Goldfarb & Idnani
 * (Math. Programming 27, 1983). Design and measured cost: docs/design/qp.md.
 *
 *   minimise    1/2 x^T H x + g^T x
 *   subject to  A_eq x  = b_eq          (m_eq rows)
 *               A_in x >= b_in          (m_in rows)
 *               lb <= x <= ub           (per variable; +-OGK_QP_INF: no bound)
 *
 * H must be symmetric positive definite (OGK_E_NOT_POSDEF otherwise: the
 * caller regularises). Optimality conditions returned with the solution:
 *   H x + g = A_eq^T y_eq + A_in^T y_in + z_lb - z_ub,
 *   y_in >= 0, z_lb >= 0, z_ub >= 0, complementary with their constraints.
 * Matrices are row-major (element (i, j) of an r x c matrix is A[i * c + j]).
 * All workspace lives in a caller-owned ogk_qp_workspace_t: no heap, no
 * globals, every loop bounded by the OGK_QP_MAX_* limits below. */
#ifndef OGK_QP_H
#define OGK_QP_H

#include <stddef.h>
#include <stdint.h>
#include "ogk/status.h"
#include "ogk/real.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Largest number of variables. */
#ifndef OGK_QP_MAX_N
#define OGK_QP_MAX_N 80u
#endif
/* Largest number of equality rows. */
#ifndef OGK_QP_MAX_EQ
#define OGK_QP_MAX_EQ 8u
#endif
/* Largest number of general inequality rows (bounds are extra). */
#ifndef OGK_QP_MAX_IN
#define OGK_QP_MAX_IN 140u
#endif

/* A bound of this magnitude or more (either sign) means "no bound". */
#define OGK_QP_INF OGK_R(1.0e20)

/* Largest number of active-set changes of one solve (fixed loop bound). */
#define OGK_QP_MAX_ITER ((4u * (OGK_QP_MAX_N + OGK_QP_MAX_EQ + OGK_QP_MAX_IN)) + 16u)

typedef struct {
    size_t n;              /* [-] variables, 1..OGK_QP_MAX_N */
    size_t m_eq;           /* [-] equality rows, 0..OGK_QP_MAX_EQ, <= n */
    size_t m_in;           /* [-] general inequality rows, 0..OGK_QP_MAX_IN */
    const ogk_real_t *H;       /* [-] n x n, symmetric positive definite (both triangles read) */
    const ogk_real_t *g;       /* [-] n, linear term */
    const ogk_real_t *A_eq;    /* [-] m_eq x n (NULL when m_eq = 0) */
    const ogk_real_t *b_eq;    /* [-] m_eq (NULL when m_eq = 0) */
    const ogk_real_t *A_in;    /* [-] m_in x n (NULL when m_in = 0) */
    const ogk_real_t *b_in;    /* [-] m_in (NULL when m_in = 0) */
    const ogk_real_t *lb;      /* [-] n lower bounds, <= -OGK_QP_INF for none; NULL: none at all */
    const ogk_real_t *ub;      /* [-] n upper bounds, >= +OGK_QP_INF for none; NULL: none at all */
} ogk_qp_problem_t;

typedef struct {
    ogk_real_t x[OGK_QP_MAX_N];       /* [-] minimiser (n entries used) */
    ogk_real_t y_eq[OGK_QP_MAX_EQ];   /* [-] equality multipliers (m_eq) */
    ogk_real_t y_in[OGK_QP_MAX_IN];   /* [-] inequality multipliers, >= 0 (m_in) */
    ogk_real_t z_lb[OGK_QP_MAX_N];    /* [-] lower-bound multipliers, >= 0 (n) */
    ogk_real_t z_ub[OGK_QP_MAX_N];    /* [-] upper-bound multipliers, >= 0 (n) */
    ogk_real_t objective;             /* [-] 1/2 x^T H x + g^T x at x */
    size_t iterations;            /* [-] constraints added to or dropped from the active set */
    size_t n_active;              /* [-] active constraints at the solution, equalities included */
} ogk_qp_solution_t;

/* Numerical tolerances (all relative; docs/design/qp.md):
 * FEAS  a constraint a^T x >= b (or a bound, a = +-e_i) is violated when
 *       a^T x - b < -OGK_QP_FEAS_TOL (|b| + |a|_2 |x|_2); a dependent equality
 *       row is consistent when |a^T x - b| is within the same tolerance;
 * DEP   a constraint normal n is linearly dependent on the active set when
 *       |J2^T n|_2 <= OGK_QP_DEP_TOL |J^T n|_2 (its part outside the active
 *       span, in the metric of H^-1, is negligible);
 * PIVOT H is not positive definite when a Cholesky pivot d_jj^2 is
 *       <= OGK_QP_PIVOT_TOL H_jj (or H_jj <= 0);
 * SYM   H is not symmetric when |H_ij - H_ji| > OGK_QP_SYM_TOL max |H_kl|
 *       (OGK_E_NOT_POSDEF); the factored matrix is (H + H^T) / 2. */
#if OGK_REAL_SINGLE
/* The float build's values, multiples of FLT_EPSILON (eps = 1.19e-7; the
 * double values, 4.5e3 to 4.5e5 DBL_EPSILON, are below float's resolution and
 * made float answer OK with a wrong x; docs/design/qp.md, "Tolerances"):
 * FEAS  64 eps = 7.6e-6: the slack of a constraint the solve made active
 *       (or satisfies degenerately) carries the rounding of x, measured up to
 *       1.5e-6 (|b| + |x|) (13 eps) in the unit tests: x5 above it;
 * DEP   128 eps = 1.5e-5: the part of J^T n outside the active span is
 *       rounding when n depends on the active set: measured 0.25 eps |d|, up
 *       to about n eps |d| for the Householder updates (80 eps at
 *       OGK_QP_MAX_N): x1.6 above that bound. 1024 eps made the elastic
 *       keep-out QP of test_proximity OGK_E_INFEASIBLE on the M4F (a row
 *       independent of the active set taken as dependent);
 * PIVOT 64 eps = 7.6e-6: the rounding of a Cholesky pivot d_jj^2 is j eps
 *       H_jj at worst, about sqrt(j) eps typically; below 64 eps H_jj a pivot
 *       is rounding, not information, and its inverse is not H's;
 * SYM   64 eps = 7.6e-6: an H computed symmetrically (the BFGS and exact
 *       Hessians of the NMPC) differs from its transpose by a few eps max |H|
 *       through the order of its sums. */
#define OGK_QP_FEAS_TOL (OGK_R(64.0) * OGK_REAL_EPSILON)
#define OGK_QP_DEP_TOL (OGK_R(128.0) * OGK_REAL_EPSILON)
#define OGK_QP_PIVOT_TOL (OGK_R(64.0) * OGK_REAL_EPSILON)
#define OGK_QP_SYM_TOL (OGK_R(64.0) * OGK_REAL_EPSILON)
#else
#define OGK_QP_FEAS_TOL OGK_R(1.0e-12)
#define OGK_QP_DEP_TOL OGK_R(1.0e-10)
#define OGK_QP_PIVOT_TOL OGK_R(1.0e-12)
#define OGK_QP_SYM_TOL OGK_R(1.0e-12)
#endif

/* Workspace of one solve; reusable, never read before it is written.
 * Constraints are numbered: equality rows 0..m_eq-1, inequality rows
 * m_eq..m_eq+m_in-1, lower bounds m_eq+m_in+i, upper bounds m_eq+m_in+n+i. */
typedef struct {
    ogk_real_t j[OGK_QP_MAX_N * OGK_QP_MAX_N];   /* [-] J^T = Q^T L^-1, row-major n x n (row k: column k of J) */
    ogk_real_t r[OGK_QP_MAX_N * OGK_QP_MAX_N];   /* [-] Cholesky factor U = L^T of H during setup, then the upper-triangular R of the active set (row stride n) */
    ogk_real_t x[OGK_QP_MAX_N];                  /* [-] primal iterate */
    ogk_real_t d[OGK_QP_MAX_N];                  /* [-] J^T n of the constraint being added */
    ogk_real_t z[OGK_QP_MAX_N];                  /* [-] primal step direction J2 J2^T n */
    ogk_real_t rdir[OGK_QP_MAX_N];               /* [-] dual step direction R^-1 J1^T n; then J2 v / beta of the Householder update that adds n */
    ogk_real_t u[OGK_QP_MAX_N];                  /* [-] multipliers of the active set, in R's column order */
    size_t active[OGK_QP_MAX_N];             /* [-] constraint numbers of the active set, in R's column order */
    ogk_real_t slack[OGK_QP_MAX_IN + (2u * OGK_QP_MAX_N)]; /* [-] a^T x - b of the inequality rows and bounds (0: active or no bound) */
    ogk_real_t rowscale[OGK_QP_MAX_EQ + OGK_QP_MAX_IN];  /* [-] 1 / |a|_2 of the rows of A_eq, then A_in (1 for a zero row): rows are handled as unit normals */
    ogk_real_t eqsign[OGK_QP_MAX_EQ];            /* [-] +-1: the sign with which each equality row was made active */
} ogk_qp_workspace_t;

/* Solves the QP. Returns OGK_OK with the solution, or:
 * OGK_E_NULL (a required pointer), OGK_E_DIM (a dimension out of range),
 * OGK_E_NONFINITE (NaN/Inf in H, g, A, b, or a NaN bound; also a solution
 * that overflowed), OGK_E_RANGE (lb > ub for some variable),
 * OGK_E_NOT_POSDEF (H not symmetric or not positive definite to working
 * precision: OGK_QP_SYM_TOL, OGK_QP_PIVOT_TOL),
 * OGK_E_INFEASIBLE (the constraints admit no point: a violated constraint
 * that can be made active neither by a primal nor by a dual step),
 * OGK_E_ITER_LIMIT (OGK_QP_MAX_ITER active-set changes reached).
 * Equality rows are made active first, in order, and never dropped; a row
 * linearly dependent on the rows before it (OGK_QP_DEP_TOL) is skipped when
 * it is consistent with them (OGK_QP_FEAS_TOL; its multiplier is then 0) and
 * gives OGK_E_INFEASIBLE when it conflicts. Bounds with lb == ub fix a variable.
 * On any error sol->x holds zeros and the multipliers are zero (sol->iterations
 * still counts the active-set changes of an OGK_E_INFEASIBLE or
 * OGK_E_ITER_LIMIT solve). */
ogk_status ogk_qp_solve(ogk_qp_workspace_t *ws, const ogk_qp_problem_t *p,
                        ogk_qp_solution_t *sol);

#ifdef __cplusplus
}
#endif

#endif /* OGK_QP_H */
