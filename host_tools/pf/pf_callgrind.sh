#!/usr/bin/env bash
# Instruction counts of the particle-filter engines under callgrind (exact and repeatable;
# wall time on a shared machine is not), for docs/results/pf.md Table 2.
# For each build given (float and/or q16):
#   bearings: each filter of scenarios/pf/gordon_bearings.json at each N of $NS, one run of the
#             24 steps, valgrind --toggle-collect=pft_pf_update (simulation, prior draws and tool
#             code are not counted) -> instructions per step and per particle-step;
#   TBD:      APF-TBD and PF-TBD (SIR engine) of scenarios/pf/pf_tbd_5db.json at N = $TBD_N,
#             30 frames -> instructions per frame (also pft_pf_update).
# Each filter is profiled alone from a one-filter copy of the scenario (written to OUT_DIR).
# Usage: host_tools/pf/pf_callgrind.sh OUT_DIR BUILD_DIR [BUILD_DIR...]
#   NS="1000 5000" TBD_N=6000 may be set in the environment.
set -euo pipefail
OUT=${1:?usage: pf_callgrind.sh OUT_DIR BUILD_DIR [BUILD_DIR...]}
shift
[ $# -ge 1 ] || { echo "usage: pf_callgrind.sh OUT_DIR BUILD_DIR [BUILD_DIR...]" >&2; exit 2; }
command -v valgrind >/dev/null || { echo "valgrind not found" >&2; exit 2; }
HERE="$(cd "$(dirname "$0")" && pwd)"
SCEN="$HERE/../scenarios/pf"
NS=${NS:-"1000 5000"}
TBD_N=${TBD_N:-6000}
mkdir -p "$OUT"

# one-filter copy of a scenario: filter_copy SRC LABEL DEST [PARTICLES]
filter_copy() {
  python3 - "$@" <<'PY'
import json, os, sys
src, label, dest = sys.argv[1], sys.argv[2], sys.argv[3]
j = json.load(open(src))
j["filters"] = [f for f in j["filters"] if f.get("label") == label]
if not j["filters"]:
    sys.exit("no filter " + label + " in " + src)
if len(sys.argv) > 4:
    f = j["filters"][0]
    f.pop("match_time_of", None)
    f["particles"] = int(sys.argv[4])
if "base" in j:  # keep the base scenario reachable from the copy
    j["base"] = os.path.normpath(os.path.join(os.path.dirname(os.path.abspath(src)), j["base"]))
json.dump(j, open(dest, "w"), indent=1)
PY
}
labels() { python3 -c "import json,sys; print('\n'.join(f['label'] for f in json.load(open(sys.argv[1]))['filters']))" "$1"; }
ir_of() { sed -n 's/^totals: *\([0-9]*\).*/\1/p' "$1" | head -1; }

printf '| build | problem | filter | N | steps | instructions/step | instructions/particle-step |\n'
printf '|---|---|---|---|---|---|---|\n'
for build in "$@"; do
  PFT="$build/host_tools/pft"
  [ -x "$PFT" ] || { echo "no $PFT" >&2; exit 2; }
  num=$(basename "$build")
  while IFS= read -r lab; do
    sc="$OUT/bearings_${lab}.json"
    filter_copy "$SCEN/gordon_bearings.json" "$lab" "$sc"
    for n in $NS; do
      cg="$OUT/$(basename "$build")_bearings_${lab}_$n.callgrind.out"
      valgrind --tool=callgrind --toggle-collect=pft_pf_update --callgrind-out-file="$cg" \
        "$PFT" bench --scenario "$sc" --particles "$n" --runs 1 -q 2>"$cg.log"
      ir=$(ir_of "$cg")
      awk -v b="$num" -v l="$lab" -v n="$n" -v ir="$ir" \
        'BEGIN { printf "| %s | bearings | %s | %d | 24 | %.0f | %.0f |\n", b, l, n, ir / 24, ir / 24 / n }'
    done
  done < <(labels "$SCEN/gordon_bearings.json")
  for lab in "APF-TBD 6000" "PF-TBD 6000"; do
    tag=$(echo "$lab" | tr ' ' '_')
    sc="$OUT/tbd_${tag}.json"
    filter_copy "$SCEN/pf_tbd_5db.json" "$lab" "$sc" "$TBD_N"
    cg="$OUT/$(basename "$build")_tbd_${tag}.callgrind.out"
    valgrind --tool=callgrind --toggle-collect=pft_pf_update --callgrind-out-file="$cg" \
      "$PFT" bench --scenario "$sc" --runs 1 -q 2>"$cg.log"
    ir=$(ir_of "$cg")
    awk -v b="$num" -v l="$lab" -v n="$TBD_N" -v ir="$ir" \
      'BEGIN { printf "| %s | TBD 5 dB | %s | %d | 30 | %.0f | %.0f |\n", b, l, n, ir / 30, ir / 30 / n }'
  done
done
