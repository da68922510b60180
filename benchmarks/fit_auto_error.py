#!/usr/bin/env python3
"""Fits technique auto's error model (engine/src/shadow/auto_technique.cpp) and states the fit's error.

    python3 benchmarks/fit_auto_error.py --auto-work DIR [--fit plates,bunny,default]
    python3 benchmarks/fit_auto_error.py --auto-work DIR --settle
    python3 benchmarks/fit_auto_error.py --auto-work DIR --counts [--fit plates,bunny,default]
    python3 benchmarks/fit_auto_error.py [--bin build/bin] [--csv benchmarks/results/error_vs_time.csv]

With --auto-work: the per-light rows of benchmarks/auto_budget.py's runs (DIR/<scene>/results.json:
every light of every fixed configuration, its RMSE over its own lit mask, and its inputs as the
planner saw them); the scenes named by --fit are fitted, the others only predicted (the check on
scenes the model did not see). Without it, the older pooled fit to the error-against-time sweep:

With --counts: the model of each light's edge counts (engine/src/shadow/auto_technique.cpp,
countedRmse): the share of its pixels within one texel of a shadow edge in a 1024-texel map and the
share in its penumbra beyond it, as the lit passes counted them while auto ran it (its inputs in
results.json); seven constants, printed in the order of the C++ file.

Each light's penumbra width (texels of a 1024 map) and screen pixels come from the planner itself:
`shadow_render builtin:SCENE --technique auto` reports them in stats.json (lights.auto). The sweep
pools every light of a scene, so the model's prediction is pooled the same way: the pixel-weighted
mean of the lights' squared RMSE. Parameters are fitted by minimising the RMS of
log(predicted / measured) over the sweep's hard, PCF (16 taps, Vogel) and PCSS (Vogel) rows.
Prints the constants for auto_technique.cpp and the per-row and overall fit error.
"""
import argparse
import csv
import glob
import json
import math
import os
import statistics
import subprocess
import sys
import tempfile

SCENES = ["plates", "bunny", "default"]
EDGE = 0.2887  # a unit step against a linear ramp
NAMES = ["kHardBlur", "kPcfBlur", "kPcssTaps", "kPcssTexel", "kPenumbraShare", "kPenumbraShareFloor", "kOtherError",
         "kEdgeBand"]


def features(binary, scene, size):
    with tempfile.TemporaryDirectory() as out:
        subprocess.run([binary, "builtin:" + scene, "--size", size, "--technique", "auto", "--frames", "2",
                        "--out", out, "--aov", "color"], check=True, capture_output=True)
        stats = json.load(open(out + "/stats.json"))
    return [(l["auto"]["penumbraTexels1024"], l["auto"]["pixels"]) for l in stats["lights"] if "auto" in l]


def light_rmse(p, technique, size, taps, w1024):
    """A light's predicted RMSE in one candidate, from its widest penumbra's width."""
    hard_blur, pcf_blur, pcss_taps, pcss_texel, share_k, share_floor, other = p[:7]
    band = p[7] if len(p) > 7 else 0.0
    # The map's own step: every edge is drawn within `band` texels of the candidate's map, so a
    # penumbra narrower than that (a point-sized light's: 0) still leaves that much edge to err.
    w1024 = w1024 + band * 1024.0 / size
    w = w1024 * size / 1024.0
    hard = EDGE * w / (w + hard_blur)
    if technique == "hard":
        pen = hard
    elif technique == "pcf":
        pen = EDGE * w / (w + pcf_blur)
    else:
        # Never more than hard's at the same map: with no penumbra to estimate, PCSS filters over
        # its narrowest kernel, the edge hard shadows have.
        pen = min(EDGE, math.hypot(pcss_taps / taps, pcss_texel / max(w, 1e-3)), hard)
    share = min(1.0, share_k * w1024 / 1024.0 + share_floor)
    return math.sqrt(share * pen * pen + other * other)


def pooled(p, row, lights):
    total = sum(px for _, px in lights)
    mse = sum(px * light_rmse(p, row["technique"], row["size"], row["taps"], w) ** 2 for w, px in lights)
    return math.sqrt(mse / total)


def loss(p, rows, feats):
    if min(p) <= 0:
        return 1e9
    errs = [math.log(pooled(p, r, feats[r["scene"]]) / r["rmse"]) for r in rows]
    return math.sqrt(sum(e * e for e in errs) / len(errs))


