# Cortex-M3, no FPU (MPS2 AN385 under qemu-system-arm).
set(PFT_MPS2_CPU_FLAGS "-mcpu=cortex-m3 -mthumb -mfloat-abi=soft")
set(PFT_MPS2_MACHINE mps2-an385)
include(${CMAKE_CURRENT_LIST_DIR}/mps2-common.cmake)
