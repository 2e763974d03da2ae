/* fuzz_nog_step.c -- the VTD-NOG step entry points (ogk_nog_sample, ogk_nog_thrust_cmd,
 * ogk_nog_tau_at, ogk_nog_reset) with arbitrary navigation and time bytes on a valid small table
 * (the 5-node synthetic table of test_nog.c), bound as a RAM table or an in-place view.
 * Input: one byte of set-up (bit 0: view instead of table; bits 1-2: tau_freeze / du_max), then
 * operations, each one op byte and its operands:
 *   0: sample with 7 raw doubles (t, r, xi, phi, v_r, v_t, v_n)
 *   1: sample near the nominal: tau from one byte, 7 one-byte perturbations
 *   2: command at a raw double time           3: command at the last time + one byte
 *   4: tau_at a raw double time               5: reset
 *   6: reload the table (every later call must answer OGK_E_TABLE_STALE until re-init)
 *   7: re-init
 * Oracle (nog.h): every output is finite whatever the status; a rejected sample is flagged SAFE;
 * a stale context answers OGK_E_TABLE_STALE; tau_at gives a tau in [0, 1] on OGK_OK. */
#include "fuzz_common.h"

static union {
    double align;
    uint8_t b[FZ_TABLE_BYTES];
} tbuf;
static ogk_nog_table_t table;
static ogk_nog_table_view_t view;
static ogk_nog_t nog;
static int built;

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

static void check_sample(const ogk_nog_sample_t *s, ogk_status st)
{
    size_t i;
    FZ_CHECK(isfinite(s->tau_k) && isfinite(s->tau_next) && isfinite(s->t_f_s) &&
             isfinite(s->dt_f_s) && isfinite(s->t_cutoff_s) && isfinite(s->alpha_rad) &&
             isfinite(s->beta_rad));
    for (i = 0u; i < OGK_NOG_NX; ++i) {
        FZ_CHECK(isfinite(s->dx[i]));
    }
    FZ_CHECK(st == OGK_OK || (s->flags & OGK_NOG_FLAG_SAFE) != 0u);
}

static void check_cmd(const ogk_thrust_cmd_t *c)
{
    FZ_CHECK(isfinite(c->alpha_rad) && isfinite(c->beta_rad));
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    fz_reader_t r;
    ogk_nog_config_t cfg;
    uint8_t setup;
    int stale = 0;
    int ops = 0;
    double t_last = 0.0;
    if (!built) { /* once (the 268 KiB RAM table is not reloaded per input) */
        fz_build_nog_table(tbuf.b);
        if (ogk_nog_table_load(&table, tbuf.b, FZ_TABLE_BYTES) != OGK_OK ||
            ogk_nog_table_view(&view, tbuf.b, FZ_TABLE_BYTES) != OGK_OK) {
            abort();
        }
        built = 1;
    }
    r.p = data;
    r.n = size;
    setup = fz_u8(&r);
    (void)ogk_nog_config_default(&cfg);
    if ((setup & 1u) != 0u) {
        cfg.view = &view;
    } else {
        cfg.table = &table;
    }
    cfg.sample_interval_s = 2.0;
    cfg.dtf_max_s = 10.0;
    cfg.du_max_rad = ((setup & 2u) != 0u) ? 0.05 : 0.5;
    cfg.tau_freeze = ((setup & 4u) != 0u) ? 0.1 : 0.0;
    FZ_CHECK(ogk_nog_init(&nog, &cfg) == OGK_OK);
    while (r.n > 0u && ops < 64) {
        const uint8_t op = (uint8_t)(fz_u8(&r) & 7u);
        ogk_nog_sample_t s;
        ogk_thrust_cmd_t c;
        ogk_nav_state_t nav;
        ogk_status st;
        double t;
        ++ops;
        switch (op) {
        case 0:
        case 1:
            if (op == 0u) {
                nav.t_s = fz_f64(&r);
                nav.r_m = fz_f64(&r);
                nav.xi_rad = fz_f64(&r);
                nav.phi_rad = fz_f64(&r);
                nav.v_r_mps = fz_f64(&r);
                nav.v_t_mps = fz_f64(&r);
                nav.v_n_mps = fz_f64(&r);
            } else {
                double x[7];
                const double tau = (double)fz_u8(&r) / 200.0;
                fz_nominal_state(tau, x);
                nav.t_s = tau * FZ_TF_STAR + fz_small(&r, 5.0);
                nav.r_m = x[0] + fz_small(&r, 1.0e4);
                nav.xi_rad = x[1] + fz_small(&r, 1.0e-2);
                nav.phi_rad = x[2] + fz_small(&r, 1.0e-2);
                nav.v_r_mps = x[3] + fz_small(&r, 50.0);
                nav.v_t_mps = x[4] + fz_small(&r, 50.0);
                nav.v_n_mps = x[5] + fz_small(&r, 50.0);
            }
            memset(&s, 0, sizeof s);
            st = ogk_nog_sample(&nog, &nav, &s);
            if (stale) {
                FZ_CHECK(st == OGK_E_TABLE_STALE);
            }
            check_sample(&s, st);
            if (st == OGK_OK) {
                t_last = nav.t_s;
            }
            break;
        case 2:
        case 3:
            t = (op == 2u) ? fz_f64(&r) : t_last + (double)fz_u8(&r);
            memset(&c, 0, sizeof c);
            st = ogk_nog_thrust_cmd(&nog, t, &c);
            if (stale) {
                FZ_CHECK(st == OGK_E_TABLE_STALE);
            }
            check_cmd(&c);
            break;
        case 4: {
            double tau = -1.0;
            st = ogk_nog_tau_at(&nog, fz_f64(&r), &tau);
            if (stale) {
                FZ_CHECK(st == OGK_E_TABLE_STALE);
            }
            if (st == OGK_OK) {
                FZ_CHECK(tau >= 0.0 && tau <= 1.0);
            }
            break;
        }
        case 5:
            st = ogk_nog_reset(&nog);
            FZ_CHECK(stale ? st == OGK_E_TABLE_STALE : st == OGK_OK);
            if (st == OGK_OK) {
                t_last = 0.0;
            }
            break;
        case 6:
            if (stale) { /* one reload per input is enough (a reload costs a full validation) */
                break;
            }
            if ((setup & 1u) != 0u) {
                FZ_CHECK(ogk_nog_table_view(&view, tbuf.b, FZ_TABLE_BYTES) == OGK_OK);
            } else {
                FZ_CHECK(ogk_nog_table_load(&table, tbuf.b, FZ_TABLE_BYTES) == OGK_OK);
            }
            stale = 1;
            break;
        default:
            FZ_CHECK(ogk_nog_init(&nog, &cfg) == OGK_OK);
            stale = 0;
            t_last = 0.0;
            break;
        }
    }
    return 0;
}
