# port/cortex-m7/pil/pil.mk -- the processor-in-the-loop flight programs (docs/guides/pil.md), one per
# law, each built for one scenario from the C its ground tools generate. Included by the top-level
# Makefile after link.mk and flightapp.mk.
#
#   make pil-program PIL_PROGRAM=oi PIL_OUT=DIR
#       DIR/c holds the generated table image and flight configuration (the campaign writes them);
#       builds DIR/PIL_PROGRAM.elf, its objects in DIR/obj. `ogk mc SCENARIO --target m7` calls
#       this (harness/ogk/sil/pil_build.py); the flight build's flags are the kernel's.
#
# Programs (one fragment each, <program>.mk.inc): oi (VTD-NOG + energy cut-off + terminal + CPD:
# oi_pil.c over oi_flight.c and the flightapp's ogk_flight.c), mpsp (MPSP re-planning), nmpc (NMPC
# re-solves), blt (the BLT correctors).

PIL_DIR := $(ARM_PORT)/pil
PIL_PROGRAM ?= oi
PIL_OUT ?= $(ARM_B)/pil/$(PIL_PROGRAM)
PIL_OBJ_DIR := $(PIL_OUT)/obj
PIL_GEN := $(PIL_OUT)/c
PIL_ELF := $(PIL_OUT)/$(PIL_PROGRAM).elf

# One fragment per program, port/cortex-m7/pil/<program>.mk.inc, sets PIL_WINDOW_<p>, PIL_SRC_<p> (its
# sources outside DIR/c), PIL_GEN_SRC_<p> (the generated C it compiles from DIR/c) and may add to
# PIL_HDR.
PIL_HDR := $(PIL_DIR)/ogk_pil.h $(LINK_DIR)/ogk_link.h
include $(wildcard $(PIL_DIR)/*.mk.inc)
# (a fragment compiles a source outside port/cortex-m7/pil with its own rule, as oi's ogk_flight.o)

# The flight code: the kernel's strict flags, -O2, the probe hook on (OGK_PIL_PROBE).
PIL_CFLAGS := $(STRICT) $(ARM_CPU) -O2 -g -ffunction-sections -fdata-sections -fstack-usage $(PIL_WINDOW_$(PIL_PROGRAM)) \
  -DOGK_PIL_PROBE=1 $(KINC) -I$(PIL_GEN) -I$(PIL_DIR) -I$(FA_DIR) -I$(LINK_DIR) -I$(ARMV7M_DIR)
# The link and the probe are port code (inline assembly, newlib's read/write): the runtime's flags.
PIL_PORT_CFLAGS := $(LINK_CFLAGS) $(PIL_WINDOW_$(PIL_PROGRAM)) -I$(PIL_DIR)

PIL_OBJ := $(patsubst %.c,$(PIL_OBJ_DIR)/%.o,$(notdir $(PIL_SRC_$(PIL_PROGRAM)) $(PIL_GEN_SRC_$(PIL_PROGRAM)))) \
  $(PIL_OBJ_DIR)/ogk_pil.o $(PIL_OBJ_DIR)/ogk_link_cm7.o

.PHONY: pil-program

$(PIL_OBJ_DIR)/%.o: $(PIL_DIR)/%.c $(PIL_HDR) $(wildcard $(PIL_GEN)/*.h) $(KHDR) | apt
	@mkdir -p $(@D)
	$(ARM_CC) $(PIL_CFLAGS) -c $< -o $@
$(PIL_OBJ_DIR)/%.o: $(PIL_GEN)/%.c $(wildcard $(PIL_GEN)/*.h) | apt
	@mkdir -p $(@D)
	$(ARM_CC) $(PIL_CFLAGS) -c $< -o $@
$(PIL_OBJ_DIR)/ogk_pil.o: $(PIL_DIR)/ogk_pil.c $(PIL_HDR) | apt
	@mkdir -p $(@D)
	$(ARM_CC) $(PIL_PORT_CFLAGS) -c $< -o $@
$(PIL_OBJ_DIR)/ogk_link_cm7.o: $(LINK_DIR)/ogk_link_cm7.c $(LINK_DIR)/ogk_link.h | apt
	@mkdir -p $(@D)
	$(ARM_CC) $(PIL_PORT_CFLAGS) -c $< -o $@

$(PIL_ELF): $(PIL_OBJ) $(ARM_BOARD_OBJ) $(ARM_B)/libogk.a $(ARM_LDSCRIPT)
	$(ARM_CC) $(PIL_OBJ) $(ARM_BOARD_OBJ) $(ARM_B)/libogk.a \
	  $(ARM_LDFLAGS) -Wl,-Map=$(@:.elf=.map) $(ARM_LDLIBS) -o $@

pil-program: $(PIL_ELF)
