/* nmpc_flight.c -- one NMPC replan of the rendezvous flight software (nmpc_flight.h), and of any
 * other problem of the same solver (ogk/ocp.h): a generated configuration that defines
 * OGK_NMPC_FLIGHT_PROBLEM (the problem's callback table) and ogk_nmpc_flight_model (its data) binds
 * that problem with ogk_nmpc_init_problem instead of the heliocentric one (the proximity approach:
 * harness/ogk/missions/proximity/flight_config.py); OGK_NMPC_FLIGHT_PRESOLVE 0 skips minimum fuel's
 * minimum-time pre-solve of the guesses (the proximity guess is the ground's minimum-fuel plan).
 * OGK_NMPC_FLIGHT_FINAL_TIME [TU] keeps that final time (the ground plan's, free on the ground): before
 * every solve the horizon bounds are narrowed to the time left to it (ogk_nmpc_set_horizon_bounds,
 * OGK_NMPC_FLIGHT_FINAL_TIME_BAND wide); the first plan comes by continuation
 * (OGK_NMPC_FLIGHT_FIRST_SOLVE_STEPS solves, their start moved from the guess's to the measured one),
 * failing that from the first guess with T free and the first BFGS matrix
 * OGK_NMPC_FLIGHT_RETRY_HESSIAN_INIT times the configuration's (its final time kept from then on); a
 * failed replan is solved again cold from the plan held with that smaller matrix
 * (harness/ogk/missions/proximity/guidance.py, KernelGuidance: the same calls). */
#include "nmpc_flight.h"

#include <string.h>

#include "ogk_nmpc_flight_config.h"

#ifndef OGK_NMPC_FLIGHT_PRESOLVE
#define OGK_NMPC_FLIGHT_PRESOLVE 1
#endif

#if defined(OGK_NMPC_FLIGHT_FINAL_TIME)
#ifndef OGK_NMPC_FLIGHT_FINAL_TIME_BAND
#define OGK_NMPC_FLIGHT_FINAL_TIME_BAND 1.0e-9
#endif
#ifndef OGK_NMPC_FLIGHT_RETRY_HESSIAN_INIT
#define OGK_NMPC_FLIGHT_RETRY_HESSIAN_INIT 1.0e-2
#endif
#ifndef OGK_NMPC_FLIGHT_FIRST_SOLVE_STEPS
#define OGK_NMPC_FLIGHT_FIRST_SOLVE_STEPS 4u
#endif
#endif

#if defined(OGK_NMPC_FLIGHT_PROBLEM)
/* the problem's data, bound to the context (ogk/ocp.h: a pointer the context keeps; copied from the
 * generated const configuration, OGK_NMPC_FLIGHT_MODEL_T its type) */
static OGK_NMPC_FLIGHT_MODEL_T flight_model;
#endif

/* ctx initialised from cfg on the flight's problem */
static ogk_status init_context(ogk_nmpc_t *ctx, const ogk_nmpc_config_t *cfg)
{
#if defined(OGK_NMPC_FLIGHT_PROBLEM)
    flight_model = ogk_nmpc_flight_model;
    return ogk_nmpc_init_problem(ctx, cfg, OGK_NMPC_FLIGHT_PROBLEM, &flight_model);
#else
    return ogk_nmpc_init(ctx, cfg);
#endif
}

#if defined(OGK_PIL_PROBE) && OGK_PIL_PROBE
#include "ogk_pil.h"
extern ogk_pil_stack_t ogk_pil_probe;   /* the PIL program's probe (nmpc_pil.c) */
#define CALL(f, slot, call)                                                                    \
    do {                                                                                       \
        ogk_status call_st_ = OGK_OK;                                                          \
        OGK_PIL_STACK(&ogk_pil_probe, (slot), call_st_ = (call));                              \
        (f)->last[(slot)] = call_st_;                                                          \
    } while (0)
#else
#define CALL(f, slot, call) ((f)->last[(slot)] = (call))
#endif

/* The SQP's own outcomes (ogk/nmpc.h, ogk_nmpc_solve): the context stays usable, the previous plan
 * (shifted) is flown. NONFINITE counts when a solve ran (a trial state left the model's domain). */
