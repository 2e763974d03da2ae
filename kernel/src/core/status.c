/* status.c -- names of the kernel status codes. */
#include "ogk/status.h"

#include <stddef.h>

ogk_status ogk_status_name(ogk_status code, const char **name)
{
    /* Indexed by code value; keep in the order of ogk/status.h. */
    static const char *const names[OGK_STATUS_COUNT] = {
        "OGK_OK",
        "OGK_E_NULL",
        "OGK_E_NONFINITE",
        "OGK_E_DIM",
        "OGK_E_RANGE",
        "OGK_E_SINGULAR",
        "OGK_E_ILL_CONDITIONED",
        "OGK_E_NOT_POSDEF",
        "OGK_E_SWITCH_OVERFLOW",
        "OGK_E_STEP_LIMIT",
        "OGK_E_CALLBACK",
        "OGK_E_TABLE_MAGIC",
        "OGK_E_TABLE_VERSION",
        "OGK_E_TABLE_TYPE",
        "OGK_E_TABLE_DIM",
        "OGK_E_TABLE_TRUNCATED",
        "OGK_E_TABLE_SIZE",
        "OGK_E_TABLE_CRC",
        "OGK_E_NOT_INIT",
        "OGK_E_CONFIG",
        "OGK_E_NOT_CONVERGED",
        "OGK_E_SAFE_COMMAND",
        "OGK_E_ALIGN",
        "OGK_E_TABLE_STALE",
        "OGK_E_INFEASIBLE",
        "OGK_E_ITER_LIMIT",
        "OGK_E_FRAME",
        "OGK_E_BYTE_ORDER",
        "OGK_E_OVERFLOW",
    };
    ogk_status st;

    if (name == NULL) {
        st = OGK_E_NULL;
    } else if ((unsigned)code >= (unsigned)OGK_STATUS_COUNT) {
        /* Through unsigned: a negative code wraps to a large index, and the
         * comparison is meaningful whether the enum is int or (AAPCS) a byte. */
        *name = "OGK_E_UNKNOWN";
        st = OGK_E_RANGE;
    } else {
        *name = names[(unsigned)code];
        st = OGK_OK;
    }
    return st;
}
