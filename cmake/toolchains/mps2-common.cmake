# Shared part of the bare-metal Cortex-M toolchains (arm-none-eabi + newlib semihosting,
# run under qemu-system-arm on an MPS2 board). Included by cortex-m3.cmake / cortex-m7.cmake
# after they set PFT_MPS2_CPU_FLAGS and PFT_MPS2_MACHINE.
set(CMAKE_SYSTEM_NAME Generic)
set(CMAKE_SYSTEM_PROCESSOR arm)
set(CMAKE_C_COMPILER arm-none-eabi-gcc)
set(CMAKE_CXX_COMPILER arm-none-eabi-g++)
set(CMAKE_ASM_COMPILER arm-none-eabi-gcc)
set(CMAKE_TRY_COMPILE_TARGET_TYPE STATIC_LIBRARY)
set(CMAKE_C_FLAGS_INIT "${PFT_MPS2_CPU_FLAGS} -ffunction-sections -fdata-sections")
set(CMAKE_EXE_LINKER_FLAGS_INIT
    "${PFT_MPS2_CPU_FLAGS} --specs=rdimon.specs -Wl,--gc-sections -T${CMAKE_CURRENT_LIST_DIR}/../../port/qemu_mps2/mps2.ld")
set(CMAKE_FIND_ROOT_PATH_MODE_PROGRAM NEVER)
set(CMAKE_FIND_ROOT_PATH_MODE_LIBRARY ONLY)
set(CMAKE_FIND_ROOT_PATH_MODE_INCLUDE ONLY)
set(PFT_TARGET "mps2" CACHE STRING "" FORCE)
set(CMAKE_CROSSCOMPILING_EMULATOR "${CMAKE_CURRENT_LIST_DIR}/../qemu-mps2.sh;${PFT_MPS2_MACHINE}")
