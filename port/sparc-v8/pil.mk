# port/sparc-v8/pil.mk -- the processor-in-the-loop flight programs (docs/guides/pil.md) built for SPARC V8
# Linux user mode (qemu-sparc32plus, static glibc). Included by the top-level Makefile after
# sparc-v8.mk and port/cortex-m7/pil/pil.mk, whose program fragments (<program>.mk.inc: sources,
# generated C, painted window) it reuses: the flight programs are the same C.
#
#   make pil-program-sparc PIL_PROGRAM=oi PIL_OUT=DIR
#       DIR/c holds the generated table image and flight configuration (the same files as the
#       Cortex-M7 build: the table image is little-endian on every target); builds
#       DIR/sparc/PIL_PROGRAM.elf, its objects in DIR/sparc/obj. `ogk mc SCENARIO --target sparc`
#       calls this (harness/ogk/sil/pil_build.py).
#
# What differs from the Cortex-M7 build: the link (ogk_link_cm7.c) is the same read/write on
# stdin/stdout, here glibc's system calls instead of newlib's semihosting; the orbit-injection
# program decodes its table into RAM (OGK_FLIGHT_TABLE_COPY=1: the in-place view is little-endian
# only, as for the SPARC flight app); the stack probe reads %sp (ogk_pil.c).

PIL_SPARC_OUT := $(PIL_OUT)/sparc
PIL_SPARC_OBJ_DIR := $(PIL_SPARC_OUT)/obj
PIL_SPARC_ELF := $(PIL_SPARC_OUT)/$(PIL_PROGRAM).elf

# The flight code: the kernel's strict flags for SPARC V8, -O2, the probe hook on.
PIL_SPARC_CFLAGS := $(STRICT) $(SPARC_CPU) -O2 -g -fstack-usage $(PIL_WINDOW_$(PIL_PROGRAM)) \
  -DOGK_PIL_PROBE=1 -DOGK_FLIGHT_TABLE_COPY=1 $(KINC) -I$(PIL_GEN) -I$(PIL_DIR) -I$(FA_DIR) \
  -I$(LINK_DIR)
# The link and the probe are port code (POSIX read/write, inline assembly): strict warnings, gnu99.
PIL_SPARC_PORT_CFLAGS := -std=gnu99 -Wall -Wextra -Werror -Wshadow -Wconversion $(SPARC_CPU) -O2 -g \
  $(PIL_WINDOW_$(PIL_PROGRAM)) $(KINC) -I$(LINK_DIR) -I$(PIL_DIR)

PIL_SPARC_OBJ := $(patsubst %.c,$(PIL_SPARC_OBJ_DIR)/%.o,$(notdir $(PIL_SRC_$(PIL_PROGRAM)) \
  $(PIL_GEN_SRC_$(PIL_PROGRAM)))) $(PIL_SPARC_OBJ_DIR)/ogk_pil.o $(PIL_SPARC_OBJ_DIR)/ogk_link_cm7.o

.PHONY: pil-program-sparc

$(PIL_SPARC_OBJ_DIR)/%.o: $(PIL_DIR)/%.c $(PIL_HDR) $(wildcard $(PIL_GEN)/*.h) $(KHDR) | apt
	@mkdir -p $(@D)
	$(SPARC_CC) $(PIL_SPARC_CFLAGS) -c $< -o $@
$(PIL_SPARC_OBJ_DIR)/%.o: $(PIL_GEN)/%.c $(wildcard $(PIL_GEN)/*.h) | apt
	@mkdir -p $(@D)
	$(SPARC_CC) $(PIL_SPARC_CFLAGS) -c $< -o $@
$(PIL_SPARC_OBJ_DIR)/ogk_flight.o: $(FA_DIR)/ogk_flight.c $(PIL_HDR) $(KHDR) | apt
	@mkdir -p $(@D)
	$(SPARC_CC) $(PIL_SPARC_CFLAGS) -c $< -o $@
$(PIL_SPARC_OBJ_DIR)/ogk_pil.o: $(PIL_DIR)/ogk_pil.c $(PIL_HDR) | apt
	@mkdir -p $(@D)
	$(SPARC_CC) $(PIL_SPARC_PORT_CFLAGS) -c $< -o $@
$(PIL_SPARC_OBJ_DIR)/ogk_link_cm7.o: $(LINK_DIR)/ogk_link_cm7.c $(LINK_DIR)/ogk_link.h | apt
	@mkdir -p $(@D)
	$(SPARC_CC) $(PIL_SPARC_PORT_CFLAGS) -c $< -o $@

$(PIL_SPARC_ELF): $(PIL_SPARC_OBJ) $(SPARC_B)/libogk.a
	$(SPARC_CC) $(PIL_SPARC_OBJ) $(SPARC_B)/libogk.a $(SPARC_LDFLAGS) -Wl,-Map=$(@:.elf=.map) \
	  $(SPARC_LDLIBS) -o $@

pil-program-sparc: $(PIL_SPARC_ELF)
