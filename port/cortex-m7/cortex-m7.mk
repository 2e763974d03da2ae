# port/cortex-m7/cortex-m7.mk -- bare-metal Cortex-M7 build, run on QEMU's
# mps2-an500 board (included by the top-level Makefile; uses its STRICT,
# KINC, KSRC, KSRC_INC, KHDR, UNIT_SRC, B). See docs/guides/ports.md.
#
#   make arm-lib             build/arm/libogk.a (kernel, strict flags, -O2)
#   make test-unit-arm       every tests/unit/*/test_*.c on QEMU (cmocka shim)
#   make test-arm-selftest   checks of this route itself (runner, faults, FPU)
#   make arm-size            code/data size of the kernel objects
#   make qemu-plugin         build/qemu-plugin/libinsn_count.so (instruction counts)
#
# Overridable: ARM_UNIT_SRC (which test sources), ARM_TIMEOUT (s per test run).

# The CPU flags of the flight target, from its CMake toolchain file (the one place they are written):
# -mthumb -mcpu=cortex-m7 -mfpu=fpv5-d16 -mfloat-abi=hard.
ARM_CPU := $(call toolchain_cpu,cortex-m7)

# Counter abstraction for tests and benchmarks (port/include/ogk_port.h):
# host programs compile $(PORT_HOST_SRC); ARM programs link $(ARM_RT_OBJ).
PORT_INC := -Iport/include
PORT_HOST_SRC := port/host/ogk_port_host.c

ARM_CC := arm-none-eabi-gcc
ARM_PORT := port/cortex-m7
ARM_B := $(B)/arm
ARM_LDSCRIPT := $(ARM_PORT)/mps2-an500.ld
ARM_TIMEOUT ?= 300
ARM_UNIT_SRC ?= $(UNIT_SRC)

# Kernel: the flight flags, plus -g (addr2line on faults; no code change),
# per-function sections (the link drops what a test does not use) and
# -fstack-usage (build/arm/kernel/*.su: frame size of every function).
# The library is CMake's (CMakeLists.txt) with ARM_KOBJ_FLAGS; ARM_KFLAGS is
# the same command line for the call-graph build below.
ARM_KOBJ_FLAGS := -O2 -g -ffunction-sections -fdata-sections -fstack-usage
ARM_KFLAGS := $(STRICT) $(ARM_CPU) $(ARM_KOBJ_FLAGS)
ARM_KOBJ := $(patsubst kernel/src/%.c,$(ARM_B)/kernel/%.o,$(KSRC))

# Runtime linked into every test: startup (vectors, reset, faults, heap),
# port counter, cmocka shim.
ARM_RT_FLAGS := -std=gnu99 -Wall -Wextra -Werror -Wshadow $(ARM_CPU) -O2 -g \
  -Iport/include -I$(ARM_PORT)
ARM_SHIM_FLAGS := -std=c99 -pedantic -Wall -Wextra -Werror -Wconversion -Wshadow \
  $(ARM_CPU) -O2 -g -I$(ARM_PORT)/testrunner
ARM_RT_OBJ := $(ARM_B)/rt/startup.o $(ARM_B)/rt/ogk_port_cm7.o $(ARM_B)/rt/cmocka_shim.o
ARM_RT_HDR := $(ARM_PORT)/ogk_cm7.h port/include/ogk_port.h $(ARM_PORT)/testrunner/cmocka.h

# Tests: the same sources and flags as the host (warnings are errors), with
# the shim's cmocka.h first on the include path.
ARM_TEST_CFLAGS := -std=c99 -Wall -Wextra -Werror -O2 -g $(ARM_CPU) \
  -I$(ARM_PORT)/testrunner -Itests/unit $(KINC) -Iport/include -I$(ARM_PORT)
ARM_LDFLAGS := $(ARM_CPU) --specs=rdimon.specs -T $(ARM_LDSCRIPT) -Wl,--gc-sections
ARM_LDLIBS := -lm

.PHONY: arm-lib test-unit-arm test-arm-selftest arm-size

# ---------------------------------------------------------------- kernel library
# Built by CMake with cmake/toolchains/cortex-m7.cmake, staged with its objects and .su files.
$(ARM_B)/libogk.a $(ARM_KOBJ) &: $(CMAKE_INPUTS) | apt
	$(call cmake_kernel,arm,cortex-m7,$(ARM_KOBJ_FLAGS),$(ARM_B))

arm-lib: $(ARM_B)/libogk.a

arm-size: $(ARM_B)/libogk.a
	arm-none-eabi-size -t $(ARM_KOBJ)

# ---------------------------------------------------------------- runtime
$(ARM_B)/rt/startup.o: $(ARM_PORT)/startup.c $(ARM_RT_HDR) | apt
	@mkdir -p $(@D)
	$(ARM_CC) $(ARM_RT_FLAGS) -c $< -o $@
$(ARM_B)/rt/ogk_port_cm7.o: $(ARM_PORT)/ogk_port_cm7.c $(ARM_RT_HDR) | apt
	@mkdir -p $(@D)
	$(ARM_CC) $(ARM_RT_FLAGS) -c $< -o $@
$(ARM_B)/rt/cmocka_shim.o: $(ARM_PORT)/testrunner/cmocka_shim.c $(ARM_RT_HDR) | apt
	@mkdir -p $(@D)
	$(ARM_CC) $(ARM_SHIM_FLAGS) -c $< -o $@

