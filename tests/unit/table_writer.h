/* table_writer.h -- the unit tests' own writer of the table-file layout
 * documented in ogk/table.h (independent of the ground tool's writer).
 *
 * It writes the element type of the build under test (OGK_TABLE_REAL: F64
 * with 8-byte values in the double build, F32 with 4-byte values in the float
 * one), so that a test's table is the one its kernel reads: tw_header,
 * tw_put_real and tw_seal, with payload offsets in units of TW_REAL_BYTES.
 * tw_to_other converts a sealed table into the other precision's (what the
 * build must refuse); tw_put_f64 writes binary64 bytes whatever the build. */
#ifndef OGK_TEST_TABLE_WRITER_H
#define OGK_TEST_TABLE_WRITER_H

#include <stdint.h>
#include <string.h>

#include "ogk/crc32.h"
#include "ogk/table.h"

/* Bytes of one payload value of this build's tables, and of the other's. */
#if OGK_REAL_SINGLE
#define TW_REAL_BYTES 4u
#define TW_OTHER_BYTES 8u
#define TW_OTHER_TYPE OGK_TABLE_F64
#else
#define TW_REAL_BYTES 8u
#define TW_OTHER_BYTES 4u
#define TW_OTHER_TYPE OGK_TABLE_F32
#endif

static void tw_put_u16(uint8_t *p, uint16_t v)
{
    p[0] = (uint8_t)(v & 0xFFu);
    p[1] = (uint8_t)(v >> 8);
}

static void tw_put_u32(uint8_t *p, uint32_t v)
{
    unsigned i;
    for (i = 0u; i < 4u; ++i) {
        p[i] = (uint8_t)((v >> (8u * i)) & 0xFFu);
    }
}

static void tw_put_f64(uint8_t *p, double d)
{
    uint64_t bits;
    unsigned i;
    memcpy(&bits, &d, sizeof bits);
    for (i = 0u; i < 8u; ++i) {
        p[i] = (uint8_t)((bits >> (8u * i)) & 0xFFu);
    }
}

/* One payload value in this build's element type (little-endian). */
static inline void tw_put_real(uint8_t *p, double d)
{
#if OGK_REAL_SINGLE
    const float f = (float)d;
    uint32_t bits;
    memcpy(&bits, &f, sizeof bits);
    tw_put_u32(p, bits);
#else
    tw_put_f64(p, d);
#endif
}

/* Recomputes both CRCs of a table of n_values payload values of this build. */
static void tw_seal(uint8_t *buf, uint32_t n_values)
{
    uint32_t crc = 0u;
    (void)ogk_crc32_update(&crc, buf + OGK_TABLE_HEADER_SIZE, TW_REAL_BYTES * (size_t)n_values);
    tw_put_u32(buf + 40, crc);
    crc = 0u;
    (void)ogk_crc32_update(&crc, buf, 44u);
    tw_put_u32(buf + 44, crc);
}

/* Header of a version-1 table of this build's element type; the payload is
 * written by the caller, then tw_seal. dims has ndims entries. */
static void tw_header(uint8_t *buf, uint32_t kind, uint16_t ndims, const uint32_t *dims,
                      uint32_t grid)
{
    uint32_t entry_len = 1u;
    uint16_t d;
    memset(buf, 0, OGK_TABLE_HEADER_SIZE);
    memcpy(buf, "OGKT", 4u);
    tw_put_u16(buf + 4, 1u);
    tw_put_u16(buf + 6, (uint16_t)OGK_TABLE_REAL);
    tw_put_u32(buf + 8, kind);
    tw_put_u16(buf + 12, ndims);
    for (d = 0u; d < ndims; ++d) {
        tw_put_u32(buf + 16 + 4u * d, dims[d]);
        entry_len *= dims[d];
    }
    tw_put_u32(buf + 32, grid);
    tw_put_u32(buf + 36, TW_REAL_BYTES * grid * (1u + entry_len));
}

/* The F32 (IEEE-754 binary32, little-endian) copy of the sealed F64 table src of
 * n_values payload values into dst (OGK_TABLE_HEADER_SIZE + 4 n_values bytes):
 * the same header with element type OGK_TABLE_F32 and the payload size of
 * 4-byte values, each value rounded to float, both CRCs recomputed. What a
 * ground tool writes for a kernel built with OGK_REAL_SINGLE=1. static inline:
 * not every test that includes this header converts a table. */
static inline void tw_to_f32(const uint8_t *src, uint8_t *dst, uint32_t n_values)
{
    uint32_t k;
    uint32_t crc = 0u;
    memcpy(dst, src, OGK_TABLE_HEADER_SIZE);
    tw_put_u16(dst + 6, (uint16_t)OGK_TABLE_F32);
    tw_put_u32(dst + 36, 4u * n_values);
    for (k = 0u; k < n_values; ++k) {
        const uint8_t *p = src + OGK_TABLE_HEADER_SIZE + 8u * (size_t)k;
        uint64_t bits = 0u;
        double d;
        float f;
        uint32_t fbits;
        unsigned i;
        for (i = 0u; i < 8u; ++i) {
            bits |= (uint64_t)p[i] << (8u * i);
        }
        memcpy(&d, &bits, sizeof d);
        f = (float)d;
        memcpy(&fbits, &f, sizeof fbits);
        tw_put_u32(dst + OGK_TABLE_HEADER_SIZE + 4u * (size_t)k, fbits);
    }
    (void)ogk_crc32_update(&crc, dst + OGK_TABLE_HEADER_SIZE, 4u * (size_t)n_values);
    tw_put_u32(dst + 40, crc);
    crc = 0u;
    (void)ogk_crc32_update(&crc, dst, 44u);
    tw_put_u32(dst + 44, crc);
}

/* The F64 copy of the sealed F32 table src (n_values payload values) into
 * dst (OGK_TABLE_HEADER_SIZE + 8 n_values bytes): what a double kernel reads,
 * which the float build refuses. */
static inline void tw_to_f64(const uint8_t *src, uint8_t *dst, uint32_t n_values)
{
    uint32_t k;
    uint32_t crc = 0u;
    memcpy(dst, src, OGK_TABLE_HEADER_SIZE);
    tw_put_u16(dst + 6, (uint16_t)OGK_TABLE_F64);
    tw_put_u32(dst + 36, 8u * n_values);
    for (k = 0u; k < n_values; ++k) {
        const uint8_t *p = src + OGK_TABLE_HEADER_SIZE + 4u * (size_t)k;
        uint32_t bits = 0u;
        float f;
        unsigned i;
        for (i = 0u; i < 4u; ++i) {
            bits |= (uint32_t)p[i] << (8u * i);
        }
        memcpy(&f, &bits, sizeof f);
        tw_put_f64(dst + OGK_TABLE_HEADER_SIZE + 8u * (size_t)k, (double)f);
    }
    (void)ogk_crc32_update(&crc, dst + OGK_TABLE_HEADER_SIZE, 8u * (size_t)n_values);
    tw_put_u32(dst + 40, crc);
    crc = 0u;
    (void)ogk_crc32_update(&crc, dst, 44u);
    tw_put_u32(dst + 44, crc);
}

/* The other precision's copy of this build's sealed table (TW_OTHER_BYTES per
 * value): the table this build must refuse. */
#if OGK_REAL_SINGLE
#define tw_to_other tw_to_f64
#else
#define tw_to_other tw_to_f32
#endif

#endif /* OGK_TEST_TABLE_WRITER_H */
