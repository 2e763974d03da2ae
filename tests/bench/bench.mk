# Benchmarks: `make bench` prints instruction counts (valgrind callgrind,
# repeatable) and ns per call (host wall clock, indicative only on a shared
# 2-core machine) for the kernel's hot paths.
BENCH_DIR := $(B)/bench
BENCH_CORE := $(BENCH_DIR)/bench_core
BENCH_CASES := rk4_step switch qp
BENCH_GNC := $(BENCH_DIR)/bench_gnc
GNC_CASES := nog_sample nog_command cpd_step
NOG_TABLE := $(BENCH_DIR)/tables/nog_bundle.ogkt

$(BENCH_GNC): tests/bench/bench_gnc.c tests/bench/bench_timer.h $(B)/host/libogk.a $(PORT_HOST_SRC) | apt
	@mkdir -p $(@D)
	gcc -std=c99 -O2 -g -Wall -Wextra -Werror $(KINC) -Iport/include \
	  $< $(PORT_HOST_SRC) $(B)/host/libogk.a -o $@ -lm

$(NOG_TABLE): scenarios/leo_geo.toml $(VENV)/.installed
	$(VENV)/bin/ogk tables leo-geo --out $(@D)


$(BENCH_CORE): tests/bench/bench_core.c tests/bench/bench_timer.h $(B)/host/libogk.a $(PORT_HOST_SRC) | apt
	@mkdir -p $(@D)
	gcc -std=c99 -O2 -g -Wall -Wextra -Werror $(KINC) -Iport/include \
	  $< $(PORT_HOST_SRC) $(B)/host/libogk.a -o $@ -lm

.PHONY: bench
bench: $(BENCH_CORE) $(BENCH_GNC) $(NOG_TABLE) $(FFI_STAMP)
	@echo "== ogk bench (host x86-64, gcc -O2) =="
	@for c in $(BENCH_CASES); do \
	  n=$$(valgrind --tool=callgrind --callgrind-out-file=/dev/null \
	       --collect-atstart=no --toggle-collect=bench_$${c}_once \
	       $(BENCH_CORE) once $$c 2>&1 | sed -n 's/.*Collected : \([0-9]*\).*/\1/p'); \
	  printf '%-10s %10s instructions/call (callgrind)   ' $$c "$$n"; \
	  $(BENCH_CORE) time $$c; \
	done
	@for c in $(GNC_CASES); do \
	  n=$$(valgrind --tool=callgrind --callgrind-out-file=/dev/null \
	       --collect-atstart=no --toggle-collect=bench_$${c}_once \
	       $(BENCH_GNC) $(NOG_TABLE) once $$c 2>&1 | sed -n 's/.*Collected : \([0-9]*\).*/\1/p'); \
	  printf '%-11s %9s instructions/call (callgrind)   ' $$c "$$n"; \
	  $(BENCH_GNC) $(NOG_TABLE) time $$c; \
	done
	@echo "== MPSP per complete case (kernel CPU of ogk_mpsp_solve, the paper's 23 Apophis cases) =="
	@$(VENV)/bin/ogk mpsp apophis --paper-tables --no-reference | \
	  awk '/^T[356] / {for (i = 1; $$i != "yes" && $$i != "no"; i++) ; label = $$1; \
	    for (j = 2; j < i; j++) label = label " " $$j; \
	    printf "%-15s NI %3s  CPU %6.3f s   (paper MPSP-CT %6.2f s)\n", label, $$(i+2), $$(NF-3), $$(NF-1)} \
	    /converged; kernel CPU/'

# MPSP (kernel/include/ogk/mpsp.h): one Newton iteration at flight size (2000
# RK4 steps, Fourier order 15: 94 unknowns) and its parts; see docs/design/mpsp.md.
BENCH_MPSP := $(BENCH_DIR)/bench_mpsp
MPSP_CASES := mpsp_iter mpsp_prop mpsp_sens mpsp_update mpsp_iter_mid2 mpsp_sens_mid2

$(BENCH_MPSP): tests/bench/bench_mpsp.c tests/bench/bench_timer.h $(B)/host/libogk.a $(PORT_HOST_SRC) | apt
	@mkdir -p $(@D)
	gcc -std=c99 -O2 -g -Wall -Wextra -Werror $(KINC) -Iport/include \
	  $< $(PORT_HOST_SRC) $(B)/host/libogk.a -o $@ -lm

