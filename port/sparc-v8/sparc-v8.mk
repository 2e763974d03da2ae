# port/sparc-v8/sparc-v8.mk -- 32-bit big-endian SPARC V8 (LEON3/GR740's ISA) under QEMU user mode
# (included by the top-level Makefile after cortex-m7.mk and flightapp.mk; uses their STRICT, KINC,
# KSRC, KHDR, UNIT_SRC, B, ARM_PORT and FA_* variables). See docs/guides/ports.md, "SPARC V8".
#
#   make sparc-lib               build/sparc/libogk.a (kernel, strict flags, -O2)
#   make test-unit-sparc         every tests/unit/*/test_*.c, static, run with qemu-sparc32plus
#   make test-flight-app-sparc   the flight app (port/cortex-m7/flightapp) built for SPARC V8, table
#                                decoded into RAM (OGK_FLIGHT_TABLE_COPY=1: the in-place view answers
#                                OGK_E_BYTE_ORDER there); its injection errors compared with the host's
#   make test-flt-eval           an x87 build (gcc -mfpmath=387: FLT_EVAL_METHOD 2) of the kernel is
#                                refused by ogk/status.h's #error; the SSE build is accepted
#
# Debian 12: gcc-sparc64-linux-gnu libc6-dev-sparc-sparc64-cross (-m32 -mcpu=v8 links Debian's
# 32-bit SPARC libc, built for v8plus, hence qemu-sparc32plus; qemu-user). The test runner is the
# M7's cmocka shim (portable C99 + stdio), the port counter the host's (POSIX clock_gettime).
# Overridable: SPARC_UNIT_SRC (which test sources), SPARC_TIMEOUT (s per test run).

SPARC_CC := sparc64-linux-gnu-gcc
SPARC_CPU := $(call toolchain_cpu,sparc-v8)
SPARC_QEMU := qemu-sparc32plus
SPARC_PORT := port/sparc-v8
SPARC_B := $(B)/sparc
SPARC_TIMEOUT ?= 300
SPARC_UNIT_SRC ?= $(UNIT_SRC)

# Kernel: the flight flags (the cross gcc 12.2 defines FLT_EVAL_METHOD 0 and __BYTE_ORDER__ big).
# -fstack-usage: build/sparc/kernel/*.su, gcc's frame of every function, against which the stack bound
# (port/profile, make stack-bound-sparc) checks its reading of the disassembly.
# The library is CMake's (CMakeLists.txt, cmake/toolchains/sparc-v8.cmake: -m32 -mcpu=v8) with these.
SPARC_KOBJ_FLAGS := -O2 -g -fstack-usage
SPARC_KOBJ := $(patsubst kernel/src/%.c,$(SPARC_B)/kernel/%.o,$(KSRC))

# Runtime linked into every test: the cmocka shim and the host port counter.
SPARC_RT_OBJ := $(SPARC_B)/rt/cmocka_shim.o $(SPARC_B)/rt/ogk_port_host.o
SPARC_TEST_CFLAGS := -std=c99 -Wall -Wextra -Werror -O2 -g $(SPARC_CPU) \
  -I$(ARM_PORT)/testrunner -Itests/unit $(KINC) -Iport/include
SPARC_LDFLAGS := $(SPARC_CPU) -static
SPARC_LDLIBS := -lm

.PHONY: sparc-lib test-unit-sparc test-flight-app-sparc test-flt-eval

$(SPARC_B)/libogk.a $(SPARC_KOBJ) &: $(CMAKE_INPUTS) | apt
	$(call cmake_kernel,sparc,sparc-v8,$(SPARC_KOBJ_FLAGS),$(SPARC_B))
sparc-lib: $(SPARC_B)/libogk.a

$(SPARC_B)/rt/cmocka_shim.o: $(ARM_PORT)/testrunner/cmocka_shim.c $(ARM_PORT)/testrunner/cmocka.h | apt
	@mkdir -p $(@D)
	$(SPARC_CC) -std=c99 -pedantic -Wall -Wextra -Werror -Wconversion -Wshadow $(SPARC_CPU) -O2 -g \
	  -I$(ARM_PORT)/testrunner -c $< -o $@
$(SPARC_B)/rt/ogk_port_host.o: port/host/ogk_port_host.c port/include/ogk_port.h | apt
	@mkdir -p $(@D)
	$(SPARC_CC) -std=c99 -Wall -Wextra -Werror $(SPARC_CPU) -O2 -g -Iport/include -c $< -o $@

