/* gen_seeds.c -- writes the seed corpus of the fuzz harnesses (make fuzz-seeds; the outputs are
 * committed in tests/fuzz/corpus/<target>/): the valid 5-node NOG table (as is, and re-sealed
 * with a defect), op streams flying it near the nominal, CPD steps near level flight, an MPSP
 * configuration patch, NMPC flights (open loop, replans, commands), BLT solves (fuzz_blt_solve.c: a
 * single burn, burn-coast-burn with a free node forward and with the last arc backward, raw transfers
 * with a NaN and into the secondary). Usage: gen_seeds DIR (DIR/<target>/ must exist). */
#include "fuzz_common.h"

#include <stddef.h>

#include "ogk/mpsp.h"

static uint8_t table[FZ_TABLE_BYTES];

/* Appends a double's bytes (the harness reads them back with memcpy on the same host). */
static size_t put_f64(uint8_t *p, size_t n, double v)
{
    (void)memcpy(&p[n], &v, sizeof v);
    return n + sizeof v;
}

static void put(const char *dir, const char *target, const char *name, const uint8_t *mode,
                const uint8_t *p, size_t n)
{
    char path[512];
    FILE *f;
    (void)snprintf(path, sizeof path, "%s/%s/%s", dir, target, name);
    f = fopen(path, "wb");
    if (f == NULL) {
        perror(path);
        exit(1);
    }
    if (mode != NULL) {
        (void)fwrite(mode, 1u, 1u, f);
    }
    (void)fwrite(p, 1u, n, f);
    (void)fclose(f);
}

