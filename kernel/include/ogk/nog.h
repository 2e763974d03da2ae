/* ogk/nog.h -- variable-time-domain neighboring optimal guidance (VTD-NOG),
 * Pontani & Celani (2021), section 4, with the formulation of docs/design/vtd-nog.md
 * (real time t as a 7th state, parameter a = t_f).
 *
 * Ground side (host/ogk_host/orbit_injection): the minimum-time nominal and, on a grid
 * of normalised time tau in [0, 1], the gains that map the state displacement
 * dx_k = [x(t_k) - x*(tau_k); t_k - t_f* tau_k] to the costate displacement
 * dlam_k and the flight-time correction dt_f, plus the costate-rate gain that
 * gives a first-order hold of dlam inside the sampling interval.
 *
 * Flight side, at each sampling time t_k (ogk_nog_sample):
 *   tau_k   = tau_(k-1) + (t_k - t_(k-1)) / t_f^(k-1)        (eq. 31, tau_0 = t_0 / t_f*)
 *   [dlam_k; dt_f] = G(tau_k) dx_k,   t_f^(k) = t_f* + dt_f
 *   cut-off predicted at t_k + (1 - tau_k) t_f^(k); eq. (32): the last interval
 *   is the one with tau_k + Delta t_S / t_f^(k) >= 1.
 * Between samples (ogk_nog_thrust_cmd), for tau = tau_k + (t - t_k) / t_f^(k):
 *   lambda(tau) = lambda*(tau) + dlam_k + N(tau_k) dx_k (tau - tau_k)
 *   and the thrust angles from the velocity costates, eq. (27) -- to first
 *   order the same as eq. (30), since H_ux = H_ua = 0 on this nominal, but it
 *   always yields a unit thrust direction.
 * End-game (the paper is silent, docs/design/vtd-nog.md): no new correction once
 * 1 - tau_k < tau_freeze or tau_k is past the last gain node; |dt_f| clipped
 * to dtf_max_s; the corrected thrust direction kept within du_max_rad of the
 * nominal one by scaling the costate correction.
 *
 * State vector order (SI): [r m, xi rad, phi rad, v_r m/s, v_t m/s, v_n m/s, t s]. */
#ifndef OGK_NOG_H
#define OGK_NOG_H

#include <stddef.h>
#include <stdint.h>
#include "ogk/status.h"
#include "ogk/types.h"
#include "ogk/real.h"

