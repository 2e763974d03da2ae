/* nmpc_keepout.c -- the keep-out of the NMPC's SQP (docs/nmpc-flight.md,
 * section 2 item 6): every interior node at least keepout_radius[b] from
 * body b's centre, its violation in the filter's measure and its
 * linearised rows in the condensed QP. Moved out of nmpc_sqp.c unchanged. */
#include "nmpc_internal.h"
#include "ogk_checks.h"

#include <math.h>

#define NX ((size_t)OGK_NMPC_NX)
/* Keep-out rows enter the QP for nodes within this many radii. */
#define KEEPOUT_ACTIVE 3.0

/* Distance of node state x at time t from body b's centre and its
 * derivatives in r, theta and t (d^2 = r^2 + R^2 - 2 r R cos(theta - phi)). */
static double keepout_distance(const ogk_nmpc_config_t *cfg, size_t b, const double *x, double t,
                               double *d_r, double *d_theta, double *d_t) /* NOLINT(bugprone-easily-swappable-parameters): internal, the derivatives in the state's order (r, theta) then t; checked by test_keepout_detour */
{
    const double big_r = cfg->body_radius[b];
    const double phi = cfg->body_phase0[b] + (cfg->body_rate[b] * t);
    const double cd = cos(x[1] - phi);
    const double sd = sin(x[1] - phi);
    const double d2 = ((x[0] * x[0]) + (big_r * big_r)) - (2.0 * x[0] * big_r * cd);
    double d = 0.0;
    double inv = 0.0;
    if (d2 > 0.0) {
        d = sqrt(d2);
    }
    if (d > 1.0e-300) {
        inv = 1.0 / d;
    }
    *d_r = (x[0] - (big_r * cd)) * inv;
    *d_theta = x[0] * big_r * sd * inv;
    *d_t = -(*d_theta) * cfg->body_rate[b];
    return d;
}

/* Keep-out violation of a plan: sum and largest of max(0, R_b - d) over the
 * interior nodes. */
void ogk_i_nmpc_keepout_violation(const ogk_nmpc_config_t *cfg, const ogk_nmpc_plan_t *p, double *sum, /* NOLINT(bugprone-easily-swappable-parameters): internal, adds to evaluate's (l1, max) pair in that order */
                                  double *largest)
{
    const double h = p->horizon / (double)p->nodes;
    /* n_bodies <= OGK_NMPC_MAX_BODIES and nodes <= OGK_NMPC_MAX_NODES (ogk_nmpc_init,
     * the plan's checks): clamped once so each loop keeps a fixed bound */
    const size_t n_bodies = ogk_i_min_size(cfg->n_bodies, OGK_NMPC_MAX_BODIES);
    const size_t nodes = ogk_i_min_size(p->nodes, OGK_NMPC_MAX_NODES);
    size_t k;
    size_t b;
    for (b = 0u; b < n_bodies; ++b) {
        if (cfg->keepout_radius[b] > 0.0) {
            for (k = 1u; k < nodes; ++k) {
                double dr;
                double dth;
                double dt;
                const double d = keepout_distance(cfg, b, &p->x[k * NX], p->t0 + ((double)k * h),
                                                  &dr, &dth, &dt);
                const double v = cfg->keepout_radius[b] - d;
                if (v > 0.0) {
                    *sum += v;
                    *largest = (v > *largest) ? v : *largest;
                }
            }
        }
    }
}

/* The keep-out rows of node k (interior) with its condensed sensitivities G
 * (5 x nv) and offsets e: d + d_X (G v + e) + d_T v_T >= R, for each body
 * with a keep-out radius that the node is within KEEPOUT_ACTIVE radii of. */
