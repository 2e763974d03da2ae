/* fuzz_mpsp_init.c -- ogk_mpsp_init (configuration validation) with arbitrary configuration
 * bytes. Start: the valid 3rd-order two-body configuration of test_mpsp_solve.c with a coarse
 * grid (40 RK4 steps) and n_seg_nom = 3 (no propagation at init, kept cheap); the input patches
 * it: a sequence of (2-byte offset, 8 bytes) written into the configuration's bytes (offset
 * modulo its size), the first input byte choosing whether n_seg_nom is left for the fuzzer
 * (bit 0) so that init's nominal propagation is reached too.
 * Oracle (mpsp.h): init returns OGK_OK, OGK_E_NONFINITE or OGK_E_CONFIG; on failure the context is
 * not initialised (init_marker != OGK_MPSP_INIT_MARKER, and ogk_mpsp_reset answers
 * OGK_E_NOT_INIT); on success the control at t0 is finite and reset succeeds. */
#include "fuzz_common.h"

#include "mpsp_fixture.h"
#include "ogk/mpsp.h"

static ogk_mpsp_t ctx;

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

static void orbit_config(ogk_mpsp_config_t *c)
{
    (void)mpsp_fixture_config(c, 20u, 30u);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    static ogk_mpsp_config_t cfg;
    fz_reader_t r;
    uint8_t setup;
    ogk_status st;
    int patches = 0;
    unsigned char *bytes = (unsigned char *)&cfg;
    orbit_config(&cfg);
    r.p = data;
    r.n = size;
    setup = fz_u8(&r);
    while (r.n > 0u && patches < 16) {
        const size_t off = ((size_t)fz_u8(&r) | ((size_t)fz_u8(&r) << 8)) % sizeof cfg;
        size_t i;
        for (i = 0u; i < 8u && off + i < sizeof cfg; ++i) {
            bytes[off + i] = fz_u8(&r);
        }
        ++patches;
    }
    if ((setup & 1u) == 0u) {
        cfg.n_seg_nom = 3u;
    }
    memset(&ctx, 0, sizeof ctx);
    st = ogk_mpsp_init(&ctx, &cfg);
    if (st != OGK_OK) {
        FZ_CHECK(st == OGK_E_CONFIG || st == OGK_E_NONFINITE);
        FZ_CHECK(ctx.init_marker != OGK_MPSP_INIT_MARKER);
        FZ_CHECK(ogk_mpsp_reset(&ctx) == OGK_E_NOT_INIT);
        return 0;
    }
    FZ_CHECK(ctx.init_marker == OGK_MPSP_INIT_MARKER);
    {
        double u[3] = {0.0, 0.0, 0.0};
        st = ogk_mpsp_control(&ctx, cfg.weights_nom, cfg.t0, u, NULL);
        FZ_CHECK(st == OGK_OK || st == OGK_E_NONFINITE);
        FZ_CHECK(st != OGK_OK || (isfinite(u[0]) && isfinite(u[1]) && isfinite(u[2])));
    }
    st = ogk_mpsp_reset(&ctx);
    FZ_CHECK(st == OGK_OK); /* init propagated the same nominal when n_seg_nom = 0 */
    return 0;
}