.PHONY: bench-mpsp
bench-mpsp: $(BENCH_MPSP)
	@for c in $(MPSP_CASES); do \
	  n=$$(valgrind --tool=callgrind --callgrind-out-file=/dev/null \
	       --collect-atstart=no --toggle-collect=bench_$${c}_once \
	       $(BENCH_MPSP) once $$c 2>&1 | sed -n 's/.*Collected : \([0-9]*\).*/\1/p'); \
	  printf '%-14s %9s instructions/call (callgrind)   ' $$c "$$n"; \
	  $(BENCH_MPSP) time $$c; \
	done

bench: bench-mpsp

# ---------------------------------------------------------------- Cortex-M7 instruction counts (QEMU plugin)
# One MPSP Newton iteration (and its parts) executed on the emulated Cortex-M7, counted by the TCG
# plugin from each function's entry to its return: instructions, not cycles (docs/guides/ports.md).
ARM_BENCH_MPSP := $(ARM_B)/bench_mpsp.elf
$(ARM_BENCH_MPSP): tests/bench/bench_mpsp.c $(ARM_RT_OBJ) $(ARM_B)/libogk.a $(ARM_LDSCRIPT)
	$(ARM_CC) -std=c99 -Wall -Wextra -Werror -O2 -g $(ARM_CPU) -DOGK_BENCH_BARE_METAL \
	  $(KINC) -Iport/include -I$(ARMV7M_DIR) $< $(ARM_RT_OBJ) $(ARM_B)/libogk.a \
	  $(ARM_LDFLAGS) $(ARM_LDLIBS) -o $@
.PHONY: bench-arm
bench-arm: $(ARM_BENCH_MPSP) qemu-plugin
	@echo "== ogk bench (Cortex-M7 on QEMU mps2-an500, instruction counts) =="
	@port/qemu-plugin/count_insns.sh $(ARM_BENCH_MPSP) bench_mpsp_iter_once bench_mpsp_prop_once \
	  bench_mpsp_sens_once bench_mpsp_update_once bench_mpsp_iter_mid2_once \
	  bench_mpsp_sens_mid2_once 2>/dev/null
bench: bench-arm

# ---------------------------------------------------------------- NMPC warm re-solve (docs/design/nmpc.md, "Cost")
# One ogk_nmpc_replan at N = 30 -> 29 after the open loop (the case: the committed fixture
# tests/bench/fixtures/nmpc_case.json, the paper's problem, bench_nmpc_case.h its bit-exact transform,
# tests/bench/nmpc_case.py): host ns (median), callgrind instructions
# of exactly one re-solve, Cortex-M7 instructions (QEMU plugin), the static worst-case stack (gcc call
# graphs) and the QEMU high-water mark; then the strongest peers on the same re-solve from the same start,
# FATROP and IPOPT JIT-compiled by gcc -O2 (tests/bench/nmpc_peers.py: compiled once per machine into
# build/bench/nmpc/peers; their callgrind counts cached there too), and the kernel through cffi, in one
# table with the ratios at the kernel's default and at matched accuracy (bench_nmpc_ipopt.py run).
NMPC_B := $(BENCH_DIR)/nmpc
NMPC_CASE_H := $(NMPC_B)/bench_nmpc_case.h
BENCH_NMPC := $(BENCH_DIR)/bench_nmpc
ARM_BENCH_NMPC := $(ARM_B)/bench_nmpc.elf

NMPC_CASE_JSON := tests/bench/fixtures/nmpc_case.json

# The C header: a pure transform of the committed fixture (stdlib Python, bit-exact; tests/bench/nmpc_case.py).
$(NMPC_CASE_H): $(NMPC_CASE_JSON) tests/bench/nmpc_case.py
	python3 tests/bench/nmpc_case.py header $(NMPC_CASE_JSON) $@

# The fixture made again from the scenario (through numpy: its last bits are this machine's; commit it
# only with a reason, docs/design/nmpc.md section 10), and the committed one checked against a fresh generation.
.PHONY: bench-nmpc-case bench-nmpc-case-check
bench-nmpc-case: $(FFI_STAMP)
	$(VPY) tests/bench/nmpc_case.py generate $(NMPC_CASE_JSON)
bench-nmpc-case-check: $(FFI_STAMP)
	$(VPY) tests/bench/nmpc_case.py check $(NMPC_CASE_JSON)

$(BENCH_NMPC): tests/bench/bench_nmpc.c $(NMPC_CASE_H) $(B)/host/libogk.a $(PORT_HOST_SRC) | apt
	@mkdir -p $(@D)
	gcc -std=c99 -O2 -g -Wall -Wextra -Werror $(KINC) -Iport/include -I$(NMPC_B) \
	  $< $(PORT_HOST_SRC) $(B)/host/libogk.a -o $@ -lm