# ---------------------------------------------------------------- unit tests on QEMU
# One rule per source (ARM_UNIT_SRC may name files outside tests/unit).
define ARM_TEST_RULE
$(ARM_B)/$(basename $(notdir $(1))).elf: $(1) $(wildcard tests/unit/*.h) $(ARM_RT_OBJ) $(ARM_B)/libogk.a $(ARM_LDSCRIPT)
	$(ARM_CC) $(ARM_TEST_CFLAGS) $$< $(ARM_RT_OBJ) $(ARM_B)/libogk.a \
	  $(ARM_LDFLAGS) -Wl,-Map=$$(@:.elf=.map) $(ARM_LDLIBS) -o $$@
endef
$(foreach src,$(ARM_UNIT_SRC),$(eval $(call ARM_TEST_RULE,$(src))))

# Builds and runs every test even when one fails, then fails if any test did
# not build, failed, faulted or timed out. The kernel library must build.
test-unit-arm: $(ARM_B)/libogk.a $(ARM_RT_OBJ)
	@pass=0; fail=0; nobuild=0; failed=""; \
	for src in $(ARM_UNIT_SRC); do \
	  t=$$(basename $$src .c); elf=$(ARM_B)/$$t.elf; \
	  if ! $(MAKE) --no-print-directory -s $$elf ARM_UNIT_SRC="$(ARM_UNIT_SRC)"; then \
	    echo "== cortex-m7 (qemu mps2-an500): $$t"; echo "-- $$t: DID NOT BUILD for cortex-m7"; \
	    nobuild=$$((nobuild + 1)); failed="$$failed $$t(build)"; continue; fi; \
	  if $(ARM_PORT)/run_qemu.sh $$elf $(ARM_TIMEOUT); then pass=$$((pass + 1)); \
	  else fail=$$((fail + 1)); failed="$$failed $$t"; fi; \
	done; \
	echo "== cortex-m7 summary: $$pass passed, $$fail failed, $$nobuild did not build$${failed:+ (}$${failed# }$${failed:+)}"; \
	[ $$fail -eq 0 ] && [ $$nobuild -eq 0 ]

# ---------------------------------------------------------------- selftest of the route
ST_SRC := $(ARM_PORT)/selftest/test_selftest.c
ST_B := $(ARM_B)/selftest
ST_DEPS := $(ST_SRC) tests/unit/ogk_test.h $(ARM_RT_OBJ) $(ARM_LDSCRIPT)
ST_HOST_CFLAGS := -std=c99 -Wall -Wextra -Werror -O1 -g -Itests/unit -Iport/include

$(ST_B)/test_selftest.elf: $(ST_DEPS)
	@mkdir -p $(@D)
	$(ARM_CC) $(ARM_TEST_CFLAGS) $< $(ARM_RT_OBJ) $(ARM_LDFLAGS) $(ARM_LDLIBS) -o $@
$(ST_B)/test_selftest_inject_failures.elf: $(ST_DEPS)
	@mkdir -p $(@D)
	$(ARM_CC) $(ARM_TEST_CFLAGS) -DOGK_SELFTEST_INJECT_FAILURES $< $(ARM_RT_OBJ) \
	  $(ARM_LDFLAGS) $(ARM_LDLIBS) -o $@
$(ST_B)/test_selftest_inject_fault.elf: $(ST_DEPS)
	@mkdir -p $(@D)
	$(ARM_CC) $(ARM_TEST_CFLAGS) -DOGK_SELFTEST_INJECT_FAULT $< $(ARM_RT_OBJ) \
	  $(ARM_LDFLAGS) $(ARM_LDLIBS) -o $@
$(ST_B)/test_selftest_inject_overflow.elf: $(ST_DEPS)
	@mkdir -p $(@D)
	$(ARM_CC) $(ARM_TEST_CFLAGS) -DOGK_SELFTEST_INJECT_OVERFLOW $< $(ARM_RT_OBJ) \
	  $(ARM_LDFLAGS) $(ARM_LDLIBS) -o $@
$(ST_B)/inject_failures.i: $(ST_SRC) tests/unit/ogk_test.h
	@mkdir -p $(@D)
	$(ARM_CC) $(ARM_TEST_CFLAGS) -DOGK_SELFTEST_INJECT_FAILURES -E $< -o $@
# The same injected-failure source on the host: real cmocka vs the shim.
$(ST_B)/host_cmocka: $(ST_SRC) tests/unit/ogk_test.h port/host/ogk_port_host.c port/include/ogk_port.h | apt
	@mkdir -p $(@D)
	gcc $(ST_HOST_CFLAGS) -DOGK_SELFTEST_INJECT_FAILURES $< port/host/ogk_port_host.c \
	  -o $@ -lcmocka -lm
$(ST_B)/host_shim: $(ST_SRC) tests/unit/ogk_test.h port/host/ogk_port_host.c port/include/ogk_port.h \
  $(ARM_PORT)/testrunner/cmocka_shim.c $(ARM_PORT)/testrunner/cmocka.h | apt
	@mkdir -p $(@D)
	gcc $(ST_HOST_CFLAGS) -I$(ARM_PORT)/testrunner -DOGK_SELFTEST_INJECT_FAILURES $< \
	  port/host/ogk_port_host.c $(ARM_PORT)/testrunner/cmocka_shim.c -o $@ -lm

ST_ALL := $(ST_B)/test_selftest.elf $(ST_B)/test_selftest_inject_failures.elf \
  $(ST_B)/test_selftest_inject_fault.elf $(ST_B)/test_selftest_inject_overflow.elf \
  $(ST_B)/host_cmocka $(ST_B)/host_shim $(ST_B)/inject_failures.i

test-arm-selftest: $(ST_ALL)
	$(ARM_PORT)/selftest/check_selftest.sh $(ST_ALL)

# ---------------------------------------------------------------- QEMU instruction counter
-include port/qemu-plugin/qemu-plugin.mk

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
