/* nmpc_shoot.c -- one multiple-shooting interval of the NMPC: fixed-step RK4
 * with the control linear over the interval and evaluated at the stage times
 * (sec. 2.3 of Starek & Kolmanovsky), and the exact derivatives of this
 * discrete map (internal numerical differentiation: the RK4 recursion
 * differentiated stage by stage), so the SQP's linearisation is that of the
 * map it constrains; with a tape, the forward sweep records what the
 * second-order adjoint sweep (nmpc_shoot_hess.c) reads back. */
#include "nmpc_internal.h"
#include "../rk4_internal.h"
#include "../ogk_checks.h"

#include <math.h>
#include <stdbool.h>
#include <string.h>

#define NX ((size_t)OGK_NMPC_NX)
#define NCOL OGK_I_NMPC_NCOL_Z

/* The column loops below go by pairs (c, c + 1) over ncol rounded up to
 * even (the row stride OGK_I_NMPC_NCOL_Z is even; a padding column starts at
 * zero and stays zero: no term below writes it but the pair's linear ones).
 * Every matrix is a local array of ogk_i_nmpc_shoot (these helpers are
 * inlined there), so gcc -O2 knows that they do not overlap and computes
 * each pair with one packed operation on x86-64; the arithmetic of each
 * column is unchanged (the same operations in the same order). */

/* Y = S + a K_prev (+ b k_prev in column col_h), for the first `ncol_e` columns. */
static void stage_sens(const ogk_real_t *s, const ogk_real_t *k_prev_sens, /* NOLINT(bugprone-easily-swappable-parameters): internal helper, the terms of Y = S + a K_prev in order; its only caller is ogk_i_nmpc_shoot, checked by central differences (test_nmpc.c) */
                       const ogk_real_t *k_prev, ogk_real_t a, ogk_real_t b, size_t col_h, /* NOLINT(bugprone-easily-swappable-parameters): as above */
                       size_t ncol_e, ogk_real_t *y)
{
    size_t i;
    for (i = 0u; i < NX; ++i) {
        const size_t row = i * NCOL;
        ogk_i_rk4_stage_state_pairs(s, a, k_prev_sens, row, ncol_e, y);
        y[row + col_h] += b * k_prev[i];
    }
}

/* Column l of k = jx y, jx a Jacobian of the problem's dynamics: only the
 * structural nonzeros that ogk/ocp.h allows are used (13 of 25; those of
 * eq. (11)-(14)'s Jacobian): x_0' = x_2 (r' = v_r); x_1' depends on x_0,
 * x_3 (theta' on r, v_theta); x_2', x_3' on every state (theta through the
 * third bodies); x_4' on x_0 (m' on r, solar-electric). */
static inline void jx_column(const ogk_real_t *jx, const ogk_real_t *y, size_t l, ogk_real_t *k) /* NOLINT(bugprone-easily-swappable-parameters): internal helper, k = jx y in the order of the product; its only caller is stage_k, checked by central differences (test_nmpc.c) */
{
    const ogk_real_t y0 = y[(0u * NCOL) + l];
    const ogk_real_t y1 = y[(1u * NCOL) + l];
    const ogk_real_t y2 = y[(2u * NCOL) + l];
    const ogk_real_t y3 = y[(3u * NCOL) + l];
    const ogk_real_t y4 = y[(4u * NCOL) + l];
    k[(0u * NCOL) + l] = y2;
    k[(1u * NCOL) + l] = (jx[5] * y0) + (jx[8] * y3);
    k[(2u * NCOL) + l] = (jx[10] * y0) + (jx[11] * y1) + (jx[13] * y3) + (jx[14] * y4);
    k[(3u * NCOL) + l] = (jx[15] * y0) + (jx[16] * y1) + (jx[17] * y2) + (jx[18] * y3) + (jx[19] * y4);
    k[(4u * NCOL) + l] = jx[20] * y0;
}

/* K = fx Y + fu dU/dp + ft dt/dp for one stage. */
static void stage_k(const ogk_real_t *jx, const ogk_real_t *ju, const ogk_real_t *jt, /* NOLINT(bugprone-easily-swappable-parameters): internal helper, the terms of K = fx Y + fu dU/dp + ft dt/dp in order; its only caller is ogk_i_nmpc_shoot, checked by central differences (test_nmpc.c) */
                    const ogk_real_t *y, uint32_t nu, ogk_real_t s_frac, size_t ncol, /* NOLINT(bugprone-easily-swappable-parameters): as above */
                    ogk_real_t *k)
{
    const size_t col_u0 = NX;
    const size_t col_u1 = NX + (size_t)nu;
    const size_t col_h = NX + (2u * (size_t)nu);
    const size_t col_t = col_h + 1u;
    size_t i;
    size_t j;
    const size_t ncol_e = ncol + (ncol % 2u);
    size_t c;
    for (c = 0u; c < ncol_e; c += 2u) {
        jx_column(jx, y, c, k);
        jx_column(jx, y, c + 1u, k);
    }
    /* r' and theta' depend on neither u nor t, m' not on t, and only the
     * third bodies bring t in (ogk_i_nmpc_rhs): the other rows of ju and jt
     * are structurally 0 */
    for (i = 2u; i < NX; ++i) {
        for (j = 0u; j < nu; ++j) {
            k[(i * NCOL) + col_u0 + j] += ju[(i * nu) + j] * (OGK_R(1.0) - s_frac);
            k[(i * NCOL) + col_u1 + j] += ju[(i * nu) + j] * s_frac;
        }
    }
    if (ncol > col_t) {
        for (i = 2u; i < 4u; ++i) {
            /* stage time t_start + s h: d/dh = s, d/dt_start = 1 */
            k[(i * NCOL) + col_h] += jt[i] * s_frac;
            k[(i * NCOL) + col_t] += jt[i];
        }
    }
}

