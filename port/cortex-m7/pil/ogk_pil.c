/* ogk_pil.c -- markers, stack probe and frame loop of the PIL flight programs (ogk_pil.h). */
#include "ogk_pil.h"

#include <string.h>

#define PIL_PAINT 0x5AC3F00Du   /* not OGK_CM7_STACK_PAINT: the probe's own pattern */
#define PIL_WORDS (OGK_PIL_STACK_WINDOW / 4u)

/* The volatile store keeps the markers real calls with a body the plugin can name. */
static volatile uint32_t pil_marks;

__attribute__((noinline)) void ogk_pil_tick_mark(void)
{
    pil_marks += 1u;
}

__attribute__((noinline)) void ogk_pil_run_mark(void)
{
    pil_marks += 0x10000u;
}

__attribute__((noinline)) uint32_t *ogk_pil_stack_paint(void)
{
    uintptr_t sp;
    volatile uint32_t *word;
    uint32_t *lo;
    uint32_t i;
#if defined(__sparc__)
    /* SPARC: gcc gives this function a register window (`save %sp, -96, %sp`; checked on the
     * built program, tests/python/test_pil_sparc.py), so its %fp is the caller's %sp. */
    __asm__ volatile("mov %%fp, %0" : "=r"(sp));
#else
    /* The leaf keeps no frame (a BL pushes nothing; checked in the disassembly, docs/guides/pil.md): its
     * sp is the caller's. */
    __asm__ volatile("mov %0, sp" : "=r"(sp));
#endif
    /* The window ends at the caller's stack pointer, which AAPCS and the SPARC ABI keep 8-aligned
     * at a call. So the figure is every byte the next call writes below the caller's pointer. On
     * SPARC the caller's register-window save area lies above its %sp, outside the window; a
     * callee's save area is written only when its window spills (a call deeper than the register
     * windows hold), so the painted figure can stay below gcc's frames by the save areas still in
     * registers: a measurement, never above the static bound. */
    lo = (uint32_t *)((sp & ~(uintptr_t)7u) - OGK_PIL_STACK_WINDOW);
    word = lo;
    for (i = 0u; i < PIL_WORDS; ++i) {
        word[i] = PIL_PAINT;
    }
    return lo;
}

uint32_t ogk_pil_stack_used(const uint32_t *lo)
{
    const volatile uint32_t *word = lo;
    uint32_t untouched = 0u;
    while (untouched < PIL_WORDS && word[untouched] == PIL_PAINT) {
        ++untouched;
    }
    return (PIL_WORDS - untouched) * 4u;
}

void ogk_pil_stack_note(ogk_pil_stack_t *probe, unsigned slot, const uint32_t *lo)
{
    const uint32_t used = ogk_pil_stack_used(lo);
    if (slot >= OGK_PIL_MAX_SLOTS) {
        return;
    }
    if (used > probe->max_bytes[slot]) {
        probe->max_bytes[slot] = used;
    }
    if (used >= OGK_PIL_STACK_WINDOW) {
        probe->overflow |= (uint32_t)1u << slot;
    }
}

static void put_u32(uint8_t *out, uint32_t v)
{
    out[0] = (uint8_t)(v & 0xFFu);
    out[1] = (uint8_t)((v >> 8) & 0xFFu);
    out[2] = (uint8_t)((v >> 16) & 0xFFu);
    out[3] = (uint8_t)((v >> 24) & 0xFFu);
}

int ogk_pil_send_run_end(ogk_pil_stack_t *probe, unsigned n_slots)
{
    uint8_t out[4u * (OGK_PIL_MAX_SLOTS + 1u)];
    unsigned s;
    if (n_slots > OGK_PIL_MAX_SLOTS) {
        n_slots = OGK_PIL_MAX_SLOTS;
    }
    for (s = 0u; s < n_slots; ++s) {
        put_u32(out + 4u * s, probe->max_bytes[s]);
    }
    put_u32(out + 4u * n_slots, probe->overflow);
    memset(probe, 0, sizeof *probe);
    ogk_pil_run_mark();
    return ogk_link_send(OGK_PIL_RUN_END, out, (uint16_t)(4u * (n_slots + 1u)));
}

void ogk_pil_get_f64s(const uint8_t *in, double *values, unsigned n)
{
    unsigned i;
    for (i = 0u; i < n; ++i) {
        values[i] = ogk_link_get_f64(in + 8u * i);
    }
}

void ogk_pil_put_f64s(uint8_t *out, const double *values, unsigned n)
{
    unsigned i;
    for (i = 0u; i < n; ++i) {
        ogk_link_put_f64(out + 8u * i, values[i]);
    }
}

void ogk_pil_get_reals(const uint8_t *in, ogk_real_t *values, unsigned n)
{
    unsigned i;
    for (i = 0u; i < n; ++i) {
        values[i] = (ogk_real_t)ogk_link_get_f64(in + 8u * i);
    }
}

void ogk_pil_put_reals(uint8_t *out, const ogk_real_t *values, unsigned n)
{
    unsigned i;
    for (i = 0u; i < n; ++i) {
        ogk_link_put_f64(out + 8u * i, (double)values[i]);
    }
}

int ogk_pil_serve(ogk_pil_handler handler, ogk_pil_stack_t *probe, unsigned n_slots)
{
    static uint8_t in[OGK_LINK_MAX_PAYLOAD];
    static uint8_t out[OGK_LINK_MAX_PAYLOAD];
    for (;;) {
        uint16_t type = 0u;
        uint16_t length = 0u;
        uint16_t reply_type = 0u;
        uint16_t reply_length = 0u;
        int rc = ogk_link_receive(&type, in, sizeof in, &length);
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
        if (type == OGK_PIL_RUN_END) {
            if (ogk_pil_send_run_end(probe, n_slots) != 0) {
                return 4;
            }
            continue;
        }
        rc = handler(type, in, length, &reply_type, out, &reply_length);
        if (rc == OGK_PIL_UNKNOWN) {
            out[0] = 255u;
            out[1] = 0u;
            reply_type = OGK_LINK_ERROR;
            reply_length = 2u;
        } else if (rc != 0) {
            return rc;
        }
        if (reply_type != 0u && ogk_link_send(reply_type, out, reply_length) != 0) {
            return 4;
        }
    }
}
