#!/usr/bin/env bash
# Instructions per TSA-AK update under callgrind (exact and repeatable; --toggle-collect on
# pft_tsa_update, so decoding and drawing are not counted): the first 100 frames of
# swing_8_3.json seed 1 (640 x 480), N = 100, from
#   - a 25 x 30 box on the vehicle (the issue's configuration), and
#   - the vehicle's bounding box from the truth (about 30 x 34: the vehicle is turned),
# for each build given. Prints a markdown table.
#
# Usage: host_tools/scripts/tsa_callgrind.sh OUT BUILD [BUILD...]
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
out=$1; shift
mkdir -p "$out"
python3 - "$here/../scenarios/tsa/swing_8_3.json" "$out/swing_8_3_100.json" <<'EOF'
import json, sys
d = json.load(open(sys.argv[1])); d['scene']['frames'] = 100
json.dump(d, open(sys.argv[2], 'w'), indent=1)
EOF
sim=$out/sim_8_3_seed1
first=$1
"$first/host_tools/pft" sim --scenario "$out/swing_8_3_100.json" --seed 1 --out "$sim" -q
# 25 x 30 box centred on the vehicle in frame 1
box=$(awk -F, 'NR==2{printf "%d,%d,25,30", $2 - 12.5 + 0.5, $3 - 15 + 0.5}' "$sim/truth.csv")
echo "| build | initial box | frames | instructions per update | kernel box (w x h) |"
echo "|---|---|---|---|---|"
for b in "$@"; do
  name=$(basename "$b")
  for mode in box truth; do
    cg=$out/callgrind_${name}_$mode.out
    if [ $mode = box ]; then
      valgrind --tool=callgrind --toggle-collect=pft_tsa_update --callgrind-out-file="$cg" \
        "$b/host_tools/pft" track --sequence "$sim" --box "$box" --max-target 64 --out "$out/track_${name}_$mode" -q \
        2> "$out/valgrind_${name}_$mode.log"
      label="25 x 30 ($box)"
    else
      valgrind --tool=callgrind --toggle-collect=pft_tsa_update --callgrind-out-file="$cg" \
        "$b/host_tools/pft" run --scenario "$out/swing_8_3_100.json" --sequence "$sim" --out "$out/track_${name}_$mode" \
        --no-video -q 2> "$out/valgrind_${name}_$mode.log"
      label="truth box"
    fi
    ir=$(grep -E '^(summary|totals):' "$cg" | head -1 | awk '{print $2}')
    frames=$(($(wc -l < "$out/track_${name}_$mode/tracks.csv") - 1))
    kbox=$(awk -F, 'NR==2{printf "%d x %d", $6, $7}' "$out/track_${name}_$mode/tracks.csv")
    echo "| $name | $label | $frames | $((ir / frames)) | $kbox |"
  done
done
