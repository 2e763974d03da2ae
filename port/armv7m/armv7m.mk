# port/armv7m/armv7m.mk -- the bare-metal ARMv7-M route that the Cortex-M7 (port/cortex-m7/cortex-m7.mk)
# and the Cortex-M4F (port/cortex-m4f/cortex-m4f.mk) share: one runtime in port/armv7m (startup, port
# counter, linker script, run script, selftest), the test runner of port/cortex-m7/testrunner, and the
# rules below, which each target instantiates with its own parameters. Included by the top-level
# Makefile before the targets' files (uses its STRICT, KINC, KSRC, KSRC_INC, KHDR, UNIT_SRC, B,
# CMAKE_INPUTS, cmake_kernel, toolchain_cpu). See docs/guides/ports.md.
#
#   $(eval $(call armv7m_target,P,TAG,NAME,BOARD,DEFS))
#     P      prefix of the target's variables (ARM for the Cortex-M7, whose names predate the M4F)
#     TAG    its build directory $(B)/TAG and CMake build $(B)/cmake-TAG
#     NAME   the core: cmake/toolchains/NAME.cmake holds its CPU flags; the runtime's label
#            ("[NAME] FAULT: ...") and ogk_port_name()
#     BOARD  the QEMU machine (qemu-system-arm -M BOARD)
#     DEFS   the kernel's configuration for this target (-DOGK_REAL_SINGLE=1 on the M4F): the library
#            and everything compiled against its headers (tests, selftest) take the same
#   defines P_CPU, P_B, P_DEFS, P_CC, P_KOBJ_FLAGS, P_KFLAGS, P_KOBJ, P_RT_FLAGS, P_RT_OBJ (startup, port
#   counter, test runner), P_BOARD_OBJ (startup and port counter: programs without the runner),
#   P_RT_HDR, P_TEST_CFLAGS, P_LDSCRIPT, P_LDFLAGS, P_LDLIBS, P_TIMEOUT, P_UNIT_SRC, P_ST_ALL; and the
#   file rules: P_B/libogk.a and its objects (CMake), the runtime objects, one ELF per source of
#   P_UNIT_SRC, the selftest's builds.
#   The targets' .mk files name their make goals; the recipes are $(call armv7m_unit_tests,P) and
#   $(call armv7m_selftest,P).
#
# Overridable per target: P_UNIT_SRC (which test sources), P_TIMEOUT (s per test run).

ARMV7M_DIR := port/armv7m
ARMV7M_RUNNER := port/cortex-m7/testrunner
ARMV7M_ST_SRC := $(ARMV7M_DIR)/selftest/test_selftest.c
ARMV7M_ST_HOST_CFLAGS := -std=c99 -Wall -Wextra -Werror -O1 -g -Itests/unit $(KINC) -Iport/include

define armv7m_target
$(1)_NAME := $(3)
$(1)_BOARD := $(4)
$(1)_DEFS := $(5)
# The CPU flags of the flight target, from its CMake toolchain file (the one place they are written).
$(1)_CPU := $$(call toolchain_cpu,$(3))
$(1)_CC := arm-none-eabi-gcc
$(1)_B := $$(B)/$(2)
$(1)_LDSCRIPT := $$(ARMV7M_DIR)/mps2.ld
$(1)_TIMEOUT ?= 300
$(1)_UNIT_SRC ?= $$(UNIT_SRC)

# Kernel: the flight flags, plus -g (addr2line on faults; no code change), per-function sections (the
# link drops what a test does not use) and -fstack-usage ($(1)_B/kernel/*.su: frame size of every
# function). The library is CMake's (CMakeLists.txt) with $(1)_KOBJ_FLAGS; $(1)_KFLAGS is the same
# command line for builds outside CMake (the M7's call graphs).
$(1)_KOBJ_FLAGS := $$(strip -O2 -g -ffunction-sections -fdata-sections -fstack-usage $$($(1)_DEFS))
$(1)_KFLAGS := $$(STRICT) $$($(1)_CPU) $$($(1)_KOBJ_FLAGS)
$(1)_KOBJ := $$(patsubst kernel/src/%.c,$$($(1)_B)/kernel/%.o,$$(KSRC))

# Runtime linked into every test: startup (vectors, reset, faults, heap), port counter, cmocka shim.
$(1)_RT_FLAGS := -std=gnu99 -Wall -Wextra -Werror -Wshadow $$($(1)_CPU) -O2 -g \
  -Iport/include -I$$(ARMV7M_DIR)
$(1)_CORE_DEF := '-DOGK_ARMV7M_CORE="$(3)"'
$(1)_SHIM_FLAGS := -std=c99 -pedantic -Wall -Wextra -Werror -Wconversion -Wshadow \
  $$($(1)_CPU) -O2 -g -I$$(ARMV7M_RUNNER)
