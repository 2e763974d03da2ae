/* bench_blt.c -- cost of ogk_blt's NRPC: one iteration and a whole convergence.
 *
 *   bench_blt time                 every case: (a) one NRPC iteration, (b) the whole
 *                                  convergence, each timed over repetitions: median wall
 *                                  time (port counter) and median CPU time of the process
 *                                  (the machine is shared: waiting for a core is not the
 *                                  kernel's cost); iterations, propagations, sizeofs;
 *                                  "blt_<key> <value>" lines for bench_blt_case.py run
 *   bench_blt once KEY iteration   exactly one iteration of case KEY, for valgrind callgrind
 *                                  with --toggle-collect=bench_blt_iteration_once
 *   bench_blt once KEY converge    exactly one convergence (--toggle-collect=bench_blt_converge_once)
 *   (bare metal)                   every case's iteration and convergence once, each in its
 *                                  own function for the QEMU instruction counter
 *                                  (bench_blt_m7_iter_<key>, bench_blt_m7_conv_<key>);
 *                                  prints "blt_m7_<key> <value>" lines, among them the stack
 *                                  used by each convergence
 *
 * The cases (docs/design/blt.md, "Cost"; generated into bench_blt_case.h by
 * tests/bench/bench_blt_case.py header from scenarios/moshup.toml, bit-exact): the transfers
 * l2_to_l1_lyapunov (single burn) and circle_to_l2_ump (burn-coast-burn, one free node), each
 * with the central-difference (eq. 62) and the variational Jacobian, NRPC, the scenario's
 * [solver] settings, from the ground pipeline's initial guess.
 *
 * One iteration = ogk_blt_solve with cfg.max_iter = 1 from the guess: the checks, the guess's
 * evaluation (one propagation of every arc), one Jacobian, one minimum-norm step (eq. 64) and
 * its line-search trials (each a full evaluation). The whole convergence = ogk_blt_solve with
 * the scenario's max_iter (40) from the guess. ogk_blt_solve starts from the guess every call
 * (the context keeps no state between solves that changes the work), so every repetition is
 * the same work; ogk_blt_init is outside the timing. */
#ifndef OGK_BENCH_BARE_METAL
#define _POSIX_C_SOURCE 199309L /* clock_gettime(CLOCK_PROCESS_CPUTIME_ID) */
#endif
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#ifndef OGK_BENCH_BARE_METAL
#include <time.h>
#endif

#include "ogk/blt.h"
#include "ogk_port.h"
#include "bench_blt_case.h"
#ifdef OGK_BENCH_BARE_METAL
#include "ogk_armv7m.h"
#endif

/* contexts in static storage (ogk_blt_t is ~46 KB) */
static ogk_blt_t ctx;
static ogk_blt_transfer_t solution;
static ogk_blt_report_t rep;
static ogk_status status;
static volatile double sink;

/* The case's configuration, max_iter = 1 for one iteration (0: the scenario's). */
static int setup(const bench_blt_case_t *c, uint32_t max_iter)
{
    ogk_blt_config_t cfg;
    ogk_status st;
    (void)ogk_blt_config_default(&cfg);
    c->config(&cfg);
    if (max_iter != 0u) {
        cfg.max_iter = max_iter;
    }
    st = ogk_blt_init(&ctx, &cfg);
    if (st != OGK_OK) {
        fprintf(stderr, "bench_blt: %s: ogk_blt_init failed (status %d)\n", c->key, (int)st);
        return 1;
    }
    return 0;
}

/* Exactly one NRPC iteration (ctx configured with max_iter = 1): the callgrind / QEMU unit.
 * noclone and different bodies: gcc must neither specialise nor fold the two units (their
 * names are the callgrind toggles). */
__attribute__((noinline, noclone)) static int bench_blt_iteration_once(const bench_blt_case_t *c)
{
    status = ogk_blt_solve(&ctx, c->guess, &solution, &rep);
    sink = rep.err_norm;
    return 0;
}

/* Exactly one whole convergence (ctx configured with the scenario's max_iter). */
__attribute__((noinline, noclone)) static int bench_blt_converge_once(const bench_blt_case_t *c)
{
    status = ogk_blt_solve(&ctx, c->guess, &solution, &rep);
    sink = (double)rep.iterations;
    return 0;
}

static int check_iteration(const bench_blt_case_t *c)
{
    if (((status != OGK_OK) && (status != OGK_E_ITER_LIMIT)) || (rep.iterations != 1u) ||
        !(rep.err_norm < rep.err_norm0)) {
        fprintf(stderr, "bench_blt: %s: one iteration did not take a step (status %d, flags 0x%x, %u iterations)\n",
                c->key, (int)status, (unsigned)rep.flags, (unsigned)rep.iterations);
        return 1;
    }
    return 0;
}

