# AArch64 Linux (Cortex-A53/A72 class), run under qemu-aarch64 (user mode).
set(CMAKE_SYSTEM_NAME Linux)
set(CMAKE_SYSTEM_PROCESSOR aarch64)
set(CMAKE_C_COMPILER aarch64-linux-gnu-gcc)
set(CMAKE_CXX_COMPILER aarch64-linux-gnu-g++)
set(CMAKE_FIND_ROOT_PATH /usr/aarch64-linux-gnu)
set(CMAKE_FIND_ROOT_PATH_MODE_PROGRAM NEVER)
set(CMAKE_FIND_ROOT_PATH_MODE_LIBRARY ONLY)
set(CMAKE_FIND_ROOT_PATH_MODE_INCLUDE ONLY)
set(PFT_TARGET "linux-cross" CACHE STRING "" FORCE)
set(CMAKE_CROSSCOMPILING_EMULATOR "qemu-aarch64;-L;/usr/aarch64-linux-gnu")
# The target core: empty (the default, the presets aarch64-float / aarch64-q16) compiles for
# generic AArch64 (no -mcpu); a core name such as cortex-a53 (the presets a53-float / a53-q16)
# adds -mcpu=<core>, so that gcc schedules for that core (docs/porting.md, section 6).
set(PFT_AARCH64_CPU "" CACHE STRING "AArch64 core for -mcpu (empty: generic AArch64)")
list(APPEND CMAKE_TRY_COMPILE_PLATFORM_VARIABLES PFT_AARCH64_CPU)
if(PFT_AARCH64_CPU)
  # set, not appended: CMake reads this file more than once
  set(CMAKE_C_FLAGS_INIT "-mcpu=${PFT_AARCH64_CPU}")
  set(CMAKE_CXX_FLAGS_INIT "-mcpu=${PFT_AARCH64_CPU}")
endif()
