/* ogk/table.h -- versioned binary table files (gain tables, nominal profiles).
 *
 * Layout, all integers little-endian, no padding (OGK_TABLE_HEADER_SIZE bytes):
 *   off  size  field
 *     0     4  magic "OGKT"
 *     4     2  format version (OGK_TABLE_VERSION)
 *     6     2  element type (OGK_TABLE_F64 = IEEE-754 binary64, little-endian)
 *     8     4  table kind (application id, e.g. a NOG gain table)
 *    12     2  number of dimensions of one entry, 1..OGK_TABLE_MAX_DIMS
 *    14     2  reserved, 0
 *    16    16  dims[4] (u32, unused ones 0)
 *    32     4  grid size: number of grid points (entries), >= 1
 *    36     4  payload size in bytes = 8 * grid * (1 + prod(dims))
 *    40     4  CRC-32 of the payload
 *    44     4  CRC-32 of bytes 0..43 of the header
 *   48 ...     payload: grid[grid size] then entry k (prod(dims) values,
 *              row-major) for k = 0..grid-1
 * The loader validates every field before anything is read from the payload. */
#ifndef OGK_TABLE_H
#define OGK_TABLE_H

#include <stddef.h>
#include <stdint.h>
#include "ogk/config.h"
#include "ogk/status.h"

#ifdef __cplusplus
extern "C" {
#endif

#define OGK_TABLE_HEADER_SIZE 48u
#define OGK_TABLE_VERSION 1u
#define OGK_TABLE_F64 1u

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

/* Validates buf[0..len-1] against spec (magic, version, element type, kind,
 * dims, grid size, exact length, both CRCs, finite values) and fills view. On
 * failure view is zeroed and the specific OGK_E_TABLE_* code (or
 * OGK_E_NONFINITE) is returned. */
ogk_status ogk_table_open(const uint8_t *buf, size_t len,
                          const ogk_table_spec_t *spec, ogk_table_view_t *view);

/* Copies the grid (grid_size values) into grid_out (capacity entries). */
ogk_status ogk_table_read_grid(const ogk_table_view_t *view, double *grid_out,
                               size_t capacity);

/* Copies all entries (grid_size * entry_len values, entry-major) into
 * data_out (capacity entries). */
ogk_status ogk_table_read_data(const ogk_table_view_t *view, double *data_out,
                               size_t capacity);

/* Reads value `index` (0..entry_len-1) of entry k. */
ogk_status ogk_table_get(const ogk_table_view_t *view, uint32_t k,
                         uint32_t index, double *value);

#ifdef __cplusplus
}
#endif

#endif /* OGK_TABLE_H */
