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
