# port/cortex-m7/cortex-m7.mk -- bare-metal Cortex-M7 build, run on QEMU's
# mps2-an500 board: the ARMv7-M route of port/armv7m/armv7m.mk with the M7's
# parameters, and what only the M7 has (call-graph stack report; the flight app,
# the PIL link and programs in their own .mk files). Included by the top-level
# Makefile after port/armv7m/armv7m.mk. See docs/guides/ports.md.
#
#   make arm-lib             build/arm/libogk.a (kernel, strict flags, -O2)
#   make test-unit-arm       every tests/unit/*/test_*.c on QEMU (cmocka shim)
#   make test-arm-selftest   checks of this route itself (runner, faults, FPU)
#   make arm-size            code/data size of the kernel objects
#   make arm-stack           worst-case stack per entry point from gcc's call graphs
#
# Overridable: ARM_UNIT_SRC (which test sources), ARM_TIMEOUT (s per test run).

# Counter abstraction for tests and benchmarks (port/include/ogk_port.h):
# host programs compile $(PORT_HOST_SRC); ARM programs link $(ARM_RT_OBJ).
PORT_INC := -Iport/include
PORT_HOST_SRC := port/host/ogk_port_host.c

# The M7's own sources: the flight app, the PIL link and programs (port/cortex-m7/*/).
ARM_PORT := port/cortex-m7

# The CPU flags come from cmake/toolchains/cortex-m7.cmake (-mthumb -mcpu=cortex-m7 -mfpu=fpv5-d16
# -mfloat-abi=hard); the kernel in double precision, its configuration's default.
$(eval $(call armv7m_target,ARM,arm,cortex-m7,mps2-an500,))

.PHONY: arm-lib test-unit-arm test-arm-selftest arm-size

arm-lib: $(ARM_B)/libogk.a

arm-size: $(ARM_B)/libogk.a
	arm-none-eabi-size -t $(ARM_KOBJ)

test-unit-arm: $(ARM_B)/libogk.a $(ARM_RT_OBJ)
	$(call armv7m_unit_tests,ARM)

test-arm-selftest: $(ARM_ST_ALL)
	$(call armv7m_selftest,ARM)

# ---------------------------------------------------------------- stack and recursion evidence
# gcc's call graphs (-fcallgraph-info=su) of every kernel source for the Cortex-M7 build: worst-case
# stack per ogk_* entry point, and a failure on any recursion or non-static frame.
ARM_CG := $(ARM_B)/callgraph
ARM_CI := $(patsubst kernel/src/%.c,$(ARM_CG)/%.ci,$(KSRC))
$(ARM_CG)/%.ci: kernel/src/%.c $(KHDR) | apt
	@mkdir -p $(@D)
	$(ARM_CC) $(ARM_KFLAGS) $(KINC) $(KSRC_INC) -fcallgraph-info=su -dumpdir $(@D)/ -dumpbase $(notdir $*) -c $< -o $(ARM_CG)/$*.o
.PHONY: arm-stack
arm-stack: $(ARM_CI) $(ARM_KOBJ)
	python3 port/cortex-m7/stack_report.py --objdump arm-none-eabi-objdump --objects $(ARM_KOBJ) -- $(ARM_CI)
