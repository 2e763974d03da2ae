# host-gcc.cmake -- the host build of ogk (x86-64 Linux, gcc), as `make kernel-host` builds it.
# The default without a toolchain file is the same; this file pins the compiler.
set(CMAKE_C_COMPILER gcc)
