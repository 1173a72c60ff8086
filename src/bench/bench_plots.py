"""Plots for `starnt bench` (embedded in the starnt binary and run with the system Python).

Usage: python3 bench_plots.py RESULTS.json OUT_DIR
Reads the bench's results.json and writes, into OUT_DIR:
  frame_time.png       frame time per scene and method (grouped bars)
  error.png            MSE x10^2 and FLIP per scene and method (grouped bars)
  quality_vs_time.png  FLIP against frame time, one point per scene and method
Exit status 3 when matplotlib cannot be imported (the bench then reports the plots as skipped).
Every file is written under a temporary name and renamed, like the bench's other outputs.
"""
import json
import math
import os
import sys

try:
    import matplotlib

    matplotlib.use("Agg")  # no display: files only
    import matplotlib.pyplot as plt
except ImportError as error:  # the bench reports this text
    print(f"matplotlib not available: {error}", file=sys.stderr)
    sys.exit(3)


def load(path):
    with open(path, encoding="utf-8") as f:
        results = json.load(f)
    variants = [v["name"] for v in results["variants"]]
    scenes = []
    for s in results["scenes"]:
        cases = {c["variant"]: c for c in s["methods"] if c["status"] == "ok"}
        scenes.append((s["scene"]["name"], cases))
    return results, variants, scenes


def value(case, getter):
    if case is None:
        return math.nan
    try:
        v = getter(case)
    except (KeyError, TypeError):
        return math.nan
    return math.nan if v is None else float(v)


def frame_ms(case):
    # The bench's compared frame time: the long-run mean (temporal frames weighted by their shares).
    v = case["stats"].get("frame_ms_long_run")
    return v if v is not None else case["stats"]["frame_ms_mean"]


def mse_x100(case):
    return case["quality"]["mse"] * 100.0


def flip(case):
    return case["quality"]["flip"]


def save(fig, out_dir, name):
    path = os.path.join(out_dir, name)
    tmp = path + ".tmp.png"
    fig.savefig(tmp, dpi=110, bbox_inches="tight")
    plt.close(fig)
    os.replace(tmp, path)
    print(name)


def grouped_bars(ax, scenes, variants, getter, ylabel, log_if_wide=False):
    width = 0.8 / max(1, len(variants))
    values = []
    for i, variant in enumerate(variants):
        ys = [value(cases.get(variant), getter) for _, cases in scenes]
        values += [y for y in ys if not math.isnan(y)]
        xs = [k + (i - (len(variants) - 1) / 2) * width for k in range(len(scenes))]
        ax.bar(xs, [0 if math.isnan(y) else y for y in ys], width, label=variant)
    ax.set_xticks(range(len(scenes)))
    ax.set_xticklabels([name for name, _ in scenes], rotation=20, ha="right")
    ax.set_ylabel(ylabel)
    positive = [v for v in values if v > 0]
    if log_if_wide and positive and max(positive) / min(positive) > 30:
        ax.set_yscale("log")
    ax.grid(axis="y", alpha=0.3)


def subtitle(results):
    s = results["settings"]
    m = results["machine"]
    return f'{s["width"]}x{s["height"]}, {s["frames"]} frames, {m["gl_renderer"]}'


def main():
    results_path, out_dir = sys.argv[1], sys.argv[2]
    results, variants, scenes = load(results_path)
    os.makedirs(out_dir, exist_ok=True)
    wide = max(6.0, 1.2 * len(scenes) + 3.0)

    fig, ax = plt.subplots(figsize=(wide, 4.2))
    grouped_bars(ax, scenes, variants, frame_ms, "frame time (ms, long-run mean of timed frames)", log_if_wide=True)
    ax.set_title("Frame time per scene\n" + subtitle(results), fontsize=10)
    ax.legend(fontsize=8, ncol=2)
    save(fig, out_dir, "frame_time.png")

    fig, (top, bottom) = plt.subplots(2, 1, figsize=(wide, 7.0))
    grouped_bars(top, scenes, variants, mse_x100, "MSE x10^2")
    top.set_title("Error against the A-buffer\n" + subtitle(results), fontsize=10)
    top.legend(fontsize=8, ncol=2)
    grouped_bars(bottom, scenes, variants, flip, "FLIP (mean)")
    save(fig, out_dir, "error.png")

    fig, ax = plt.subplots(figsize=(7.0, 5.0))
    markers = "osD^v<>ph*"
    for i, variant in enumerate(variants):
        points = [(value(c.get(variant), frame_ms), value(c.get(variant), flip), name) for name, c in scenes]
        points = [p for p in points if not (math.isnan(p[0]) or math.isnan(p[1]))]
        if not points:
            continue
        ax.scatter([p[0] for p in points], [p[1] for p in points], marker=markers[i % len(markers)], label=variant, s=40)
        for x, y, name in points:
            ax.annotate(name, (x, y), fontsize=6, alpha=0.6, xytext=(3, 3), textcoords="offset points")
    times = [value(c.get(v), frame_ms) for _, c in scenes for v in variants]
    times = [t for t in times if t > 0]
    if times and max(times) / min(times) > 30:
        ax.set_xscale("log")
    ax.set_xlabel("frame time (ms, long-run mean of timed frames)")
    ax.set_ylabel("FLIP (mean, lower is better)")
    ax.set_title("Quality versus time\n" + subtitle(results), fontsize=10)
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)
    save(fig, out_dir, "quality_vs_time.png")


if __name__ == "__main__":
    main()
