/* ogk/real.h -- the kernel's one real type, chosen at compile time.
 *
 * Every floating-point value of the kernel (its API, its contexts, its
 * arithmetic) is an ogk_real_t: double by default, float when the kernel is
 * compiled with -DOGK_REAL_SINGLE=1, for a target whose FPU does single
 * precision only (Cortex-M4F: there every double operation is a call into a
 * software library). One switch for the whole kernel, so that no expression
 * mixes the two types by accident (the float build compiles with
 * -Wdouble-promotion -Wfloat-conversion: make lint-single) and its tables
 * carry the same type (ogk/table.h: OGK_TABLE_F64 or OGK_TABLE_F32).
 *
 * A program that includes the kernel's headers must be compiled with the same
 * define as the library it links (the CMake package and ogk.pc pass it on);
 * ogk_real_bytes (ogk/version.h) tells at run time which type a built library
 * has, so that a binding can refuse a mismatched one.
 *
 * Nothing here is a function: the type, its literals, the <math.h> function of
 * the type for each one the kernel calls, and the type's limits. */
#ifndef OGK_REAL_H
#define OGK_REAL_H

#include <float.h>
#include <math.h>

/* 0: double (the default), 1: float. Any other value is refused: a typo such
 * as -DOGK_REAL_SINGLE=2 must not quietly pick one of the two. */
#ifndef OGK_REAL_SINGLE
#define OGK_REAL_SINGLE 0
#endif
#if (OGK_REAL_SINGLE != 0) && (OGK_REAL_SINGLE != 1)
#error "OGK_REAL_SINGLE must be 0 (double, the default) or 1 (float)"
#endif

/* A literal (or an integer constant) of the real type: OGK_R(0.5). A cast, so
 * the compiler rounds the constant to the type at translation time: nothing is
 * converted at run time, and in the double build the cast of a double literal
 * to double is the identity (the same object code as the bare literal). Not
 * token pasting (0.5 ## f): MISRA C:2012 rule 20.10. */
#define OGK_R(x) ((ogk_real_t)(x))

#if OGK_REAL_SINGLE

/* The float build's tables are IEEE-754 binary32 (OGK_TABLE_F32), read in
 * place where the target stores a float as the file does. */
#if defined(FLT_MANT_DIG) && defined(FLT_MAX_EXP) && \
    ((FLT_MANT_DIG != 24) || (FLT_MAX_EXP != 128))
#error "ogk's single-precision build needs float to be IEEE-754 binary32"
#endif

typedef float ogk_real_t;

/* The limits of the type (<float.h>, <math.h>). */
#define OGK_REAL_EPSILON FLT_EPSILON
#define OGK_REAL_MAX FLT_MAX
#define OGK_REAL_MIN FLT_MIN
#define OGK_REAL_HUGE_VAL HUGE_VALF

/* Magnitudes derived from the type's range, where the kernel needs a "zero
 * for every purpose" or a bound whose square stays finite (each use says why):
 * TINY counts as zero, its reciprocal finite with a wide margin (1e30 here,
 * 1e300 in double); ROOT_TINY and ROOT_BIG are its square root and that of its
 * reciprocal, so a product or quotient of two magnitudes within [ROOT_TINY,
 * ROOT_BIG] lies within [TINY, 1 / TINY]. TINY is about 2^26 above FLT_MIN
 * and 1 / TINY about 2^28 below FLT_MAX, as the double values are about 2^25
 * above DBL_MIN and 2^27 below DBL_MAX. */
#define OGK_REAL_TINY OGK_R(1.0e-30)
#define OGK_REAL_ROOT_TINY OGK_R(1.0e-15)
#define OGK_REAL_ROOT_BIG OGK_R(1.0e15)

/* The <math.h> functions the kernel calls, in the type's own version: no
 * float operand is promoted to double (-Wdouble-promotion). */
#define OGK_ATAN2(y, x) atan2f((y), (x))
#define OGK_CEIL(x) ceilf(x)
#define OGK_COPYSIGN(x, y) copysignf((x), (y))
#define OGK_COS(x) cosf(x)
#define OGK_FABS(x) fabsf(x)
#define OGK_FLOOR(x) floorf(x)
#define OGK_FMAX(x, y) fmaxf((x), (y))
#define OGK_FMIN(x, y) fminf((x), (y))
#define OGK_FMOD(x, y) fmodf((x), (y))
#define OGK_HYPOT(x, y) hypotf((x), (y))
#define OGK_POW(x, y) powf((x), (y))
#define OGK_SIN(x) sinf(x)
#define OGK_SQRT(x) sqrtf(x)
#define OGK_TAN(x) tanf(x)

#else /* double */

typedef double ogk_real_t;

#define OGK_REAL_EPSILON DBL_EPSILON
#define OGK_REAL_MAX DBL_MAX
#define OGK_REAL_MIN DBL_MIN
#define OGK_REAL_HUGE_VAL HUGE_VAL

/* The literals the kernel has always used for these roles (bit for bit). */
#define OGK_REAL_TINY OGK_R(1.0e-300)
#define OGK_REAL_ROOT_TINY OGK_R(1.0e-150)
#define OGK_REAL_ROOT_BIG OGK_R(1.0e150)

#define OGK_ATAN2(y, x) atan2((y), (x))
#define OGK_CEIL(x) ceil(x)
#define OGK_COPYSIGN(x, y) copysign((x), (y))
#define OGK_COS(x) cos(x)
#define OGK_FABS(x) fabs(x)
#define OGK_FLOOR(x) floor(x)
#define OGK_FMAX(x, y) fmax((x), (y))
#define OGK_FMIN(x, y) fmin((x), (y))
#define OGK_FMOD(x, y) fmod((x), (y))
#define OGK_HYPOT(x, y) hypot((x), (y))
#define OGK_POW(x, y) pow((x), (y))
#define OGK_SIN(x) sin(x)
#define OGK_SQRT(x) sqrt(x)
#define OGK_TAN(x) tan(x)

#endif /* OGK_REAL_SINGLE */

#endif /* OGK_REAL_H */
