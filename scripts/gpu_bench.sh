#!/usr/bin/env bash
# Runs the GPU preset from a bundle (scripts/bundle.sh) on a lent GPU machine inside a fixed time
# window, one `bench` per scene so that a window that runs out still leaves every finished scene's
# report. After each scene it packs what came so far into one file, OUT/gpu_bench.tar.gz or
# $STARNT_PACK (reports, results, logs, and the ground truth and `recommended` images of the first
# two scenes): a lent machine hands back a few files, not a tree.
#
# Usage: scripts/gpu_bench.sh BUNDLE OUT [SECONDS [SCENES]]
#   SECONDS  the window (default 420): a scene starts only when the slowest scene so far (or 60 s
#            before the first) still fits in what is left.
#   SCENES   comma-separated (default: the preset's six headline scenes).
# Environment: STARNT_PACK=FILE, where the pack goes; STARNT_BENCH_ARGS, extra bench arguments (a dry run here: "--width 64 --height 36 --frames 3").
# Merge the per-scene results with scripts/bench_summary.py OUT/*/results.json.
set -uo pipefail
b="${1:?usage: gpu_bench.sh BUNDLE OUT [SECONDS [SCENES]]}"
out="${2:?usage: gpu_bench.sh BUNDLE OUT [SECONDS [SCENES]]}"
window="${3:-420}"
scenes="${4:-magic_stars,chess,tree,hair,hairball,engine}"
mkdir -p "$out/runs"
packed="$(realpath -m "${STARNT_PACK:-$out/gpu_bench.tar.gz}")"
start=$SECONDS
pack() {
  (cd "$out" && tar czf "$packed.part" --exclude='*.png' --exclude='*.exr' runs \
     $(ls runs/*/images/*/ground_truth.png runs/*/images/*/recommended.png 2>/dev/null | head -n 4) &&
   mv "$packed.part" "$packed")
}
{ nvidia-smi -L 2>&1 || true; "$b/starnt" --bundle-info; } | tee "$out/runs/machine.txt"

# One short render first (a built-in scene, the recommended method against the A-buffer): a broken
# context or shader fails here in seconds, with its message.
timeout 90 "$b/starnt" render --scene builtin:tubes --method recommended --width 640 --height 360 --frames 6 \
  --camera-path orbit:0,12 --reference-method abuffer --stats "$out/runs/smoke.json" --out "$out/runs/smoke.png" \
  > "$out/runs/smoke.log" 2>&1
echo "smoke render: exit $? ($(tail -n 2 "$out/runs/smoke.log" | tr '\n' ' '))"

slowest=60
IFS=, read -ra list <<<"$scenes"
for s in "${list[@]}"; do
  left=$(( window - (SECONDS - start) ))
  if (( left < slowest )); then echo "skipped $s: ${left} s left, the slowest scene took ${slowest} s"; continue; fi
  t0=$SECONDS
  timeout "$left" "$b/starnt" bench --preset gpu --scenes "$s" --no-plots ${STARNT_BENCH_ARGS:-} --out "$out/runs/$s" > "$out/runs/$s.log" 2>&1
  rc=$?
  took=$(( SECONDS - t0 )); (( took > slowest )) && slowest=$took
  echo "$s: exit $rc in ${took} s: $(tail -n 1 "$out/runs/$s.log")"
  pack
done
echo "done in $(( SECONDS - start )) s"
