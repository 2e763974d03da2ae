/* bench_mpsp.c -- cost of one MPSP Newton iteration at flight size.
 *
 *   bench_mpsp time CASE      ns per call (median of 7 batches)
 *   bench_mpsp once CASE      one call, for valgrind callgrind with
 *                             --toggle-collect=bench_CASE_once
 * Problem: the Apophis transfer in the paper's normalised units (Table 1-2:
 * mu = 1, T_max = 1.5 mN -> 0.010118, c = 3000 s g0 -> 0.98775, m0 = 1,
 * tf = 1156 d = 19.886 TU), Fourier order 15 (93 weights + lambda_m0 = 94
 * unknowns), h_max = 5e-4 tf (2000 RK4 steps); synthetic weights that switch
 * the engine 8 times (the bench needs the size, not the optimum).
 * CASE: mpsp_iter    one Newton iteration of Algorithm 1: sensitivities
 *                    (eqs. 28-35 with 22-25), update (eqs. 44-46), and the
 *                    propagation of the updated weights with switch detection
 *       mpsp_prop    the propagation alone
 *       mpsp_sens    the sensitivities alone
 *       mpsp_update  the update alone (7 x 94 minimum-norm solve)
 *       mpsp_iter_mid2, mpsp_sens_mid2  the same with the second-order
 *                    sweep (sens_sweep = OGK_MPSP_SWEEP_MID2); the others run
 *                    the exact one (OGK_MPSP_SWEEP_RK4) */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <math.h>

#include "ogk/mpsp.h"
#include "ogk_port.h"
#ifndef OGK_BENCH_BARE_METAL
#include "bench_timer.h"
#endif

static ogk_mpsp_t ctx;
static ogk_mpsp_config_t cfg;
static double w_new[OGK_MPSP_MAX_WEIGHTS];
static volatile double sink;

static const double dy_fixed[OGK_MPSP_NY] = {1e-4, -2e-4, 5e-5, 1e-4, 0.0, -1e-4, 1e-5};

static int setup(uint32_t sweep)
{
    static const double x0[7] = {1.001367, 0.140622, -6.594513e-6,
                                 -0.155386, 0.986258, -4.827818e-5, 1.0};
    const double tu_s = 5.022643e6;
    const double lu_m = 1.495979e11;
    const double acc_unit = lu_m / (tu_s * tu_s);
    ogk_mpsp_prop_t prop;
    size_t i;

    memset(&cfg, 0, sizeof cfg);
    cfg.mu = 1.0;
    cfg.t_max = 1.5e-3 / (25.0 * acc_unit);
    cfg.c_exhaust = 3000.0 * 9.80655 / (lu_m / tu_s);
    cfg.t0 = 0.0;
    cfg.tf = 1156.0 * 86400.0 / tu_s;
    memcpy(cfg.x0_nom, x0, sizeof x0);
    cfg.r_f[0] = -1.044138;
    cfg.r_f[1] = -0.122918;
    cfg.r_f[2] = -0.018183;
    cfg.v_f[0] = 0.222668;
    cfg.v_f[1] = -0.875235;
    cfg.v_f[2] = 0.051944;
    cfg.fourier_order = 15u;
    cfg.fourier_period = 2.0 * cfg.tf;
    cfg.fourier_t_ref = 0.0;
    cfg.h_max = 5e-4 * cfg.tf;
    cfg.delta_max = 1.0;
    cfg.delta_tau_0 = 0.5;
    cfg.delta_tau_min = 0.1;
    for (i = 0u; i < OGK_MPSP_MAX_WEIGHTS; ++i) {
        cfg.r_eps[i] = 1.0;
        cfg.weights_nom[i] = 0.01 * sin(1.0 + (double)i); /* every harmonic present */
    }
    cfg.weights_nom[0] = 2.2;   /* |lambda_v| ~ 1.1 + 0.4 cos 5 th: 8 switches */
    cfg.weights_nom[9] = 0.4;
    cfg.weights_nom[31 + 2] = 0.3;
    cfg.r_lambda = 1.0;
    cfg.tol_r = 3.342e-6;       /* 500 km */
    cfg.tol_v = 3.357e-3;       /* 0.1 km/s */
    cfg.tol_lambda_m = 1e-6;
    cfg.s_tol = 1e-12;
    cfg.max_newton = 100u;
    cfg.max_outer = 50u;
    cfg.n_seg_tol = 0u;
    cfg.n_seg_tol_step = 2u;
    cfg.lambda_m0_nom = 0.0;
    cfg.sens_sweep = sweep;
    if (ogk_mpsp_init(&ctx, &cfg) != OGK_OK ||
        ogk_mpsp_propagate(&ctx, cfg.weights_nom, 0.0, x0, 1.0, &prop) != OGK_OK) {
        fprintf(stderr, "bench_mpsp: setup failed\n");
        return 1;
    }
    if (prop.n_nodes < 2001u || prop.n_switches < 4u) {
        fprintf(stderr, "bench_mpsp: unexpected trajectory (%u nodes, %u switches)\n",
                (unsigned)prop.n_nodes, (unsigned)prop.n_switches);
        return 1;
    }
    return 0;
}

