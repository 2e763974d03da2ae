/* table.c -- loader of the versioned binary table format (ogk/table.h).
 *
 * Every header field is decoded byte by byte (little-endian), so the loader
 * works on any host endianness and on unaligned buffers. Nothing is read from
 * the payload before the header CRC, the sizes and the payload CRC check out. */
#include "ogk/table.h"

#include <math.h>
#include <string.h>

#include "ogk/crc32.h"

/* Byte offsets of the header fields (layout in ogk/table.h). */
#define OFF_MAGIC 0u
#define OFF_VERSION 4u
#define OFF_ELEM_TYPE 6u
#define OFF_KIND 8u
#define OFF_NDIMS 12u
#define OFF_RESERVED 14u
#define OFF_DIMS 16u
#define OFF_GRID 32u
#define OFF_PAYLOAD_BYTES 36u
#define OFF_PAYLOAD_CRC 40u
#define OFF_HEADER_CRC 44u

/* Largest entry or payload the loader accepts: keeps every size product
 * below 2^31 so no intermediate overflows on 32-bit targets. */
#define OGK_TABLE_MAX_VALUES 0x0FFFFFFFu

/* Size in bytes of one payload value of this build's element type
 * (OGK_TABLE_REAL), which is sizeof(ogk_real_t): ogk/status.h refuses a double
 * that is not binary64, ogk/real.h a float that is not binary32. */
#if OGK_REAL_SINGLE
#define TABLE_VALUE_BYTES 4u
#else
#define TABLE_VALUE_BYTES 8u
#endif

static uint16_t get_u16(const uint8_t *p)
{
    return (uint16_t)((uint16_t)p[0] | (uint16_t)((uint16_t)p[1] << 8));
}

static uint32_t get_u32(const uint8_t *p)
{
    return (uint32_t)p[0] | ((uint32_t)p[1] << 8) | ((uint32_t)p[2] << 16) |
           ((uint32_t)p[3] << 24);
}

#if OGK_REAL_SINGLE
/* One payload value of an F32 table, from its little-endian binary32 bytes. */
static ogk_real_t get_value(const uint8_t *p)
{
    uint32_t bits = 0u;
    ogk_real_t value;
    unsigned i;
    for (i = 0u; i < 4u; ++i) {
        bits = (bits << 8u) | (uint32_t)p[3u - i];
    }
    /* The object representation of a binary32 from its bits: deviation D3
     * (rule 21.15, docs/evidence/misra-deviations.md). memcpy returns its
     * destination: nothing to check. */
    (void)memcpy(&value, &bits, sizeof value);
    return value;
}
#else
/* One payload value of an F64 table, from its little-endian binary64 bytes. */
static ogk_real_t get_value(const uint8_t *p)
{
    uint64_t bits = 0u;
    ogk_real_t value;
    unsigned i;
    for (i = 0u; i < 8u; ++i) {
        bits = (bits << 8u) | (uint64_t)p[7u - i];
    }
    /* The object representation of a binary64 from its bits: deviation D3
     * (rule 21.15, docs/evidence/misra-deviations.md). memcpy returns its
     * destination: nothing to check. */
    (void)memcpy(&value, &bits, sizeof value);
    return value;
}
#endif

/* Checks the dims against the caller's spec and computes their product. */
static ogk_status check_dims(const uint8_t *hdr, const ogk_table_spec_t *spec,
                             ogk_table_view_t *v)
{
    ogk_status st = OGK_OK;
    uint32_t product = 1u;
    uint16_t d;

    v->ndims = get_u16(&hdr[OFF_NDIMS]);
    if ((v->ndims == 0u) || (v->ndims > OGK_TABLE_MAX_DIMS) || (v->ndims != spec->ndims)) {
        st = OGK_E_TABLE_DIM;
    }
    for (d = 0u; (d < OGK_TABLE_MAX_DIMS) && (st == OGK_OK); ++d) {
        v->dims[d] = get_u32(&hdr[OFF_DIMS + ((size_t)4u * d)]);
        if (d < v->ndims) {
            if ((v->dims[d] == 0u) ||
                ((spec->dims[d] != 0u) && (spec->dims[d] != v->dims[d]))) {
                st = OGK_E_TABLE_DIM;
            } else if (v->dims[d] > (OGK_TABLE_MAX_VALUES / product)) {
                st = OGK_E_TABLE_SIZE;
            } else {
                product *= v->dims[d];
            }
        } else if (v->dims[d] != 0u) {
            st = OGK_E_TABLE_DIM;
        } else {
            /* an unused dimension, 0 as the format requires */
        }
    }
    if (st == OGK_OK) {
        v->entry_len = product;
    }
    return st;
}

