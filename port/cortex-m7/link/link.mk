# port/cortex-m7/link/link.mk -- the processor-in-the-loop link of the emulated Cortex-M7 (docs/guides/pil.md)
# (included by the top-level Makefile after cortex-m7.mk).
#
#   make link-echo     build/arm/link/link_echo.elf: the link's test program
#                      (tests/python/test_target_link.py flies frames through it on QEMU)

LINK_DIR := $(ARM_PORT)/link
LINK_B := $(ARM_B)/link
LINK_ECHO_ELF := $(LINK_B)/link_echo.elf
# Port code (newlib's read/write for semihosting): the runtime's flags, strict warnings as errors.
LINK_CFLAGS := $(ARM_RT_FLAGS) -Wconversion $(KINC) -I$(LINK_DIR)
LINK_OBJ := $(LINK_B)/ogk_link_cm7.o $(LINK_B)/link_echo.o

.PHONY: link-echo

$(LINK_B)/%.o: $(LINK_DIR)/%.c $(LINK_DIR)/ogk_link.h $(ARM_RT_HDR) | apt
	@mkdir -p $(@D)
	$(ARM_CC) $(LINK_CFLAGS) -c $< -o $@

$(LINK_ECHO_ELF): $(LINK_OBJ) $(ARM_BOARD_OBJ) $(ARM_B)/libogk.a $(ARM_LDSCRIPT)
	$(ARM_CC) $(LINK_OBJ) $(ARM_BOARD_OBJ) $(ARM_B)/libogk.a \
	  $(ARM_LDFLAGS) $(ARM_LDLIBS) -o $@

link-echo: $(LINK_ECHO_ELF)
