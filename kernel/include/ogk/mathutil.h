/* ogk/mathutil.h -- small numerical helpers shared by every law. */
#ifndef OGK_MATHUTIL_H
#define OGK_MATHUTIL_H

#include "ogk/status.h"
#include "ogk/real.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Inputs whose magnitude exceeds this are rejected (OGK_E_RANGE) by the
 * angle-taking functions: beyond it sin/cos argument reduction of a double no
 * longer resolves 1e-9 rad, and no navigation filter produces such angles
 * except by a fault. [rad] */
#define OGK_ANGLE_LIMIT OGK_R(1.0e4)

/* *wrapped = angle + 2 pi k in (-pi, pi]; exact (the angle itself) for angle
 * in (-pi, pi]. OGK_E_NULL, OGK_E_NONFINITE, OGK_E_RANGE (|angle| >
 * OGK_ANGLE_LIMIT). The one wrap every law uses (kernel/src/ogk_checks.h). */
/*@ requires wrapped_valid: wrapped == \null || \valid(wrapped); */
ogk_status ogk_wrap_pi(ogk_real_t angle, ogk_real_t *wrapped);

#ifdef __cplusplus
}
#endif

#endif /* OGK_MATHUTIL_H */
