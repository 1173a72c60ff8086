#!/usr/bin/env bash
# Builds the libFuzzer targets (fuzz/) with Clang, ASan and UBSan into build-fuzz/ and runs each.
#   bash scripts/fuzz.sh [SECONDS_PER_TARGET=60] [RUNS_PER_TARGET=0 (no limit)] [TARGETS...]
# A target stops at SECONDS or after RUNS inputs, whichever comes first (0 = that limit is off).
# Each run starts from the seeds in fuzz/corpus/<target> plus what earlier runs found
# (build-fuzz/corpus/<target>). A crash, a sanitizer report or any exception other than
# starnt::Error fails the script and leaves the input in build-fuzz/findings/<target>/; the
# script then prints the end of the fuzzer's report (CI keeps no build folder). Every run prints
# its seed: `build-fuzz/fuzz/fuzz_<target> -seed=N <same corpora>` replays the same inputs.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
seconds=${1:-60}
runs=${2:-0}
shift $(( $# > 2 ? 2 : $# ))
targets=("$@")
[ ${#targets[@]} -gt 0 ] || targets=(gltf obj weights camera image)
cmake -S . -B build-fuzz -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_COMPILER=clang++ \
  -DSTARNT_FUZZ=ON -DSTARNT_BUILD_TESTS=OFF -DSTARNT_BUILD_VIEWER=OFF >/dev/null
ninja -C build-fuzz "${targets[@]/#/fuzz_}"
export ASAN_OPTIONS=detect_leaks=1:allocator_may_return_null=0
export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
status=0
for t in "${targets[@]}"; do
  corpus=build-fuzz/corpus/$t findings=build-fuzz/findings/$t
  mkdir -p "$corpus" "$findings"
  log=build-fuzz/fuzz_$t.log
  echo "fuzz_$t: ${seconds}s, runs ${runs} (0 = unlimited)" >&2
  if ! build-fuzz/fuzz/fuzz_$t "$corpus" fuzz/corpus/$t -max_total_time="$seconds" -runs="${runs/#0/-1}" \
       -max_len=65536 -rss_limit_mb=2048 -timeout=20 -print_final_stats=1 -artifact_prefix="$findings/" \
       >"$log" 2>&1; then
    echo "fuzz_$t: FAILED, see $log and $findings/; the report:" >&2
    grep -v -E "^#[0-9]+|^INFO:|^MS:|^base unit" "$log" | tail -n 40 | sed "s/^/fuzz_$t: | /" >&2 || true
    status=1
  fi
  # The seed makes a run repeatable: build-fuzz/fuzz/fuzz_$t ... -seed=N replays the same inputs.
  grep -E "INFO: Seed:|stat::number_of_executed_units|stat::peak_rss_mb|Done [0-9]+ runs" "$log" | sed "s/^/fuzz_$t: /" >&2 || true
done
exit $status
