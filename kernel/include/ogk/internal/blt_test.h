/* ogk/internal/blt_test.h -- test entry points of ogk_blt: NOT flight API.
 *
 * The corrector's Jacobian on its own, for the unit tests' checks of the
 * variational Jacobian against central differences (tests/unit/blt/test_blt.c,
 * test_blt_failure_paths.c) and the Python bindings (bindings/ogk_bindings/blt.py;
 * bindings/build_ffi.py declares this header in its TEST_HEADERS list). A
 * flight application includes ogk/blt.h only. Why here and not in
 * kernel/src/blt/blt_internal.h: docs/guides/adding-a-law.md, "Test entry points". */
#ifndef OGK_INTERNAL_BLT_TEST_H
#define OGK_INTERNAL_BLT_TEST_H

#include <stddef.h>
#include "ogk/blt.h"
#include "ogk/status.h"
#include "ogk/real.h"

#ifdef __cplusplus
extern "C" {
#endif

/* J = de/du at `tr` (n_errors x n_unknowns, row-major into jac[0 .. n_errors * n_unknowns - 1])
 * with the configured Jacobian; the unknowns' order: free start components, then each segment's
 * free parameters (A, B, T), then each free node's six components. */
ogk_status ogk_blt_jacobian(ogk_blt_t *ctx, const ogk_blt_transfer_t *tr, ogk_real_t *jac,
                            size_t jac_len);

#ifdef __cplusplus
}
#endif

#endif /* OGK_INTERNAL_BLT_TEST_H */
