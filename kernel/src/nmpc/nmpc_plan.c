/* nmpc_plan.c -- the plan operations of the receding-horizon strategies
 * (sec. 2.3 of Starek & Kolmanovsky): the control of a plan at a time,
 * dropping flown subintervals (SNN), regridding the same horizon on another
 * node count by interpolation (CNCN), and subdividing every subinterval in
 * two (the SNNS doubling). */
#include "nmpc_internal.h"
#include "../ogk_checks.h"

#include <string.h>

#define NX ((size_t)OGK_NMPC_NX)

/* Position of absolute time t in plan p: subinterval k and fraction in it. */
static void locate(const ogk_nmpc_plan_t *p, ogk_real_t t, uint32_t *k, ogk_real_t *frac)
{
    const ogk_real_t h = p->horizon / (ogk_real_t)p->nodes;
    ogk_real_t s = (t - p->t0) / h;
    uint32_t idx;
    s = (s > OGK_R(0.0)) ? s : OGK_R(0.0);
    s = (s < (ogk_real_t)p->nodes) ? s : (ogk_real_t)p->nodes;
    idx = (uint32_t)s;
    idx = (idx < p->nodes) ? idx : (p->nodes - 1u);
    *k = idx;
    *frac = s - (ogk_real_t)idx;
}

void ogk_i_nmpc_plan_control(const ogk_nmpc_plan_t *p, ogk_real_t t, ogk_real_t *u)
{
    uint32_t k;
    ogk_real_t frac;
    uint32_t i;
    /* nu <= OGK_NMPC_MAX_NU (ogk_nmpc_init): clamped once, a fixed bound */
    const uint32_t nu = ogk_i_min_u32(p->nu, OGK_NMPC_MAX_NU);
    locate(p, t, &k, &frac);
    for (i = 0u; i < nu; ++i) {
        u[i] = ((OGK_R(1.0) - frac) * p->u[(k * p->nu) + i]) + (frac * p->u[((k + 1u) * p->nu) + i]);
    }
}

void ogk_i_nmpc_plan_drop(ogk_nmpc_plan_t *p, uint32_t count)
{
    const ogk_real_t h = p->horizon / (ogk_real_t)p->nodes;
    const uint32_t keep = p->nodes - count; /* caller: count < nodes */
    (void)memmove(p->x, &p->x[count * NX], ((size_t)keep + 1u) * NX * sizeof(ogk_real_t));
    (void)memmove(p->u, &p->u[(size_t)count * p->nu], ((size_t)keep + 1u) * p->nu * sizeof(ogk_real_t));
    p->t0 += (ogk_real_t)count * h;
    p->horizon -= (ogk_real_t)count * h;
    p->nodes = keep;
}

void ogk_i_nmpc_plan_regrid(const ogk_nmpc_plan_t *src, ogk_real_t t0,
                            uint32_t nodes, ogk_nmpc_plan_t *dst)
{
    const ogk_real_t t_f = src->t0 + src->horizon;
    /* nodes <= OGK_NMPC_MAX_NODES and nu <= OGK_NMPC_MAX_NU (callers, ogk_nmpc_init):
     * clamped once so each loop keeps a fixed bound */
    const uint32_t nodes_b = ogk_i_min_u32(nodes, OGK_NMPC_MAX_NODES);
    const uint32_t nu = ogk_i_min_u32(src->nu, OGK_NMPC_MAX_NU);
    uint32_t j;
    uint32_t i;

    dst->t0 = t0;
    dst->horizon = t_f - t0;
    dst->nodes = nodes;
    dst->nu = src->nu;
    (void)memcpy(dst->lambda, src->lambda, sizeof(dst->lambda));
    for (j = 0u; j <= nodes_b; ++j) {
        const ogk_real_t t = t0 + ((dst->horizon * (ogk_real_t)j) / (ogk_real_t)nodes);
        uint32_t k;
        ogk_real_t frac;
        locate(src, t, &k, &frac);
        for (i = 0u; i < NX; ++i) {
            dst->x[(j * NX) + i] = ((OGK_R(1.0) - frac) * src->x[(k * NX) + i])
                + (frac * src->x[(((size_t)k + 1u) * NX) + i]);
        }
        for (i = 0u; i < nu; ++i) {
            dst->u[(j * src->nu) + i] = ((OGK_R(1.0) - frac) * src->u[(k * src->nu) + i])
                + (frac * src->u[((k + 1u) * src->nu) + i]);
        }
    }
}

ogk_status ogk_i_nmpc_plan_subdivide(const ogk_i_ocp_t *ocp,
                                     const ogk_nmpc_plan_t *src,
                                     ogk_nmpc_plan_t *dst)
{
    ogk_status st = OGK_OK;
    const uint32_t nu = src->nu;
    const ogk_real_t h_half = OGK_R(0.5) * src->horizon / (ogk_real_t)src->nodes;
    /* src->nodes <= doubling_max_nodes <= OGK_NMPC_MAX_NODES / 2 (ogk_nmpc_init):
     * clamped once so the loop keeps a fixed bound */
    const uint32_t half = ogk_i_min_u32(src->nodes, (OGK_NMPC_MAX_NODES / 2u));
    uint32_t k;
    uint32_t i;

    dst->t0 = src->t0;
    dst->horizon = src->horizon;
    dst->nodes = 2u * src->nodes;
    dst->nu = nu;
    (void)memcpy(dst->lambda, src->lambda, sizeof(dst->lambda));
    for (k = 0u; (k < half) && (st == OGK_OK); ++k) {
        ogk_real_t u_mid[OGK_NMPC_MAX_NU];
        for (i = 0u; i < nu; ++i) {
            /* piecewise linear: the midpoint value is exact */
            u_mid[i] = OGK_R(0.5) * (src->u[(k * nu) + i] + src->u[((k + 1u) * nu) + i]);
            dst->u[(2u * k * nu) + i] = src->u[(k * nu) + i];
            dst->u[(((2u * k) + 1u) * nu) + i] = u_mid[i];
        }
        (void)memcpy(&dst->x[2u * (size_t)k * NX], &src->x[k * NX], NX * sizeof(ogk_real_t));
        /* midpoint state propagated over the first half (a consistent guess) */
        st = ogk_i_nmpc_shoot(ocp, nu, src->t0 + ((OGK_R(2.0) * (ogk_real_t)k) * h_half), h_half,
                              &src->x[k * NX], &src->u[(size_t)k * nu], u_mid,
                              &dst->x[((2u * (size_t)k) + 1u) * NX], NULL, NULL);
    }
    if (st == OGK_OK) {
        (void)memcpy(&dst->x[dst->nodes * NX], &src->x[src->nodes * NX], NX * sizeof(ogk_real_t));
        (void)memcpy(&dst->u[(size_t)dst->nodes * nu], &src->u[(size_t)src->nodes * nu],
                     (size_t)nu * sizeof(ogk_real_t));
    }
    return st;
}
