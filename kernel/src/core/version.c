/* version.c -- kernel version string. */
#include "ogk/version.h"

#include <stddef.h>

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
