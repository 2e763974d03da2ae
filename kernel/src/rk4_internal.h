/* rk4_internal.h -- the one source of the classical RK4 step's arithmetic
 * (Butcher tableau c = 0, 1/2, 1/2, 1; b = 1/6, 1/3, 1/3, 1/6): the stage
 * states and the step's weighted sum, for a state and for its forward
 * sensitivities alike. Used by rk4.c (ogk_rk4_step, MPSP's propagation),
 * mpsp_adjoint.c (the stage states of that step, again), nmpc_shoot.c (the
 * NMPC interval and its sensitivities) and blt_arc.c (the BLT arcs and their
 * variational equations); each user brings its dynamics. static inline: the
 * NMPC's and MPSP's inner loops pay no call.
 * Internal to the kernel. */
#ifndef OGK_RK4_INTERNAL_H
#define OGK_RK4_INTERNAL_H

#include <stddef.h>

#include "ogk/real.h"

/* The tableau: stage j's offset c_j (fraction of the step) and its weight
 * 6 b_j (1, 2, 2, 1), j = 0..3. */
static inline ogk_real_t ogk_i_rk4_c(size_t j)
{
    static const ogk_real_t c[4] = {OGK_R(0.0), OGK_R(0.5), OGK_R(0.5), OGK_R(1.0)};
    return c[j];
}

static inline ogk_real_t ogk_i_rk4_w6(size_t j)
{
    static const ogk_real_t w6[4] = {OGK_R(1.0), OGK_R(2.0), OGK_R(2.0), OGK_R(1.0)};
    return w6[j];
}

/* One entry of a stage state y = x + c k_prev (c = dt/2, dt/2, dt for stages
 * 2-4; the first stage is at x itself). */
static inline ogk_real_t ogk_i_rk4_stage_entry(ogk_real_t x, ogk_real_t c, ogk_real_t k_prev)
{
    return x + (c * k_prev);
}

/* One entry of the step x + b6 (k1 + 2 k2 + 2 k3 + k4), b6 = dt/6 (or a
 * derivative's: NMPC's d/dh), the sum from the left. Used where x is the
 * state or a sensitivity that starts at +0 or 1 and only ever has terms
 * added (never -0: then x + (+0) and x + (-0) are the same bits, so a sum
 * begun at 0.0, as NMPC's once was, gives the same step). */
static inline ogk_real_t ogk_i_rk4_step_entry(ogk_real_t x, ogk_real_t b6, ogk_real_t k1, ogk_real_t k2, ogk_real_t k3, ogk_real_t k4) /* NOLINT(bugprone-easily-swappable-parameters): the terms in order */
{
    return x + (b6 * (((k1 + (OGK_R(2.0) * k2)) + (OGK_R(2.0) * k3)) + k4));
}

/* The loops over n entries. One entry per iteration: the Cortex-M7 has no
 * double SIMD and this is its shortest loop (BLT's arcs measured 4.7 % more
 * instructions by pairs). y may be x, not k_prev. */
static inline void ogk_i_rk4_stage_state(const ogk_real_t *x, ogk_real_t c, const ogk_real_t *k_prev, size_t n, ogk_real_t *y) /* NOLINT(bugprone-easily-swappable-parameters): the terms of y = x + c k in order */
{
    size_t i;
    for (i = 0u; i < n; ++i) {
        y[i] = ogk_i_rk4_stage_entry(x[i], c, k_prev[i]);
    }
}

static inline void ogk_i_rk4_accumulate(ogk_real_t *x, const ogk_real_t *k1, const ogk_real_t *k2, const ogk_real_t *k3, /* NOLINT(bugprone-easily-swappable-parameters): the stages in order */
                                        const ogk_real_t *k4, ogk_real_t b6, size_t n) /* NOLINT(bugprone-easily-swappable-parameters): as above */
{
    size_t i;
    for (i = 0u; i < n; ++i) {
        x[i] = ogk_i_rk4_step_entry(x[i], b6, k1[i], k2[i], k3[i], k4[i]);
    }
}

/* The same over the entries lo .. lo + n - 1 by pairs (n even), each
 * array indexed from its own start: where the arrays are the NMPC's local
 * sensitivity matrices (rows of even stride, not overlapping), gcc -O2
 * computes each pair with one packed operation on x86-64, and the
 * Cortex-M7 addresses them from one index (nmpc_shoot.c). */
static inline void ogk_i_rk4_stage_state_pairs(const ogk_real_t *x, ogk_real_t c, const ogk_real_t *k_prev, size_t lo, size_t n, /* NOLINT(bugprone-easily-swappable-parameters): as ogk_i_rk4_stage_state, then the range */
                                               ogk_real_t *y)
{
    size_t i;
    for (i = 0u; i < n; i += 2u) {
        y[lo + i] = ogk_i_rk4_stage_entry(x[lo + i], c, k_prev[lo + i]);
        y[lo + i + 1u] = ogk_i_rk4_stage_entry(x[lo + i + 1u], c, k_prev[lo + i + 1u]);
    }
}

static inline void ogk_i_rk4_accumulate_pairs(ogk_real_t *x, const ogk_real_t *k1, const ogk_real_t *k2, const ogk_real_t *k3, /* NOLINT(bugprone-easily-swappable-parameters): as ogk_i_rk4_accumulate */
                                              const ogk_real_t *k4, ogk_real_t b6, size_t lo, size_t n) /* NOLINT(bugprone-easily-swappable-parameters): as above */
{
    size_t i;
    for (i = 0u; i < n; i += 2u) {
        const size_t e = lo + i;
        const ogk_real_t xa = ogk_i_rk4_step_entry(x[e], b6, k1[e], k2[e], k3[e], k4[e]);
        const ogk_real_t xb = ogk_i_rk4_step_entry(x[e + 1u], b6, k1[e + 1u], k2[e + 1u], k3[e + 1u], k4[e + 1u]);
        x[e] = xa;
        x[e + 1u] = xb;
    }
}

/* ogk_rk4_step's step x_next = x + (dt/6) (k1 + 2 (k2 + k3) + k4): the
 * middle stages summed first. This grouping is not that of
 * ogk_i_rk4_accumulate (the sums differ in the last bit), and MPSP's
 * propagation, its dense output and its adjoint (mpsp_adjoint.c) are built
 * on it: it stays the public stepper's, unchanged. x_next may alias x. */
static inline void ogk_i_rk4_next_grouped(const ogk_real_t *x, const ogk_real_t *k1, const ogk_real_t *k2, const ogk_real_t *k3, /* NOLINT(bugprone-easily-swappable-parameters): the stages in order */
                                          const ogk_real_t *k4, ogk_real_t dt, size_t n, ogk_real_t *x_next) /* NOLINT(bugprone-easily-swappable-parameters): as above */
{
    size_t i;
    for (i = 0u; i < n; ++i) {
        x_next[i] = x[i] + ((dt / OGK_R(6.0)) * (k1[i] + (OGK_R(2.0) * (k2[i] + k3[i])) + k4[i]));
    }
}

#endif /* OGK_RK4_INTERNAL_H */
