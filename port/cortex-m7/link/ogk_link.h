/* ogk_link.h -- the processor-in-the-loop link of the emulated Cortex-M7 (docs/guides/pil.md): framed
 * messages between the flight program and the host's truth model over semihosting stdin/stdout.
 * Not part of the kernel (it is the port's I/O).
 *
 * Frame, every field little-endian whatever the target's byte order (written byte by byte):
 *   magic "OGKL" (4 bytes) | type (u16) | length (u16, payload bytes) | payload | CRC-32 (u32)
 * The CRC (ogk/crc32.h, zlib's) covers type, length and payload. Doubles travel as their IEEE 754
 * binary64 bit patterns, little-endian (ogk_link_put_f64 / ogk_link_get_f64): bit-exact, NaN
 * payloads included. */
#ifndef OGK_LINK_H
#define OGK_LINK_H

#include <stddef.h>
#include <stdint.h>

#define OGK_LINK_MAX_PAYLOAD 1024u   /* bytes: the largest payload a frame carries */

/* Frame types of the link itself (a flight program adds its own from 16 up). */
#define OGK_LINK_STOP  1u    /* host -> target: end the program (exit 0) */
#define OGK_LINK_ERROR 2u    /* target -> host: payload = one u16 OGK_LINK_E_* code */
#define OGK_LINK_ECHO  3u    /* host -> target: the link test (link_echo.c) */

/* Results of ogk_link_receive (0: a frame). */
#define OGK_LINK_E_EOF    (-1)  /* the host closed the link */
#define OGK_LINK_E_MAGIC  (-2)  /* no "OGKL" where a frame starts */
#define OGK_LINK_E_LENGTH (-3)  /* length above OGK_LINK_MAX_PAYLOAD or the caller's capacity */
#define OGK_LINK_E_CRC    (-4)  /* CRC mismatch */
#define OGK_LINK_E_WRITE  (-5)  /* ogk_link_send could not write the whole frame */

/* Reads one frame; its payload into payload[0..*length). Returns 0 or an OGK_LINK_E_* code. */
int ogk_link_receive(uint16_t *type, uint8_t *payload, size_t capacity, uint16_t *length);

/* Writes one frame. Returns 0 or OGK_LINK_E_LENGTH / OGK_LINK_E_WRITE. */
int ogk_link_send(uint16_t type, const uint8_t *payload, uint16_t length);

/* binary64 <-> 8 little-endian bytes. */
void ogk_link_put_f64(uint8_t *out, double value);
double ogk_link_get_f64(const uint8_t *in);

#endif /* OGK_LINK_H */