$(ARM_BENCH_NMPC): tests/bench/bench_nmpc.c $(NMPC_CASE_H) $(ARM_RT_OBJ) $(ARM_B)/libogk.a $(ARM_LDSCRIPT)
	$(ARM_CC) -std=c99 -Wall -Wextra -Werror -O2 -g $(ARM_CPU) -DOGK_BENCH_BARE_METAL \
	  $(KINC) -Iport/include -I$(ARMV7M_DIR) -I$(NMPC_B) $< $(ARM_RT_OBJ) $(ARM_B)/libogk.a \
	  $(ARM_LDFLAGS) $(ARM_LDLIBS) -o $@

# The same re-solve with the exact Hessian (set after the same open loop; bench_nmpc.c).
ARM_BENCH_NMPC_EXACT := $(ARM_B)/bench_nmpc_exact.elf
$(ARM_BENCH_NMPC_EXACT): tests/bench/bench_nmpc.c $(NMPC_CASE_H) $(ARM_RT_OBJ) $(ARM_B)/libogk.a $(ARM_LDSCRIPT)
	$(ARM_CC) -std=c99 -Wall -Wextra -Werror -O2 -g $(ARM_CPU) -DOGK_BENCH_BARE_METAL -DBENCH_NMPC_HESSIAN=1 \
	  $(KINC) -Iport/include -I$(ARMV7M_DIR) -I$(NMPC_B) $< $(ARM_RT_OBJ) $(ARM_B)/libogk.a \
	  $(ARM_LDFLAGS) $(ARM_LDLIBS) -o $@

.PHONY: bench-nmpc bench-nmpc-profile
bench-nmpc: $(BENCH_NMPC) $(ARM_BENCH_NMPC) $(ARM_BENCH_NMPC_EXACT) $(ARM_CI) qemu-plugin $(FFI_STAMP)
	@echo "== NMPC warm re-solve: the kernel against FATROP + JIT and IPOPT + JIT (docs/design/nmpc.md, \"Cost\") =="
	@rm -f $(NMPC_B)/*.txt
	@for m in "" tol0 exact "exact tol0"; do $(BENCH_NMPC) time $$m; done > $(NMPC_B)/host.txt
	@for m in "" tol0 exact "exact tol0"; do \
	  n=$$(valgrind --tool=callgrind --callgrind-out-file=/dev/null \
	     --collect-atstart=no --toggle-collect=bench_nmpc_replan_once \
	     $(BENCH_NMPC) once $$m 2>&1 | sed -n 's/.*Collected : \([0-9]*\).*/\1/p'); \
	  k=$$(echo "nmpc $$m" | sed 's/ *$$//; s/ /_/g'); echo "$${k}_replan_callgrind $$n"; \
	done > $(NMPC_B)/callgrind.txt
	@port/qemu-plugin/count_insns.sh $(ARM_BENCH_NMPC_EXACT) bench_nmpc_replan_once 2> /dev/null | \
	  awk '$$2 == "fn" && $$3 == "bench_nmpc_replan_once" { print "nmpc_exact_replan_m7_insns", $$9 }' > $(NMPC_B)/m7_exact.txt
	@port/qemu-plugin/count_insns.sh $(ARM_BENCH_NMPC) bench_nmpc_replan_once 2> $(NMPC_B)/m7_run.log | \
	  awk '$$2 == "fn" && $$3 == "bench_nmpc_replan_once" { print "nmpc_replan_m7_insns", $$9 }' > $(NMPC_B)/m7.txt
	@sed -n 's/^\(nmpc_m7_[a-z0-9_]* [0-9.e+-]*\).*/\1/p; s/.*stack high-water mark: \([0-9]*\) of.*/nmpc_m7_stack_hwm \1/p' \
	  $(NMPC_B)/m7_run.log >> $(NMPC_B)/m7.txt
	@python3 port/cortex-m7/stack_report.py $(ARM_CI) > $(NMPC_B)/stack_report.log; \
	  awk '$$1 == "ogk_nmpc_replan" { print "nmpc_stack_replan", $$3 } $$1 == "ogk_nmpc_solve" { print "nmpc_stack_solve", $$3 }' \
	  $(NMPC_B)/stack_report.log > $(NMPC_B)/stack.txt
	@$(VPY) tests/bench/bench_nmpc_ipopt.py peer-insns $(NMPC_B)/peers_callgrind.txt > /dev/null
	@$(VPY) tests/bench/bench_nmpc_ipopt.py run --figures $(NMPC_B)

