/* ogk/internal/mpsp_test.h -- test entry points of ogk_mpsp: NOT flight API.
 *
 * One RK4 step of eq. (16) with its Jacobians (Appendix A) and the switching
 * compensation at a switch (eqs. 24-25, Appendix B), for the unit tests'
 * finite-difference checks of the sensitivities (tests/unit/test_mpsp_*.c,
 * test_mpsp_rejections.c, test_mpsp_config_readouts.c) and the Python bindings
 * (bindings/ogk_bindings/mpsp.py; bindings/build_ffi.py declares this header in
 * its TEST_HEADERS list). A flight application includes ogk/mpsp.h only. Why
 * here and not in kernel/src/mpsp/mpsp_internal.h: docs/guides/adding-a-law.md, "Test
 * entry points". */
#ifndef OGK_INTERNAL_MPSP_TEST_H
#define OGK_INTERNAL_MPSP_TEST_H

#include "ogk/mpsp.h"
#include "ogk/status.h"
#include "ogk/real.h"

#ifdef __cplusplus
extern "C" {
#endif

/* One RK4 step of eq. (16) from (t, x) of length dt in mode (0 coast, 1 thrust),
 * thrust T_max * thrust_scale, and its Jacobians (Appendix A with U at the stage
 * times): x_next (8), dfdx = dX_next/dX (8 x 8) and dfdw = dX_next/dW
 * (8 x n_weights). Outputs other than x_next may be NULL. */
ogk_status ogk_mpsp_step_jacobian(const ogk_mpsp_t *ctx, const ogk_real_t *weights,
                                  ogk_real_t thrust_scale, ogk_real_t t, const ogk_real_t *x,
                                  ogk_real_t dt, int mode, ogk_real_t *x_next,
                                  ogk_real_t *dfdx, ogk_real_t *dfdw);

/* Switching compensation at a switch (t_s, x_s) left in mode_before
 * (eqs. 24-25, Appendix B): jx = dX+/dX- (8 x 8), jw = dX+/dW (8 x n_weights,
 * through dU = P(t_s) dW), dts_dx = dt_s/dX- (8) and dts_dw = dt_s/dW
 * (n_weights) from eq. (B.2). Any output may be NULL. OGK_E_SINGULAR when
 * dS/dt = 0 at t_s. */
ogk_status ogk_mpsp_switch_jump(const ogk_mpsp_t *ctx, const ogk_real_t *weights,
                                ogk_real_t thrust_scale, ogk_real_t t_s, const ogk_real_t *x_s,
                                int mode_before, ogk_real_t *jx, ogk_real_t *jw,
                                ogk_real_t *dts_dx, ogk_real_t *dts_dw);

#ifdef __cplusplus
}
#endif

#endif /* OGK_INTERNAL_MPSP_TEST_H */
