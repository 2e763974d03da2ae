/* mpsp_flight.c -- the MPSP re-planning flight software (mpsp_flight.h). */
#include "mpsp_flight.h"

#include <string.h>

#include "ogk/thrust_cmd.h"
#include "ogk_mpsp_flight_config.h"

#if defined(OGK_PIL_PROBE) && OGK_PIL_PROBE
#include "ogk_pil.h"
extern ogk_pil_stack_t ogk_pil_probe;   /* the PIL program's probe (mpsp_pil.c) */
#define CALL(slot, st, call) OGK_PIL_STACK(&ogk_pil_probe, (slot), (st) = (call))
#else
#define CALL(slot, st, call) ((st) = (call))
#endif

/* ogk_mpsp_init on the const configuration; the plan result and the command cleared (engine off
 * until the next command: the nominal trajectory is held when the init propagated it). */
static ogk_mpsp_flight_action init_context(ogk_mpsp_flight_t *f)
{
    ogk_status st = OGK_OK;
    (void)memset(&f->plan, 0, sizeof f->plan);
    (void)ogk_thrust_cmd_safe(0.0, OGK_FRAME_INERTIAL, 0u, &f->cmd);
    CALL(OGK_MPSP_FLIGHT_INIT, st, ogk_mpsp_init(&f->mpsp, &ogk_flight_mpsp_config));
    f->status[OGK_MPSP_FLIGHT_INIT] = st;
    if (st != OGK_OK) {
        f->n_nonok[OGK_MPSP_FLIGHT_INIT] += 1u;
        return OGK_MPSP_ABORT;   /* a rejected configuration (CONFIG, NONFINITE): do not thrust */
    }
    return OGK_MPSP_FLY;
}

ogk_mpsp_flight_action ogk_mpsp_flight_init(ogk_mpsp_flight_t *f)
{
    if (f == NULL) {
        return OGK_MPSP_ABORT;
    }
    f->n_replans = 0u;
    (void)memset(f->n_nonok, 0, sizeof f->n_nonok);
    (void)memset(f->status, 0, sizeof f->status);
    return init_context(f);
}

ogk_mpsp_flight_action ogk_mpsp_flight_replan(ogk_mpsp_flight_t *f, const ogk_real_t *x0,
                                              ogk_real_t thrust_scale, const ogk_real_t *target_rv)
{
    ogk_status st = OGK_OK;
    ogk_mpsp_flight_action a;
    if (f == NULL) {
        return OGK_MPSP_ABORT;
    }
    f->n_replans += 1u;
    /* into f->plan directly: on NOT_CONVERGED the kernel leaves its safe command there */
    CALL(OGK_MPSP_FLIGHT_SOLVE, st, ogk_mpsp_solve(&f->mpsp, x0, thrust_scale, target_rv,
                                                   &f->plan));
    f->status[OGK_MPSP_FLIGHT_SOLVE] = st;
    if (st != OGK_OK) {
        f->n_nonok[OGK_MPSP_FLIGHT_SOLVE] += 1u;
    }
    switch (st) {
    case OGK_OK:
        a = OGK_MPSP_FLY;            /* converged: the trajectory held is the plan's */
        break;
    case OGK_E_NOT_CONVERGED:
        a = OGK_MPSP_SAFE;           /* the safe plan (largest tau solved, else the nominal) */
        break;
    case OGK_E_NULL:
    case OGK_E_NONFINITE:
    case OGK_E_RANGE:
        /* a bad request (navigation fix, thrust estimate or target): the kernel rejects it
         * before touching the context or the result, so the previous plan (f->plan and the
         * trajectory the command reads) is still held */
        a = OGK_MPSP_HOLD;
        break;
    default:
        /* NOT_INIT: the context was corrupted (and any status ogk/mpsp.h does not list for the
         * solve, treated the same): back to the const configuration (the nominal held again
         * when the init propagates it); the previous plan is gone with the context */
        a = init_context(f);
        if (a == OGK_MPSP_FLY) {
            a = OGK_MPSP_REINIT;
        }
        break;
    }
    return a;
}

ogk_mpsp_flight_action ogk_mpsp_flight_command(ogk_mpsp_flight_t *f, ogk_real_t t)
{
    ogk_status st = OGK_OK;
    if (f == NULL) {
        return OGK_MPSP_ABORT;
    }
    /* without a trajectory held the kernel answers NOT_INIT with its safe command (engine off) */
    CALL(OGK_MPSP_FLIGHT_CMD, st, ogk_mpsp_thrust_cmd(&f->mpsp, t, &f->cmd));
    f->status[OGK_MPSP_FLIGHT_CMD] = st;
    if (st != OGK_OK) {
        /* NOT_INIT, NONFINITE, RANGE (t outside [t0, tf]), SAFE_COMMAND (lambda_v = 0): the
         * kernel wrote its safe command (engine off, SAFE flag); coast until the next re-plan */
        f->n_nonok[OGK_MPSP_FLIGHT_CMD] += 1u;
        return OGK_MPSP_SAFE;
    }
    return OGK_MPSP_FLY;
}
