/* ogk/version.h -- what a built kernel is: its version and its real type. */
#ifndef OGK_VERSION_H
#define OGK_VERSION_H

#include <stdint.h>
#include "ogk/status.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Numeric version for integrators (compile-time checks, the Python
 * bindings); not used inside the kernel: MISRA deviation D2 (rule 2.5,
 * docs/evidence/misra-deviations.md). */
#define OGK_VERSION_MAJOR 0
#define OGK_VERSION_MINOR 1
#define OGK_VERSION_PATCH 1
#define OGK_VERSION_STRING "0.1.1"

/* *text = OGK_VERSION_STRING. */
ogk_status ogk_version(const char **text);

/* *bytes = sizeof(ogk_real_t) of the library (ogk/real.h): 8 when it was built
 * in double (the default), 4 when built with OGK_REAL_SINGLE=1. A caller that
 * did not compile the headers with the library (a binding, a loader of a
 * shared library) asks before passing any real, and refuses a library whose
 * answer is not its own sizeof(ogk_real_t). OGK_E_NULL. */
/*@ requires bytes_valid: bytes == \null || \valid(bytes); */
ogk_status ogk_real_bytes(uint32_t *bytes);

#ifdef __cplusplus
}
#endif

#endif /* OGK_VERSION_H */
