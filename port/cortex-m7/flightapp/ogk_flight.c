/* ogk_flight.c -- flight integration layer (ogk_flight.h, docs/guides/flight-integration.md). */
#include "ogk_flight.h"

#include <math.h>
#include <string.h>

ogk_flight_action ogk_flight_reaction(ogk_flight_call call, ogk_status st)
{
    switch (st) {
    case OGK_OK:
        return OGK_FLIGHT_FLY;
    case OGK_E_TABLE_MAGIC:
    case OGK_E_TABLE_VERSION:
    case OGK_E_TABLE_TYPE:
    case OGK_E_TABLE_DIM:
    case OGK_E_TABLE_TRUNCATED:
    case OGK_E_TABLE_SIZE:
    case OGK_E_TABLE_CRC:
        /* Only the table loader returns these: the image is corrupt or not the expected table.
         * The context is empty (n_grid = 0): load a redundant copy, never fly a rejected one. */
        return OGK_FLIGHT_RELOAD_TABLE;
    case OGK_E_NONFINITE:
    case OGK_E_RANGE:
        if (call == OGK_FLIGHT_CALL_TABLE) {
            return OGK_FLIGHT_RELOAD_TABLE; /* NaN/Inf in the payload */
        }
        if (call == OGK_FLIGHT_CALL_INIT) {
            return OGK_FLIGHT_ABORT;        /* NaN in a configuration: a ground error */
        }
        /* Bad navigation or attitude input (NaN/Inf, time not increasing, past the cut-off):
         * the kernel has written its safe output (NOG: last valid correction held, tau advanced
         * with the t_f in force; CPD: zero torque and deflections). Fly it; the next good input
         * recovers. */
        return OGK_FLIGHT_SAFE;
    case OGK_E_SAFE_COMMAND:
        return OGK_FLIGHT_SAFE;
    case OGK_E_NOT_INIT:
        /* A context was lost (e.g. memory scrubbed or reset): re-initialise it from the const
         * configuration; at init it means an empty table, i.e. the load failed. */
        if (call == OGK_FLIGHT_CALL_INIT) {
            return OGK_FLIGHT_RELOAD_TABLE;
        }
        return OGK_FLIGHT_HOLD;
    case OGK_E_TABLE_STALE:
        /* The table the NOG context was bound to has been (re)loaded since its init (the kernel
         * flew the held correction and read nothing from the table): re-initialise the context on
         * the table as it is now; if that table is bad, the init says so and it is reloaded. */
        if (call == OGK_FLIGHT_CALL_INIT) {
            return OGK_FLIGHT_RELOAD_TABLE;
        }
        return OGK_FLIGHT_HOLD;
    case OGK_E_CONFIG:
        return OGK_FLIGHT_ABORT;            /* rejected configuration: do not ignite */
    case OGK_E_FRAME:
        /* The attitude loop was handed a command in a frame it cannot convert (a synodic command
         * not rotated to inertial): the application wired a law wrongly; no tick can fix it. */
        return OGK_FLIGHT_ABORT;
    case OGK_E_ALIGN:
        /* The image is not 8-byte aligned (a build defect; the generated C aligns it): reading
         * it again does not help. Do not ignite (or decode it with ogk_nog_table_load). */
        return OGK_FLIGHT_ABORT;
    case OGK_E_BYTE_ORDER:
        /* A valid image, but this target does not store a double as the image does (big-endian:
         * SPARC/LEON, PowerPC), so it cannot be read in place: a build defect, reading it again
         * does not help. Do not ignite; build with OGK_FLIGHT_TABLE_COPY=1 (docs/guides/ports.md). */
        return OGK_FLIGHT_ABORT;
    case OGK_E_NULL:
    case OGK_E_DIM:
    case OGK_E_SINGULAR:
    case OGK_E_ILL_CONDITIONED:
    case OGK_E_OVERFLOW:
    case OGK_E_NOT_POSDEF:
    case OGK_E_SWITCH_OVERFLOW:
    case OGK_E_STEP_LIMIT:
    case OGK_E_CALLBACK:
    case OGK_E_NOT_CONVERGED:
    case OGK_STATUS_COUNT:
    default:
        /* Not returned by these calls with valid arguments: a software fault. */
        return OGK_FLIGHT_ABORT;
    }
}

