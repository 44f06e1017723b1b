#!/usr/bin/env bash
# Instruction counts of the TBD trackers under callgrind (exact and repeatable; wall time on
# this shared machine is not). For each build given (float and/or q16) and each configuration
#   single: one RBPF-TBD filter, N = 6000 (scenario single_6db)      toggle: pft_tbd_filter_update
#   pf:     one PF-TBD filter, N = 6000 (the same scenario)           toggle: pft_tbd_filter_update
#   two:    the manager, Ns = 6000, Nt = 500 (scenario two_case1)     toggle: pft_tbd_update
# it runs `pft bench --frames K` under valgrind with --toggle-collect on the library's update
# function (so simulation and tool code are not counted) and prints instructions per frame and
# per particle update, the wall time per frame outside valgrind, and the workspace bytes.
# Usage: host_tools/scripts/tbd_callgrind.sh OUT_DIR BUILD_DIR [BUILD_DIR...]
#   e.g. host_tools/scripts/tbd_callgrind.sh results/callgrind build/host-float build/host-q16
# FRAMES (default: the scenario's 30/35 frames) and RUNS (wall-time repeats, default 5) may be
# set in the environment. COMPONENTS=1 also prints, for builds with debug information
# (-DCMAKE_C_FLAGS=-g; the code is the same), instructions per particle update by source
# function with inlined code included (host_tools/tbd/tbd_components.py).
set -euo pipefail
OUT=${1:?usage: tbd_callgrind.sh OUT_DIR BUILD_DIR [BUILD_DIR...]}
shift
[ $# -ge 1 ] || { echo "usage: tbd_callgrind.sh OUT_DIR BUILD_DIR [BUILD_DIR...]" >&2; exit 2; }
command -v valgrind >/dev/null || { echo "valgrind not found" >&2; exit 2; }
HERE="$(cd "$(dirname "$0")" && pwd)"
SCEN="$HERE/../scenarios/tbd"
RUNS=${RUNS:-5}
mkdir -p "$OUT"

jget() { sed -n "s/.*\"$2\": *\([-0-9.e+]*\).*/\1/p" "$1" | head -1; }
jstr() { sed -n "s/.*\"$2\": *\"\([^\"]*\)\".*/\1/p" "$1" | head -1; }

printf '| build | configuration | frames | instructions/frame | instructions/particle update | particles/frame | wall ms/frame (median) | paper s/frame | workspace bytes |\n'
printf '|---|---|---|---|---|---|---|---|---|\n'
for build in "$@"; do
  PFT="$build/host_tools/pft"
  [ -x "$PFT" ] || { echo "no $PFT" >&2; exit 2; }
  for cfg in single pf two; do
    extra=()
    if [ "$cfg" = single ]; then sc="$SCEN/single_6db.json"; fn=pft_tbd_filter_update; label="single RBPF-TBD N=6000"
    elif [ "$cfg" = pf ]; then sc="$SCEN/single_6db.json"; fn=pft_tbd_filter_update; label="single PF-TBD N=6000"
      extra=(--filter pf --particles 6000)
    else sc="$SCEN/two_case1.json"; fn=pft_tbd_update; label="two-target manager Ns=6000 Nt=500"; fi
    frames_opt=("${extra[@]}")
    [ -n "${FRAMES:-}" ] && frames_opt+=(--frames "$FRAMES")
    tag="$(basename "$build")_$cfg"
    # wall time (outside valgrind)
    "$PFT" bench --scenario "$sc" --runs "$RUNS" "${frames_opt[@]}" --out "$OUT/$tag.wall" -q
    # instructions (one run under callgrind)
    "$PFT" bench --scenario "$sc" "${frames_opt[@]}" --out "$OUT/$tag.cg" -q
    valgrind --tool=callgrind --toggle-collect="$fn" --callgrind-out-file="$OUT/$tag.callgrind.out" \
      "$PFT" bench --scenario "$sc" "${frames_opt[@]}" -q 2>"$OUT/$tag.valgrind.log"
    ir=$(sed -n 's/^totals: *\([0-9]*\).*/\1/p' "$OUT/$tag.callgrind.out" | head -1)
    [ -n "$ir" ] || ir=$(sed -n 's/^summary: *\([0-9]*\).*/\1/p' "$OUT/$tag.callgrind.out" | head -1)
    frames=$(jget "$OUT/$tag.cg/bench.json" frames)
    pupd=$(jget "$OUT/$tag.cg/bench.json" particle_updates)
    ppf=$(jget "$OUT/$tag.cg/bench.json" particles_per_frame_mean)
    ws=$(jget "$OUT/$tag.cg/bench.json" workspace_bytes)
    num=$(jstr "$OUT/$tag.cg/bench.json" numeric)
    med=$(jget "$OUT/$tag.wall/bench.json" median_s_per_frame)
    awk -v b="$num" -v l="$label" -v f="$frames" -v ir="$ir" -v pu="$pupd" -v ppf="$ppf" -v med="$med" -v ws="$ws" \
      'BEGIN { printf "| %s | %s | %d | %.0f | %.0f | %.0f | %.3f | 0.3287 | %d |\n", b, l, f, ir / f, ir / pu, ppf, med * 1e3, ws }'
    if [ -n "${COMPONENTS:-}" ]; then
      python3 "$HERE/../tbd/tbd_components.py" "$OUT/$tag.callgrind.out" "$pupd" --groups >"$OUT/$tag.components.txt"
    fi
  done
done
if [ -n "${COMPONENTS:-}" ]; then
  for f in "$OUT"/*.components.txt; do echo; echo "== $(basename "$f" .components.txt) (instructions per particle update)"; cat "$f"; done
fi
