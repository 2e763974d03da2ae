/* ogk_port_host.c -- ogk_port.h on a POSIX host: CLOCK_MONOTONIC in ns. */
#define _POSIX_C_SOURCE 199309L

#include "ogk_port.h"

#include <time.h>

static bool ogk_port_host_live;

static uint64_t ogk_port_host_read(bool *ok)
{
    struct timespec now;
    if (clock_gettime(CLOCK_MONOTONIC, &now) != 0) {
        *ok = false;
        return 0u;
    }
    *ok = true;
    return (uint64_t)now.tv_sec * UINT64_C(1000000000) + (uint64_t)now.tv_nsec;
}

bool ogk_port_counter_init(void)
{
    bool ok = false;
    (void)ogk_port_host_read(&ok);
    ogk_port_host_live = ok;
    return ok;
}

bool ogk_port_counter_live(void)
{
    return ogk_port_host_live;
}

uint64_t ogk_port_counter_now(void)
{
    bool ok = false;
    const uint64_t ns = ogk_port_host_read(&ok);
    return ok ? ns : 0u;
}

ogk_port_unit ogk_port_counter_unit(void)
{
    return OGK_PORT_UNIT_NS;
}

const char *ogk_port_counter_unit_name(void)
{
    return "ns";
}

const char *ogk_port_name(void)
{
    return "host";
}
