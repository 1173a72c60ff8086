#!/usr/bin/env python3
"""Summarises one or more `starnt bench` results.json files (one run, or one run per scene) as the
headline table: per variant the mean over scenes of MSE and FLIP relative to WBOIT, MSE relative to
MBOIT (and on how many scenes below it), frame time relative to DFAOIT (mean and max; the bench's
long-run frame time, where temporal variants weigh real and interpolated frames by their shares in
the schedule, and beside it the plain mean of the timed frames; and the GPU time, a timestamp pair
around each frame, where the bench recorded one), the GPU
estimate relative to DFAOIT's (an estimate from the fragments and the bytes they write, never a
measurement), fragments relative to DFAOIT, the bytes a fragment writes over every geometry pass
(32-bit float bytes in brackets); then each acceleration against the same method without it, from the
same files, paired as the bench pairs them (each variant's acceleration_off in results.json).

Usage: scripts/bench_summary.py RESULTS.json [RESULTS.json ...]   (Markdown on stdout)
Ratios need wboit, mboit and dfaoit in every file; a variant missing from a scene is left out there;
a variant with times but no errors (it failed after its timed run) gets "-" for its errors.
"""
import json
import statistics
import sys


def load(paths):
    scenes, machine, pairs = [], None, {}
    for path in paths:
        with open(path) as f:
            r = json.load(f)
        machine = machine or r.get("machine")
        # Each accelerated variant names the same method with its acceleration off (the bench's pairs).
        for v in r.get("variants", []):
            if v.get("acceleration_off"):
                pairs[v["name"]] = (v["acceleration_off"], v.get("acceleration") or "")
        for s in r["scenes"]:
            if s.get("status") == "ok" or s.get("methods"):
                # A variant that failed after its timed run (its errors, say) still has its times.
                scenes.append((s["scene"]["name"], {m["variant"]: m for m in s["methods"] if "frame_ms_mean" in m.get("stats", {})}))
    return scenes, machine, pairs


def frame_ms(m):
    """The long-run frame time the bench compares (results from before it: the plain mean)."""
    v = m["stats"].get("frame_ms_long_run")
    return v if isinstance(v, (int, float)) else m["stats"]["frame_ms_mean"]


def window_ms(m):
    """The plain mean of the timed frames."""
    return m["stats"]["frame_ms_mean"]


def gpu_ms(m):
    """The frame's GPU time (a timestamp pair around each frame), or None where there is none."""
    v = m["stats"].get("frame_gpu_ms_long_run")
    if not isinstance(v, (int, float)):
        v = m["stats"].get("frame_gpu_ms_mean")
    return v if isinstance(v, (int, float)) else None


def estimate_ms(m):
    """The GPU estimate (render/gpu_estimate.hpp) of the frame, or None in results from before it."""
    v = m["stats"].get("gpu_estimate_ms_long_run")
    return v if isinstance(v, (int, float)) else None


def blend_bytes(m, cls=None):
    """Bytes a fragment writes, summed over the geometry passes of the real frames (one class, or all)."""
    total = 0.0
    for p in m["stats"].get("pass_blend", {}).values():
        total += sum(b for k, b in p.items() if k != "target_bits_per_pixel" and (cls is None or k == cls))
    return total


def fragments(m):
    """Fragments over every geometry pass: samples_passed where counted (exact), else invocations."""
    return sum(p.get("samples_passed", p.get("fragment_invocations", 0)) for p in m["stats"].get("pass_counters", {}).values())


