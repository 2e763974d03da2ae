# Dense QP against its peers (docs/design/qp.md, "Measured against DAQP and qpOASES"): `make bench-qp`.
# Two sets of QPs: (a) every QP that `bench_nmpc once` hands to ogk_qp_solve (the open loop and the
# one re-solve; recorded by a build of tests/bench/bench_nmpc.c linked with
# -Wl,--wrap=ogk_qp_solve and tests/bench/bench_qp_record.c, no hook in kernel/), (b) random strictly
# convex QPs, n = 16-67, of tests/python/test_qp.py's generator with a fixed seed. The kernel and
# DAQP are both called from C on the same arrays (DAQP's C sources from its PyPI sdist, the version in
# the venv, compiled with the kernel's compiler and -O2); qpOASES (CasADi) through Python, beside the
# kernel and DAQP through Python. Callgrind counts the kernel's instructions per set.
QPPEER_B := $(BENCH_DIR)/qp
QPPEER_BIN := $(QPPEER_B)/bench_qp_peers
QPPEER_REC := $(QPPEER_B)/bench_nmpc_record
QPPEER_DAQP := $(QPPEER_B)/daqp
QPPEER_DAQP_STAMP := $(QPPEER_DAQP)/.unpacked

# The sdist of the daqp in the venv (pip's ordinary download; its csrc/ is DAQP's C solver).
$(QPPEER_DAQP_STAMP): $(VENV)/.installed
	@rm -rf $(QPPEER_DAQP) && mkdir -p $(QPPEER_DAQP)
	v=$$($(VPY) -c 'import importlib.metadata as m; print(m.version("daqp"))'); \
	  $(VENV)/bin/pip download --quiet --no-deps --no-binary :all: -d $(QPPEER_DAQP) "daqp==$$v" && \
	  tar -xzf $(QPPEER_DAQP)/daqp-$$v.tar.gz -C $(QPPEER_DAQP) && \
	  ln -sfn daqp-$$v/csrc $(QPPEER_DAQP)/csrc
	@touch $@

$(QPPEER_BIN): tests/bench/bench_qp_peers.c $(B)/host/libogk.a $(QPPEER_DAQP_STAMP) | apt
	@mkdir -p $(@D)
	gcc -std=c99 -O2 -g $(KINC) -I$(QPPEER_DAQP)/csrc/include $< $(QPPEER_DAQP)/csrc/src/*.c \
	  $(B)/host/libogk.a -o $@ -lm

# The same with DAQP compiled with the flags of its own setup.py (the kernel stays at -O2).
QPPEER_BIN_O3 := $(QPPEER_B)/bench_qp_peers_daqp_o3
QPPEER_DAQP_O3_FLAGS := -O3 -fassociative-math -fno-signed-zeros -fno-trapping-math
$(QPPEER_BIN_O3): tests/bench/bench_qp_peers.c $(B)/host/libogk.a $(QPPEER_DAQP_STAMP) | apt
	@mkdir -p $(QPPEER_B)/daqp_o3
	cd $(QPPEER_B)/daqp_o3 && for f in $(CURDIR)/$(QPPEER_DAQP)/csrc/src/*.c; do \
	  gcc -std=c99 $(QPPEER_DAQP_O3_FLAGS) -I$(CURDIR)/$(QPPEER_DAQP)/csrc/include -c $$f || exit 1; done
	gcc -std=c99 -O2 -g $(KINC) -I$(QPPEER_DAQP)/csrc/include $< $(QPPEER_B)/daqp_o3/*.o \
	  $(B)/host/libogk.a -o $@ -lm

$(QPPEER_REC): tests/bench/bench_nmpc.c tests/bench/bench_qp_record.c $(NMPC_CASE_H) $(B)/host/libogk.a $(PORT_HOST_SRC) | apt
	@mkdir -p $(@D)
	gcc -std=c99 -O2 -g -Wall -Wextra -Werror $(KINC) -Iport/include -I$(NMPC_B) \
	  tests/bench/bench_nmpc.c tests/bench/bench_qp_record.c $(PORT_HOST_SRC) $(B)/host/libogk.a \
	  -Wl,--wrap=ogk_qp_solve -o $@ -lm

.PHONY: bench-qp
bench-qp: $(QPPEER_BIN) $(QPPEER_BIN_O3) $(QPPEER_REC) $(FFI_STAMP)
	@$(VPY) tests/bench/bench_qp_peers.py --peers $(QPPEER_BIN) --peers-daqp-o3 $(QPPEER_BIN_O3) \
	  --recorder $(QPPEER_REC) --out $(QPPEER_B)
