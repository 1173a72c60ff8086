#!/usr/bin/env bash
# Installs, builds and runs the whole test suite (CTest on Mesa llvmpipe; no GPU needed).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/build.sh
export LP_NUM_THREADS="${LP_NUM_THREADS:-2}"
export MESA_SHADER_CACHE_DIR="$(mktemp -d)"
cd build
ctest --output-on-failure -j "$(nproc)" --timeout 900
