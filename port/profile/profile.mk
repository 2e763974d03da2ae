# port/profile/profile.mk -- certification evidence (issue 22, docs/evidence/profile.md). Included by the top-level
# Makefile after the ports.
#
#   make stack-bound-m7   worst-case stack of every public entry point on the Cortex-M7, libm, libc and the
#                         kernel's own callbacks included: the disassembly of the linked unit-test ELFs, each
#                         frame checked against gcc -fstack-usage (port/profile/stack_bound.py). Fails on
#                         recursion, an unsized frame or a frame gcc disagrees with. In make test.
#   make footprint-m7     code / read-only / RAM per kernel module and the size of every public type
#                         (port/profile/footprint.py); fails on a mutable global. In make test.
#   make stack-bound-m4f, footprint-m4f   the same on the Cortex-M4F (its unit-test ELFs and objects, the
#                         kernel's configuration for it). In make test.

PROFILE_B := $(B)/profile
PROFILE_PY := $(wildcard port/profile/*.py)

# $(call profile_armv7m,P,TAG): build/profile/stack_TAG.json and footprint_TAG.json of the ARMv7-M target
# P (port/armv7m/armv7m.mk), from its unit-test ELFs P_UNIT_ELF and its kernel objects; the public types
# are sized with its CPU flags and kernel configuration.
define profile_armv7m
$(1)_UNIT_ELF := $$(patsubst %,$$($(1)_B)/%.elf,$$(basename $$(notdir $$($(1)_UNIT_SRC))))
$$(PROFILE_B)/stack_$(2).json: $$($(1)_UNIT_ELF) $$($(1)_KOBJ) $$(PROFILE_PY)
	@mkdir -p $$(@D)
	python3 port/profile/stack_bound.py --isa thumb --objdump arm-none-eabi-objdump \
	  --su-dir $$($(1)_B)/kernel --objects $$($(1)_KOBJ) --json $$@.tmp -- $$($(1)_UNIT_ELF) \
	  && mv $$@.tmp $$@
$$(PROFILE_B)/footprint_$(2).json: $$($(1)_KOBJ) $$(KHDR) $$(PROFILE_PY)
	@mkdir -p $$(@D)
	python3 port/profile/footprint.py --cc "$$(strip $$($(1)_CC) -std=c99 $$($(1)_CPU) $$($(1)_DEFS))" \
	  --size arm-none-eabi-size --nm arm-none-eabi-nm --json $$@ -- $$($(1)_KOBJ)
endef
$(eval $(call profile_armv7m,ARM,m7))
$(eval $(call profile_armv7m,M4F,m4f))

.PHONY: stack-bound-m7 footprint-m7 stack-bound-m4f footprint-m4f stack-bound-sparc footprint-sparc
stack-bound-m7: $(PROFILE_B)/stack_m7.json
footprint-m7: $(PROFILE_B)/footprint_m7.json
stack-bound-m4f: $(PROFILE_B)/stack_m4f.json
footprint-m4f: $(PROFILE_B)/footprint_m4f.json

# The same on SPARC V8 (the static glibc of the qemu-user route; docs/guides/ports.md). glibc's libm there is
# built with the stack protector: its abort path, __stack_chk_fail, sizes its message on the stack from a
# register and ends the process, so it is named a terminating path (its own frame still counts).
SPARC_UNIT_EXE := $(patsubst %,$(SPARC_B)/%,$(basename $(notdir $(SPARC_UNIT_SRC))))
stack-bound-sparc: $(PROFILE_B)/stack_sparc.json
$(PROFILE_B)/stack_sparc.json: $(SPARC_UNIT_EXE) $(SPARC_KOBJ) $(PROFILE_PY)
	@mkdir -p $(@D)
	python3 port/profile/stack_bound.py --isa sparc --objdump sparc64-linux-gnu-objdump \
	  --su-dir $(SPARC_B)/kernel --objects $(SPARC_KOBJ) --no-return __stack_chk_fail \
	  --json $@.tmp -- $(SPARC_UNIT_EXE) && mv $@.tmp $@
footprint-sparc: $(PROFILE_B)/footprint_sparc.json
$(PROFILE_B)/footprint_sparc.json: $(SPARC_KOBJ) $(KHDR) $(PROFILE_PY)
	@mkdir -p $(@D)
	python3 port/profile/footprint.py --cc "$(SPARC_CC) -std=c99 $(SPARC_CPU)" \
	  --size sparc64-linux-gnu-size --nm sparc64-linux-gnu-nm --json $@ -- $(SPARC_KOBJ)

# ---------------------------------------------------------------- make profile (not in make test: minutes)
#   make profile          build/profile/profile.json and docs/evidence/profile.md: per target (M7, SPARC V8, M4F), every public entry
#                         point's stack bound, the painted stack and QEMU's instructions per call at the
#                         worst input of small processor-in-the-loop campaigns of every family on both
#                         targets (fixed seed and runs: identical from run to run), code / read-only / RAM per module and the
#                         size of every public type. Fails if a painted stack exceeds its bound.
PROFILE_SEED := 20261203
# Orbit injection's watchdog allowance per run (the family's default, 2 s, is an idle machine's; under
# load 20-25 on the shared 2-core VM, leo_geo on the M7, 4 runs in lock step, had no result after
# 128 s). The other families' allowances are already long (MPSP 1800 s). The counts do not depend on it.
PROFILE_WATCHDOG_leo_geo := --watchdog-per-run 120
PROFILE_WATCHDOG_scout_upper_stage := --watchdog-per-run 120
# scenario:runs -- one or more missions of every family, flown on the emulated Cortex-M7
PROFILE_CAMPAIGNS := leo_geo:8 scout_upper_stage:4 apophis_cubesat:4 rendezvous_nep_min_time:2 \
  rendezvous_sep_min_fuel:2 moshup:6
PROFILE_PIL_M7 := $(foreach c,$(PROFILE_CAMPAIGNS),$(PROFILE_B)/pil_m7/$(firstword $(subst :, ,$(c))).json)
# ... and the same campaigns (scenarios, runs, seed) with the same flight programs on SPARC V8
PROFILE_PIL_SPARC := $(foreach c,$(PROFILE_CAMPAIGNS),$(PROFILE_B)/pil_sparc/$(firstword $(subst :, ,$(c))).json)
# ... and on the Cortex-M4F, the flight programs built on the single-precision kernel (issue 35)
PROFILE_PIL_M4F := $(foreach c,$(PROFILE_CAMPAIGNS),$(PROFILE_B)/pil_m4f/$(firstword $(subst :, ,$(c))).json)

.PHONY: profile profile-pil-m7 profile-pil-sparc profile-pil-m4f

# Each campaign's envelope is rebuilt when the kernel, the ports or its scenario change. A campaign
# whose runs fail their mission criterion, or whose target results leave the host's bounds (a perturbed
# rendezvous flown to its end amplifies libm's ulps into days, docs/guides/pil.md), exits 1 with its envelope
# written: its resource figures stand, and profile.json lists its failures and host-vs-target verdict.
# Any other exit (bad input, interrupted, no envelope) fails the profile and leaves nothing behind.
$(PROFILE_B)/pil_m7/%.json: scenarios/%.toml $(ARM_B)/libogk.a $(ARM_RT_OBJ) $(QP_SO) $(FFI_STAMP)
	@mkdir -p $(@D)
	rm -f $@ $(@:.json=.tmp.json)*
	$(VENV)/bin/ogk mc $* --target m7 --runs $(lastword $(subst :, ,$(filter $*:%,$(PROFILE_CAMPAIGNS)))) \
	  --seed $(PROFILE_SEED) --workers 2 $(PROFILE_WATCHDOG_$*) --json $(@:.json=.tmp.json); rc=$$?; \
	  if [ $$rc -gt 1 ] || [ ! -f $(@:.json=.tmp.json) ]; then exit 1; fi
	mv $(@:.json=.tmp.json) $@
profile-pil-m7: $(PROFILE_PIL_M7)

# The SPARC V8 campaigns: the PIL flight programs built for SPARC V8 Linux user mode (port/sparc-v8/pil.mk)
# under qemu-sparc32plus with the same plugin; the same rules for failed runs and bounds as above.
$(PROFILE_B)/pil_sparc/%.json: scenarios/%.toml $(SPARC_B)/libogk.a $(QP_SO) $(FFI_STAMP)
	@mkdir -p $(@D)
	rm -f $@ $(@:.json=.tmp.json)*
	$(VENV)/bin/ogk mc $* --target sparc --runs $(lastword $(subst :, ,$(filter $*:%,$(PROFILE_CAMPAIGNS)))) \
	  --seed $(PROFILE_SEED) --workers 2 $(PROFILE_WATCHDOG_$*) --json $(@:.json=.tmp.json); rc=$$?; \
	  if [ $$rc -gt 1 ] || [ ! -f $(@:.json=.tmp.json) ]; then exit 1; fi
	mv $(@:.json=.tmp.json) $@
profile-pil-sparc: $(PROFILE_PIL_SPARC)

# The Cortex-M4F campaigns (mps2-an386): the PIL flight programs on the float kernel; the same rules.
$(PROFILE_B)/pil_m4f/%.json: scenarios/%.toml $(M4F_B)/libogk.a $(QP_SO) $(FFI_STAMP)
	@mkdir -p $(@D)
	rm -f $@ $(@:.json=.tmp.json)*
	$(VENV)/bin/ogk mc $* --target m4f --runs $(lastword $(subst :, ,$(filter $*:%,$(PROFILE_CAMPAIGNS)))) \
	  --seed $(PROFILE_SEED) --workers 2 $(PROFILE_WATCHDOG_$*) --json $(@:.json=.tmp.json); rc=$$?; \
	  if [ $$rc -gt 1 ] || [ ! -f $(@:.json=.tmp.json) ]; then exit 1; fi
	mv $(@:.json=.tmp.json) $@
profile-pil-m4f: $(PROFILE_PIL_M4F)

# SPARC V8, besides the campaigns: instructions per call of the orbit-injection entry points over the
# flight application's whole flight (port/cortex-m7/flightapp built for SPARC, table decoded into RAM), by the QEMU plugin
# under qemu-user (calls return after their delay slot; make test-qemu-plugin-sparc checks it).
PROFILE_FA_ENTRIES := ogk_nog_sample ogk_nog_thrust_cmd ogk_cpd_step ogk_cpd_input_from_thrust_cmd \
  ogk_nog_table_load ogk_nog_init ogk_cpd_init
$(PROFILE_B)/insns_sparc_flightapp.txt: $(SPARC_FA) $(QP_SO)
	@mkdir -p $(@D)
	QEMU_PLUGIN_SO=$(QP_SO) QEMU_USER=$(SPARC_QEMU) NM=sparc64-linux-gnu-nm \
	  port/qemu-plugin/count_insns.sh $(SPARC_FA) $(PROFILE_FA_ENTRIES) > $@.tmp 2> /dev/null && mv $@.tmp $@

profile: deps stack-bound-m7 footprint-m7 stack-bound-sparc footprint-sparc stack-bound-m4f footprint-m4f \
  profile-pil-m7 profile-pil-sparc profile-pil-m4f $(PROFILE_B)/insns_sparc_flightapp.txt
	python3 port/profile/profile.py --stack m7=$(PROFILE_B)/stack_m7.json sparc=$(PROFILE_B)/stack_sparc.json \
	  m4f=$(PROFILE_B)/stack_m4f.json \
	  --footprint m7=$(PROFILE_B)/footprint_m7.json sparc=$(PROFILE_B)/footprint_sparc.json \
	  m4f=$(PROFILE_B)/footprint_m4f.json \
	  --campaign $(foreach f,$(PROFILE_PIL_M7),m7=$(f)) $(foreach f,$(PROFILE_PIL_SPARC),sparc=$(f)) \
	  $(foreach f,$(PROFILE_PIL_M4F),m4f=$(f)) \
	  --program sparc=flightapp=$(PROFILE_B)/insns_sparc_flightapp.txt --beside m7:m4f \
	  --json $(PROFILE_B)/profile.json --doc docs/evidence/profile.md
