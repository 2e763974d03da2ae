/* ogk_checks.h -- internal helpers shared by every law (not public API): the
 * finite check of an input vector, the unchecked angle wrap behind
 * ogk_wrap_pi (ogk/mathutil.h) and the clamp of a loop dimension to its
 * bound. static inline so the hot paths pay no call. */
#ifndef OGK_CHECKS_H
#define OGK_CHECKS_H

#include <math.h>
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "ogk/real.h"

#define OGK_I_PI OGK_R(3.14159265358979323846)
#define OGK_I_TWO_PI OGK_R(6.28318530717958647692)

/* true when v[0..n-1] are all finite (n = 0: true). */
static inline bool ogk_i_all_finite(const ogk_real_t *v, size_t n)
{
    bool finite = true;
    size_t i;
    for (i = 0u; (i < n) && finite; ++i) {
        if (!isfinite(v[i])) {
            finite = false;
        }
    }
    return finite;
}

/* min(n, bound): a loop's dimension clamped once to its compile-time bound
 * before the loop, so the loop keeps a fixed bound with one condition (the
 * dimension was checked against the bound at init: MC/DC could never show a
 * second `k < BOUND` operand, docs/evidence/mcdc-exceptions.md). */
static inline size_t ogk_i_min_size(size_t n, size_t bound)
{
    return (n < bound) ? n : bound;
}

static inline uint32_t ogk_i_min_u32(uint32_t n, uint32_t bound)
{
    return (n < bound) ? n : bound;
}

/* angle + 2 pi k in (-pi, pi], angle finite. fmod is exact, so an angle
 * already in (-pi, pi] comes back unchanged; otherwise one rounding of the
 * +-2 pi correction. */
static inline ogk_real_t ogk_i_wrap_pi(ogk_real_t angle)
{
    ogk_real_t w = OGK_FMOD(angle, OGK_I_TWO_PI);
    if (w > OGK_I_PI) {
        w -= OGK_I_TWO_PI;
    } else if (w <= -OGK_I_PI) {
        w += OGK_I_TWO_PI;
    } else {
        /* already in (-pi, pi] */
    }
    return w;
}

#endif /* OGK_CHECKS_H */
