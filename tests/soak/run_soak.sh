#!/usr/bin/env bash
# Long soak runs and the per-frame work sample (docs/reliability.md, "Soak"; docs/size.md,
# "Per-frame work of every tracker").
#   bash tests/soak/run_soak.sh long [frames]   pft_soak over `frames` frames per tracker
#                                               (default 1000000), float and q16, nice 19
#   bash tests/soak/run_soak.sh work [frames]   per-frame instructions of every tracker's
#                                               update on the host under callgrind (default
#                                               1000 frames after 100 of warm-up)
#   bash tests/soak/run_soak.sh work-qemu [frames]
#                                               the same on the emulated targets: pft_soak of
#                                               each preset in SOAK_PRESETS (default m3-q16
#                                               m7-float m7-q16 aarch64-float aarch64-q16) under
#                                               QEMU with the plugin tests/soak/qemu_marks.c
#   SOAK_SEED=S, SOAK_TRACKERS="tsa ..." choose the scene's seed and the trackers (work modes);
#   SOAK_ARGS="--tbd-bern" passes more options to pft_soak (work modes)
#   SOAK_KEEP=DIR (work mode) keeps the per-update callgrind dumps (self-contained: uncompressed
#   names, so `callgrind_annotate --inclusive=yes DIR/<build>-<tracker>/cg.out.<i>` gives the
#   functions of update i, 1-based, warm-up included)
#   and the trace in DIR instead of deleting them
# long and work build build/soak-float and build/soak-q16 (Release, library and pft_soak only);
# work-qemu builds pft_soak in build/<preset> and the plugin in build/qemu-plugin, against the
# qemu-plugin.h of the installed QEMU's Debian source package (fetched with apt-get source, or
# taken from $QEMU_PLUGIN_INCLUDE): the header is not part of this repository.
set -euo pipefail
cd "$(dirname "$0")/../.."
mode=${1:-long}; frames=${2:-}
trackers=${SOAK_TRACKERS:-tbd pf tsa pte pte_dp pte_dbt}
warm=100

host_builds() {
  for t in float q16; do
    cmake -S . -B build/soak-$t -G Ninja -DPFT_NUMERIC=$t -DCMAKE_BUILD_TYPE=Release \
          -DUNITY_SOURCE_DIR="$PWD/.deps/unity" -DPFT_WERROR=ON >/dev/null
    cmake --build build/soak-$t --target pft_soak -j 2 >/dev/null
  done
}

plugin() {
  local out=build/qemu-plugin inc=${QEMU_PLUGIN_INCLUDE:-}
  mkdir -p "$out"
  if [ -z "$inc" ]; then
    inc=$out/include
    if [ ! -f "$inc/qemu-plugin.h" ]; then
      echo "fetching qemu-plugin.h from the Debian source of the installed QEMU ..." >&2
      mkdir -p "$out/src" "$inc"
      (cd "$out/src" && apt-get source --download-only qemu >/dev/null 2>&1) ||
        { echo "run_soak.sh: apt-get source qemu failed (deb-src lines needed), or set QEMU_PLUGIN_INCLUDE" >&2; exit 1; }
      tar -xJf "$out"/src/qemu_*.orig.tar.xz -C "$out/src" --wildcards '*/include/qemu/qemu-plugin.h'
      cp "$out"/src/qemu-*/include/qemu/qemu-plugin.h "$inc/"
    fi
  fi
  gcc -shared -fPIC -O2 -Wall -Wextra -I"$inc" tests/soak/qemu_marks.c -o "$out/qemu_marks.so"
}

case "$mode" in
plugin)  # build the plugin only (tests/target/run_cycles.sh uses it)
  plugin;;
long)
  host_builds
  for t in float q16; do
    start=$(date +%s)
    nice -n 19 build/soak-$t/tests/soak/pft_soak --frames "${frames:-1000000}" \
      | tee build/soak-$t/soak-long.log
    echo "soak $t: $(( $(date +%s) - start )) s"
  done;;
work)
  host_builds
  n=${frames:-1000}
  # tracker -> the public update function called once per frame
  declare -A fn=([tbd]=pft_tbd_update [pf]=pft_pf_update [tsa]=pft_tsa_update
                 [pte]=pft_pte_update [pte_dp]=pft_pte_dp_update [pte_dbt]=pft_pte_dbt_update)
  for t in float q16; do
    for k in $trackers; do
      if [ -n "${SOAK_KEEP:-}" ]; then
        d=$SOAK_KEEP/$t-$k; rm -rf "$d"; mkdir -p "$d"
      else
        d=$(mktemp -d)
      fi
      # collect inside the update only (the soak's own frame generation is not the tracker's
      # work); one dump after every update
      valgrind --tool=callgrind --callgrind-out-file="$d/cg.out" --collect-atstart=no \
        --compress-strings=no --compress-pos=no \
        --toggle-collect="${fn[$k]}" --dump-after="${fn[$k]}" \
        build/soak-$t/tests/soak/pft_soak --tracker $k --frames $((n + warm)) --seed "${SOAK_SEED:-1}" --quiet \
        --trace ${SOAK_ARGS:-} >"$d/trace" 2>"$d/err" || { cat "$d/err"; exit 1; }
      # cg.out.<i> is the i-th update (1-based); cg.out itself, the part after the last update,
      # is not an update
      for ((i = 1; ; i++)); do
        [ -f "$d/cg.out.$i" ] || break
        awk '/^(summary|totals):/ {print $2; exit}' "$d/cg.out.$i"
      done >"$d/counts"
      python3 tests/soak/work_stats.py "$d/counts" "$d/trace" "$t" "$k" $warm
      [ -n "${SOAK_KEEP:-}" ] || rm -rf "$d"
    done
  done;;
work-qemu)
  plugin
  n=${frames:-1000}
  for p in ${SOAK_PRESETS:-m3-q16 m7-float m7-q16 aarch64-float aarch64-q16}; do
    cmake --preset "$p" >/dev/null
    cmake --build --preset "$p" --target pft_soak -j 2 >/dev/null
    elf=build/$p/tests/soak/pft_soak
    for k in $trackers; do
      d=$(mktemp -d)
      args="--tracker $k --frames $((n + warm)) --seed ${SOAK_SEED:-1} --quiet --trace ${SOAK_ARGS:-}"
      plug="$PWD/build/qemu-plugin/qemu_marks.so,out=$d/counts"
      case "$p" in
        m3-*|m7-*)
          board=mps2-an385; [[ $p == m7-* ]] && board=mps2-an500
          timeout 3600 qemu-system-arm -M $board -nographic -monitor none \
            -semihosting-config enable=on,target=native -plugin "$plug" -kernel "$elf" \
            -append "$args" >"$d/trace" 2>"$d/err" || { cat "$d/err" "$d/trace" | tail -5; exit 1; };;
        aarch64-*)
          qemu-aarch64 -L /usr/aarch64-linux-gnu -plugin "$plug" "$elf" $args >"$d/trace" 2>"$d/err" ||
            { cat "$d/err"; exit 1; };;
        *) echo "run_soak.sh: no emulator for preset $p" >&2; exit 2;;
      esac
      python3 tests/soak/work_stats.py "$d/counts" "$d/trace" "$p" "$k" $warm
      rm -rf "$d"
    done
  done;;
*) echo "usage: bash tests/soak/run_soak.sh long|work|work-qemu|plugin [frames]"; exit 2;;
esac
