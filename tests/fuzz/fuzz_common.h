/* fuzz_common.h -- shared pieces of the libFuzzer harnesses (tests/fuzz, make fuzz / fuzz-short,
 * tests/gates/gates.mk): a small valid NOG table (the synthetic one of tests/unit/nog/test_nog.c),
 * re-sealing of fuzzed table bytes (so that mutations get past the CRCs and reach the field
 * checks), a byte reader, and the oracle's abort. */
#ifndef OGK_FUZZ_COMMON_H
#define OGK_FUZZ_COMMON_H

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "ogk/crc32.h"
#include "ogk/nog.h"
#include "ogk/table.h"
#include "table_writer.h"

#define FZ_GRID 5u
#define FZ_TF_STAR 100.0
#define FZ_N_VALUES (FZ_GRID * (1u + OGK_NOG_ENTRY_LEN))
#define FZ_TABLE_BYTES (OGK_TABLE_HEADER_SIZE + 8u * FZ_N_VALUES)
/* Largest fuzzed table (bytes after the mode byte). */
#define FZ_MAX_LEN 16384u

/* An oracle violation: print it and abort (libFuzzer records the input as a crash). */
#define FZ_CHECK(cond)                                                                    \
    do {                                                                                  \
        if (!(cond)) {                                                                    \
            (void)fprintf(stderr, "fuzz oracle failed: %s (%s:%d)\n", #cond, __FILE__,    \
                          __LINE__);                                                      \
            abort();                                                                      \
        }                                                                                 \
    } while (0)

static const double fz_x0[7] = {7.0e6, 0.0, 0.0, 10.0, 9000.0, 0.0, 0.0};
static const double fz_x_rate[7] = {2.0e6, 0.5, 0.0, -5.0, 2000.0, 0.0, FZ_TF_STAR};

static void fz_nominal_state(double tau, double *x)
{
    size_t i;
    for (i = 0u; i < 7u; ++i) {
        x[i] = fz_x0[i] + tau * fz_x_rate[i];
    }
}

/* The 5-node table of test_nog.c: straight-line nominal, constant costate, sparse gains. */
static void fz_build_nog_table(uint8_t *buf)
{
    static const double tau_grid[FZ_GRID] = {0.0, 0.25, 0.5, 0.75, 1.0};
    const uint32_t dims[1] = {OGK_NOG_ENTRY_LEN};
    size_t k, i;
    memset(buf, 0, FZ_TABLE_BYTES);
    tw_header(buf, OGK_NOG_TABLE_KIND, 1u, dims, FZ_GRID);
    for (k = 0u; k < FZ_GRID; ++k) {
        double row[OGK_NOG_ENTRY_LEN];
        memset(row, 0, sizeof row);
        fz_nominal_state(tau_grid[k], &row[OGK_NOG_OFF_X]);
        for (i = 0u; i < 7u; ++i) {
            row[OGK_NOG_OFF_XDOT + i] = fz_x_rate[i];
        }
        row[OGK_NOG_OFF_LAM + 3u] = -sin(0.3);
        row[OGK_NOG_OFF_LAM + 4u] = -cos(0.3);
        if (k + 1u < FZ_GRID) {
            row[OGK_NOG_OFF_GAIN + 5u * 7u + 5u] = 0.01;
            row[OGK_NOG_OFF_GAIN + 3u * 7u + 6u] = 0.05;
            row[OGK_NOG_OFF_GAIN + 7u * 7u + 4u] = 2.0;
            row[OGK_NOG_OFF_NRATE + 5u * 7u + 5u] = 0.02;
        }
        tw_put_f64(buf + OGK_TABLE_HEADER_SIZE + 8u * k, tau_grid[k]);
        for (i = 0u; i < OGK_NOG_ENTRY_LEN; ++i) {
            tw_put_f64(buf + OGK_TABLE_HEADER_SIZE + 8u * (FZ_GRID + k * OGK_NOG_ENTRY_LEN + i),
                       row[i]);
        }
    }
    tw_seal(buf, FZ_N_VALUES);
}

static uint32_t fz_get_u32(const uint8_t *p)
{
    return (uint32_t)p[0] | ((uint32_t)p[1] << 8) | ((uint32_t)p[2] << 16) | ((uint32_t)p[3] << 24);
}

/* Recomputes both CRCs of fuzzed table bytes: the payload CRC over what the header's payload
 * size claims, as far as the bytes reach. */
static void fz_reseal(uint8_t *buf, size_t len)
{
    uint32_t crc = 0u;
    size_t payload;
    if (len < OGK_TABLE_HEADER_SIZE) {
        return;
    }
    payload = fz_get_u32(buf + 36);
    if (payload > len - OGK_TABLE_HEADER_SIZE) {
        payload = len - OGK_TABLE_HEADER_SIZE;
    }
    (void)ogk_crc32_update(&crc, buf + OGK_TABLE_HEADER_SIZE, payload);
    tw_put_u32(buf + 40, crc);
    crc = 0u;
    (void)ogk_crc32_update(&crc, buf, 44u);
    tw_put_u32(buf + 44, crc);
}

/* Byte reader: takes from the input while it lasts, zeros after. */
typedef struct {
    const uint8_t *p;
    size_t n;
} fz_reader_t;

static uint8_t fz_u8(fz_reader_t *r)
{
    uint8_t v = 0u;
    if (r->n > 0u) {
        v = r->p[0];
        r->p++;
        r->n--;
    }
    return v;
}

static double fz_f64(fz_reader_t *r)
{
    uint8_t b[8] = {0};
    double d;
    size_t i;
    for (i = 0u; i < 8u; ++i) {
        b[i] = fz_u8(r);
    }
    memcpy(&d, b, sizeof d);
    return d;
}

/* A small signed value from one byte: (b - 128) / 128 * scale. */
static double fz_small(fz_reader_t *r, double scale)
{
    return ((double)fz_u8(r) - 128.0) / 128.0 * scale;
}

#endif /* OGK_FUZZ_COMMON_H */
