#!/usr/bin/env bash
# Leave-one-family-out table (docs/results/families.md): for each network and each training family, train on every
# other family (built-in captures + procedural families + the generic synthetic lists) and report
# the image-space MSE on the held-out family's validation lists against hybrid and WBOIT (CPU
# references, over black). Writes the JSON reports to OUT_DIR and a markdown table to stdout.
#   [NETWORKS="starnt starnt-residual dfaoit"] scripts/families_table.sh [STARNT_BINARY] [OUT_DIR] [extra train options...]
set -euo pipefail
bin=${1:-build/starnt}
out=${2:-out/families}
shift $(( $# < 2 ? $# : 2 ))
mkdir -p "$out"
# The built-ins captured (curtains too: it is not in the default capture list) and the procedural families.
scenes="builtin:tubes builtin:smoke builtin:panes builtin:random builtin:curtains"
families="tubes smoke panes random curtains sheets particles foliage shells strands"
networks=${NETWORKS:-starnt starnt-residual dfaoit}
for network in $networks; do
    for family in $families; do
        LP_NUM_THREADS=${LP_NUM_THREADS:-1} "$bin" train --network "$network" --out "$out/${network}_without_${family}.json" \
            --scenes $scenes --hold-out "$family" --report "$out/${network}_without_${family}.report.json" "$@" >/dev/null 2>&1
    done
done
python3 - "$out" "$networks" $families <<'PY'
import json, sys
out, networks, families = sys.argv[1], sys.argv[2].split(), sys.argv[3:]
# Columns: each network, hybrid, hybrid-moments and wboit (whole family), each network / wboit, then the tail
# pixels (N > 3) of each network, hybrid and wboit.
head = ["held-out family", "pixels (tail)"] + networks + ["hybrid", "hybrid-moments", "wboit"] + [f"{n}/wboit" for n in networks]
head += [f"tail: {n}" for n in networks] + ["tail: hybrid", "tail: wboit"]
print("| " + " | ".join(head) + " |")
print("|" + "---|" * len(head))
for fam in families:
    row = {}
    for net in networks:
        rep = json.load(open(f"{out}/{net}_without_{fam}.report.json"))
        row[net] = next(f for f in rep["families"] if f["family"] == fam and f["held_out"])
    first = row[networks[0]]
    cells = [fam, f"{first['validation_pixels']} ({first['validation_tail_pixels']})"]
    cells += [f"{row[n]['mse_network']:.3e}" for n in networks] + [f"{first['mse_hybrid']:.3e}",
                                                                   f"{first['mse_hybrid_moments']:.3e}", f"{first['mse_wboit']:.3e}"]
    cells += [f"{row[n]['mse_network'] / row[n]['mse_wboit']:.3f}" for n in networks]
    cells += [f"{row[n]['tail_mse_network']:.3e}" for n in networks]
    cells += [f"{first['tail_mse_hybrid']:.3e}", f"{first['tail_mse_wboit']:.3e}"]
    print("| " + " | ".join(cells) + " |")
PY
