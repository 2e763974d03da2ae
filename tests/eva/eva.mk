# tests/eva/eva.mk -- Frama-C EVA over the kernel's public entry points (issue 22, item 3).
# Included by the top-level Makefile; uses its PYTHON. docs/evidence/eva.md says what is analysed, with
# which ranges, and lists every remaining alarm with its reason.
#
#   make eva            every driver of tests/eva/eva_gate.py (tests/eva/drv_*.c), two at a time;
#                       fails when a driver's alarm count exceeds tests/eva/baseline.json, when a
#                       zero-alarm module has one, or when an analysis does not finish
#   make eva-update     the same, then lowers the baseline to today's counts (never raises it)

.PHONY: eva eva-update
eva: | apt
	$(PYTHON) tests/eva/eva_gate.py --jobs 2

eva-update: | apt
	$(PYTHON) tests/eva/eva_gate.py --jobs 2 --update
