#!/usr/bin/env python3
"""Technique auto against fixed configurations, per scene, in one run (llvmpipe or whatever GL runs).

    python3 benchmarks/auto_budget.py [--bin build/bin] [--work DIR] [--size 320x240] [--frames 40]
                                      [--samples 256] [--rounds 1] [--markdown FILE] SCENE...

SCENE: builtin:NAME, a sample scene's name or a glTF file (what shadow_render takes). Per scene:
- the ray-traced truth (shadow_reference) at the time of the last frame rendered;
- every run renders FRAMES frames 1/30 s apart with every layer redrawn each frame (--no-cache),
  forward lookups (--screen-visibility off: what auto's cost model describes); its frame time is
  the median shadow passes + the median main passes over the frames after the first, its shadow
  cost that minus the frame time of the same scene with every shadow off (--technique none);
- PCSS at the module's defaults (1024 texels, 16 + 16 taps) for every light: the budget B is its
  shadow cost, measured once before the rounds;
- each of auto's 12 candidates as a fixed configuration for every light;
- --technique auto at budget B and B/2, in the same rounds as the others.
Errors: every light's visibility over the truth's lit_<i>.exr, pooled (shadow_compare --mask lit).
With --rounds R every run is made R times, interleaved, and each figure is the median (auto's errors
and choices are those of its run of median frame time).
Prints a Markdown report (the checks of docs/auto_technique.md "Measured") and writes it to
--markdown when given.
"""
import argparse
import json
import math
import os
import statistics
import subprocess
import sys

DT = 1.0 / 30.0
CANDIDATES = [(t, m, p, b) for t, p, b in (("hard", 1, 1), ("pcf", 16, 16), ("pcss", 8, 8), ("pcss", 16, 16))
              for m in (512, 1024, 2048)]
PCSS_DEFAULT = ("pcss", 1024, 16, 16)


def label(c):
    t, m, p, b = c
    return {"hard": f"hard {m}", "pcf": f"PCF {m}/{p}"}.get(t, f"PCSS {m}/{b}+{p}")


