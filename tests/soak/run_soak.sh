#!/usr/bin/env bash
# Long soak runs and the per-frame work sample (docs/reliability.md, "Soak").
#   bash tests/soak/run_soak.sh long [frames]   pft_soak over `frames` frames per tracker
#                                               (default 1000000), float and q16, nice 19
#   bash tests/soak/run_soak.sh work [frames]   per-frame instructions of every tracker's
#                                               update under callgrind (default 1000 frames
#                                               after 100 of warm-up): max / median per tracker
#   SOAK_SEED=S, SOAK_TRACKERS="tsa ..." choose the scene's seed and the trackers (work mode)
# Builds build/soak-float and build/soak-q16 (Release, library and pft_soak only).
set -euo pipefail
cd "$(dirname "$0")/../.."
mode=${1:-long}; frames=${2:-}
for t in float q16; do
  cmake -S . -B build/soak-$t -G Ninja -DPFT_NUMERIC=$t -DCMAKE_BUILD_TYPE=Release \
        -DUNITY_SOURCE_DIR="$PWD/.deps/unity" -DPFT_WERROR=ON >/dev/null
  cmake --build build/soak-$t --target pft_soak -j 2 >/dev/null
done
case "$mode" in
long)
  for t in float q16; do
    start=$(date +%s)
    nice -n 19 build/soak-$t/tests/soak/pft_soak --frames "${frames:-1000000}" \
      | tee build/soak-$t/soak-long.log
    echo "soak $t: $(( $(date +%s) - start )) s"
  done;;
work)
  n=${frames:-1000}
  # tracker -> the public update function called once per frame
  declare -A fn=([tbd]=pft_tbd_update [pf]=pft_pf_update [tsa]=pft_tsa_update
                 [pte]=pft_pte_update [pte_dp]=pft_pte_dp_update [pte_dbt]=pft_pte_dbt_update)
  for t in float q16; do
    for k in ${SOAK_TRACKERS:-tbd pf tsa pte pte_dp pte_dbt}; do
      d=$(mktemp -d)
      valgrind --tool=callgrind --callgrind-out-file="$d/cg.out" --dump-after="${fn[$k]}" \
        build/soak-$t/tests/soak/pft_soak --tracker $k --frames $((n + 100)) --seed "${SOAK_SEED:-1}" --quiet \
        --trace >"$d/trace" 2>"$d/err" || { cat "$d/err"; exit 1; }
      # one dump per update: its total instruction count, with the load of that frame (tracks
      # after the update) from --trace; the first 100 updates are warm-up
      python3 - "$d" "$t" "$k" 100 <<'PY'
import glob, re, statistics, sys
d, t, k, warm = sys.argv[1], sys.argv[2], sys.argv[3], int(sys.argv[4])
tot = []
for f in glob.glob(d + "/cg.out.*"):
    m = re.search(r"\.(\d+)$", f)
    for line in open(f):
        if line.startswith("summary:") or line.startswith("totals:"):
            tot.append((int(m.group(1)) if m else 0, int(line.split()[1])))
            break
tot = [v for p, v in sorted(tot)]
load = [int(l.split()[2]) for l in open(d + "/trace") if l.startswith("trace ")]
n = min(len(tot), len(load))
pairs = list(zip(load[:n], tot[:n]))[warm:]
vals = [v for _, v in pairs]
med = statistics.median(vals)
by = {}
for l, v in pairs:
    by.setdefault(l, []).append(v)
per = "  ".join("load %d: %d frames, max/median %.2f" % (l, len(v), max(v) / statistics.median(v))
                for l, v in sorted(by.items()))
print("work %-5s %-8s frames %4d  instructions per update: median %.0f  max %.0f  max/median %.2f  |  %s"
      % (t, k, len(vals), med, max(vals), max(vals) / med, per))
PY
      rm -rf "$d"
    done
  done;;
*) echo "usage: bash tests/soak/run_soak.sh long|work [frames]"; exit 2;;
esac
