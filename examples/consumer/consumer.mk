# examples/consumer/consumer.mk -- `make test-consumer` (in `make test`; docs/guides/cmake.md): what a flight
# project does with ogk, from scratch, with nothing from the Makefile's own kernel builds:
#   the package built and installed by CMake alone, for the host and for the Cortex-M7
#   (build/cm-host -> build/ogk-prefix-host, build/cm-m7 -> build/ogk-prefix-m7), then
#   examples/consumer configured with find_package(ogk 0.1) against each prefix, built and run:
#   on the host directly, on the Cortex-M7 under QEMU (mps2-an500, the board files of port/armv7m).
# Fails on any configure, build, install or link error and on any law whose flight loop fails.
# Included by the top-level Makefile (uses its B, CMAKE_BUILD, ARMV7M_DIR, armv7m_env).
CONSUMER_DIRS := $(B)/cm-host $(B)/cm-m7 $(B)/ogk-prefix-host $(B)/ogk-prefix-m7 $(B)/consumer-host $(B)/consumer-m7
PREFIX_M7 := $(abspath $(B)/ogk-prefix-m7)

.PHONY: test-consumer
test-consumer: | apt
	rm -rf $(CONSUMER_DIRS)
	cmake -B $(B)/cm-host -S . --log-level=WARNING
	$(CMAKE_BUILD) $(B)/cm-host -j2
	cmake --install $(B)/cm-host --prefix $(B)/ogk-prefix-host > $(B)/cm-host/install.log
	cmake -B $(B)/cm-m7 -S . -DCMAKE_TOOLCHAIN_FILE=cmake/toolchains/cortex-m7.cmake --log-level=WARNING
	$(CMAKE_BUILD) $(B)/cm-m7 -j2
	cmake --install $(B)/cm-m7 --prefix $(B)/ogk-prefix-m7 > $(B)/cm-m7/install.log
	cmake -S examples/consumer -B $(B)/consumer-host -DCMAKE_PREFIX_PATH=$(abspath $(B)/ogk-prefix-host) \
	  --log-level=WARNING
	$(CMAKE_BUILD) $(B)/consumer-host
	$(B)/consumer-host/ogk_consumer
	@# the package's own toolchain file, as a flight project would take it
	cmake -S examples/consumer -B $(B)/consumer-m7 -DCMAKE_PREFIX_PATH=$(PREFIX_M7) \
	  -DCMAKE_TOOLCHAIN_FILE=$(PREFIX_M7)/lib/cmake/ogk/toolchains/cortex-m7.cmake \
	  -DOGK_CONSUMER_BOARD_DIR=$(abspath $(ARMV7M_DIR)) --log-level=WARNING
	$(CMAKE_BUILD) $(B)/consumer-m7
	$(call armv7m_env,ARM) $(ARMV7M_DIR)/run_qemu.sh $(B)/consumer-m7/ogk_consumer.elf 300
