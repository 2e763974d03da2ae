# port/cortex-m7/flightapp/flightapp.mk -- the flight application on the emulated Cortex-M7
# (docs/guides/flight-integration.md). Included by the top-level Makefile after cortex-m7.mk; uses its
# STRICT, KINC, B, VENV, FFI_STAMP and cortex-m7.mk's ARM_* variables.
#
#   make test-flight-app    generate the LEO-to-GEO table image and flight configuration header
#                           (ogk tables leo-geo), build build/arm/flightapp/flightapp.elf, run it on
#                           QEMU; fails unless it exits 0 and prints "flightapp: PASS", and unless
#                           the same app built for the host gives the same injection errors
#   make flight-app-sil-compare  the same runs against the host SIL (point-mass truth), ~15 s
#   make flight-app-size    flash / RAM of the ELF and of each object, largest symbols
#   make flight-app-stack   worst-case stack of the ogk_flight_* entry points (gcc call graphs)
#
# Included by the top-level Makefile (after bench.mk); make test runs test-flight-app.

# Prerequisites are expanded when this file is read: include it after FFI_STAMP and HOST_OBJ are set
# (e.g. next to `include tests/bench/bench.mk`).
ifeq ($(strip $(FFI_STAMP)),)
$(error flightapp.mk: include it after FFI_STAMP is defined in the Makefile)
endif
ifeq ($(strip $(HOST_OBJ)),)
$(error flightapp.mk: include it after HOST_OBJ is defined in the Makefile)
endif

FA_DIR := $(ARM_PORT)/flightapp
FA_B := $(ARM_B)/flightapp
# Generated into the app's own build tree (`ogk tables leo-geo --out DIR`), so that a campaign
# regenerating build/tables/... at the same time cannot change the files under a build.
FA_TABLES ?= $(FA_B)/tables
FA_GEN := $(FA_TABLES)/c
FA_GEN_C := $(FA_GEN)/ogk_nog_bundle.c
FA_GEN_H := $(FA_GEN)/ogk_nog_bundle.h $(FA_GEN)/ogk_orbit_injection_flight_config.h \
  $(FA_GEN)/ogk_sil_plant.h
FA_SRC := $(FA_DIR)/ogk_flight.c $(FA_DIR)/main.c
FA_HDR := $(FA_DIR)/ogk_flight.h

# The flight flags of the kernel (STRICT, -O2, per-function sections, -fstack-usage) for the
# application and the generated table image as well.
# FA_DEFS: build options of the app, e.g. -DOGK_FLIGHT_TABLE_COPY=1 (table decoded into RAM instead
# of read in place; build it into its own tree: make ... FA_DEFS=-DOGK_FLIGHT_TABLE_COPY=1
# ARM_B=build/arm-tablecopy).
FA_DEFS ?=
FA_CFLAGS := $(STRICT) $(ARM_CPU) -O2 -g -ffunction-sections -fdata-sections -fstack-usage \
  $(FA_DEFS) $(KINC) -I$(FA_GEN) -I$(FA_DIR)
FA_OBJ := $(FA_B)/ogk_flight.o $(FA_B)/main.o $(FA_B)/ogk_nog_bundle.o
# Runtime: start-up (vectors, reset, FPU/MPU, semihosting exit) and the port counter; no test runner.
FA_RT_OBJ := $(ARM_BOARD_OBJ)
FA_ELF := $(FA_B)/flightapp.elf

.PHONY: test-flight-app flight-app flight-app-size flight-app-stack

