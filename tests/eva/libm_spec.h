/* tests/eva/libm_spec.h -- ACSL contracts for the libm functions the kernel
 * calls that Frama-C 25's libc leaves without a specification (hypot, fmax,
 * fmin, copysign: EVA would otherwise take their result as any double,
 * NaN and infinities included, and every finite check after them would
 * alarm). Each contract states C99 7.12 / IEEE 754 behaviour for finite
 * arguments; a NaN or infinite argument is outside the requires, so EVA
 * reports a call that could pass one. Included by every driver (analysis
 * only: never compiled into the kernel). */
#ifndef OGK_EVA_LIBM_SPEC_H
#define OGK_EVA_LIBM_SPEC_H

#include <math.h>

/* sqrt(x^2 + y^2) without undue overflow (C99 7.12.7.3): at least the
 * larger magnitude, at most their sum; finite while the sum is (2^1022
 * bounds each term so the sum cannot overflow). */
/*@ requires finite_args: \is_finite(x) && \is_finite(y);
    requires no_overflow: -0x1p1022 <= x <= 0x1p1022 && -0x1p1022 <= y <= 0x1p1022;
    assigns \result \from x, y;
    ensures finite_result: \is_finite(\result);
    ensures positive_result: \result >= 0.;
    ensures lower_x: \result >= \abs(x);
    ensures lower_y: \result >= \abs(y);
    ensures upper: \result <= \abs(x) + \abs(y);
*/
extern double hypot(double x, double y);

/* The larger (C99 7.12.12.2) of two finite numbers: one of them, at least
 * both. (EVA does not use behaviours' \result == x, so the bounds are
 * stated unconditionally.) */
/*@ requires finite_args: \is_finite(x) && \is_finite(y);
    assigns \result \from x, y;
    ensures finite_result: \is_finite(\result);
    ensures lower_x: \result >= x;
    ensures lower_y: \result >= y;
    ensures upper: \result <= \max(x, y);
    ensures one_of: \result == x || \result == y;
*/
extern double fmax(double x, double y);

/* The smaller (C99 7.12.12.3) of two finite numbers: one of them, at most
 * both. */
/*@ requires finite_args: \is_finite(x) && \is_finite(y);
    assigns \result \from x, y;
    ensures finite_result: \is_finite(\result);
    ensures upper_x: \result <= x;
    ensures upper_y: \result <= y;
    ensures lower: \result >= \min(x, y);
    ensures one_of: \result == x || \result == y;
*/
extern double fmin(double x, double y);

/* |x| with the sign of y (C99 7.12.11.1): +-|x|, finite for a finite x. */
/*@ requires finite_x: \is_finite(x);
    requires not_nan_y: !\is_NaN(y);
    assigns \result \from x, y;
    ensures finite_result: \is_finite(\result);
    ensures magnitude: -\abs(x) <= \result <= \abs(x);
    ensures sign: \result == \abs(x) || \result == -\abs(x);
*/
extern double copysign(double x, double y);

#endif /* OGK_EVA_LIBM_SPEC_H */