def nelder_mead(f, x0, steps=4000):
    """Minimises f over log-parameters (all parameters are positive)."""
    g = lambda y: f([math.exp(v) for v in y])
    n = len(x0)
    simplex = [[math.log(v) for v in x0]]
    for i in range(n):
        y = list(simplex[0])
        y[i] += 0.5
        simplex.append(y)
    values = [g(y) for y in simplex]
    for _ in range(steps):
        order = sorted(range(n + 1), key=lambda i: values[i])
        simplex = [simplex[i] for i in order]
        values = [values[i] for i in order]
        centroid = [sum(simplex[i][k] for i in range(n)) / n for k in range(n)]
        reflect = [c + (c - w) for c, w in zip(centroid, simplex[-1])]
        fr = g(reflect)
        if fr < values[0]:
            expand = [c + 2 * (c - w) for c, w in zip(centroid, simplex[-1])]
            fe = g(expand)
            simplex[-1], values[-1] = (expand, fe) if fe < fr else (reflect, fr)
        elif fr < values[-2]:
            simplex[-1], values[-1] = reflect, fr
        else:
            contract = [c + 0.5 * (w - c) for c, w in zip(centroid, simplex[-1])]
            fc = g(contract)
            if fc < values[-1]:
                simplex[-1], values[-1] = contract, fc
            else:
                simplex = [simplex[0]] + [[b + 0.5 * (y - b) for b, y in zip(simplex[0], s)] for s in simplex[1:]]
                values = [values[0]] + [g(y) for y in simplex[1:]]
    best = min(range(n + 1), key=lambda i: values[i])
    return [math.exp(v) for v in simplex[best]]


def sweep_rows(path):
    rows = []
    for r in csv.DictReader(open(path)):
        c = r["config"]
        if r["scene"] not in SCENES or any(k in c for k in ("midpoint", "screen", "r0.05", "poisson")):
            continue
        if r["technique"] == "hard" or (r["technique"] == "pcf" and "taps16 " in c) or r["technique"] == "pcss":
            rows.append({"scene": r["scene"], "config": c, "technique": r["technique"], "size": int(r["mapSize"]),
                         "taps": int(r["blockerSamples"]), "rmse": float(r["rmse"])})
    return rows


OTHER = 0.007252  # kOtherError, the width model's floor, kept by the counts' model


def counted_rmse(p, technique, size, taps, edge, penumbra):
    """countedRmse of auto_technique.cpp: the band within one texel of an edge and the penumbra
    beyond it, each times the squared error within it."""
    band_error = {"hard": p[0], "pcf": p[1], "pcss": p[2]}[technique]
    if technique == "pcss":
        within = p[5] * (16.0 / max(taps, 1)) ** p[6]
    else:
        within = p[3] if technique == "hard" else p[4]
    band = min(1.0, edge * 1024.0 / size)
    return math.sqrt(min(1.0, band_error * band + within * min(1.0, penumbra)) + OTHER * OTHER)


def predict(p, r):
    if r["edge"] is not None:
        return counted_rmse(p, r["technique"], r["size"], r["taps"], r["edge"], r["penumbra"])
    return light_rmse(p, r["technique"], r["size"], r["taps"], r["w"])


def light_rows(work, scenes, counts=False):
    """Per-light rows of auto_budget.py's fixed configurations, for the scenes given; with
    `counts`, each light's counted shares as auto measured them (its inputs)."""
    rows = []
    for scene in scenes:
        path = os.path.join(work, scene, "results.json")
        if not os.path.exists(path):
            sys.exit(f"fit_auto_error: {path}: missing (run benchmarks/auto_budget.py first)")
        r = json.load(open(path))
        for name, (technique, size, _pcf, blocker) in r["fixed"].items():
            measured = r["runs"][name]["lightRmse"]
            for index, inp in r["inputs"].items():
                if index in measured and measured[index] > 0:
                    rows.append({"scene": scene, "config": f"{name} {inp['node']}", "technique": technique,
                                 "size": size, "taps": blocker, "rmse": measured[index],
                                 "w": inp["penumbraTexels1024"], "edge": inp.get("edgeShare1024") if counts else None,
                                 "penumbra": inp.get("penumbraShare")})
                    if counts and not (rows[-1]["edge"] is not None and rows[-1]["edge"] >= 0
                                       and rows[-1]["penumbra"] is not None and rows[-1]["penumbra"] >= 0):
                        sys.exit(f"fit_auto_error: {path}: no edge counts for {inp['node']} (rerun the benchmark)")
    return rows


def light_loss(p, rows):
    if min(p) <= 0:
        return 1e9
    errs = [math.log(predict(p, r) / r["rmse"]) for r in rows]
    return math.sqrt(sum(e * e for e in errs) / len(errs))


