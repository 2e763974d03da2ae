/* table.c -- loader of the versioned binary table format (ogk/table.h).
 *
 * Every header field is decoded byte by byte (little-endian), so the loader
 * works on any host endianness and on unaligned buffers. Nothing is read from
 * the payload before the header CRC, the sizes and the payload CRC check out. */
#include "ogk/table.h"

#include <math.h>
#include <string.h>

#include "ogk/crc32.h"

enum {
    OFF_MAGIC = 0,
    OFF_VERSION = 4,
    OFF_ELEM_TYPE = 6,
    OFF_KIND = 8,
    OFF_NDIMS = 12,
    OFF_RESERVED = 14,
    OFF_DIMS = 16,
    OFF_GRID = 32,
    OFF_PAYLOAD_BYTES = 36,
    OFF_PAYLOAD_CRC = 40,
    OFF_HEADER_CRC = 44
};

/* Largest entry or payload the loader accepts: keeps every size product
 * below 2^31 so no intermediate overflows on 32-bit targets. */
#define OGK_TABLE_MAX_VALUES 0x0FFFFFFFu

static uint16_t get_u16(const uint8_t *p)
{
    return (uint16_t)((uint16_t)p[0] | (uint16_t)((uint16_t)p[1] << 8));
}

static uint32_t get_u32(const uint8_t *p)
{
    return (uint32_t)p[0] | ((uint32_t)p[1] << 8) | ((uint32_t)p[2] << 16) |
           ((uint32_t)p[3] << 24);
}

static double get_f64(const uint8_t *p)
{
    uint64_t bits = 0u;
    double value;
    unsigned i;
    for (i = 0u; i < 8u; ++i) {
        bits |= (uint64_t)p[i] << (8u * i);
    }
    memcpy(&value, &bits, sizeof value);
    return value;
}

/* Checks the dims against the caller's spec and computes their product. */
static ogk_status check_dims(const uint8_t *hdr, const ogk_table_spec_t *spec,
                             ogk_table_view_t *v)
{
    uint32_t product = 1u;
    uint16_t d;

    v->ndims = get_u16(hdr + OFF_NDIMS);
    if ((v->ndims == 0u) || (v->ndims > OGK_TABLE_MAX_DIMS) || (v->ndims != spec->ndims)) {
        return OGK_E_TABLE_DIM;
    }
    for (d = 0u; d < OGK_TABLE_MAX_DIMS; ++d) {
        v->dims[d] = get_u32(hdr + OFF_DIMS + (size_t)4u * d);
        if (d < v->ndims) {
            if (v->dims[d] == 0u) {
                return OGK_E_TABLE_DIM;
            }
            if ((spec->dims[d] != 0u) && (spec->dims[d] != v->dims[d])) {
                return OGK_E_TABLE_DIM;
            }
            if (v->dims[d] > (OGK_TABLE_MAX_VALUES / product)) {
                return OGK_E_TABLE_SIZE;
            }
            product *= v->dims[d];
        } else if (v->dims[d] != 0u) {
            return OGK_E_TABLE_DIM;
        }
    }
    v->entry_len = product;
    return OGK_OK;
}

