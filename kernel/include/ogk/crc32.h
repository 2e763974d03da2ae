/* ogk/crc32.h -- CRC-32 (IEEE 802.3, reflected polynomial 0xEDB88320, initial
 * value and final xor 0xFFFFFFFF; the same as zlib's crc32). */
#ifndef OGK_CRC32_H
#define OGK_CRC32_H

#include <stddef.h>
#include <stdint.h>
#include "ogk/status.h"

#ifdef __cplusplus
extern "C" {
#endif

/* *crc = CRC-32 of data[0..len-1], continuing from a previous value: pass
 * *crc = 0 for a new computation (len may be 0; data may be NULL only then). */
/*@ requires crc_valid: crc == \null || \valid(crc);
    requires data_valid: data == \null || \valid_read(data + (0 .. len - 1));
*/
ogk_status ogk_crc32_update(uint32_t *crc, const uint8_t *data, size_t len);

#ifdef __cplusplus
}
#endif

#endif /* OGK_CRC32_H */
