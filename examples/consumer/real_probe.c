/* real_probe.c -- a program built against an installed ogk package compiles with the library's real type
 * (kernel/include/ogk/real.h): ogk::ogk and ogk.pc carry OGK_REAL_SINGLE=1 from a package built with
 * OGK_PRECISION=single. Prints the type and exits 0 when the library's ogk_real_bytes is this program's
 * sizeof(ogk_real_t), 1 otherwise. */
#include <stdint.h>
#include <stdio.h>

#include <ogk/real.h>
#include <ogk/version.h>

int main(void)
{
    uint32_t bytes = 0u;
    const ogk_status st = ogk_real_bytes(&bytes);
    int rc = 0;
    if ((st != OGK_OK) || (bytes != (uint32_t)sizeof(ogk_real_t))) {
        (void)printf("ogk_real_probe: the library's ogk_real_t is %u bytes, this program's %u\n",
                     (unsigned)bytes, (unsigned)sizeof(ogk_real_t));
        rc = 1;
    } else {
        (void)printf("ogk_real_probe: ogk_real_t is %s (%u bytes) in the library and here\n",
                     (OGK_REAL_SINGLE != 0) ? "float" : "double", (unsigned)bytes);
    }
    return rc;
}
