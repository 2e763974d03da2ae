# ogk -- top-level build. `make run` (main job) and `make test` (every test)
# install what they need themselves, idempotently (Debian 12, as root).
SHELL := /bin/bash
.DEFAULT_GOAL := all
# Keep intermediate objects (sanitizer builds of the kernel) between links.
.SECONDARY:

# ---------------------------------------------------------------- setup
APT_PKGS := build-essential valgrind clang clang-tidy libclang-rt-14-dev \
  clang-19 llvm-19 libclang-rt-19-dev \
  libcmocka-dev cppcheck gcovr libeigen3-dev gcc-arm-none-eabi \
  libnewlib-arm-none-eabi binutils-arm-none-eabi qemu-system-arm qemu-user \
  python3-venv pkg-config gcc-sparc64-linux-gnu libc6-dev-sparc-sparc64-cross \
  lib32gcc-12-dev-sparc64-cross frama-c-base cmake
PYTHON ?= python3
VENV := .venv
VPY := $(VENV)/bin/python

.PHONY: deps apt venv
deps: apt venv

# Installs only the missing Debian packages; a failing `apt-get update`
# (mirror sync) is tolerated and the install decides.
apt:
	@missing=$$(for p in $(APT_PKGS); do \
	  dpkg-query -W -f='$${Status}' $$p 2>/dev/null | grep -q 'ok installed' || echo $$p; done); \
	if [ -n "$$missing" ]; then \
	  echo "apt: installing $$missing"; \
	  if [ "$$(id -u)" != 0 ]; then echo "apt: need root to install: $$missing" >&2; exit 1; fi; \
	  apt-get update -q || true; \
	  DEBIAN_FRONTEND=noninteractive apt-get install -y -q --no-install-recommends $$missing; \
	fi

# The package in editable mode (setup.py compiles the kernel's extensions in place, as `make ffi` does),
# with every extra the tests use: Basilisk (test_basilisk), Dask (test_dask_executor), DAQP (make bench).
venv: $(VENV)/.installed
$(VENV)/.installed: pyproject.toml setup.py kernel/include/ogk/version.h | apt
	test -x $(VPY) || $(PYTHON) -m venv $(VENV)
	$(VPY) -m pip install -q --upgrade pip
	$(VPY) -m pip install -q -e '.[test,peers,dask,basilisk]'
	touch $@

# ---------------------------------------------------------------- flags
STRICT := -std=c99 -pedantic -Wall -Wextra -Werror -Wconversion \
  -Wdouble-promotion -Wshadow
KINC := -Ikernel/include
# The kernel's sources by module, kernel/src/<module>/*.c (docs/design/architecture.md, "Kernel source layout"),
# and the internal headers the modules share, kernel/src/*.h, which the modules include by relative path
# ("../ogk_checks.h"): a flight project compiles the kernel with kernel/include alone (make lint checks it).
# KSRC_INC stays for the tools that read the sources as a set.
KSRC := $(sort $(wildcard kernel/src/*.c) $(wildcard kernel/src/*/*.c))
KSRC_INC := -Ikernel/src
KHDR := $(wildcard kernel/include/ogk/*.h) $(wildcard kernel/include/ogk/internal/*.h) $(wildcard kernel/src/*.h) \
  $(wildcard kernel/src/*/*.h)
SAN := -fsanitize=address,undefined -fno-sanitize-recover=all -fno-omit-frame-pointer
B := build
# A command under an exclusive lock, shared with the Python tests that make the same target
# (tests/python/pil_checks.py: locked_make)
locked = mkdir -p $(B) && flock $(B)/.lock-$(1)

