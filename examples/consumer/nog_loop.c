/* nog_loop.c -- VTD-NOG (ogk/nog.h) flown on a gain table made here with the public table layout
 * (ogk/table.h, ogk/crc32.h): a straight-line nominal of t_f* = 100 s with a constant thrust angle,
 * whose flight-time row maps a transverse-velocity error to a flight-time correction (2 s per m/s).
 * The vehicle flies the nominal stretched to 103 s, 1.5 m/s fast all along, and its navigation errs
 * by 1 mm/s on v_t, alternately up and down from sample to sample: every sample must predict the
 * cut-off at 103 s (within the 2 ms that error moves it) and the engine must go off there.
 *
 * The law samples the nominal at its own phase tau = tau_k + dt / t_f, with the t_f it last
 * predicted, so a t_f off by d puts the nominal it compares with off along the nominal's tangent
 * (x*' dtau, 2e6 m of r and 2000 m/s of v_t per unit tau). A flight-time row with a gain on v_t
 * alone reads that displacement as a velocity error: 2000 K t / t_f^2 per second of d, a loop gain
 * above one after the first three seconds (39 at the end), whose fixed point only exact navigation
 * held (in float the rounding of v_t, in double a single 1 mm/s error, carried the prediction 5 s
 * off). The row is therefore made blind to the tangent, as a neighbouring-optimal gain is to a
 * displacement the law's own clock accounts for: K_TF_R on r cancels K_TF_VT along x*'
 * (K_TF_R 2e6 + K_TF_VT 2000 = 0), and a phase error no longer feeds back into t_f. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include <ogk/crc32.h>
#include <ogk/nog.h>
#include <ogk/table.h>

#include "consumer.h"

#define GRID 5u
#define N_VALUES (GRID * (1u + OGK_NOG_ENTRY_LEN))
#define ELEM_BYTES ((uint32_t)sizeof(ogk_real_t)) /* the table's element: the kernel's real type */
#define TABLE_BYTES (OGK_TABLE_HEADER_SIZE + (ELEM_BYTES * N_VALUES))
#define TF_STAR 100.0 /* [s] */
#define ALPHA0 0.3    /* [rad] nominal thrust angle */
#define K_TF_VT 2.0   /* [s per m/s] dt_f = K_TF_VT dv_t */
#define DV_T 1.5      /* [m/s] the vehicle's transverse-velocity error */
#define K_TF_R (-K_TF_VT * 2000.0 / 2.0e6) /* [s/m] the flight-time row blind to the nominal's tangent */
#define NAV_ERR_VT 1.0e-3 /* [m/s] the navigation's error on v_t, alternating in sign from sample to sample */

static const double x0[OGK_NOG_NX] = {7.0e6, 0.0, 0.0, 10.0, 9000.0, 0.0, 0.0};
static const double x_rate[OGK_NOG_NX] = {2.0e6, 0.5, 0.0, -5.0, 2000.0, 0.0, TF_STAR}; /* d/dtau */

/* 8-byte aligned, as the in-place view of a payload needs */
static union {
    double align;
    uint8_t bytes[TABLE_BYTES];
} image;
static ogk_nog_table_view_t view;
static ogk_nog_table_t table; /* the decoded copy, where the target cannot read the image in place */
static ogk_nog_t nog;

static void put_le(uint8_t *p, uint64_t v, unsigned n)
{
    unsigned i;
    for (i = 0u; i < n; ++i) {
        p[i] = (uint8_t)((v >> (8u * i)) & 0xFFu);
    }
}

/* A value of the table, written on the ground in double, stored in the element type the kernel reads
 * (OGK_TABLE_REAL: F64 in the double build, F32 in the float build). */
static void put_real(uint8_t *p, double d)
{
#if OGK_REAL_SINGLE
    const float f = (float)d;
    uint32_t bits;
    (void)memcpy(&bits, &f, sizeof bits);
    put_le(p, bits, 4u);
#else
    uint64_t bits;
    (void)memcpy(&bits, &d, sizeof bits);
    put_le(p, bits, 8u);
#endif
}

/* The table file of ogk/table.h: header, grid, one row of OGK_NOG_ENTRY_LEN values per node, CRCs. */
static void make_table(void)
{
    uint8_t *b = image.bytes;
    uint32_t crc = 0u;
    size_t k;
    size_t i;
    (void)memset(b, 0, sizeof image.bytes);
    (void)memcpy(b, "OGKT", 4u);
    put_le(b + 4, OGK_TABLE_VERSION, 2u);
    put_le(b + 6, OGK_TABLE_REAL, 2u);
    put_le(b + 8, OGK_NOG_TABLE_KIND, 4u);
    put_le(b + 12, 1u, 2u);
    put_le(b + 16, OGK_NOG_ENTRY_LEN, 4u);
    put_le(b + 32, GRID, 4u);
    put_le(b + 36, ELEM_BYTES * N_VALUES, 4u);
    for (k = 0u; k < GRID; ++k) {
        double row[OGK_NOG_ENTRY_LEN];
        const double tau = (double)k / (double)(GRID - 1u);
        (void)memset(row, 0, sizeof row);
        for (i = 0u; i < OGK_NOG_NX; ++i) {
            row[OGK_NOG_OFF_X + i] = x0[i] + (tau * x_rate[i]);
            row[OGK_NOG_OFF_XDOT + i] = x_rate[i];
        }
        row[OGK_NOG_OFF_LAM + 3u] = -sin(ALPHA0); /* thrust along -lambda_v */
        row[OGK_NOG_OFF_LAM + 4u] = -cos(ALPHA0);
        if (k + 1u < GRID) { /* no gains at tau = 1 */
            row[OGK_NOG_OFF_GAIN + (7u * 7u) + 4u] = K_TF_VT;
            row[OGK_NOG_OFF_GAIN + (7u * 7u) + 0u] = K_TF_R;
        }
        put_real(b + OGK_TABLE_HEADER_SIZE + (ELEM_BYTES * k), tau);
        for (i = 0u; i < OGK_NOG_ENTRY_LEN; ++i) {
            put_real(b + OGK_TABLE_HEADER_SIZE + (ELEM_BYTES * (GRID + (k * OGK_NOG_ENTRY_LEN) + i)), row[i]);
        }
    }
    (void)ogk_crc32_update(&crc, b + OGK_TABLE_HEADER_SIZE, ELEM_BYTES * N_VALUES);
    put_le(b + 40, crc, 4u);
    crc = 0u;
    (void)ogk_crc32_update(&crc, b, 44u);
    put_le(b + 44, crc, 4u);
}

