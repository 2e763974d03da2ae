/* oi_flight.c -- one control tick of the orbit-injection flight software (oi_flight.h). */
#include "oi_flight.h"

#include <math.h>
#include <string.h>

#include "ogk/thrust_cmd.h"
#include "ogk_orbit_injection_flight_config.h"

#if defined(OGK_PIL_PROBE) && OGK_PIL_PROBE
#include "ogk_pil.h"
extern ogk_pil_stack_t ogk_pil_probe;   /* the PIL program's probe (oi_pil.c) */
#define CALL(slot, st, call) OGK_PIL_STACK(&ogk_pil_probe, (slot), (st) = (call))
#else
#define CALL(slot, st, call) ((st) = (call))
#endif

ogk_flight_action ogk_oi_flight_init(ogk_oi_flight_t *f, const uint8_t *image, size_t len)
{
    ogk_flight_action a;
    if (f == NULL) {
        return OGK_FLIGHT_ABORT;
    }
    memset(f->status, 0, sizeof f->status);
    f->t_predicted_s = INFINITY;
    f->t_cutoff_s = INFINITY;
    f->engaged = 0u;
    f->sampled = 0u;
#if OGK_REAL_SINGLE
    f->r_lo_m = OGK_R(0.0);
#endif
    /* NOG with the end-game's last sampling interval, CPD: the reactions of ogk_flight.c */
    a = ogk_flight_init(&f->base, image, len, &ogk_flight_endgame_nog_config,
                        &ogk_flight_cpd_config, OGK_FLIGHT_CONTROL_RATE_HZ);
    if (a != OGK_FLIGHT_FLY) {
        return a;
    }
    if (ogk_cutoff_init(&f->cutoff, &ogk_flight_cutoff_config) != OGK_OK ||
        ogk_terminal_init(&f->terminal, &ogk_flight_terminal_config) != OGK_OK) {
        f->base.engine_on = 0u;
        return OGK_FLIGHT_ABORT;   /* a rejected configuration: do not ignite */
    }
    return OGK_FLIGHT_FLY;
}

/* Whether guidance samples at tick k: every Delta t_S, and every fine period once the predicted
 * time to go is inside the fine window (sil.py's schedule, on the previous tick's prediction). */
static int sample_due(const ogk_oi_flight_t *f, uint32_t k, ogk_real_t t_s)
{
    int due = (k % (uint32_t)OGK_FLIGHT_TICKS_PER_SAMPLE) == 0u;
#if OGK_FLIGHT_FINE_TICKS > 0
    if (k % (uint32_t)OGK_FLIGHT_FINE_TICKS == 0u &&
        f->t_predicted_s - t_s <= OGK_FLIGHT_FINE_WINDOW_S) {
        due = 1;
    }
#else
    (void)t_s;
#endif
    /* eq. (32): after the terminating sample the cut-off time is final, no further sample */
    return due && t_s < f->t_predicted_s && !f->base.terminating;
}

/* Keeps the first failure of the tick: the tick goes on with the kernel's safe outputs, as in flight. */
static void note(ogk_oi_failure *first, ogk_oi_failure fail)
{
    if (*first == OGK_OI_OK) {
        *first = fail;
    }
}

