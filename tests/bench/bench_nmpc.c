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
 *   bench_nmpc scan [tol0] [exact|bfgs] [-v] [ULPS]
 *                       the re-solve's stability under ulp moves of its start:
 *                       each component of x_1 and t_1 moved by -ULPS..ULPS
 *                       ulps (default 20), one re-solve each from the saved
 *                       context; the distinct SQP and QP counts and the t_f
 *                       range ("nmpc<mode>_scan_*" lines; -v: every solve)
 *   bench_nmpc scan ... open     the same with x_0 (0..4) or the guess's
 *                       horizon (5) moved instead: the open loop again each
 *                       time, then the re-solve from its plan
 *   bench_nmpc scan ... guess N  N patterns of one-ulp moves of the guess
 *                       (each double with probability 1/8), open loop and
 *                       re-solve each
 *
 * The case (docs/design/nmpc.md, section 10; the committed fixture
 * tests/bench/fixtures/nmpc_case.json, of which bench_nmpc_case.h is the
 * bit-exact transform by tests/bench/nmpc_case.py header): the paper's
 * problem, paper_problem() of scenarios/rendezvous_nep_min_time.toml with
 * the configuration of kernel_config(..., mass_min = 0) (the robustness
 * options of [nmpc] off), the open loop
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
#include <math.h>
#include <string.h>
#ifndef OGK_BENCH_BARE_METAL
#include <time.h>
#endif

#include "ogk/nmpc.h"
#include "ogk_port.h"
#include "bench_nmpc_case.h"
#ifdef OGK_BENCH_BARE_METAL
#include "ogk_armv7m.h"
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
/* bench_nmpc scan open: the open loop's x0 (components 0..4) or the guess's
 * horizon (5) moved by open_move_ulps ulps */
static int open_move_comp = -1;
static int open_move_ulps = 0;
/* bench_nmpc scan guess: every double of the guess (node states past x0,
 * controls, horizon) moved by one ulp up or down with probability 1/8,
 * from a pattern numbered guess_seed (0: the guess as it is) */
static uint32_t guess_seed = 0u;
static double ulps(double x, int k);

/* x moved by k ulps (k > 0 up, k < 0 down). */
static double ulps(double x, int k)
{
    int i;
    for (i = 0; i < k; ++i) {
        x = nextafter(x, INFINITY);
    }
    for (i = 0; i > k; --i) {
        x = nextafter(x, -INFINITY);
    }
    return x;
}

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
    if (open_move_comp == 5) {
        plan.horizon = ulps(plan.horizon, open_move_ulps);
    }
    if (guess_seed != 0u) {
        uint32_t r = guess_seed * 2654435761u;
        size_t j;
        for (j = OGK_NMPC_NX; j <= (BENCH_NMPC_NODES + 1u) * OGK_NMPC_NX + BENCH_NMPC_NODES + 1u; ++j) {
            double *v = (j < (BENCH_NMPC_NODES + 1u) * OGK_NMPC_NX) ? &plan.x[j]
                : ((j < (BENCH_NMPC_NODES + 1u) * OGK_NMPC_NX + BENCH_NMPC_NODES + 1u)
                   ? &plan.u[j - (BENCH_NMPC_NODES + 1u) * OGK_NMPC_NX] : &plan.horizon);
            r = r * 1664525u + 1013904223u;
            if ((r >> 29) == 0u) {
                *v = ulps(*v, ((r >> 28) & 1u) ? 1 : -1);
            }
        }
    }
    plan.nodes = BENCH_NMPC_NODES;
    plan.nu = 1u;
    (void)memcpy(plan.x, bench_nmpc_guess_x, sizeof bench_nmpc_guess_x);
    (void)memcpy(plan.u, bench_nmpc_guess_u, sizeof bench_nmpc_guess_u);
    in.t = 0.0;
    (void)memcpy(in.x, bench_nmpc_x0, sizeof in.x);
    if ((open_move_comp >= 0) && (open_move_comp < 5)) {
        in.x[open_move_comp] = ulps(in.x[open_move_comp], open_move_ulps);
        plan.x[open_move_comp] = in.x[open_move_comp];
    }
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
    hwm_open = ogk_armv7m_stack_high_water();
    depth = (uint32_t)((uintptr_t)__StackTop - (uintptr_t)&here);
    ogk_armv7m_stack_repaint_below((uintptr_t)&here - 1024u);
    if (bench_nmpc_replan_once() != 0) {
        return 1;
    }
    hwm_after = ogk_armv7m_stack_high_water();
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

#define SCAN_MAX_ULPS 20

