/* nmpc_keepout.c -- the keep-out of the NMPC's SQP (docs/design/nmpc-flight.md,
 * section 2 item 6): every interior node, and every RK4 step end along the
 * arcs, at least R_j from the centre of the problem's disc j (ogk/ocp.h:
 * the heliocentric problem's planets, the proximity problem's discs about
 * the target), its violation in the filter's measure and its linearised
 * rows in the condensed QP. */
#include "nmpc_internal.h"
#include "../ogk_checks.h"

#include <math.h>

#define NX ((size_t)OGK_NMPC_NX)
/* Keep-out rows enter the QP for nodes within this many radii. */
#define KEEPOUT_ACTIVE OGK_R(3.0)

#define KO ((size_t)OGK_OCP_MAX_KEEPOUT)

/* Distance of x at time t from disc j's centre and its derivatives in x_0,
 * x_1 and t (the problem's callback). */
static ogk_real_t disc_distance(const ogk_i_ocp_t *ocp, size_t j, const ogk_real_t *x, ogk_real_t t, ogk_real_t *d_x0,
                            ogk_real_t *d_x1, ogk_real_t *d_t)
{
    return ocp->ops->keepout_distance(ocp->data, j, x, t, d_x0, d_x1, d_t);
}

/* Keep-out violation of a plan: sum and largest of max(0, R_j - d_j) over the
 * interior nodes. */
void ogk_i_nmpc_keepout_violation(const ogk_i_ocp_t *ocp, const ogk_nmpc_plan_t *p, ogk_real_t *sum, /* NOLINT(bugprone-easily-swappable-parameters): internal, adds to evaluate's (l1, max) pair in that order */
                                  ogk_real_t *largest)
{
    const ogk_real_t h = p->horizon / (ogk_real_t)p->nodes;
    /* nodes <= OGK_NMPC_MAX_NODES (ogk_nmpc_init, the plan's checks): clamped once so the loop keeps a fixed bound */
    const size_t nodes = ogk_i_min_size(p->nodes, OGK_NMPC_MAX_NODES);
    size_t k;
    size_t b;
    for (b = 0u; b < KO; ++b) {
        const ogk_real_t radius = ocp->ops->keepout_radius(ocp->data, b);
        if (radius > OGK_R(0.0)) {
            for (k = 1u; k < nodes; ++k) {
                ogk_real_t dr;
                ogk_real_t dth;
                ogk_real_t dt;
                const ogk_real_t d = disc_distance(ocp, b, &p->x[k * NX], p->t0 + ((ogk_real_t)k * h),
                                               &dr, &dth, &dt);
                const ogk_real_t v = radius - d;
                if (v > OGK_R(0.0)) {
                    *sum += v;
                    *largest = (v > *largest) ? v : *largest;
                }
            }
        }
    }
}

/* The keep-out rows of node k (interior) with its condensed sensitivities G
 * (5 x nv) and offsets e: d + d_X (G v + e) + d_T v_T >= R, for each disc
 * that the node is within KEEPOUT_ACTIVE radii of. */
void ogk_i_nmpc_keepout_rows(ogk_nmpc_t *ctx, const ogk_nmpc_plan_t *p, size_t nv, size_t k, /* NOLINT(bugprone-easily-swappable-parameters): internal, condense's (G, e) of the node in that order */
                             const ogk_real_t *g, const ogk_real_t *e) /* NOLINT(bugprone-easily-swappable-parameters): as above */
{
    const ogk_i_ocp_t ocp = ogk_i_nmpc_problem(ctx);
    const ogk_real_t h = p->horizon / (ogk_real_t)p->nodes;
    size_t b;
    size_t c;
    for (b = 0u; b < KO; ++b) {
        const ogk_real_t radius = ocp.ops->keepout_radius(ocp.data, b);
        if ((radius > OGK_R(0.0)) && (ctx->ko_rows < OGK_I_NMPC_MAX_KO_ROWS_Z)) {
            ogk_real_t dr;
            ogk_real_t dth;
            ogk_real_t dt;
            const ogk_real_t d = disc_distance(&ocp, b, &p->x[k * NX], p->t0 + ((ogk_real_t)k * h), &dr, &dth, &dt);
            if (d < (KEEPOUT_ACTIVE * radius)) {
                ogk_real_t *row = &ctx->ko_a[ctx->ko_rows * nv];
                for (c = 0u; c < nv; ++c) {
                    row[c] = (dr * g[(0u * nv) + c]) + (dth * g[(1u * nv) + c]);
                }
                /* the node's time t0 + k T / N moves with T */
                row[nv - 1u] += dt * (ogk_real_t)k / (ogk_real_t)p->nodes;
                ctx->ko_b[ctx->ko_rows] = radius - d - (dr * e[0]) - (dth * e[1]);
                ctx->ko_rows += 1u;
            }
        }
    }
}

