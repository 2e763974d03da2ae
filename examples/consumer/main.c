/* main.c -- the example consumer: every law's flight loop, then one summary line; the exit code is
 * the number of laws that failed (on the Cortex-M7 under QEMU it becomes QEMU's exit code). */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include <ogk/real.h>
#include <ogk/version.h>

#include "consumer.h"

int consumer_verdict(const char *law, int pass, const char *detail)
{
    (void)printf("%-5s %s  %s\n", law, pass ? "PASS" : "FAIL", detail);
    return pass ? 0 : 1;
}

double consumer_unit_error(const ogk_thrust_cmd_t *cmd)
{
    const double u0 = (double)cmd->u[0];
    const double u1 = (double)cmd->u[1];
    const double u2 = (double)cmd->u[2];
    return fabs(sqrt((u0 * u0) + (u1 * u1) + (u2 * u2)) - 1.0);
}

int main(void)
{
    const char *text = "";
    uint32_t real_bytes = 0u;
    int failed = 0;
    /* the library linked and the headers compiled against are the same release */
    if ((ogk_version(&text) != OGK_OK) || (strcmp(text, OGK_VERSION_STRING) != 0)) {
        (void)printf("consumer: library version %s, headers %s\n", text, OGK_VERSION_STRING);
        return 100;
    }
    /* ... and have the same real type (the package passes the library's OGK_REAL_SINGLE on) */
    if ((ogk_real_bytes(&real_bytes) != OGK_OK) || (real_bytes != (uint32_t)sizeof(ogk_real_t))) {
        (void)printf("consumer: library's real type %u bytes, headers' %u\n", (unsigned)real_bytes,
                     (unsigned)sizeof(ogk_real_t));
        return 101;
    }
    (void)printf("consumer of ogk %s\n", text);
    failed += fly_nog();
    failed += fly_cpd();
    failed += fly_mpsp();
    failed += fly_nmpc();
    failed += fly_prox();
    failed += fly_blt();
    (void)printf("consumer: %d passed, %d failed\n", 6 - failed, failed);
    return failed;
}
