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
tr = [l.split() for l in open(d + "/trace") if l.startswith("trace ")]
load = [int(x[2]) for x in tr]
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
if tr and len(tr[0]) > 3:
    # tbd, pf: only particles with E = 1 are moved and weighed on the pixels, and their share at
    # frame i follows the existence probability p after frame i - 1; least squares
    # instructions = a + b p(i-1) + c tracks(i-1), and how far any frame lies above that model
    p = [float(x[3]) for x in tr]
    rows = [(1.0, p[i - 1], float(load[i - 1]), float(tot[i])) for i in range(max(warm, 1), n)]
    m = 3 if len(set(r[2] for r in rows)) > 1 else 2
    A = [[sum(r[a] * r[b] for r in rows) for b in range(m)] for a in range(m)]
    y = [sum(r[a] * r[3] for r in rows) for a in range(m)]
    for c in range(m):  # Gauss-Jordan on the normal equations
        piv = A[c][c]
        A[c] = [v / piv for v in A[c]]; y[c] /= piv
        for r2 in range(m):
            if r2 != c and A[r2][c] != 0.0:
                f_ = A[r2][c]
                A[r2] = [u - f_ * v for u, v in zip(A[r2], A[c])]; y[r2] -= f_ * y[c]
    fit = [sum(y[a] * r[a] for a in range(m)) for r in rows]
    obs = [r[3] for r in rows]
    mean = sum(obs) / len(obs)
    r2 = 1.0 - sum((o - f_) ** 2 for o, f_ in zip(obs, fit)) / sum((o - mean) ** 2 for o in obs)
    worst = max(o / f_ for o, f_ in zip(obs, fit))
    print("work %-5s %-8s model a + b p + c tracks: a %.0f  b %.0f%s  R^2 %.3f  max observed/model %.2f"
          "  (p = 1, no track: %.0f = %.2f x median)"
          % (t, k, y[0], y[1], ("  c %.0f" % y[2]) if m == 3 else "", r2, worst, y[0] + y[1], (y[0] + y[1]) / med))
PY
      rm -rf "$d"
    done
  done;;
*) echo "usage: bash tests/soak/run_soak.sh long|work [frames]"; exit 2;;
esac