def main(paths):
    scenes, machine, pairs = load(paths)
    if not scenes:
        sys.exit("bench_summary: no scene results in " + ", ".join(paths))
    if machine:
        print(f"Machine: {machine.get('gl_renderer', '?')} ({machine.get('gl_version', '?')}); "
              f"{machine.get('cpu_threads', '?')} threads of {machine.get('cpu_model', '?')}; build {machine.get('commit', '?')}\n")
    print("Scenes: " + ", ".join(name for name, _ in scenes) + "\n")
    variants = []
    for _, d in scenes:
        variants += [v for v in d if v not in variants]
    print("| variant | MSE / WBOIT | FLIP / WBOIT | MSE / MBOIT (scenes below) | time / DFAOIT (max) | window time / DFAOIT (max) "
          "| GPU time / DFAOIT (max) | GPU estimate / DFAOIT (max) | fragments / DFAOIT | bytes a fragment writes, all passes (float32) "
          "| ms per frame (per scene) |")
    print("|---|---|---|---|---|---|---|---|---|---|---|")
    for v in variants:
        rows = [(n, d) for n, d in scenes if v in d and all(k in d for k in ("wboit", "mboit", "dfaoit"))]
        if not rows:
            continue
        t = [frame_ms(d[v]) / frame_ms(d["dfaoit"]) for _, d in rows]
        w = [window_ms(d[v]) / window_ms(d["dfaoit"]) for _, d in rows]
        g = [gpu_ms(d[v]) / gpu_ms(d["dfaoit"]) for _, d in rows if gpu_ms(d[v]) and gpu_ms(d["dfaoit"])]
        gpu = f"{statistics.mean(g):.2f} ({max(g):.2f})" if len(g) == len(rows) else "-"  # llvmpipe: none
        e = [estimate_ms(d[v]) / estimate_ms(d["dfaoit"]) for _, d in rows if estimate_ms(d[v]) and estimate_ms(d["dfaoit"])]
        est = f"{statistics.mean(e):.2f} ({max(e):.2f})" if len(e) == len(rows) else "-"  # results from before the estimate
        first = rows[0][1][v]
        written = f"{blend_bytes(first):.0f} ({blend_bytes(first, 'float32'):.0f})" if first["stats"].get("pass_blend") else "-"
        fr = [fragments(d[v]) / max(fragments(d["dfaoit"]), 1) for _, d in rows]
        ms = ", ".join(f"{frame_ms(d[v]):.2f}" for _, d in rows)
        q = lambda d, k, x: (d[k].get("quality") or {}).get(x)
        if all(q(d, k, x) is not None for _, d in rows for k in (v, "wboit", "mboit") for x in ("mse", "flip")):
            mse = [q(d, v, "mse") / q(d, "wboit", "mse") for _, d in rows]
            flip = [q(d, v, "flip") / q(d, "wboit", "flip") for _, d in rows]
            mb = [q(d, v, "mse") / q(d, "mboit", "mse") for _, d in rows]
            errors = (f"{statistics.mean(mse):.3f} | {statistics.mean(flip):.3f} | "
                      f"{statistics.mean(mb):.2f} ({sum(x < 1 for x in mb)}/{len(rows)})")
        else:
            errors = "- | - | -"  # no errors measured (a run that failed after its timed frames)
        print(f"| {v} | {errors} | {statistics.mean(t):.2f} ({max(t):.2f}) | {statistics.mean(w):.2f} ({max(w):.2f}) | {gpu} | {est} | {statistics.mean(fr):.2f} | {written} | {ms} |")
    print("\nEach acceleration against the same method without it (frame time ratio per scene, mean):\n")
    for faster, (base, what) in pairs.items():
        ratios = [(n, frame_ms(d[faster]) / frame_ms(d[base])) for n, d in scenes if faster in d and base in d]
        if ratios:
            per = ", ".join(f"{n} {r:.2f}" for n, r in ratios)
            print(f"- {faster} / {base} ({what}): {statistics.mean(r for _, r in ratios):.2f} ({per})")


if __name__ == "__main__":
    if len(sys.argv) < 2 or sys.argv[1] in ("-h", "--help"):
        print(__doc__)
        sys.exit(0 if len(sys.argv) >= 2 else 2)
    main(sys.argv[1:])
