#!/usr/bin/env bash
# The numbers of docs/results/ir_clutter.md, "Preprocessing building blocks".
#   bash host_tools/scripts/pre_results.sh OUT_DIR BUILD_DIR_FLOAT BUILD_DIR_Q16 [IR_SKY_DIR]
# 1. instructions per frame (callgrind) per method, float and q16, 384x288 and 640x512;
# 2. registration accuracy and residual over temporal noise on procedural cloud scenes,
#    against drift speed and noise;
# 3. the same figures per method on the real frames of IR_SKY_DIR when given (evaluation only:
#    the development set is not part of the project);
# 4. column fixed-pattern removal.
set -euo pipefail
out=$1; bf=$2; bq=$3; sky=${4:-}
src=$(cd "$(dirname "$0")/../.." && pwd)
mkdir -p "$out"
py=/usr/bin/python3
ex="$src/host_tools/scripts/pre_explore.py"
echo "== 1. instructions (callgrind, pft_pre_update, mean of frames 2..12)"
python3 "$src/host_tools/scripts/callgrind.py" --only stage "$out/cg" "$src/host_tools/scripts/callgrind/pre.json" "$bf" "$bq"
echo "-- variants (host q16, 384x288): reg_step 3; bilinear warp; sigma of the frame itself (second pass); sigma held per tile"
python3 "$src/host_tools/scripts/callgrind.py" --only variant "$out/cg-variants" "$src/host_tools/scripts/callgrind/pre.json" "$bq"
probe="$bq/tests/tools/pre_probe"
echo "== 2. procedural scenes (4 scenes x 30 frames, 14 bits, blur 0.7 px, jitter 0.1 px)"
for d in "0.1 0.05" "0.3 0.2" "0.5 0.3"; do
  for n in 16 64 256; do
    echo "-- drift $d px/frame, sigma_t $n counts"
    $py "$ex" "$probe" --procedural 4 --frames 30 --drift $d --sigma-t $n | tail -3
  done
done
echo "-- jitter 0 (drift 0.3 0.2, sigma_t 64)"
$py "$ex" "$probe" --procedural 4 --frames 30 --jitter 0 | tail -3
echo "-- registration on every 3rd pixel (reg_step 3); with 3 iterations; bilinear warp"
$py "$ex" "$probe" --procedural 4 --frames 30 --set "step=3" | sed -n 2p
$py "$ex" "$probe" --procedural 4 --frames 30 --set "iters=3" | sed -n 2p
$py "$ex" "$probe" --procedural 4 --frames 30 --set "cubic=0" | tail -3
echo "-- local background (9 x 9, guard 3 x 3), drift 0.3 0.2, sigma_t 64"
$py "$ex" "$probe" --procedural 4 --frames 30 --method local | tail -2
echo "== 4. column offsets (sigma_col 32 counts), temporal, procedural, drift 0.3 0.2"
$py "$ex" "$probe" --procedural 4 --frames 60 --skip 40 --sigma-col 32 | tail -2
$py "$ex" "$probe" --procedural 4 --frames 60 --skip 40 --sigma-col 32 --set "col=0" | tail -2
if [ -n "$sky" ]; then
  echo "== 3. real frames: $sky (29 frames x8 -> 14 bits, 29 frames each, drift 0.3 0.2 px, jitter 0.1, sigma_t 64)"
  echo "-- temporal"
  $py "$ex" "$probe" --images "$sky" --frames 29 | tail -3
  echo "-- local"
  $py "$ex" "$probe" --images "$sky" --frames 29 --method local | tail -2
  echo "-- temporal, bilinear warp"
  $py "$ex" "$probe" --images "$sky" --frames 29 --set "cubic=0" | tail -3
  echo "-- temporal, column offsets sigma_col 32, estimated / not"
  $py "$ex" "$probe" --images "$sky" --frames 29 --sigma-col 32 | tail -2
  $py "$ex" "$probe" --images "$sky" --frames 29 --sigma-col 32 --set "col=0" | tail -2
fi
