/* ogk/cpd.h -- constrained PD (CPD) attitude control with thrust vectoring.
 *
 * Pontani & Celani 2021 (seeds/004), sections 2.2 and 5.1-5.4; design notes
 * and the deviations from the paper in docs/design/cpd.md.
 *
 * Frames (all right-handed):
 *   c      inertial, c1-c2 plane = nominal orbit plane;
 *   a      auxiliary inertial, a1 = c2, a2 = -c3, a3 = -c1 (matrix R_A);
 *   body   x_b longitudinal (thrust axis), from a by R1(Phi) R2(Theta) R3(Psi)
 *          (eq. 9; R_i are elementary FRAME rotations, e.g.
 *          R3(t) = [[cos t, sin t, 0], [-sin t, cos t, 0], [0, 0, 1]]);
 *   r-t-n  local: r radial, t = (-sin xi, cos xi, 0) in c, n = r x t, from the
 *          right ascension xi and declination phi.
 * Thrust direction in r-t-n: (cos b sin a, cos b cos a, sin b) (eqs. 39, 52).
 * Thrust direction of the deflected nozzle in body axes:
 *   (cos Dz cos Dy, sin Dz, cos Dz sin Dy) (eq. 50), which with the swivel
 *   point at -l x_b gives the torques of eqs. (14)-(15).
 *
 * Control law (eqs. 45-46), one call of ogk_cpd_step per control sample:
 *   M_xc  = sat_Mxc { k_px e_x - k_dx P }
 *   D_yc  = sat_Dyc { k_py e_y - k_dy Q }
 *   D_zc  = sat_Dzc { -k_pz e_z + k_dz R }
 * e_x = wrap(Phi_c - Phi) in both modes; e_y, e_z depend on the pointing mode
 * (ogk_cpd_pointing_t). Every output is bounded by its limit, so eq. (47)
 * bounds the actuator rates: |dM_x/dt| <= 2 M_xc_max / tau_x, etc. */
#ifndef OGK_CPD_H
#define OGK_CPD_H

#include <stdint.h>
#include "ogk/mathutil.h"
#include "ogk/status.h"
#include "ogk/types.h"
#include "ogk/real.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Inputs whose magnitude exceeds this are rejected (OGK_E_RANGE): the kernel's
 * one angle limit (ogk/mathutil.h). [rad] */
#define OGK_CPD_ANGLE_LIMIT OGK_ANGLE_LIMIT

/* Which pitch/yaw pointing error feeds the TVC loops. */
typedef enum {
    /* Default to fly. Rotation vector taking the body x axis onto the
     * commanded thrust direction, in body axes: e_y about y_b replaces
     * (Theta_c - Theta), e_z about z_b replaces (Psi_c - Psi). Independent of
     * the roll angle, correct for any error up to 180 deg (docs/design/cpd.md). */
    OGK_CPD_POINTING_BODY = 0,
    /* Eqs. (45)-(46) literally: e_y = Theta_c - Theta, e_z = wrap(Psi_c - Psi).
     * Valid near zero roll only: past ~90 deg of roll the pitch/yaw loops
     * reverse sign (seeds/README.md errata). For comparison runs. */
    OGK_CPD_POINTING_EULER = 1
} ogk_cpd_pointing_t;

/* Output flags (ogk_cpd_output_t.flags). */
#define OGK_CPD_FLAG_SAT_X 0x01u       /* M_xc clipped at +-m_xc_max */
#define OGK_CPD_FLAG_SAT_Y 0x02u       /* delta_yc clipped at +-delta_yc_max */
#define OGK_CPD_FLAG_SAT_Z 0x04u       /* delta_zc clipped at +-delta_zc_max */
#define OGK_CPD_FLAG_SAFE 0x08u        /* output is the safe command (status != OGK_OK) */
#define OGK_CPD_FLAG_BEHIND 0x10u      /* commanded direction more than 90 deg from x_b */
#define OGK_CPD_FLAG_YAW_UNDEFINED 0x20u /* commanded direction along +-a3: psi_c set to 0 */

