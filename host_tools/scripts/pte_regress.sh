#!/usr/bin/env bash
# "Nothing lost" check for PTE-TBD changes: the PTE-TBD part of the evidence of
# docs/results/pte.md (Fig. 5 sweep with table and exact operators, sea clutter, air target),
# run with an old and a new pair of builds on the same seeds, printed side by side.
# Only PTE-TBD is evaluated (eval.methods = ["pte"]); DP-TBD and the DBT are left out.
# Usage: host_tools/scripts/pte_regress.sh OLD_FLOAT OLD_Q16 NEW_FLOAT NEW_Q16 OUT_DIR [RUNS] [THREADS]
#   e.g. host_tools/scripts/pte_regress.sh main/build/host-float main/build/host-q16 \
#          build/host-float build/host-q16 build/pte_regress 100 1
# SKIP_EVAL=1 only prints the tables from OUT_DIR.
set -euo pipefail
OF=${1:?usage: pte_regress.sh OLD_FLOAT OLD_Q16 NEW_FLOAT NEW_Q16 OUT_DIR [RUNS] [THREADS]}
OQ=${2:?}
NF=${3:?}
NQ=${4:?}
OUT=${5:?}
RUNS=${6:-100}
THREADS=${7:-1}
HERE="$(cd "$(dirname "$0")" && pwd)"
SC="$HERE/../scenarios/pte"
mkdir -p "$OUT/scenarios"

python3 - "$SC" "$OUT/scenarios" <<'EOF'
import json, sys
sc, out = sys.argv[1], sys.argv[2]
for name, ov, new in [('snr_sweep.json', {}, 'snr_sweep_pte'),
                      ('snr_sweep.json', {'op': 'exact'}, 'snr_sweep_pte_exact'),
                      ('sea_boat_6db.json', {}, 'sea_boat_pte'),
                      ('air_turn_6db.json', {}, 'air_turn_pte')]:
    s = json.load(open(f'{sc}/{name}'))
    s['name'] = new
    s['methods']['pte'] = dict(s['methods'].get('pte', {}), **ov)
    s['eval']['methods'] = ['pte']
    json.dump(s, open(f'{out}/{new}.json', 'w'), indent=1)
EOF

if [ -z "${SKIP_EVAL:-}" ]; then
  for side in old new; do
    for b in float q16; do
      case $side$b in
        oldfloat) B=$OF ;; oldq16) B=$OQ ;; newfloat) B=$NF ;; newq16) B=$NQ ;;
      esac
      for s in air_turn_pte sea_boat_pte snr_sweep_pte snr_sweep_pte_exact; do
        tag=(); [ $s = snr_sweep_pte_exact ] && tag=(--tag exact)
        "$B/host_tools/pft" eval --scenario "$OUT/scenarios/$s.json" --runs "$RUNS" --threads "$THREADS" \
          "${tag[@]}" --out "$OUT/$side/$b/$s" -q
      done
    done
  done
fi

python3 - "$OUT" <<'EOF'
import json, os, sys
out = sys.argv[1]
def load(side, b, s):
    return json.load(open(os.path.join(out, side, b, s, 'summary.json')))
def f3(v):
    return '-' if v is None else f'{v:.3f}'
keys = [('detection_prob', 'Pd'), ('reliable3_prob', 'reliable3'), ('false_track_prob', 'false'),
        ('rmse_cells', 'RMSE')]
s0 = load('new', 'float', 'air_turn_pte')
print(f'Runs: {s0["runs"]} per point, seeds {s0["seeds"][0]}..{s0["seeds"][1]}, the same for old and new.\n')
for s, title in [('air_turn_pte', 'air_turn_6db'), ('sea_boat_pte', 'sea_boat_6db')]:
    print(f'{title}, PTE-TBD M=40:\n')
    print('| build | ' + ' | '.join(f'{n} old | {n} new' for _, n in keys) + ' |')
    print('|---|' + '---|---|' * len(keys))
    for b in ('float', 'q16'):
        o, n = load('old', b, s)['results'][0], load('new', b, s)['results'][0]
        print(f'| {b} | ' + ' | '.join(f'{f3(o[k])} | {f3(n[k])}' for k, _ in keys) + ' |')
    print()
for k, name in keys:
    print(f'Fig. 5 sweep, {name} (old / new):\n')
    cols = [(b, s) for s in ('snr_sweep_pte', 'snr_sweep_pte_exact') for b in ('float', 'q16')]
    hdr = ['table' if s == 'snr_sweep_pte' else 'exact' for _, s in cols]
    print('| SNR dB | ' + ' | '.join(f'{h} {b}' for h, (b, _) in zip(hdr, cols)) + ' |')
    print('|---|' + '---|' * len(cols))
    data = [(load('old', b, s), load('new', b, s)) for b, s in cols]
    snrs = data[0][1]['snr_db']
    for i, snr in enumerate(snrs):
        cells = []
        for o, n in data:
            ro = [r for r in o['results'] if r['snr_db'] == snr][0]
            rn = [r for r in n['results'] if r['snr_db'] == snr][0]
            cells.append(f'{f3(ro[k])} / {f3(rn[k])}')
        print(f'| {snr:g} | ' + ' | '.join(cells) + ' |')
    print()
EOF
