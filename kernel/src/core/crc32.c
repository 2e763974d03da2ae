/* crc32.c -- CRC-32 (IEEE 802.3, reflected), nibble-table implementation:
 * 16 constant words instead of 1 KiB, two lookups per byte. */
#include "ogk/crc32.h"

ogk_status ogk_crc32_update(uint32_t *crc, const uint8_t *data, size_t len)
{
    /* CRC of each 4-bit value under the reflected polynomial 0xEDB88320. */
    static const uint32_t nibble_crc[16] = {
        0x00000000u, 0x1DB71064u, 0x3B6E20C8u, 0x26D930ACu,
        0x76DC4190u, 0x6B6B51F4u, 0x4DB26158u, 0x5005713Cu,
        0xEDB88320u, 0xF00F9344u, 0xD6D6A3E8u, 0xCB61B38Cu,
        0x9B64C2B0u, 0x86D3D2D4u, 0xA00AE278u, 0xBDBDF21Cu,
    };
    ogk_status st;

    if ((crc == NULL) || ((data == NULL) && (len > 0u))) {
        st = OGK_E_NULL;
    } else {
        uint32_t c = ~(*crc);
        size_t i;
        for (i = 0u; i < len; ++i) {
            c ^= (uint32_t)data[i];
            c = (c >> 4) ^ nibble_crc[c & 0x0Fu];
            c = (c >> 4) ^ nibble_crc[c & 0x0Fu];
        }
        *crc = ~c;
        st = OGK_OK;
    }
    return st;
}
