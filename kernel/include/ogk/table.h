/* ogk/table.h -- versioned binary table files (gain tables, nominal profiles).
 *
 * Layout, all integers little-endian, no padding (OGK_TABLE_HEADER_SIZE bytes):
 *   off  size  field
 *     0     4  magic "OGKT"
 *     4     2  format version (OGK_TABLE_VERSION)
 *     6     2  element type: OGK_TABLE_F64 (IEEE-754 binary64, little-endian)
 *              or OGK_TABLE_F32 (IEEE-754 binary32, little-endian)
 *     8     4  table kind (application id, e.g. a NOG gain table)
 *    12     2  number of dimensions of one entry, 1..OGK_TABLE_MAX_DIMS
 *    14     2  reserved, 0
 *    16    16  dims[4] (u32, unused ones 0)
 *    32     4  grid size: number of grid points (entries), >= 1
 *    36     4  payload size in bytes = e * grid * (1 + prod(dims)), e the
 *              element's size (8 for F64, 4 for F32)
 *    40     4  CRC-32 of the payload
 *    44     4  CRC-32 of bytes 0..43 of the header
 *   48 ...     payload: grid[grid size] then entry k (prod(dims) values,
 *              row-major) for k = 0..grid-1
 * The loader validates every field before anything is read from the payload.
 * A kernel reads the element type of its own real type (ogk/real.h): F64 in the
 * double build, F32 in the float build (OGK_REAL_SINGLE=1), and refuses the
 * other with OGK_E_TABLE_TYPE: a table is made for the build that flies it
 * (host/ogk_host/tablefile.py writes either). The decoding readers below work
 * on any target; reading the payload in place as ogk_real_t needs a target
 * that stores one exactly as the file does (ogk_table_check_in_place). */
#ifndef OGK_TABLE_H
#define OGK_TABLE_H

#include <stddef.h>
#include <stdint.h>
#include "ogk/config.h"
#include "ogk/status.h"
#include "ogk/real.h"

#ifdef __cplusplus
extern "C" {
#endif

#define OGK_TABLE_HEADER_SIZE 48u
#define OGK_TABLE_VERSION 1u
#define OGK_TABLE_F64 1u
#define OGK_TABLE_F32 2u

/* The element type this build reads, the one of ogk_real_t. */
#if OGK_REAL_SINGLE
#define OGK_TABLE_REAL OGK_TABLE_F32
#else
#define OGK_TABLE_REAL OGK_TABLE_F64
#endif

/* What the caller expects. A dims entry of 0 accepts any size there;
 * max_grid bounds the grid so the caller's buffers fit. */
typedef struct {
    uint32_t kind;                       /* [-] required table kind */
    uint16_t ndims;                      /* [-] required number of dimensions */
    uint32_t dims[OGK_TABLE_MAX_DIMS];   /* [-] required dims, 0 = any */
    uint32_t min_grid;                   /* [-] smallest acceptable grid size, >= 1 */
    uint32_t max_grid;                   /* [-] largest acceptable grid size */
} ogk_table_spec_t;

/* A validated table inside a caller-owned byte buffer (not copied). */
typedef struct {
    const uint8_t *buf;                  /* start of the table bytes */
    uint32_t kind;                       /* [-] table kind */
    uint16_t ndims;                      /* [-] number of dimensions */
    uint32_t dims[OGK_TABLE_MAX_DIMS];   /* [-] dims of one entry */
    uint32_t grid_size;                  /* [-] number of grid points */
    uint32_t entry_len;                  /* [-] prod(dims): values per entry */
} ogk_table_view_t;

/* Validates buf[0..len-1] against spec (magic, version, element type
 * OGK_TABLE_REAL, kind, dims, grid size, exact length, both CRCs, finite
 * values) and fills view. On
 * failure view is zeroed and the specific OGK_E_TABLE_* code (or
 * OGK_E_NONFINITE) is returned. */
ogk_status ogk_table_open(const uint8_t *buf, size_t len,
                          const ogk_table_spec_t *spec, ogk_table_view_t *view);

/* Copies the grid (grid_size values) into grid_out (capacity entries). */
ogk_status ogk_table_read_grid(const ogk_table_view_t *view, ogk_real_t *grid_out,
                               size_t capacity);

/* Copies all entries (grid_size * entry_len values, entry-major) into
 * data_out (capacity entries). */
ogk_status ogk_table_read_data(const ogk_table_view_t *view, ogk_real_t *data_out,
                               size_t capacity);

/* Reads value `index` (0..entry_len-1) of entry k. */
ogk_status ogk_table_get(const ogk_table_view_t *view, uint32_t k,
                         uint32_t index, ogk_real_t *value);

/* The byte-order probe: pi, whose binary64 bits 0x400921FB54442D18 are eight
 * different bytes, so any reordering of them (big-endian, word-swapped) shows;
 * its binary32 bits 0x40490FDB are four different bytes too (the float build). */
#define OGK_TABLE_ORDER_PROBE OGK_R(3.141592653589793)

/* OGK_OK when bytes[0..7] are OGK_TABLE_ORDER_PROBE in the file's binary64
 * representation (little-endian: 18 2D 44 54 FB 21 09 40),
 * OGK_E_BYTE_ORDER when they are not, OGK_E_NULL. */
ogk_status ogk_table_check_f64_bytes(const uint8_t *bytes);

/* OGK_OK when this target stores an ogk_real_t exactly as the file stores
 * this build's element (OGK_TABLE_REAL: its size and its byte order), so a
 * payload may be read in place as ogk_real_t (ogk_nog_table_view); OGK_E_BYTE_ORDER
 * on a big-endian (SPARC/LEON, PowerPC, MIPS BE) or word-swapped target, where
 * only the decoding readers work (ogk_table_read_*, ogk_table_get,
 * ogk_nog_table_load: they assemble each value from its bytes on any target).
 * Checks the target's own representation of OGK_TABLE_ORDER_PROBE at run time:
 * C99 has no portable byte-order macro. */
ogk_status ogk_table_check_in_place(void);

#ifdef __cplusplus
}
#endif

#endif /* OGK_TABLE_H */