/* bench_nmpc scan: the re-solve from the start (x_1, t_1) with one component
 * moved by -max..-1, 1..max ulps (the others as the bench's), each from the
 * saved context: one line per solve ("scan <component> <ulps> <status> <SQP>
 * <QP> <t_f>"), then the distinct (SQP, QP) counts with how often each came
 * and the t_f range. Component 0..4: x_1 (r, theta, v_r, v_theta, m); 5: t_1. */
static int scan_guess(const char *key, int patterns, int verbose)
{
    static unsigned hist_sqp[OGK_NMPC_MAX_SQP_ITER + 1u];
    static unsigned hist_open[OGK_NMPC_MAX_SQP_ITER + 1u];
    double tf_min = INFINITY;
    double tf_max = -INFINITY;
    unsigned failed = 0u;
    unsigned i;
    int k;
    for (k = 1; k <= patterns; ++k) {
        guess_seed = (uint32_t)k;
        if ((setup() != 0) || (bench_nmpc_replan_once() != 0)
            || ((rep_replan.flags & OGK_NMPC_FLAG_CONVERGED) == 0u)) {
            failed += 1u;
            continue;
        }
        hist_open[rep_open.sqp_iterations <= OGK_NMPC_MAX_SQP_ITER ? rep_open.sqp_iterations : 0u] += 1u;
        hist_sqp[rep_replan.sqp_iterations <= OGK_NMPC_MAX_SQP_ITER ? rep_replan.sqp_iterations : 0u] += 1u;
        tf_min = (rep_replan.t_f < tf_min) ? rep_replan.t_f : tf_min;
        tf_max = (rep_replan.t_f > tf_max) ? rep_replan.t_f : tf_max;
        if (verbose) {
            printf("scan guess %d %u %u %u %.17g\n", k, (unsigned)rep_open.sqp_iterations,
                   (unsigned)rep_replan.sqp_iterations, (unsigned)rep_replan.qp_iterations, rep_replan.t_f);
        }
    }
    guess_seed = 0u;
    printf("%s_scan_guess_solves %d (ulp patterns of the guess), failed %u\n%s_scan_guess_open_sqp", key, patterns,
           failed, key);
    for (i = 0u; i <= OGK_NMPC_MAX_SQP_ITER; ++i) {
        if (hist_open[i] != 0u) {
            printf(" %u:%u", i, hist_open[i]);
        }
    }
    printf(" (open loop SQP iterations:solves)\n%s_scan_guess_sqp", key);
    for (i = 0u; i <= OGK_NMPC_MAX_SQP_ITER; ++i) {
        if (hist_sqp[i] != 0u) {
            printf(" %u:%u", i, hist_sqp[i]);
        }
    }
    printf(" (SQP iterations:solves)\n%s_scan_guess_tf %.17g %.17g (min, max TU; spread %.3g s)\n", key, tf_min,
           tf_max, (tf_max - tf_min) * BENCH_NMPC_TU_S);
    return failed == 0u ? 0 : 1;
}

