#!/usr/bin/env bash
# Installs everything pftrack needs on a fresh Debian/Ubuntu machine (as root, or with sudo;
# never reads stdin). Idempotent: when every package is present and Unity is in .deps/, it
# changes nothing and uses no network; otherwise it runs apt-get update before installing.
# doxygen: the ctest docs_doxygen; gcc-arm-none-eabi also runs the recipe check (.ci/check-recipe);
# clang + libclang-rt-14-dev (libFuzzer), cppcheck, gcovr: .ci/reliability.
set -euo pipefail
here=$(cd "$(dirname "$0")/.." && pwd)
SUDO=""; [ "$(id -u)" -eq 0 ] || SUDO="sudo"
export DEBIAN_FRONTEND=noninteractive

pkgs=(cmake ninja-build gcc g++ make pkg-config
      gcc-arm-none-eabi libnewlib-arm-none-eabi qemu-system-arm
      gcc-aarch64-linux-gnu libc6-dev-arm64-cross qemu-user
      libopencv-dev libcli11-dev nlohmann-json3-dev libopencv-contrib-dev opencv-doc
      valgrind binutils dpkg-dev doxygen
      clang libclang-rt-14-dev cppcheck gcovr python3)
missing=()
for p in "${pkgs[@]}"; do dpkg -s "$p" >/dev/null 2>&1 || missing+=("$p"); done
# deb-src entries are needed for Unity (Debian's cjson source package ships Unity 2.4.3 in tests/unity)
need_src=0
[ -f "$here/.deps/unity/src/unity.c" ] || need_src=1
if [ "$need_src" = 1 ] && ! grep -rqsE '^(Types:.*deb-src|deb-src )' /etc/apt/sources.list /etc/apt/sources.list.d/; then
  # deb822 files (Debian 12: debian.sources, Ubuntu 24.04: ubuntu.sources) and one-line lists
  for f in /etc/apt/sources.list.d/*.sources; do
    [ -f "$f" ] && $SUDO sed -i 's/^Types: deb$/Types: deb deb-src/' "$f"
  done
  if [ -f /etc/apt/sources.list ] && grep -qE '^deb ' /etc/apt/sources.list; then
    grep -E '^deb ' /etc/apt/sources.list | sed 's/^deb /deb-src /' | $SUDO tee -a /etc/apt/sources.list >/dev/null
  fi
fi
# apt-get source needs current package lists
[ "$need_src" = 0 ] || missing+=(__update__)
if [ ${#missing[@]} -gt 0 ]; then
  $SUDO apt-get update -qq </dev/null
  real=(); for p in "${missing[@]}"; do [ "$p" = __update__ ] || real+=("$p"); done
  [ ${#real[@]} -eq 0 ] || $SUDO apt-get install -y -qq --no-install-recommends "${real[@]}" </dev/null
fi

if [ "$need_src" = 1 ]; then
  tmp=$(mktemp -d)
  (cd "$tmp" && apt-get source -qq --download-only cjson </dev/null >/dev/null && dpkg-source -x --no-check ./*.dsc src >/dev/null)
  mkdir -p "$here/.deps/unity"
  cp -r "$tmp/src/tests/unity/src" "$here/.deps/unity/"
  rm -rf "$tmp"
  echo "Unity sources in $here/.deps/unity/src (from Debian's cjson source package)"
fi

# Debian's copy of unity_internals.h includes ../examples/unity_config.h unconditionally:
# give it pftrack's own configuration there.
if [ ! -f "$here/.deps/unity/examples/unity_config.h" ]; then
  mkdir -p "$here/.deps/unity/examples"
  cp "$here/tests/support/unity_config.h" "$here/.deps/unity/examples/unity_config.h"
fi
