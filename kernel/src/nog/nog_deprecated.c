/* nog_deprecated.c -- the deprecated names of ogk/nog.h (removed in 0.3;
 * docs/guides/deprecations.md): thin wrappers of the new names, same results. Kept
 * apart from nog.c so that the removal is this file and its header block. */
#include "ogk/nog.h"

ogk_status ogk_nog_command(const ogk_nog_t *ctx, ogk_real_t t_s, ogk_thrust_cmd_t *out)
{
    return ogk_nog_thrust_cmd(ctx, t_s, out);
}
