/* mathutil.c -- shared numerical helpers (ogk/mathutil.h). */
#include "ogk/mathutil.h"

#include <math.h>

#include "ogk_checks.h"

ogk_status ogk_wrap_pi(double angle, double *wrapped)
{
    if (wrapped == NULL) {
        return OGK_E_NULL;
    }
    if (!isfinite(angle)) {
        return OGK_E_NONFINITE;
    }
    if (fabs(angle) > OGK_ANGLE_LIMIT) {
        return OGK_E_RANGE;
    }
    *wrapped = ogk_i_wrap_pi(angle);
    return OGK_OK;
}
