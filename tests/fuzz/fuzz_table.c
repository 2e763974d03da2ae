/* fuzz_table.c -- ogk_table_open, ogk_table_read_grid, ogk_table_read_data, ogk_table_get on
 * arbitrary bytes. Input: one mode byte (bit 0: re-seal the CRCs; bit 1: expect the header's own
 * kind and dims instead of the NOG spec; bits 2-3: min_grid - 1), then the table bytes.
 * Oracle: a rejected table leaves the view zeroed; an accepted one is within the spec and every
 * read inside it succeeds, every read past it fails. */
#include "fuzz_common.h"

static union {
    double align;
    uint8_t b[FZ_MAX_LEN];
} tbuf;
static double grid[FZ_MAX_LEN / 8u];
static double data_out[FZ_MAX_LEN / 8u];

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    ogk_table_spec_t spec;
    ogk_table_view_t view;
    ogk_status st;
    uint8_t mode;
    size_t len;
    size_t i;
    if (size < 1u || size - 1u > FZ_MAX_LEN) {
        return 0;
    }
    mode = data[0];
    len = size - 1u;
    memcpy(tbuf.b, data + 1, len);
    if ((mode & 1u) != 0u) {
        fz_reseal(tbuf.b, len);
    }
    memset(&spec, 0, sizeof spec);
    if ((mode & 2u) != 0u && len >= 32u) {
        spec.kind = fz_get_u32(tbuf.b + 8);
        spec.ndims = (uint16_t)(tbuf.b[12] | (tbuf.b[13] << 8));
        if (spec.ndims > OGK_TABLE_MAX_DIMS) {
            spec.ndims = OGK_TABLE_MAX_DIMS;
        }
        for (i = 0u; i < OGK_TABLE_MAX_DIMS; ++i) {
            spec.dims[i] = (i & 1u) ? 0u : fz_get_u32(tbuf.b + 16 + 4u * i); /* some "any" */
        }
    } else {
        spec.kind = OGK_NOG_TABLE_KIND;
        spec.ndims = 1u;
        spec.dims[0] = OGK_NOG_ENTRY_LEN;
    }
    spec.min_grid = 1u + ((mode >> 2) & 3u);
    spec.max_grid = (uint32_t)(FZ_MAX_LEN / 8u);
    memset(&view, 0xA5, sizeof view);
    st = ogk_table_open(tbuf.b, len, &spec, &view);
    if (st != OGK_OK) {
        FZ_CHECK(view.buf == NULL && view.grid_size == 0u && view.entry_len == 0u);
        return 0;
    }
    FZ_CHECK(view.buf == tbuf.b);
    FZ_CHECK(view.kind == spec.kind && view.ndims == spec.ndims);
    FZ_CHECK(view.grid_size >= spec.min_grid && view.grid_size <= spec.max_grid);
    FZ_CHECK((size_t)view.grid_size * (1u + (size_t)view.entry_len) * 8u + OGK_TABLE_HEADER_SIZE == len);
    FZ_CHECK(ogk_table_read_grid(&view, grid, view.grid_size) == OGK_OK);
    for (i = 0u; i < view.grid_size; ++i) {
        FZ_CHECK(isfinite(grid[i]));
    }
    if (view.grid_size > 0u) {
        FZ_CHECK(ogk_table_read_grid(&view, grid, view.grid_size - 1u) != OGK_OK);
    }
    FZ_CHECK(ogk_table_read_data(&view, data_out, (size_t)view.grid_size * view.entry_len) == OGK_OK);
    for (i = 0u; i < (size_t)view.grid_size * view.entry_len; ++i) {
        FZ_CHECK(isfinite(data_out[i])); /* "finite values" are validated at open */
    }
    if (view.entry_len > 0u) {
        double v = 0.0;
        const uint32_t k = (uint32_t)mode % view.grid_size;
        const uint32_t j = (uint32_t)(len % view.entry_len);
        FZ_CHECK(ogk_table_read_data(&view, data_out,
                                     (size_t)view.grid_size * view.entry_len - 1u) != OGK_OK);
        FZ_CHECK(ogk_table_get(&view, k, j, &v) == OGK_OK);
        FZ_CHECK(v == data_out[(size_t)k * view.entry_len + j]);
        FZ_CHECK(ogk_table_get(&view, view.grid_size, 0u, &v) != OGK_OK);
        FZ_CHECK(ogk_table_get(&view, 0u, view.entry_len, &v) != OGK_OK);
    }
    return 0;
}
