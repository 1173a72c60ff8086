#!/usr/bin/env python3
"""Fit the GPU frame-time estimate of src/render/gpu_estimate.cpp to committed GPU runs.

The model (src/render/gpu_estimate.hpp): a geometry pass costs
    fragments x (nsPerFragment + nsPerNarrowByte x narrow bytes + nsPerWideByte x wide bytes)
(bytes a fragment writes into targets of <= 16 bits a channel, and into 32-bit-channel targets:
float32, uint32, int32), and every other timed pass (composite, inference, resolve, tiles, ...)
costs width x height x nsPerPixelFullscreen. (MODEL_HAS_TARGET: a target term, width x height x
bytes a pixel of a geometry pass's colour targets x nsPerTargetByte; the diagnostics weigh it, the
model does not have it.)

The GPU runs (docs/results/gpu_*_1080p/*_results.csv) have per-pass GL_TIMESTAMP times but no
per-pass fragment counts or bytes; those come from llvmpipe runs of the same variants, scenes,
size and camera path, collected by `collect` into docs/results/gpu_estimate_fit_counts.csv: per
geometry pass `samples_passed` (GL_SAMPLES_PASSED, exact on llvmpipe) as its fragments, as
gpuEstimateMs counts them, and `fragment_invocations` (pipeline statistics: whole 4x4 blocks)
beside it. A geometry pass's counters pair with its timed pass as in gpuEstimateMs: the same name,
or the timed name after the method's prefix (counts "wboit_accumulate", times "accumulate").

    # llvmpipe counts (48 renders, one at a time, LP_NUM_THREADS=2, nice 10: about 6 minutes on 2 cores):
    scripts/fit_gpu_estimate.py collect --starnt /tmp/starnt-fit/starnt --scenes-dir /work/shared/scenes \
        --out docs/results/gpu_estimate_fit_counts.csv
    # the fit and its tables (markdown on stdout; python3 with numpy, e.g. /usr/bin/python3):
    scripts/fit_gpu_estimate.py fit --counts docs/results/gpu_estimate_fit_counts.csv

python3 + numpy only.
"""
import argparse
import csv
import glob
import json
import os
import subprocess
import sys
import time

import numpy as np

# Bench variants and the render options they stand for (src/bench/bench_plan.cpp, allVariants).
VARIANTS = {
    "wboit": ["--method", "wboit"],
    "mboit": ["--method", "mboit", "--mboit-moments", "6"],
    "dfaoit": ["--method", "dfaoit"],
    "starnt-full": ["--method", "starnt", "--spatial", "off"],
    "starnt": ["--method", "starnt", "--spatial", "on"],
    "hybrid": ["--method", "hybrid", "--spatial", "off"],
    "hybrid-moments": ["--method", "hybrid-moments"],
    "starnt-d": ["--method", "starnt-d"],
}
# The gpu preset's scenes (bench_plan.cpp, suiteScenes; alpha override where the file is opaque).
SCENES = {
    "magic_stars": ("magic_stars/magic_stars_procedural.glb", []),
    "chess": ("chess/chess_classic_board.glb", []),
    "tree": ("tree/tree_grove.glb", []),
    "engine": ("engine/2CylinderEngine.glb", ["--alpha", "0.3"]),
    "hair": ("hair/hair_procedural.glb", []),
    "hairball": ("hairball/hairball_procedural.glb", []),
}
SCENE_ORDER = ["chess", "engine", "hair", "hairball", "magic_stars", "tree"]
VARIANT_ORDER = list(VARIANTS)
WIDE = {"float32", "uint32", "int32"}  # render/gpu_estimate.cpp, wideFormatClass
KNOWN_CLASSES = ["float32", "float16", "unorm16", "unorm8", "uint32"]
COUNT_FIELDS = ["scene", "variant", "pass", "timed_pass", "kind", "fragments", "fragment_invocations", "primitives", "narrow_bytes",
                "wide_bytes"] + KNOWN_CLASSES + [
    "other_classes", "target_bits_per_pixel", "timed_frames", "scale_pass2", "scale_pass3", "llvmpipe_pass_ms"]

