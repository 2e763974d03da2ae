# tests/unit/unit_errors.mk -- the worst error of every tolerance assertion of the unit tests, in both
# precisions of the real type: the figures of docs/design/precision-unit-tests.md. Not a gate (not in
# make test): a measurement, re-made by one command when a law or a tolerance changes.
#
#   make unit-errors    every tests/unit/*/test_*.c built with -DOGK_TEST_MEASURE (tests/unit/ogk_test.h:
#                       each OGK_ASSERT_NEAR / _LE / _LT site prints its worst value so far) on the host
#                       in double and in single (ASan/UBSan as test-unit-host) and on the Cortex-M4F
#                       (QEMU mps2-an386, single); tests/unit/unit_errors.py keeps each site's worst and
#                       writes $(B)/unit-errors/unit_errors.{md,json}. A test that fails still reports the
#                       sites it reached; the failures are listed.
#
# Included by the top-level Makefile after the ARMv7-M targets (uses host_unit_target, M4F_*, ARMV7M_DIR).

UERR_B := $(B)/unit-errors
$(eval $(call host_unit_target,UERR_HD,unit-errors/host-double,,-DOGK_TEST_MEASURE))
$(eval $(call host_unit_target,UERR_HS,unit-errors/host-single,-DOGK_REAL_SINGLE=1,-DOGK_TEST_MEASURE))
UERR_M4F := $(addprefix $(UERR_B)/m4f/,$(addsuffix .elf,$(UNIT_NAMES)))
$(UERR_B)/m4f/test_%.elf: test_%.c $(UNIT_HDR) $(M4F_RT_OBJ) $(M4F_B)/libogk.a $(M4F_LDSCRIPT)
	@mkdir -p $(@D)
	$(M4F_CC) $(M4F_TEST_CFLAGS) -DOGK_TEST_MEASURE $< $(M4F_RT_OBJ) $(M4F_B)/libogk.a $(M4F_LDFLAGS) \
	  $(M4F_LDLIBS) -o $@

.PHONY: unit-errors
unit-errors: $(UERR_HD_TESTS) $(UERR_HS_TESTS) $(UERR_M4F)
	@for t in $(UERR_HD_TESTS); do $$t > $$t.log 2>&1; echo "exit $$?" >> $$t.log; done
	@for t in $(UERR_HS_TESTS); do $$t > $$t.log 2>&1; echo "exit $$?" >> $$t.log; done
	@for e in $(UERR_M4F); do $(call armv7m_env,M4F) $(ARMV7M_DIR)/run_qemu.sh $$e $(M4F_TIMEOUT) > $${e%.elf}.log 2>&1; \
	  echo "exit $$?" >> $${e%.elf}.log; done
	$(PYTHON) tests/unit/unit_errors.py --build $(UERR_B) --out $(UERR_B)/unit_errors
