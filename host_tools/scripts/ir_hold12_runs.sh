#!/bin/bash
# The runs of docs/results/ir_clutter.md, section "Branch irhold12": TBD at 9 and 12 dB with the
# report hold k = 1, 2, 3, 4, 5, 8 against DBT at 15 dB at several false-alarm rates, on the real
# backgrounds (the ir_sky development set: evaluation only; run i on image (i - 1) mod 29).
# Every scenario is a copy of host_tools/scenarios/tbd_ir/sweep_snr_<dB>db.json with the page's
# best setting + integ_alpha 0.7 and `scene_hold` k in its tracker block (real<dB>_h<k>), and,
# for DBT, the k = 1 copy with dbt.pfa patched (real<dB>_h1_pfa<P>); ship15* are the shipped
# 15 dB file (DBT's shipped setting) and its dbt.pfa 3e-6, 3e-5 and 1e-4 copies. One pft eval per scenario
# and block of seeds, 1 thread, nice; evaluations already in OUT are skipped.
#
# Usage: host_tools/scripts/ir_hold12_runs.sh OUT IR_SKY PFT BASE_SEED RUNS TAG NAME...
#   e.g. host_tools/scripts/ir_hold12_runs.sh OUT IR_SKY build/host-float/host_tools/pft 1 29 f_s1 \
#          real12_h1 real12_h2 real12_h3 real12_h5 real15_h1 real15_h1_pfa1e-4
#   outputs: OUT/<NAME>_<TAG>/summary.json; then host_tools/scripts/ir_hold12_tables.py
set -euo pipefail
OUT=$1
BG=$2
PFT=$3
BASE=$4
RUNS=$5
TAG=$6
shift 6
HERE=$(cd "$(dirname "$0")" && pwd)
SC=$HERE/../scenarios/tbd_ir
mkdir -p "$OUT/sc"
python3 - "$SC" "$OUT/sc" <<'PY'
import json, sys
src, out = sys.argv[1], sys.argv[2]
best = {"flat_block": 32, "flat_relative": True, "clutter_mean": True, "clutter_persist": 4,
        "clutter_alpha": 0.2, "integ_alpha": 0.7}
for db in ('09', '12', '15'):
    for k in (1, 2, 3, 4, 5, 8):
        s = json.load(open(f'{src}/sweep_snr_{db}db.json'))
        s['tracker'].update(best)
        s['tracker']['scene_hold'] = k
        json.dump(s, open(f'{out}/real{db}_h{k}.json', 'w'), indent=1)
    for pfa in ('3e-5', '1e-4', '3e-4', '1e-3'):
        s = json.load(open(f'{src}/sweep_snr_{db}db.json'))
        s['tracker'].update(best)
        s['tracker']['scene_hold'] = 1
        s['dbt'] = {'pfa': float(pfa)}
        json.dump(s, open(f'{out}/real{db}_h1_pfa{pfa}.json', 'w'), indent=1)
for pfa in (None, '3e-6', '3e-5', '1e-4'):
    s = json.load(open(f'{src}/sweep_snr_15db.json'))
    if pfa:
        s['dbt'] = {'pfa': float(pfa)}
    json.dump(s, open(f'{out}/ship15' + (f'_pfa{pfa}' if pfa else '') + '.json', 'w'), indent=1)
PY
for n in "$@"; do
  d=$OUT/${n}_$TAG
  [ -f "$d/summary.json" ] && continue
  echo "$(date -u +%H:%M:%S) $n seeds $BASE..$((BASE + RUNS - 1))"
  nice "$PFT" eval --scenario "$OUT/sc/$n.json" --runs "$RUNS" --seed "$BASE" --threads 1 \
    --backgrounds "$BG" --out "$d" -q 2>/dev/null
done