/* The keep-out along the arcs (docs/design/nmpc-flight.md, "Robustness"): the
 * nodes of a plan are 12-15 days apart early in a flight, and an arc between
 * two nodes outside the radius can pass inside it; the interior RK4 step
 * ends of every subinterval are scanned, and the closest one per body is
 * constrained like a node (its sensitivities from a sweep stopped there). */

void ogk_i_nmpc_arc_start(const ogk_i_ocp_t *ocp, const ogk_nmpc_plan_t *p, size_t k,
                          ogk_i_nmpc_arc_t *arc)
{
    size_t b;
    arc->viol_sum = OGK_R(0.0);
    arc->viol_max = OGK_R(0.0);
    for (b = 0u; b < KO; ++b) {
        arc->mask[b] = 0u;
        arc->radius[b] = ocp->ops->keepout_radius(ocp->data, b);
        arc->r_start[b] = arc->radius[b];
    }
    arc->steps = ocp->cfg->rk4_steps;
    if (k == 0u) {
        for (b = 0u; b < KO; ++b) {
            /* a measured state the truth has pushed inside: the required radius grows straight from
             * its distance to R at node 1 (every plan would be infeasible otherwise) */
            if (arc->radius[b] > OGK_R(0.0)) {
                ogk_real_t dr;
                ogk_real_t dth;
                ogk_real_t dt;
                const ogk_real_t d0 = disc_distance(ocp, b, p->x, p->t0, &dr, &dth, &dt);
                arc->r_start[b] = (d0 < arc->radius[b]) ? d0 : arc->radius[b];
            }
        }
    }
}

/* The radius required at step end j of an arc starting at r_start. */
static ogk_real_t arc_radius(const ogk_i_nmpc_arc_t *arc, size_t b, uint32_t j)
{
    return arc->r_start[b] + ((arc->radius[b] - arc->r_start[b]) * (ogk_real_t)j / (ogk_real_t)arc->steps);
}

void ogk_i_nmpc_keepout_scan(const ogk_i_ocp_t *ocp, const ogk_real_t *x, ogk_real_t t, uint32_t step, /* NOLINT(bugprone-easily-swappable-parameters): internal, the step end's time then its index, as ogk_i_nmpc_shoot_arc computes them; checked by test_keepout_along_arcs */
                             ogk_i_nmpc_arc_t *arc)
{
    size_t b;
    for (b = 0u; b < KO; ++b) {
        if (arc->radius[b] > OGK_R(0.0)) {
            ogk_real_t dr;
            ogk_real_t dth;
            ogk_real_t dt;
            const ogk_real_t d = disc_distance(ocp, b, x, t, &dr, &dth, &dt);
            const ogk_real_t v = arc_radius(arc, b, step) - d;
            if (v > OGK_R(0.0)) {
                arc->viol_sum += v;
                arc->viol_max = (v > arc->viol_max) ? v : arc->viol_max;
            }
            if (d < (KEEPOUT_ACTIVE * arc->radius[b])) {
                /* step <= OGK_NMPC_MAX_RK4_STEPS - 1 = 31: one bit of the mask */
                arc->mask[b] |= (uint32_t)1u << step;
            }
        }
    }
}

