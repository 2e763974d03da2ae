/* bench_nmpc.c -- cost of one warm NMPC re-solve (ogk_nmpc_replan) at N = 30.
 *
 *   bench_nmpc time     the open loop (median of 3), then the re-solve timed
 *                       over repetitions: median wall time (port counter)
 *                       and median CPU time of the process (the machine is
 *                       shared: waiting for a core is not the kernel's cost),
 *                       SQP iterations, sizeofs;
 *                       "nmpc_<key> <value>" lines for bench_nmpc_ipopt.py
 *   bench_nmpc once     the open loop, then exactly one re-solve, for valgrind
 *                       callgrind with --toggle-collect=bench_nmpc_replan_once
 *   bench_nmpc time|once [tol0] [exact|bfgs]
 *                       the same re-solve with tol_obj = 0 (the stationarity
 *                       test alone: the converged optimum, IPOPT's accuracy)
 *                       and/or the exact (or damped-BFGS) Hessian in place
 *                       of the configuration's, both set AFTER the same open
 *                       loop (the configuration's): every mode re-solves from
 *                       the same (t_1, x_1) and warm start, only the solver
 *                       differs; keys "nmpc[_exact|_bfgs][_tol0]_<key>"
 *   (bare metal)        the same as once, for the QEMU instruction counter
 *                       (`make bench-nmpc`); prints "nmpc_m7_<key> <value>"
 *                       lines, among them the stack used by the re-solve
 *
 * The case (docs/nmpc.md, "Cost"; generated into bench_nmpc_case.h by
 * tests/bench/bench_nmpc_ipopt.py header from the scenario, bit-exact):
 * scenarios/rendezvous_nep_min_time.toml with the configuration of
 * kernel_config() (what `ogk nmpc --solver kernel` flies), the open loop
 * ogk_nmpc_solve from the documented guess (guidance_base.first_guess), then one
 * SNNS ogk_nmpc_replan at the plan's first node time t_next from the plan's
 * node-1 state with r + 1e-4 LU and v_theta + 1e-4 VU (N 30 -> 29; its BFGS
 * matrix and multipliers kept). Every repetition starts from the same saved
 * context (memcpy of the ogk_nmpc_t after the open loop, outside the timing),
 * so every repetition is the same work. */
#ifndef OGK_BENCH_BARE_METAL
#define _POSIX_C_SOURCE 199309L /* clock_gettime(CLOCK_PROCESS_CPUTIME_ID) */
#endif
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#ifndef OGK_BENCH_BARE_METAL
#include <time.h>
#endif

#include "ogk/nmpc.h"
#include "ogk_port.h"
#include "bench_nmpc_case.h"
#ifdef OGK_BENCH_BARE_METAL
#include "ogk_cm7.h"
#endif

static ogk_nmpc_t ctx;
static ogk_nmpc_report_t rep_open;
static ogk_nmpc_report_t rep_replan;
static ogk_nmpc_input_t in_replan;
static volatile double sink;
/* The options of the command line, or for the bare-metal build
 * -DBENCH_NMPC_TOL0=1 and -DBENCH_NMPC_HESSIAN=<OGK_NMPC_HESSIAN_*>. */
#ifndef BENCH_NMPC_TOL0
#define BENCH_NMPC_TOL0 0
#endif
#ifndef BENCH_NMPC_HESSIAN
#define BENCH_NMPC_HESSIAN (-1)
#endif
static int opt_tol0 = BENCH_NMPC_TOL0;          /* tol_obj = 0 */
static int opt_hessian = BENCH_NMPC_HESSIAN;    /* OGK_NMPC_HESSIAN_*, -1: the configuration's */