static int solver_outcome(ogk_status st, const ogk_nmpc_report_t *rep)
{
    return (st == OGK_E_ITER_LIMIT) || (st == OGK_E_NOT_CONVERGED) || (st == OGK_E_INFEASIBLE) ||
           (st == OGK_E_NOT_POSDEF) || ((st == OGK_E_NONFINITE) && (rep->solves > 0u));
}

/* A solve or replan of the flown context done: counted (the step's solves, and its failed ones). */
static ogk_status counted(ogk_nmpc_flight_t *f, ogk_status st)
{
    f->step_solves += f->rep.solves;
    f->step_failed += (st != OGK_OK) ? 1u : 0u;
    return st;
}

ogk_nmpc_action ogk_nmpc_flight_init(ogk_nmpc_flight_t *f)
{
    if (f == NULL) {
        return OGK_NMPC_ABORT;
    }
    (void)memset(f->last, 0, sizeof f->last);
    (void)memset(&f->rep, 0, sizeof f->rep);
    (void)memset(&f->cmd, 0, sizeof f->cmd);
    f->status = OGK_OK;
    f->plan_status = OGK_E_RANGE;
    f->cmd_status = OGK_E_RANGE;
    f->started = 0u;
    f->pre_iterations = 0u;
    f->guesses_tried = 0u;
    f->n_guesses = (uint32_t)OGK_NMPC_FLIGHT_N_GUESSES;
    f->settings_status = OGK_OK;
    f->step_solves = 0u;
    f->step_failed = 0u;
#if defined(OGK_NMPC_FLIGHT_FINAL_TIME)
    f->t_f_kept = (ogk_real_t)OGK_NMPC_FLIGHT_FINAL_TIME;
#else
    f->t_f_kept = 0.0;
#endif
    CALL(f, OGK_NMPC_FL_INIT, init_context(&f->ctx, &ogk_nmpc_flight_config));
    /* a rejected configuration (OGK_E_CONFIG, NONFINITE): do not start the loop */
    return (f->last[OGK_NMPC_FL_INIT] == OGK_OK) ? OGK_NMPC_FLY : OGK_NMPC_ABORT;
}

/* The guess k with the measured time and state as node 0 (guidance_base.first_guesses). */
static void measured_guess(ogk_nmpc_flight_t *f, uint32_t k)
{
    uint32_t i;
    (void)memcpy(&f->guess, &ogk_nmpc_flight_guesses[k], sizeof f->guess);
    f->guess.t0 = f->in.t;
    for (i = 0u; i < OGK_NMPC_NX; ++i) {
        f->guess.x[i] = f->in.x[i];
    }
}

/* Minimum fuel: the guess replaced by the minimum-time optimum from it at the ground's throttle
 * (kernel_guidance._first_solve, nlp.py), when that pre-solve converges; otherwise kept. */
static void min_fuel_guess(ogk_nmpc_flight_t *f)
{
    ogk_nmpc_config_t cfg = ogk_nmpc_flight_config;
    ogk_nmpc_report_t pre;
    ogk_status st;
    (void)memset(&pre, 0, sizeof pre);
    cfg.objective = OGK_NMPC_MIN_TIME;
    CALL(f, OGK_NMPC_FL_INIT, init_context(&f->time_opt, &cfg));
    if (f->last[OGK_NMPC_FL_INIT] != OGK_OK) {
        return;                 /* the time context is refused: solve from the guess itself */
    }
    CALL(f, OGK_NMPC_FL_LOAD_PLAN, ogk_nmpc_load_plan(&f->time_opt, &f->guess));
    if (f->last[OGK_NMPC_FL_LOAD_PLAN] != OGK_OK) {
        return;
    }
    CALL(f, OGK_NMPC_FL_SOLVE, ogk_nmpc_solve(&f->time_opt, &f->in, &pre));
    f->pre_iterations = pre.sqp_iterations;
    if (f->last[OGK_NMPC_FL_SOLVE] == OGK_OK) {
        CALL(f, OGK_NMPC_FL_GET_PLAN, ogk_nmpc_get_plan(&f->time_opt, &f->guess));
        st = f->last[OGK_NMPC_FL_GET_PLAN];
        if ((st == OGK_OK) && (f->guess.nu > 1u)) {   /* a throttle column to set */
            uint32_t k;
            for (k = 0u; (k <= f->guess.nodes) && (k <= OGK_NMPC_MAX_NODES); ++k) {
                f->guess.u[(k * f->guess.nu) + 1u] = OGK_NMPC_FLIGHT_MIN_FUEL_THROTTLE;
            }
            /* the ground's guess carries no multipliers (a Plan of states and controls) */
            (void)memset(f->guess.lambda, 0, sizeof f->guess.lambda);
        }
    }
}

