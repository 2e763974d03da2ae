/* tests/eva/drv_core.c -- EVA drivers for crc32, mathutil and status. */
#include "libm_spec.h"
#include "__fc_builtin.h"
#include "ogk/crc32.h"
#include "ogk/mathutil.h"
#include "ogk/status.h"

#define CRC_MAX_LEN 64u

void eva_crc32(void)
{
    uint8_t data[CRC_MAX_LEN];
    uint32_t crc = Frama_C_unsigned_int_interval(0u, 0xFFFFFFFFu);
    size_t len = Frama_C_size_t_interval(0u, CRC_MAX_LEN);
    Frama_C_make_unknown((char *)data, sizeof data);
    (void)ogk_crc32_update(&crc, data, len);
    (void)ogk_crc32_update(&crc, NULL, 0u);
    (void)ogk_crc32_update(&crc, NULL, 1u);
    (void)ogk_crc32_update(NULL, data, len);
}

void eva_mathutil(void)
{
    double w;
    double a = Frama_C_double_interval(-1.0e308, 1.0e308);
    (void)ogk_wrap_pi(a, &w);
    (void)ogk_wrap_pi(a, NULL);
}

void eva_status(void)
{
    const char *name;
    ogk_status code = (ogk_status)Frama_C_int_interval(-2, OGK_STATUS_COUNT + 2);
    (void)ogk_status_name(code, &name);
    (void)ogk_status_name(code, NULL);
}