/* Defaults (ogk_cpd_config_default): the paper's gains and limits as printed
 * (eq. 54 and sec. 6: k_px 21.6e3, k_dx 7.2e3, k_py = k_pz 21.6, k_dy = k_dz
 * 7.2, 30 N m, 0.65 deg, tau 0.1 s; see docs/design/cpd.md for the pitch/yaw gain
 * erratum), phi_c = 0, BODY pointing, braking cap and feed-forward off. */
typedef struct {
    ogk_real_t k_px;          /* [N m/rad] roll proportional gain, eq. (45), > 0 */
    ogk_real_t k_dx;          /* [N m s/rad] roll derivative gain, > k_px tau_x */
    ogk_real_t k_py;          /* [rad/rad] pitch proportional gain, eq. (46), > 0 */
    ogk_real_t k_dy;          /* [rad s/rad] = [s] pitch derivative gain, > k_py tau_y */
    ogk_real_t k_pz;          /* [rad/rad] yaw proportional gain, eq. (46), > 0 */
    ogk_real_t k_dz;          /* [s] yaw derivative gain, > k_pz tau_z */
    ogk_real_t m_xc_max;      /* [N m] roll torque command limit (Mbar_xc), > 0 */
    ogk_real_t delta_yc_max;  /* [rad] pitch deflection command limit (Deltabar_yc), > 0 */
    ogk_real_t delta_zc_max;  /* [rad] yaw deflection command limit (Deltabar_zc), > 0 */
    ogk_real_t tau_x;         /* [s] side-jet actuator time constant, eq. (18), > 0 */
    ogk_real_t tau_y;         /* [s] TVC pitch actuator time constant, eq. (16), > 0 */
    ogk_real_t tau_z;         /* [s] TVC yaw actuator time constant, eq. (16), > 0 */
    ogk_real_t phi_c;         /* [rad] commanded roll Phi_c, in [-pi, pi] (0 in the paper) */
    ogk_cpd_pointing_t pointing; /* [-] pointing-error mode */
    /* Braking-curve cap of the proportional term (not in the paper; docs/design/cpd.md):
     * with a > 0 the PD law k_p e - k_d w is flown as k_d (w_c - w) with the
     * rate command w_c = sign(e) min(k_p |e| / k_d, sqrt(2 a |e|)), so a large
     * error is approached no faster than the saturated actuator can brake
     * (a = margin * control acceleration at the command limit). Identical to
     * eqs. (45)-(46) while k_p |e| / k_d <= sqrt(2 a |e|); a = 0 flies the
     * paper's law unchanged. The command saturation, hence eq. (47), is kept. */
    ogk_real_t approach_accel_x; /* [rad/s^2] roll braking acceleration, >= 0 (0: off) */
    ogk_real_t approach_accel_y; /* [rad/s^2] pitch braking acceleration, >= 0 (0: off) */
    ogk_real_t approach_accel_z; /* [rad/s^2] yaw braking acceleration, >= 0 (0: off) */
    /* Feed-forward of the commanded turn rate (not in the paper; docs/design/cpd.md):
     * the body-axis rate of the commanded thrust direction between two
     * consecutive steps, omega_c = (d_prev x d_now) / ff_period_s, is added to
     * the rate command of the pitch and yaw loops, k_d (w_c + omega_c - w),
     * so a steadily turning command is tracked without the ramp lag
     * (k_d / k_p) x rate of eq. (46). Its magnitude is clipped to ff_rate_max
     * (a guidance sample that steps the command is not a rate). */
    ogk_real_t ff_period_s;      /* [s] control period between steps, >= 0 (0: no feed-forward) */
    ogk_real_t ff_rate_max;      /* [rad/s] clip of the feed-forward rate, >= 0 */
} ogk_cpd_config_t;

typedef struct {
    ogk_real_t psi;       /* [rad] yaw Psi, eq. (9) */
    ogk_real_t theta;     /* [rad] pitch Theta, eq. (9) */
    ogk_real_t phi_roll;  /* [rad] roll Phi, eq. (9) */
    ogk_real_t rate_p;    /* [rad/s] body angular rate about x_b (P) */
    ogk_real_t rate_q;    /* [rad/s] body angular rate about y_b (Q) */
    ogk_real_t rate_r;    /* [rad/s] body angular rate about z_b (R) */
    ogk_real_t alpha_c;   /* [rad] commanded in-plane thrust angle (from guidance) */
    ogk_real_t beta_c;    /* [rad] commanded out-of-plane thrust angle */
    ogk_real_t xi;        /* [rad] right ascension of the vehicle */
    ogk_real_t phi;       /* [rad] declination of the vehicle */
} ogk_cpd_input_t;