/* init, the documented guess, the open loop. */
static int setup(void)
{
    ogk_nmpc_config_t cfg;
    static ogk_nmpc_plan_t plan;
    ogk_nmpc_input_t in;
    ogk_status st;
    (void)ogk_nmpc_config_default(&cfg);
    bench_nmpc_case_config(&cfg);
    (void)memset(&plan, 0, sizeof plan);
    plan.t0 = bench_nmpc_guess_t0;
    plan.horizon = bench_nmpc_guess_horizon;
    plan.nodes = BENCH_NMPC_NODES;
    plan.nu = 1u;
    (void)memcpy(plan.x, bench_nmpc_guess_x, sizeof bench_nmpc_guess_x);
    (void)memcpy(plan.u, bench_nmpc_guess_u, sizeof bench_nmpc_guess_u);
    in.t = 0.0;
    (void)memcpy(in.x, bench_nmpc_x0, sizeof in.x);
    st = ogk_nmpc_init(&ctx, &cfg);
    if (st == OGK_OK) {
        st = ogk_nmpc_load_plan(&ctx, &plan);
    }
    if (st == OGK_OK) {
        st = ogk_nmpc_solve(&ctx, &in, &rep_open);
    }
    if (st == OGK_OK) {
        st = ogk_nmpc_get_plan(&ctx, &plan);
    }
    if (st != OGK_OK) {
        fprintf(stderr, "bench_nmpc: open loop failed (status %d)\n", (int)st);
        return 1;
    }
    /* the re-solve's options, after the open loop: the same start for every mode */
    if (opt_tol0) {
        ctx.cfg.tol_obj = 0.0;
    }
    if (opt_hessian >= 0) {
        ctx.cfg.hessian = (uint32_t)opt_hessian;
    }
    /* the replan: at the first node's time, the plan's node-1 state perturbed */
    in_replan.t = rep_open.t_next;
    (void)memcpy(in_replan.x, &plan.x[OGK_NMPC_NX], sizeof in_replan.x);
    in_replan.x[0] += BENCH_NMPC_DR;
    in_replan.x[3] += BENCH_NMPC_DVT;
    return 0;
}

/* Exactly one warm re-solve (the callgrind / QEMU unit). */
__attribute__((noinline)) static int bench_nmpc_replan_once(void)
{
    int st = (int)ogk_nmpc_replan(&ctx, &in_replan, &rep_replan);
    sink = rep_replan.t_f;
    return st;
}

static int check_replan(void)
{
    if ((rep_replan.flags & OGK_NMPC_FLAG_CONVERGED) == 0u || rep_replan.nodes != BENCH_NMPC_NODES - 1u) {
        fprintf(stderr, "bench_nmpc: the re-solve did not converge (status %d, flags 0x%x, N %u)\n",
                (int)rep_replan.solve_status, (unsigned)rep_replan.flags, (unsigned)rep_replan.nodes);
        return 1;
    }
    return 0;
}

#ifdef OGK_BENCH_BARE_METAL
extern uint32_t __StackTop[];

/* Bare metal (QEMU, no command line): the open loop, then one re-solve. The
 * stack of the re-solve: the stack below main's frame repainted after the
 * open loop, then high-water mark after the re-solve - depth at its call. */
int main(void)
{
    uint32_t hwm_open, hwm_after, depth;
    volatile uint32_t here = 0u;
    if (setup() != 0) {
        return 1;
    }
    hwm_open = ogk_cm7_stack_high_water();
    depth = (uint32_t)((uintptr_t)__StackTop - (uintptr_t)&here);
    ogk_cm7_stack_repaint_below((uintptr_t)&here - 1024u);
    if (bench_nmpc_replan_once() != 0) {
        return 1;
    }
    hwm_after = ogk_cm7_stack_high_water();
    if (check_replan() != 0) {
        return 1;
    }
    printf("nmpc_m7_open_sqp %u\n", (unsigned)rep_open.sqp_iterations);
    printf("nmpc_m7_replan_sqp %u\n", (unsigned)rep_replan.sqp_iterations);
    printf("nmpc_m7_replan_qp %u\n", (unsigned)rep_replan.qp_iterations);
    printf("nmpc_m7_replan_tf %.17g\n", rep_replan.t_f);
    printf("nmpc_m7_sizeof_ctx %u\n", (unsigned)sizeof(ogk_nmpc_t));
    printf("nmpc_m7_sizeof_qp_ws %u\n", (unsigned)sizeof(ogk_qp_workspace_t));
    printf("nmpc_m7_open_hwm %u (setup and open loop, from the stack top)\n", (unsigned)hwm_open);
    printf("nmpc_m7_depth_at_replan_call %u\n", (unsigned)depth);
    printf("nmpc_m7_replan_stack %u (bench_nmpc_replan_once and below)\n", (unsigned)(hwm_after - depth));
    return 0;
}
#else
static ogk_nmpc_t saved;

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

