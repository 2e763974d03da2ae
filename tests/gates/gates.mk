# tests/gates/gates.mk -- quality gates of the kernel (issue 8, item 3). Included by the top-level
# Makefile after port/cortex-m7/flightapp/flightapp.mk; uses its STRICT, KINC, KSRC, KHDR, SAN, B,
# VENV and UNIT_SRC. Everything is built under $(B)/gates, $(B)/fuzz, $(B)/coverage, $(B)/mutants.
#
#   make tidy                    clang-tidy (bugprone-*, cert-*, clang-analyzer-*; .clang-tidy) over
#                                kernel/src: fails on any finding (docs/static-analysis.md)
#   make fuzz-short              every libFuzzer harness of tests/fuzz for FUZZ_SHORT_SECONDS each
#                                (about a minute in all; for make test)
#   make fuzz FUZZ_SECONDS=N     the same, N seconds per harness
#   make coverage                the unit tests built with gcc --coverage, gcovr over kernel/:
#                                fails under COVERAGE_LINES / COVERAGE_BRANCHES (docs/coverage.md)
#   make mutants                 deterministic mutation run over kernel/src (tests/gates/mutants.py),
#                                C unit tests only; prints killed/survived and the score
#   make gates                   tidy fuzz-short coverage (what make test should run)

GATES_B := $(B)/gates

# ---------------------------------------------------------------- clang-tidy
CLANG_TIDY ?= clang-tidy
TIDY_FLAGS := -std=c99 $(KINC)
TIDY_LOG := $(GATES_B)/tidy.log

.PHONY: tidy gates
tidy: | apt
	@mkdir -p $(GATES_B)
	@$(CLANG_TIDY) --quiet $(KSRC) -- $(TIDY_FLAGS) > $(TIDY_LOG) 2> $(TIDY_LOG).err; rc=$$?; \
	n=$$(grep -cE '(warning|error):' $(TIDY_LOG)); \
	grep -E '(warning|error):' $(TIDY_LOG) | sed 's|^$(CURDIR)/||'; \
	if [ $$n -ne 0 ] || [ $$rc -ne 0 ]; then \
	  echo "tidy: $$n finding(s) in kernel/src (full log: $(TIDY_LOG)); fix each or suppress it at its line with a reason"; \
	  [ $$n -ne 0 ] || cat $(TIDY_LOG).err; exit 1; fi; \
	echo "tidy: clang-tidy clean over kernel/src ($(words $(KSRC)) files; checks of .clang-tidy)"