# ---------------------------------------------------------------- kernel libraries (CMake)
# CMakeLists.txt is the one description of how the kernel compiles (docs/guides/cmake.md): make configures and
# builds it per target in $(B)/cmake-<target> with that target's toolchain file and the flags its
# evidence needs (OGK_C_FLAGS: -O2, plus -g and -fstack-usage on the flight targets), then stages the
# library, its objects and their .su files where the rules below read them (cmake/stage.sh).
# CMAKE_BUILD clears the make variables: CMake's own make is not a child of this one (no job server).
CMAKE_BUILD := env -u MAKEFLAGS -u MFLAGS -u MAKELEVEL cmake --build
CMAKE_INPUTS := CMakeLists.txt $(wildcard cmake/*.cmake cmake/*.in cmake/*.sh cmake/toolchains/*.cmake) \
  $(KSRC) $(KHDR)
# $(call cmake_kernel,NAME,TOOLCHAIN,OGK_C_FLAGS,STAGE_DIR). CMake reads a toolchain file at the first
# configure only: a build directory older than its toolchain file is configured afresh. The precision is
# the flags' (OGK_C_FLAGS with -DOGK_REAL_SINGLE=1: single), whatever a toolchain file's default.
cmake_kernel = bd=$(B)/cmake-$(1); tc=cmake/toolchains/$(2).cmake; \
  if [ ! $$bd/CMakeCache.txt -nt $$tc ]; then rm -rf $$bd; tca=-DCMAKE_TOOLCHAIN_FILE=$$tc; else tca=; fi; \
  cmake -S . -B $$bd $$tca -DCMAKE_BUILD_TYPE= -DOGK_C_FLAGS="$(3)" \
    -DOGK_PRECISION=$(if $(findstring -DOGK_REAL_SINGLE=1,$(3)),single,double) --log-level=WARNING > /dev/null && \
  $(CMAKE_BUILD) $$bd -j2 && cmake/stage.sh $$bd $(4)
# The CPU flags of a toolchain file, which the Makefile's own target rules (tests, runtime) use too.
toolchain_cpu = $(or $(shell sed -n 's/^set(CMAKE_C_FLAGS_INIT "\(.*\)")$$/\1/p' cmake/toolchains/$(1).cmake),\
  $(error cmake/toolchains/$(1).cmake: no CMAKE_C_FLAGS_INIT line))

# ---------------------------------------------------------------- host kernel
# -O2 -fPIC (CMake's position-independent objects, shared by libogk.a and libogk.so).
HOST_OBJ := $(patsubst kernel/src/%.c,$(B)/host/kernel/%.o,$(KSRC))
$(B)/host/libogk.a $(B)/host/libogk.so $(HOST_OBJ) &: $(CMAKE_INPUTS) | apt
	$(call cmake_kernel,host,host-gcc,-O2,$(B)/host)

.PHONY: kernel-host
kernel-host: $(B)/host/libogk.a $(B)/host/libogk.so

# ---------------------------------------------------------------- host unit tests (cmocka, ASan+UBSan)
# The C unit tests, grouped by module: tests/unit/<module>/test_*.c (core, qp, nog, cpd, mpsp, blt,
# nmpc, contract), the shared fixtures and helpers in tests/unit/*.h (-Itests/unit). Every build names
# a test by its file name alone (build/<gate>/test_x), so the names are unique across the folders.
# (A test left at the top, tests/unit/test_*.c, still runs everywhere: move it to its module's folder.)
UNIT_SRC := $(sort $(wildcard tests/unit/test_*.c) $(wildcard tests/unit/*/test_*.c))
UNIT_NAMES := $(basename $(notdir $(UNIT_SRC)))
UNIT_HDR := $(wildcard tests/unit/*.h)
$(if $(filter-out $(words $(UNIT_NAMES)),$(words $(sort $(UNIT_NAMES)))),\
  $(error tests/unit: two test sources share a file name: $(sort $(UNIT_NAMES))))
vpath test_%.c $(sort $(dir $(UNIT_SRC)))
TEST_CFLAGS := -std=c99 -Wall -Wextra -Werror -O1 -g $(SAN) $(KINC) -Itests/unit

# One sanitizer build of the kernel and the tests per precision of the real type (ogk/real.h), each in its
# own directory: $(call host_unit_target,P,DIR,DEFS) defines P_B, P_DEFS, P_OBJ (the kernel's objects),
# P_TESTS (one program per test source) and their rules; $(call host_unit_run,P,LABEL) is the recipe that
# runs them all, every one even after a failure. The double build (test-unit-host: build/host-san, the
# default configuration) and the float build (test-unit-host-single: build/host-san-single,
# -DOGK_REAL_SINGLE=1 on the kernel and on the tests alike, so that both see one ogk_real_t). An optional
# fourth argument is compiled into the tests only (make unit-errors: -DOGK_TEST_MEASURE).
define host_unit_target
$(1)_B := $$(B)/$(2)
$(1)_DEFS := $(3)
$(1)_TEST_DEFS := $(4)
$(1)_OBJ := $$(patsubst kernel/src/%.c,$$($(1)_B)/kernel/%.o,$$(KSRC))
$(1)_TESTS := $$(addprefix $$($(1)_B)/,$$(UNIT_NAMES))
$$($(1)_B)/kernel/%.o: kernel/src/%.c $$(KHDR) | apt
	@mkdir -p $$(@D)
	gcc $$(strip $$(STRICT) $$($(1)_DEFS)) -O1 -g $$(SAN) $$(KINC) $$(KSRC_INC) -c $$< -o $$@
$$($(1)_B)/test_%: test_%.c $$(UNIT_HDR) $$($(1)_OBJ) | apt
	@mkdir -p $$(@D)
	gcc $$(strip $$(TEST_CFLAGS) $$($(1)_DEFS) $$($(1)_TEST_DEFS)) $$< $$($(1)_OBJ) -o $$@ -lcmocka -lm
endef
host_unit_run = @fail=0; for t in $($(1)_TESTS); do echo "== $(2): $$t"; \
	  $$t 2>&1 || fail=1; done; exit $$fail

$(eval $(call host_unit_target,HOST_SAN,host-san,))
$(eval $(call host_unit_target,HOST_SAN_SINGLE,host-san-single,-DOGK_REAL_SINGLE=1))

.PHONY: test-unit-host test-unit-host-single
test-unit-host: $(HOST_SAN_TESTS)
	$(call host_unit_run,HOST_SAN,host)
test-unit-host-single: $(HOST_SAN_SINGLE_TESTS)
	$(call host_unit_run,HOST_SAN_SINGLE,host single)

# ---------------------------------------------------------------- Cortex-M7 and Cortex-M4F (bare metal, QEMU)
# The ARMv7-M route (runtime, test runner, rules), then each target's parameters and goals.
include port/armv7m/armv7m.mk
include port/cortex-m7/cortex-m7.mk
include port/cortex-m4f/cortex-m4f.mk
# the QEMU instruction counter (after the ARMv7-M targets, whose runtimes its known-answer programs link)
include port/qemu-plugin/qemu-plugin.mk
# before test-python, whose prerequisites name its LINK_ECHO_ELF (prerequisites expand when read)
include port/cortex-m7/link/link.mk

# the measured errors of the unit tests per precision (make unit-errors: docs/design/precision-unit-tests.md)
include tests/unit/unit_errors.mk

# ---------------------------------------------------------------- the package as a flight project takes it
# make test-consumer: the kernel built and installed by CMake alone, examples/consumer built against it
include examples/consumer/consumer.mk

# ---------------------------------------------------------------- Eigen cross-check (host only)
EIGEN_BIN := $(B)/host/eigen_crosscheck
$(EIGEN_BIN): tests/eigen/crosscheck.cpp $(B)/host/libogk.a | apt
	g++ -std=c++17 -O2 -Wall -Wextra -I/usr/include/eigen3 $(KINC) $< $(B)/host/libogk.a -o $@
.PHONY: test-eigen
test-eigen: $(EIGEN_BIN)
	$(EIGEN_BIN)

# ---------------------------------------------------------------- strict compile + static analysis
.PHONY: lint lint-single
lint: | apt
	@# with kernel/include only, as a flight project compiles it (the shared internal headers are included by relative path)
	@for f in $(KSRC); do gcc $(STRICT) $(KINC) -c $$f -o /dev/null || exit 1; done
	@for f in $(KSRC); do arm-none-eabi-gcc $(STRICT) $(ARM_CPU) $(KINC) -c $$f -o /dev/null || exit 1; done
	@echo "lint: kernel/ compiles clean (gcc x86-64, arm-none-eabi cortex-m7) with strict flags"
	$(MAKE) lint-single
	@# the double build's configuration (its #if variants, e.g. __SSE2__); lint-single checks the float build's.
	@# One configuration per run: cppcheck's cross-file checks would pair one file's float configuration with
	@# another's double one (an array of 8 floats read as 8 doubles).
	cppcheck --quiet --std=c99 --enable=warning,style,performance,portability \
	  --inline-suppr --suppressions-list=docs/evidence/cppcheck-suppressions.txt \
	  --error-exitcode=3 -UOGK_REAL_SINGLE $(KINC) $(KSRC_INC) $(KSRC)
	@echo "lint: cppcheck clean (justified suppressions: docs/evidence/cppcheck-suppressions.txt)"
	$(MAKE) misra

# The float build (kernel/include/ogk/real.h: ogk_real_t is float with -DOGK_REAL_SINGLE=1) compiles clean,
# strict flags and -Wfloat-conversion, with gcc x86-64, clang and arm-none-eabi-gcc for a Cortex-M4F
# (single-precision FPU only), cppcheck finds nothing in its configuration, and it does no double
# arithmetic: its Cortex-M4F objects (-O2, as a flight build) reference no double-precision run-time
# helper of libgcc (__aeabi_dadd, __aeabi_f2d, __aeabi_i2d, ..., the __*df* names) and no double libm
# function (sqrt rather than sqrtf). The check is first shown to catch a one-line double function, so
# that a pattern matching nothing cannot pass.
LINT_SINGLE := -DOGK_REAL_SINGLE=1 -Wfloat-conversion
LINT_SINGLE_M4F_CPU := $(call toolchain_cpu,cortex-m4f)
LINT_SINGLE_B := $(B)/lint-single
LINT_SINGLE_DOUBLE_LIBM := sqrt cbrt hypot sin cos tan asin acos atan atan2 sinh cosh tanh exp exp2 expm1 log \
  log10 log1p log2 pow fabs floor ceil trunc round lround nearbyint rint fmod remainder fmin fmax fdim fma copysign \
  ldexp frexp modf scalbn nextafter
lint_single_space := $(subst x, ,x)
LINT_SINGLE_DOUBLE_RE := (__aeabi_d[a-z0-9]+|__aeabi_[a-z0-9]+2d|__[a-z]+df[a-z0-9]*|$(subst \
  $(lint_single_space),|,$(strip $(LINT_SINGLE_DOUBLE_LIBM))))
lint-single: | apt
	@# at -O2, as every build of the kernel compiles: some diagnostics (-Wmaybe-uninitialized) need the optimiser
	@for f in $(KSRC); do gcc $(STRICT) $(LINT_SINGLE) -O2 $(KINC) -c $$f -o /dev/null || exit 1; done
	@for f in $(KSRC); do clang $(STRICT) $(LINT_SINGLE) -O2 $(KINC) -c $$f -o /dev/null || exit 1; done
	@rm -rf $(LINT_SINGLE_B) && mkdir -p $(LINT_SINGLE_B)
	@for f in $(KSRC); do o=$$(echo $${f#kernel/src/} | tr / _); o=$(LINT_SINGLE_B)/$${o%.c}.o; \
	  arm-none-eabi-gcc $(STRICT) $(LINT_SINGLE) $(LINT_SINGLE_M4F_CPU) -O2 $(KINC) -c $$f -o $$o || exit 1; done
	@printf 'double ogk_lint_twice(double x);\ndouble ogk_lint_twice(double x) { return x * 2.0 + (double)sqrt(x); }\n' \
	  | arm-none-eabi-gcc -std=c99 $(LINT_SINGLE_M4F_CPU) -O2 -include math.h -x c -c - -o $(LINT_SINGLE_B)/selfcheck.d
	@arm-none-eabi-nm -u $(LINT_SINGLE_B)/selfcheck.d | awk '{print $$NF}' | grep -Eqx '$(LINT_SINGLE_DOUBLE_RE)' || \
	  { echo "lint-single: FAILED: the double-symbol check misses a double function (selfcheck)"; exit 1; }
	@bad=$$(for o in $(LINT_SINGLE_B)/*.o; do arm-none-eabi-nm -u $$o | awk -v o=$$o '{print o ": " $$NF}'; done \
	  | grep -E ': $(LINT_SINGLE_DOUBLE_RE)$$'); \
	  if [ -n "$$bad" ]; then echo "lint-single: FAILED: double arithmetic in the float build:"; echo "$$bad"; exit 1; fi
	@# cppcheck over the float build's configuration (and its #if variants: --force)
	@cppcheck --quiet --force --std=c99 --enable=warning,style,performance,portability \
	  --inline-suppr --suppressions-list=docs/evidence/cppcheck-suppressions.txt \
	  --error-exitcode=3 -DOGK_REAL_SINGLE=1 $(KINC) $(KSRC_INC) $(KSRC)
	@echo "lint-single: the float build (OGK_REAL_SINGLE=1) compiles clean (gcc x86-64, clang, arm-none-eabi \
	cortex-m4f) with strict flags and -Wfloat-conversion, cppcheck clean; its $(words $(KSRC)) Cortex-M4F objects \
	reference no double helper or double libm function"

# ---------------------------------------------------------------- Python harness (cffi)
FFI_STAMP := bindings/ogk_bindings/.ffi-built
# The kernel's extension (bindings), then each family's C batch loops in an extension of its own,
# built by the family layer on the kernel's types (harness/ogk/missions/build_csrc.py).
$(FFI_STAMP): $(KSRC) $(KHDR) $(wildcard bindings/csrc/*) $(wildcard harness/ogk/missions/*/csrc/*) bindings/build_ffi.py harness/ogk/missions/build_csrc.py $(VENV)/.installed
	$(VPY) bindings/build_ffi.py
	$(VPY) harness/ogk/missions/build_csrc.py
	touch $@
.PHONY: ffi
ffi: $(FFI_STAMP)

.PHONY: test-python test-slow test-imports
# The import contract of docs/design/architecture.md (pyproject.toml [tool.importlinter]).
test-imports: $(VENV)/.installed
	$(VENV)/bin/lint-imports --no-cache
	@# one family interface (issue 33): every family and the test family are a MissionFamily
	MYPYPATH=harness:host:bindings:tests/python $(VENV)/bin/mypy --follow-imports=silent \
	  --ignore-missing-imports --cache-dir $(B)/mypy tests/typecheck/families.py

# Two pytest workers (pytest-xdist), each taking whole files (--dist loadfile: a module's fixtures are
# built once): 9:02 instead of 15:51 alone on 2 cores (2026-12-05). What two tests may make at once is
# locked: the default table directories (ogk_host.dir_lock), the PIL flight programs and the QEMU plugin
# (ogk.sil.pil_build), the Makefile targets the tests make (pil_checks.locked_make). --durations: the
# 25 slowest tests at the end of every run (issue 34: make test within 20 minutes).
PYTEST_WORKERS ?= 2
test-python: $(FFI_STAMP) $(LINK_ECHO_ELF) $(QP_SO) $(ARM_B)/libogk.a $(ARM_BOARD_OBJ)
	$(VPY) -m pytest -q -m "not slow" -n $(PYTEST_WORKERS) --dist loadfile --durations=25 tests/python

# Minutes-long checks kept out of `make test`: the Apophis nominal regenerated from scratch.
test-slow: $(FFI_STAMP)
	$(VPY) -m pytest -q -m slow tests/python

# ---------------------------------------------------------------- the wheel (docs/guides/install.md)
# test-wheel (in make test): `python -m build` (the sdist, then the wheel from it: setup.py compiles the
# kernel's and the families' extensions), a clean venv under build/wheel with the wheel alone installed,
# then from a temporary directory outside the repository `ogk mc leo-geo --runs 4` and `ogk run
# apophis_cubesat --case thrust --param=3`, their JSON checked, and the one-line refusals of what needs
# the repository (--target m7) or an extra (--dask). 49-104 s in four runs on 2026-12-05 (2 cores, the
# slower ones beside another job): removing the last check's venv up to 15 s, build 18-39 s, pip install
# 19-22 s (the dependencies from the index), the flights and refusals 6-9 s (tests/wheel/check_wheel.py
# prints each step's time). Needs the network, or pip's cache, for the wheel's dependencies.
.PHONY: test-wheel
test-wheel: $(VENV)/.installed
	$(VPY) tests/wheel/check_wheel.py --out $(B)/wheel

# ---------------------------------------------------------------- benchmarks
include tests/bench/bench.mk

# ---------------------------------------------------------------- Cortex-M7 flight application
# (docs/guides/flight-integration.md): make test-flight-app, flight-app-size, flight-app-stack
include port/cortex-m7/flightapp/flightapp.mk
# 32-bit big-endian SPARC V8 (LEON3) under qemu-user (docs/guides/ports.md): make test-unit-sparc,
# test-flight-app-sparc, test-flt-eval
include port/sparc-v8/sparc-v8.mk
# processor-in-the-loop flight programs (docs/guides/pil.md): make pil-program PIL_PROGRAM=oi PIL_OUT=DIR
include port/cortex-m7/pil/pil.mk
# ... and the same programs for SPARC V8 Linux user mode: make pil-program-sparc PIL_PROGRAM=oi PIL_OUT=DIR
include port/sparc-v8/pil.mk
# ... and for the Cortex-M4F on the single-precision kernel: make pil-program-m4f PIL_PROGRAM=oi PIL_OUT=DIR
include port/cortex-m4f/pil.mk

# ---------------------------------------------------------------- gates (issue 8): make tidy,
# fuzz-short / fuzz, coverage, mutants (not in make test), misra (a ratchet, in make lint)
include tests/gates/gates.mk
# certification evidence (docs/evidence/profile.md): make stack-bound-m7
include port/profile/profile.mk

# ---------------------------------------------------------------- Frama-C EVA (issue 22): make eva
include tests/eva/eva.mk

.PHONY: misra
misra: | apt
	$(PYTHON) tests/misra/misra_gate.py --build $(B)/misra

# ---------------------------------------------------------------- requirements traceability
# docs/evidence/requirements.md, the req: tags of the tests and tests/trace/gates.txt: `make trace` fails on an
# untagged test, a requirement without a test, an unknown id or a stale docs/evidence/traceability.md
# (stdlib Python, parses the sources: under a second); `make trace-matrix` regenerates the matrix.
.PHONY: trace trace-matrix
trace:
	$(PYTHON) tests/trace/check_trace.py
trace-matrix:
	$(PYTHON) tests/trace/check_trace.py --write

# ---------------------------------------------------------------- versioned API (CHANGELOG.md, "Versioning")
# api-check (in make test, ~1 s): the public headers against the interface recorded for the last release
# (api/ogk-X.Y.Z.api); fails on a change the version in ogk/version.h does not cover (a removed or changed
# declaration or macro: the breaking bump, the minor one while the major is 0; an added one: the next
# compatible version). api-record: records the current headers under the current version, at a release.
.PHONY: api-check api-record
api-check: | apt
	$(PYTHON) tests/api/check_api.py check
api-record: | apt
	$(PYTHON) tests/api/check_api.py record

# ---------------------------------------------------------------- documentation
# docs/: docs/index.md (getting started), then guides/, design/, evidence/; the nav in mkdocs.yml.
# `make docs` builds the site into build/site (open build/site/index.html); --strict fails on a broken
# link or anchor and on a page missing from the nav. docs-check (in make test, seconds) adds the plain
# docs/... and notes/... paths every tracked file names (the pages, code comments, scenarios), which no
# Markdown parser sees (tests/docs/check_docs.py --tree).
.PHONY: docs docs-check
docs: venv
	$(VENV)/bin/mkdocs build --strict --site-dir $(B)/site
docs-check: docs
	$(VPY) tests/docs/check_docs.py --tree

# ---------------------------------------------------------------- top-level
.PHONY: all test run clean
all: deps kernel-host arm-lib ffi

# Two lanes on the 2-core machine (issue 34: make test within 20 minutes): the Python tests, the
# long pole (~16 min), on one core; every other check on the other, in the order it fails fastest
# (~10 min of work; the unit tests in float on the host and the Cortex-M4F ~10 s and ~40 s). The first
# three (seconds) run alone: a stale trace, API or link fails at once.
# What both lanes build is built first (test-python-prereqs); the two targets the Python tests also
# make themselves (arm-stack, stack-bound-sparc: tests/python/pil_checks.py, test_pil_sparc.py) are
# made under a lock (locked: flock on build/.lock-NAME), so that the lane that comes second finds them
# made. The lanes build
# in their own directories: the gates in build/gates, fuzz, coverage, mcdc (Frama-C in memory); the
# flight app its tables under build/arm/flightapp; the Cortex-M4F build/m4f and build/cmake-m4f; the
# consumer build/cm-*; the wheel build/wheel.
test: deps
	$(MAKE) trace
	$(MAKE) api-check
	$(MAKE) docs-check
	$(MAKE) test-python-prereqs
	$(MAKE) -j2 --output-sync=line test-python test-beside-python

.PHONY: test-beside-python test-static-gates test-python-prereqs
test-beside-python:
	$(MAKE) lint
	$(MAKE) test-unit-host
	$(MAKE) test-unit-host-single
	$(MAKE) test-unit-arm
	$(MAKE) test-arm-selftest test-qemu-plugin stack-bound-m7 footprint-m7
	$(call locked,arm-stack) $(MAKE) arm-stack
	$(MAKE) test-flight-app
	$(call locked,stack-bound-sparc) $(MAKE) test-unit-sparc test-flight-app-sparc test-flt-eval stack-bound-sparc \
	  footprint-sparc test-qemu-plugin-sparc
	$(MAKE) test-unit-m4f
	$(MAKE) test-m4f-selftest test-qemu-plugin-m4f stack-bound-m4f footprint-m4f
	$(MAKE) test-consumer
	$(MAKE) test-wheel
	$(MAKE) test-eigen
	$(MAKE) test-imports
	$(MAKE) test-static-gates

test-static-gates:
	$(MAKE) gates
	$(MAKE) eva
test-python-prereqs: $(FFI_STAMP) $(LINK_ECHO_ELF) $(QP_SO) $(ARM_B)/libogk.a $(ARM_BOARD_OBJ)

# Long campaigns of every family's shipped scenarios (soak.toml: >= 1,000 runs each on fixed seeds no test
# uses) through the one engine, summarised per family; exit 1 when a campaign loses a flight its law's
# stated envelope does not allow (docs/guides/campaigns.md, "make soak"). Not part of `make test`: ~30 min.
.PHONY: soak
soak: $(FFI_STAMP)
	$(VENV)/bin/ogk soak --out $(B)/soak

# Campaign records (tests/records/records.toml, issue 33): every shipped scenario flown through `ogk mc` on
# the host and the emulated Cortex-M7, compared bit for bit with the committed records (make test checks the
# quick entries: tests/python/test_campaign_records.py). `make records` rewrites them: only for an intended,
# explained change of output.
.PHONY: records records-check
records-check: test-python-prereqs
	$(VENV)/bin/python tests/python/campaign_records.py check --all
records: test-python-prereqs
	$(VENV)/bin/python tests/python/campaign_records.py write --all

# The main job, through the verbs every family has (ogk tables / mc / run): LEO-to-GEO VTD-NOG + CPD,
# ground tables (build/tables/leo_geo-<sha12>) then a 100-run SIL Monte Carlo flying them, against the
# paper's Table 7 (envelope JSON, Parquet table and PNG plots in build/mc), and PIL_RUNS of them on the
# emulated Cortex-M7; MPSP on the 23 Apophis cases against Wang & Topputo's Tables 3, 5, 6
# (build/apophis); the Earth-to-Mars NMPC against Tables I and II (build/nmpc); the six BLT transfers
# about Moshup and the Table 3 campaign (build/blt; TABLE3_RUNS over its 6 levels). Each report states
# its run count beside the paper's. `make run` in under 10 minutes on 2 cores: 24 runs on the target and
# 100 per Table 3 level (measured solo on a fresh clone: the 100 target runs took 116 s, the 600 per
# level 298 s of a 12-minute job); `make reproduce`: the full sizes (100 on the target, the paper's 600 per
# level), the same commands.
PIL_RUNS ?= 24
TABLE3_RUNS ?= 600
.PHONY: reproduce
reproduce:
	$(MAKE) run PIL_RUNS=100 TABLE3_RUNS=3600
run: all $(QP_SO)
	$(VENV)/bin/ogk demo switching
	$(VENV)/bin/ogk tables leo-geo
	$(VENV)/bin/ogk mc leo-geo --runs 100 --seed 1 --workers 2 \
	  --json $(B)/mc/leo_geo_100.json --plots $(B)/mc/plots
	# the first PIL_RUNS of those runs with the flight program on the emulated Cortex-M7 (docs/guides/pil.md)
	$(VENV)/bin/ogk mc leo-geo --target m7 --runs $(PIL_RUNS) --seed 1 --workers 2 \
	  --json $(B)/pil/leo_geo_m7_$(PIL_RUNS).json
	$(VENV)/bin/ogk run apophis --paper-tables \
	  --json $(B)/apophis/paper_tables.json --plots $(B)/apophis/plots
	# the 23 paper cases solved on the emulated Cortex-M7, the host's iteration counts beside them
	$(VENV)/bin/ogk mc apophis_cubesat --cases paper --target m7 --workers 2 \
	  --json $(B)/pil/apophis_paper_m7.json
	# the paper's problem unperturbed (Table I's rows), then the shipped law (its robustness of
	# docs/design/nmpc-flight.md, "Robustness"): unperturbed, one perturbed flight with plots, and the
	# perturbed campaigns beside Tables I and II
	$(VENV)/bin/ogk run rendezvous_nep_min_time --strategy snns --solver kernel --paper-problem \
	  --json $(B)/nmpc/snns_unperturbed_paper_problem.json
	$(VENV)/bin/ogk run rendezvous_nep_min_time --strategy cncn --solver kernel --paper-problem \
	  --json $(B)/nmpc/cncn_unperturbed_paper_problem.json
	$(VENV)/bin/ogk run rendezvous_nep_min_time --strategy snns --solver kernel \
	  --json $(B)/nmpc/snns_unperturbed.json --plots $(B)/nmpc/plots
	$(VENV)/bin/ogk run rendezvous_nep_min_time --strategy snns --solver kernel --perturbed --seed 1 \
	  --json $(B)/nmpc/snns_perturbed_seed1.json --plots $(B)/nmpc/plots
	for s in rendezvous_nep_min_time rendezvous_nep_min_fuel rendezvous_sep_min_fuel; do \
	  $(VENV)/bin/ogk mc $$s --runs 24 --seed 1 --workers 2 --json $(B)/nmpc/$${s}_24.json || exit 1; done
	for t in l2_to_l1_lyapunov l1_to_l2_lyapunov l2_to_l1_halo l1_to_l2_halo l1_to_l2_lyapunov_bmp l1_to_l2_halo_bmp \
	  circle_to_l2_ump; do \
	  $(VENV)/bin/ogk run moshup --transfer $$t --json $(B)/blt/$$t.json --plots $(B)/blt/plots || exit 1; done
	$(VENV)/bin/ogk mc moshup --runs $(TABLE3_RUNS) --seed 20261202 --workers 2 --json $(B)/blt/mc_table3.json \
	  --plots $(B)/blt/plots
	# the scenario's transfers corrected on the emulated Cortex-M7, beside the host's
	$(VENV)/bin/python -m ogk.missions.binary.pil_transfers moshup --json $(B)/pil/moshup_transfers_m7.json

clean:
	rm -rf $(B) dist ogk.egg-info $(FFI_STAMP) bindings/ogk_bindings/_ogk_cffi* harness/ogk/missions/*/_csrc_cffi*