# The re-solve's iteration counts under ulp moves of its start (x_1, t_1; then x_0 and the guess's
# horizon through the open loop; then 200 one-ulp patterns of the guess), in each mode: one count each.
.PHONY: bench-nmpc-scan
bench-nmpc-scan: $(BENCH_NMPC)
	@for m in "" tol0 exact "exact tol0"; do $(BENCH_NMPC) scan $$m | grep -v '^scan '; \
	  $(BENCH_NMPC) scan $$m open | grep -v '^scan '; $(BENCH_NMPC) scan $$m guess 200; done

# Where the re-solve's instructions go: callgrind of one re-solve, inclusive per function.
bench-nmpc-profile: $(BENCH_NMPC)
	valgrind --tool=callgrind --callgrind-out-file=$(NMPC_B)/callgrind.out \
	  --collect-atstart=no --toggle-collect=bench_nmpc_replan_once $(BENCH_NMPC) once
	callgrind_annotate --inclusive=yes $(NMPC_B)/callgrind.out | head -40
	callgrind_annotate $(NMPC_B)/callgrind.out | head -30

bench: bench-nmpc

# ---------------------------------------------------------------- BLT / NRPC (docs/design/blt.md, "Cost")
# One NRPC iteration (ogk_blt_solve with max_iter = 1 from the guess) and a whole convergence, for the
# single-burn l2_to_l1_lyapunov and the burn-coast-burn circle_to_l2_ump of scenarios/moshup.toml, each with
# the central-difference and the variational Jacobian (the cases: tests/bench/bench_blt_case.py, generated into
# bench_blt_case.h bit-exact from the scenario through the ground pipeline): host ns (medians), callgrind
# instructions of exactly one iteration / convergence, Cortex-M7 instructions (QEMU plugin), the static
# worst-case stack (gcc call graphs) and the QEMU high-water mark; one table (bench_blt_case.py run).
BLT_B := $(BENCH_DIR)/blt
BLT_CASE_H := $(BLT_B)/bench_blt_case.h
BENCH_BLT := $(BENCH_DIR)/bench_blt
ARM_BENCH_BLT := $(ARM_B)/bench_blt.elf
BLT_KEYS := sb_cd sb_var ump_cd ump_var

