/* blt_internal.h -- internals of ogk_blt shared by blt.c (configuration, corrector),
 * blt_model.c (the right-hand side and its derivatives) and blt_arc.c (propagation of the
 * arcs, errors, Jacobians). Not public API. Design notes: docs/design/blt.md. */
#ifndef OGK_BLT_INTERNAL_H
#define OGK_BLT_INTERNAL_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "ogk/blt.h"
#include "../ogk_checks.h"

/* the linear algebra of the corrector must hold the error vector */
#if OGK_BLT_MAX_ERRORS > OGK_LA_MAX_N
#error "OGK_BLT_MAX_ERRORS exceeds OGK_LA_MAX_N (ogk_minnorm)"
#endif
#if (OGK_BLT_MAX_UNKNOWNS + OGK_BLT_MAX_ERRORS) > OGK_LA_MAX_LONG
#error "OGK_BLT_MAX_UNKNOWNS + OGK_BLT_MAX_ERRORS exceeds OGK_LA_MAX_LONG (ogk_minnorm)"
#endif
/* the segment_free bits are the parameter indices of a segment: A 0-2, B 3-5, T 6 */
#if (OGK_BLT_FREE_A != 0x07u) || (OGK_BLT_FREE_B != 0x38u) || (OGK_BLT_FREE_T != (1u << 6)) || \
    (OGK_BLT_FREE_ALL != (OGK_BLT_FREE_A | OGK_BLT_FREE_B | OGK_BLT_FREE_T))
#error "OGK_BLT_FREE_* must be the bits of the parameter indices"
#endif

#define BLT_T_ABS_MAX OGK_R(1.0e6) /* [TU] |t0| bound */

/* What a segment's right-hand side needs besides the state. */
typedef struct {
    ogk_real_t t_start;   /* [TU] absolute time at tau = 0 */
    ogk_real_t m_start;   /* [-] mass fraction at tau = 0 */
    ogk_real_t a[3];      /* [-] BLT A (burn) */
    ogk_real_t b[3];      /* [1/TU] BLT B (burn) */
    bool burn;        /* engine on */
} ogk_i_blt_seg_t;

/* Per-term pieces of the right-hand side at one point, for the variational equations. */
typedef struct {
    ogk_real_t grad[9];     /* [1/TU^2] d(acceleration)/d(position), gravity + centrifugal + solar tide */
    ogk_real_t u_hat[3];    /* [-] thrust direction (burn) */
    ogk_real_t w_norm;      /* [-] |A + B tau| (burn) */
    ogk_real_t thrust;      /* [LU/TU^2] thrust acceleration magnitude, thrust_accel / m (burn) */
    ogk_real_t srp;         /* [LU/TU^2] SRP acceleration magnitude, srp_accel / m */
    ogk_real_t s_hat[3];    /* [-] the Sun's direction */
    ogk_real_t ds_hat[3];   /* [1/TU] its time derivative */
    ogk_real_t mass;        /* [-] mass fraction */
} ogk_i_blt_rhs_parts_t;

/* f(t, x): dx = (v, a). tau = time since the segment's start. parts (may be NULL) receives the
 * pieces the variational equations need (grad only when parts is given). Returns false when the
 * direction A + B tau vanishes or the mass is not positive (no finite thrust direction). */
bool ogk_i_blt_rhs(const ogk_blt_model_t *m, const ogk_i_blt_seg_t *seg, ogk_real_t tau, const ogk_real_t x[OGK_BLT_NX],
             ogk_real_t dx[OGK_BLT_NX], ogk_i_blt_rhs_parts_t *parts);

/* Segment k's start time, start mass, kind and A, B. */
void ogk_i_blt_segment(const ogk_blt_config_t *cfg, const ogk_blt_transfer_t *tr, uint32_t k, ogk_i_blt_seg_t *seg);

/* Number of unknowns / errors the configuration implies. */
uint32_t ogk_i_blt_count_unknowns(const ogk_blt_config_t *cfg);
uint32_t ogk_i_blt_count_errors(const ogk_blt_config_t *cfg);
/* u <- the unknowns of tr; tr <- tr with its unknowns replaced by u. */
void ogk_i_blt_pack(const ogk_blt_config_t *cfg, const ogk_blt_transfer_t *tr, ogk_real_t *u);
void ogk_i_blt_unpack(const ogk_blt_config_t *cfg, const ogk_real_t *u, ogk_blt_transfer_t *tr);

/* Result of one evaluation of the error vector. */
typedef struct {
    bool impact;              /* a body was hit (propagation of that arc stopped there) */
    bool bad_rhs;             /* no finite right-hand side (A + B tau = 0 or mass <= 0) */
    uint32_t propagations;    /* segments propagated */
    ogk_real_t min_distance[2];   /* [LU] closest approach at the RK4 nodes */
} ogk_i_blt_eval_t;

/* e = the errors of tr (all arcs). sens (ctx->jac layout) receives de/du when non-NULL
 * (variational equations). Uses ctx->seg_steps when ctx->steps_frozen. */
void ogk_i_blt_errors(ogk_blt_t *ctx, const ogk_blt_transfer_t *tr, ogk_real_t *e, ogk_real_t *sens, ogk_i_blt_eval_t *ev);

/* Forward propagation of the whole chain (free nodes ignored). */
void ogk_i_blt_chain(ogk_blt_t *ctx, const ogk_blt_transfer_t *tr, ogk_real_t x_end[OGK_BLT_NX], ogk_i_blt_eval_t *ev);

/* RK4 step count of a segment of duration T. */
uint32_t ogk_i_blt_steps_for(const ogk_blt_config_t *cfg, ogk_real_t duration);

#endif /* OGK_BLT_INTERNAL_H */
