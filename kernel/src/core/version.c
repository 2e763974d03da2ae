/* version.c -- what a built kernel is: its version string and its real type. */
#include "ogk/version.h"

#include <stddef.h>

#include "ogk/real.h"

ogk_status ogk_version(const char **text)
{
    ogk_status st;

    if (text == NULL) {
        st = OGK_E_NULL;
    } else {
        *text = OGK_VERSION_STRING;
        st = OGK_OK;
    }
    return st;
}

ogk_status ogk_real_bytes(uint32_t *bytes)
{
    ogk_status st;

    if (bytes == NULL) {
        st = OGK_E_NULL;
    } else {
        /* the library's own type, as compiled: the answer a caller checks
         * against the sizeof(ogk_real_t) it was compiled with */
        *bytes = (uint32_t)sizeof(ogk_real_t);
        st = OGK_OK;
    }
    return st;
}