int main(int argc, char **argv)
{
    static double t_ns[MAX_REPS];
    static double c_ns[MAX_REPS];
    static char key[32];
    int reps = 0;
    int i;
    if (argc < 2 || (strcmp(argv[1], "time") != 0 && strcmp(argv[1], "once") != 0)) {
        fprintf(stderr, "usage: %s time|once [tol0] [exact|bfgs]\n", argv[0]);
        return 2;
    }
    for (i = 2; i < argc; ++i) {
        if (strcmp(argv[i], "tol0") == 0) {
            opt_tol0 = 1;
        } else if (strcmp(argv[i], "bfgs") == 0) {
            opt_hessian = (int)OGK_NMPC_HESSIAN_BFGS;
        } else if (strcmp(argv[i], "exact") == 0) {
            opt_hessian = (int)OGK_NMPC_HESSIAN_EXACT;
        } else {
            fprintf(stderr, "usage: %s time|once [tol0] [exact|bfgs]\n", argv[0]);
            return 2;
        }
    }
    (void)snprintf(key, sizeof key, "nmpc%s%s",
                   opt_hessian < 0 ? "" : (opt_hessian == (int)OGK_NMPC_HESSIAN_EXACT ? "_exact" : "_bfgs"),
                   opt_tol0 ? "_tol0" : "");
    (void)ogk_port_counter_init();
    if (strcmp(argv[1], "once") == 0) {
        if (setup() != 0 || bench_nmpc_replan_once() != 0 || check_replan() != 0) {
            return 1;
        }
        /* what the counted re-solve did (the same as time's, or the count is of another solve) */
        printf("%s_open_sqp %u\n%s_replan_sqp %u\n%s_replan_tf %.17g\n", key, (unsigned)rep_open.sqp_iterations,
               key, (unsigned)rep_replan.sqp_iterations, key, rep_replan.t_f);
        return 0;
    }
    /* the open loop: median of 3 from scratch (init + load + solve) */
    for (i = 0; i < 3; ++i) {
        const uint64_t t0 = ogk_port_counter_now();
        if (setup() != 0) {
            return 1;
        }
        t_ns[i] = (double)(ogk_port_counter_now() - t0);
    }
    qsort(t_ns, 3u, sizeof t_ns[0], cmp_double);
    printf("%s_open_ns %.0f open loop N = %u: %u SQP iterations (%u QP), t_f %.17g TU, median of 3\n", key,
           t_ns[1], (unsigned)BENCH_NMPC_NODES, (unsigned)rep_open.sqp_iterations,
           (unsigned)rep_open.qp_iterations, rep_open.t_f);
    (void)memcpy(&saved, &ctx, sizeof saved);
    /* the re-solve: at least 11 repetitions and about 1.5 s */
    while (reps < MAX_REPS) {
        uint64_t t0;
        double c0;
        (void)memcpy(&ctx, &saved, sizeof ctx);
        c0 = cpu_ns();
        t0 = ogk_port_counter_now();
        if (bench_nmpc_replan_once() != 0) {
            fprintf(stderr, "bench_nmpc: ogk_nmpc_replan failed\n");
            return 1;
        }
        t_ns[reps] = (double)(ogk_port_counter_now() - t0);
        c_ns[reps++] = cpu_ns() - c0;
        if (check_replan() != 0) {
            return 1;
        }
        if (reps >= 11) {
            double total = 0.0;
            int k;
            for (k = 0; k < reps; ++k) {
                total += t_ns[k];
            }
            if (total > 1.5e9) {
                break;
            }
        }
    }
    qsort(t_ns, (size_t)reps, sizeof t_ns[0], cmp_double);
    printf("%s_replan_ns %.0f warm re-solve N = %u: median of %d, min %.0f, max %.0f ns\n", key,
           t_ns[reps / 2], (unsigned)rep_replan.nodes, reps, t_ns[0], t_ns[reps - 1]);
    qsort(c_ns, (size_t)reps, sizeof c_ns[0], cmp_double);
    printf("%s_replan_cpu_ns %.0f CPU time of the process: median of %d, min %.0f, max %.0f ns\n", key,
           c_ns[reps / 2], reps, c_ns[0], c_ns[reps - 1]);
    printf("%s_replan_reps %d\n", key, reps);
    printf("%s_replan_sqp %u SQP iterations\n", key, (unsigned)rep_replan.sqp_iterations);
    printf("%s_replan_qp %u QP iterations\n", key, (unsigned)rep_replan.qp_iterations);
    printf("%s_replan_tf %.17g TU\n", key, rep_replan.t_f);
    printf("nmpc_sizeof_ctx %u B sizeof(ogk_nmpc_t)\n", (unsigned)sizeof(ogk_nmpc_t));
    printf("nmpc_sizeof_qp_ws %u B sizeof(ogk_qp_workspace_t)\n", (unsigned)sizeof(ogk_qp_workspace_t));
    return 0;
}
#endif /* OGK_BENCH_BARE_METAL */