typedef struct {
    ogk_real_t m_xc;      /* [N m] commanded roll torque, eq. (45), |m_xc| <= m_xc_max */
    ogk_real_t delta_yc;  /* [rad] commanded pitch deflection, eq. (46) */
    ogk_real_t delta_zc;  /* [rad] commanded yaw deflection, eq. (46) */
    ogk_real_t psi_c;     /* [rad] commanded yaw, eqs. (38)-(39), in (-pi, pi] */
    ogk_real_t theta_c;   /* [rad] commanded pitch, in [-pi/2, pi/2] */
    ogk_real_t phi_c;     /* [rad] commanded roll (configuration value) */
    ogk_real_t err_x;     /* [rad] roll error used: wrap(Phi_c - Phi) */
    ogk_real_t err_y;     /* [rad] pitch pointing error used (about y_b in BODY mode) */
    ogk_real_t err_z;     /* [rad] yaw pointing error used (about z_b in BODY mode) */
    uint32_t flags;   /* [-] OGK_CPD_FLAG_* bits */
} ogk_cpd_output_t;

/* Value of ogk_cpd_t.init_marker in a usable context (any other: not initialised). */
#define OGK_CPD_INIT_MARKER 0x43504431u /* "CPD1" */

typedef struct {
    ogk_cpd_config_t cfg;     /* copy of the accepted configuration */
    ogk_cpd_output_t last;    /* last command written by ogk_cpd_step */
    ogk_real_t dir_prev_a[3];     /* [-] commanded thrust direction of the previous step (a frame) */
    uint32_t has_prev;        /* [-] 1 when dir_prev_a holds a direction */
    uint32_t init_marker;     /* [-] OGK_CPD_INIT_MARKER once initialised */
} ogk_cpd_t;

/* Fills every field with the defaults documented at ogk_cpd_config_t (a
 * configuration ogk_cpd_init accepts). OGK_E_NULL. */
/*@ requires cfg_valid: cfg == \null || \valid(cfg); */
ogk_status ogk_cpd_config_default(ogk_cpd_config_t *cfg);

/* Validates cfg and copies it into ctx. Rejections leave ctx zeroed (every
 * step then returns OGK_E_NOT_INIT): OGK_E_NULL (ctx or cfg NULL),
 * OGK_E_NONFINITE (a NaN/Inf field), OGK_E_CONFIG (a gain, limit or time
 * constant <= 0, k_d <= k_p tau on any axis -- the convergence condition of
 * sec. 5.2 --, |phi_c| > pi, or an unknown pointing mode). */
/*@ requires ctx_valid: ctx == \null || \valid(ctx);
    requires cfg_valid: cfg == \null || \valid_read(cfg);
*/
ogk_status ogk_cpd_init(ogk_cpd_t *ctx, const ogk_cpd_config_t *cfg);

/* Back to the state right after ogk_cpd_init (no previous direction for the
 * feed-forward, last = safe command), configuration kept. OGK_E_NULL,
 * OGK_E_NOT_INIT. */
/*@ requires ctx_valid: ctx == \null || \valid(ctx); */
ogk_status ogk_cpd_reset(ogk_cpd_t *ctx);

/* Sets the guidance part of a CPD input from any law's thrust command
 * (ogk_thrust_cmd_t, ogk/types.h) and the navigation state: alpha_c, beta_c
 * = the command's r-t-n angles at (xi, phi) (ogk_thrust_cmd_to_rtn: the
 * angles of an OGK_FRAME_RTN command as they are, an OGK_FRAME_INERTIAL
 * vector rotated into r-t-n), xi, phi from nav (the attitude and rates of in
 * are left as they are). A command without ENGINE_ON still carries the
 * direction to hold. Rejections leave in untouched: OGK_E_NULL;
 * OGK_E_FRAME (a synodic command: convert it first with
 * ogk_thrust_cmd_synodic_to_inertial; or an unknown frame); OGK_E_NONFINITE
 * (a non-finite angle, vector, time, throttle, xi or phi); OGK_E_RANGE (an
 * inertial u that is not a unit vector, a throttle outside [0, 1], |xi| or
 * |phi| > OGK_ANGLE_LIMIT with an inertial u). */
