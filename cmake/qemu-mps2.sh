#!/bin/sh
# CTest emulator hook for bare-metal tests: qemu-mps2.sh MACHINE ELF [ARGS...]
# Runs ELF on the MPS2 board under qemu-system-arm with semihosting (stdio, argv, exit code).
# A hung image is killed after PFT_QEMU_TIMEOUT seconds (default 300: the Cortex-M3 q16 stage
# tests took about 50 s in CI runs and up to about 120 s on a loaded two-core machine).
machine=$1; elf=$2; shift 2
exec timeout "${PFT_QEMU_TIMEOUT:-300}" qemu-system-arm -M "$machine" -nographic -monitor none \
  -semihosting-config enable=on,target=native -kernel "$elf" ${1:+-append "$*"}
