#!/usr/bin/env bash
# Evidence of docs/results/pte.md: the Fig. 5 sweep (PTE-TBD, sliding DP-TBD K = 20 and
# K = 10, Kalman DBT; PTE-TBD also with exact operators) over SNR 0..15 dB, the sea-clutter
# scenario, both builds, 100 Monte Carlo runs each (seeds 1..100, the same at every SNR), the
# merged Fig. 5 curves and the tracked range-time images.
# Usage: host_tools/scripts/pte_results.sh FLOAT_BUILD Q16_BUILD OUT_DIR IMG_DIR [RUNS] [THREADS]
#   e.g. host_tools/scripts/pte_results.sh build/host-float build/host-q16 results/pte docs/results/pte
# SKIP_EVAL=1 only redraws the figures and tables from OUT_DIR.
set -euo pipefail
FB=${1:?usage: pte_results.sh FLOAT_BUILD Q16_BUILD OUT_DIR IMG_DIR [RUNS] [THREADS]}
QB=${2:?}
OUT=${3:?}
IMG=${4:?}
RUNS=${5:-100}
THREADS=${6:-2}
HERE="$(cd "$(dirname "$0")" && pwd)"
SC="$HERE/../scenarios/pte"
mkdir -p "$OUT" "$IMG"

# PTE-TBD with the exact operators of docs/algorithms.md 5.3 (taps of width sigma_w per frame)
python3 - "$SC/snr_sweep.json" "$OUT/snr_sweep_pte_exact.json" <<'EOF'
import json, sys
s = json.load(open(sys.argv[1]))
s['name'] = 'snr_sweep_pte_exact'
s['description'] = 'Fig. 5 sweep (snr_sweep.json), PTE-TBD with exact operators (op = exact) only.'
s['methods']['pte'] = dict(s['methods'].get('pte', {}), op='exact')
s['eval']['methods'] = ['pte']
json.dump(s, open(sys.argv[2], 'w'), indent=1)
EOF

for b in float q16; do
  [ -n "${SKIP_EVAL:-}" ] && break
  PFT="$([ $b = float ] && echo "$FB" || echo "$QB")/host_tools/pft"
  [ -x "$PFT" ] || { echo "no $PFT" >&2; exit 2; }
  "$PFT" eval --scenario "$SC/snr_sweep.json" --runs "$RUNS" --threads "$THREADS" --out "$OUT/$b/snr_sweep" -q
  "$PFT" eval --scenario "$SC/snr_sweep_dp10.json" --runs "$RUNS" --threads "$THREADS" --out "$OUT/$b/snr_sweep_dp10" -q
  "$PFT" eval --scenario "$OUT/snr_sweep_pte_exact.json" --runs "$RUNS" --threads "$THREADS" --tag exact \
    --out "$OUT/$b/snr_sweep_pte_exact" -q
  "$PFT" eval --scenario "$SC/sea_boat_6db.json" --runs "$RUNS" --threads "$THREADS" --out "$OUT/$b/sea_boat_6db" -q
  "$PFT" eval --scenario "$SC/air_turn_6db.json" --runs "$RUNS" --threads "$THREADS" --out "$OUT/$b/air_turn_6db" -q
  # tracked range-time images (seed 1)
  "$PFT" demo --scenario "$SC/air_turn_6db.json" --out "$OUT/$b/demo_air" > "$OUT/$b/demo_air.txt"
  "$PFT" demo --scenario "$SC/sea_boat_6db.json" --out "$OUT/$b/demo_boat" > "$OUT/$b/demo_boat.txt"
  if [ $b = float ]; then  # the q16 images stay in OUT_DIR
    cp "$OUT/$b/demo_air/tracked.png" "$IMG/air_turn_6db_tracked_$b.png"
    cp "$OUT/$b/demo_boat/tracked.png" "$IMG/sea_boat_6db_tracked_$b.png"
  fi
done

# Fig. 5: the four measures against SNR, every method in one figure per measure and build
# (the q16 curves lie on the float ones; the tables give both). The page shows the float
# figures (IMG_DIR); the q16 figures and the per-frame times stay in OUT_DIR/figures.
PFT="$FB/host_tools/pft"
mkdir -p "$OUT/figures"
for b in float q16; do
  pts=("$OUT/$b"/snr_sweep/points/*.json "$OUT/$b"/snr_sweep_dp10/points/*.json)
  [ $b = float ] && pts+=("$OUT/$b"/snr_sweep_pte_exact/points/*.json)
  D="$([ $b = float ] && echo "$IMG" || echo "$OUT/figures")"
  plot() { "$PFT" plot "${pts[@]}" --x /snr_db --group /tag --floor '' --xlabel "SNR (dB)" "$@"; }
  plot --y /rmse_cells --ylabel "RMSE of correct points (cells)" --title "Fig. 5(a) RMSE, $RUNS runs, $b" \
    --out "$D/fig5a_rmse_$b.png"
  plot --y /detection_prob --ylabel "detection probability" --title "Fig. 5(b) detection probability, $RUNS runs, $b" \
    --out "$D/fig5b_detection_$b.png"
  plot --y /reliable3_prob --ylabel "3-frame reliable tracking probability" \
    --title "Fig. 5(c) 3-frame reliable tracking, $RUNS runs, $b" --out "$D/fig5c_reliable3_$b.png"
  plot --y /false_track_prob --ylabel "false-track probability" \
    --title "Fig. 5(d) false-track probability, $RUNS runs, $b" --out "$D/fig5d_false_$b.png"
  plot --y /us_per_frame --ylabel "us per frame (wall, 2 shared cores)" \
    --title "Per-frame time in the sweep, $RUNS runs, $b" --out "$OUT/figures/time_per_frame_$b.png"
done
python3 "$HERE/pte_tables.py" "$OUT" > "$OUT/tables.md"
echo "wrote $OUT/tables.md, $IMG/*.png and $OUT/figures/*.png"
