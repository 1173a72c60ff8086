#!/usr/bin/env bash
# Checks scripts/bundle.sh end to end: bundles the six headline scenes (honours STARNT_BINARY;
# without it bundle.sh builds), moves the bundle (it must be relocatable), then with an EMPTY
# environment and from an empty folder: `starnt --bundle-info` through a symlink, the GPU preset
# (`bench --preset gpu`: every scene and variant it names, here at a tiny size and 3 timed frames
# so that llvmpipe gets through it) on the bundled scenes (exit 0, report.md and results.json
# written, 0 failures, scenes read from the bundle), and the launcher's refusal, with a clear EGL
# message, when the machine has no libEGL.so.1 (a fake ldconfig that lists nothing and no library
# folders to search); scripts/gpu_bench.sh on two scenes from the bundle and scripts/bench_summary.py
# on its pack.
# Usage: scripts/check_bundle.sh [SCENES...]   (default: the preset's six headline scenes)
# Prints the bundle's size; exits non-zero on any failure. ctest runs it (Bundle.GpuPresetUnderAnEmptyEnvironment).
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
scenes="$(IFS=,; echo "${*:-magic_stars,chess,tree,hair,hairball,engine}")"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
fail() { echo "check_bundle: FAILED: $*" >&2; exit 1; }
# Runs "$@" with output to $work/log; prints the log and fails when the exit status is not $expect.
run() {
  local expect="$1"; shift
  local rc=0
  "$@" > "$work/log" 2>&1 || rc=$?
  if [[ $expect == 0 && $rc -ne 0 ]] || [[ $expect != 0 && $rc -eq 0 ]]; then
    cat "$work/log" >&2; fail "exit $rc (expected $([[ $expect == 0 ]] && echo 0 || echo non-zero)): $*"
  fi
}

run 0 bash "$root/scripts/bundle.sh" "$work/made" "$scenes"
mv "$work/made" "$work/bundle"
b="$work/bundle"
mkdir "$work/empty"
cd "$work/empty"
ln -s "$b/starnt" "$work/link"

run 0 env -i "$work/link" --bundle-info
grep -q '^binary: bin/starnt' "$work/log" || { cat "$work/log" >&2; fail "--bundle-info: no summary"; }
grep '^size:\|^this machine:' "$work/log"

run 0 env -i LP_NUM_THREADS=2 "$b/starnt" bench --preset gpu --suite-dir "$b/scenes" --scenes "$scenes" \
  --width 64 --height 36 --frames 3 --no-plots --out "$work/out"
for f in report.md results.json results.csv; do [[ -s $work/out/$f ]] || { cat "$work/log" >&2; fail "bench wrote no $f"; }; done
grep -q '(0 failures)' "$work/log" || { cat "$work/log" >&2; fail "bench reported failures"; }
grep -q "\"suite_dir\": *\"$b/scenes\"" "$work/out/results.json" || fail "results.json: the scenes did not come from $b/scenes"
for v in wboit mboit-t3 dfaoit starnt-d starnt-total-warp recommended; do
  grep -q "\"variant\": *\"$v\"" "$work/out/results.json" || fail "results.json: the gpu preset did not run $v"
done
[[ -z $(ls -A "$work/empty") ]] || fail "the bench wrote into the current folder: $(ls -A "$work/empty")"
echo "check_bundle: bench under env -i: ok ($(tail -n1 "$work/log"))"

# The windowed runner for lent machines: two scenes, packed into one file, merged by bench_summary.
run 0 env -i PATH=/usr/bin:/bin LP_NUM_THREADS=2 STARNT_PACK="$work/pack.tgz" \
  STARNT_BENCH_ARGS="--width 32 --height 18 --frames 3 --methods wboit,mboit,dfaoit,starnt-d,recommended" \
  bash "$root/scripts/gpu_bench.sh" "$b" "$work/windowed" 300 chess,tree
grep -q '^smoke render: exit 0' "$work/log" || { cat "$work/log" >&2; fail "gpu_bench.sh: the smoke render failed"; }
[[ $(grep -c ': exit 0 in .*(0 failures)' "$work/log") == 2 ]] || { cat "$work/log" >&2; fail "gpu_bench.sh: not both scenes ran"; }
mkdir "$work/unpacked"
tar xzf "$work/pack.tgz" -C "$work/unpacked"
for s in chess tree; do
  [[ -s $work/unpacked/runs/$s/report.md ]] || fail "gpu_bench.sh: the pack lacks runs/$s/report.md"
done
python3 "$root/scripts/bench_summary.py" "$work"/unpacked/runs/*/results.json > "$work/summary.md"
grep -q '^| dfaoit | .* | 1.00 (1.00) |' "$work/summary.md" || { cat "$work/summary.md" >&2; fail "bench_summary.py: no DFAOIT row at 1.00"; }
grep -q '^- recommended / starnt-d .*chess .*tree' "$work/summary.md" || { cat "$work/summary.md" >&2; fail "bench_summary.py: no recommended / starnt-d line for both scenes"; }
echo "check_bundle: gpu_bench.sh and bench_summary.py: ok"

mkdir "$work/fake"
printf '#!/bin/sh\nexit 0\n' > "$work/fake/ldconfig"
chmod 755 "$work/fake/ldconfig"
run 1 env -i PATH="$work/fake:/usr/bin:/bin" STARNT_LIB_DIRS=/nonexistent "$b/starnt" bench --out "$work/out2"
grep -q 'libEGL.so.1' "$work/log" || { cat "$work/log" >&2; fail "no EGL message without libEGL.so.1"; }
[[ ! -e $work/out2 ]] || fail "the binary ran although the EGL check failed"
echo "check_bundle: EGL check: ok ($(cat "$work/log"))"

echo "check_bundle: ok: bundle of $scenes is $(du -sb "$b" | awk '{printf "%.1f", $1 / 1048576}') MiB"
