#!/usr/bin/env bash
# The test suite under AddressSanitizer + UndefinedBehaviorSanitizer (float-cast-overflow included),
# a Debug build in build-sanitize/ (viewer off), as .ci/run runs it after the Release suite.
#   bash scripts/sanitize.sh [CTEST_ARGS...]
# Leak checking: on in every test process that never creates a GL context, and in the fuzzers
# (scripts/fuzz.sh); off in processes that do (the GL tests and the command-line tests, which start
# `starnt`). There LeakSanitizer's own thread tracer crashes at random at exit while llvmpipe's
# worker threads run, which no suppression can stop (docs/DESIGN.md, "Sanitizers"). Driver leaks
# that are reported are suppressed by tests/lsan.supp (the GL driver stack only).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
cmake -S . -B build-sanitize -G Ninja -DCMAKE_BUILD_TYPE=Debug -DSTARNT_SANITIZE=ON -DSTARNT_BUILD_VIEWER=OFF >/dev/null
ninja -C build-sanitize -j "$(nproc)"
export LP_NUM_THREADS="${LP_NUM_THREADS:-2}"
export MESA_SHADER_CACHE_DIR="$(mktemp -d)"
cd build-sanitize
ctest --output-on-failure -j "$(nproc)" --timeout 1800 "$@"