/* Header up to the dims: length, magic, header CRC, version, element type, kind. */
static ogk_status check_header(const uint8_t *buf, size_t len,
                               const ogk_table_spec_t *spec, ogk_table_view_t *v)
{
    /* The magic "OGKT" as bytes (not a string: no terminator in the file). */
    static const uint8_t table_magic[4] = {0x4Fu, 0x47u, 0x4Bu, 0x54u};
    ogk_status st;
    uint32_t crc = 0u;

    if (len < OGK_TABLE_HEADER_SIZE) {
        st = ((len >= 4u) && (memcmp(buf, table_magic, 4u) != 0)) ? OGK_E_TABLE_MAGIC
                                                              : OGK_E_TABLE_TRUNCATED;
    } else if (memcmp(&buf[OFF_MAGIC], table_magic, 4u) != 0) {
        st = OGK_E_TABLE_MAGIC;
    } else {
        /* Cannot fail: crc is a local and buf is non-NULL (checked by the caller). */
        (void)ogk_crc32_update(&crc, buf, OFF_HEADER_CRC);
        if (crc != get_u32(&buf[OFF_HEADER_CRC])) {
            st = OGK_E_TABLE_CRC;
        } else if (get_u16(&buf[OFF_VERSION]) != OGK_TABLE_VERSION) {
            st = OGK_E_TABLE_VERSION;
        } else if ((get_u16(&buf[OFF_ELEM_TYPE]) != OGK_TABLE_REAL) ||
                   (get_u16(&buf[OFF_RESERVED]) != 0u)) {
            /* the other precision's table (F64 in the float build, F32 in
             * the double build) too: made for the other build */
            st = OGK_E_TABLE_TYPE;
        } else {
            v->kind = get_u32(&buf[OFF_KIND]);
            st = (v->kind != spec->kind) ? OGK_E_TABLE_TYPE : OGK_OK;
        }
    }
    return st;
}

/* Grid size, and the payload size against the dims (v->entry_len) and len;
 * *values = number of values in the payload. */
static ogk_status check_sizes(const uint8_t *buf, size_t len, const ogk_table_spec_t *spec,
                              ogk_table_view_t *v, uint32_t *values)
{
    ogk_status st;

    v->grid_size = get_u32(&buf[OFF_GRID]);
    if ((v->grid_size < spec->min_grid) || (v->grid_size > spec->max_grid) || (v->grid_size == 0u)) {
        st = OGK_E_TABLE_DIM;
    } else if ((v->entry_len >= OGK_TABLE_MAX_VALUES) ||
               (v->grid_size > (OGK_TABLE_MAX_VALUES / (v->entry_len + 1u)))) {
        /* values = grid * (1 + entry_len), guarded against overflow. */
        st = OGK_E_TABLE_SIZE;
    } else {
        const uint32_t payload_bytes = get_u32(&buf[OFF_PAYLOAD_BYTES]);
        *values = v->grid_size * (v->entry_len + 1u);
        if ((*values > (OGK_TABLE_MAX_VALUES / TABLE_VALUE_BYTES)) ||
            (payload_bytes != (TABLE_VALUE_BYTES * *values))) {
            st = OGK_E_TABLE_SIZE;
        } else if ((len - OGK_TABLE_HEADER_SIZE) == (size_t)payload_bytes) {
            st = OGK_OK;
        } else {
            /* shorter than the header says, or longer */
            st = ((len - OGK_TABLE_HEADER_SIZE) < (size_t)payload_bytes) ? OGK_E_TABLE_TRUNCATED
                                                                       : OGK_E_TABLE_SIZE;
        }
    }
    return st;
}

/* Payload CRC, then every value finite; the payload is `values` values of
 * TABLE_VALUE_BYTES each, its length checked by check_sizes. */
static ogk_status check_payload(const uint8_t *buf, uint32_t values)
{
    const uint8_t *payload = &buf[OGK_TABLE_HEADER_SIZE];
    ogk_status st = OGK_OK;
    uint32_t crc = 0u;
    uint32_t i;

    /* Cannot fail: crc is a local and payload is non-NULL. */
    (void)ogk_crc32_update(&crc, payload, (size_t)TABLE_VALUE_BYTES * (size_t)values);
    if (crc != get_u32(&buf[OFF_PAYLOAD_CRC])) {
        st = OGK_E_TABLE_CRC;
    }
    for (i = 0u; (i < values) && (st == OGK_OK); ++i) {
        if (!isfinite(get_value(&payload[(size_t)TABLE_VALUE_BYTES * (size_t)i]))) {
            st = OGK_E_NONFINITE;
        }
    }
    return st;
}

static ogk_status open_checked(const uint8_t *buf, size_t len,
                               const ogk_table_spec_t *spec, ogk_table_view_t *v)
{
    uint32_t values = 0u;
    ogk_status st = check_header(buf, len, spec, v);

    if (st == OGK_OK) {
        st = check_dims(buf, spec, v);
    }
    if (st == OGK_OK) {
        st = check_sizes(buf, len, spec, v, &values);
    }
    if (st == OGK_OK) {
        st = check_payload(buf, values);
    }
    if (st == OGK_OK) {
        v->buf = buf;
    }
    return st;
}

