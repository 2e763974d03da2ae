/* bench_timer.h -- median-of-batches timing shared by the benchmark programs. */
#ifndef OGK_BENCH_TIMER_H
#define OGK_BENCH_TIMER_H

#include <stdio.h>
#include <stdlib.h>

#include "ogk_port.h"

static int bench_cmp_double(const void *a, const void *b)
{
    const double da = *(const double *)a, db = *(const double *)b;
    return (da > db) - (da < db);
}

/* Calls fn iters times in each of 7 batches and prints the median cost per
 * call in the port counter's unit; returns 1 if a call fails. */
static int bench_time_case(int (*fn)(void), long iters, const char *name)
{
    double per_call[7];
    int b;
    for (b = 0; b < 7; ++b) {
        const uint64_t t0 = ogk_port_counter_now();
        long i;
        for (i = 0; i < iters; ++i) {
            if (fn() != 0) {
                fprintf(stderr, "%s: kernel call failed\n", name);
                return 1;
            }
        }
        per_call[b] = (double)(ogk_port_counter_now() - t0) / (double)iters;
    }
    qsort(per_call, 7u, sizeof per_call[0], bench_cmp_double);
    printf("%s %.1f %s/call (median of 7 batches of %ld)\n", name, per_call[3],
           ogk_port_counter_unit_name(), iters);
    return 0;
}

#endif /* OGK_BENCH_TIMER_H */
