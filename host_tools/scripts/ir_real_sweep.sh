#!/bin/bash
# The real-background SNR sweep of docs/results/ir_clutter.md ("Branch irsweep (2026-12-03):
# real backgrounds, 3-15 dB, per kind of background"): the shipped sweep points
# host_tools/scenarios/tbd_ir/sweep_snr_{03,06,09,12,15}db.json (TBD beside DBT, the
# scenarios' defaults) over the ir_sky development set (evaluation only; run i on image
# (i - 1) mod 29), for each build given. One pft eval per build, SNR and block of seeds;
# evaluations already in OUT are skipped. 1 thread, nice (the machine is shared).
#
# Usage: host_tools/scripts/ir_real_sweep.sh OUT IR_SKY BASE_SEED RUNS BUILD...   (IR_SKY: the ir_sky folder)
#   e.g. host_tools/scripts/ir_real_sweep.sh build/ir-real IR_SKY 1 29 \
#          build/host-float build/host-q16
#        host_tools/scripts/ir_real_sweep.sh build/ir-real IR_SKY 30 87 build/host-float
#   TAG=pfa1e-4 PATCH='{"dbt": {"pfa": 1e-4}}' host_tools/scripts/ir_real_sweep.sh ...  (a variant:
#        the patch updates the sweep point's sections; its outputs go to OUT/<build>_<dB>_s<seed>_TAG)
# Then: python3 host_tools/scripts/ir_real_kinds.py tables OUT [--tag TAG]
set -euo pipefail
OUT=$1
BG=$2
BASE=$3
RUNS=$4
shift 4
HERE=$(cd "$(dirname "$0")" && pwd)
SC=$HERE/../scenarios/tbd_ir
THREADS=${THREADS:-1}
TAG=${TAG:-}
PATCH=${PATCH:-}
for build in "$@"; do
  bin=$build/host_tools/pft
  num=$(basename "$build")
  num=${num#host-}
  for db in 03 06 09 12 15; do
    dir=$OUT/${num}_${db}_s${BASE}${TAG:+_$TAG}
    [ -f "$dir/summary.json" ] && continue
    echo "$(date -u +%H:%M:%S) $num $db dB seeds $BASE..$((BASE + RUNS - 1)) ${TAG}"
    scen=$SC/sweep_snr_${db}db.json
    if [ -n "$PATCH" ]; then
      mkdir -p "$OUT/scenarios"
      scen=$OUT/scenarios/sweep_snr_${db}db_$TAG.json
      python3 - "$SC/sweep_snr_${db}db.json" "$scen" "$PATCH" <<'PY'
import json, sys
s = json.load(open(sys.argv[1]))
for sec, val in json.loads(sys.argv[3]).items():
    if isinstance(val, dict) and isinstance(s.get(sec), dict):
        s[sec].update(val)
    else:
        s[sec] = val
json.dump(s, open(sys.argv[2], "w"), indent=1)
PY
    fi
    nice "$bin" eval --scenario "$scen" --runs "$RUNS" --seed "$BASE" \
      --threads "$THREADS" --backgrounds "$BG" --out "$dir" -q 2>/dev/null
  done
done
