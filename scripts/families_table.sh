#!/usr/bin/env bash
# Leave-one-family-out table (issue 15): for each network and each training family, train on every
# other family (built-in captures + procedural families + the generic synthetic lists) and report
# the image-space MSE on the held-out family's validation lists against hybrid and WBOIT (CPU
# references, over black). Writes the JSON reports to OUT_DIR and a markdown table to stdout.
#   scripts/families_table.sh [STARNT_BINARY] [OUT_DIR] [extra train options...]
set -euo pipefail
bin=${1:-build/starnt}
out=${2:-out/families}
shift $(( $# < 2 ? $# : 2 ))
mkdir -p "$out"
# The built-ins captured (curtains too: it is not in the default capture list) and the procedural families.
scenes="builtin:tubes builtin:smoke builtin:panes builtin:random builtin:curtains"
families="tubes smoke panes random curtains sheets particles foliage shells strands"
for network in starnt dfaoit; do
    for family in $families; do
        LP_NUM_THREADS=${LP_NUM_THREADS:-1} "$bin" train --network "$network" --out "$out/${network}_without_${family}.json" \
            --scenes $scenes --hold-out "$family" --report "$out/${network}_without_${family}.report.json" "$@" >/dev/null 2>&1
    done
done
python3 - "$out" $families <<'PY'
import json, sys
out, families = sys.argv[1], sys.argv[2:]
print("| held-out family | pixels (tail) | starnt | dfaoit | hybrid | wboit | starnt/wboit | dfaoit/wboit "
      "| tail: starnt | tail: hybrid | tail: wboit | tail starnt/wboit |")
print("|---|---|---|---|---|---|---|---|---|---|---|---|")
for fam in families:
    row = {}
    for net in ("starnt", "dfaoit"):
        rep = json.load(open(f"{out}/{net}_without_{fam}.report.json"))
        row[net] = next(f for f in rep["families"] if f["family"] == fam and f["held_out"])
    s, d = row["starnt"], row["dfaoit"]
    print(f"| {fam} | {s['validation_pixels']} ({s['validation_tail_pixels']}) | {s['mse_network']:.3e} | "
          f"{d['mse_network']:.3e} | {s['mse_hybrid']:.3e} | {s['mse_wboit']:.3e} | "
          f"{s['mse_network'] / s['mse_wboit']:.3f} | {d['mse_network'] / d['mse_wboit']:.3f} | "
          f"{s['tail_mse_network']:.3e} | {s['tail_mse_hybrid']:.3e} | {s['tail_mse_wboit']:.3e} | "
          f"{s['tail_mse_network'] / s['tail_mse_wboit']:.3f} |")
PY
