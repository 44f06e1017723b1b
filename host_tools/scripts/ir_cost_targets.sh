#!/usr/bin/env bash
# Instructions per frame of the IR pipeline's library calls on every instruction set
# (docs/results/ir_clutter.md, "Branch ira53", "Branch irmap"; docs/size.md, "Per-frame work"):
# the stage (pft_pre_update_inplace) and the TBD manager (pft_tbd_update), each and summed (the
# goal's figure), the clutter map between them (pft_pre_clutter_update_inplace, or with
# IRC_MAP=copy pft_pre_clutter_update) and the sum of the three, mean and max over frames 2..N, for the shipped scenario tbd_ir/procedural_384x288.json (seed 1) and the same
# at 640 x 512, float and q16, on
#   x86       x86-64 under callgrind (Release, the host presets' flags: the goal's figure)
#   x86v2     the same with -DCMAKE_C_FLAGS=-march=x86-64-v2 (SSE4.1/SSE4.2/POPCNT)
#   aarch64   the aarch64-float / aarch64-q16 presets under qemu-aarch64 with the plugin
#             tests/soak/qemu_marks.c (guest instructions between the work markers)
#   m7        the m7-float / m7-q16 presets (Cortex-M7, qemu-system-arm mps2-an500, same plugin;
#             a frame size whose buffers exceed the board's 4 MiB of RAM is reported as such)
# The frames are made once by `pft sim --format raw` (a host-float build's pft) and the same
# .u16 bytes go to tests/tools/ir_probe of every build, which runs stage, clutter map and manager
# with pft run's settings (its confirmed tracks are printed; the script reports whether every
# build printed the same tracks as x86 float / q16).
#
#   bash host_tools/scripts/ir_cost_targets.sh [FRAMES]      (default 30: frames 2..30 counted)
#   IRC_TARGETS="x86 x86v2 aarch64 m7"  IRC_SIZES="384x288 640x512"  IRC_NUMERIC="float q16"
#   IRC_OUT=build/ir-cost (frames, logs, counts; the table is printed and kept as table.md)
#   IRC_TAG=name  adds a suffix to the build directories (build/irc-<target>-<numeric><tag>):
#                 a before / after comparison keeps two sets of builds
#   PFT=path      the pft that makes the frames (default build/host-float/host_tools/pft)
#   IRC_MAP=inplace|copy  how ir_probe runs the clutter map (default inplace, as pft run does)
#   IRC_BLOCK=0|2|4       the map's block (pft_pre_clutter_config_t.block; default 0, as pft run)
#   IRC_CLUTTER="MEAN PERSIST ALPHA"  the map's tracker fields clutter_mean (0|1), clutter_persist
#                 and clutter_alpha (ir_probe's last three arguments; unset: the pipeline's
#                 defaults 0 0 0.1); "1 4 0.2" is the best setting of docs/results/ir_clutter.md;
#                 a fourth value 1 sets the map's 8-bit form (map8, clutter_map8): "0 0 0.1 1"
#
# The flight build of any tbd_ir scenario (docs/results/ir_clutter.md, "Branch ircost31"): with
#   IRC_FLIGHT="A.json B.json ..."  the scenario files (IRC_SIZES, IRC_MAP, IRC_BLOCK and
#                 IRC_CLUTTER are then not read); `pft bench --scenario F --frames N --seed
#                 IRC_SEED --probe-out DIR` of the numeric's host build (PFT for float, PFT_Q for
#                 q16, default build/host-q16/host_tools/pft) writes the frames and the library
#                 configurations its pipeline runs with, and tests/tools/ir_probe -c of every build
#                 runs the flight build's library calls on them: the stage, the flat field, the
#                 clutter map, the manager and the calls after it (pft_tbd_tracks, the scene-motion
#                 test and its raises), each bracketed by the work markers (five counts per frame).
#                 The table gives each call's mean per frame over frames 1..IRC_SPLIT and
#                 IRC_SPLIT+1..N (default 13) and whether the checksums of every call's outputs
#                 equal x86 float's / q16's (expect.txt of the host pipeline is compared on x86).
#   IRC_SEED=1  IRC_BACKGROUNDS=DIR (passed to pft bench as --backgrounds DIR for the scenarios
#                 whose background source is "folder")
# Every long job runs under nice; one job at a time.
set -euo pipefail
cd "$(dirname "$0")/../.."
N=${1:-30}
targets=${IRC_TARGETS:-x86 x86v2 aarch64 m7}
sizes=${IRC_SIZES:-384x288 640x512}
numerics=${IRC_NUMERIC:-float q16}
out=${IRC_OUT:-build/ir-cost}
tag=${IRC_TAG:-}
pft=${PFT:-build/host-float/host_tools/pft}
map=${IRC_MAP:-inplace}
block=${IRC_BLOCK:-0}
clutter=${IRC_CLUTTER:-}
mkdir -p "$out"
out=$(cd "$out" && pwd)