#if defined(OGK_NMPC_FLIGHT_FINAL_TIME)
/* The bounds of T that keep f->t_f_kept from f->in.t (guidance.py, _Base._fixed_bounds); *mid their
 * middle. Not probed: a setter's frame is a leaf of a few words (make arm-stack), and a new slot would
 * change every NMPC program's stack report. */
static void keep_final_time(ogk_nmpc_flight_t *f, ogk_real_t *mid)
{
    const ogk_real_t h_min = ogk_nmpc_flight_config.horizon_min;
    ogk_real_t rem = f->t_f_kept - f->in.t;
    ogk_real_t lo;
    ogk_real_t hi;
    rem = (rem > h_min) ? rem : h_min;
    lo = rem * (OGK_R(1.0) - OGK_NMPC_FLIGHT_FINAL_TIME_BAND);
    hi = rem * (OGK_R(1.0) + OGK_NMPC_FLIGHT_FINAL_TIME_BAND);
    *mid = OGK_R(0.5) * (lo + hi);
    f->settings_status = ogk_nmpc_set_horizon_bounds(&f->ctx, lo, hi);
}

/* The configuration's bounds of T (free). */
static void free_final_time(ogk_nmpc_flight_t *f)
{
    f->settings_status = ogk_nmpc_set_horizon_bounds(&f->ctx, ogk_nmpc_flight_config.horizon_min,
                                                     ogk_nmpc_flight_config.horizon_max);
}

/* The first BFGS matrix of the next cold solve: the configuration's times scale. */
static void scale_hessian_init(ogk_nmpc_flight_t *f, ogk_real_t scale)
{
    f->settings_status = ogk_nmpc_set_hessian_init(&f->ctx, ogk_nmpc_flight_config.hessian_init * scale);
}

/* The first plan from guess k (loaded) by continuation: its start moved from the guess's node 0 to the
 * measurement in OGK_NMPC_FLIGHT_FIRST_SOLVE_STEPS solves, the last from the measurement itself
 * (KernelGuidance._first_kept). */
static void first_solve_kept(ogk_nmpc_flight_t *f, uint32_t k)
{
    const ogk_real_t *x_nom = ogk_nmpc_flight_guesses[k].x;
    const ogk_real_t steps = (ogk_real_t)OGK_NMPC_FLIGHT_FIRST_SOLVE_STEPS;
    ogk_nmpc_input_t in_j;
    ogk_real_t mid;
    uint32_t j;
    uint32_t i;
    keep_final_time(f, &mid);
    f->status = OGK_E_RANGE;
    for (j = 1u; j <= OGK_NMPC_FLIGHT_FIRST_SOLVE_STEPS; ++j) {
        in_j.t = f->in.t;
        for (i = 0u; i < OGK_NMPC_NX; ++i) {
            in_j.x[i] = (j == OGK_NMPC_FLIGHT_FIRST_SOLVE_STEPS)
                ? f->in.x[i] : (x_nom[i] + (((ogk_real_t)j / steps) * (f->in.x[i] - x_nom[i])));
        }
        CALL(f, OGK_NMPC_FL_SOLVE, ogk_nmpc_solve(&f->ctx, &in_j, &f->rep));
        f->status = counted(f, f->last[OGK_NMPC_FL_SOLVE]);
        if (f->status != OGK_OK) {
            return;
        }
    }
}