$(BLT_CASE_H): tests/bench/bench_blt_case.py scenarios/moshup.toml $(wildcard host/ogk_host/binary/*.py) $(FFI_STAMP)
	$(VPY) tests/bench/bench_blt_case.py header $@

$(BENCH_BLT): tests/bench/bench_blt.c $(BLT_CASE_H) $(B)/host/libogk.a $(PORT_HOST_SRC) | apt
	@mkdir -p $(@D)
	gcc -std=c99 -O2 -g -Wall -Wextra -Werror $(KINC) -Iport/include -I$(BLT_B) \
	  $< $(PORT_HOST_SRC) $(B)/host/libogk.a -o $@ -lm

$(ARM_BENCH_BLT): tests/bench/bench_blt.c $(BLT_CASE_H) $(ARM_RT_OBJ) $(ARM_B)/libogk.a $(ARM_LDSCRIPT)
	$(ARM_CC) -std=c99 -Wall -Wextra -Werror -O2 -g $(ARM_CPU) -DOGK_BENCH_BARE_METAL \
	  $(KINC) -Iport/include -I$(ARMV7M_DIR) -I$(BLT_B) $< $(ARM_RT_OBJ) $(ARM_B)/libogk.a \
	  $(ARM_LDFLAGS) $(ARM_LDLIBS) -o $@

.PHONY: bench-blt bench-blt-profile
bench-blt: $(BENCH_BLT) $(ARM_BENCH_BLT) $(ARM_CI) qemu-plugin $(FFI_STAMP)
	@echo "== BLT / NRPC: one iteration and a whole convergence (docs/design/blt.md, \"Cost\") =="
	@rm -f $(BLT_B)/*.txt
	@$(BENCH_BLT) time > $(BLT_B)/host.txt
	@for k in $(BLT_KEYS); do for u in iteration converge; do \
	  n=$$(valgrind --tool=callgrind --callgrind-out-file=/dev/null \
	       --collect-atstart=no --toggle-collect=bench_blt_$${u}_once \
	       $(BENCH_BLT) once $$k $$u 2>&1 | sed -n 's/.*Collected : \([0-9]*\).*/\1/p'); \
	  case $$u in iteration) s=iter;; *) s=conv;; esac; \
	  echo "blt_$${k}_$${s}_callgrind $$n"; \
	done; done > $(BLT_B)/callgrind.txt
	@port/qemu-plugin/count_insns.sh $(ARM_BENCH_BLT) $(foreach k,$(BLT_KEYS),bench_blt_m7_iter_$(k) bench_blt_m7_conv_$(k)) \
	  2> $(BLT_B)/m7_run.log | \
	  awk '$$2 == "fn" && $$3 ~ /^bench_blt_m7_(iter|conv)_/ { k = $$3; sub(/^bench_blt_m7_/, "", k); \
	    u = substr(k, 1, 4); k = substr(k, 6); print "blt_" k "_" u "_m7_insns", $$9 }' > $(BLT_B)/m7.txt
	@sed -n 's/^\(blt_m7_[a-z0-9_]* [0-9.e+-]*\).*/\1/p; s/.*stack high-water mark: \([0-9]*\) of.*/blt_m7_stack_hwm \1/p' \
	  $(BLT_B)/m7_run.log >> $(BLT_B)/m7.txt
	@python3 port/cortex-m7/stack_report.py $(ARM_CI) > $(BLT_B)/stack_report.log; \
	  awk '$$1 == "ogk_blt_solve" { print "blt_stack_solve", $$3 } $$1 == "ogk_blt_jacobian" { print "blt_stack_jacobian", $$3 } \
	    $$1 == "ogk_blt_evaluate" { print "blt_stack_evaluate", $$3 }' $(BLT_B)/stack_report.log > $(BLT_B)/stack.txt
	@$(VPY) tests/bench/bench_blt_case.py run --figures $(BLT_B)

# Where an iteration's instructions go: callgrind of one iteration of BLT_PROFILE (a key of BLT_KEYS),
# inclusive and self cost per function.
BLT_PROFILE ?= ump_cd
bench-blt-profile: $(BENCH_BLT)
	valgrind --tool=callgrind --callgrind-out-file=$(BLT_B)/callgrind_$(BLT_PROFILE).out \
	  --collect-atstart=no --toggle-collect=bench_blt_iteration_once $(BENCH_BLT) once $(BLT_PROFILE) iteration
	callgrind_annotate --inclusive=yes $(BLT_B)/callgrind_$(BLT_PROFILE).out | head -40
	callgrind_annotate $(BLT_B)/callgrind_$(BLT_PROFILE).out | head -30

bench: bench-blt

# Dense QP against DAQP and qpOASES (docs/design/qp.md): after the NMPC section, whose case header it uses.
include tests/bench/bench_qp.mk
bench: bench-qp

# ---------------------------------------------------------------- flops per call (docs/design/performance.md)
# Double-precision flops of each hot path's one call, counted exactly from callgrind's per-instruction
# counts and the binaries' disassembly (tests/bench/flops.py), beside its instructions.
FLOPS := $(VPY) tests/bench/flops.py
.PHONY: bench-flops
bench-flops: $(BENCH_CORE) $(BENCH_GNC) $(NOG_TABLE) $(BENCH_MPSP) $(BENCH_NMPC) $(BENCH_BLT) | apt
	@echo "== flops per call (x86-64 gcc -O2, callgrind; docs/design/performance.md) =="
	@$(FLOPS) rk4_step bench_rk4_step_once -- $(BENCH_CORE) once rk4_step
	@$(FLOPS) qp bench_qp_once -- $(BENCH_CORE) once qp
	@$(FLOPS) nog_sample bench_nog_sample_once -- $(BENCH_GNC) $(NOG_TABLE) once nog_sample
	@$(FLOPS) cpd_step bench_cpd_step_once -- $(BENCH_GNC) $(NOG_TABLE) once cpd_step
	@$(FLOPS) mpsp_iter bench_mpsp_iter_once -- $(BENCH_MPSP) once mpsp_iter
	@$(FLOPS) "mpsp_iter mid2" bench_mpsp_iter_mid2_once -- $(BENCH_MPSP) once mpsp_iter_mid2
	@$(FLOPS) nmpc_replan bench_nmpc_replan_once -- $(BENCH_NMPC) once
	@$(FLOPS) "nmpc_replan exact" bench_nmpc_replan_once -- $(BENCH_NMPC) once exact
	@$(FLOPS) "nmpc_replan exact tol0" bench_nmpc_replan_once -- $(BENCH_NMPC) once exact tol0
	@$(FLOPS) "blt iteration sb_var" bench_blt_iteration_once -- $(BENCH_BLT) once sb_var iteration
	@$(FLOPS) "blt iteration ump_var" bench_blt_iteration_once -- $(BENCH_BLT) once ump_var iteration

bench: bench-flops