static int scan(const char *key, int max_ulps, int verbose, int open)
{
    static const char *const names[6] = {"r", "theta", "v_r", "v_theta", "m", "t"};
    static const char *const open_names[6] = {"x0_r", "x0_theta", "x0_v_r", "x0_v_theta", "x0_m", "horizon"};
    static unsigned hist_open[OGK_NMPC_MAX_SQP_ITER + 1u];
    static unsigned hist_sqp[OGK_NMPC_MAX_SQP_ITER + 1u];
    static unsigned hist_qp[4096];
    const ogk_nmpc_input_t base = in_replan;
    double tf_min = INFINITY;
    double tf_max = -INFINITY;
    unsigned failed = 0u;
    unsigned solves = 0u;
    unsigned i;
    int c;
    int k;
    (void)memcpy(&saved, &ctx, sizeof saved);
    for (c = 0; c < 6; ++c) {
        for (k = -max_ulps; k <= max_ulps; ++k) {
            int st;
            if (open) {
                /* the open loop from a moved x0 or guess horizon, then the re-solve from its plan */
                open_move_comp = c;
                open_move_ulps = k;
                if (setup() != 0) {
                    failed += 1u;
                    continue;
                }
                hist_open[rep_open.sqp_iterations <= OGK_NMPC_MAX_SQP_ITER ? rep_open.sqp_iterations : 0u] += 1u;
            } else {
                in_replan = base;
                if (c < 5) {
                    in_replan.x[c] = ulps(base.x[c], k);
                } else {
                    in_replan.t = ulps(base.t, k);
                }
                (void)memcpy(&ctx, &saved, sizeof ctx);
            }
            st = bench_nmpc_replan_once();
            solves += 1u;
            if ((st != 0) || ((rep_replan.flags & OGK_NMPC_FLAG_CONVERGED) == 0u)) {
                failed += 1u;
            } else {
                hist_sqp[rep_replan.sqp_iterations <= OGK_NMPC_MAX_SQP_ITER ? rep_replan.sqp_iterations : 0u] += 1u;
                hist_qp[rep_replan.qp_iterations < 4096u ? rep_replan.qp_iterations : 0u] += 1u;
                tf_min = (rep_replan.t_f < tf_min) ? rep_replan.t_f : tf_min;
                tf_max = (rep_replan.t_f > tf_max) ? rep_replan.t_f : tf_max;
            }
            if (verbose || (k == 0 && c == 0)) {
                printf("scan %s %+d %d %u %u %.17g\n", open ? open_names[c] : names[c], k, st,
                       (unsigned)rep_replan.sqp_iterations, (unsigned)rep_replan.qp_iterations, rep_replan.t_f);
            }
        }
    }
    in_replan = base;
    (void)memcpy(&ctx, &saved, sizeof ctx);
    open_move_comp = -1;
    printf("%s_scan%s_solves %u (6 components x %d ulps either way and 0), failed %u\n", key,
           open ? "_open" : "", solves, max_ulps, failed);
    if (open) {
        printf("%s_scan_open_open_sqp", key);
        for (i = 0u; i <= OGK_NMPC_MAX_SQP_ITER; ++i) {
            if (hist_open[i] != 0u) {
                printf(" %u:%u", i, hist_open[i]);
            }
        }
        printf(" (open loop SQP iterations:solves)\n");
    }
    printf("%s_scan%s_sqp", key, open ? "_open" : "");
    for (i = 0u; i <= OGK_NMPC_MAX_SQP_ITER; ++i) {
        if (hist_sqp[i] != 0u) {
            printf(" %u:%u", i, hist_sqp[i]);
        }
    }
    printf(" (SQP iterations:solves)\n%s_scan%s_qp", key, open ? "_open" : "");
    for (i = 0u; i < 4096u; ++i) {
        if (hist_qp[i] != 0u) {
            printf(" %u:%u", i, hist_qp[i]);
        }
    }
    printf(" (QP iterations:solves)\n%s_scan%s_tf %.17g %.17g (min, max TU; spread %.3g s)\n", key,
           open ? "_open" : "", tf_min, tf_max, (tf_max - tf_min) * BENCH_NMPC_TU_S);
    return failed == 0u ? 0 : 1;
}

int main(int argc, char **argv)
{
    static double t_ns[MAX_REPS];
    static double c_ns[MAX_REPS];
    static char key[32];
    int reps = 0;
    int i;
    int max_ulps = SCAN_MAX_ULPS;
    int verbose = 0;
    int open = 0;
    int guess = 0;
    if (argc < 2 || (strcmp(argv[1], "time") != 0 && strcmp(argv[1], "once") != 0
                     && strcmp(argv[1], "scan") != 0)) {
        fprintf(stderr, "usage: %s time|once|scan [tol0] [exact|bfgs] [open|guess] [-v] [ULPS]\n", argv[0]);
        return 2;
    }
    for (i = 2; i < argc; ++i) {
        if (strcmp(argv[i], "tol0") == 0) {
            opt_tol0 = 1;
        } else if (strcmp(argv[i], "bfgs") == 0) {
            opt_hessian = (int)OGK_NMPC_HESSIAN_BFGS;
        } else if (strcmp(argv[i], "exact") == 0) {
            opt_hessian = (int)OGK_NMPC_HESSIAN_EXACT;
        } else if (strcmp(argv[i], "-v") == 0) {
            verbose = 1;
        } else if (strcmp(argv[i], "open") == 0) {
            open = 1;
        } else if (strcmp(argv[i], "guess") == 0) {
            guess = 1;
        } else if (atoi(argv[i]) > 0 && atoi(argv[i]) <= 1000) {
            max_ulps = atoi(argv[i]);
        } else {
            fprintf(stderr, "usage: %s time|once [tol0] [exact|bfgs]\n", argv[0]);
            return 2;
        }
    }
    (void)snprintf(key, sizeof key, "nmpc%s%s",
                   opt_hessian < 0 ? "" : (opt_hessian == (int)OGK_NMPC_HESSIAN_EXACT ? "_exact" : "_bfgs"),
                   opt_tol0 ? "_tol0" : "");
    (void)ogk_port_counter_init();
    if (strcmp(argv[1], "scan") == 0) {
        if (guess) {
            return scan_guess(key, max_ulps, verbose);
        }
        return (setup() != 0) ? 1 : scan(key, max_ulps, verbose, open);
    }
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
