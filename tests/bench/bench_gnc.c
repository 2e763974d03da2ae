/* bench_gnc.c -- cost of one VTD-NOG sampling step and one CPD step (host).
 *
 *   bench_gnc TABLE time CASE    ns per call (median of 7 batches)
 *   bench_gnc TABLE once CASE    one call, for callgrind --toggle-collect=bench_CASE_once
 * CASE: nog_sample   ogk_nog_sample at mid-burn (tau = 0.5) from a state displaced by
 *                    Table 3 1-sigma errors: nominal and gain interpolation, dx, the 8x7 and
 *                    7x7 gain products, the direction bound, eq. (27)
 *       nog_command  ogk_nog_thrust_cmd inside the interval (what the attitude loop calls)
 *       cpd_step     ogk_cpd_step in BODY pointing with the braking cap, saturated pitch
 * TABLE is the LEO-to-GEO bundle written by `ogk tables leo-geo`. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "ogk/cpd.h"
#include "ogk/nog.h"
#include "ogk/table.h"
#include "ogk_port.h"
#include "bench_timer.h"

static ogk_nog_table_t table;
static uint8_t image[OGK_TABLE_HEADER_SIZE + 8u * OGK_NOG_MAX_GRID * (1u + OGK_NOG_ENTRY_LEN)];
static ogk_nog_t nog;
static ogk_nog_nav_t nav_mid;
static ogk_cpd_t cpd;
static ogk_cpd_input_t cpd_in;
static volatile double sink;

__attribute__((noinline)) static int bench_nog_sample_once(void)
{
    ogk_nog_sample_t out;
    int st;
    /* Re-arm the context at the previous sample so every call is the same work. */
    nog.n_samples = 1u;
    nog.t_k_s = nav_mid.t_s - 2.0;
    nog.tau_k = (nav_mid.t_s - 2.0) / table.t_f_star_s;
    nog.t_f_s = table.t_f_star_s;
    st = (int)ogk_nog_sample(&nog, &nav_mid, &out);
    sink = out.alpha_rad;
    return st;
}

__attribute__((noinline)) static int bench_nog_command_once(void)
{
    ogk_thrust_cmd_t out;
    int st = (int)ogk_nog_thrust_cmd(&nog, nav_mid.t_s + 1.3, &out);
    sink = out.alpha_rad;
    return st;
}

__attribute__((noinline)) static int bench_cpd_step_once(void)
{
    ogk_cpd_output_t out;
    int st = (int)ogk_cpd_step(&cpd, &cpd_in, &out);
    sink = out.delta_yc;
    return st;
}

static int setup(const char *path)
{
    FILE *f = fopen(path, "rb");
    size_t len;
    double x_mid[OGK_NOG_NX];
    ogk_nog_config_t cfg;
    ogk_cpd_config_t cc;
    size_t k;
    if (f == NULL) {
        fprintf(stderr, "cannot open %s\n", path);
        return 1;
    }
    len = fread(image, 1u, sizeof image, f);
    fclose(f);
    if (ogk_nog_table_load(&table, image, len) != OGK_OK) {
        fprintf(stderr, "table rejected\n");
        return 1;
    }
    (void)ogk_nog_config_default(&cfg);
    cfg.table = &table;
    cfg.sample_interval_s = 2.0;
    cfg.dtf_max_s = 40.0;
    cfg.du_max_rad = 1.0471975511965976;
    cfg.tau_freeze = 0.5 / table.t_f_star_s;
    if (ogk_nog_init(&nog, &cfg) != OGK_OK) {
        return 1;
    }
    /* The node nearest tau = 0.5, displaced by Table 3 1-sigma values. */
    k = table.n_grid / 2u;
    memcpy(x_mid, &table.entry[k * OGK_NOG_ENTRY_LEN + OGK_NOG_OFF_X], sizeof x_mid);
    nav_mid.t_s = x_mid[6];
    nav_mid.r_m = x_mid[0] + 5.0e3;
    nav_mid.xi_rad = x_mid[1];
    nav_mid.phi_rad = x_mid[2] + 1.19e-4;
    nav_mid.v_r_mps = x_mid[3] + 30.0;
    nav_mid.v_t_mps = x_mid[4] - 30.0;
    nav_mid.v_n_mps = x_mid[5] + 30.0;
    if (bench_nog_sample_once() != 0) {
        fprintf(stderr, "nog sample failed\n");
        return 1;
    }
    memset(&cc, 0, sizeof cc);
    cc.k_px = 21573.12;
    cc.k_dx = 7194.432;
    cc.k_py = cc.k_pz = 2.1980875528095924;
    cc.k_dy = cc.k_dz = 0.7330414621869725;
    cc.m_xc_max = 30.0;
    cc.delta_yc_max = cc.delta_zc_max = 0.011344640137963142;
    cc.tau_x = cc.tau_y = cc.tau_z = 0.1;
    cc.pointing = OGK_CPD_POINTING_BODY;
    cc.approach_accel_x = 0.0125;
    cc.approach_accel_y = cc.approach_accel_z = 0.0464;
    if (ogk_cpd_init(&cpd, &cc) != OGK_OK) {
        return 1;
    }
    memset(&cpd_in, 0, sizeof cpd_in);
    cpd_in.psi = 0.05;
    cpd_in.theta = -0.2;
    cpd_in.phi_roll = 0.3;
    cpd_in.rate_p = 0.02;
    cpd_in.rate_q = 0.05;
    cpd_in.rate_r = -0.01;
    cpd_in.alpha_c = 0.4;
    cpd_in.beta_c = 0.02;
    cpd_in.xi = 3.0;
    cpd_in.phi = 1e-4;
    return bench_cpd_step_once();
}

int main(int argc, char **argv)
{
    int (*fn)(void) = NULL;
    (void)ogk_port_counter_init();
    if (argc != 4 || setup(argv[1]) != 0) {
        fprintf(stderr, "usage: %s TABLE time|once nog_sample|nog_command|cpd_step\n", argv[0]);
        return 2;
    }
    if (strcmp(argv[3], "nog_sample") == 0) {
        fn = bench_nog_sample_once;
    } else if (strcmp(argv[3], "nog_command") == 0) {
        fn = bench_nog_command_once;
    } else if (strcmp(argv[3], "cpd_step") == 0) {
        fn = bench_cpd_step_once;
    } else {
        return 2;
    }
    if (strcmp(argv[2], "once") == 0) {
        return fn();
    }
    return bench_time_case(fn, 200000L, argv[3]);
}
