#!/usr/bin/env bash
# The long noise-only check of docs/results/tsa_ak.md (issue #10): tests/unit/test_tsa_loss.c
# compiled with TSA_SOAK_FRAMES=FRAMES against a host build's libraries and run. Its noise soak
# starts each of TSA, TS and NCV (with the loss handling and without it, the paper's) on a
# target moving for 10 frames, then feeds FRAMES - 10 frames of pure noise (96 x 64 RGB, every
# byte uniform) and fails on the first estimate that leaves the frame by more than the
# target's box; it prints how many noise frames each reported a tracking state.
#
# Usage: host_tools/scripts/tsa_noise_soak.sh BUILD [FRAMES=1000000]   (BUILD: build/host-float ...)
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/../.." && pwd)
b=$(cd "$1" && pwd); frames=${2:-1000000}
lib=$(ls "$b"/lib/libpftrack_*.a | head -1)
port=$(ls "$b"/port/libpftrack_port_*.a | head -1)
exe=$(mktemp -d)/test_tsa_loss_soak
cc -O3 -DNDEBUG -DUNITY_INCLUDE_CONFIG_H -DTSA_SOAK_FRAMES="${frames}L" \
  -I"$root/tests/support" -I"$root/tests/vectors" -I"$root/.deps/unity/src" -I"$b/lib/include" \
  -I"$root/lib/include" -I"$root/port/include" "$root/tests/unit/test_tsa_loss.c" \
  "$b/tests/libpft_test_support.a" "$port" "$b/tests/libunity.a" "$lib" -lm -o "$exe"
"$exe"
