#!/usr/bin/env bash
# Instructions per update of the TBD filters of tests/target/tbd_cycles.c on every emulated
# target, counted by the QEMU plugin tests/soak/qemu_marks.c (docs/size.md, "Cycle budget per
# frame"). Usage: bash tests/target/run_cycles.sh [PRESET ...]
# (default: m3-q16 m7-float m7-q16 aarch64-float aarch64-q16). The plugin is built as by
# tests/soak/run_soak.sh (its header from the installed QEMU's source, or $QEMU_PLUGIN_INCLUDE).
set -euo pipefail
cd "$(dirname "$0")/../.."
bash tests/soak/run_soak.sh plugin
presets=${*:-m3-q16 m7-float m7-q16 aarch64-float aarch64-q16}
for p in $presets; do
  cmake --preset "$p" >/dev/null
  cmake --build --preset "$p" --target tbd_cycles -j 2 >/dev/null
  elf=build/$p/tests/target/tbd_cycles
  d=$(mktemp -d)
  plug="$PWD/build/qemu-plugin/qemu_marks.so,out=$d/counts"
  case "$p" in
    m3-*|m7-*)
      board=mps2-an385; [[ $p == m7-* ]] && board=mps2-an500
      timeout 1800 qemu-system-arm -M $board -nographic -monitor none -icount shift=0 \
        -semihosting-config enable=on,target=native -plugin "$plug" -kernel "$elf" >"$d/out" 2>&1 ||
        { tail -5 "$d/out"; exit 1; };;
    aarch64-*)
      qemu-aarch64 -L /usr/aarch64-linux-gnu -plugin "$plug" "$elf" >"$d/out" 2>&1 ||
        { tail -5 "$d/out"; exit 1; };;
    *) echo "run_cycles.sh: no emulator for preset $p" >&2; exit 2;;
  esac
  python3 - "$d/out" "$d/counts" "$p" <<'PY'
import re, sys
out, counts, preset = sys.argv[1], sys.argv[2], sys.argv[3]
c = [int(l) for l in open(counts) if l.strip()]
secs = re.findall(r"section (\S+) frames (\d+) particles (\d+)", open(out).read())
if sum(int(f) for _, f, _ in secs) != len(c):
    sys.exit("run_cycles: %d counts for %d frames" % (len(c), sum(int(f) for _, f, _ in secs)))
i = 0
for name, f, n in secs:
    v = c[i:i + int(f)]; i += int(f)
    mean = sum(v) / len(v)
    per = (" per particle update %.0f" % (mean / int(n))) if int(n) else ""
    print("cycles %-13s %-9s frames %2d  instructions/frame mean %.0f  max %d (frame %d)%s"
          % (preset, name, len(v), mean, max(v), v.index(max(v)) + 1, per))
for line in open(out):
    if "instructions/frame" in line or "calibration" in line:
        print("cycles %-13s SysTick: %s" % (preset, line.strip()))
PY
  rm -rf "$d"
done