static ogk_status open_checked(const uint8_t *buf, size_t len,
                               const ogk_table_spec_t *spec, ogk_table_view_t *v)
{
    uint32_t crc = 0u;
    uint32_t payload_bytes;
    uint32_t values;
    uint32_t i;
    ogk_status st;

    if (len < OGK_TABLE_HEADER_SIZE) {
        return (len >= 4u && memcmp(buf, "OGKT", 4u) != 0) ? OGK_E_TABLE_MAGIC
                                                            : OGK_E_TABLE_TRUNCATED;
    }
    if (memcmp(buf + OFF_MAGIC, "OGKT", 4u) != 0) {
        return OGK_E_TABLE_MAGIC;
    }
    (void)ogk_crc32_update(&crc, buf, OFF_HEADER_CRC);
    if (crc != get_u32(buf + OFF_HEADER_CRC)) {
        return OGK_E_TABLE_CRC;
    }
    if (get_u16(buf + OFF_VERSION) != OGK_TABLE_VERSION) {
        return OGK_E_TABLE_VERSION;
    }
    if (get_u16(buf + OFF_ELEM_TYPE) != OGK_TABLE_F64 || get_u16(buf + OFF_RESERVED) != 0u) {
        return OGK_E_TABLE_TYPE;
    }
    v->kind = get_u32(buf + OFF_KIND);
    if (v->kind != spec->kind) {
        return OGK_E_TABLE_TYPE;
    }
    st = check_dims(buf, spec, v);
    if (st != OGK_OK) {
        return st;
    }
    v->grid_size = get_u32(buf + OFF_GRID);
    if ((v->grid_size < spec->min_grid) || (v->grid_size > spec->max_grid) || (v->grid_size == 0u)) {
        return OGK_E_TABLE_DIM;
    }
    /* values = grid * (1 + entry_len), guarded against overflow. */
    if ((v->entry_len >= OGK_TABLE_MAX_VALUES) ||
        (v->grid_size > (OGK_TABLE_MAX_VALUES / (v->entry_len + 1u)))) {
        return OGK_E_TABLE_SIZE;
    }
    values = v->grid_size * (v->entry_len + 1u);
    if (values > (OGK_TABLE_MAX_VALUES / 8u)) {
        return OGK_E_TABLE_SIZE;
    }
    payload_bytes = get_u32(buf + OFF_PAYLOAD_BYTES);
    if (payload_bytes != (8u * values)) {
        return OGK_E_TABLE_SIZE;
    }
    if ((len - OGK_TABLE_HEADER_SIZE) < (size_t)payload_bytes) {
        return OGK_E_TABLE_TRUNCATED;
    }
    if ((len - OGK_TABLE_HEADER_SIZE) > (size_t)payload_bytes) {
        return OGK_E_TABLE_SIZE;
    }
    crc = 0u;
    (void)ogk_crc32_update(&crc, buf + OGK_TABLE_HEADER_SIZE, payload_bytes);
    if (crc != get_u32(buf + OFF_PAYLOAD_CRC)) {
        return OGK_E_TABLE_CRC;
    }
    for (i = 0u; i < values; ++i) {
        if (!isfinite(get_f64(buf + OGK_TABLE_HEADER_SIZE + 8u * (size_t)i))) {
            return OGK_E_NONFINITE;
        }
    }
    v->buf = buf;
    return OGK_OK;
}

ogk_status ogk_table_open(const uint8_t *buf, size_t len,
                          const ogk_table_spec_t *spec, ogk_table_view_t *view)
{
    ogk_status st;

    if (view == NULL) {
        return OGK_E_NULL;
    }
    memset(view, 0, sizeof *view);
    if ((buf == NULL) || (spec == NULL)) {
        return OGK_E_NULL;
    }
    st = open_checked(buf, len, spec, view);
    if (st != OGK_OK) {
        memset(view, 0, sizeof *view);
    }
    return st;
}

ogk_status ogk_table_read_grid(const ogk_table_view_t *view, double *grid_out,
                               size_t capacity)
{
    uint32_t k;

    if ((view == NULL) || (grid_out == NULL)) {
        return OGK_E_NULL;
    }
    if (view->buf == NULL) {
        return OGK_E_NOT_INIT;
    }
    if (capacity < (size_t)view->grid_size) {
        return OGK_E_DIM;
    }
    for (k = 0u; k < view->grid_size; ++k) {
        grid_out[k] = get_f64(view->buf + OGK_TABLE_HEADER_SIZE + 8u * (size_t)k);
    }
    return OGK_OK;
}

ogk_status ogk_table_read_data(const ogk_table_view_t *view, double *data_out,
                               size_t capacity)
{
    size_t count;
    size_t i;
    const uint8_t *data;

    if ((view == NULL) || (data_out == NULL)) {
        return OGK_E_NULL;
    }
    if (view->buf == NULL) {
        return OGK_E_NOT_INIT;
    }
    count = (size_t)view->grid_size * (size_t)view->entry_len;
    if (capacity < count) {
        return OGK_E_DIM;
    }
    data = view->buf + OGK_TABLE_HEADER_SIZE + 8u * (size_t)view->grid_size;
    for (i = 0u; i < count; ++i) {
        data_out[i] = get_f64(data + 8u * i);
    }
    return OGK_OK;
}

ogk_status ogk_table_get(const ogk_table_view_t *view, uint32_t k,
                         uint32_t index, double *value)
{
    size_t offset;

    if ((view == NULL) || (value == NULL)) {
        return OGK_E_NULL;
    }
    if (view->buf == NULL) {
        return OGK_E_NOT_INIT;
    }
    if ((k >= view->grid_size) || (index >= view->entry_len)) {
        return OGK_E_RANGE;
    }
    offset = OGK_TABLE_HEADER_SIZE +
             (8u * ((size_t)view->grid_size + ((size_t)k * (size_t)view->entry_len) + (size_t)index));
    *value = get_f64(view->buf + offset);
    return OGK_OK;
}