/* A first plan that failed with the final time kept: once more from the first guess with T free and a
 * smaller first BFGS matrix (longer first steps), its final time kept from here on. */
static void retry_free(ogk_nmpc_flight_t *f)
{
    free_final_time(f);
    scale_hessian_init(f, OGK_NMPC_FLIGHT_RETRY_HESSIAN_INIT);
    measured_guess(f, 0u);
    CALL(f, OGK_NMPC_FL_LOAD_PLAN, ogk_nmpc_load_plan(&f->ctx, &f->guess));
    f->status = f->last[OGK_NMPC_FL_LOAD_PLAN];
    if (f->status == OGK_OK) {
        CALL(f, OGK_NMPC_FL_SOLVE, ogk_nmpc_solve(&f->ctx, &f->in, &f->rep));
        f->status = counted(f, f->last[OGK_NMPC_FL_SOLVE]);
    }
    scale_hessian_init(f, 1.0);
    if (f->status == OGK_OK) {
        CALL(f, OGK_NMPC_FL_GET_PLAN, ogk_nmpc_get_plan(&f->ctx, &f->plan));
        if (f->last[OGK_NMPC_FL_GET_PLAN] == OGK_OK) {
            f->t_f_kept = f->plan.t0 + f->plan.horizon;
        }
    }
}

/* A replan with the final time kept; failed, solved again cold from the plan held (the previous one,
 * shifted) with a smaller first BFGS matrix (KernelGuidance._replan_kept). */
static void replan_kept(ogk_nmpc_flight_t *f)
{
    ogk_real_t mid;
    keep_final_time(f, &mid);
    CALL(f, OGK_NMPC_FL_REPLAN, ogk_nmpc_replan(&f->ctx, &f->in, &f->rep));
    f->status = counted(f, f->last[OGK_NMPC_FL_REPLAN]);
    if (!solver_outcome(f->status, &f->rep)) {
        return;                 /* converged, or the measurement itself was rejected */
    }
    CALL(f, OGK_NMPC_FL_GET_PLAN, ogk_nmpc_get_plan(&f->ctx, &f->guess));
    if (f->last[OGK_NMPC_FL_GET_PLAN] != OGK_OK) {
        return;
    }
    f->guess.t0 = f->in.t;
    f->guess.horizon = mid;
    (void)memset(f->guess.lambda, 0, sizeof f->guess.lambda);   /* as the SIL's load_plan of it */
    scale_hessian_init(f, OGK_NMPC_FLIGHT_RETRY_HESSIAN_INIT);
    CALL(f, OGK_NMPC_FL_LOAD_PLAN, ogk_nmpc_load_plan(&f->ctx, &f->guess));
    if (f->last[OGK_NMPC_FL_LOAD_PLAN] == OGK_OK) {
        CALL(f, OGK_NMPC_FL_SOLVE, ogk_nmpc_solve(&f->ctx, &f->in, &f->rep));
        f->status = counted(f, f->last[OGK_NMPC_FL_SOLVE]);
    }
    scale_hessian_init(f, 1.0);
}
#endif