ogk_status ogk_table_open(const uint8_t *buf, size_t len,
                          const ogk_table_spec_t *spec, ogk_table_view_t *view)
{
    ogk_status st;

    if (view == NULL) {
        st = OGK_E_NULL;
    } else {
        /* memset returns its destination: nothing to check (here and below). */
        (void)memset(view, 0, sizeof *view);
        if ((buf == NULL) || (spec == NULL)) {
            st = OGK_E_NULL;
        } else {
            st = open_checked(buf, len, spec, view);
            if (st != OGK_OK) {
                (void)memset(view, 0, sizeof *view);
            }
        }
    }
    return st;
}

/* NULL and not-opened checks shared by the readers. */
static ogk_status view_check(const ogk_table_view_t *view, const ogk_real_t *out)
{
    ogk_status st;
    if ((view == NULL) || (out == NULL)) {
        st = OGK_E_NULL;
    } else if (view->buf == NULL) {
        st = OGK_E_NOT_INIT;
    } else {
        st = OGK_OK;
    }
    return st;
}

ogk_status ogk_table_read_grid(const ogk_table_view_t *view, ogk_real_t *grid_out,
                               size_t capacity)
{
    ogk_status st = view_check(view, grid_out);

    if ((st == OGK_OK) && (capacity < (size_t)view->grid_size)) {
        st = OGK_E_DIM;
    }
    if (st == OGK_OK) {
        const uint8_t *grid = &view->buf[OGK_TABLE_HEADER_SIZE];
        uint32_t k;
        for (k = 0u; k < view->grid_size; ++k) {
            grid_out[k] = get_value(&grid[(size_t)TABLE_VALUE_BYTES * (size_t)k]);
        }
    }
    return st;
}

ogk_status ogk_table_read_data(const ogk_table_view_t *view, ogk_real_t *data_out,
                               size_t capacity)
{
    size_t count = 0u;
    ogk_status st = view_check(view, data_out);

    if (st == OGK_OK) {
        count = (size_t)view->grid_size * (size_t)view->entry_len;
        if (capacity < count) {
            st = OGK_E_DIM;
        }
    }
    if (st == OGK_OK) {
        const uint8_t *data = &view->buf[OGK_TABLE_HEADER_SIZE + ((size_t)TABLE_VALUE_BYTES * (size_t)view->grid_size)];
        size_t i;
        for (i = 0u; i < count; ++i) {
            data_out[i] = get_value(&data[(size_t)TABLE_VALUE_BYTES * i]);
        }
    }
    return st;
}

ogk_status ogk_table_get(const ogk_table_view_t *view, uint32_t k,
                         uint32_t index, ogk_real_t *value)
{
    ogk_status st = view_check(view, value);

    if ((st == OGK_OK) && ((k >= view->grid_size) || (index >= view->entry_len))) {
        st = OGK_E_RANGE;
    }
    if (st == OGK_OK) {
        const size_t offset = OGK_TABLE_HEADER_SIZE +
            ((size_t)TABLE_VALUE_BYTES * ((size_t)view->grid_size + ((size_t)k * (size_t)view->entry_len) + (size_t)index));
        *value = get_value(&view->buf[offset]);
    }
    return st;
}

ogk_status ogk_table_check_f64_bytes(const uint8_t *bytes)
{
    /* OGK_TABLE_ORDER_PROBE as the file stores it: the bits 0x400921FB54442D18,
     * least significant byte first. */
    static const uint8_t probe_le[8] = {0x18u, 0x2Du, 0x44u, 0x54u, 0xFBu, 0x21u, 0x09u, 0x40u};
    ogk_status st;

    if (bytes == NULL) {
        st = OGK_E_NULL;
    } else if (memcmp(bytes, probe_le, sizeof probe_le) != 0) {
        st = OGK_E_BYTE_ORDER;
    } else {
        st = OGK_OK;
    }
    return st;
}

#if OGK_REAL_SINGLE
ogk_status ogk_table_check_in_place(void)
{
    /* OGK_TABLE_ORDER_PROBE as an F32 table stores it: the bits 0x40490FDB,
     * least significant byte first. */
    static const uint8_t probe_le[4] = {0xDBu, 0x0Fu, 0x49u, 0x40u};
    static const ogk_real_t probe = OGK_TABLE_ORDER_PROBE;

    /* The target's object representation of the probe, read through a
     * character type (C99 6.2.6.1p4, 6.5p7; the exception of MISRA rule 11.3),
     * compared over the element's 4 bytes: ogk/real.h makes float binary32,
     * 4 bytes (the element size of an F32 table). */
    return (memcmp((const uint8_t *)&probe, probe_le, sizeof probe_le) != 0) ? OGK_E_BYTE_ORDER
                                                                            : OGK_OK;
}
#else
ogk_status ogk_table_check_in_place(void)
{
    static const ogk_real_t probe = OGK_TABLE_ORDER_PROBE;

    /* The target's object representation of the probe, read through a
     * character type (C99 6.2.6.1p4, 6.5p7; the exception of MISRA rule 11.3);
     * ogk/status.h makes double binary64, 8 bytes (the element size of an F64
     * table). */
    return ogk_table_check_f64_bytes((const uint8_t *)&probe);
}
#endif