static ogk_flight_action count(ogk_flight_t *f, ogk_flight_call call, ogk_status st)
{
    f->last_status = st;
    if (st != OGK_OK) {
        f->n_nonok[call] += 1u;
    }
    return ogk_flight_reaction(call, st);
}

/* How far Delta t_S x rate may lie from a whole number of ticks: rounding of the product (below a
 * million ticks: 1e-9 in double; a float's ulp at 2^20 is 2^-3, so the single-precision kernel allows
 * 1e-4 relative to the tick count, below any real misconfiguration of a fraction of a tick). */
#if OGK_REAL_SINGLE
#define OGK_FLIGHT_TICKS_TOL (OGK_R(1.0e-4) * ticks)
#else
#define OGK_FLIGHT_TICKS_TOL 1.0e-9
#endif

ogk_flight_action ogk_flight_init(ogk_flight_t *f, const uint8_t *image, size_t len,
                                  const ogk_nog_config_t *nog_cfg,
                                  const ogk_cpd_config_t *cpd_cfg, ogk_real_t control_rate_hz)
{
    ogk_flight_action a;
    ogk_real_t ticks;

    if (f == NULL || nog_cfg == NULL || cpd_cfg == NULL) {
        return OGK_FLIGHT_ABORT;
    }
    f->engine_on = 0u;
#if OGK_FLIGHT_TABLE_COPY
    a = count(f, OGK_FLIGHT_CALL_TABLE, ogk_nog_table_load(&f->table, image, len));
#else
    a = count(f, OGK_FLIGHT_CALL_TABLE, ogk_nog_table_view(&f->table, image, len));
#endif
    if (a != OGK_FLIGHT_FLY) {
        return a;
    }
    f->nog_cfg = *nog_cfg;
#if OGK_FLIGHT_TABLE_COPY
    f->nog_cfg.table = &f->table;
    f->nog_cfg.view = NULL;
#else
    f->nog_cfg.table = NULL;
    f->nog_cfg.view = &f->table;
#endif
    f->cpd_cfg = *cpd_cfg;
    a = count(f, OGK_FLIGHT_CALL_INIT, ogk_nog_init(&f->nog, &f->nog_cfg));
    if (a != OGK_FLIGHT_FLY) {
        return a;
    }
    a = count(f, OGK_FLIGHT_CALL_INIT, ogk_cpd_init(&f->cpd, &f->cpd_cfg));
    if (a != OGK_FLIGHT_FLY) {
        return a;
    }
    ticks = f->nog_cfg.sample_interval_s * control_rate_hz;
    if (!(ticks >= OGK_R(1.0) && ticks < OGK_R(1.0e6)) ||
        OGK_FABS(ticks - OGK_FLOOR(ticks + OGK_R(0.5))) > OGK_FLIGHT_TICKS_TOL) {
        return OGK_FLIGHT_ABORT; /* the sampling interval is not a whole number of ticks */
    }
    f->ticks_per_sample = (uint32_t)OGK_FLOOR(ticks + OGK_R(0.5));
    f->t_cutoff_s = f->table.t_f_star_s;
    f->n_samples = 0u;
    f->n_ticks = 0u;
    f->terminating = 0u;
    memset(&f->sample, 0, sizeof f->sample);
    memset(&f->cmd, 0, sizeof f->cmd);
    memset(&f->act, 0, sizeof f->act);
    f->engine_on = 1u;
    return OGK_FLIGHT_FLY;
}

