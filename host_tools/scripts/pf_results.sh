#!/usr/bin/env bash
# Every evaluation of docs/results/pf.md, for a float and a q16 build of `pft`:
#   bearings benchmark (scale 1000 and scale 1), Monte Carlo eval of SIS / SIR / APF / APF-nr
#   over N = 100..5000; single-thread bench; APF-TBD against PF-TBD at 2 and 5 dB; callgrind
#   instruction counts (callgrind.py with callgrind/pf.json); the markdown tables (pf_tables.py) and the
#   float-vs-q16 comparisons
#   (compare_builds.py).
# Usage: host_tools/scripts/pf_results.sh FLOAT_BUILD Q16_BUILD OUT_DIR [RUNS] [THREADS]
#   e.g. host_tools/scripts/pf_results.sh build/host-float build/host-q16 results/pf 100 2
# Seeds: every eval uses its scenario's base seed 1; run i uses seed 1 + i (recorded in each
# summary.json); bench uses seeds 1..30.
set -euo pipefail
FB=${1:?usage: pf_results.sh FLOAT_BUILD Q16_BUILD OUT_DIR [RUNS] [THREADS]}
QB=${2:?usage}
OUT=${3:?usage}
RUNS=${4:-100}
THREADS=${5:-2}
HERE="$(cd "$(dirname "$0")" && pwd)"
SCEN="$HERE/../scenarios/pf"
mkdir -p "$OUT"
for b in float q16; do
  [ $b = float ] && PFT="$FB/host_tools/pft" || PFT="$QB/host_tools/pft"
  [ -x "$PFT" ] || { echo "no $PFT" >&2; exit 2; }
  for sc in gordon_bearings gordon_bearings_scale1; do
    echo "== $sc $b" >&2
    "$PFT" eval --scenario "$SCEN/$sc.json" --runs "$RUNS" --threads "$THREADS" --out "$OUT/${sc}_$b" > "$OUT/${sc}_$b.log"
  done
  for snr in 2 5; do
    echo "== pf_tbd_${snr}db $b" >&2
    "$PFT" eval --scenario "$SCEN/pf_tbd_${snr}db.json" --runs "$RUNS" --threads "$THREADS" --out "$OUT/pf_tbd_${snr}db_$b" > "$OUT/pf_tbd_${snr}db_$b.log"
  done
  echo "== bench $b" >&2
  "$PFT" bench --scenario "$SCEN/gordon_bearings.json" --runs 30 --out "$OUT/bench_bearings_$b" > "$OUT/bench_bearings_$b.log"
done
echo "== callgrind" >&2
mkdir -p "$OUT/callgrind"
python3 "$HERE/callgrind.py" "$OUT/callgrind" "$HERE/callgrind/pf.json" "$FB" "$QB" > "$OUT/callgrind/table.md"
python3 "$HERE/pf_tables.py" "$OUT" > "$OUT/tables.md"
{
  echo "float vs q16, scale 1000"; python3 "$HERE/compare_builds.py" "$OUT/gordon_bearings_float/summary.json" "$OUT/gordon_bearings_q16/summary.json" --md
  echo; echo "float vs q16, scale 1"; python3 "$HERE/compare_builds.py" "$OUT/gordon_bearings_scale1_float/summary.json" "$OUT/gordon_bearings_scale1_q16/summary.json" --md
  echo; echo "q16 scale 1000 vs q16 scale 1"; python3 "$HERE/compare_builds.py" "$OUT/gordon_bearings_q16/summary.json" "$OUT/gordon_bearings_scale1_q16/summary.json" --md
  echo; echo "float scale 1000 vs float scale 1"; python3 "$HERE/compare_builds.py" "$OUT/gordon_bearings_float/summary.json" "$OUT/gordon_bearings_scale1_float/summary.json" --md
} > "$OUT/compare.md"
echo "wrote $OUT/tables.md, $OUT/compare.md" >&2
