/* ogk/internal/nmpc_test.h -- test entry points of ogk_nmpc: NOT flight API.
 *
 * The predictive model's right-hand side and one shooting interval with its
 * sensitivities, for the unit tests' closed-form and finite-difference checks
 * (tests/unit/test_nmpc.c, test_gate_nmpc.c) and the Python bindings'
 * cross-checks (bindings/ogk_bindings/nmpc.py; bindings/build_ffi.py declares
 * this header in its TEST_HEADERS list). A flight application includes
 * ogk/nmpc.h only. Why here and not in kernel/src/nmpc/nmpc_internal.h:
 * docs/guides/adding-a-law.md, "Test entry points". */
#ifndef OGK_INTERNAL_NMPC_TEST_H
#define OGK_INTERNAL_NMPC_TEST_H

#include "ogk/nmpc.h"
#include "ogk/status.h"
#include "ogk/real.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Right-hand side of the predictive model at (t, x, u) (for tests and the
 * harness's cross-checks); u has the engine's nu entries. */
ogk_status ogk_nmpc_model_rhs(const ogk_nmpc_t *ctx, ogk_real_t t, const ogk_real_t *x,
                              const ogk_real_t *u, ogk_real_t *xdot);

/* One subinterval F(x0, u0, u1) of length h starting at absolute time t0,
 * with its sensitivities (each may be NULL): dfdx (5 x 5), dfdu0 and dfdu1
 * (5 x nu), dfdh (5, t0 held) and dfdt0 (5, h held): for the tests'
 * finite-difference checks. */
ogk_status ogk_nmpc_interval(const ogk_nmpc_t *ctx, ogk_real_t t0, ogk_real_t h,
                             const ogk_real_t *x0, const ogk_real_t *u0,
                             const ogk_real_t *u1, ogk_real_t *x1, ogk_real_t *dfdx,
                             ogk_real_t *dfdu0, ogk_real_t *dfdu1, ogk_real_t *dfdh,
                             ogk_real_t *dfdt0);

/* The second derivatives of the same subinterval weighted by w (5):
 * hess = sum_i w_i d2F_i/dp2, p = (x0 (5), u0 (nu), u1 (nu), h, t0), a
 * symmetric (5 + 2 nu + 2)-square row-major matrix (the exact SQP Hessian's
 * per-interval block), for the tests' finite-difference checks of
 * w . dF/dp. Uses the context's tape (hence not const). */
ogk_status ogk_nmpc_interval_hess(ogk_nmpc_t *ctx, ogk_real_t t0, ogk_real_t h,
                                  const ogk_real_t *x0, const ogk_real_t *u0,
                                  const ogk_real_t *u1, const ogk_real_t *w,
                                  ogk_real_t *hess);

#ifdef __cplusplus
}
#endif

#endif /* OGK_INTERNAL_NMPC_TEST_H */