static int check_converged(const bench_blt_case_t *c)
{
    if ((status != OGK_OK) || ((rep.flags & OGK_BLT_FLAG_CONVERGED) == 0u)) {
        fprintf(stderr, "bench_blt: %s: did not converge (status %d, flags 0x%x, %u iterations, |e| %.3g)\n",
                c->key, (int)status, (unsigned)rep.flags, (unsigned)rep.iterations, rep.err_norm);
        return 1;
    }
    return 0;
}

#ifdef OGK_BENCH_BARE_METAL
extern uint32_t __StackTop[];

#if BENCH_BLT_NCASES != 4u
#error "bench_blt.c: the bare-metal wrappers below name the four cases of bench_blt_case.py"
#endif
/* One function per case and unit: the QEMU plugin counts per function. */
#define BENCH_BLT_M7_UNITS(key, index)                                                         \
    __attribute__((noinline)) static int bench_blt_m7_iter_##key(void)                         \
    {                                                                                          \
        int r = bench_blt_iteration_once(&bench_blt_cases[index]);                             \
        sink = rep.err_norm0;                                                                  \
        return r;                                                                              \
    }                                                                                          \
    __attribute__((noinline)) static int bench_blt_m7_conv_##key(void)                         \
    {                                                                                          \
        int r = bench_blt_converge_once(&bench_blt_cases[index]);                              \
        sink = rep.err_norm0;                                                                  \
        return r;                                                                              \
    }
BENCH_BLT_M7_UNITS(sb_cd, 0)
BENCH_BLT_M7_UNITS(sb_var, 1)
BENCH_BLT_M7_UNITS(ump_cd, 2)
BENCH_BLT_M7_UNITS(ump_var, 3)

static int (*const m7_iter[BENCH_BLT_NCASES])(void) = {bench_blt_m7_iter_sb_cd, bench_blt_m7_iter_sb_var,
                                                       bench_blt_m7_iter_ump_cd, bench_blt_m7_iter_ump_var};
static int (*const m7_conv[BENCH_BLT_NCASES])(void) = {bench_blt_m7_conv_sb_cd, bench_blt_m7_conv_sb_var,
                                                       bench_blt_m7_conv_ump_cd, bench_blt_m7_conv_ump_var};

/* Bare metal (QEMU, no command line): each case's iteration, then its convergence. The stack of
 * a convergence: the stack below main's frame repainted before it, then high-water mark after
 * it - depth at its call. */
int main(void)
{
    uint32_t depth;
    uint32_t i;
    volatile uint32_t here = 0u;
    depth = (uint32_t)((uintptr_t)__StackTop - (uintptr_t)&here);
    for (i = 0u; i < BENCH_BLT_NCASES; ++i) {
        const bench_blt_case_t *c = &bench_blt_cases[i];
        uint32_t hwm;
        if ((setup(c, 1u) != 0) || (m7_iter[i]() != 0) || (check_iteration(c) != 0)) {
            return 1;
        }
        printf("blt_m7_%s_iter_props %u\n", c->key, (unsigned)rep.propagations);
        if (setup(c, 0u) != 0) {
            return 1;
        }
        ogk_armv7m_stack_repaint_below((uintptr_t)&here - 1024u);
        if ((m7_conv[i]() != 0) || (check_converged(c) != 0)) {
            return 1;
        }
        hwm = ogk_armv7m_stack_high_water();
        printf("blt_m7_%s_conv_iters %u\n", c->key, (unsigned)rep.iterations);
        printf("blt_m7_%s_conv_props %u\n", c->key, (unsigned)rep.propagations);
        printf("blt_m7_%s_conv_err %.17g\n", c->key, rep.err_norm);
        printf("blt_m7_%s_conv_stack %u (bench_blt_m7_conv_%s and below)\n", c->key, (unsigned)(hwm - depth),
               c->key);
    }
    printf("blt_m7_sizeof_ctx %u\n", (unsigned)sizeof(ogk_blt_t));
    printf("blt_m7_depth_at_call %u\n", (unsigned)depth);
    return 0;
}
#else
static double cpu_ns(void)
{
    struct timespec ts;
    (void)clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
    return (double)ts.tv_sec * 1e9 + (double)ts.tv_nsec;
}

static int cmp_double(const void *a, const void *b)
{
    const double da = *(const double *)a, db = *(const double *)b;
    return (da > db) - (da < db);
}

#define MAX_REPS 401
#define BUDGET_NS 1.0e9 /* per case and unit: at least 11 repetitions and about 1 s */

/* Times fn over repetitions (at least 11, about BUDGET_NS, at most MAX_REPS); prints
 * blt_<key>_<unit>_ns and _cpu_ns. */
