/* ogk/status.h -- status codes returned by every public kernel function.
 *
 * Also the kernel's floating-point evaluation guard: every kernel header
 * includes this one, so every kernel and application translation unit sees it. */
#ifndef OGK_STATUS_H
#define OGK_STATUS_H

#include <float.h>

/* The kernel's boundary checks (a value against its bound, a step landing
 * exactly on a node or a cut-off) assume that every real expression is
 * evaluated in its own type, double in double and float in float (ogk/real.h;
 * C99 5.2.4.2.2, FLT_EVAL_METHOD 0). With excess
 * precision (x87 without SSE: FLT_EVAL_METHOD 2) the same source gives other
 * answers at those boundaries (issue 22: 8 unit tests fail), so such a build
 * is refused here rather than flown (docs/guides/ports.md, "Floating-point
 * evaluation"). A C99 <float.h> always defines the macro; testing defined()
 * first only spares analysers that read no system header (cppcheck), which
 * would otherwise stop at the #error and report nothing. */
#if defined(FLT_EVAL_METHOD) && (FLT_EVAL_METHOD != 0)
#error "ogk needs FLT_EVAL_METHOD == 0 (double evaluated as double); x87: build with -msse2 -mfpmath=sse"
#endif
/* double must be IEEE-754 binary64 (the element type of F64 tables; ogk/real.h
 * checks float, the element of F32 tables, in the float build). */
#if defined(DBL_MANT_DIG) && defined(DBL_MAX_EXP) && \
    ((DBL_MANT_DIG != 53) || (DBL_MAX_EXP != 1024))
#error "ogk needs double to be IEEE-754 binary64"
#endif

#ifdef __cplusplus
extern "C" {
#endif

/* Keep OGK_STATUS_COUNT last; codes are stable across versions (append only). */
typedef enum {
    OGK_OK = 0,                 /* success */
    OGK_E_NULL = 1,             /* a required pointer argument is NULL */
    OGK_E_NONFINITE = 2,        /* NaN or Inf in an input */
    OGK_E_DIM = 3,              /* a dimension is zero, too large, or inconsistent */
    OGK_E_RANGE = 4,            /* a scalar argument is outside its valid range */
    OGK_E_SINGULAR = 5,         /* matrix is singular to working precision */
    OGK_E_ILL_CONDITIONED = 6,  /* matrix is invertible but its condition number is too large */
    OGK_E_NOT_POSDEF = 7,       /* matrix is not symmetric positive definite */
    OGK_E_SWITCH_OVERFLOW = 8,  /* more switching events than the result can hold */
    OGK_E_STEP_LIMIT = 9,       /* propagation needs more steps than OGK_RK4_MAX_STEPS */
    OGK_E_CALLBACK = 10,        /* a user callback returned a failure */
    OGK_E_TABLE_MAGIC = 11,     /* table buffer does not start with the table magic */
    OGK_E_TABLE_VERSION = 12,   /* unsupported table format version */
    OGK_E_TABLE_TYPE = 13,      /* unsupported element type (also the other precision's: ogk/table.h) or table kind */
    OGK_E_TABLE_DIM = 14,       /* table dimensions differ from what the caller expects */
    OGK_E_TABLE_TRUNCATED = 15, /* buffer shorter than the header says */
    OGK_E_TABLE_SIZE = 16,      /* buffer longer than the header says, or sizes overflow */
    OGK_E_TABLE_CRC = 17,       /* CRC-32 mismatch (header or payload corrupted) */
    OGK_E_NOT_INIT = 18,        /* context used before a successful init */
    OGK_E_CONFIG = 19,          /* configuration rejected at init */
    OGK_E_NOT_CONVERGED = 20,   /* an iteration did not converge within its bound */
    OGK_E_SAFE_COMMAND = 21,    /* no correction computed: output holds the defined safe command */
    OGK_E_ALIGN = 22,           /* buffer not aligned as the in-place reader requires */
    OGK_E_TABLE_STALE = 23,     /* the table a context is bound to was reloaded since init: re-init */
    OGK_E_INFEASIBLE = 24,      /* a constrained subproblem (QP) has no feasible point */
    OGK_E_ITER_LIMIT = 25,      /* an iterative solver reached its iteration bound before its tolerance */
    OGK_E_FRAME = 26,           /* a thrust command's frame is unknown, or one the consumer cannot convert */
    OGK_E_BYTE_ORDER = 27,      /* the target's ogk_real_t is not the file's little-endian element: cannot read in place */
    OGK_E_OVERFLOW = 28,        /* a result would exceed its documented bound (linalg: OGK_LA_SOLVE_MAX); not computed */
    OGK_STATUS_COUNT = 29
} ogk_status;

/* Stores in *name the code's identifier ("OGK_E_DIM", ...). Unknown codes
 * give "OGK_E_UNKNOWN" and return OGK_E_RANGE. */
/*@ requires name_valid: name == \null || \valid(name); */
ogk_status ogk_status_name(ogk_status code, const char **name);

#ifdef __cplusplus
}
#endif

#endif /* OGK_STATUS_H */