void ogk_i_nmpc_keepout_rows(ogk_nmpc_t *ctx, const ogk_nmpc_plan_t *p, size_t nv, size_t k, /* NOLINT(bugprone-easily-swappable-parameters): internal, condense's (G, e) of the node in that order */
                             const double *g, const double *e) /* NOLINT(bugprone-easily-swappable-parameters): as above */
{
    const ogk_nmpc_config_t *cfg = &ctx->cfg;
    const double h = p->horizon / (double)p->nodes;
    /* n_bodies <= OGK_NMPC_MAX_BODIES (ogk_nmpc_init): clamped once, a fixed bound */
    const size_t n_bodies = ogk_i_min_size(cfg->n_bodies, OGK_NMPC_MAX_BODIES);
    size_t b;
    size_t c;
    for (b = 0u; b < n_bodies; ++b) {
        if ((cfg->keepout_radius[b] > 0.0) && (ctx->ko_rows < OGK_NMPC_MAX_NODES)) {
            double dr;
            double dth;
            double dt;
            const double d = keepout_distance(cfg, b, &p->x[k * NX], p->t0 + ((double)k * h), &dr, &dth, &dt);
            if (d < (KEEPOUT_ACTIVE * cfg->keepout_radius[b])) {
                double *row = &ctx->ko_a[ctx->ko_rows * nv];
                for (c = 0u; c < nv; ++c) {
                    row[c] = (dr * g[(0u * nv) + c]) + (dth * g[(1u * nv) + c]);
                }
                /* the node's time t0 + k T / N moves with T */
                row[nv - 1u] += dt * (double)k / (double)p->nodes;
                ctx->ko_b[ctx->ko_rows] = cfg->keepout_radius[b] - d - (dr * e[0]) - (dth * e[1]);
                ctx->ko_rows += 1u;
            }
        }
    }
}

/* The keep-out along the arcs (docs/nmpc-flight.md, "Robustness"): the
 * nodes of a plan are 12-15 days apart early in a flight, and an arc between
 * two nodes outside the radius can pass inside it; the interior RK4 step
 * ends of every subinterval are scanned, and the closest one per body is
 * constrained like a node (its sensitivities from a sweep stopped there). */

double ogk_i_nmpc_body_distance(const ogk_nmpc_config_t *cfg, size_t b, const double *x, double t)
{
    double dr;
    double dth;
    double dt;
    return keepout_distance(cfg, b, x, t, &dr, &dth, &dt);
}

void ogk_i_nmpc_arc_clear(ogk_i_nmpc_arc_t *arc)
{
    size_t b;
    for (b = 0u; b < OGK_NMPC_MAX_BODIES; ++b) {
        arc->d[b] = OGK_I_NMPC_ARC_NONE;
        arc->step[b] = 0u;
    }
}

void ogk_i_nmpc_keepout_scan(const ogk_nmpc_config_t *cfg, const double *x, double t, uint32_t step,
                             ogk_i_nmpc_arc_t *arc)
{
    /* n_bodies <= OGK_NMPC_MAX_BODIES (ogk_nmpc_init): clamped once, a fixed bound */
    const size_t n_bodies = ogk_i_min_size(cfg->n_bodies, OGK_NMPC_MAX_BODIES);
    size_t b;
    for (b = 0u; b < n_bodies; ++b) {
        if (cfg->keepout_radius[b] > 0.0) {
            double dr;
            double dth;
            double dt;
            const double d = keepout_distance(cfg, b, x, t, &dr, &dth, &dt);
            if (d < arc->d[b]) {
                arc->d[b] = d;
                arc->step[b] = step;
            }
        }
    }
}

/* The radius required of the arc of interval k at step j: R, or on interval 0
 * when node 0 (the measured state) is inside R, the straight recovery from
 * its distance d0 to R at node 1 (a measured state the truth has pushed
 * inside would otherwise make every plan infeasible). */
static double arc_radius(const ogk_nmpc_config_t *cfg, const ogk_nmpc_plan_t *p, size_t b, size_t k,
                         uint32_t j)
{
    double req = cfg->keepout_radius[b];
    if (k == 0u) {
        double dr;
        double dth;
        double dt;
        const double d0 = keepout_distance(cfg, b, p->x, p->t0, &dr, &dth, &dt);
        if (d0 < req) {
            req = d0 + ((req - d0) * (double)j / (double)cfg->rk4_steps);
        }
    }
    return req;
}

