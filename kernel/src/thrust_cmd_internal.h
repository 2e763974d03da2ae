/* thrust_cmd_internal.h -- unchecked builders of the thrust command for the
 * kernel's producers (the laws' contract calls), which hold values already
 * valid: finite angles or a unit vector, a throttle in [0, 1], a known frame.
 * Not public API: the checked forms are in ogk/thrust_cmd.h. Each builder zeroes the
 * command first (padding included, so commands compare with memcmp) and
 * stores the throttle as 0 when flags lacks OGK_THRUST_FLAG_ENGINE_ON. */
#ifndef OGK_THRUST_CMD_INTERNAL_H
#define OGK_THRUST_CMD_INTERNAL_H

#include <stdint.h>
#include "ogk/status.h"
#include "ogk/types.h"

/* An r-t-n command from finite angles (u computed from them). */
void ogk_i_thrust_cmd_angles(ogk_thrust_cmd_t *cmd, ogk_real_t t_s, ogk_real_t alpha_rad, ogk_real_t beta_rad,
                             ogk_real_t throttle, uint32_t flags, uint32_t law_flags);

/* A command from a unit vector u in a known frame (in r-t-n its angles too). */
void ogk_i_thrust_cmd_unit(ogk_thrust_cmd_t *cmd, ogk_real_t t_s, ogk_frame_t frame, const ogk_real_t *u,
                           ogk_real_t throttle, uint32_t flags, uint32_t law_flags);

/* The command's direction in r-t-n at nav's position, checked as ogk_thrust_cmd_to_rtn checks it
 * (in, nav, ab not NULL): ab = (alpha, beta) [rad], and u_rtn (3) the unit vector unless NULL (CPD
 * needs only the angles: an r-t-n command then costs no trigonometry). Outputs untouched on a
 * rejection. */
ogk_status ogk_i_thrust_cmd_rtn_direction(const ogk_thrust_cmd_t *in, const ogk_nav_state_t *nav,
                                          ogk_real_t ab[2], ogk_real_t *u_rtn);

/* The safe command of a known frame (ogk_thrust_cmd_safe). */
void ogk_i_thrust_cmd_safe(ogk_thrust_cmd_t *cmd, ogk_real_t t_s, ogk_frame_t frame, uint32_t law_flags);

#endif /* OGK_THRUST_CMD_INTERNAL_H */
