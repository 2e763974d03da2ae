/* ogk/thrust_cmd.h -- build, check and convert the one thrust-direction
 * command every guidance law produces (ogk_thrust_cmd_t, ogk/types.h).
 *
 * The frames (OGK_FRAME_RTN, _INERTIAL, _SYNODIC) and the one angle
 * convention are documented at ogk_frame_t and ogk_thrust_cmd_t in
 * ogk/types.h, and in docs/design/kernel-core.md, "Thrust commands":
 *   u_rtn = (cos beta sin alpha, cos beta cos alpha, sin beta),
 *   alpha = atan2(u_r, u_t) in (-pi, pi], beta = atan2(u_n, hypot(u_r, u_t))
 *   in [-pi/2, pi/2] (alpha = 0 along +-n, where it is undefined).
 *
 * A law's contract call (ogk_nog_thrust_cmd, ogk_mpsp_thrust_cmd,
 * ogk_nmpc_thrust_cmd, ogk_blt_thrust_cmd) fills the command with these
 * helpers; a consumer that needs r-t-n angles (CPD) converts any command with
 * ogk_thrust_cmd_to_rtn. Every function returns ogk_status; on a rejection
 * the outputs are left untouched. */
#ifndef OGK_THRUST_CMD_H
#define OGK_THRUST_CMD_H

#include <stdint.h>
#include "ogk/status.h"
#include "ogk/types.h"
#include "ogk/real.h"

#ifdef __cplusplus
extern "C" {
#endif

/* A direction is a unit vector when | |u| - 1 | <= this; the helpers store
 * u / |u|. [-]
 * Double: 1e-9 (about 4.5e6 eps: a law's direction off by more is not a unit
 * vector whatever its rounding). Float: 8 eps (9.5e-7), because 1e-9 is below
 * float's resolution of 1 (an ulp is eps above 1, eps / 2 below): a unit vector
 * the kernel built in float (sines and cosines of float angles, or v / |v|,
 * each component within about an ulp, then |u| by two hypotf) has | |u| - 1 |
 * of a few eps, and 1e-9 refused it or not by the luck of its rounding,
 * differently on the host's and newlib's libm. 8 eps (9.5e-7) accepts every
 * such vector (the unit tests' worst is measured in
 * docs/design/precision-unit-tests.md) and still refuses any direction a law
 * did not normalise. */
#if OGK_REAL_SINGLE
#define OGK_THRUST_CMD_UNIT_TOL (OGK_R(8.0) * OGK_REAL_EPSILON)
#else
#define OGK_THRUST_CMD_UNIT_TOL OGK_R(1.0e-9)
#endif

/* u = (cos b sin a, cos b cos a, sin b): the r-t-n unit vector of the angles.
 * OGK_E_NULL, OGK_E_NONFINITE, OGK_E_RANGE (|angle| > OGK_ANGLE_LIMIT,
 * ogk/mathutil.h). */
ogk_status ogk_thrust_cmd_angles_to_unit(ogk_real_t alpha_rad, ogk_real_t beta_rad, ogk_real_t u[3]);

/* The angles of an r-t-n unit vector: alpha in (-pi, pi], beta in
 * [-pi/2, pi/2]; alpha = 0 when u is along +-n. OGK_E_NULL, OGK_E_NONFINITE,
 * OGK_E_RANGE (| |u| - 1 | > OGK_THRUST_CMD_UNIT_TOL, a zero vector among
 * them). */
ogk_status ogk_thrust_cmd_unit_to_angles(const ogk_real_t u[3], ogk_real_t *alpha_rad, ogk_real_t *beta_rad);

/* A complete r-t-n command from the angles: frame OGK_FRAME_RTN, the angles as
 * given, u from them, throttle (stored as 0 when flags lacks ENGINE_ON), the
 * flags, the law's flags and the time. OGK_E_NULL, OGK_E_NONFINITE (t, an
 * angle or the throttle), OGK_E_RANGE (|angle| > OGK_ANGLE_LIMIT, throttle
 * outside [0, 1]). */
ogk_status ogk_thrust_cmd_from_angles(ogk_real_t t_s, ogk_real_t alpha_rad, ogk_real_t beta_rad,
                                      ogk_real_t throttle, uint32_t flags, uint32_t law_flags,
                                      ogk_thrust_cmd_t *cmd);

/* A complete command from a unit vector in `frame`: u / |u| stored, in
 * OGK_FRAME_RTN also its angles (0 in the other frames), throttle as
 * ogk_thrust_cmd_from_angles. OGK_E_NULL, OGK_E_FRAME (unknown frame),
 * OGK_E_NONFINITE, OGK_E_RANGE (not a unit vector, throttle outside [0, 1]). */
ogk_status ogk_thrust_cmd_from_unit(ogk_real_t t_s, ogk_frame_t frame, const ogk_real_t u[3],
                                    ogk_real_t throttle, uint32_t flags, uint32_t law_flags,
                                    ogk_thrust_cmd_t *cmd);

/* The safe command in `frame`: engine off (throttle 0, flags SAFE), the law's
 * flags, the time (0 when t_s is not finite), and the frame's reference
 * direction: in r-t-n the zero angles (u = t), in the other frames their first
 * axis (1, 0, 0). OGK_E_NULL, OGK_E_FRAME (unknown frame). */
ogk_status ogk_thrust_cmd_safe(ogk_real_t t_s, ogk_frame_t frame, uint32_t law_flags,
                               ogk_thrust_cmd_t *cmd);

/* The command in r-t-n at the position of nav (its xi, phi; the rest of nav is
 * not read): time, flags, law flags and throttle kept, frame OGK_FRAME_RTN.
 *   OGK_FRAME_RTN       the angles are the command (u is not read); out gets
 *                       them and u recomputed from them (any finite angles);
 *   OGK_FRAME_INERTIAL  u rotated into r-t-n at (xi, phi), its angles;
 *   OGK_FRAME_SYNODIC   OGK_E_FRAME: the frame's angle is not known here
 *                       (convert first with ogk_thrust_cmd_synodic_to_inertial).
 * out may alias in. OGK_E_NULL; OGK_E_FRAME (unknown or synodic frame);
 * OGK_E_NONFINITE (angles, u, throttle, time, or xi / phi for an inertial u);
 * OGK_E_RANGE (u not a unit vector, throttle outside [0, 1], |xi| or |phi| >
 * OGK_ANGLE_LIMIT for an inertial u). */
ogk_status ogk_thrust_cmd_to_rtn(const ogk_thrust_cmd_t *in, const ogk_nav_state_t *nav,
                                 ogk_thrust_cmd_t *out);

/* A synodic command in the inertial frame whose I3 is the synodic z axis:
 * u_I = R3(-angle) u_S, with angle_rad the angle from I1 to the synodic x axis
 * about I3 at the command's time (theta_0 + omega t for a circular binary).
 * Time, flags, throttle kept; frame OGK_FRAME_INERTIAL. out may alias in.
 * OGK_E_NULL; OGK_E_FRAME (in is not synodic); OGK_E_NONFINITE; OGK_E_RANGE
 * (|angle| > OGK_ANGLE_LIMIT, u not a unit vector, throttle outside [0, 1]). */
ogk_status ogk_thrust_cmd_synodic_to_inertial(const ogk_thrust_cmd_t *in, ogk_real_t angle_rad,
                                              ogk_thrust_cmd_t *out);

#ifdef __cplusplus
}
#endif

#endif /* OGK_THRUST_CMD_H */