if [ ! -x "$pft" ]; then
  echo "ir_cost_targets.sh: $pft not found (cmake --preset host-float && cmake --build --preset host-float)" >&2
  exit 2
fi
# the frames: once per size, the same bytes for every build (the flight mode makes its own)
[ -n "${IRC_FLIGHT:-}" ] && sizes=""
for sz in $sizes; do
  w=${sz%x*}; h=${sz#*x}
  d=$out/frames-$sz
  if [ ! -f "$d/frames.u16" ]; then
    python3 - "$w" "$h" "$out/scenario-$sz.json" <<'EOF'
import json, sys
s = json.load(open('host_tools/scenarios/tbd_ir/procedural_384x288.json'))
s['image'] = {'width': int(sys.argv[1]), 'height': int(sys.argv[2])}
json.dump(s, open(sys.argv[3], 'w'), indent=1)
EOF
    nice -n 10 "$pft" sim --scenario "$out/scenario-$sz.json" --seed 1 --format raw --out "$d" -q
  fi
done

build() {  # build <target> <numeric>: prints the ir_probe path
  local t=$1 n=$2 dir
  case "$t" in
    x86|x86v2)
      dir=build/irc-$t-$n$tag
      local flags=""; [ "$t" = x86v2 ] && flags="-march=x86-64-v2"
      cmake -S . -B "$dir" -G Ninja -DPFT_NUMERIC="$n" -DCMAKE_BUILD_TYPE=Release \
            -DCMAKE_C_FLAGS="$flags" -DUNITY_SOURCE_DIR="$PWD/.deps/unity" -DPFT_WERROR=ON >/dev/null;;
    aarch64|m7|m3)
      dir=build/irc-$t-$n$tag
      cmake --preset "$t-$n" -B "$dir" >/dev/null;;
    *) echo "ir_cost_targets.sh: unknown target $t" >&2; exit 2;;
  esac
  nice -n 10 cmake --build "$dir" --target ir_probe -j 2 >/dev/null
  echo "$dir/tests/tools/ir_probe"
}

# run_probe <target> <ir_probe> <arguments> <run dir>: runs one build of ir_probe, its log, err
# and per-region instruction counts (callgrind's dumps or the QEMU plugin's) in the run dir;
# prints ok, fail or no-fit (the arena too small for the frame on the board)
run_probe() {
  local t=$1 exe=$2 args=$3 r=$4 status=ok board
  case "$t" in
    x86|x86v2)
      nice -n 10 valgrind --tool=callgrind --callgrind-out-file="$r/cg.out" --collect-atstart=no \
        --toggle-collect=irp_measured --dump-after=irp_measured "$exe" $args >"$r/log" 2>"$r/err" || status=fail
      for ((i = 1; ; i++)); do
        [ -f "$r/cg.out.$i" ] || break
        awk '/^(summary|totals):/ {print $2; exit}' "$r/cg.out.$i"
      done >"$r/counts"
      rm -f "$r"/cg.out*;;
    aarch64)
      nice -n 10 qemu-aarch64 -L /usr/aarch64-linux-gnu -plugin "$plug,out=$r/counts" "$exe" $args \
        >"$r/log" 2>"$r/err" || status=fail;;
    m7|m3)
      board=mps2-an500; [ "$t" = m3 ] && board=mps2-an385
      nice -n 10 timeout 3600 qemu-system-arm -M $board -nographic -monitor none \
        -semihosting-config enable=on,target=native -plugin "$plug,out=$r/counts" -kernel "$exe" \
        -append "$args" >"$r/log" 2>"$r/err" || status=fail;;
  esac
  if grep -q "arena of .* too small" "$r/log" "$r/err"; then status=no-fit; fi
  if [ $status = ok ] && ! grep -q "ir_probe: done" "$r/log"; then status=fail; fi
  echo $status
}