$(1)_BOARD_OBJ := $$($(1)_B)/rt/startup.o $$($(1)_B)/rt/ogk_port_armv7m.o
$(1)_RT_OBJ := $$($(1)_BOARD_OBJ) $$($(1)_B)/rt/cmocka_shim.o
$(1)_RT_HDR := $$(ARMV7M_DIR)/ogk_armv7m.h port/include/ogk_port.h $$(ARMV7M_RUNNER)/cmocka.h

# Tests: the same sources and flags as the host (warnings are errors), the kernel's configuration, the
# shim's cmocka.h first on the include path.
$(1)_TEST_CFLAGS := $$(strip -std=c99 -Wall -Wextra -Werror -O2 -g $$($(1)_CPU) $$($(1)_DEFS)) \
  -I$$(ARMV7M_RUNNER) -Itests/unit $$(KINC) -Iport/include -I$$(ARMV7M_DIR)
$(1)_LDFLAGS := $$($(1)_CPU) --specs=rdimon.specs -T $$($(1)_LDSCRIPT) -Wl,--gc-sections
$(1)_LDLIBS := -lm

# ---------------------------------------------------------------- kernel library
# Built by CMake with cmake/toolchains/$(3).cmake, staged with its objects and .su files; rebuilt when its
# definitions change (defs.stamp: e.g. `make test-unit-m4f M4F_PRECISION=double` after a single build).
$$($(1)_B)/libogk.a $$($(1)_KOBJ) &: $$(CMAKE_INPUTS) $$($(1)_B)/defs.stamp | apt
	$$(call cmake_kernel,$(2),$(3),$$($(1)_KOBJ_FLAGS),$$($(1)_B))
$$($(1)_B)/defs.stamp: armv7m-force
	@mkdir -p $$(@D); echo '$$($(1)_DEFS)' | cmp -s - $$@ || echo '$$($(1)_DEFS)' > $$@

# ---------------------------------------------------------------- runtime
$$($(1)_B)/rt/startup.o: $$(ARMV7M_DIR)/startup.c $$($(1)_RT_HDR) | apt
	@mkdir -p $$(@D)
	$$($(1)_CC) $$($(1)_RT_FLAGS) $$($(1)_CORE_DEF) -c $$< -o $$@
$$($(1)_B)/rt/ogk_port_armv7m.o: $$(ARMV7M_DIR)/ogk_port_armv7m.c $$($(1)_RT_HDR) | apt
	@mkdir -p $$(@D)
	$$($(1)_CC) $$($(1)_RT_FLAGS) $$($(1)_CORE_DEF) -c $$< -o $$@
$$($(1)_B)/rt/cmocka_shim.o: $$(ARMV7M_RUNNER)/cmocka_shim.c $$($(1)_RT_HDR) | apt
	@mkdir -p $$(@D)
	$$($(1)_CC) $$($(1)_SHIM_FLAGS) -c $$< -o $$@

# ---------------------------------------------------------------- unit tests on QEMU
# One rule per source ($(1)_UNIT_SRC may name files outside tests/unit).
$$(foreach src,$$($(1)_UNIT_SRC),$$(eval $$(call armv7m_test_rule,$(1),$$(src))))

# ---------------------------------------------------------------- selftest of the route
$(1)_ST_B := $$($(1)_B)/selftest
$(1)_ST_DEPS := $$(ARMV7M_ST_SRC) tests/unit/ogk_test.h $$($(1)_RT_OBJ) $$($(1)_LDSCRIPT)
$$($(1)_ST_B)/test_selftest.elf: $$($(1)_ST_DEPS)
	@mkdir -p $$(@D)
	$$($(1)_CC) $$($(1)_TEST_CFLAGS) $$< $$($(1)_RT_OBJ) $$($(1)_LDFLAGS) $$($(1)_LDLIBS) -o $$@
$$($(1)_ST_B)/test_selftest_inject_failures.elf: $$($(1)_ST_DEPS)
	@mkdir -p $$(@D)
	$$($(1)_CC) $$($(1)_TEST_CFLAGS) -DOGK_SELFTEST_INJECT_FAILURES $$< $$($(1)_RT_OBJ) \
	  $$($(1)_LDFLAGS) $$($(1)_LDLIBS) -o $$@
$$($(1)_ST_B)/test_selftest_inject_fault.elf: $$($(1)_ST_DEPS)
	@mkdir -p $$(@D)
	$$($(1)_CC) $$($(1)_TEST_CFLAGS) -DOGK_SELFTEST_INJECT_FAULT $$< $$($(1)_RT_OBJ) \
	  $$($(1)_LDFLAGS) $$($(1)_LDLIBS) -o $$@
$$($(1)_ST_B)/test_selftest_inject_overflow.elf: $$($(1)_ST_DEPS)
	@mkdir -p $$(@D)
	$$($(1)_CC) $$($(1)_TEST_CFLAGS) -DOGK_SELFTEST_INJECT_OVERFLOW $$< $$($(1)_RT_OBJ) \
	  $$($(1)_LDFLAGS) $$($(1)_LDLIBS) -o $$@
