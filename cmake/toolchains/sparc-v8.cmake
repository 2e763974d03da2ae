# sparc-v8.cmake -- 32-bit big-endian SPARC V8 (LEON3 / GR740's ISA) with Debian's cross gcc, as the
# Makefile's SPARC build (port/sparc-v8): -m32 -mcpu=v8 links Debian's 32-bit SPARC libc (v8plus), so
# programs are linked -static and run with qemu-sparc32plus.
set(CMAKE_SYSTEM_NAME Linux)
set(CMAKE_SYSTEM_PROCESSOR sparc)
set(CMAKE_C_COMPILER sparc64-linux-gnu-gcc)
set(CMAKE_C_FLAGS_INIT "-m32 -mcpu=v8")
set(CMAKE_EXE_LINKER_FLAGS_INIT "-static")
set(CMAKE_FIND_ROOT_PATH_MODE_PROGRAM NEVER)
set(CMAKE_FIND_ROOT_PATH_MODE_PACKAGE BOTH)
