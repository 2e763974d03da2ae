/* ogk_link_cm7.c -- ogk_link.h over semihosting stdin/stdout (newlib rdimon's read/write: SYS_READ
 * and SYS_WRITE on the console). Chosen over the board's CMSDK UART by measurement (docs/guides/pil.md):
 * no MPU region or driver to add, and 8k round trips of 64 B a second on QEMU 7.2. */
#include "ogk_link.h"

#include <string.h>
#include <unistd.h>

#include "ogk/crc32.h"

static int read_exact(uint8_t *p, size_t n)
{
    while (n > 0u) {
        ssize_t k = read(0, p, n);
        if (k <= 0) {
            return OGK_LINK_E_EOF;
        }
        p += (size_t)k;
        n -= (size_t)k;
    }
    return 0;
}

static uint16_t get_u16(const uint8_t *in) { return (uint16_t)(in[0] | (uint16_t)(in[1] << 8)); }

static uint32_t get_u32(const uint8_t *in)
{
    return (uint32_t)in[0] | ((uint32_t)in[1] << 8) | ((uint32_t)in[2] << 16) | ((uint32_t)in[3] << 24);
}

static void put_u16(uint8_t *out, uint16_t v)
{
    out[0] = (uint8_t)(v & 0xFFu);
    out[1] = (uint8_t)(v >> 8);
}

static void put_u32(uint8_t *out, uint32_t v)
{
    for (unsigned i = 0u; i < 4u; ++i) {
        out[i] = (uint8_t)((v >> (8u * i)) & 0xFFu);
    }
}

static uint32_t frame_crc(const uint8_t head[4], const uint8_t *payload, uint16_t length)
{
    uint32_t crc = 0u;
    (void)ogk_crc32_update(&crc, head, 4u);
    if (length > 0u) {
        (void)ogk_crc32_update(&crc, payload, length);
    }
    return crc;
}

int ogk_link_receive(uint16_t *type, uint8_t *payload, size_t capacity, uint16_t *length)
{
    uint8_t magic[4];
    uint8_t head[4];
    uint8_t tail[4];
    int rc = read_exact(magic, sizeof magic);
    if (rc != 0) {
        return rc;
    }
    if (memcmp(magic, "OGKL", 4u) != 0) {
        return OGK_LINK_E_MAGIC;
    }
    rc = read_exact(head, sizeof head);
    if (rc != 0) {
        return rc;
    }
    *type = get_u16(head);
    *length = get_u16(head + 2);
    if (*length > OGK_LINK_MAX_PAYLOAD || *length > capacity) {
        return OGK_LINK_E_LENGTH;
    }
    rc = read_exact(payload, *length);
    if (rc == 0) {
        rc = read_exact(tail, sizeof tail);
    }
    if (rc != 0) {
        return rc;
    }
    return get_u32(tail) == frame_crc(head, payload, *length) ? 0 : OGK_LINK_E_CRC;
}

int ogk_link_send(uint16_t type, const uint8_t *payload, uint16_t length)
{
    static uint8_t frame[12u + OGK_LINK_MAX_PAYLOAD];   /* one write: the host reads whole frames */
    if (length > OGK_LINK_MAX_PAYLOAD) {
        return OGK_LINK_E_LENGTH;
    }
    memcpy(frame, "OGKL", 4u);
    put_u16(frame + 4, type);
    put_u16(frame + 6, length);
    if (length > 0u) {
        memcpy(frame + 8, payload, length);
    }
    put_u32(frame + 8u + length, frame_crc(frame + 4, payload, length));
    const size_t total = 12u + (size_t)length;
    return write(1, frame, total) == (ssize_t)total ? 0 : OGK_LINK_E_WRITE;
}

void ogk_link_put_f64(uint8_t *out, double value)
{
    uint64_t bits;
    memcpy(&bits, &value, sizeof bits);
    for (unsigned i = 0u; i < 8u; ++i) {
        out[i] = (uint8_t)((bits >> (8u * i)) & 0xFFu);
    }
}

double ogk_link_get_f64(const uint8_t *in)
{
    uint64_t bits = 0u;
    for (unsigned i = 0u; i < 8u; ++i) {
        bits |= (uint64_t)in[i] << (8u * i);
    }
    double value;
    memcpy(&value, &bits, sizeof value);
    return value;
}
