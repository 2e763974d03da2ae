/* version.c -- kernel version string. */
#include "ogk/version.h"

#include <stddef.h>

ogk_status ogk_version(const char **text)
{
    if (text == NULL) {
        return OGK_E_NULL;
    }
    *text = OGK_VERSION_STRING;
    return OGK_OK;
}
