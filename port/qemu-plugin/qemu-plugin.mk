# port/qemu-plugin/qemu-plugin.mk -- QEMU TCG plugin counting executed guest
# instructions (included by the top-level Makefile after the ARMv7-M targets). No glib needed.
#   make qemu-plugin        build/qemu-plugin/libinsn_count.so
#   make test-qemu-plugin   known-answer + repeatability check (Cortex-M7, mps2-an500)
#   make test-qemu-plugin-m4f   the same on the Cortex-M4F (mps2-an386; count_insns.sh with QEMU_MACHINE)
#   port/qemu-plugin/count_insns.sh ELF FUNCTION...   per-function counts
#   make test-qemu-plugin-sparc   the same on SPARC V8 (qemu-user; count_insns.sh with QEMU_USER, NM)
QP_B := $(B)/qemu-plugin
QP_SO := $(QP_B)/libinsn_count.so

.PHONY: qemu-plugin test-qemu-plugin
$(QP_SO): port/qemu-plugin/insn_count.c port/qemu-plugin/qemu_plugin_api.h | apt
	@mkdir -p $(@D)
	gcc -std=gnu11 -O2 -Wall -Wextra -Werror -fPIC -shared -fvisibility=hidden $< -o $@
qemu-plugin: $(QP_SO)

# The known-answer program linked with an ARMv7-M target's runtime: $(call qp_known_counts,P,SUFFIX)
define qp_known_counts
$(QP_B)/known_counts$(2).elf: port/qemu-plugin/known_counts.c $$($(1)_RT_OBJ) $$($(1)_LDSCRIPT)
	@mkdir -p $$(@D)
	$$($(1)_CC) -std=gnu99 -Wall -Wextra -Werror -O2 $$($(1)_CPU) $$< $$($(1)_RT_OBJ) \
	  $$($(1)_LDFLAGS) $$($(1)_LDLIBS) -o $$@
endef
$(eval $(call qp_known_counts,ARM,))
$(eval $(call qp_known_counts,M4F,_m4f))
test-qemu-plugin: $(QP_SO) $(QP_B)/known_counts.elf
	QEMU_PLUGIN_SO=$(QP_SO) port/qemu-plugin/check_plugin.sh $(QP_B)/known_counts.elf

# The same known answers on the Cortex-M4F (QEMU mps2-an386; the same Thumb-2 instructions):
#   make test-qemu-plugin-m4f
.PHONY: test-qemu-plugin-m4f
test-qemu-plugin-m4f: $(QP_SO) $(QP_B)/known_counts_m4f.elf
	QEMU_PLUGIN_SO=$(QP_SO) QEMU_MACHINE=$(M4F_BOARD) port/qemu-plugin/check_plugin.sh $(QP_B)/known_counts_m4f.elf

# The same known answers on SPARC V8 under qemu-user (calls return after their delay slot):
#   make test-qemu-plugin-sparc
$(QP_B)/known_counts_sparc: port/qemu-plugin/known_counts_sparc.c | apt
	@mkdir -p $(@D)
	sparc64-linux-gnu-gcc -m32 -mcpu=v8 -std=gnu99 -Wall -Wextra -Werror -O2 -static $< -o $@
.PHONY: test-qemu-plugin-sparc
test-qemu-plugin-sparc: $(QP_SO) $(QP_B)/known_counts_sparc
	QEMU_PLUGIN_SO=$(QP_SO) QEMU_USER=qemu-sparc32plus NM=sparc64-linux-gnu-nm \
	  TEN=12 CALLS=17 port/qemu-plugin/check_plugin.sh $(QP_B)/known_counts_sparc
