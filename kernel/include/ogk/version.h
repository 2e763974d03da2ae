/* ogk/version.h -- kernel version. */
#ifndef OGK_VERSION_H
#define OGK_VERSION_H

#include "ogk/status.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Numeric version for integrators (compile-time checks, the Python
 * bindings); not used inside the kernel: MISRA deviation D2 (rule 2.5,
 * docs/evidence/misra-deviations.md). */
#define OGK_VERSION_MAJOR 0
#define OGK_VERSION_MINOR 1
#define OGK_VERSION_PATCH 0
#define OGK_VERSION_STRING "0.1.0"

/* *text = OGK_VERSION_STRING. */
ogk_status ogk_version(const char **text);

#ifdef __cplusplus
}
#endif

#endif /* OGK_VERSION_H */
