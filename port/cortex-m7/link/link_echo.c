/* link_echo.c -- the link's own test program (tests/python/test_target_link.py, docs/guides/pil.md): each
 * OGK_LINK_ECHO frame carries n binary64 values; the reply (the same type) carries their negations
 * (a sign-bit flip: exact for every value, NaN payloads included), so the host checks the link and
 * the byte order bit for bit. A frame that fails its checks is answered with OGK_LINK_ERROR and the
 * code, and the program goes on reading; OGK_LINK_STOP ends it (exit 0), end of input with exit 3. */
#include <stdint.h>

#include "ogk_armv7m.h"
#include "ogk_link.h"

int main(void)
{
    static uint8_t in[OGK_LINK_MAX_PAYLOAD];
    static uint8_t out[OGK_LINK_MAX_PAYLOAD];
    for (;;) {
        uint16_t type = 0u;
        uint16_t length = 0u;
        const int rc = ogk_link_receive(&type, in, sizeof in, &length);
        if (rc == OGK_LINK_E_EOF) {
            return 3;
        }
        if (rc != 0) {
            uint8_t code[2] = {(uint8_t)(-rc), 0u};
            (void)ogk_link_send(OGK_LINK_ERROR, code, 2u);
            continue;
        }
        if (type == OGK_LINK_STOP) {
            return 0;
        }
        for (uint16_t i = 0u; i + 8u <= length; i = (uint16_t)(i + 8u)) {
            ogk_link_put_f64(out + i, -ogk_link_get_f64(in + i));
        }
        if (ogk_link_send(type, out, length) != 0) {
            return 4;
        }
    }
}