$$($(1)_ST_B)/inject_failures.i: $$(ARMV7M_ST_SRC) tests/unit/ogk_test.h
	@mkdir -p $$(@D)
	$$($(1)_CC) $$($(1)_TEST_CFLAGS) -DOGK_SELFTEST_INJECT_FAILURES -E $$< -o $$@
# The same injected-failure source on the host: real cmocka vs the shim.
$$($(1)_ST_B)/host_cmocka: $$(ARMV7M_ST_SRC) tests/unit/ogk_test.h port/host/ogk_port_host.c \
  port/include/ogk_port.h | apt
	@mkdir -p $$(@D)
	gcc $$(ARMV7M_ST_HOST_CFLAGS) -DOGK_SELFTEST_INJECT_FAILURES $$< port/host/ogk_port_host.c \
	  -o $$@ -lcmocka -lm
$$($(1)_ST_B)/host_shim: $$(ARMV7M_ST_SRC) tests/unit/ogk_test.h port/host/ogk_port_host.c \
  port/include/ogk_port.h $$(ARMV7M_RUNNER)/cmocka_shim.c $$(ARMV7M_RUNNER)/cmocka.h | apt
	@mkdir -p $$(@D)
	gcc $$(ARMV7M_ST_HOST_CFLAGS) -I$$(ARMV7M_RUNNER) -DOGK_SELFTEST_INJECT_FAILURES $$< \
	  port/host/ogk_port_host.c $$(ARMV7M_RUNNER)/cmocka_shim.c -o $$@ -lm
$(1)_ST_ALL := $$($(1)_ST_B)/test_selftest.elf $$($(1)_ST_B)/test_selftest_inject_failures.elf \
  $$($(1)_ST_B)/test_selftest_inject_fault.elf $$($(1)_ST_B)/test_selftest_inject_overflow.elf \
  $$($(1)_ST_B)/host_cmocka $$($(1)_ST_B)/host_shim $$($(1)_ST_B)/inject_failures.i
endef

# $(call armv7m_test_rule,P,SOURCE): the ELF of one test source.
define armv7m_test_rule
$$($(1)_B)/$$(basename $$(notdir $(2))).elf: $(2) $$(wildcard tests/unit/*.h) $$($(1)_RT_OBJ) $$($(1)_B)/libogk.a \
  $$($(1)_LDSCRIPT)
	$$($(1)_CC) $$($(1)_TEST_CFLAGS) $$< $$($(1)_RT_OBJ) $$($(1)_B)/libogk.a \
	  $$($(1)_LDFLAGS) -Wl,-Map=$$(@:.elf=.map) $$($(1)_LDLIBS) -o $$@
endef

# The environment of the route's scripts (run_qemu.sh, check_selftest.sh) for target P.
armv7m_env = TARGET_NAME=$($(1)_NAME) QEMU_MACHINE=$($(1)_BOARD)

# Recipe of test-unit-<target>: builds and runs every test even when one fails, then fails if any test did
# not build, failed, faulted or timed out. The kernel library must build.
armv7m_unit_tests = @pass=0; fail=0; nobuild=0; failed=""; \
	for src in $($(1)_UNIT_SRC); do \
	  t=$$(basename $$src .c); elf=$($(1)_B)/$$t.elf; \
	  if ! $(MAKE) --no-print-directory -s $$elf $(1)_UNIT_SRC="$($(1)_UNIT_SRC)"; then \
	    echo "== $($(1)_NAME) (qemu $($(1)_BOARD)): $$t"; echo "-- $$t: DID NOT BUILD for $($(1)_NAME)"; \
	    nobuild=$$((nobuild + 1)); failed="$$failed $$t(build)"; continue; fi; \
	  if $(call armv7m_env,$(1)) $(ARMV7M_DIR)/run_qemu.sh $$elf $($(1)_TIMEOUT); then pass=$$((pass + 1)); \
	  else fail=$$((fail + 1)); failed="$$failed $$t"; fi; \
	done; \
	echo "== $($(1)_NAME) summary: $$pass passed, $$fail failed, $$nobuild did not build$${failed:+ (}$${failed\# }$${failed:+)}"; \
	[ $$fail -eq 0 ] && [ $$nobuild -eq 0 ]

# Recipe of the selftest goal (test-arm-selftest, test-m4f-selftest): judges the runs of $(1)_ST_ALL.
armv7m_selftest = $(call armv7m_env,$(1)) SELFTEST_GOAL=$@ $(ARMV7M_DIR)/selftest/check_selftest.sh \
	$($(1)_ST_ALL)

# a prerequisite that is always out of date (the stamps compare their contents themselves)
.PHONY: armv7m-force
armv7m-force:
