#!/usr/bin/env bash
# Installs the Debian 12 packages STAR-NT builds and runs with. Safe to run again: apt skips what is there.
# All Mesa packages go in one apt call so their versions stay matched (a mismatched libgl1-mesa-dri
# and libegl-mesa0 fails at context creation). libglx-mesa0 is the GLX side, for `starnt view` under X/Xvfb.
# clang + libclang-rt-14-dev (libFuzzer, sanitizer runtimes) build the fuzz targets (scripts/fuzz.sh).
set -euo pipefail
PKGS=(
  build-essential cmake ninja-build pkg-config git
  libegl-dev libgl1-mesa-dri libegl-mesa0 libglx-mesa0 libgles-dev libepoxy-dev
  libglm-dev libtinygltf-dev libtinyobjloader-dev libstb-dev libopenexr-dev
  libcli11-dev nlohmann-json3-dev libgtest-dev libbenchmark-dev libeigen3-dev
  libglfw3-dev libimgui-dev xvfb xauth python3-matplotlib
  clang libclang-rt-14-dev
)
missing=()
for p in "${PKGS[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then exit 0; fi
SUDO=""
[ "$(id -u)" -eq 0 ] || SUDO="sudo"
echo "setup: installing ${missing[*]}" >&2
$SUDO apt-get update -qq
DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