void ogk_i_nmpc_keepout_arc_rows(ogk_nmpc_t *ctx, const ogk_nmpc_plan_t *p, size_t nv, size_t k, /* NOLINT(bugprone-easily-swappable-parameters): internal, condense's (G, e) of node k in that order */
                                 const ogk_real_t *g, const ogk_real_t *e) /* NOLINT(bugprone-easily-swappable-parameters): as above */
{
    const ogk_i_ocp_t ocp = ogk_i_nmpc_problem(ctx);
    const ogk_nmpc_config_t *cfg = &ctx->cfg;
    const uint32_t nu = p->nu;
    const ogk_real_t h = p->horizon / (ogk_real_t)p->nodes;
    const ogk_real_t t_start = p->t0 + ((ogk_real_t)k * h);
    const uint32_t steps = ogk_i_min_u32(cfg->rk4_steps, OGK_NMPC_MAX_RK4_STEPS);
    const size_t col_u0 = NX;
    const size_t col_u1 = NX + (size_t)nu;
    const size_t col_h = NX + (2u * (size_t)nu);
    const size_t ncol = ogk_i_nmpc_ncol(&ocp, nu);
    uint32_t any = 0u;
    ogk_i_nmpc_arc_t arc;
    size_t b;
    uint32_t j;
    size_t c;
    size_t i;
    for (b = 0u; b < KO; ++b) {
        any |= ctx->arc_mask[(k * KO) + b];
    }
    ogk_i_nmpc_arc_start(&ocp, p, k, &arc);
    if (any != 0u) {
        ogk_real_t xf[NX];
        ogk_real_t sens[NX * OGK_I_NMPC_MAX_COLS];
        /* the step ends' states and sensitivities (X_k, U_k, U_k+1, h[, t_start]), recorded in the
         * tape (the exact Hessian's, free while condensing) */
        any = (ogk_i_nmpc_shoot_arc(&ocp, nu, t_start, h, &p->x[k * NX], &p->u[k * nu], &p->u[(k + 1u) * nu],
                                    xf, sens, NULL, NULL, ctx->tape) == OGK_OK) ? any : 0u;
    }
    for (b = 0u; (b < KO) && (any != 0u); ++b) {
        const uint32_t mask = ctx->arc_mask[(k * KO) + b];
        for (j = 1u; j < steps; ++j) {
            if ((((mask >> j) & 1u) != 0u) && (ctx->ko_rows < OGK_I_NMPC_MAX_KO_ROWS_Z)) {
                const ogk_real_t *rec = &ctx->tape[((size_t)j - 1u) * OGK_I_NMPC_REC_STRIDE];
                const ogk_real_t *s_r = &rec[NX + (0u * OGK_I_NMPC_MAX_COLS)];
                const ogk_real_t *s_th = &rec[NX + (1u * OGK_I_NMPC_MAX_COLS)];
                const ogk_real_t frac = (ogk_real_t)j / (ogk_real_t)cfg->rk4_steps;
                ogk_real_t dr;
                ogk_real_t dth;
                ogk_real_t dt;
                const ogk_real_t d = disc_distance(&ocp, b, rec, t_start + (frac * h), &dr, &dth, &dt);
                ogk_real_t *row = &ctx->ko_a[ctx->ko_rows * nv];
                ogk_real_t offset = OGK_R(0.0);
                /* dd/dv = (dr, dth) (S_X G_k + S_U0 E_k + S_U1 E_k+1 + S_h dh/dT + S_ts dts/dT) + dd/dt dt_j/dT */
                for (c = 0u; c < nv; ++c) {
                    ogk_real_t acc = OGK_R(0.0);
                    for (i = 0u; i < NX; ++i) {
                        acc += ((dr * s_r[i]) + (dth * s_th[i])) * g[(i * nv) + c];
                    }
                    row[c] = acc;
                }
                for (i = 0u; i < NX; ++i) {
                    offset += ((dr * s_r[i]) + (dth * s_th[i])) * e[i];
                }
                for (i = 0u; i < nu; ++i) {
                    row[(k * nu) + i] += (dr * s_r[col_u0 + i]) + (dth * s_th[col_u0 + i]);
                    row[((k + 1u) * nu) + i] += (dr * s_r[col_u1 + i]) + (dth * s_th[col_u1 + i]);
                }
                {
                    /* h = T / N, t_start = t0 + k T / N, the step end at t_start + frac h */
                    ogk_real_t d_dt = ((dr * s_r[col_h]) + (dth * s_th[col_h])) / (ogk_real_t)p->nodes;
                    if (ncol > (col_h + 1u)) {
                        d_dt += ((dr * s_r[col_h + 1u]) + (dth * s_th[col_h + 1u])) * (ogk_real_t)k / (ogk_real_t)p->nodes;
                    }
                    d_dt += dt * ((ogk_real_t)k + frac) / (ogk_real_t)p->nodes;
                    row[nv - 1u] += d_dt;
                }
                ctx->ko_b[ctx->ko_rows] = arc_radius(&arc, b, j) - d - offset;
                ctx->ko_rows += 1u;
            }
        }
    }
}
