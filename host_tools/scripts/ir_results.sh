#!/bin/bash
# The TBD-beside-DBT evaluation of the IR pipeline (kind tbd_ir) in docs/results/ir_clutter.md:
# the shipped SNR sweep (host_tools/scenarios/tbd_ir/sweep_snr_{03..15}db.json, procedural
# clouds, temporal preprocessing) and variants of it written into OUT: spatial preprocessing,
# a clear sky (no clouds, no horizon) and other DBT false-alarm rates. 20 runs (seeds 1..20),
# 2 threads per evaluation; about 40 s wall per evaluation on a quiet 2-core machine.
#
# Usage: host_tools/scripts/ir_results.sh OUT FLOAT_BUILD [Q16_BUILD]
#   e.g. host_tools/scripts/ir_results.sh build/ir-results build/host-float build/host-q16
# Then: python3 host_tools/scripts/ir_tables.py OUT
set -euo pipefail
OUT=$1
F=$2/host_tools/pft
Q=${3:+$3/host_tools/pft}
HERE=$(cd "$(dirname "$0")" && pwd)
SC=$HERE/../scenarios/tbd_ir
RUNS=${RUNS:-20}
mkdir -p "$OUT/scenarios"
# variant NAME SNR JSON-PATCH: the shipped sweep point with a patch (python dict update per section)
variant() {
  python3 - "$SC/sweep_snr_$2db.json" "$OUT/scenarios/$1_$2.json" "$3" <<'PY'
import json, sys
s = json.load(open(sys.argv[1]))
for sec, val in json.loads(sys.argv[3]).items():
    if isinstance(val, dict) and isinstance(s.get(sec), dict) and sec != "background":
        s[sec].update(val)
    else:
        s[sec] = val
json.dump(s, open(sys.argv[2], "w"), indent=1)
PY
}
ev() {  # ev BIN SCENARIO OUTDIR
  [ -f "$3/summary.json" ] || "$1" eval --scenario "$2" --runs "$RUNS" --threads 2 --out "$3" -q
}
CLEAR='{"background": {"source": "procedural", "cloud_cover": 0, "horizon": null}}'
for db in 03 06 09 12 15; do
  ev "$F" "$SC/sweep_snr_${db}db.json" "$OUT/float_temporal_$db"
  variant spatial $db '{"tracker": {"preprocess": "spatial"}}'
  ev "$F" "$OUT/scenarios/spatial_$db.json" "$OUT/float_spatial_$db"
  variant clearsky $db "$CLEAR"
  ev "$F" "$OUT/scenarios/clearsky_$db.json" "$OUT/float_clearsky_$db"
done
for db in 12 15; do for pfa in 1e-7 1e-9; do
  variant pfa$pfa $db "{\"dbt\": {\"pfa\": $pfa}}"
  ev "$F" "$OUT/scenarios/pfa${pfa}_$db.json" "$OUT/float_pfa${pfa}_$db"
done; done
for db in 06 09 12; do for pfa in 1e-4 1e-3; do
  python3 - "$OUT/scenarios/clearsky_$db.json" "$OUT/scenarios/cspfa${pfa}_$db.json" "$pfa" <<'PY'
import json, sys
s = json.load(open(sys.argv[1])); s["dbt"] = {"pfa": float(sys.argv[3])}
json.dump(s, open(sys.argv[2], "w"), indent=1)
PY
  ev "$F" "$OUT/scenarios/cspfa${pfa}_$db.json" "$OUT/float_cspfa${pfa}_$db"
done; done
if [ -n "$Q" ]; then
  ev "$Q" "$SC/sweep_snr_09db.json" "$OUT/q16_temporal_09"
  ev "$Q" "$OUT/scenarios/clearsky_12.json" "$OUT/q16_clearsky_12"
fi
