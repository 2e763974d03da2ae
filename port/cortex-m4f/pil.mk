# port/cortex-m4f/pil.mk -- the processor-in-the-loop flight programs (docs/guides/pil.md) built for the
# Cortex-M4F (QEMU mps2-an386) on the single-precision kernel (M4F_DEFS: -DOGK_REAL_SINGLE=1 when
# M4F_PRECISION is single). Included by the top-level Makefile after port/cortex-m4f/cortex-m4f.mk and
# port/cortex-m7/pil/pil.mk, whose program fragments (<program>.mk.inc: sources, generated C, painted
# window) it reuses: the flight programs are the same C.
#
#   make pil-program-m4f PIL_PROGRAM=oi PIL_OUT=DIR
#       DIR/m4f/c holds the generated table image and flight configuration for the single-precision
#       kernel (the harness writes them with precision "single": F32 tables, float configurations);
#       builds DIR/m4f/PIL_PROGRAM.elf, its objects in DIR/m4f/obj. `ogk mc SCENARIO --target m4f`
#       calls this (harness/ogk/sil/pil_build.py).
#
# What differs from the Cortex-M7 build: the CPU (fpv4-sp-d16: single-precision FPU only), the kernel
# library (build/m4f/libogk.a, float), the generated C (DIR/m4f/c), and the precision of the flight code:
# the link's frames stay binary64 (target_link.py); the *_pil.c files convert each value to ogk_real_t
# where they read a frame and back where they write one (ogk_pil.h, ogk_pil_get_reals / put_reals),
# the only double arithmetic of the program (libgcc's soft-float conversions).

PIL_M4F_OUT := $(PIL_OUT)/m4f
PIL_M4F_OBJ_DIR := $(PIL_M4F_OUT)/obj
PIL_M4F_GEN := $(PIL_M4F_OUT)/c
PIL_M4F_ELF := $(PIL_M4F_OUT)/$(PIL_PROGRAM).elf

# The flight code: the kernel's strict flags and configuration on the M4F, -O2, the probe hook on.
PIL_M4F_CFLAGS := $(STRICT) $(M4F_CPU) $(M4F_DEFS) -O2 -g -ffunction-sections -fdata-sections \
  -fstack-usage $(PIL_WINDOW_$(PIL_PROGRAM)) -DOGK_PIL_PROBE=1 $(KINC) -I$(PIL_M4F_GEN) -I$(PIL_DIR) \
  -I$(FA_DIR) -I$(LINK_DIR) -I$(ARMV7M_DIR)
# The link and the probe are port code (inline assembly, newlib's read/write): the runtime's flags.
PIL_M4F_PORT_CFLAGS := $(M4F_RT_FLAGS) $(M4F_DEFS) -Wconversion $(KINC) -I$(LINK_DIR) \
  $(PIL_WINDOW_$(PIL_PROGRAM)) -I$(PIL_DIR)

PIL_M4F_OBJ := $(patsubst %.c,$(PIL_M4F_OBJ_DIR)/%.o,$(notdir $(PIL_SRC_$(PIL_PROGRAM)) \
  $(PIL_GEN_SRC_$(PIL_PROGRAM)))) $(PIL_M4F_OBJ_DIR)/ogk_pil.o $(PIL_M4F_OBJ_DIR)/ogk_link_cm7.o

.PHONY: pil-program-m4f

$(PIL_M4F_OBJ_DIR)/%.o: $(PIL_DIR)/%.c $(PIL_HDR) $(wildcard $(PIL_M4F_GEN)/*.h) $(KHDR) | apt
	@mkdir -p $(@D)
	$(M4F_CC) $(PIL_M4F_CFLAGS) -c $< -o $@
$(PIL_M4F_OBJ_DIR)/%.o: $(PIL_M4F_GEN)/%.c $(wildcard $(PIL_M4F_GEN)/*.h) | apt
	@mkdir -p $(@D)
	$(M4F_CC) $(PIL_M4F_CFLAGS) -c $< -o $@
$(PIL_M4F_OBJ_DIR)/ogk_flight.o: $(FA_DIR)/ogk_flight.c $(PIL_HDR) $(KHDR) | apt
	@mkdir -p $(@D)
	$(M4F_CC) $(PIL_M4F_CFLAGS) -c $< -o $@
$(PIL_M4F_OBJ_DIR)/ogk_pil.o: $(PIL_DIR)/ogk_pil.c $(PIL_HDR) | apt
	@mkdir -p $(@D)
	$(M4F_CC) $(PIL_M4F_PORT_CFLAGS) -c $< -o $@
$(PIL_M4F_OBJ_DIR)/ogk_link_cm7.o: $(LINK_DIR)/ogk_link_cm7.c $(LINK_DIR)/ogk_link.h | apt
	@mkdir -p $(@D)
	$(M4F_CC) $(PIL_M4F_PORT_CFLAGS) -c $< -o $@

$(PIL_M4F_ELF): $(PIL_M4F_OBJ) $(M4F_BOARD_OBJ) $(M4F_B)/libogk.a $(M4F_LDSCRIPT)
	$(M4F_CC) $(PIL_M4F_OBJ) $(M4F_BOARD_OBJ) $(M4F_B)/libogk.a \
	  $(M4F_LDFLAGS) -Wl,-Map=$(@:.elf=.map) $(M4F_LDLIBS) -o $@

pil-program-m4f: $(PIL_M4F_ELF)