ROOT = os.path.normpath(os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
RESULTS = os.path.join(ROOT, "docs", "results")
GPU_RUNS = {
    # name -> list of CSV globs, earlier ones win for a (scene, variant) they hold
    "H200": ["gpu_h200_1080p/*_results.csv"],  # run A (*_results.csv) and run B (*_temporal_run_results.csv)
    # H100: run 1 (every scene but engine, hybrid too), then run 2 for engine (older code; see the report)
    "H100": ["gpu_h100_1080p/*_first_run_times_results.csv", "gpu_h100_1080p/*_results.csv"],
}
WIDTH, HEIGHT = 1920, 1080
# Whether the model (gpuEstimateMs) has the target term: a geometry pass's width x height x bytes a
# pixel of its colour targets (PassBlend::targetBitsPerPixel / 8) x nsPerTargetByte.
MODEL_HAS_TARGET = False


# ----------------------------------------------------------------------------------------------
# collect: llvmpipe renders -> counts CSV


def timed_pass_of(counter, timed):
    """The timed pass a geometry pass's counters belong to, as gpuEstimateMs pairs them: the same
    name, or the timed name after the method's prefix (wboit counts "wboit_accumulate", times
    "accumulate"); "" when none."""
    if counter in timed:
        return counter
    return next((t for t in sorted(timed) if counter.endswith("_" + t) and len(counter) > len(t) + 1), "")


def rows_of_stats(scene, variant, stats):
    """One row per geometry pass (fragments = samples_passed, GL_SAMPLES_PASSED: exact on llvmpipe;
    fragment_invocations, pipeline statistics, beside it: whole 4x4 blocks) and per other timed pass."""
    rows = []
    counters = stats.get("pass_counters", {})
    blend = stats.get("pass_blend", {})
    timed = stats.get("pass_ms", {})
    geometry = set(counters) | set(blend)
    for name in sorted(geometry):
        b = blend.get(name, {})
        c = counters.get(name, {})
        row = {"scene": scene, "variant": variant, "pass": name, "timed_pass": timed_pass_of(name, timed), "kind": "geometry",
               "fragments": c.get("samples_passed", c.get("fragment_invocations", 0.0)),
               "fragment_invocations": c.get("fragment_invocations", ""), "primitives": c.get("primitives", 0.0)}
        narrow = wide = 0.0
        other = {}
        for cls, v in b.items():
            if cls == "target_bits_per_pixel":
                continue
            if cls in WIDE:
                wide += v
            else:
                narrow += v
            if cls not in KNOWN_CLASSES and v:
                other[cls] = v
        for cls in KNOWN_CLASSES:
            row[cls] = b.get(cls, 0.0)
        row.update(narrow_bytes=narrow, wide_bytes=wide, other_classes=json.dumps(other, sort_keys=True) if other else "",
                   target_bits_per_pixel=b.get("target_bits_per_pixel", ""))
        rows.append(row)
    paired = {r["timed_pass"] for r in rows}
    for name in sorted(timed):
        if name not in paired:
            rows.append({"scene": scene, "variant": variant, "pass": name, "timed_pass": name, "kind": "fullscreen"})
    for row in rows:
        row.update(timed_frames=stats.get("timed_frames"), scale_pass2=stats.get("scale_pass2"),
                   scale_pass3=stats.get("scale_pass3"), llvmpipe_pass_ms=timed.get(row["timed_pass"], ""))
    return rows


def collect(args):
    done = set()
    if os.path.exists(args.out):
        with open(args.out) as f:
            done = {(r["scene"], r["variant"]) for r in csv.DictReader(f)}
    scenes = args.scenes.split(",") if args.scenes else list(SCENES)
    variants = args.variants.split(",") if args.variants else list(VARIANTS)
    os.makedirs(args.work, exist_ok=True)
    for scene in scenes:
        path, scene_opts = SCENES[scene]
        for variant in variants:
            if (scene, variant) in done:
                continue
            frames = args.frames_for.get(scene, args.frames)
            stats_path = os.path.join(args.work, f"{scene}_{variant}.json")
            cmd = ["nice", "-n", "10", args.starnt, "render", "--scene", os.path.join(args.scenes_dir, path)] + scene_opts + \
                VARIANTS[variant] + ["--width", str(WIDTH), "--height", str(HEIGHT), "--frames", str(frames),
                                     "--warmup", str(args.warmup), "--camera-path", "orbit:0,126,15", "--stats", stats_path,
                                     "--out", os.path.join(args.work, "x.png")]
            env = dict(os.environ, LP_NUM_THREADS=str(args.threads))
            t0 = time.time()
            print(" ".join(cmd), file=sys.stderr, flush=True)
            if not (args.reuse and os.path.exists(stats_path)):
                subprocess.run(cmd, env=env, check=True, stdout=subprocess.DEVNULL)
            print(f"  {scene} {variant}: {time.time() - t0:.0f} s", file=sys.stderr, flush=True)
            with open(stats_path) as f:
                rows = rows_of_stats(scene, variant, json.load(f))
            new = not os.path.exists(args.out)
            with open(args.out, "a", newline="") as f:
                w = csv.DictWriter(f, fieldnames=COUNT_FIELDS)
                if new:
                    w.writeheader()
                w.writerows(rows)


# ----------------------------------------------------------------------------------------------
# fit


def read_counts(path, source="fragments"):
    """(scene, variant) -> {timed pass name: row}; a geometry pass's row under the timed pass its
    counters pair with (`timed_pass`, as gpuEstimateMs pairs them), with its count from column
    `source` ("fragments": samples_passed; "fragment_invocations": llvmpipe's 4x4-block count)."""
    counts = {}
    with open(path) as f:
        rows = list(csv.DictReader(f))
    for r in rows:
        if r["kind"] == "geometry":
            r = dict(r, fragments=r[source] or r["fragments"])
        counts.setdefault((r["scene"], r["variant"]), {})[r.get("timed_pass") or r["pass"]] = r
    return counts


def read_gpu(globs):
    """(scene, variant) -> {"passes": {pass: ms}, "frame_ms": mean frame ms, "run": file}; the first glob wins."""
    runs = {}
    for g in globs:
        for path in sorted(glob.glob(os.path.join(RESULTS, g))):
            with open(path) as f:
                for r in csv.DictReader(f):
                    key = (r["scene"], r["variant"])
                    if key in runs or r["variant"] not in VARIANTS:
                        continue  # recommended, the temporal variants and starnt-vrs are not fitted
                    passes = {k[5:-3]: float(v) for k, v in r.items() if k.startswith("pass_") and k.endswith("_ms") and v}
                    if float(r.get("scale_pass2") or 1) != 1 or float(r.get("scale_pass3") or 1) != 1:
                        continue
                    runs[key] = {"passes": passes, "frame_ms": float(r["frame_ms_mean"]), "run": os.path.relpath(path, RESULTS)}
    return runs


def observations(gpu, counts):
    """One row per timed GPU pass: features [fragments, fragments x narrow, fragments x wide, full-screen
    pixels, target bytes (a geometry pass's pixels x bytes a pixel of its colour targets)] (millions), ms."""
    obs, missing = [], []
    for (scene, variant), run in sorted(gpu.items()):
        c = counts.get((scene, variant))
        if c is None:
            missing.append((scene, variant, "no llvmpipe counts"))
            continue
        for name, ms in run["passes"].items():
            row = c.get(name)
            if row is None:
                missing.append((scene, variant, f"pass {name} not on llvmpipe"))
                continue
            if row["kind"] == "geometry":
                n = float(row["fragments"])
                x = [n, n * float(row["narrow_bytes"]), n * float(row["wide_bytes"]), 0.0,
                     WIDTH * HEIGHT * float(row["target_bits_per_pixel"] or 0) / 8]
            else:
                x = [0.0, 0.0, 0.0, WIDTH * HEIGHT, 0.0]
            obs.append({"scene": scene, "variant": variant, "pass": name, "kind": row["kind"], "x": np.array(x) * 1e-6, "ms": ms,
                        "fragments": float(row["fragments"] or 0), "primitives": float(row.get("primitives") or 0),
                        "target_bytes": float(row["target_bits_per_pixel"] or 0) / 8})
        for name, row in c.items():
            if name not in run["passes"]:
                missing.append((scene, variant, f"llvmpipe pass {name} not timed on the GPU"))
    return obs, missing


def read_gpu_report_counts(folder):
    """The GPU's own fragment counts per geometry pass (millions), from the bench reports of a run
    (docs/results/gpu_h200_1080p/SCENE_report.md): "Fragments shaded per frame" gives each variant's
    total over its geometry passes, "Scales and passes 2 + 3 work" starnt-full's passes 2 + 3.
    Pass 3 and WBOIT's one pass shade every fragment of the scene (N = WBOIT's total), so for the
    STAR-NT passes pass 3 = N, pass 2 = (2 + 3) - N, pass 1 = total - (2 + 3); MBOIT's two passes
    N each; DFAOIT's passes 1 and 2 (the same bytes) only together: total - N, as "pass1+pass2".
    hybrid (not in the reports' run) takes starnt-full's. Two decimals: about 2 % on magic_stars."""
    out = {}
    for path in sorted(glob.glob(os.path.join(RESULTS, folder, "*_report.md"))):
        scene = os.path.basename(path)[: -len("_report.md")]
        text = open(path).read().split("\n")
        totals, f23, section = {}, None, ""
        for i, line in enumerate(text):
            if line.startswith("## "):
                section = line
            if line.startswith("## Fragments shaded per frame"):
                header = next(l for l in text[i:] if l.startswith("| scene"))
                row = next(l for l in text[i:] if l.startswith(f"| {scene} "))
                names = [c.strip() for c in header.strip("|").split("|")][1:]
                vals = [float(c) for c in row.strip("|").split("|")[1:]]
                totals = dict(zip(names, vals))
            if section.startswith("## Scales and passes 2 + 3") and line.startswith(f"| {scene} | starnt-full |"):
                f23 = float(line.strip("|").split("|")[5])
        if not totals or f23 is None:
            continue
        n = totals["wboit"]
        c = {("wboit", "accumulate"): n, ("mboit", "moments"): totals["mboit"] / 2, ("mboit", "shade"): totals["mboit"] / 2,
             ("dfaoit", "pass3"): n, ("dfaoit", "pass1+pass2"): totals["dfaoit"] - n}
        for v in ["starnt-full", "starnt", "hybrid", "hybrid-moments", "starnt-d"]:
            t = totals.get(v, totals["starnt-full"])
            c[(v, "pass3")], c[(v, "pass2")], c[(v, "pass1")] = n, f23 - n, t - f23
        out[scene] = {k: v * 1e6 for k, v in c.items()}
    return out


def report_totals(folder):
    """scene -> {variant: the GPU's fragments a frame over all geometry passes (millions)} from the
    bench reports' "Fragments shaded per frame" (the GPU's pipeline-statistics invocations)."""
    out = {}
    for path in sorted(glob.glob(os.path.join(RESULTS, folder, "*_report.md"))):
        scene = os.path.basename(path)[: -len("_report.md")]
        text = open(path).read().split("\n")
        for i, line in enumerate(text):
            if line.startswith("## Fragments shaded per frame"):
                header = next(l for l in text[i:] if l.startswith("| scene"))
                row = next(l for l in text[i:] if l.startswith(f"| {scene} "))
                names = [c.strip() for c in header.strip("|").split("|")][1:]
                out[scene] = dict(zip(names, [float(c) for c in row.strip("|").split("|")[1:]]))
    return out


def count_check(counts, folder, out):
    """llvmpipe's samples_passed (and fragment_invocations) over a frame's geometry passes against
    the GPU's own counts (bench reports), per variant and scene."""
    p = lambda *a: print(*a, file=out)
    totals = report_totals(folder)
    scenes = [sc for sc in SCENE_ORDER if sc in totals]
    p(f"#### Fragments a frame over all geometry passes (millions): llvmpipe samples_passed / the GPU's ({folder} reports) "
      "(ratio); last row: llvmpipe fragment_invocations / GPU's\n")
    p("| variant | " + " | ".join(scenes) + " |")
    p("|---|" + "---|" * len(scenes))
    ratios, inv = [], []
    for v in VARIANT_ORDER:
        cells = []
        for sc in scenes:
            c, g = counts.get((sc, v)), totals[sc].get(v)
            if c is None or g is None:
                cells.append("")
                continue
            geo = [r for r in c.values() if r["kind"] == "geometry"]
            n = sum(float(r["fragments"]) for r in geo) / 1e6
            ratios.append(n / g)
            inv.append(sum(float(r["fragment_invocations"] or 0) for r in geo) / 1e6 / g)
            cells.append(f"{n:.2f} / {g:.2f} ({n / g:.2f})")
        if any(cells):
            p(f"| {v} | " + " | ".join(cells) + " |")
    p("")
    p(f"samples_passed / GPU's: {min(ratios):.2f}-{max(ratios):.2f} (mean {np.mean(ratios):.2f}); "
      f"fragment_invocations / GPU's: {min(inv):.2f}-{max(inv):.2f} (mean {np.mean(inv):.2f})\n")


def with_gpu_counts(obs, gpu_counts):
    """The observations with the GPU's fragment counts in place of llvmpipe's (DFAOIT's passes 1
    and 2 merged into one); those of scenes without counts dropped."""
    out, merged = [], {}
    for o in obs:
        c = gpu_counts.get(o["scene"])
        if c is None:
            continue
        o = dict(o)
        if o["kind"] == "geometry":
            if o["variant"] == "dfaoit" and o["pass"] in ("pass1", "pass2"):
                if o["scene"] in merged:
                    merged[o["scene"]]["ms"] += o["ms"]
                    continue
                o["pass"] = "pass1+pass2"
                merged[o["scene"]] = o
            scale = c[(o["variant"], o["pass"])] * 1e-6 / o["x"][0]
            o["x"] = np.concatenate([o["x"][:3] * scale, o["x"][3:]])
            o["fragments"] *= scale
        out.append(o)
    return out


def nonneg_lstsq(A, b, free=None):
    """Least squares with coefficients >= 0: solve, pin the most negative one at 0, solve again."""
    active = list(range(A.shape[1])) if free is None else list(free)
    while True:
        coef = np.zeros(A.shape[1])
        if active:
            coef[active] = np.linalg.lstsq(A[:, active], b, rcond=None)[0]
        neg = [i for i in active if coef[i] < 0]
        if not neg:
            return coef
        active.remove(min(neg, key=lambda i: coef[i]))


def fit(obs, target=MODEL_HAS_TARGET):
    """Relative least squares (each pass's error over its measured time), coefficients in ns:
    fragment, narrow byte, wide byte, full-screen pixel, and (with `target`) target byte."""
    A = np.array([o["x"] for o in obs])
    m = np.array([o["ms"] for o in obs])
    w = 1.0 / m
    return nonneg_lstsq(A * w[:, None], m * w, free=range(5 if target else 4))


def fit_fullscreen_table(obs):
    """One ns/pixel per full-screen pass name (relative least squares)."""
    table = {}
    for name in sorted({o["pass"] for o in obs if o["kind"] == "fullscreen"}):
        px = np.array([o["x"][3] for o in obs if o["pass"] == name])
        m = np.array([o["ms"] for o in obs if o["pass"] == name])
        table[name] = float(np.sum(px / m) / np.sum((px / m) ** 2))
    return table


def predict(o, coef, table=None):
    if o["kind"] == "fullscreen" and table is not None and o["pass"] in table:
        return o["x"][3] * table[o["pass"]]
    return float(o["x"] @ coef)


def rel(p, m):
    return (p - m) / m


def pct(x):
    return f"{100 * x:+.0f} %"


def frames(obs, gpu, coef, table=None):
    """(scene, variant) -> measured pass sum, measured frame ms, predicted frame ms."""
    out = {}
    for o in obs:
        f = out.setdefault((o["scene"], o["variant"]), {"pass_sum": 0.0, "pred": 0.0})
        f["pass_sum"] += o["ms"]
        f["pred"] += predict(o, coef, table)
    for key, f in out.items():
        f["frame_ms"] = gpu[key]["frame_ms"]
    return out


def summary(obs, fr, coef, table=None):
    pe = np.array([abs(rel(predict(o, coef, table), o["ms"])) for o in obs])
    ge = np.array([abs(rel(predict(o, coef, table), o["ms"])) for o in obs if o["kind"] == "geometry"])
    fe = np.array([abs(rel(predict(o, coef, table), o["ms"])) for o in obs if o["kind"] == "fullscreen"])
    te = np.array([abs(rel(f["pred"], f["pass_sum"])) for f in fr.values()])
    tw = np.array([abs(rel(f["pred"], f["frame_ms"])) for f in fr.values()])
    return {"pass": (pe.mean(), pe.max()), "geometry": (ge.mean(), ge.max()), "fullscreen": (fe.mean(), fe.max()),
            "frame_vs_pass_sum": (te.mean(), te.max()), "frame_vs_frame_ms": (tw.mean(), tw.max())}


def ratio_rows(fr):
    """variant -> per scene (measured pass-sum ratio, measured frame ratio, predicted ratio) to DFAOIT."""
    rows = {}
    for (scene, variant), f in fr.items():
        d = fr.get((scene, "dfaoit"))
        if d is None:
            continue
        rows.setdefault(variant, {})[scene] = (f["pass_sum"] / d["pass_sum"], f["frame_ms"] / d["frame_ms"], f["pred"] / d["pred"])
    return rows


def fmt_coef(coef):
    return (f"nsPerFragment {coef[0]:.4f}, nsPerNarrowByte {coef[1]:.4f}, nsPerWideByte {coef[2]:.4f}, "
            f"nsPerPixelFullscreen {coef[3]:.4f}" + (f", nsPerTargetByte {coef[4]:.4f}" if MODEL_HAS_TARGET else ""))


def report(name, gpu, counts, detail, out):
    obs, missing = observations(gpu, counts)
    coef = fit(obs)
    table = fit_fullscreen_table(obs)
    fr = frames(obs, gpu, coef)
    frt = frames(obs, gpu, coef, table)
    s, st = summary(obs, fr, coef), summary(obs, frt, coef, table)
    p = lambda *a: print(*a, file=out)
    p(f"### {name}: {len(obs)} passes of {len(gpu)} (scene, variant) runs\n")
    p(f"Coefficients (ns): {fmt_coef(coef)}\n")
    p("Per-pass-name full-screen table (ns a pixel): " + ", ".join(f"{k} {v:.4f}" for k, v in table.items()) + "\n")
    p("| absolute relative error, mean (max) | one full-screen coefficient | per-name full-screen table |")
    p("|---|---|---|")
    for k, label in [("pass", "every pass"), ("geometry", "geometry passes"), ("fullscreen", "full-screen passes"),
                     ("frame_vs_pass_sum", "frame: predicted vs sum of measured passes"),
                     ("frame_vs_frame_ms", "frame: predicted vs measured frame ms (glFinish + wall clock)")]:
        p(f"| {label} | {100 * s[k][0]:.1f} % ({100 * s[k][1]:.0f} %) | {100 * st[k][0]:.1f} % ({100 * st[k][1]:.0f} %) |")
    p("")
    if missing:
        p("Not fitted: " + "; ".join(f"{a} {b}: {c}" for a, b, c in missing) + "\n")
    if not detail:
        rr = ratio_rows(fr)
        p("Time / DFAOIT, mean over scenes: measured (pass sums) vs predicted: " +
          ", ".join(f"{v} {np.mean([x[0] for x in rr[v].values()]):.2f} vs {np.mean([x[2] for x in rr[v].values()]):.2f}"
                    for v in VARIANT_ORDER if v in rr) + "\n")
        return coef, obs, fr
    scenes = [sc for sc in SCENE_ORDER if any(k[0] == sc for k in gpu)]
    p("#### Per pass: measured ms / predicted ms (relative error; full-screen passes with the one coefficient)\n")
    p("| variant | pass | " + " | ".join(scenes) + " |")
    p("|---|---|" + "---|" * len(scenes))
    by = {(o["scene"], o["variant"], o["pass"]): o for o in obs}
    for v in VARIANT_ORDER:
        names = sorted({o["pass"] for o in obs if o["variant"] == v}, key=lambda n: (by_kind(obs, n), n))
        for n in names:
            cells = []
            for sc in scenes:
                o = by.get((sc, v, n))
                if o is None:
                    cells.append("")
                    continue
                pr = predict(o, coef)
                cells.append(f"{o['ms']:.2f} / {pr:.2f} ({pct(rel(pr, o['ms']))})")
            p(f"| {v} | {n} | " + " | ".join(cells) + " |")
    p("\n#### Per frame: measured (sum of pass times; frame ms) / predicted ms (error against the pass sum)\n")
    p("| variant | " + " | ".join(scenes) + " |")
    p("|---|" + "---|" * len(scenes))
    for v in VARIANT_ORDER:
        cells = []
        for sc in scenes:
            f = fr.get((sc, v))
            cells.append("" if f is None else f"{f['pass_sum']:.2f}; {f['frame_ms']:.2f} / {f['pred']:.2f} ({pct(rel(f['pred'], f['pass_sum']))})")
        if any(cells):
            p(f"| {v} | " + " | ".join(cells) + " |")
    p("\n#### Time / DFAOIT: measured (pass sums; frame ms) / predicted\n")
    rr = ratio_rows(fr)
    p("| variant | mean over scenes | " + " | ".join(scenes) + " |")
    p("|---|---|" + "---|" * len(scenes))
    for v in VARIANT_ORDER:
        if v not in rr:
            continue
        vals = rr[v]
        mean = [np.mean([x[i] for x in vals.values()]) for i in range(3)]
        cells = [f"{vals[sc][0]:.2f}; {vals[sc][1]:.2f} / {vals[sc][2]:.2f}" if sc in vals else "" for sc in scenes]
        p(f"| {v} | {mean[0]:.2f}; {mean[1]:.2f} / {mean[2]:.2f} | " + " | ".join(cells) + " |")
    p("")
    return coef, obs, fr


TERMS = {  # name -> (feature of an observation, unit) for the diagnostic models
    "fragment": (lambda o: o["x"][0], "ns a fragment"),
    "narrow": (lambda o: o["x"][1], "ns a narrow byte"),
    "wide": (lambda o: o["x"][2], "ns a wide byte"),
    "fullscreen": (lambda o: o["x"][3], "ns a full-screen pixel"),
    "target": (lambda o: o["x"][4],
               "ns a byte of the pass's targets a pixel (clears)"),
    "primitive": (lambda o: o["primitives"] * 1e-6 if o["kind"] == "geometry" else 0.0, "ns a primitive"),
    "pass": (lambda o: 1e-6 if o["kind"] == "geometry" else 0.0, "a geometry pass (printed in ms)"),
}


def diagnostic(obs, terms):
    A = np.array([[TERMS[t][0](o) for t in terms] for o in obs])
    m = np.array([o["ms"] for o in obs])
    coef = nonneg_lstsq(A / m[:, None], np.ones_like(m))
    pred = A @ coef
    fr = {}
    for o, pr in zip(obs, pred):
        f = fr.setdefault((o["scene"], o["variant"]), [0.0, 0.0])
        f[0] += o["ms"]
        f[1] += pr
    geo = np.array([abs(pr / o["ms"] - 1) for o, pr in zip(obs, pred) if o["kind"] == "geometry"])
    fe = np.array([abs(p / mm - 1) for mm, p in fr.values()])
    re = np.array([abs((p / fr[(sc, "dfaoit")][1]) / (mm / fr[(sc, "dfaoit")][0]) - 1)
                   for (sc, v), (mm, p) in fr.items() if v != "dfaoit" and (sc, "dfaoit") in fr])
    return coef, geo, fe, re


def diagnostics(sets, out):
    """sets: [(label of the fragment counts, observations)]."""
    p = lambda *a: print(*a, file=out)
    p("#### Diagnostics: which fragment counts, which terms (H200; absolute relative errors, mean (max))\n")
    p("| fragment counts | terms | coefficients (ns) | geometry passes | frames (vs pass sums) | time / DFAOIT |")
    p("|---|---|---|---|---|---|")
    base = ["fragment", "narrow", "wide", "fullscreen"]
    for label, ob in sets:
        for terms in [base, base + ["pass"], base + ["target"], base + ["primitive"]]:
            coef, geo, fe, re = diagnostic(ob, terms)
            extra = ", ".join(terms[4:]) or "the model"
            cs = ", ".join(f"{t} {c * 1e-6:.3g} ms" if t == "pass" else f"{t} {c:.3g}" for t, c in zip(terms, coef))
            p(f"| {label} | {'the model' if not terms[4:] else 'model + ' + extra} | {cs} | "
              f"{100 * geo.mean():.0f} % ({100 * geo.max():.0f} %) | {100 * fe.mean():.0f} % ({100 * fe.max():.0f} %) | "
              f"{100 * re.mean():.0f} % ({100 * re.max():.0f} %) |")
    p("")


def compact(fits, out):
    """fits: {gpu name: (coef, obs, fr)} -> per (variant, pass) and per variant tables, the GPUs side by side."""
    p = lambda *a: print(*a, file=out)
    names = list(fits)
    p("#### Per pass, over the scenes: mean absolute error (most negative .. most positive)\n")
    p("| variant | pass | " + " | ".join(names) + " |")
    p("|---|---|" + "---|" * len(names))
    for v in VARIANT_ORDER:
        obs0 = fits[names[0]][1]
        for n in sorted({o["pass"] for o in obs0 if o["variant"] == v}, key=lambda n: (by_kind(obs0, n), n)):
            cells = []
            for g in names:
                coef, obs, _ = fits[g]
                e = [rel(predict(o, coef), o["ms"]) for o in obs if o["variant"] == v and o["pass"] == n]
                cells.append(f"{100 * np.mean(np.abs(e)):.0f} % ({pct(min(e))} .. {pct(max(e))})" if e else "")
            p(f"| {v} | {n} | " + " | ".join(cells) + " |")
    p("\n#### Per variant, over the scenes: frame (sum of passes) error, mean absolute (range); time / DFAOIT, "
      "measured (pass sums) / predicted, mean over scenes (worst scene's error)\n")
    p("| variant | " + " | ".join(f"{g} frame | {g} time / DFAOIT" for g in names) + " |")
    p("|---|" + "---|---|" * len(names))
    for v in VARIANT_ORDER:
        cells = []
        for g in names:
            _, _, fr = fits[g]
            fe = [rel(f["pred"], f["pass_sum"]) for (sc, vv), f in fr.items() if vv == v]
            rr = ratio_rows(fr).get(v, {})
            worst = max((rel(x[2], x[0]) for x in rr.values()), key=abs, default=0.0)
            cells.append(f"{100 * np.mean(np.abs(fe)):.0f} % ({pct(min(fe))} .. {pct(max(fe))})")
            cells.append(f"{np.mean([x[0] for x in rr.values()]):.2f} / {np.mean([x[2] for x in rr.values()]):.2f} ({pct(worst)})")
        p(f"| {v} | " + " | ".join(cells) + " |")
    p("")


def by_kind(obs, name):
    return 0 if any(o["pass"] == name and o["kind"] == "geometry" for o in obs) else 1


def counts_table(counts, out):
    p = lambda *a: print(*a, file=out)
    p("#### llvmpipe counts: fragments a frame (millions) and bytes a fragment writes, narrow + wide, per geometry pass\n")
    scenes = [sc for sc in SCENE_ORDER if any(k[0] == sc for k in counts)]
    p("| variant | pass | bytes (narrow + wide) | " + " | ".join(scenes) + " |")
    p("|---|---|---|" + "---|" * len(scenes))
    for v in VARIANT_ORDER:
        names = sorted({n for (sc, vv), c in counts.items() if vv == v for n, r in c.items() if r["kind"] == "geometry"})
        for n in names:
            rows = [counts.get((sc, v), {}).get(n) for sc in scenes]
            r0 = next(r for r in rows if r)
            cells = [f"{float(r['fragments']) / 1e6:.2f}" if r else "" for r in rows]
            p(f"| {v} | {n} | {float(r0['narrow_bytes']):g} + {float(r0['wide_bytes']):g} | " + " | ".join(cells) + " |")
    p("")


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    sub = ap.add_subparsers(dest="cmd", required=True)
    c = sub.add_parser("collect", help="llvmpipe renders -> counts CSV (appends; skips (scene, variant) already there)")
    c.add_argument("--starnt", required=True)
    c.add_argument("--scenes-dir", required=True)
    c.add_argument("--out", required=True)
    c.add_argument("--work", default="/tmp/fit_gpu_estimate")
    c.add_argument("--scenes", default="")
    c.add_argument("--variants", default="")
    c.add_argument("--frames", type=int, default=4)
    c.add_argument("--frames-for", default="", help="per-scene frames, e.g. hairball=2")
    c.add_argument("--warmup", type=int, default=1)
    c.add_argument("--threads", type=int, default=2)
    c.add_argument("--reuse", action="store_true", help="read a stats JSON already in --work instead of rendering again")
    f = sub.add_parser("fit", help="fit and print markdown tables")
    f.add_argument("--counts", default=os.path.join(RESULTS, "gpu_estimate_fit_counts.csv"))
    a = ap.parse_args()
    if a.cmd == "collect":
        a.frames_for = {k: int(v) for k, v in (kv.split("=") for kv in a.frames_for.split(",") if kv)}
        collect(a)
        return
    counts = read_counts(a.counts)
    counts_table(counts, sys.stdout)
    count_check(counts, "gpu_h200_1080p", sys.stdout)
    fits = {name: report(name, read_gpu(globs), counts, name == "H200", sys.stdout) for name, globs in GPU_RUNS.items()}
    compact(fits, sys.stdout)
    gpu = read_gpu(GPU_RUNS["H200"])
    obs, _ = observations(gpu, counts)
    inv, _ = observations(gpu, read_counts(a.counts, "fragment_invocations"))
    diagnostics([("llvmpipe samples_passed", obs), ("llvmpipe fragment_invocations", inv),
                 ("GPU's (bench reports)", with_gpu_counts(obs, read_gpu_report_counts("gpu_h200_1080p")))], sys.stdout)


if __name__ == "__main__":
    main()
