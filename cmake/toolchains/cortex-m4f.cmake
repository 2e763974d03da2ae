# cortex-m4f.cmake -- bare-metal Arm Cortex-M4F (arm-none-eabi-gcc, newlib): the single-precision FPU
# only (FPv4-SP-D16), as on radiation-hardened M4F parts and cubesat boards. The CPU flags are the
# kernel's flight flags for this core (the Makefile's M4F_CPU): float arithmetic on the FPU, double
# arithmetic as library calls (libgcc's __aeabi_d*), the AAPCS-VFP calling convention. They are also on
# every link line, which picks newlib's matching multilib (thumb/v7e-m+fp/hard). The board (linker
# script, startup, --specs) is the application's: see examples/consumer for QEMU's mps2-an386.
set(CMAKE_SYSTEM_NAME Generic)
set(CMAKE_SYSTEM_PROCESSOR cortex-m4f)
set(CMAKE_C_COMPILER arm-none-eabi-gcc)
set(CMAKE_C_FLAGS_INIT "-mthumb -mcpu=cortex-m4 -mfpu=fpv4-sp-d16 -mfloat-abi=hard")
# No board yet when CMake checks the compiler: test it by building a library, not by linking a program.
set(CMAKE_TRY_COMPILE_TARGET_TYPE STATIC_LIBRARY)
# Build tools are the host's; packages (ogkConfig.cmake) are found under CMAKE_PREFIX_PATH as given.
set(CMAKE_FIND_ROOT_PATH_MODE_PROGRAM NEVER)
set(CMAKE_FIND_ROOT_PATH_MODE_PACKAGE BOTH)
# The kernel's floating-point type on this FPU: single. OGK_PRECISION (double | single) is the project's
# cache option; this makes its entry first, with the value single, and the project's own
# set(... CACHE ...) then keeps it. An entry already in the cache (-DOGK_PRECISION=double on the
# command line, a re-configure) is left as it is. A CMakeLists.txt without the option never reads it.
if(NOT DEFINED CACHE{OGK_PRECISION})
  set(OGK_PRECISION single CACHE STRING "floating-point type of the kernel: double or single")
endif()