#ifdef __cplusplus
extern "C" {
#endif

#define OGK_NOG_NX 7u            /* state (and costate) size */
#define OGK_NOG_TABLE_KIND 0x4E4F4742u /* "NOGB": one bundle entry per tau node */

/* Entry layout of the table bundle (one row of OGK_NOG_ENTRY_LEN reals per
 * tau node, SI, ' = d/dtau):
 *   [  0,  7) x*        [  7, 14) x*'       [ 14, 21) lambda*   [ 21, 28) lambda*'
 *   [ 28, 84) G (8 x 7, row-major): rows 0..6 -> dlam_k, row 7 -> dt_f [s]
 *   [ 84,133) N (7 x 7, row-major): dlam'(tau_k) = N dx_k
 * Costates are scaled with H = -1 at tau = 1 (any positive scale would do:
 * only the direction of the velocity costates is flown). The grid runs from
 * tau = 0 to tau = 1 inclusive; the gain blocks of the last node (tau = 1,
 * where they are singular) are zero and never used. */
#define OGK_NOG_OFF_X 0u
#define OGK_NOG_OFF_XDOT 7u
#define OGK_NOG_OFF_LAM 14u
#define OGK_NOG_OFF_LAMDOT 21u
#define OGK_NOG_OFF_GAIN 28u
#define OGK_NOG_OFF_NRATE 84u
#define OGK_NOG_ENTRY_LEN 133u

#ifndef OGK_NOG_MAX_GRID
#define OGK_NOG_MAX_GRID 256u
#endif

/* Validated gain table, decoded once (at init or after an uplink) and shared
 * read-only by any number of guidance contexts. RAM copy: 268 KiB with the
 * default OGK_NOG_MAX_GRID; a flight build with the table in flash uses
 * ogk_nog_table_view instead and needs no copy. */
typedef struct {
    ogk_real_t tau[OGK_NOG_MAX_GRID];                        /* [-] grid, 0 .. 1 strictly increasing */
    ogk_real_t entry[OGK_NOG_MAX_GRID * OGK_NOG_ENTRY_LEN];  /* [SI] rows as documented above */
    size_t n_grid;                                       /* [-] nodes in use; 0 = no valid table */
    ogk_real_t t_f_star_s;                                   /* [s] nominal flight time */
    uint32_t generation;                                 /* [-] bumped by every ogk_nog_table_load, good or failed: a bound context compares it with the value it recorded at init */
} ogk_nog_table_t;

/* Largest nominal flight time a table may carry [s] (~32 years): far above any
 * burn, low enough that every time bound derived from t_f* stays finite. */
#define OGK_NOG_TF_MAX_S OGK_R(1.0e9)

/* Decodes and validates a table file (ogk/table.h format, kind
 * OGK_NOG_TABLE_KIND, one dimension OGK_NOG_ENTRY_LEN): CRC, dims, grid from 0
 * to 1, a single consistent t_f* in (0, OGK_NOG_TF_MAX_S] (x*' of the time
 * state). On failure the table is left empty (n_grid = 0) and the specific
 * code returned. Every call, good or failed, first bumps table->generation
 * (unsigned wrap-around; its first value is whatever the struct holds, zero
 * for static storage): every context bound to the table is then stale and
 * answers OGK_E_TABLE_STALE, with its safe output, until re-initialised. The
 * generation is read by the contexts, so never copy a table over a bound one
 * (memcpy would also copy the counter): reload it with this function. */
ogk_status ogk_nog_table_load(ogk_nog_table_t *table, const uint8_t *buf, size_t len);

/* Value of ogk_nog_table_view_t.init_marker in a validated view. */
#define OGK_NOG_VIEW_MARKER 0x4E4F4756u /* "NOGV" */

/* A validated table read in place (no copy): tau and entry point into the
 * caller's table bytes, which must stay unchanged while any context bound to
 * the view is used. */
typedef struct {
    const ogk_real_t *tau;     /* [-] n_grid grid values inside the table bytes */
    const ogk_real_t *entry;   /* [SI] n_grid rows of OGK_NOG_ENTRY_LEN values inside the table bytes */
    size_t n_grid;         /* [-] nodes; 0 = no valid table */
    ogk_real_t t_f_star_s;     /* [s] nominal flight time */
    uint32_t init_marker;  /* [-] OGK_NOG_VIEW_MARKER once validated */
    uint32_t generation;   /* [-] bumped by every ogk_nog_table_view on this struct, good or failed (stale-binding check, as ogk_nog_table_t.generation) */
} ogk_nog_table_view_t;

/* Validates buf[0..len-1] exactly as ogk_nog_table_load (magic, version, type,
 * kind, dims, grid size, length, both CRCs, finite values, grid from 0 to 1,
 * t_f* consistency) and then points the view into buf: the payload is read in
 * place as ogk_real_t (IEEE-754 binary64; binary32 in the float build, from an
 * F32 table), so buf must be aligned to sizeof(ogk_real_t) (8 bytes; 4 in the
 * float build; OGK_E_ALIGN otherwise) and the target must store an ogk_real_t
 * as the file does, little-endian
 * (x86-64 and Cortex-M7 do; on a big-endian target such as SPARC/LEON or
 * PowerPC a valid image gives OGK_E_BYTE_ORDER: decode it with
 * ogk_nog_table_load instead, docs/guides/ports.md). The payload
 * starts at offset OGK_TABLE_HEADER_SIZE = 48, a multiple of 8, so an aligned
 * buffer aligns every value. On failure the view is zeroed (unusable) and the
 * specific code returned. Every call (also with buf NULL or failing) bumps
 * view->generation, which every other field's reset keeps: contexts bound to
 * the view are then stale (OGK_E_TABLE_STALE) until re-initialised. */
ogk_status ogk_nog_table_view(ogk_nog_table_view_t *view, const uint8_t *buf, size_t len);

/* Exactly one of table and view is set; neither is copied, both must outlive
 * the context, and a context must be re-initialised after the table it is
 * bound to is reloaded: every call checks the binding's generation first and
 * a reloaded one (good or failed) gives OGK_E_TABLE_STALE, never a read of
 * the new (possibly empty) grid through the old sizes. */
typedef struct {
    const ogk_nog_table_t *table;     /* validated RAM table (ogk_nog_table_load), or NULL */
    const ogk_nog_table_view_t *view; /* validated in-place view (ogk_nog_table_view), or NULL */
    ogk_real_t sample_interval_s;     /* [s] Delta t_S, > 0 and <= t_f* (default 2 s, the paper's sec. 6) */
    ogk_real_t dtf_max_s;             /* [s] bound on |dt_f|, > 0 and <= t_f* / 2 (default 40 s) */
    ogk_real_t du_max_rad;            /* [rad] bound on the angle between corrected and nominal thrust directions, (0, pi] (default pi/3) */
    ogk_real_t tau_freeze;            /* [-] no new correction when 1 - tau_k < tau_freeze, [0, 1) (default 0) */
} ogk_nog_config_t;

/* Navigation state at a sampling time (ogk/types.h). */
typedef ogk_nav_state_t ogk_nog_nav_t;

/* Flags of a sample or command (law_flags of the command). */
#define OGK_NOG_FLAG_TERMINATING 0x01u /* eq. (32): cut-off falls inside this interval */
#define OGK_NOG_FLAG_FROZEN 0x02u      /* end-game: no new correction computed */
#define OGK_NOG_FLAG_LIMITED 0x04u     /* dt_f or the direction correction was clipped */
#define OGK_NOG_FLAG_SAFE 0x08u        /* safe command: last valid correction held (or nominal) */
#define OGK_NOG_FLAG_CUTOFF 0x10u      /* t is at or past the cut-off time: engine off */

typedef struct {
    ogk_real_t tau_k;        /* [-] normalised time of this sample */
    ogk_real_t tau_next;     /* [-] tau_(k+1) of eq. (31) (may exceed 1 in the last interval) */
    ogk_real_t t_f_s;        /* [s] t_f^(k) = t_f* + dt_f */
    ogk_real_t dt_f_s;       /* [s] applied flight-time correction */
    ogk_real_t t_cutoff_s;   /* [s] predicted engine cut-off time, t_k + (1 - tau_k) t_f^(k) */
    ogk_real_t dx[OGK_NOG_NX]; /* [SI] state displacement dx_k used */
    ogk_real_t alpha_rad;    /* [rad] commanded in-plane thrust angle at t_k */
    ogk_real_t beta_rad;     /* [rad] commanded out-of-plane thrust angle at t_k */
    uint32_t flags;      /* [-] OGK_NOG_FLAG_* */
} ogk_nog_sample_t;

/* Value of ogk_nog_t.init_marker in a usable context (any other: not initialised). */
#define OGK_NOG_INIT_MARKER 0x4E4F4731u /* "NOG1" */

/* Guidance context: fixed size, caller-owned. */
typedef struct {
    ogk_nog_config_t cfg;            /* copy of the configuration */
    ogk_nog_table_view_t tbl;        /* the bound table (view, or pointers into the RAM table) */
    ogk_real_t t_k_s;                    /* [s] time of the current sample */
    ogk_real_t tau_k;                    /* [-] tau of the current sample */
    ogk_real_t t_f_s;                    /* [s] t_f in force */
    ogk_real_t dlam_k[OGK_NOG_NX];       /* [costate units] dlam at tau_k */
    ogk_real_t dlam_rate[OGK_NOG_NX];    /* [costate units] d(dlam)/dtau held over the interval */
    ogk_real_t hold_alpha_rad;           /* [rad] in-plane angle of the last good sample (nominal at tau = 0 before): flown when the table cannot be read (stale) or the costate overflows */
    ogk_real_t hold_beta_rad;            /* [rad] out-of-plane angle, as hold_alpha_rad */
    uint32_t n_samples;              /* [-] good samples taken */
    uint32_t flags;                  /* [-] OGK_NOG_FLAG_* of the current sample */
    uint32_t table_generation;       /* [-] generation of the bound table (or view) at init */
    uint32_t init_marker;            /* [-] OGK_NOG_INIT_MARKER after a successful init */
} ogk_nog_t;

/* Fills every field with the defaults documented in ogk_nog_config_t
 * (table = view = NULL: bind one before ogk_nog_init). OGK_E_NULL. */
/*@ requires cfg_valid: cfg == \null || \valid(cfg); */
ogk_status ogk_nog_config_default(ogk_nog_config_t *cfg);

/* Checks the configuration and resets the context to the nominal (tau = 0,
 * t_f = t_f*, no correction), recording the table's generation. OGK_E_NULL
 * (ctx, cfg, or both table and view NULL), OGK_E_CONFIG for bad settings
 * (ranges in ogk_nog_config_t) or both table and view set,
 * OGK_E_NOT_INIT for an empty table or an unvalidated view; the context is
 * then unusable (init_marker 0) until a good init. */
/*@ requires ctx_valid: ctx == \null || \valid(ctx);
    requires cfg_valid: cfg == \null || \valid_read(cfg);
*/
ogk_status ogk_nog_init(ogk_nog_t *ctx, const ogk_nog_config_t *cfg);

/* Back to the state right after ogk_nog_init (nominal, no sample taken),
 * configuration and table binding kept. OGK_E_NULL, OGK_E_NOT_INIT,
 * OGK_E_TABLE_STALE (the table was reloaded: re-initialise instead). */
/*@ requires ctx_valid: ctx == \null || \valid(ctx); */
ogk_status ogk_nog_reset(ogk_nog_t *ctx);

/* Navigation envelope of ogk_nog_sample, checked before any arithmetic
 * (OGK_E_RANGE outside; NaN/Inf is OGK_E_NONFINITE). Physically generous on
 * purpose: only values no vehicle flown by this law can have are rejected,
 * and every product with the table's finite gains stays far from overflow.
 *   r_m      (0, 1e9] m      ~2.6 x the lunar distance; > 0: the spherical
 *                             coordinates are singular at the centre
 *   xi_rad   |xi| <= 1e4 rad  longitude, may be unwrapped over revolutions
 *                             (the kernel's OGK_ANGLE_LIMIT: the wrap is exact)
 *   phi_rad  |phi| < pi/2     latitude; the poles are singular in r-t-n
 *   v_*_mps  |v| <= 1e5 m/s   ~9 x Earth escape speed at the surface
 *   t_s      [0, 2 t_f* + dtf_max_s] s  t = 0 is the nominal ignition; no
 *                             cut-off can come after t_f* + dtf_max (t_f is
 *                             clipped there), and one more t_f* separates a
 *                             late sample (past the cut-off: tau > 1) from a
 *                             corrupted time tag; both are rejected */
#define OGK_NOG_R_MAX_M OGK_R(1.0e9)
#define OGK_NOG_XI_MAX_RAD OGK_R(1.0e4)
#define OGK_NOG_PHI_MAX_RAD OGK_R(1.5707963267948966)
#define OGK_NOG_V_MAX_MPS OGK_R(1.0e5)

/* One guidance sample. Rejected samples: the table was reloaded
 * (OGK_E_TABLE_STALE); NaN/Inf input (OGK_E_NONFINITE); input outside the
 * envelope above, time not after the previous good sample, or a time past
 * the predicted cut-off, i.e. tau > 1 (OGK_E_RANGE); a correction or output
 * that is not finite although the input is (gains too large for this
 * displacement: OGK_E_SAFE_COMMAND). A rejected sample sets
 * OGK_NOG_FLAG_SAFE (also in the commands until the next good sample) and
 * out holds the safe sample: the correction in force (the nominal before the
 * first good sample), held, at the sample's time; when the table cannot be
 * read (stale) or the costate overflows, the last good sample's angles.
 * Where the context goes:
 *   - time usable (finite, inside the envelope, not before the current
 *     sample) and tau <= 1: tau advances to it with the t_f in force and dlam
 *     is continued to it and held (as before this change; the next sample
 *     must be later than it, as after a good one);
 *   - time past the predicted cut-off (tau > 1) but inside the envelope:
 *     shown in out, not committed (a wrong time tag must not cut the engine);
 *   - time not finite or outside the envelope (e.g. t = 1e6 s): nothing moves.
 * So one bad sample latches nothing for the later good ones. What does latch
 * is the cut-off: it is predicted by the last good sample (eq. 32: the good
 * sample whose interval is terminating fixes it), the commands clear
 * ENGINE_ON from that time on, and no later sample can reopen it, since every
 * later one has tau > 1. Every output (tau, t_f, cut-off time, dx, angles) is
 * finite whatever the status. */
/*@ requires ctx_valid: ctx == \null || \valid(ctx);
    requires nav_valid: nav == \null || \valid_read(nav);
    requires out_valid: out == \null || \valid(out);
*/
ogk_status ogk_nog_sample(ogk_nog_t *ctx, const ogk_nav_state_t *nav, ogk_nog_sample_t *out);

/* Thrust-direction command at time t_s (>= the current sample's time; before
 * the first sample the nominal from tau = 0 is served): NOG's contract call
 * for the one command of every law (ogk/types.h), in OGK_FRAME_RTN:
 * out->t_s = t_s, the angles and their unit vector u, throttle 1 (0 at and
 * past the cut-off), flags ENGINE_ON (cleared at and past the cut-off), SAFE,
 * LIMITED, and law_flags = OGK_NOG_FLAG_* (FROZEN, LIMITED, SAFE, CUTOFF).
 * OGK_E_NOT_INIT: the safe command of ogk/thrust_cmd.h (engine off, alpha =
 * beta = 0, flags SAFE, law_flags OGK_NOG_FLAG_SAFE). OGK_E_RANGE
 * for a time before the current sample (out then holds the command at the
 * sample time, flagged SAFE); OGK_E_NONFINITE for a non-finite time (same safe
 * command). Any finite later time is valid (far past the cut-off the engine
 * is simply off). OGK_E_TABLE_STALE: the table was reloaded; out holds the
 * last good sample's angles, flagged SAFE, ENGINE_ON until the predicted
 * cut-off (computed without the table). OGK_E_SAFE_COMMAND: the costate at t
 * is not finite (table values too large); same held angles. The angles are
 * finite whatever the status. */
/*@ requires ctx_valid: ctx == \null || \valid_read(ctx);
    requires out_valid: out == \null || \valid(out);
*/
ogk_status ogk_nog_thrust_cmd(const ogk_nog_t *ctx, ogk_real_t t_s, ogk_thrust_cmd_t *out);

/* *tau = normalised time of eq. (31) at t_s >= the current sample's time with
 * the t_f in force (clamped to 1 after the cut-off), for telemetry.
 * OGK_E_NULL, OGK_E_NOT_INIT, OGK_E_TABLE_STALE, OGK_E_NONFINITE, OGK_E_RANGE
 * (t_s before the current sample). */
/*@ requires ctx_valid: ctx == \null || \valid_read(ctx);
    requires tau_valid: tau == \null || \valid(tau);
*/
ogk_status ogk_nog_tau_at(const ogk_nog_t *ctx, ogk_real_t t_s, ogk_real_t *tau);

/* ---------------------------------------------------------------------------
 * Deprecated (removed in 0.2): the names before issue 33's uniform naming
 * (docs/guides/deprecations.md). Thin wrappers of the new names, same results.
 * ------------------------------------------------------------------------- */

/* Deprecated (removed in 0.2): ogk_nog_thrust_cmd, the thrust-command
 * producer named as every law's (ogk_<law>_thrust_cmd). */
/*@ requires ctx_valid: ctx == \null || \valid_read(ctx);
    requires out_valid: out == \null || \valid(out);
*/
ogk_status ogk_nog_command(const ogk_nog_t *ctx, ogk_real_t t_s, ogk_thrust_cmd_t *out);

#ifdef __cplusplus
}
#endif

#endif /* OGK_NOG_H */