def concordance(p, rows):
    """Share of the pairs of one light's candidates, measured more than 5 % apart, whose predicted
    order is the measured one: what the chooser relies on."""
    by_light = {}
    for r in rows:
        by_light.setdefault((r["scene"], r["config"].split(" ", 2)[-1]), []).append(
            (predict(p, r), r["rmse"]))
    same = total = 0
    for values in by_light.values():
        for i, (p1, m1) in enumerate(values):
            for p2, m2 in values[i + 1:]:
                if abs(m1 - m2) >= 0.05 * max(m1, m2):
                    total += 1
                    same += (p1 - p2) * (m1 - m2) > 0
    return f"{same} of {total} ({same / max(total, 1):.0%})"


def fit_lights(a):
    scenes = sorted({d for d in os.listdir(a.auto_work) if os.path.exists(os.path.join(a.auto_work, d, "results.json"))})
    fitted = a.fit.split(",")
    rows = light_rows(a.auto_work, [s for s in scenes if s in fitted], a.counts)
    held = light_rows(a.auto_work, [s for s in scenes if s not in fitted], a.counts)
    start = [0.05, 0.08, 0.05, 0.06, 0.02, 4e-4, 3.0] if a.counts else [1.0, 3.2, 0.6, 2.8, 0.84, 0.01, 0.007, 1.0]
    p = a.constants or nelder_mead(lambda q: light_loss(q, rows), start, steps=8000)
    if a.counts:
        print(f"constexpr std::array<double, 3> kBandError{{{p[0]:.4g}, {p[1]:.4g}, {p[2]:.4g}}};  // hard, PCF, PCSS")
        print(f"constexpr std::array<double, 2> kPenumbraError{{{p[3]:.4g}, {p[4]:.4g}}};  // hard, PCF")
        print(f"constexpr double kPcssPenumbra16 = {p[5]:.4g};\nconstexpr double kPcssPenumbraPower = {p[6]:.4g};")
    else:
        for name, value in zip(NAMES, p):
            print(f"constexpr double {name} = {value:.4g};")
    print("\n| scene | config, light | measured RMSE | predicted | ratio |\n|---|---|---:|---:|---:|")
    for r in rows + held:
        pr = predict(p, r)
        print(f"| {r['scene']} | {r['config']} | {r['rmse']:.4f} | {pr:.4f} | {pr / r['rmse']:.2f} |")
    print(f"\nfit error: RMS of log(predicted / measured) = {light_loss(p, rows):.3f} over {len(rows)} rows of "
          f"{', '.join(s for s in scenes if s in fitted)}")
    print(f"within each light, pairs of candidates measured more than 5 % apart that the model orders the same "
          f"way: {concordance(p, rows + held)}")
    if held:
        within = sum(abs(predict(p, r) / r["rmse"] - 1) <= 0.3 for r in held)
        print(f"scenes not fitted ({', '.join(s for s in scenes if s not in fitted)}): RMS of log = "
              f"{light_loss(p, held):.3f} over {len(held)} rows, {within} of them within 30 %")


def lookup_costs(work):
    """The cost model's lit-pass defaults from auto_budget.py's fixed runs: per family, the lit pass's
    growth over the run without shadows per pixel a light reaches (median over the scenes), then
    the per-tap cost from PCSS's two tap counts and each family's per-pixel rest; and the lit pass
    without shadows as screen pixels x (perScreenPixel + shaded lights x perShadedPixel) +
    triangles drawn x perLitTriangle, least squares over the scenes' runs without shadows."""
    growth = {}
    base_rows = []
    for scene in sorted(os.listdir(work)):
        path = os.path.join(work, scene, "results.json")
        if not os.path.exists(path):
            continue
        r = json.load(open(path))
        pixels = sum(v["pixels"] for v in r["inputs"].values())
        stats = lambda key: json.load(open(os.path.join(work, scene, r["runs"][key]["folder"], "stats.json")))
        lit = lambda key: stats(key)["timingsMs"]["passes"]["Main/Lit"]["median"]
        base = lit("none")
        for name, (technique, _size, pcf, blocker) in r["fixed"].items():
            growth.setdefault((technique, pcf, blocker), []).append((lit(name) - base) / pixels * 1e6)
        none = stats("none")
        screen = none["size"][0] * none["size"][1]
        base_rows.append((scene, screen, len(none["lights"]), none["counters"].get("mainTriangles", 0), base))
    med = {k: statistics.median(v) for k, v in growth.items()}
    tap = (med[("pcss", 16, 16)] - med[("pcss", 8, 8)]) / 12.0
    print(f"ns per pixel a light reaches (median over {len(base_rows)} scenes):")
    for k, v in sorted(med.items()):
        print(f"  {' '.join(map(str, k))}: {v:.0f}")
    print(f"perTapMs = {tap * 1e-6:.3g}; perPixelMs = {{{(med[('hard', 1, 1)] - tap) * 1e-6:.3g}, "
          f"{(med[('pcf', 16, 16)] - 16 * tap) * 1e-6:.3g}, {(med[('pcss', 8, 8)] - 12 * tap) * 1e-6:.3g}}}")
    # The lit pass without shadows: normal equations of the three terms (ms).
    cols = [lambda row: row[1], lambda row: row[1] * row[2], lambda row: row[3]]
    n = [[sum(a(row) * b(row) for row in base_rows) for b in cols] for a in cols]
    y = [sum(a(row) * row[4] for row in base_rows) for a in cols]
    for k in range(3):
        for i in range(k + 1, 3):
            f = n[i][k] / n[k][k]
            n[i] = [n[i][j] - f * n[k][j] for j in range(3)]
            y[i] -= f * y[k]
    x = [0.0] * 3
    for k in reversed(range(3)):
        x[k] = (y[k] - sum(n[k][j] * x[j] for j in range(k + 1, 3))) / n[k][k]
    print(f"perScreenPixelMs = {x[0]:.3g}; perShadedPixelMs = {x[1]:.3g}; perLitTriangleMs = {x[2]:.3g}")
    for scene, screen, lights, triangles, base in base_rows:
        fitted = screen * (x[0] + lights * x[1]) + triangles * x[2]
        print(f"  {scene}: lit pass without shadows {base:.2f} ms, fitted {fitted:.2f} "
              f"({screen} pixels, {lights} lights, {triangles} triangles)")


