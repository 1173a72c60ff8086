#!/usr/bin/env bash
# The test suite under AddressSanitizer + UndefinedBehaviorSanitizer (float-cast-overflow included),
# a Debug build in build-sanitize/ (viewer off), as .ci/run runs it after the Release suite.
#   bash scripts/sanitize.sh [CTEST_ARGS...]
# Leak checking is on in every test process that never creates a GL context (CTest label `cpu`)
# and in the fuzzers (scripts/fuzz.sh), and off in the processes that do (label `gl`: the GL
# tests, and the command-line tests, whose `starnt` children inherit the options). There
# LeakSanitizer's own thread tracer crashes at random at exit ("Tracer caught signal 11") while
# llvmpipe's worker threads run, which no suppression can stop. Leaks that the GL driver stack
# reports in the others are suppressed by tests/lsan.supp (that stack only).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
cmake -S . -B build-sanitize -G Ninja -DCMAKE_BUILD_TYPE=Debug -DSTARNT_SANITIZE=ON -DSTARNT_BUILD_VIEWER=OFF >/dev/null
ninja -C build-sanitize -j "$(nproc)"
export LP_NUM_THREADS="${LP_NUM_THREADS:-2}"
export MESA_SHADER_CACHE_DIR="$(mktemp -d)"
export LSAN_OPTIONS="suppressions=$PWD/tests/lsan.supp:print_suppressions=0"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"
asan="abort_on_error=0:strict_string_checks=1"
# The retraining test trains both networks on 10 M samples (about 20 s each in Release); a Debug +
# ASan build takes many times that. The trainer's code runs under the sanitizers in the NnTrain
# tests at small sizes; the retraining itself is checked by the Release suite.
# The bundle check runs its binary under `env -i`, where the sanitizer settings above do not reach
# (LeakSanitizer would report the GL driver's leaks); the Release suite runs it.
skip="ShippedWeights|Bundle[.]"
cd build-sanitize
status=0
ASAN_OPTIONS="detect_leaks=1:$asan" ctest --output-on-failure -j "$(nproc)" --timeout 1800 -L cpu -E "$skip" "$@" || status=1
ASAN_OPTIONS="detect_leaks=0:$asan" ctest --output-on-failure -j "$(nproc)" --timeout 1800 -L gl -E "$skip" "$@" || status=1
exit $status