/* The first replan: each guess in turn until a solve converges (KernelGuidance.replan). */
static void first_replan(ogk_nmpc_flight_t *f)
{
    uint32_t k;
    f->status = OGK_E_RANGE;
    for (k = 0u; k < (uint32_t)OGK_NMPC_FLIGHT_N_GUESSES; ++k) {
        measured_guess(f, k);
        if ((OGK_NMPC_FLIGHT_PRESOLVE != 0) && (ogk_nmpc_flight_config.objective != OGK_NMPC_MIN_TIME)) {
            min_fuel_guess(f);
        }
        f->guesses_tried = k + 1u;
        CALL(f, OGK_NMPC_FL_RESET, ogk_nmpc_reset(&f->ctx));
        if (f->last[OGK_NMPC_FL_RESET] != OGK_OK) {
            f->status = f->last[OGK_NMPC_FL_RESET];
            return;             /* the context is lost: the step re-initialises it */
        }
#if defined(OGK_NMPC_FLIGHT_FINAL_TIME)
        free_final_time(f);     /* the guess is checked against the configuration's bounds */
#endif
        CALL(f, OGK_NMPC_FL_LOAD_PLAN, ogk_nmpc_load_plan(&f->ctx, &f->guess));
        if (f->last[OGK_NMPC_FL_LOAD_PLAN] != OGK_OK) {
            f->status = f->last[OGK_NMPC_FL_LOAD_PLAN];
            (void)memset(&f->rep, 0, sizeof f->rep);
            return;             /* a guess the kernel refuses: the measurement is out of range */
        }
#if defined(OGK_NMPC_FLIGHT_FINAL_TIME)
        first_solve_kept(f, k);
#else
        CALL(f, OGK_NMPC_FL_SOLVE, ogk_nmpc_solve(&f->ctx, &f->in, &f->rep));
        f->status = counted(f, f->last[OGK_NMPC_FL_SOLVE]);
#endif
        if (f->status == OGK_OK || !solver_outcome(f->status, &f->rep)) {
            return;             /* converged, or the measurement itself was rejected */
        }
    }
#if defined(OGK_NMPC_FLIGHT_FINAL_TIME)
    retry_free(f);
#endif
}

ogk_nmpc_action ogk_nmpc_flight_step(ogk_nmpc_flight_t *f, const ogk_nmpc_input_t *in)
{
    ogk_nmpc_action action;
    uint32_t first;
    if (f == NULL || in == NULL) {
        return OGK_NMPC_REINIT;
    }
    f->in = *in;
    f->pre_iterations = 0u;
    f->step_solves = 0u;
    f->step_failed = 0u;
    first = (f->started == 0u) ? 1u : 0u;
    if (first != 0u) {
        first_replan(f);
        f->started = 1u;
    } else {
#if defined(OGK_NMPC_FLIGHT_FINAL_TIME)
        replan_kept(f);
#else
        CALL(f, OGK_NMPC_FL_REPLAN, ogk_nmpc_replan(&f->ctx, &f->in, &f->rep));
        f->status = counted(f, f->last[OGK_NMPC_FL_REPLAN]);
#endif
    }
    if (f->status == OGK_OK) {
        action = OGK_NMPC_FLY;
    } else if (solver_outcome(f->status, &f->rep)) {
        /* a failed first replan has only its last guess loaded: nothing worth flying */
        action = (first != 0u) ? OGK_NMPC_NO_PLAN : OGK_NMPC_FLY_STALE;
    } else if (f->status == OGK_E_NOT_INIT || f->status == OGK_E_NULL) {
        action = OGK_NMPC_REINIT;
    } else {
        action = OGK_NMPC_HOLD;   /* NONFINITE / RANGE / DIM of the measurement: plan untouched */
    }
    /* the plan flown and the command at t, whatever the outcome (the link sends both) */
    CALL(f, OGK_NMPC_FL_GET_PLAN, ogk_nmpc_get_plan(&f->ctx, &f->plan));
    f->plan_status = f->last[OGK_NMPC_FL_GET_PLAN];
    CALL(f, OGK_NMPC_FL_COMMAND, ogk_nmpc_command(&f->ctx, f->in.t, &f->cmd));
    f->cmd_status = f->last[OGK_NMPC_FL_COMMAND];
    if ((first != 0u) && ((action == OGK_NMPC_NO_PLAN) || (f->plan_status != OGK_OK))) {
        f->started = 0u;   /* no first plan: the next replan starts cold again, from the guesses */
    }
    if (action == OGK_NMPC_REINIT) {
        const ogk_status st = f->status;
        (void)ogk_nmpc_flight_init(f);   /* ABORT here leaves the context refusing every call */
        f->status = st;
    }
    if (action == OGK_NMPC_NO_PLAN || action == OGK_NMPC_REINIT || f->cmd_status != OGK_OK) {
        /* engine off: the kernel's safe command (ogk_nmpc_command with no plan) */
        f->cmd.t = f->in.t;
        f->cmd.alpha = 0.0;
        f->cmd.throttle = 0.0;
        f->cmd.flags = OGK_THRUST_FLAG_SAFE;
    }
    return action;
}
