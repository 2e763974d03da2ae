# cortex-m7.cmake -- bare-metal Arm Cortex-M7 with the double-precision FPU (arm-none-eabi-gcc, newlib).
# The CPU flags are the kernel's flight flags (the Makefile's ARM_CPU); without -mfpu=fpv5-d16 and
# -mfloat-abi=hard every double operation would be a library call. They are also on every link line,
# which picks newlib's matching hard-float multilib. The board (linker script, startup, --specs) is the
# application's: see examples/consumer for QEMU's mps2-an500.
set(CMAKE_SYSTEM_NAME Generic)
set(CMAKE_SYSTEM_PROCESSOR cortex-m7)
set(CMAKE_C_COMPILER arm-none-eabi-gcc)
set(CMAKE_C_FLAGS_INIT "-mthumb -mcpu=cortex-m7 -mfpu=fpv5-d16 -mfloat-abi=hard")
# No board yet when CMake checks the compiler: test it by building a library, not by linking a program.
set(CMAKE_TRY_COMPILE_TARGET_TYPE STATIC_LIBRARY)
# Build tools are the host's; packages (ogkConfig.cmake) are found under CMAKE_PREFIX_PATH as given.
set(CMAKE_FIND_ROOT_PATH_MODE_PROGRAM NEVER)
set(CMAKE_FIND_ROOT_PATH_MODE_PACKAGE BOTH)
