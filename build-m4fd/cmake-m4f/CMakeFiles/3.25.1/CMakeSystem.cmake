set(CMAKE_HOST_SYSTEM "Linux-6.18.44-fc-v1272")
set(CMAKE_HOST_SYSTEM_NAME "Linux")
set(CMAKE_HOST_SYSTEM_VERSION "6.18.44-fc-v1272")
set(CMAKE_HOST_SYSTEM_PROCESSOR "x86_64")

include("/work/wt-utf/cmake/toolchains/cortex-m4f.cmake")

set(CMAKE_SYSTEM "Generic")
set(CMAKE_SYSTEM_NAME "Generic")
set(CMAKE_SYSTEM_VERSION "")
set(CMAKE_SYSTEM_PROCESSOR "cortex-m4f")

set(CMAKE_CROSSCOMPILING "TRUE")

set(CMAKE_SYSTEM_LOADED 1)