size_t ogk_i_nmpc_ncol(const ogk_i_ocp_t *ocp, uint32_t nu)
{
    /* the start-time column is identically zero for a time-invariant model
     * (the heliocentric one without attracting third bodies): it is not
     * propagated */
    const bool varying = (ocp->ops->structure(ocp->data, nu) & OGK_OCP_TIME_VARYING) != 0u;
    return NX + (2u * (size_t)nu) + 1u + (size_t)(varying ? 1u : 0u);
}

ogk_status ogk_i_nmpc_shoot(const ogk_i_ocp_t *ocp, uint32_t nu, /* NOLINT(bugprone-easily-swappable-parameters): internal, the order of nmpc_internal.h (nu, t_start, h as in ogk_nmpc_interval); checked by central differences (test_nmpc.c) */
                            ogk_real_t t_start, ogk_real_t h, const ogk_real_t *x0,
                            const ogk_real_t *u0, const ogk_real_t *u1, ogk_real_t *xf,
                            ogk_real_t *sens, ogk_real_t *tape)
{
    return ogk_i_nmpc_shoot_arc(ocp, nu, t_start, h, x0, u0, u1, xf, sens, tape, NULL, NULL);
}

ogk_status ogk_i_nmpc_shoot_arc(const ogk_i_ocp_t *ocp, uint32_t nu, /* NOLINT(bugprone-easily-swappable-parameters): internal, the order of nmpc_internal.h (nu, t_start, h as in ogk_nmpc_interval); checked by central differences (test_nmpc.c) */
                                ogk_real_t t_start, ogk_real_t h, const ogk_real_t *x0,
                                const ogk_real_t *u0, const ogk_real_t *u1, ogk_real_t *xf,
                                ogk_real_t *sens, ogk_real_t *tape, ogk_i_nmpc_arc_t *arc, ogk_real_t *ends)
{
    static const uint32_t trig_index[4] = { 0u, 1u, 1u, 2u };
    ogk_status st = OGK_OK;
    const uint32_t steps = ocp->cfg->rk4_steps;
    /* rk4_steps <= OGK_NMPC_MAX_RK4_STEPS (ogk_nmpc_init): clamped once so the
     * loops below keep a fixed bound with one condition for it */
    const uint32_t steps_b = ogk_i_min_u32(steps, OGK_NMPC_MAX_RK4_STEPS);
    const ogk_real_t dt = h / (ogk_real_t)steps;
    const ogk_real_t inv_steps = OGK_R(1.0) / (ogk_real_t)steps;
    const size_t col_h = NX + (2u * (size_t)nu);
    const size_t ncol = ogk_i_nmpc_ncol(ocp, nu);
    const size_t ncol_e = ncol + (ncol % 2u);
    const bool taped = (sens != NULL) && (tape != NULL);
    ogk_real_t x[NX];
    ogk_real_t stage_x[NX];
    ogk_real_t k[4][NX];
    ogk_real_t u[OGK_NMPC_MAX_NU];
    ogk_real_t jx[NX * NX];
    ogk_real_t ju[NX * OGK_NMPC_MAX_NU];
    ogk_real_t jt[NX];
    ogk_real_t trig[(2u * OGK_NMPC_MAX_RK4_STEPS) + 1u][2];
    ogk_real_t s_mat[NX * NCOL];
    ogk_real_t y_mat[NX * NCOL];
    ogk_real_t k_mat[4][NX * NCOL];
    uint32_t step;
    uint32_t j;
    size_t i;

    (void)memcpy(x, x0, sizeof(x));
    /* cos and sin of the angle at the 2 steps + 1 distinct stage offsets
     * (a step's last stage is the next one's first), the same arithmetic as
     * the stage loop's s_frac */
    for (i = 0u; i <= (2u * (size_t)steps_b); ++i) {
        const size_t i_step = i / 2u; /* the step of stage offset i (exact integer division) */
        const ogk_real_t s_frac = ((ogk_real_t)i_step + (((i % 2u) != 0u) ? OGK_R(0.5) : OGK_R(0.0))) * inv_steps;
        const ogk_real_t angle = u0[0] + ((u1[0] - u0[0]) * s_frac);
        trig[i][0] = OGK_COS(angle);
        trig[i][1] = OGK_SIN(angle);
    }
    if (sens != NULL) {
        /* the Jacobians' structural zeros, which the problem's dynamics do not write */
        (void)memset(jx, 0, sizeof(jx));
        (void)memset(ju, 0, sizeof(ju));
        (void)memset(s_mat, 0, sizeof(s_mat));
        for (i = 0u; i < NX; ++i) {
            s_mat[(i * NCOL) + i] = OGK_R(1.0);
        }
    }
    for (step = 0u; (step < steps_b) && (st == OGK_OK); ++step) {
        ogk_real_t *tape_step = taped ? &tape[(size_t)step * OGK_I_NMPC_TAPE_STEP_Z] : NULL;
        if (tape_step != NULL) {
            (void)memcpy(tape_step, s_mat, sizeof(s_mat));
        }
        for (j = 0u; (j < 4u) && (st == OGK_OK); ++j) {
            const ogk_real_t s_frac = ((ogk_real_t)step + ogk_i_rk4_c(j)) * inv_steps;
            const ogk_real_t t_stage = t_start + (s_frac * h);
            for (i = 0u; i < nu; ++i) {
                u[i] = u0[i] + ((u1[i] - u0[i]) * s_frac);
            }
            if (j == 0u) {
                (void)memcpy(stage_x, x, sizeof(stage_x));
            } else {
                ogk_i_rk4_stage_state(x, ogk_i_rk4_c(j) * dt, k[j - 1u], NX, stage_x);
            }
            st = ocp->ops->dynamics(ocp->data, nu, t_stage, stage_x, u, trig[(2u * step) + trig_index[j]], k[j],
                                (sens != NULL) ? jx : NULL, ju, jt);
            if ((st == OGK_OK) && (sens != NULL)) {
                if (j != 0u) {
                    /* y = x + c dt k_prev, dt = h / steps (the first stage is
                     * at the step's start: Y = S) */
                    stage_sens(s_mat, k_mat[j - 1u], k[j - 1u], ogk_i_rk4_c(j) * dt,
                               ogk_i_rk4_c(j) * inv_steps, col_h, ncol_e, y_mat);
                }
                stage_k(jx, ju, jt, (j == 0u) ? s_mat : y_mat, nu, s_frac, ncol, k_mat[j]);
                if (tape_step != NULL) {
                    ogk_real_t *rec = &tape_step[OGK_I_NMPC_TAPE_STAGE0 + ((size_t)j * OGK_I_NMPC_TAPE_STAGE)];
                    (void)memcpy(&rec[OGK_I_NMPC_TAPE_X], stage_x, sizeof(stage_x));
                    (void)memcpy(&rec[OGK_I_NMPC_TAPE_K], k[j], sizeof(k[j]));
                    (void)memcpy(&rec[OGK_I_NMPC_TAPE_TRIG], trig[(2u * step) + trig_index[j]], 2u * sizeof(ogk_real_t));
                    (void)memcpy(&rec[OGK_I_NMPC_TAPE_JX], jx, sizeof(jx));
                    (void)memcpy(&rec[OGK_I_NMPC_TAPE_KS], k_mat[j], sizeof(k_mat[j]));
                }
            }
        }
        if (st == OGK_OK) {
            ogk_i_rk4_accumulate(x, k[0], k[1], k[2], k[3], dt / OGK_R(6.0), NX);
            if (sens != NULL) {
                for (i = 0u; i < NX; ++i) {
                    const size_t row = i * NCOL;
                    /* S += dt/6 sum_j b_j K_j, then the step's own d/dh: (1 / 6M) sum_j b_j k_j */
                    ogk_i_rk4_accumulate_pairs(s_mat, k_mat[0], k_mat[1], k_mat[2], k_mat[3], dt / OGK_R(6.0), row, ncol_e);
                    s_mat[row + col_h] =
                        ogk_i_rk4_step_entry(s_mat[row + col_h], inv_steps / OGK_R(6.0), k[0][i], k[1][i], k[2][i], k[3][i]);
                }
                if ((ends != NULL) && ((step + 1u) < steps)) {
                    /* an interior step end's state and sensitivities (ends needs sens) */
                    ogk_real_t *r = &ends[(size_t)step * OGK_I_NMPC_REC_STRIDE];
                    (void)memcpy(r, x, sizeof(x));
                    (void)memcpy(&r[NX], s_mat, sizeof(s_mat));
                }
            }
            if ((arc != NULL) && ((step + 1u) < steps)) {
                /* an interior step end of the arc (the interval's ends are nodes) */
                const uint32_t step_end = step + 1u;
                ogk_i_nmpc_keepout_scan(ocp, x, t_start + ((ogk_real_t)step_end * inv_steps * h), step_end, arc);
            }
        }
    }
    if (st == OGK_OK) {
        (void)memcpy(xf, x, sizeof(x));
        if (sens != NULL) {
            (void)memcpy(sens, s_mat, sizeof(s_mat));
        }
    }
    return st;
}