def settle_frames(work):
    """How much slower than the steady state the frames after the programs' build run, over
    every fixed configuration of auto_budget.py's runs (what kAutoSettleFrames rests on)."""
    columns = [[] for _ in range(8)]
    for path in sorted(glob.glob(os.path.join(work, "*", "*", "stats.json"))):
        if os.path.basename(os.path.dirname(path)).startswith("auto"):
            continue
        frames = json.load(open(path))["perFrame"]
        if len(frames) < 20:
            continue
        steady = statistics.median(f["mainMs"] + f["shadowMs"] for f in frames[10:])
        for k in range(1, 9):
            columns[k - 1].append((frames[k]["mainMs"] + frames[k]["shadowMs"]) / steady)
    for k, ratios in enumerate(columns, 1):
        if ratios:
            print(f"frame {k} after the build: median {statistics.median(ratios):.3f}, mean "
                  f"{statistics.mean(ratios):.3f} of the steady frame ({len(ratios)} runs)")


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--settle", action="store_true",
                    help="with --auto-work: the frames after the programs' build against the steady frame")
    ap.add_argument("--lookup-costs", action="store_true",
                    help="with --auto-work: print the lit pass's cost defaults measured by its fixed runs")
    ap.add_argument("--auto-work", help="benchmarks/auto_budget.py's work folder: fit its per-light rows")
    ap.add_argument("--fit", default="plates,bunny,default", help="with --auto-work: the scenes fitted")
    ap.add_argument("--constants", type=lambda t: [float(v) for v in t.split(",")],
                    help="with --auto-work: evaluate these constants (eight, or seven with --counts, in the order printed) instead of fitting")
    ap.add_argument("--counts", action="store_true",
                    help="with --auto-work: the model of the lit passes' edge counts")
    ap.add_argument("--bin", default="build/bin")
    ap.add_argument("--csv", default="benchmarks/results/error_vs_time.csv")
    ap.add_argument("--size", default="320x240")
    a = ap.parse_args()
    if a.auto_work and a.settle:
        settle_frames(a.auto_work)
        return
    if a.auto_work and a.lookup_costs:
        lookup_costs(a.auto_work)
        return
    if a.auto_work:
        fit_lights(a)
        return
    feats = {s: features(a.bin + "/shadow_render", s, a.size) for s in SCENES}
    rows = sweep_rows(a.csv)
    p = nelder_mead(lambda q: loss(q, rows, feats), [1.0, 2.0, 0.6, 1.5, 1.0, 0.01, 0.005])
    for name, value in zip(NAMES, p):
        print(f"constexpr double {name} = {value:.4g};")
    print("\n| scene | config | measured RMSE | predicted | ratio |\n|---|---|---:|---:|---:|")
    for r in rows:
        pr = pooled(p, r, feats[r["scene"]])
        print(f"| {r['scene']} | {r['config']} | {r['rmse']:.4f} | {pr:.4f} | {pr / r['rmse']:.2f} |")
    print(f"\nfit error: RMS of log(predicted / measured) = {loss(p, rows, feats):.3f} over {len(rows)} rows")


if __name__ == "__main__":
    main()
