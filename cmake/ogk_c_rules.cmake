# ogk_c_rules.cmake -- CMAKE_USER_MAKE_RULES_OVERRIDE_C of the kernel's build: object files are named
# crc32.o on every target (CMake names them crc32.obj on a Generic system such as the bare-metal
# Cortex-M7, and the extension is fixed when the language is enabled), so the archive members and the
# -fstack-usage files keep the names the Makefile's evidence (map files, profile, stack bound) reads.
set(CMAKE_C_OUTPUT_EXTENSION .o)
