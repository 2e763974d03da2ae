/* ogk_pil.h -- what every processor-in-the-loop flight program shares (docs/guides/pil.md): the markers the
 * host's instruction log is cut at, the painted-stack probe around each entry-point call, and the
 * frame loop. Port code, not kernel code: a flight program on a board keeps its own scheduler and
 * drops these.
 *
 * Instructions: QEMU's insn_count plugin logs every returned call of the entry points and of the two
 * markers (`NAME COUNT`, in return order). The program calls ogk_pil_tick_mark() after each step
 * it answers and ogk_pil_run_mark() after each run, so the host attributes every logged call to its
 * run and step (harness/ogk/sil/pil.py).
 *
 * Stack: OGK_PIL_STACK(probe, slot, call) paints OGK_PIL_STACK_WINDOW bytes below the current stack
 * pointer, makes the call, and keeps in probe->max_bytes[slot] the deepest word the call wrote
 * (bytes below the caller's stack pointer). A call deeper than the window sets
 * OGK_PIL_STACK_OVERFLOW in probe->overflow (the figure is then at least the window). */
#ifndef OGK_PIL_H
#define OGK_PIL_H

#include <stddef.h>
#include <stdint.h>

#include "ogk/real.h"

#include "ogk_link.h"

#ifndef OGK_PIL_STACK_WINDOW
#define OGK_PIL_STACK_WINDOW 8192u   /* bytes painted below the caller's stack pointer */
#endif
#define OGK_PIL_MAX_SLOTS 16u        /* entry points per program */

/* Frame types every PIL program answers (a family's own start at 32). */
#define OGK_PIL_RUN_END 16u  /* host -> target: the run is over; reply: per-slot stack (u32 each)
                                then the overflow mask (u32) */

typedef struct {
    uint32_t max_bytes[OGK_PIL_MAX_SLOTS]; /* [B] deepest stack below the caller per entry point */
    uint32_t overflow;                     /* bit s: slot s went deeper than the window */
} ogk_pil_stack_t;

/* Markers for the instruction log (do nothing; never inlined). */
void ogk_pil_tick_mark(void);
void ogk_pil_run_mark(void);

/* Paints the window below the stack pointer; returns its lowest word. */
uint32_t *ogk_pil_stack_paint(void);
/* Bytes of the window written since ogk_pil_stack_paint returned lo. */
uint32_t ogk_pil_stack_used(const uint32_t *lo);
void ogk_pil_stack_note(ogk_pil_stack_t *probe, unsigned slot, const uint32_t *lo);

#define OGK_PIL_STACK(probe, slot, call)                                                       \
    do {                                                                                       \
        uint32_t *ogk_pil_lo_ = ogk_pil_stack_paint();                                         \
        call;                                                                                  \
        ogk_pil_stack_note((probe), (slot), ogk_pil_lo_);                                      \
    } while (0)

/* Sends the RUN_END reply (the probe's figures) and clears the probe. Returns ogk_link_send's. */
int ogk_pil_send_run_end(ogk_pil_stack_t *probe, unsigned n_slots);

/* The frame loop: RUN_END is answered from probe (n_slots entry points); every other frame that is
 * not STOP or a link error goes to handler, which fills the reply (type, payload, length) and
 * returns 0; returns OGK_PIL_UNKNOWN for a frame it does not know (or of a wrong length), which the
 * loop answers with OGK_LINK_ERROR code 255; or returns a positive code to end the program with it. STOP ends it with 0, end of input with 3. Never returns otherwise. */
#define OGK_PIL_UNKNOWN (-1)
typedef int (*ogk_pil_handler)(uint16_t type, const uint8_t *in, uint16_t length, uint16_t *reply_type,
                               uint8_t *out, uint16_t *reply_length);
int ogk_pil_serve(ogk_pil_handler handler, ogk_pil_stack_t *probe, unsigned n_slots);

/* Payload helpers: n binary64 values in and out (little-endian bit patterns). */
void ogk_pil_get_f64s(const uint8_t *in, double *values, unsigned n);
void ogk_pil_put_f64s(uint8_t *out, const double *values, unsigned n);

/* The program's precision boundary: the frames carry binary64 on every target (target_link.py); the
 * flight code computes in the kernel's ogk_real_t. A double kernel (Cortex-M7, SPARC V8) reads and
 * writes the values as they are; a float kernel (Cortex-M4F, -DOGK_REAL_SINGLE=1) rounds each
 * received value to the nearest float here (IEEE round to nearest; NaN and infinities kept) and widens
 * each reply value exactly: the only double arithmetic of a float program (libgcc's __aeabi_d2f and
 * __aeabi_f2d on the M4F). The *_pil.c handlers convert a scalar at the boundary with OGK_PIL_REAL(x)
 * (a frame's double to ogk_real_t) and (double)x (back). */
#define OGK_PIL_REAL(x) ((ogk_real_t)(x))
void ogk_pil_get_reals(const uint8_t *in, ogk_real_t *values, unsigned n);
void ogk_pil_put_reals(uint8_t *out, const ogk_real_t *values, unsigned n);

#endif /* OGK_PIL_H */