/* One Newton iteration: sensitivities, update, propagation. The update always
 * starts from the nominal weights, so the trajectory (and the cost) is the
 * same at every call. Inlined into each named entry below (a call would be a
 * tail jump, not a function of its own for callgrind and the QEMU plugin);
 * each entry sinks another element, so that gcc does not fold them. */
__attribute__((always_inline)) static inline int newton_iteration(size_t sink_at)
{
    double lm0 = 0.0;
    ogk_mpsp_prop_t prop;
    int st = (int)ogk_mpsp_sensitivity(&ctx, NULL, NULL);
    memcpy(w_new, cfg.weights_nom, ctx.n_weights * sizeof w_new[0]);
    if (st == 0) {
        st = (int)ogk_mpsp_newton_update(&ctx, dy_fixed, w_new, &lm0);
    }
    if (st == 0) {
        st = (int)ogk_mpsp_propagate(&ctx, w_new, lm0, cfg.x0_nom, 1.0, &prop);
        sink = prop.x_f[sink_at];
    }
    return st;
}

__attribute__((noinline)) static int bench_mpsp_iter_once(void)
{
    return newton_iteration(0u);
}

/* The same iteration after setup(OGK_MPSP_SWEEP_MID2), under its own name. */
__attribute__((noinline)) static int bench_mpsp_iter_mid2_once(void)
{
    return newton_iteration(1u);
}

__attribute__((noinline)) static int bench_mpsp_sens_mid2_once(void)
{
    int st = (int)ogk_mpsp_sensitivity(&ctx, NULL, NULL);
    sink = ctx.dy_dlm0[1];
    return st;
}

__attribute__((noinline)) static int bench_mpsp_prop_once(void)
{
    ogk_mpsp_prop_t prop;
    int st = (int)ogk_mpsp_propagate(&ctx, cfg.weights_nom, 0.0, cfg.x0_nom, 1.0, &prop);
    sink = prop.x_f[0];
    return st;
}

__attribute__((noinline)) static int bench_mpsp_sens_once(void)
{
    int st = (int)ogk_mpsp_sensitivity(&ctx, NULL, NULL);
    sink = ctx.dy_dlm0[0];
    return st;
}

__attribute__((noinline)) static int bench_mpsp_update_once(void)
{
    double lm0 = 0.0;
    int st;
    memcpy(w_new, cfg.weights_nom, ctx.n_weights * sizeof w_new[0]);
    st = (int)ogk_mpsp_newton_update(&ctx, dy_fixed, w_new, &lm0);
    sink = lm0;
    return st;
}

typedef struct {
    const char *name;
    int (*fn)(void);
    long iters;
} bench_case_t;

#ifdef OGK_BENCH_BARE_METAL
/* Bare-metal build (QEMU, no command line): one call of every case, for the
 * instruction-counting plugin (`make bench-arm`). */
int main(void)
{
    int st;
    if (setup(OGK_MPSP_SWEEP_RK4) != 0 || ogk_mpsp_sensitivity(&ctx, NULL, NULL) != OGK_OK) {
        return 1;
    }
    st = bench_mpsp_iter_once() | bench_mpsp_prop_once() | bench_mpsp_sens_once() |
         bench_mpsp_update_once();
    if (setup(OGK_MPSP_SWEEP_MID2) != 0 || ogk_mpsp_sensitivity(&ctx, NULL, NULL) != OGK_OK) {
        return 1;
    }
    return st | bench_mpsp_iter_mid2_once() | bench_mpsp_sens_mid2_once();
}
#else
int main(int argc, char **argv)
{
    static const bench_case_t cases[] = {
        {"mpsp_iter", bench_mpsp_iter_once, 100L},
        {"mpsp_prop", bench_mpsp_prop_once, 200L},
        {"mpsp_sens", bench_mpsp_sens_once, 200L},
        {"mpsp_update", bench_mpsp_update_once, 2000L},
        {"mpsp_iter_mid2", bench_mpsp_iter_mid2_once, 100L},
        {"mpsp_sens_mid2", bench_mpsp_sens_mid2_once, 200L},
    };
    size_t i;
    (void)ogk_port_counter_init();
    if (argc != 3) {
        fprintf(stderr, "usage: %s time|once mpsp_iter|mpsp_prop|mpsp_sens|mpsp_update|"
                "mpsp_iter_mid2|mpsp_sens_mid2\n", argv[0]);
        return 2;
    }
    if (setup((strstr(argv[2], "_mid2") != NULL) ? OGK_MPSP_SWEEP_MID2 : OGK_MPSP_SWEEP_RK4) != 0) {
        return 1;
    }
    /* The sensitivity and update cases need a trajectory and its sensitivities. */
    if (ogk_mpsp_sensitivity(&ctx, NULL, NULL) != OGK_OK) {
        return 1;
    }
    for (i = 0u; i < sizeof cases / sizeof cases[0]; ++i) {
        if (strcmp(argv[2], cases[i].name) != 0) {
            continue;
        }
        if (strcmp(argv[1], "once") == 0) {
            return cases[i].fn();
        }
        if (strcmp(argv[1], "time") == 0) {
            return bench_time_case(cases[i].fn, cases[i].iters, cases[i].name);
        }
    }
    fprintf(stderr, "unknown arguments\n");
    return 2;
}
#endif /* OGK_BENCH_BARE_METAL */