class Scene:
    def __init__(self, args, spec):
        self.args, self.spec = args, spec
        self.name = spec.split(":")[-1].split("/")[-1].removesuffix(".gltf").removesuffix(".glb")
        self.dir = os.path.join(args.work, self.name)
        self.truth = os.path.join(self.dir, "truth")

    def reference(self):
        if os.path.exists(os.path.join(self.truth, "reference.json")):
            return
        t = (self.args.frames - 1) * DT
        subprocess.run([self.args.bin + "/shadow_reference", self.spec, "--out", self.truth, "--size", self.args.size,
                        "--samples", str(self.args.samples), "--time", f"{t:.9f}"], check=True,
                       stdout=subprocess.DEVNULL)

    def render(self, key, extra):
        out = os.path.join(self.dir, key)
        reuse = self.args.reuse_fixed and "auto" not in extra and os.path.exists(os.path.join(out, "stats.json"))
        if not reuse:
            subprocess.run([self.args.bin + "/shadow_render", self.spec, "--out", out, "--size", self.args.size,
                        "--frames", str(self.args.frames), "--dt", f"{DT:.9f}", "--no-cache",
                            "--screen-visibility", "off", "--aov", "visibility,position"] + extra,
                           check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        stats = json.load(open(os.path.join(out, "stats.json")))
        t = stats["timingsMs"]
        run = {"frame": t["shadowPassesTotal"]["median"] + t["mainPassesTotal"]["median"], "lights": stats["lights"],
               "renderer": stats.get("renderer", "?")}
        if extra[:2] != ["--technique", "none"]:
            cmp = subprocess.run([self.args.bin + "/shadow_compare", out, self.truth, "--mask", "lit"], check=True,
                                 capture_output=True, text=True).stdout
            cmp = json.loads(cmp)
            run["rmse"] = cmp["allLights"]["rmse"]
            run["lightRmse"] = {l["index"]: l["rmse"] for l in cmp["lights"]}
        return run


def folder(key):
    """The run folder of a run's label (results.json names it, for fit_auto_error.py)."""
    return key.replace(" ", "_").replace("/", "-").replace("+", "p")


def fixed_args(c):
    t, m, p, b = c
    return ["--technique", t, "--map-size", str(m), "--pcf-samples", str(p), "--blocker-samples", str(b)]


def median_runs(runs):
    """The run of median frame time among `runs` (the lower middle one of an even count), with the
    median frame time: a fixed configuration's errors are the same in every run, auto's belong to
    the choices of the run that stands for it."""
    out = dict(sorted(runs, key=lambda r: r["frame"])[(len(runs) - 1) // 2])
    out["frame"] = statistics.median(r["frame"] for r in runs)
    return out


def measure(scene, rounds):
    """Every run of the scene, round by round. Auto's two runs take their place in each round
    with the others, so that a drift of the machine's speed (2 shared cores here) falls on them
    as on the fixed configurations they are compared with; their budgets come from a first run
    of the defaults and of no shadows before the rounds (B, as auto is given it)."""
    scene.reference()
    keys = {"none": ["--technique", "none"], "pcss": fixed_args(PCSS_DEFAULT)}
    keys.update({label(c): fixed_args(c) for c in CANDIDATES})
    first = {k: scene.render(folder(k), keys[k]) for k in ("none", "pcss")}
    budget = first["pcss"]["frame"] - first["none"]["frame"]
    for share, key in ((1.0, "autoB"), (0.5, "autoHalf")):
        keys[key] = ["--technique", "auto", "--shadow-budget-ms", f"{budget * share:.4f}"]
    runs = {k: [] for k in keys}
    for _ in range(rounds):
        for k, extra in keys.items():
            runs[k].append(scene.render(folder(k), extra))
    res = {k: median_runs(v) for k, v in runs.items()}
    base = res["none"]["frame"]
    for r in res.values():
        r["cost"] = r["frame"] - base
    save(scene, res, budget)
    return res, budget


def save(scene, res, budget):
    """results.json in the scene's folder: what benchmarks/fit_auto_error.py --auto-work reads (each
    fixed configuration's per-light RMSE, each auto light's inputs)."""
    inputs = {l["index"]: {"node": l["node"], "penumbraTexels1024": l["auto"]["penumbraTexels1024"],
                           "edgeShare1024": l["auto"]["edgeShare1024"], "penumbraShare": l["auto"]["penumbraShare"],
                           "pixels": l["auto"]["pixels"]} for l in res["autoB"]["lights"] if "auto" in l}
    runs = {k: {"folder": folder(k), "frame": r["frame"], "cost": r["cost"], "rmse": r.get("rmse"),
                "lightRmse": r.get("lightRmse")} for k, r in res.items()}
    fixed = {label(c): list(c) for c in CANDIDATES}
    with open(os.path.join(scene.dir, "results.json"), "w") as f:
        json.dump({"scene": scene.name, "budget": budget, "inputs": inputs, "runs": runs, "fixed": fixed}, f, indent=1)


def auto_summary(run):
    predicted = sum(l["auto"]["predictedMs"] for l in run["lights"] if "auto" in l)
    choices = ", ".join(
        f'{l["node"]}: {label((l["auto"]["technique"], l["auto"]["mapSize"], l["auto"]["pcfSamples"], l["auto"]["blockerSamples"]))}'
        for l in run["lights"] if "auto" in l)
    return predicted, choices


def light_rows(scene, key, run):
    rows = []
    for l in run["lights"]:
        if "auto" not in l:
            continue
        a = l["auto"]
        measured = run["lightRmse"].get(l["index"])
        if measured is None:
            continue
        rows.append(f'| {scene.name} | {key} | {l["node"]} | {a["penumbraTexels1024"]:.1f} | '
                    f'{a["predictedShadowPassMs"]:.2f} / {a["measuredShadowPassMs"]:.2f} | '
                    f'{a["predictedRmse"]:.4f} / {measured:.4f} ({a["predictedRmse"] / max(measured, 1e-9):.2f}) |')
    return rows


def report(results, args, fitted):
    renderer = results[0][1][0]["pcss"]["renderer"] if results else "?"
    lines = [f"Renderer `{renderer}`. Size {args.size}, {args.frames} frames 1/30 s apart, every layer redrawn each frame, forward lookups; "
             f"{args.rounds} interleaved round(s), median. Cost = frame (shadow + main passes, median) minus the frame "
             "with every shadow off. B = PCSS's cost at the module's defaults (1024 texels, 16 + 16 taps), measured before the rounds (the budget auto is given); auto's runs are interleaved with the others in each round. "
             "RMSE: every light over the truth's lit mask, pooled (shadow_compare --mask lit), "
             f"truth shadow_reference --samples {args.samples} at the last frame's time.", "",
             "| scene | fitted on | PCSS default ms / RMSE | B ms | auto at B: cost (predicted) / RMSE | auto at B/2: cost "
             "(predicted) / RMSE | best fixed within B/2 | checks |",
             "|---|---|---|---|---|---|---|---|"]
    details = ["", "Each auto light's choice and predictions (last frame): penumbra width in texels of a 1024 map, "
               "its shadow passes predicted / measured (ms), its RMSE predicted / measured (ratio).", "",
               "| scene | run | light | width | shadow passes ms | RMSE |", "|---|---|---|---|---|---|"]
    choices = ["", "Choices:", ""]
    for scene, (res, budget) in results:
        pcss = res["pcss"]
        fits = [(r["rmse"], k, r) for k, r in res.items() if k in {label(c) for c in CANDIDATES} and r["cost"] <= budget / 2]
        best = min(fits, key=lambda x: x[0]) if fits else None
        cells, ok = [], []
        for key, b in (("autoB", budget), ("autoHalf", budget / 2)):
            r = res[key]
            pred, chosen = auto_summary(r)
            cells.append(f'{r["cost"]:.2f} ({pred:.2f}) / {r["rmse"]:.4f}')
            choices.append(f"- {scene.name}, {'B' if key == 'autoB' else 'B/2'}: {chosen}")
            ok.append(f"time {pred / max(r['cost'], 1e-9):.2f}x")
        ok.insert(0, "B: " + ("RMSE <= PCSS" if res["autoB"]["rmse"] <= pcss["rmse"] else "**RMSE > PCSS**"))
        half = res["autoHalf"]
        ok.insert(1, "B/2: " + ("within" if half["cost"] <= budget / 2 else "**over**") + (
            f", RMSE {half['rmse'] / best[0]:.2f}x best" if best else ", no fixed fits"))
        best_cell = f"{best[1]}: {best[2]['cost']:.2f} ms / {best[0]:.4f}" if best else "none"
        lines.append(f"| {scene.name} | {'yes' if scene.name in fitted else 'no'} | {pcss['frame']:.2f} / "
                     f"{pcss['rmse']:.4f} | {budget:.2f} | {cells[0]} | {cells[1]} | {best_cell} | {'; '.join(ok)} |")
        for key in ("autoB", "autoHalf"):
            details += light_rows(scene, "B" if key == "autoB" else "B/2", res[key])
    return "\n".join(lines + choices + details) + "\n"


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("scenes", nargs="+")
    ap.add_argument("--bin", default="build/bin")
    ap.add_argument("--work", default="benchmarks/results/tmp/auto")
    ap.add_argument("--size", default="320x240")
    ap.add_argument("--frames", type=int, default=40)
    ap.add_argument("--samples", type=int, default=256)
    ap.add_argument("--rounds", type=int, default=1)
    ap.add_argument("--markdown")
    ap.add_argument("--reuse-fixed", action="store_true",
                    help="keep the fixed configurations' runs already in --work (when only auto changed)")
    ap.add_argument("--fitted", default="plates,bunny,default", help="scenes the error model was fitted on")
    args = ap.parse_args()
    if args.frames < 2 or args.rounds < 1:
        sys.exit("auto_budget: --frames must be >= 2 and --rounds >= 1")
    results = []
    for spec in args.scenes:
        scene = Scene(args, spec)
        results.append((scene, measure(scene, args.rounds)))
        print(f"auto_budget: {scene.name} done", file=sys.stderr)
    text = report(results, args, set(args.fitted.split(",")))
    print(text)
    if args.markdown:
        with open(args.markdown, "w") as f:
            f.write(text)


if __name__ == "__main__":
    main()
