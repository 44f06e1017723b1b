#!/usr/bin/env bash
# Every evaluation of docs/results/tsa_ak.md (issue #10): the three swing levels (3/1, 8/3, 15/5
# px/frame, px/frame^2; 300 frames) and their forced-loss versions (120 frames, 10 blank),
# RUNS seeds each. The float build runs TSA-AK, the paper's variant, NCV, TS, KCF and CSRT in
# the same run (one eval per scenario, THREADS worker threads, OpenCV single-threaded, so the
# thread CPU times compare); the q16 build runs TSA-AK alone on the same seeds. Then
# tsa_tables.py writes the tables.
#
# Usage: host_tools/scripts/tsa_results.sh BUILD_FLOAT BUILD_Q16 OUT [RUNS=50] [THREADS=2]
# Environment: LEVELS="15_5 8_3 3_1" chooses the levels and their order; SEED (default 1) the
# first seed; TRACKERS (default "tsa tsa_paper ncv ts kcf csrt") the float build's trackers;
# Q16=0 skips the q16 runs.
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
bf=$1; bq=$2; out=$3; runs=${4:-50}; threads=${5:-2}
mkdir -p "$out/scenarios"
for lv in ${LEVELS:-3_1 8_3 15_5}; do
  for v in "" _loss; do
    sc=$here/../scenarios/tsa/swing_${lv}${v}.json
    python3 - "$sc" "$out/scenarios" <<'EOF'
import json, os, sys
src, dst = sys.argv[1], sys.argv[2]
d = json.load(open(src))
name = os.path.basename(src)
d['eval']['trackers'] = os.environ.get('TRACKERS', 'tsa tsa_paper ncv ts kcf csrt').split()
json.dump(d, open(os.path.join(dst, 'float_' + name), 'w'), indent=1)
d['eval']['trackers'] = ['tsa']
json.dump(d, open(os.path.join(dst, 'q16_' + name), 'w'), indent=1)
EOF
    bl="float"; [ "${Q16:-1}" = 0 ] || bl="float q16"
    for b in $bl; do
      build=$bf; [ $b = q16 ] && build=$bq
      echo "== $b swing_${lv}${v}" >&2
      "$build/host_tools/pft" eval --scenario "$out/scenarios/${b}_swing_${lv}${v}.json" --runs "$runs" \
        --threads "$threads" --seed "${SEED:-1}" --out "$out/${b}_swing_${lv}${v}" -q
    done
  done
done
python3 "$here/tsa_tables.py" "$out" > "$out/tables.md"
echo "tables: $out/tables.md" >&2