ogk_oi_failure ogk_oi_flight_tick(ogk_oi_flight_t *f, uint32_t k, const ogk_nav_state_t *nav,
                                  const ogk_flight_att_t *att)
{
    ogk_flight_t *b = &f->base;
    ogk_oi_failure fail = OGK_OI_OK;
    ogk_status st = OGK_OK;
    ogk_cpd_input_t in;

    f->sampled = 0u;
    if (sample_due(f, k, nav->t_s)) {
        ogk_flight_action a;
        CALL(OGK_OI_NOG_SAMPLE, st, ogk_nog_sample(&b->nog, nav, &b->sample));
        f->status[OGK_OI_NOG_SAMPLE] = st;
        f->sampled = 1u;
        b->n_samples += 1u;
        a = ogk_flight_reaction(OGK_FLIGHT_CALL_SAMPLE, st);
        if (a == OGK_FLIGHT_FLY || a == OGK_FLIGHT_SAFE) {
            /* both wrote a sample: the safe one holds the last valid correction and t_f */
            f->t_predicted_s = b->sample.t_cutoff_s;
            if ((b->sample.flags & OGK_NOG_FLAG_TERMINATING) != 0u) {
                b->terminating = 1u;
            }
        } else if (a == OGK_FLIGHT_HOLD) {
            /* context lost: re-initialise from the const configuration (nominal from tau = 0) */
            (void)ogk_nog_init(&b->nog, &b->nog_cfg);
        } else {
            b->engine_on = 0u;   /* RELOAD_TABLE / ABORT: not recoverable in flight */
        }
        if (st != OGK_OK) {
            b->n_nonok[OGK_FLIGHT_CALL_SAMPLE] += 1u;
            note(&fail, OGK_OI_FAIL_GUIDANCE);   /* the SIL counts the run failed from here */
        }
    }
    if (isnan(f->t_predicted_s)) {
        note(&fail, OGK_OI_FAIL_GUIDANCE);
    }
    f->t_cutoff_s = f->t_predicted_s;
#if OGK_FLIGHT_ENERGY_CUTOFF
    if (isfinite(f->t_predicted_s)) {
        ogk_cutoff_out_t co;
        CALL(OGK_OI_CUTOFF_STEP, st, ogk_cutoff_step(&f->cutoff, nav, f->t_predicted_s, &co));
        f->status[OGK_OI_CUTOFF_STEP] = st;
        if (st == OGK_OK) {
            f->t_cutoff_s = co.t_cutoff_s;
        } else {
            note(&fail, OGK_OI_FAIL_CUTOFF);     /* the prediction stays the cut-off */
        }
    }
#endif
    CALL(OGK_OI_NOG_COMMAND, st, ogk_nog_thrust_cmd(&b->nog, nav->t_s, &b->cmd));
    f->status[OGK_OI_NOG_COMMAND] = st;
    if (!(isfinite(b->cmd.alpha_rad) && isfinite(b->cmd.beta_rad))) {
        note(&fail, OGK_OI_FAIL_GUIDANCE);       /* CPD below answers with its safe command */
    }
#if OGK_FLIGHT_TERMINAL
    if (isfinite(f->t_predicted_s)) {
        ogk_thrust_cmd_t law;
        ogk_thrust_cmd_t out;
        st = ogk_thrust_cmd_from_angles(nav->t_s, b->cmd.alpha_rad, b->cmd.beta_rad, 1.0,
                                        OGK_THRUST_FLAG_ENGINE_ON, 0u, &law);
        if (st == OGK_OK) {
#if OGK_REAL_SINGLE
            /* the float radius steps by 4 m at the GEO radius: the terminal stage takes its low part
             * too (docs/design/vtd-nog.md, "Single precision") */
            CALL(OGK_OI_TERMINAL_STEP, st,
                 ogk_terminal_step_split(&f->terminal, nav, f->r_lo_m, f->t_predicted_s, &law, &out));
#else
            CALL(OGK_OI_TERMINAL_STEP, st,
                 ogk_terminal_step(&f->terminal, nav, f->t_predicted_s, &law, &out));
#endif
        }
        f->status[OGK_OI_TERMINAL_STEP] = st;
        if (st == OGK_OK) {
            b->cmd.alpha_rad = out.alpha_rad;
            b->cmd.beta_rad = out.beta_rad;
            f->engaged = (uint8_t)((out.law_flags & OGK_TERMINAL_FLAG_ENGAGED) != 0u);
        } else {
            f->engaged = 0u;                     /* the law's command is flown */
            note(&fail, OGK_OI_FAIL_TERMINAL);
        }
    }
#endif
    /* CPD on the command's angles (as the SIL's batch step: alpha, beta, xi, phi) */
    ogk_flight_cpd_attitude(att, &in);
    in.alpha_c = b->cmd.alpha_rad;
    in.beta_c = b->cmd.beta_rad;
    in.xi = nav->xi_rad;
    in.phi = nav->phi_rad;
    CALL(OGK_OI_CPD_STEP, st, ogk_cpd_step(&b->cpd, &in, &b->act));
    f->status[OGK_OI_CPD_STEP] = st;
    b->n_ticks += 1u;
    if (ogk_flight_reaction(OGK_FLIGHT_CALL_CPD, st) == OGK_FLIGHT_HOLD) {
        (void)ogk_cpd_init(&b->cpd, &b->cpd_cfg);   /* context lost: re-init, safe command held */
    }
    if (st != OGK_OK) {
        /* CPD wrote its safe command (zero torque, zero deflections) */
        note(&fail, OGK_OI_FAIL_ATTITUDE);
    }
    return fail;
}
