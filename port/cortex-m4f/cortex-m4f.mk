# port/cortex-m4f/cortex-m4f.mk -- bare-metal Cortex-M4F (single-precision FPU only), run on QEMU's
# mps2-an386 board: the ARMv7-M route of port/armv7m/armv7m.mk with the M4F's parameters. Included by
# the top-level Makefile after port/armv7m/armv7m.mk. See docs/guides/ports.md, "Cortex-M4F".
#
#   make m4f-lib             build/m4f/libogk.a (kernel, strict flags, -O2, single precision)
#   make test-unit-m4f       every tests/unit/*/test_*.c on QEMU mps2-an386 (cmocka shim)
#   make test-m4f-selftest   the route's own checks on the M4F (runner, faults, stack overflow, FPU)
#   make m4f-size            code/data size of the kernel objects
#
# Overridable: M4F_UNIT_SRC (which test sources), M4F_TIMEOUT (s per test run).

# The kernel's precision on the M4F (M4F_PRECISION: single or double): the library, the tests, the
# selftest and the consumer are compiled with it, so that they agree on the kernel's types. The CPU flags
# come from cmake/toolchains/cortex-m4f.cmake (-mthumb -mcpu=cortex-m4 -mfpu=fpv4-sp-d16 -mfloat-abi=hard).
# single: the unit tests are precision-aware (tests/unit/ogk_test.h, OGK_TEST_TOL;
# docs/design/precision-unit-tests.md). `make test-unit-m4f M4F_PRECISION=double` runs them on the double
# kernel in software (every double operation a libgcc call), as the board's first gates did.
M4F_PRECISION ?= single
M4F_REAL := $(if $(filter single,$(M4F_PRECISION)),-DOGK_REAL_SINGLE=1)
$(eval $(call armv7m_target,M4F,m4f,cortex-m4f,mps2-an386,$(M4F_REAL)))

.PHONY: m4f-lib test-unit-m4f test-m4f-selftest m4f-size

m4f-lib: $(M4F_B)/libogk.a

m4f-size: $(M4F_B)/libogk.a
	arm-none-eabi-size -t $(M4F_KOBJ)

test-unit-m4f: $(M4F_B)/libogk.a $(M4F_RT_OBJ)
	$(call armv7m_unit_tests,M4F)

test-m4f-selftest: $(M4F_ST_ALL)
	$(call armv7m_selftest,M4F)