if [ -n "${IRC_FLIGHT:-}" ]; then
  pft_q=${PFT_Q:-build/host-q16/host_tools/pft}
  split=${IRC_SPLIT:-13}
  seed=${IRC_SEED:-1}
  bgs=()
  [ -n "${IRC_BACKGROUNDS:-}" ] && bgs=(--backgrounds "$IRC_BACKGROUNDS")
  need_plugin=0
  for t in $targets; do [[ $t == aarch64 || $t == m7 || $t == m3 ]] && need_plugin=1; done
  [ $need_plugin = 1 ] && bash tests/soak/run_soak.sh plugin >/dev/null
  plug=$PWD/build/qemu-plugin/qemu_marks.so
  : >"$out/flight_rows.csv"
  for n in $numerics; do
    p=$pft; [ "$n" = q16 ] && p=$pft_q
    [ -x "$p" ] || { echo "ir_cost_targets.sh: $p not found (the host-$n build)" >&2; exit 2; }
    for sc in $IRC_FLIGHT; do
      name=$(basename "$sc" .json)
      d=$out/probe-$name-$n
      if [ ! -f "$d/probe.cfg" ]; then
        b=("${bgs[@]}")   # --backgrounds only for a scenario of background images
        grep -q '"source": *"folder"' "$sc" || b=()
        nice -n 10 "$p" bench --scenario "$sc" --frames "$N" --seed "$seed" -q "${b[@]}" --probe-out "$d" >/dev/null
      fi
    done
  done
  for t in $targets; do
    for n in $numerics; do
      if [ "$t" = m3 ]; then
        [ "$n" = q16 ] || continue   # the Cortex-M3 preset is q16 only
        exe=$(build m3 q16)
      else
        exe=$(build "$t" "$n")
      fi
      for sc in $IRC_FLIGHT; do
        name=$(basename "$sc" .json)
        d=$out/probe-$name-$n
        r=$out/flight-$t-$n-$name$tag; rm -rf "$r"; mkdir -p "$r"
        args="-c $d/probe.cfg $d/frames.u16 $N"
        status=$(run_probe "$t" "$exe" "$args" "$r")
        echo "$t,$n,$name,$status,$r,$d" >>"$out/flight_rows.csv"
        echo "$t $n $name: $status" >&2
      done
    done
  done
  python3 - "$out/flight_rows.csv" "$N" "$split" <<'EOF2' | tee "$out/flight_table$tag.md"
import sys
rows = [l.strip().split(',') for l in open(sys.argv[1]) if l.strip()]
N, split = int(sys.argv[2]), int(sys.argv[3])
calls = ['stage', 'flat', 'map', 'manager', 'after']
def outputs(run):
    lines = open(run + '/log').read().splitlines()
    return [l for l in lines if l.startswith('F ') or l.startswith('ir_probe: checksums')]
ref = {}
for t, n, name, st, run, d in rows:
    if t == 'x86' and st == 'ok':
        ref[(n, name)] = outputs(run)
print('| scenario | target | numeric | frames | ' + ' | '.join(calls) + ' | total | outputs as x86 | x86 = host pipeline |')
print('|---|---|---|---|' + '---:|' * (len(calls) + 1) + '---|---|')
for t, n, name, st, run, d in rows:
    if st != 'ok':
        print(f'| {name} | {t} | {n} | | {st} |' + ' |' * (len(calls) + 2))
        continue
    c = [int(x) for x in open(run + '/counts').read().split()]
    if len(c) != 5 * N:
        print(f'| {name} | {t} | {n} | | {len(c)} counts, expected {5 * N} |' + ' |' * (len(calls) + 2))
        continue
    o = outputs(run)
    same = 'n/a' if (n, name) not in ref else ('yes' if ref[(n, name)] == o else 'NO')
    host = ''
    if t == 'x86':
        exp = open(d + '/expect.txt').read().splitlines()
        host = 'yes' if exp == [l for l in o if l.startswith('F ')] else 'NO'
    for lo, hi in ((1, split), (split + 1, N)):
        if lo > hi:
            continue
        per = [[c[5 * (f - 1) + k] for f in range(lo, hi + 1)] for k in range(5)]
        m = [sum(v) / len(v) / 1e6 for v in per]
        cells = ' | '.join(f'{x:.2f}' for x in m)
        print(f'| {name} | {t} | {n} | {lo}-{hi} | {cells} | {sum(m):.2f} | {same} | {host} |')