ogk_flight_action ogk_flight_guidance(ogk_flight_t *f, const ogk_nav_state_t *nav)
{
    ogk_flight_action a = count(f, OGK_FLIGHT_CALL_SAMPLE, ogk_nog_sample(&f->nog, nav, &f->sample));

    f->n_samples += 1u;
    switch (a) {
    case OGK_FLIGHT_FLY:
    case OGK_FLIGHT_SAFE:
        /* Both write a sample (the safe one keeps the correction and t_f in force). */
        f->t_cutoff_s = f->sample.t_cutoff_s;
        if ((f->sample.flags & OGK_NOG_FLAG_TERMINATING) != 0u) {
            f->terminating = 1u; /* eq. (32): no further sample, the cut-off time is final */
        }
        break;
    case OGK_FLIGHT_HOLD:
        /* Context lost: restart from the nominal. The command then serves the nominal from
         * tau = 0 until the next sample; in flight, prefer restoring a checkpoint of f->nog. */
        (void)count(f, OGK_FLIGHT_CALL_INIT, ogk_nog_init(&f->nog, &f->nog_cfg));
        break;
    case OGK_FLIGHT_RELOAD_TABLE:
    case OGK_FLIGHT_ABORT:
    default:
        f->engine_on = 0u;
        break;
    }
    return a;
}

void ogk_flight_cpd_attitude(const ogk_flight_att_t *att, ogk_cpd_input_t *in)
{
    in->psi = att->psi;
    in->theta = att->theta;
    in->phi_roll = att->phi_roll;
    in->rate_p = att->rate_p;
    in->rate_q = att->rate_q;
    in->rate_r = att->rate_r;
}

ogk_flight_action ogk_flight_attitude(ogk_flight_t *f, const ogk_thrust_cmd_t *cmd,
                                      const ogk_flight_att_t *att, const ogk_nav_state_t *nav)
{
    ogk_cpd_input_t in;
    ogk_flight_action b;

    if (cmd != &f->cmd) {
        f->cmd = *cmd;
    }
    if ((f->cmd.flags & OGK_THRUST_FLAG_ENGINE_ON) == 0u) {
        f->engine_on = 0u; /* at or past the cut-off (or the law's own engine-off) */
    }
    ogk_flight_cpd_attitude(att, &in);
    /* any frame CPD converts: the law's direction as r-t-n angles at nav's position */
    b = count(f, OGK_FLIGHT_CALL_CPD, ogk_cpd_input_from_thrust_cmd(&in, &f->cmd, nav));
    if (b == OGK_FLIGHT_FLY) {
        b = count(f, OGK_FLIGHT_CALL_CPD, ogk_cpd_step(&f->cpd, &in, &f->act));
    } else {
        /* A non-finite command or position, or a frame CPD cannot take: no CPD step, the safe
         * actuator command. */
        memset(&f->act, 0, sizeof f->act);
        f->act.flags = OGK_CPD_FLAG_SAFE;
    }
    if (b == OGK_FLIGHT_HOLD) {
        /* CPD context lost: re-initialise from the const configuration; f->act holds the safe
         * command (zero torque, zero deflections) for this tick. */
        (void)count(f, OGK_FLIGHT_CALL_INIT, ogk_cpd_init(&f->cpd, &f->cpd_cfg));
    } else if (b == OGK_FLIGHT_ABORT) {
        f->engine_on = 0u;
    }
    return b;
}

ogk_flight_action ogk_flight_control(ogk_flight_t *f, ogk_real_t t_s, const ogk_flight_att_t *att,
                                     const ogk_nav_state_t *nav)
{
    ogk_flight_action a;
    ogk_flight_action b;

    f->n_ticks += 1u;
    if (!(t_s < f->t_cutoff_s)) {
        f->engine_on = 0u;
    }
    a = count(f, OGK_FLIGHT_CALL_COMMAND, ogk_nog_thrust_cmd(&f->nog, t_s, &f->cmd));
    if (a == OGK_FLIGHT_HOLD) {
        /* Guidance context lost: re-initialise (nominal from tau = t / t_f*) and command again. */
        (void)count(f, OGK_FLIGHT_CALL_INIT, ogk_nog_init(&f->nog, &f->nog_cfg));
        (void)count(f, OGK_FLIGHT_CALL_COMMAND, ogk_nog_thrust_cmd(&f->nog, t_s, &f->cmd));
    } else if (a != OGK_FLIGHT_FLY && a != OGK_FLIGHT_SAFE) {
        f->engine_on = 0u;
        memset(&f->act, 0, sizeof f->act);
        return a;
    }
    /* NOG's command is the common thrust command (r-t-n): the same attitude tick as any law's */
    b = ogk_flight_attitude(f, &f->cmd, att, nav);
    return b > a ? b : a;
}