static int time_unit(const bench_blt_case_t *c, const char *unit, int (*fn)(const bench_blt_case_t *),
                     int (*check)(const bench_blt_case_t *))
{
    static double t_ns[MAX_REPS];
    static double c_ns[MAX_REPS];
    double total = 0.0;
    int reps = 0;
    while ((reps < MAX_REPS) && ((reps < 11) || (total < BUDGET_NS))) {
        uint64_t t0;
        double c0;
        c0 = cpu_ns();
        t0 = ogk_port_counter_now();
        (void)fn(c);
        t_ns[reps] = (double)(ogk_port_counter_now() - t0);
        c_ns[reps] = cpu_ns() - c0;
        total += t_ns[reps];
        ++reps;
        if (check(c) != 0) {
            return 1;
        }
    }
    qsort(t_ns, (size_t)reps, sizeof t_ns[0], cmp_double);
    qsort(c_ns, (size_t)reps, sizeof c_ns[0], cmp_double);
    printf("blt_%s_%s_ns %.0f wall: median of %d, min %.0f, max %.0f ns\n", c->key, unit, t_ns[reps / 2], reps,
           t_ns[0], t_ns[reps - 1]);
    printf("blt_%s_%s_cpu_ns %.0f CPU time of the process: median of %d, min %.0f, max %.0f ns\n", c->key, unit,
           c_ns[reps / 2], reps, c_ns[0], c_ns[reps - 1]);
    printf("blt_%s_%s_reps %d\n", c->key, unit, reps);
    return 0;
}

static const bench_blt_case_t *find_case(const char *key)
{
    uint32_t i;
    for (i = 0u; i < BENCH_BLT_NCASES; ++i) {
        if (strcmp(bench_blt_cases[i].key, key) == 0) {
            return &bench_blt_cases[i];
        }
    }
    return NULL;
}

static int usage(const char *argv0)
{
    uint32_t i;
    fprintf(stderr, "usage: %s time | once KEY iteration|converge   (KEY:", argv0);
    for (i = 0u; i < BENCH_BLT_NCASES; ++i) {
        fprintf(stderr, " %s", bench_blt_cases[i].key);
    }
    fprintf(stderr, ")\n");
    return 2;
}

int main(int argc, char **argv)
{
    uint32_t i;
    (void)ogk_port_counter_init();
    if ((argc == 4) && (strcmp(argv[1], "once") == 0)) {
        const bench_blt_case_t *c = find_case(argv[2]);
        if (c == NULL) {
            return usage(argv[0]);
        }
        if (strcmp(argv[3], "iteration") == 0) {
            return setup(c, 1u) != 0 || bench_blt_iteration_once(c) != 0 || check_iteration(c) != 0;
        }
        if (strcmp(argv[3], "converge") == 0) {
            return setup(c, 0u) != 0 || bench_blt_converge_once(c) != 0 || check_converged(c) != 0;
        }
        return usage(argv[0]);
    }
    if ((argc != 2) || (strcmp(argv[1], "time") != 0)) {
        return usage(argv[0]);
    }
    for (i = 0u; i < BENCH_BLT_NCASES; ++i) {
        const bench_blt_case_t *c = &bench_blt_cases[i];
        if ((setup(c, 1u) != 0) || (time_unit(c, "iter", bench_blt_iteration_once, check_iteration) != 0)) {
            return 1;
        }
        printf("blt_%s_iter_props %u propagations of one iteration\n", c->key, (unsigned)rep.propagations);
        printf("blt_%s_iter_err %.17g |e| after one iteration (guess %.17g)\n", c->key, rep.err_norm,
               rep.err_norm0);
        if ((setup(c, 0u) != 0) || (time_unit(c, "conv", bench_blt_converge_once, check_converged) != 0)) {
            return 1;
        }
        printf("blt_%s_conv_iters %u NRPC iterations\n", c->key, (unsigned)rep.iterations);
        printf("blt_%s_conv_props %u propagations\n", c->key, (unsigned)rep.propagations);
        printf("blt_%s_conv_err %.17g |e| converged\n", c->key, rep.err_norm);
        printf("blt_%s_unknowns %u x %u errors\n", c->key, (unsigned)rep.n_unknowns, (unsigned)rep.n_errors);
    }
    printf("blt_reps_max %d\n", MAX_REPS);
    printf("blt_sizeof_ctx %u B sizeof(ogk_blt_t)\n", (unsigned)sizeof(ogk_blt_t));
    printf("blt_sizeof_transfer %u B sizeof(ogk_blt_transfer_t)\n", (unsigned)sizeof(ogk_blt_transfer_t));
    return 0;
}
#endif /* OGK_BENCH_BARE_METAL */
