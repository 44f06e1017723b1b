#!/usr/bin/env bash
# Instructions per frame and per pixel of pft_pre_update (callgrind, exact), per method, for
# the library of each build directory given (e.g. build/host-float build/host-q16), on a
# procedural drifting scene of the given size (12 frames; the first, the background's start,
# is cheap for the temporal method and included: the table gives the mean over frames 2..12).
#   bash tests/tools/pre_callgrind.sh OUT_DIR WxH BUILD_DIR... [-- key=value ...]
set -euo pipefail
out=$1; size=$2; shift 2
builds=(); extra=()
while [ $# -gt 0 ]; do
  if [ "$1" = "--" ]; then shift; extra=("$@"); break; fi
  builds+=("$1"); shift
done
src=$(cd "$(dirname "$0")/../.." && pwd)
mkdir -p "$out"
w=${size%x*}; h=${size#*x}
seq="$out/seq_${size}.u16"
[ -f "$seq" ] || /usr/bin/python3 "$src/tests/tools/pre_explore.py" /bin/true --procedural 1 \
  --size "$size" --frames 12 --sigma-col 8 --write-seq "$seq" >/dev/null
printf "%-22s %-9s %14s %10s\n" build method "instr/frame" "instr/px"
for b in "${builds[@]}"; do
  num=$(sed -n 's/^#define PFT_NUMERIC_\([A-Z0-9]*\) 1/\1/p' "$b/lib/include/pft/pft_build_config.h" | tr A-Z a-z)
  probe="$out/pre_probe_$(basename "$b")"
  cc -O2 -std=c99 -I"$src/lib/include" -I"$b/lib/include" "$src/tests/tools/pre_probe.c" \
     "$b/lib/libpftrack_${num}.a" -lm -o "$probe"
  for m in temporal local; do
    cg="$out/callgrind.$(basename "$b").$m.$size"
    valgrind --tool=callgrind --callgrind-out-file="$cg" --toggle-collect=pft_pre_update \
      --dump-after=pft_pre_update "$probe" "$seq" "$w" "$h" 14 method=$m "${extra[@]}" \
      >/dev/null 2>"$cg.log"
    # one dump per frame: frames 2..12
    tot=0; n=0
    for f in "$cg".*; do
      case "$f" in *.log) continue ;; esac
      k=${f##*.}
      [ "$k" -ge 2 ] 2>/dev/null || continue
      ir=$(sed -n 's/^summary: \([0-9]*\).*/\1/p' "$f")
      [ -n "$ir" ] || continue
      tot=$((tot + ir)); n=$((n + 1))
    done
    per=$((tot / n))
    printf "%-22s %-9s %14d %10.1f\n" "$(basename "$b")" "$m" "$per" "$(echo "$per / ($w * $h)" | bc -l)"
  done
done