# ---------------------------------------------------------------- unit tests under qemu-sparc32plus
define SPARC_TEST_RULE
$(SPARC_B)/$(basename $(notdir $(1))): $(1) $(wildcard tests/unit/*.h) $(SPARC_RT_OBJ) $(SPARC_B)/libogk.a
	$(SPARC_CC) $(SPARC_TEST_CFLAGS) $$< $(SPARC_RT_OBJ) $(SPARC_B)/libogk.a $(SPARC_LDFLAGS) \
	  $(SPARC_LDLIBS) -o $$@
endef
$(foreach src,$(SPARC_UNIT_SRC),$(eval $(call SPARC_TEST_RULE,$(src))))

# Builds and runs every test even when one fails, then fails if any test did not build, failed or
# timed out (the exit code of a cmocka group is its number of failed tests).
test-unit-sparc: $(SPARC_B)/libogk.a $(SPARC_RT_OBJ)
	@pass=0; fail=0; nobuild=0; failed=""; \
	for src in $(SPARC_UNIT_SRC); do \
	  t=$$(basename $$src .c); exe=$(SPARC_B)/$$t; \
	  echo "== sparc-v8 (qemu-sparc32plus): $$t"; \
	  if ! $(MAKE) --no-print-directory -s $$exe SPARC_UNIT_SRC="$(SPARC_UNIT_SRC)"; then \
	    echo "-- $$t: DID NOT BUILD for sparc-v8"; \
	    nobuild=$$((nobuild + 1)); failed="$$failed $$t(build)"; continue; fi; \
	  timeout --kill-after=5 $(SPARC_TIMEOUT) $(SPARC_QEMU) $$exe 2>&1 < /dev/null; rc=$$?; \
	  if [ $$rc -eq 0 ]; then pass=$$((pass + 1)); \
	  else echo "-- $$t: exit $$rc"; fail=$$((fail + 1)); failed="$$failed $$t"; fi; \
	done; \
	echo "== sparc-v8 summary: $$pass passed, $$fail failed, $$nobuild did not build$${failed:+ (}$${failed# }$${failed:+)}"; \
	[ $$fail -eq 0 ] && [ $$nobuild -eq 0 ]

# ---------------------------------------------------------------- flight application
# The Cortex-M7's flight app (port/cortex-m7/flightapp: ogk_flight.c, main.c, the generated table
# image and configurations of `ogk tables leo-geo`) built for SPARC V8 with the table decoded into RAM
# (OGK_FLIGHT_TABLE_COPY=1: the same CRC'd little-endian image as every target, decoded value by value
# by ogk_nog_table_load; the in-place view answers OGK_E_BYTE_ORDER here, which the app checks). Its
# injection errors are compared with the host build's (FA_HOST, table read in place) to
# SPARC_FA_TOL: both run IEEE-754 binary64 with round-to-nearest and no contraction (SPARC V8 has no
# FMA, x86-64 -O2 without -march none), and glibc's libm on both; measured 0 in every printed digit.
SPARC_FA_B := $(SPARC_B)/flightapp
SPARC_FA := $(SPARC_FA_B)/flightapp
SPARC_FA_TOL ?= 1e-6
$(SPARC_FA): $(FA_SRC) $(FA_HDR) $(FA_GEN_C) $(FA_GEN_H) $(SPARC_B)/libogk.a | apt
	@mkdir -p $(@D)
	$(SPARC_CC) $(STRICT) $(SPARC_CPU) -O2 -g -DOGK_FLIGHT_TABLE_COPY=1 $(KINC) -I$(FA_GEN) -I$(FA_DIR) \
	  $(FA_SRC) $(FA_GEN_C) $(SPARC_B)/libogk.a $(SPARC_LDFLAGS) $(SPARC_LDLIBS) -o $@

test-flight-app-sparc: $(SPARC_FA) $(FA_HOST)
	@timeout --kill-after=5 $(SPARC_TIMEOUT) $(SPARC_QEMU) $(SPARC_FA) > $(SPARC_FA_B)/flightapp.log 2>&1 \
	  < /dev/null; rc=$$?; \
	cat $(SPARC_FA_B)/flightapp.log; \
	if [ $$rc -ne 0 ] || ! grep -q '^flightapp: PASS' $(SPARC_FA_B)/flightapp.log; then \
	  echo "test-flight-app-sparc: FAILED (exit $$rc)"; exit 1; fi; \
	$(FA_HOST) > $(SPARC_FA_B)/flightapp_host.log 2>&1 || { cat $(SPARC_FA_B)/flightapp_host.log; \
	  echo "test-flight-app-sparc: FAILED (host build)"; exit 1; }; \
	python3 $(FA_DIR)/compare_runs.py --tol $(SPARC_FA_TOL) $(SPARC_FA_B)/flightapp.log \
	  $(SPARC_FA_B)/flightapp_host.log

# ---------------------------------------------------------------- FLT_EVAL_METHOD guard
# ogk/status.h refuses excess-precision evaluation (#error). Checked with gcc's x87 code generation
# on x86-64 (-mfpmath=387 gives FLT_EVAL_METHOD 2; `gcc -m32` needs gcc-multilib, which conflicts
# with the cross compilers): every kernel source must fail with the guard's message, and the same
# sources with -mfpmath=sse (FLT_EVAL_METHOD 0) must compile.
FLT_EVAL_B := $(B)/flt-eval
test-flt-eval: | apt
	@mkdir -p $(FLT_EVAL_B); bad=""; \
	for src in $(KSRC); do \
	  if gcc $(STRICT) -mfpmath=387 $(KINC) $(KSRC_INC) -c $$src -o $(FLT_EVAL_B)/x87.o \
	       > $(FLT_EVAL_B)/x87.log 2>&1; then bad="$$bad $$src(accepted)"; \
	  elif ! grep -q 'ogk needs FLT_EVAL_METHOD == 0' $(FLT_EVAL_B)/x87.log; then \
	    bad="$$bad $$src(other error)"; fi; \
	  gcc $(STRICT) -mfpmath=sse $(KINC) $(KSRC_INC) -c $$src -o $(FLT_EVAL_B)/sse.o || bad="$$bad $$src(sse)"; \
	done; \
	if [ -n "$$bad" ]; then echo "test-flt-eval: FAILED:$$bad"; exit 1; fi; \
	echo "test-flt-eval: the x87 build (FLT_EVAL_METHOD 2) of all $(words $(KSRC)) kernel sources is refused, the SSE build accepted"
