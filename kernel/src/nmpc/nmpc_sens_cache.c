/* nmpc_sens_cache.c -- the sensitivities of a subinterval kept with the
 * inputs they were computed from (docs/design/nmpc-flight.md, section 2c).
 *
 * ogk_i_nmpc_shoot is a deterministic function of the predictive model
 * (the configuration's model fields and rk4_steps), nu, X_k, U_k, U_{k+1},
 * h and, when a third body attracts, t_start (the model is autonomous
 * otherwise). Its outputs for the same bits of these inputs are the same
 * bits, so an interval whose inputs match its slot's key takes the stored
 * F_k and sensitivities instead of a new sweep: after the SNNS shift a warm
 * start's intervals 1 .. N-1 are the converged plan's intervals 2 .. N, and
 * only the first (the new measured state) is swept. Anything else (another
 * model, a regridded plan, a rejected trial's slot) fails the comparison
 * and is swept as before. */
#include "nmpc_internal.h"

#include <math.h>
#include <string.h>

#define NX ((size_t)OGK_NMPC_NX)
/* OGK_NMPC_SENS_KEY from the atoms (no composite expression cast) */
#define KEY (((size_t)OGK_NMPC_NX + (2u * (size_t)OGK_NMPC_MAX_NU)) + 2u)
#define MODEL (16u + (5u * (size_t)OGK_NMPC_MAX_BODIES))

/* True when a[0..n) and b[0..n) are the same bits: equal and of the same
 * sign (only the zeros have two encodings; a NaN equals nothing, so it is
 * never taken for a stored input). */
static bool same_bits(const ogk_real_t *a, const ogk_real_t *b, size_t n)
{
    bool same = true;
    size_t i;
    for (i = 0u; (i < n) && same; ++i) {
        same = (a[i] == b[i]) && ((signbit(a[i]) != 0) == (signbit(b[i]) != 0));
    }
    return same;
}

/* The doubles that define the problem's dynamics (its model_key callback,
 * which writes all OGK_OCP_MODEL_KEY: for the heliocentric problem the
 * configuration's model fields and rk4_steps). */
static void model_fields(const ogk_nmpc_t *ctx, ogk_real_t *out)
{
    const ogk_i_ocp_t ocp = ogk_i_nmpc_problem(ctx);
    ocp.ops->model_key(ocp.data, out);
}

void ogk_i_nmpc_cache_reset(ogk_nmpc_t *ctx)
{
    /* a key with h = 0 matches no interval (h > 0), so the model the keys are kept for does not matter
     * until one is stored: it is zeroed (defined), and the first evaluation's cache_begin stores the
     * problem's when it differs (init and reset need not compute it) */
    (void)memset(ctx->sens_key, 0, sizeof(ctx->sens_key));
    (void)memset(ctx->sens_model, 0, sizeof(ctx->sens_model));
}

void ogk_i_nmpc_cache_begin(ogk_nmpc_t *ctx)
{
    ogk_real_t model[OGK_NMPC_SENS_MODEL];
    model_fields(ctx, model);
    if (!same_bits(model, ctx->sens_model, MODEL)) {
        /* another model (or none yet): every key forgotten, this model's kept */
        (void)memset(ctx->sens_key, 0, sizeof(ctx->sens_key));
        (void)memcpy(ctx->sens_model, model, sizeof(model));
    }
}

size_t ogk_i_nmpc_cache_key(const ogk_nmpc_t *ctx, const ogk_nmpc_plan_t *p, size_t k, /* NOLINT(bugprone-easily-swappable-parameters): internal, the interval then its (t_start, h) in ogk_i_nmpc_shoot's order; callers in nmpc_sqp.c */
                            ogk_real_t t_start, ogk_real_t h, ogk_real_t *key)
{
    const size_t nu = (size_t)p->nu;
    size_t n = (NX + (2u * nu)) + 1u;
    (void)memset(key, 0, KEY * sizeof(ogk_real_t));
    (void)memcpy(key, &p->x[k * NX], NX * sizeof(ogk_real_t));
    (void)memcpy(&key[NX], &p->u[k * nu], 2u * nu * sizeof(ogk_real_t));
    key[n - 1u] = h;
    const ogk_i_ocp_t ocp = ogk_i_nmpc_problem(ctx);
    if (ogk_i_nmpc_ncol(&ocp, p->nu) > n) {
        /* a time-varying model (an attracting body) */
        key[n] = t_start;
        n += 1u;
    }
    return n;
}

bool ogk_i_nmpc_cache_hit(const ogk_nmpc_t *ctx, size_t k, const ogk_real_t *key, size_t n_key)
{
    /* k < OGK_NMPC_MAX_NODES: the caller's loop bound */
    return same_bits(&ctx->sens_key[k * KEY], key, n_key);
}

void ogk_i_nmpc_cache_store(ogk_nmpc_t *ctx, size_t k, const ogk_real_t *key)
{
    /* k < OGK_NMPC_MAX_NODES: the caller's loop bound */
    if (key != NULL) {
        (void)memcpy(&ctx->sens_key[k * KEY], key, KEY * sizeof(ogk_real_t));
    } else {
        (void)memset(&ctx->sens_key[k * KEY], 0, KEY * sizeof(ogk_real_t));
    }
}

void ogk_i_nmpc_cache_drop(ogk_nmpc_t *ctx, uint32_t nodes, uint32_t count, uint32_t nu) /* NOLINT(bugprone-easily-swappable-parameters): internal, the plan's node count then the dropped count, as ogk_i_nmpc_plan_drop; its only caller is nmpc.c */
{
    /* slots count .. nodes - 1 move to 0 .. nodes - count - 1, keys with
     * their data; the slots above keep theirs (each slot stays a matching
     * pair) */
    const size_t keep = (size_t)nodes - (size_t)count; /* caller: count < nodes <= OGK_NMPC_MAX_NODES */
    const size_t c = (size_t)count;
    const size_t u = (size_t)nu;
    (void)memmove(ctx->sens_f, &ctx->sens_f[c * NX], keep * NX * sizeof(ogk_real_t));
    (void)memmove(ctx->sens_a, &ctx->sens_a[c * NX * NX], keep * NX * NX * sizeof(ogk_real_t));
    (void)memmove(ctx->sens_b0, &ctx->sens_b0[c * NX * u], keep * NX * u * sizeof(ogk_real_t));
    (void)memmove(ctx->sens_b1, &ctx->sens_b1[c * NX * u], keep * NX * u * sizeof(ogk_real_t));
    (void)memmove(ctx->sens_h, &ctx->sens_h[c * NX], keep * NX * sizeof(ogk_real_t));
    (void)memmove(ctx->sens_ts, &ctx->sens_ts[c * NX], keep * NX * sizeof(ogk_real_t));
    (void)memmove(ctx->sens_key, &ctx->sens_key[c * KEY], keep * KEY * sizeof(ogk_real_t));
    (void)memmove(ctx->arc_mask, &ctx->arc_mask[c * OGK_OCP_MAX_KEEPOUT],
                  keep * OGK_OCP_MAX_KEEPOUT * sizeof(uint32_t));
    (void)memmove(ctx->arc_viol, &ctx->arc_viol[c * 2u], keep * 2u * sizeof(ogk_real_t));
}