print(f'\nM instructions per frame (10^6), mean over the frames named; seed from IRC_SEED; '
      f'stage pft_pre_update(_inplace), flat pft_pre_flat_update, map pft_pre_clutter_update(_inplace), '
      f'manager pft_tbd_update, after: pft_tbd_tracks, the scene-motion test and its map raises')
EOF2
  exit 0
fi

need_plugin=0
for t in $targets; do [[ $t == aarch64 || $t == m7 ]] && need_plugin=1; done
[ $need_plugin = 1 ] && bash tests/soak/run_soak.sh plugin >/dev/null
plug=$PWD/build/qemu-plugin/qemu_marks.so

: >"$out/rows.csv"
for t in $targets; do
  for n in $numerics; do
    exe=$(build "$t" "$n")
    for sz in $sizes; do
      w=${sz%x*}; h=${sz#*x}
      in=$out/frames-$sz/frames.u16
      r=$out/run-$t-$n-$sz$tag; rm -rf "$r"; mkdir -p "$r"
      args="$in $w $h 14 $N 1 12000 $map $block"
      [ -n "$clutter" ] && args="$args 3 $clutter"
      status=$(run_probe "$t" "$exe" "$args" "$r")
      echo "$t,$n,$sz,$status,$r" >>"$out/rows.csv"
      echo "$t $n $sz: $status" >&2
    done
  done
done

python3 - "$out/rows.csv" "$N" "$map block $block${clutter:+ mean persist alpha $clutter}" <<'EOF' | tee "$out/table$tag.md"
import sys
rows = [l.strip().split(',') for l in open(sys.argv[1]) if l.strip()]
N = int(sys.argv[2])
def tracks(run):
    return [l for l in open(run + '/log') if l[:1].isdigit()]
ref = {}
for t, n, sz, st, run in rows:
    if t == 'x86' and st == 'ok':
        ref[(n, sz)] = tracks(run)
# sum: stage + manager (the goal's figure, as before the map was counted); all three: stage,
# map and manager
print(f'| target | numeric | frame | stage mean | stage max | manager mean | manager max | '
      f'sum mean | sum max | map mean | map max | all three mean | all three max | tracks as x86 |')
print('|---|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---|')
for t, n, sz, st, run in rows:
    if st != 'ok':
        print(f'| {t} | {n} | {sz} | {st} | | | | | | | | | | |')
        continue
    c = [int(x) for x in open(run + '/counts').read().split()]
    if len(c) != 3 * N:
        print(f'| {t} | {n} | {sz} | {len(c)} counts, expected {3 * N} | | | | | | | | | | |')
        continue
    pre, cl, tbd = c[0::3][1:], c[1::3][1:], c[2::3][1:]   # frames 2..N
    s = [a + b for a, b in zip(pre, tbd)]
    s3 = [a + b for a, b in zip(s, cl)]
    m = lambda v: f'{sum(v) / len(v) / 1e6:.2f} M'
    x = lambda v: f'{max(v) / 1e6:.2f} M'
    same = 'n/a (no x86 run)' if (n, sz) not in ref else ('yes' if ref[(n, sz)] == tracks(run) else 'no')
    print(f'| {t} | {n} | {sz} | {m(pre)} | {x(pre)} | {m(tbd)} | {x(tbd)} | {m(s)} | {x(s)} | '
          f'{m(cl)} | {x(cl)} | {m(s3)} | {x(s3)} | {same} |')
print(f'\nframes 2..{N} of seed 1 ({N - 1} frames); instructions per frame, M = 10^6; '
      f'sum = stage + manager (the goal\'s figure), all three = stage + map + manager; map: {sys.argv[3]}')
EOF
