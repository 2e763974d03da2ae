/* mathutil.c -- shared numerical helpers (ogk/mathutil.h). */
#include "ogk/mathutil.h"

#include <math.h>

#include "../ogk_checks.h"

ogk_status ogk_wrap_pi(ogk_real_t angle, ogk_real_t *wrapped)
{
    ogk_status st;

    if (wrapped == NULL) {
        st = OGK_E_NULL;
    } else if (!isfinite(angle)) {
        st = OGK_E_NONFINITE;
    } else if (OGK_FABS(angle) > OGK_ANGLE_LIMIT) {
        st = OGK_E_RANGE;
    } else {
        *wrapped = ogk_i_wrap_pi(angle);
        st = OGK_OK;
    }
    return st;
}
