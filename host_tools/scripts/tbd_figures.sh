#!/usr/bin/env bash
# Runs the Monte Carlo evaluations of docs/results/tbd.md with one build of `pft` and merges
# them into the paper's figures:
#   single target (Exp. 1): SNR 2, 5, 6, 8, 11 dB; RBPF-TBD N=6000 and PF-TBD N=6000, 36000,
#     60000 -> fig5_rmse_vs_snr.png (RMSE vs SNR with the PCRLB floor), fig4_existence_<snr>db.png
#     (mean existence probability vs frame), fig5_correct_vs_snr.png
#   two targets (Exp. 2, Table 1): cases 1-3 at 6 dB, library presets "paper" and "recommended"
# Usage: host_tools/scripts/tbd_figures.sh BUILD_DIR OUT_DIR [RUNS] [THREADS]
#   e.g. host_tools/scripts/tbd_figures.sh build/h6-host-float results/float 100 2
# Seeds: every eval uses the scenario's base seed (1), run i uses seed 1 + i (recorded in each
# summary.json). PF_SIZES and SNRS may be overridden from the environment; SKIP_SINGLE=1 reruns
# only the two-target cases (the figures are then merged from the summaries already in OUT).
set -euo pipefail
BUILD=${1:?usage: tbd_figures.sh BUILD_DIR OUT_DIR [RUNS] [THREADS]}
OUT=${2:?usage: tbd_figures.sh BUILD_DIR OUT_DIR [RUNS] [THREADS]}
RUNS=${3:-100}
THREADS=${4:-2}
PFT="$BUILD/host_tools/pft"
HERE="$(cd "$(dirname "$0")" && pwd)"
SCEN="$HERE/../scenarios/tbd"
SNRS=${SNRS:-"2 5 6 8 11"}
PF_SIZES=${PF_SIZES:-"6000 36000 60000"}
[ -x "$PFT" ] || { echo "no $PFT: build the host tools first" >&2; exit 2; }
mkdir -p "$OUT"

ev() { # name scenario [pft eval options...]
  local name=$1 sc=$2; shift 2
  echo "== $name" >&2
  "$PFT" eval --scenario "$sc" --runs "$RUNS" --threads "$THREADS" --out "$OUT/$name" -q "$@"
}

if [ -z "${SKIP_SINGLE:-}" ]; then
for snr in $SNRS; do
  ev "single_${snr}db_rbpf_6000" "$SCEN/single_${snr}db.json" --filter rbpf --particles 6000
  for n in $PF_SIZES; do
    ev "single_${snr}db_pf_${n}" "$SCEN/single_${snr}db.json" --filter pf --particles "$n"
  done
done
fi
for c in 1 2 3; do
  for preset in paper recommended; do
    ev "two_case${c}_${preset}" "$SCEN/two_case${c}.json" --preset "$preset"
  done
done

NUM=$(sed -n 's/.*"numeric": "\([a-z0-9]*\)".*/\1/p' "$OUT/single_6db_rbpf_6000/summary.json" | head -1)
"$PFT" plot "$OUT"/single_*db_*/summary.json --out "$OUT/fig5_rmse_vs_snr.png" \
  --x /snr_db --y /averaged/rmse --group /tag --floor /averaged/pcrlb \
  --title "RMSE vs SNR, single target, $RUNS runs ($NUM)" --xlabel "SNR (dB)" \
  --ylabel "radial RMSE over correct points (px)"
"$PFT" plot "$OUT"/single_*db_*/summary.json --out "$OUT/fig5_rmse_all_vs_snr.png" \
  --x /snr_db --y /averaged/rmse_all_assigned --group /tag --floor /averaged/pcrlb \
  --title "RMSE (all tracked frames of the life) vs SNR ($NUM)" --xlabel "SNR (dB)" \
  --ylabel "radial RMSE, all assigned points (px)"
"$PFT" plot "$OUT"/single_*db_*/summary.json --out "$OUT/fig5_correct_vs_snr.png" \
  --x /snr_db --y /averaged/correct_frames --group /tag --floor '' \
  --title "Correctly detected frames (of 16) vs SNR ($NUM)" --xlabel "SNR (dB)" --ylabel "frames"
for snr in $SNRS; do
  "$PFT" plot "$OUT"/single_${snr}db_*/summary.json --out "$OUT/fig4_existence_${snr}db.png" \
    --y /averaged/existence_probability --group /tag --ymax 1.05 \
    --title "Mean existence probability, SNR $snr dB, $RUNS runs ($NUM)" --ylabel "P(exist)"
done
python3 "$HERE/tbd_tables.py" "$OUT" > "$OUT/tables.md"
echo "wrote $OUT/tables.md and the figures" >&2
