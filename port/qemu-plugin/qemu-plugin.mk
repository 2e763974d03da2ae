# port/qemu-plugin/qemu-plugin.mk -- QEMU TCG plugin counting executed guest
# instructions (included by the top-level Makefile after the ARMv7-M targets). No glib needed.
#   make qemu-plugin        build/qemu-plugin/libinsn_count.so
#   make test-qemu-plugin   known-answer + repeatability check
#   port/qemu-plugin/count_insns.sh ELF FUNCTION...   per-function counts
#   make test-qemu-plugin-sparc   the same on SPARC V8 (qemu-user; count_insns.sh with QEMU_USER, NM)
QP_B := $(B)/qemu-plugin
QP_SO := $(QP_B)/libinsn_count.so

.PHONY: qemu-plugin test-qemu-plugin
$(QP_SO): port/qemu-plugin/insn_count.c port/qemu-plugin/qemu_plugin_api.h | apt
	@mkdir -p $(@D)
	gcc -std=gnu11 -O2 -Wall -Wextra -Werror -fPIC -shared -fvisibility=hidden $< -o $@
qemu-plugin: $(QP_SO)

$(QP_B)/known_counts.elf: port/qemu-plugin/known_counts.c $(ARM_RT_OBJ) $(ARM_LDSCRIPT)
	@mkdir -p $(@D)
	$(ARM_CC) -std=gnu99 -Wall -Wextra -Werror -O2 $(ARM_CPU) $< $(ARM_RT_OBJ) \
	  $(ARM_LDFLAGS) $(ARM_LDLIBS) -o $@
test-qemu-plugin: $(QP_SO) $(QP_B)/known_counts.elf
	QEMU_PLUGIN_SO=$(QP_SO) port/qemu-plugin/check_plugin.sh $(QP_B)/known_counts.elf

# The same known answers on SPARC V8 under qemu-user (calls return after their delay slot):
#   make test-qemu-plugin-sparc
$(QP_B)/known_counts_sparc: port/qemu-plugin/known_counts_sparc.c | apt
	@mkdir -p $(@D)
	sparc64-linux-gnu-gcc -m32 -mcpu=v8 -std=gnu99 -Wall -Wextra -Werror -O2 -static $< -o $@
.PHONY: test-qemu-plugin-sparc
test-qemu-plugin-sparc: $(QP_SO) $(QP_B)/known_counts_sparc
	QEMU_PLUGIN_SO=$(QP_SO) QEMU_USER=qemu-sparc32plus NM=sparc64-linux-gnu-nm \
	  TEN=12 CALLS=17 port/qemu-plugin/check_plugin.sh $(QP_B)/known_counts_sparc