ogk_status ogk_cpd_input_from_thrust_cmd(ogk_cpd_input_t *in, const ogk_thrust_cmd_t *cmd,
                                         const ogk_nav_state_t *nav);

/* One control sample. On OGK_OK, out holds the CPD command. Otherwise, when out
 * is not NULL, out holds the safe command (zero torque, zero deflections, zero
 * angles and errors, OGK_CPD_FLAG_SAFE): OGK_E_NULL (ctx, in or out NULL),
 * OGK_E_NOT_INIT, OGK_E_NONFINITE (NaN/Inf input), OGK_E_RANGE (an angle
 * beyond OGK_CPD_ANGLE_LIMIT), OGK_E_SAFE_COMMAND (finite input, but an
 * output would not be finite: absurd gains meeting absurd rates). Every
 * output is finite whatever the status. The context stays usable after any
 * of these. */
/*@ requires ctx_valid: ctx == \null || \valid(ctx);
    requires in_valid: in == \null || \valid_read(in);
    requires out_valid: out == \null || \valid(out);
*/
ogk_status ogk_cpd_step(ogk_cpd_t *ctx, const ogk_cpd_input_t *in,
                        ogk_cpd_output_t *out);

/* Commanded yaw and pitch putting x_b along the commanded thrust direction
 * (alpha_c, beta_c) at position (xi, phi): eqs. (38)-(39). theta_c in
 * [-pi/2, pi/2], psi_c in (-pi, pi]; when the direction is along +-a3 (within
 * 1e-12) yaw is undefined and psi_c = 0. OGK_E_NULL, OGK_E_NONFINITE,
 * OGK_E_RANGE (|angle| > OGK_CPD_ANGLE_LIMIT). */
ogk_status ogk_cpd_commanded_attitude(ogk_real_t alpha_c, ogk_real_t beta_c, ogk_real_t xi,
                                      ogk_real_t phi, ogk_real_t *psi_c,
                                      ogk_real_t *theta_c);

/* Actual thrust angles (alpha_a in (-pi, pi], beta_a in [-pi/2, pi/2]) of the
 * deflected thrust for attitude (psi, theta, phi_roll), position (xi, phi) and
 * deflections (delta_y, delta_z): eqs. (49)-(52). Error codes as
 * ogk_cpd_commanded_attitude (deflections are range-checked the same way). */
ogk_status ogk_cpd_thrust_angles(ogk_real_t psi, ogk_real_t theta, ogk_real_t phi_roll,
                                 ogk_real_t xi, ogk_real_t phi, ogk_real_t delta_y,
                                 ogk_real_t delta_z, ogk_real_t *alpha_a,
                                 ogk_real_t *beta_a);

/* Body-axis pointing error (OGK_CPD_POINTING_BODY) of attitude (psi, theta,
 * phi_roll) towards the direction (alpha_c, beta_c) at (xi, phi): the rotation
 * vector taking x_b onto the direction has body components (0, *err_y,
 * *err_z), magnitude in [0, pi]. Exactly behind (angle pi, axis undefined) it
 * is (0, pi, 0). Error codes as ogk_cpd_commanded_attitude. */
ogk_status ogk_cpd_pointing_error_body(ogk_real_t psi, ogk_real_t theta, ogk_real_t phi_roll,
                                       ogk_real_t alpha_c, ogk_real_t beta_c, ogk_real_t xi,
                                       ogk_real_t phi, ogk_real_t *err_y, ogk_real_t *err_z);

/* The angle wrap is ogk_wrap_pi (ogk/mathutil.h), shared by every law. */

#ifdef __cplusplus
}
#endif

#endif /* OGK_CPD_H */
