# examples/consumer/consumer.mk -- `make test-consumer` (in `make test`; docs/guides/cmake.md): what a flight
# project does with ogk, from scratch, with nothing from the Makefile's own kernel builds:
#   the package built and installed by CMake alone, for the host, the Cortex-M7 and the Cortex-M4F
#   (build/cm-host -> build/ogk-prefix-host, build/cm-m7 -> build/ogk-prefix-m7, build/cm-m4f ->
#   build/ogk-prefix-m4f), then examples/consumer configured with find_package(ogk 0.1) against each
#   prefix, built and run: on the host directly, on the Cortex-M7 (mps2-an500) and the Cortex-M4F
#   (mps2-an386) under QEMU, with the board files of port/armv7m; the M4F's package in its M4F_PRECISION
#   (single: the law loops compute in float there, examples/consumer/consumer.h).
#   Then the single-precision package (OGK_PRECISION=single, kernel/include/ogk/real.h) for the host
#   (build/cm-host-single -> build/ogk-prefix-host-single): its ogk.pc and ogk::ogk carry OGK_REAL_SINGLE=1,
#   examples/consumer's real-type probe built against it finds the library's float, and its law loops
#   run in float as on the M4F.
# Fails on any configure, build, install or link error and on any law whose flight loop fails.
# Included by the top-level Makefile (uses its B, CMAKE_BUILD, ARMV7M_DIR, armv7m_env).
CONSUMER_DIRS := $(B)/cm-host $(B)/ogk-prefix-host $(B)/consumer-host \
  $(foreach t,m7 m4f,$(B)/cm-$(t) $(B)/ogk-prefix-$(t) $(B)/consumer-$(t)) \
  $(B)/cm-host-single $(B)/ogk-prefix-host-single $(B)/consumer-host-single
PREFIX_HOST_SINGLE := $(abspath $(B)/ogk-prefix-host-single)

# $(call consumer_armv7m,TAG,TOOLCHAIN,P[,CMAKE_ARGS]): the package built and installed with cmake/toolchains/TOOLCHAIN.cmake
# into build/ogk-prefix-TAG, the consumer built with the installed toolchain file (as a flight project
# would take it) and run on the board of ARMv7-M target P.
consumer_armv7m = cmake -B $(B)/cm-$(1) -S . -DCMAKE_TOOLCHAIN_FILE=cmake/toolchains/$(2).cmake $(4) \
	  --log-level=WARNING && \
	$(CMAKE_BUILD) $(B)/cm-$(1) -j2 && \
	cmake --install $(B)/cm-$(1) --prefix $(B)/ogk-prefix-$(1) > $(B)/cm-$(1)/install.log && \
	cmake -S examples/consumer -B $(B)/consumer-$(1) -DCMAKE_PREFIX_PATH=$(abspath $(B)/ogk-prefix-$(1)) \
	  -DCMAKE_TOOLCHAIN_FILE=$(abspath $(B)/ogk-prefix-$(1))/lib/cmake/ogk/toolchains/$(2).cmake \
	  -DOGK_CONSUMER_BOARD_DIR=$(abspath $(ARMV7M_DIR)) --log-level=WARNING && \
	$(CMAKE_BUILD) $(B)/consumer-$(1) && \
	$(call armv7m_env,$(3)) $(ARMV7M_DIR)/run_qemu.sh $(B)/consumer-$(1)/ogk_consumer.elf 300

.PHONY: test-consumer
test-consumer: | apt
	rm -rf $(CONSUMER_DIRS)
	cmake -B $(B)/cm-host -S . --log-level=WARNING
	$(CMAKE_BUILD) $(B)/cm-host -j2
	cmake --install $(B)/cm-host --prefix $(B)/ogk-prefix-host > $(B)/cm-host/install.log
	cmake -S examples/consumer -B $(B)/consumer-host -DCMAKE_PREFIX_PATH=$(abspath $(B)/ogk-prefix-host) \
	  --log-level=WARNING
	$(CMAKE_BUILD) $(B)/consumer-host
	$(B)/consumer-host/ogk_real_probe | grep -q 'double (8 bytes)'
	$(B)/consumer-host/ogk_consumer
	@# the package's own toolchain file, as a flight project would take it
	$(call consumer_armv7m,m7,cortex-m7,ARM)
	$(call consumer_armv7m,m4f,cortex-m4f,M4F,-DOGK_PRECISION=$(M4F_PRECISION))
	@# the single-precision package: the definition reaches a consumer by pkg-config and by the CMake target
	cmake -B $(B)/cm-host-single -S . -DOGK_PRECISION=single -DOGK_BUILD_SHARED=OFF --log-level=WARNING
	$(CMAKE_BUILD) $(B)/cm-host-single -j2
	cmake --install $(B)/cm-host-single --prefix $(B)/ogk-prefix-host-single > $(B)/cm-host-single/install.log
	PKG_CONFIG_PATH=$(PREFIX_HOST_SINGLE)/lib/pkgconfig pkg-config --cflags ogk | grep -q -- '-DOGK_REAL_SINGLE=1'
	cmake -S examples/consumer -B $(B)/consumer-host-single -DCMAKE_PREFIX_PATH=$(PREFIX_HOST_SINGLE) \
	  --log-level=WARNING
	$(CMAKE_BUILD) $(B)/consumer-host-single
	$(B)/consumer-host-single/ogk_real_probe | grep -q 'float (4 bytes)'
	$(B)/consumer-host-single/ogk_consumer
