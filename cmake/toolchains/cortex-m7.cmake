# Cortex-M7 with double-precision FPU, hard-float ABI (MPS2 AN500 under qemu-system-arm).
set(PFT_MPS2_CPU_FLAGS "-mcpu=cortex-m7 -mthumb -mfpu=fpv5-d16 -mfloat-abi=hard")
set(PFT_MPS2_MACHINE mps2-an500)
include(${CMAKE_CURRENT_LIST_DIR}/mps2-common.cmake)
