#!/usr/bin/env bash
# Checks the library as engines use it (docs/INTEGRATION.md). Needs a finished build in build/.
#   install       (default) `cmake --install` into a temporary prefix, then against that prefix:
#                 builds examples/minimal_engine with find_package(starnt), runs it (its own EGL
#                 context, geometry and shaders; it checks its images against the A-buffer), builds
#                 a probe with find_package(starnt COMPONENTS oit) and links it with pkg-config.
#   subdirectory  configures a parent project that add_subdirectory()s this tree and builds the
#                 runtime and the probe there (a few minutes: it compiles starnt::oit again).
set -euo pipefail
cd "$(dirname "$0")/.."
root="$PWD"
mode="${1:-install}"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
export LP_NUM_THREADS="${LP_NUM_THREADS:-2}"
# Runs a step quietly; on failure prints its output and stops.
quiet() { local log="$work/step.log"; "$@" > "$log" 2>&1 || { cat "$log" >&2; echo "check_install: failed: $*" >&2; exit 1; }; }
case "$mode" in
  install)
    quiet cmake --install build --prefix "$work/prefix"
    quiet cmake -S examples/minimal_engine -B "$work/example" -G Ninja -DCMAKE_BUILD_TYPE=Release \
      -DCMAKE_PREFIX_PATH="$work/prefix"
    quiet cmake --build "$work/example"
    # The same engine with its context on OpenGL 4.5 core, then on OpenGL ES 3.2.
    for api in gl gles; do
      "$work/example/minimal_engine" "$work/images-$api" "$api"
      for m in abuffer peel wboit mboit starnt; do
        test -s "$work/images-$api/$m.png" || { echo "check_install: $api $m.png missing" >&2; exit 1; }
      done
    done
    quiet cmake -S tests/cmake/oit_only -B "$work/oit_only" -G Ninja -DCMAKE_PREFIX_PATH="$work/prefix"
    quiet cmake --build "$work/oit_only"
    "$work/oit_only/oit_only"
    export PKG_CONFIG_PATH="$work/prefix/lib/pkgconfig"
    # shellcheck disable=SC2046
    c++ -std=c++20 tests/cmake/pkgconfig_probe/probe.cpp -o "$work/probe" $(pkg-config --cflags --libs --static starnt)
    "$work/probe"
    echo "check_install: install, find_package example and pkg-config probe OK"
    ;;
  subdirectory)
    quiet cmake -S tests/cmake/parent_project -B "$work/parent" -G Ninja -DCMAKE_BUILD_TYPE=Release \
      -DSTARNT_SOURCE_DIR="$root"
    quiet cmake --build "$work/parent" --target parent_check
    "$work/parent/parent_check"
    echo "check_install: add_subdirectory build OK"
    ;;
  *) echo "usage: $0 [install|subdirectory]" >&2; exit 2 ;;
esac