void ogk_i_nmpc_keepout_arc_violation(const ogk_nmpc_config_t *cfg, const ogk_nmpc_plan_t *p, size_t k,
                                      const ogk_i_nmpc_arc_t *arc, double *sum, double *largest)
{
    const size_t n_bodies = ogk_i_min_size(cfg->n_bodies, OGK_NMPC_MAX_BODIES);
    size_t b;
    for (b = 0u; b < n_bodies; ++b) {
        if ((cfg->keepout_radius[b] > 0.0) && (arc->step[b] > 0u)) {
            const double v = arc_radius(cfg, p, b, k, arc->step[b]) - arc->d[b];
            if (v > 0.0) {
                *sum += v;
                *largest = (v > *largest) ? v : *largest;
            }
        }
    }
}

void ogk_i_nmpc_keepout_arc_rows(ogk_nmpc_t *ctx, const ogk_nmpc_plan_t *p, size_t nv, size_t k, /* NOLINT(bugprone-easily-swappable-parameters): internal, condense's (G, e) of node k in that order */
                                 const double *g, const double *e) /* NOLINT(bugprone-easily-swappable-parameters): as above */
{
    const ogk_nmpc_config_t *cfg = &ctx->cfg;
    const uint32_t nu = p->nu;
    const double h = p->horizon / (double)p->nodes;
    const double t_start = p->t0 + ((double)k * h);
    const size_t n_bodies = ogk_i_min_size(cfg->n_bodies, OGK_NMPC_MAX_BODIES);
    const size_t col_u0 = NX;
    const size_t col_u1 = NX + (size_t)nu;
    const size_t col_h = NX + (2u * (size_t)nu);
    const size_t ncol = ogk_i_nmpc_ncol(cfg, nu);
    size_t b;
    size_t c;
    size_t i;
    for (b = 0u; b < n_bodies; ++b) {
        const size_t slot = (k * OGK_NMPC_MAX_BODIES) + b;
        const uint32_t j = ctx->arc_step[slot];
        if ((cfg->keepout_radius[b] > 0.0) && (j > 0u) && (ctx->ko_rows < OGK_NMPC_MAX_NODES)
            && (ctx->arc_d[slot] < (KEEPOUT_ACTIVE * cfg->keepout_radius[b]))) {
            double xs[NX];
            double sens[NX * OGK_I_NMPC_MAX_COLS];
            /* the state at step j's end and its sensitivities (X_k, U_k, U_k+1, h[, t_start]) */
            if (ogk_i_nmpc_shoot_arc(cfg, nu, t_start, h, &p->x[k * NX], &p->u[k * nu], &p->u[(k + 1u) * nu],
                                     xs, sens, NULL, j, NULL) == OGK_OK) {
                const double frac = (double)j / (double)cfg->rk4_steps;
                double dr;
                double dth;
                double dt;
                const double d = keepout_distance(cfg, b, xs, t_start + (frac * h), &dr, &dth, &dt);
                const double *s_r = &sens[0u * OGK_I_NMPC_MAX_COLS];
                const double *s_th = &sens[1u * OGK_I_NMPC_MAX_COLS];
                double *row = &ctx->ko_a[ctx->ko_rows * nv];
                double offset = 0.0;
                /* dd/dv = (dr, dth) (S_X G_k + S_U0 E_k + S_U1 E_k+1 + S_h dh/dT + S_ts dts/dT) + dd/dt dt_s/dT */
                for (c = 0u; c < nv; ++c) {
                    double acc = 0.0;
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
                    double d_dt = (dr * s_r[col_h]) + (dth * s_th[col_h]);
                    d_dt /= (double)p->nodes;
                    if (ncol > (col_h + 1u)) {
                        d_dt += ((dr * s_r[col_h + 1u]) + (dth * s_th[col_h + 1u])) * (double)k / (double)p->nodes;
                    }
                    d_dt += dt * ((double)k + frac) / (double)p->nodes;
                    row[nv - 1u] += d_dt;
                }
                ctx->ko_b[ctx->ko_rows] = arc_radius(cfg, p, b, k, j) - d - offset;
                ctx->ko_rows += 1u;
            }
        }
    }
}