int main(int argc, char **argv)
{
    uint8_t m0 = 0u;
    uint8_t m1 = 1u;
    uint8_t m3 = 3u;
    uint8_t ops[256];
    size_t n = 0u;
    size_t k;
    if (argc != 2) {
        (void)fprintf(stderr, "usage: gen_seeds DIR\n");
        return 2;
    }
    fz_build_nog_table(table);
    put(argv[1], "table", "nog5", &m0, table, sizeof table);
    put(argv[1], "table", "nog5_own_spec", &m3, table, sizeof table);
    put(argv[1], "nog_table", "nog5", &m0, table, sizeof table);
    /* grid not ending at 1, re-sealed by the harness (mode 1): the field check must catch it */
    tw_put_f64(table + OGK_TABLE_HEADER_SIZE + 8u * (FZ_GRID - 1u), 0.9);
    put(argv[1], "nog_table", "nog5_grid_end", &m1, table, sizeof table);
    fz_build_nog_table(table);
    put(argv[1], "table", "header_only", &m1, table, OGK_TABLE_HEADER_SIZE);

    /* NOG: samples near the nominal every 2 s, commands between, a reload, a re-init. */
    ops[n++] = 0u; /* set-up: RAM table */
    for (k = 0u; k < 8u; ++k) {
        size_t i;
        ops[n++] = 1u;
        ops[n++] = (uint8_t)(4u * k); /* tau = 0.02 k: t = 2 k s */
        for (i = 0u; i < 7u; ++i) {
            ops[n++] = (uint8_t)(128u + ((k * 7u + i) % 5u)); /* small displacements */
        }
        ops[n++] = 3u;
        ops[n++] = 1u;
    }
    ops[n++] = 4u;
    for (k = 0u; k < 8u; ++k) {
        ops[n++] = 0u;
    }
    ops[n++] = 6u;
    ops[n++] = 3u;
    ops[n++] = 0u;
    ops[n++] = 7u;
    put(argv[1], "nog_step", "fly_near_nominal", NULL, ops, n);
    ops[0] = 1u; /* view */
    put(argv[1], "nog_step", "fly_near_nominal_view", NULL, ops, n);

    /* CPD: level flight with small errors, feed-forward on. */
    n = 0u;
    ops[n++] = 1u;
    for (k = 0u; k < 16u; ++k) {
        size_t i;
        ops[n++] = 1u; /* odd: near level flight */
        for (i = 0u; i < 10u; ++i) {
            ops[n++] = (uint8_t)(128u + ((k + 3u * i) % 7u) - 3u);
        }
    }
    put(argv[1], "cpd_step", "level_flight_ff", NULL, ops, n);
    ops[0] = 2u; /* Euler pointing */
    put(argv[1], "cpd_step", "level_flight_euler", NULL, ops, n);

    /* MPSP: no patch (valid), and n_seg_nom left to the input (0: init propagates). */
    {
        static const uint8_t none[1] = {0u};
        uint8_t patch[11] = {0u};
        const size_t off = offsetof(ogk_mpsp_config_t, n_seg_nom);
        put(argv[1], "mpsp_init", "valid", NULL, none, sizeof none);
        patch[0] = 1u;
        patch[1] = (uint8_t)(off & 0xFFu);
        patch[2] = (uint8_t)(off >> 8);
        put(argv[1], "mpsp_init", "count_segments", NULL, patch, sizeof patch);
        /* h_max (a double) patched to 0: rejected */
        patch[0] = 0u;
        patch[1] = (uint8_t)(offsetof(ogk_mpsp_config_t, h_max) & 0xFFu);
        patch[2] = (uint8_t)(offsetof(ogk_mpsp_config_t, h_max) >> 8);
        put(argv[1], "mpsp_init", "h_max_zero", NULL, patch, sizeof patch);
    }

    /* NMPC (fuzz_nmpc_step.c): the unperturbed guess of N = 4 nodes, a solve, then replans at the
     * next node with commands between; once with the constant engine (SNNS, doubling test with
     * threshold 0), once throttled, minimum fuel, CNCN, two softened bodies and the sweep bound. */
    {
        static const uint8_t modes[2][2] = {
            { 0x00u, 0x03u | 0x04u | 0x18u | 0x40u }, /* N 4, rk4 2, max_iter 4, doubling N <= 1 */
            { 0x01u | 0x02u | 0x04u | 0x30u | 0x40u, 0x03u | 0x04u | 0x18u },
        };
        static const char *const names[2] = { "snns_open_loop_replans", "cncn_throttled_fuel_bodies" };
        size_t s;
        for (s = 0u; s < 2u; ++s) {
            const int throttled = (modes[s][0] & 0x01u) != 0u;
            size_t i;
            n = 0u;
            ops[n++] = modes[s][0];
            ops[n++] = modes[s][1];
            ops[n++] = 128u; /* horizon scale 1 */
            for (k = 0u; k <= 4u; ++k) {
                ops[n++] = 128u; /* r as guessed */
                ops[n++] = 128u; /* alpha = 135 deg */
                if (throttled) {
                    ops[n++] = 200u;
                }
            }
            for (k = 0u; k < 3u; ++k) {
                ops[n++] = (k == 0u) ? 0u : 1u; /* solve, then replans */
                for (i = 0u; i < 6u; ++i) {
                    ops[n++] = 128u; /* at the next node, on the plan */
                }
                ops[n++] = 2u; /* command inside the plan */
                ops[n++] = 30u;
            }
            ops[n++] = 2u + 128u; /* command at a raw time: +Inf */
            for (i = 0u; i < 6u; ++i) {
                ops[n++] = 0u;
            }
            ops[n++] = 0xF0u;
            ops[n++] = 0x7Fu;
            put(argv[1], "nmpc_step", names[s], NULL, ops, n);
        }
    }

    /* BLT (fuzz_blt_solve.c): structured transfers, small displacements (bytes near 128), two
     * iterations, tol 1e-6, step 0.03 TU; commands at 10, 50, 90 and 120 % of the flight. */
    {
        static const uint8_t modes[3][3] = {
            { 0x00u, 0xABu, 0x0Cu },               /* single burn, NRPC, central, Moshup-like */
            { 0x01u | 0x02u | 0x08u | 0x40u, 0xABu, 0x0Cu }, /* b-c-b, free node, LM, variational, x and vy free */
            { 0x02u | 0x0Cu | 0x20u, 0xABu, 0x0Cu }, /* b-c-b, last arc backward, NRPC, variational, point mass */
        };
        static const char *const names[3] = { "single_burn_nrpc", "bcb_node_lm_variational",
                                              "bcb_backward_point_mass" };
        size_t s;
        for (s = 0u; s < 3u; ++s) {
            const size_t nseg = (s == 0u) ? 1u : 3u;
            size_t i;
            n = 0u;
            ops[n++] = modes[s][0];
            ops[n++] = modes[s][1];
            ops[n++] = modes[s][2];
            ops[n++] = 0u; /* structured transfer */
            for (i = 0u; i < 6u; ++i) {
                ops[n++] = (uint8_t)(126u + (i % 5u)); /* x0 */
            }
            ops[n++] = 255u; /* mass0 1 */
            for (i = 0u; i < 6u; ++i) {
                ops[n++] = (uint8_t)(129u - (i % 3u)); /* xf */
            }
            for (k = 0u; k < nseg; ++k) {
                for (i = 0u; i < 7u; ++i) {
                    ops[n++] = (uint8_t)(124u + ((3u * i + k) % 9u)); /* A, B, T */
                }
            }
            ops[n++] = 10u;
            ops[n++] = 50u;
            ops[n++] = 90u;
            ops[n++] = 120u;
            put(argv[1], "blt_solve", names[s], NULL, ops, n);
        }
    }
    /* BLT raw: the model's doubles given (valid), a single burn with a NaN in xf, then one into the
     * secondary (guess impact), a command at a raw +Inf time */
    {
        static const double x0_ok[6] = { 0.3, 0.8, 0.05, -0.3, 0.2, 0.01 };
        static const double x0_hit[6] = { 0.5956, 0.0, 0.0, 1.0, 0.0, 0.0 };
        static const double p[7] = { 0.6, 0.5, 0.1, -0.4, 0.8, 0.3, 0.3 };
        static const char *const names[2] = { "raw_nan_target", "raw_into_secondary" };
        size_t s;
        for (s = 0u; s < 2u; ++s) {
            const double *x0 = (s == 0u) ? x0_ok : x0_hit;
            size_t i;
            n = 0u;
            ops[n++] = 0x00u;
            ops[n++] = 0x00u;
            ops[n++] = 0x20u | 0x0Cu; /* raw model doubles follow */
            n = put_f64(ops, n, 0.0544);
            n = put_f64(ops, n, -0.09);
            n = put_f64(ops, n, 0.02);
            n = put_f64(ops, n, 0.01);
            ops[n++] = 0xFFu; /* raw transfer */
            n = put_f64(ops, n, 0.25); /* t0 */
            n = put_f64(ops, n, 0.9);  /* mass0 */
            for (i = 0u; i < 6u; ++i) {
                n = put_f64(ops, n, x0[i]);
                n = put_f64(ops, n, ((s == 0u) && (i == 2u)) ? (double)NAN : 1.0);
            }
            for (i = 0u; i < 7u; ++i) {
                n = put_f64(ops, n, (s == 1u) ? ((i == 0u) ? 1.0 : ((i == 6u) ? 0.28 : 0.0)) : p[i]);
            }
            for (i = 0u; i < 6u; ++i) {
                n = put_f64(ops, n, 0.0); /* node (unused) */
            }
            ops[n++] = 200u;
            n = put_f64(ops, n, (double)INFINITY);
            put(argv[1], "blt_solve", names[s], NULL, ops, n);
        }
    }
    return 0;
}