# Generated sources: the CRC'd table image as const C, the const configurations, the plant constants.
$(FA_B)/tables.stamp: $(VENV)/.installed $(FFI_STAMP) scenarios/leo_geo.toml host/ogk_host/cgen.py \
  harness/ogk/missions/orbit_injection/flight_config.py harness/ogk/missions/orbit_injection/ground_tables.py \
  $(wildcard host/ogk_host/orbit_injection/*.py)
	$(VENV)/bin/ogk tables leo-geo --out $(FA_TABLES)
	@mkdir -p $(@D)
	@touch $@
$(FA_GEN_C) $(FA_GEN_H): $(FA_B)/tables.stamp

$(FA_B)/%.o: $(FA_DIR)/%.c $(FA_HDR) $(FA_GEN_H) $(KHDR) | apt
	@mkdir -p $(@D)
	$(ARM_CC) $(FA_CFLAGS) -c $< -o $@
$(FA_B)/ogk_nog_bundle.o: $(FA_GEN_C) $(FA_GEN_H) | apt
	@mkdir -p $(@D)
	$(ARM_CC) $(FA_CFLAGS) -c $< -o $@

$(FA_ELF): $(FA_OBJ) $(FA_RT_OBJ) $(ARM_B)/libogk.a $(ARM_LDSCRIPT)
	$(ARM_CC) $(FA_OBJ) $(FA_RT_OBJ) $(ARM_B)/libogk.a $(ARM_LDFLAGS) -Wl,-Map=$(@:.elf=.map) \
	  $(ARM_LDLIBS) -o $@

flight-app: $(FA_ELF)

# The same application for the host (gcc x86-64, glibc libm, the host kernel objects): its
# injection errors must agree with the Cortex-M7 run (compare_runs.py).
FA_HOST := $(ARM_B)/flightapp/host/flightapp
$(FA_HOST): $(FA_SRC) $(FA_HDR) $(FA_GEN_C) $(FA_GEN_H) $(HOST_OBJ) | apt
	@mkdir -p $(@D)
	gcc $(STRICT) -O2 $(FA_DEFS) $(KINC) -I$(FA_GEN) -I$(FA_DIR) $(FA_SRC) $(FA_GEN_C) $(HOST_OBJ) \
	  -lm -o $@

test-flight-app: $(FA_ELF) $(FA_HOST)
	@$(call armv7m_env,ARM) $(ARMV7M_DIR)/run_qemu.sh $(FA_ELF) $(ARM_TIMEOUT) > $(FA_B)/flightapp.log 2>&1; rc=$$?; \
	cat $(FA_B)/flightapp.log; \
	if [ $$rc -ne 0 ] || ! grep -q '^flightapp: PASS' $(FA_B)/flightapp.log; then \
	  echo "test-flight-app: FAILED (qemu exit $$rc)"; exit 1; fi; \
	$(FA_HOST) > $(FA_B)/flightapp_host.log 2>&1 || { cat $(FA_B)/flightapp_host.log; \
	  echo "test-flight-app: FAILED (host build)"; exit 1; }; \
	python3 $(FA_DIR)/compare_runs.py $(FA_B)/flightapp.log $(FA_B)/flightapp_host.log

# Against the host SIL (python -m ogk.missions.orbit_injection.flightapp_reference: point-mass truth,
# the kernel NOG through cffi; the script lives with its mission family, the port imports none) with the
# plant taking the command at every RK4 stage as the SIL does: runs A and B must agree to 1e-3
# (measured: identical in all printed digits). About 15 s; not part of test-flight-app.
FA_HOST_STAGE := $(ARM_B)/flightapp/host/flightapp_stage
$(FA_HOST_STAGE): $(FA_SRC) $(FA_HDR) $(FA_GEN_C) $(FA_GEN_H) $(HOST_OBJ) | apt
	@mkdir -p $(@D)
	gcc $(STRICT) -O2 -DFLIGHTAPP_STAGE_COMMANDS=1 $(KINC) -I$(FA_GEN) -I$(FA_DIR) $(FA_SRC) \
	  $(FA_GEN_C) $(HOST_OBJ) -lm -o $@
.PHONY: flight-app-sil-compare
flight-app-sil-compare: $(FA_HOST_STAGE) $(FA_B)/tables.stamp
	$(FA_HOST_STAGE) > $(FA_B)/flightapp_stage.log
	$(VPY) -m ogk.missions.orbit_injection.flightapp_reference $(FA_TABLES) > $(FA_B)/sil_reference.log
	python3 $(FA_DIR)/compare_runs.py --common --tol 1e-3 $(FA_B)/flightapp_stage.log \
	  $(FA_B)/sil_reference.log

flight-app-size: $(FA_ELF)
	arm-none-eabi-size -A $(FA_ELF) | grep -E '^(section|\.vectors|\.text|\.rodata|\.init_array|\.fini_array|\.data|\.bss|\.heap|\.stack|Total)'
	arm-none-eabi-size -t $(FA_OBJ) $(FA_RT_OBJ) $(ARM_KOBJ)
	arm-none-eabi-nm --size-sort -S -r $(FA_ELF) | head -15
	python3 $(FA_DIR)/map_sizes.py $(FA_ELF:.elf=.map)

# Call graphs of the application sources, with the kernel's ($(ARM_CI) from cortex-m7.mk).
FA_CI := $(FA_B)/callgraph/ogk_flight.ci
$(FA_B)/callgraph/%.ci: $(FA_DIR)/%.c $(FA_HDR) $(FA_GEN_H) $(KHDR) | apt
	@mkdir -p $(@D)
	$(ARM_CC) $(FA_CFLAGS) -fcallgraph-info=su -dumpdir $(@D)/ -dumpbase $* -c $< -o $(@D)/$*.o
flight-app-stack: $(FA_CI) $(ARM_CI)
	python3 $(ARM_PORT)/stack_report.py $(FA_CI) $(ARM_CI) | grep -E '^(entry point|ogk_flight_|ogk_nog_|ogk_cpd_step|ogk_cpd_init|outside|stack check)'