/* The vehicle: on the nominal stretched to 103 s, DV_T fast (the navigation's double, handed over). */
static ogk_nav_state_t nav_at(ogk_real_t t, double nav_err_vt)
{
    const double tau = (double)t / (TF_STAR + (K_TF_VT * DV_T));
    ogk_nav_state_t nav;
    nav.t_s = t;
    nav.r_m = (ogk_real_t)(x0[0] + (tau * x_rate[0]));
    nav.xi_rad = (ogk_real_t)(x0[1] + (tau * x_rate[1]));
    nav.phi_rad = 0.0;
    nav.v_r_mps = (ogk_real_t)(x0[3] + (tau * x_rate[3]));
    nav.v_t_mps = (ogk_real_t)(x0[4] + (tau * x_rate[4]) + DV_T + nav_err_vt);
    nav.v_n_mps = 0.0;
    return nav;
}

int fly_nog(void)
{
    ogk_nog_config_t cfg;
    ogk_nog_sample_t s;
    ogk_thrust_cmd_t cmd;
    ogk_status st;
    char detail[160];
    double worst_cutoff = 0.0; /* [s] largest distance of a predicted cut-off from 103 s */
    ogk_real_t t_off = -1.0;   /* [s] first tick with the engine off */
    unsigned samples = 0u;
    unsigned n;
    int terminating = 0;
    int ok = 1;
    make_table();
    (void)ogk_nog_config_default(&cfg);
    /* in place where the target stores a double as the file does (x86-64, Cortex-M7), else a copy */
    if (ogk_table_check_in_place() == OGK_OK) {
        st = ogk_nog_table_view(&view, image.bytes, sizeof image.bytes);
        cfg.view = &view;
    } else {
        st = ogk_nog_table_load(&table, image.bytes, sizeof image.bytes);
        cfg.table = &table;
    }
    cfg.sample_interval_s = 2.0;
    cfg.dtf_max_s = 10.0;
    if ((st != OGK_OK) || (ogk_nog_init(&nog, &cfg) != OGK_OK)) {
        return consumer_verdict("nog", 0, "table or init rejected");
    }
    /* commands at 10 Hz; a sample every 2 s until the cut-off falls in the interval (eq. 32) */
    for (n = 0u; (n < 1200u) && (t_off < OGK_R(0.0)); ++n) {
        const ogk_real_t t = (ogk_real_t)n / OGK_R(10.0);
        if (((n % 20u) == 0u) && !terminating) {
            const ogk_nav_state_t nav = nav_at(t, ((samples % 2u) == 0u) ? NAV_ERR_VT : -NAV_ERR_VT);
            ok = ok && (ogk_nog_sample(&nog, &nav, &s) == OGK_OK);
            worst_cutoff = fmax(worst_cutoff, fabs((double)s.t_cutoff_s - 103.0));
            terminating = (s.flags & OGK_NOG_FLAG_TERMINATING) != 0u;
            ++samples;
        }
        ok = ok && (ogk_nog_thrust_cmd(&nog, t, &cmd) == OGK_OK);
        /* float: ALPHA0 from its float sine and cosine (atan2f), a few ulp of 0.3 rad: 8 eps */
        ok = ok && (fabs((double)cmd.alpha_rad - ALPHA0) < CONSUMER_TOL(1e-9, 8.0 * (double)FLT_EPSILON));
        if ((cmd.flags & OGK_THRUST_FLAG_ENGINE_ON) == 0u) {
            t_off = t;
        }
    }
    /* each sample's prediction moves by K_TF_VT NAV_ERR_VT = 2 ms with the navigation's error (float
     * adds the rounding of r, 1 m at 9e6 m, through K_TF_R: about 1 ms); 0.01 s holds both builds,
     * and fails by seconds with a table whose row is not blind to the tangent; the engine goes off at
     * the first tick at or after the cut-off predicted last */
    ok = ok && (worst_cutoff < 0.01) && (t_off >= s.t_cutoff_s) && (t_off < s.t_cutoff_s + OGK_R(0.1));
    (void)snprintf(detail, sizeof detail, "cut-off predicted at 103 s (within %.1e s), engine off at %.1f s, %u samples",
                   worst_cutoff, (double)t_off, samples);
    return consumer_verdict("nog", ok, detail);
}
