#!/usr/bin/env python3
"""Helper of benchmarks/run_screen_visibility.sh: the Markdown section (stdout) and
benchmarks/results/screen_visibility.json from the runs in WORK.

    python3 benchmarks/screen_visibility.py WORK ROUNDS FRAMES SAMPLES SECONDS

WORK/time/<scene>_<technique|own>_<mode>_r<k>/stats.json: timed runs; a run's time is the
median over its frames after the first of shadowMs + mainMs; a configuration's time the median
of its rounds. WORK/error/<scene>_<technique>_<mode>.json: shadow_compare against the truth.
"""
import glob
import json
import os
import statistics
import sys

MODES = ["off", "auto", "full", "half", "quarter"]
SPOT_SCENES = ["bunny-spot", "bunny-spot-wide"]
SPOT_TECHNIQUES = ["hard", "pcf", "pcss", "vssm", "msm-soft", "sdf"]
SAMPLE_SCENES = ["courtyard", "contact", "character", "fence", "sunfield"]


def run_time(stats, main_only=False):
    frames = stats["perFrame"][1:] or stats["perFrame"]
    return statistics.median(f["mainMs"] + (0.0 if main_only else f["shadowMs"]) for f in frames)


def timing(work, scene, technique, mode, main_only=False):
    """Median over rounds, and whether the stage ran (its surface pass was timed)."""
    times, staged = [], False
    for path in sorted(glob.glob(f"{work}/time/{scene}_{technique}_{mode}_r*/stats.json")):
        stats = json.load(open(path))
        times.append(run_time(stats, main_only))
        staged = staged or "Main/Surfaces" in stats["timingsMs"]["passes"]
    if not times:
        return None, staged, None
    return statistics.median(times), staged, stats.get("renderer", "")


def error(work, scene, technique, mode):
    path = f"{work}/error/{scene}_{technique}_{mode}.json"
    if not os.path.exists(path) or os.path.getsize(path) == 0:
        return None
    light = json.load(open(path))["lights"][0]
    return {"rmse": light["rmse"], "penumbraRmse": light["penumbraRmse"]}


def main():
    if len(sys.argv) != 6:
        print(__doc__, file=sys.stderr)
        return 2
    work, rounds, frames, samples, seconds = sys.argv[1:6]
    data = {"spot": [], "samples": []}
    renderer = ""
    for scene in SPOT_SCENES:
        for t in SPOT_TECHNIQUES:
            row = {"scene": scene, "technique": t, "ms": {}, "staged": {}, "error": {}}
            for m in MODES:
                ms, staged, r = timing(work, scene, t, m)
                renderer = renderer or r or ""
                row["ms"][m] = ms
                row["staged"][m] = staged
                row["error"][m] = error(work, scene, t, m)
            data["spot"].append(row)
    for scene in SAMPLE_SCENES:
        row = {"scene": scene, "ms": {}, "staged": {}}
        for m in ["off", "auto"]:
            ms, staged, r = timing(work, scene, "own", m)
            row["ms"][m] = ms
            row["staged"][m] = staged
        data["samples"].append(row)
    data["renderer"] = renderer
    json.dump(data, open("benchmarks/results/screen_visibility.json", "w"), indent=1)

    def ms(v):
        return "—" if v is None else f"{v:.1f}"

    def ratio(v, base):
        return "—" if v is None or not base else f"{v / base:.2f}"

    def err(e):
        return "—" if e is None else f"{e['rmse']:.4f}"

    out = []
    out.append(
        "The renderer's screen-space visibility stage (`--screen-visibility`, `RenderOptions::screenVisibility`) "
        "against its forward passes (`off`), measured in one run. `auto` is what the CLIs run by default: the "
        "stage (filtered shadows at half resolution, at quarter from 720 rows) for a `pcss` or `sdf` light, two "
        "or more filtered lights or contact shadows, in images of 360 rows or more, and for any filtered light "
        "from 720 rows; forward otherwise (the table marks where it ran the "
        "stage with *s*; where it did not, auto and forward ran the same passes, and their ratio shows the run's "
        "noise). `full`, `half`, `quarter` force the stage at that resolution for every light. Time: 1280x720, every map redrawn each frame (`--no-cache`), median over "
        f"{int(frames) - 1} frames of shadow + main passes, median of {rounds} interleaved rounds; ratio = the "
        "mode's time over forward's (below 1: faster). Error: RMSE of the light's visibility against "
        f"`shadow_reference --samples {samples}` at 1280x720 (the timed size) over its lit mask (`shadow_compare --mask "
        "lit_0.exr`), one frame after a warm-up. Renderer "
        f"`{renderer}`; the whole run took {seconds} s."
    )
    out.append("")
    out.append("```sh\nbash benchmarks/run_screen_visibility.sh\n```")
    out.append("")
    out.append("| scene | technique | forward ms | auto ms (ratio) | full ms (ratio) | half ms (ratio) | quarter ms (ratio) "
               "| RMSE forward | auto | full | half | quarter |")
    out.append("|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|")
    for row in data["spot"]:
        base = row["ms"]["off"]
        cells = [row["scene"], row["technique"], ms(base)]
        for m in ["auto", "full", "half", "quarter"]:
            mark = " *s*" if m == "auto" and row["staged"][m] else ""
            cells.append(f"{ms(row['ms'][m])}{mark} ({ratio(row['ms'][m], base)})")
        cells += [err(row["error"][m]) for m in MODES]
        out.append("| " + " | ".join(cells) + " |")
    out.append("")
    ratios = []
    for scene in SPOT_SCENES:
        sdf, _, _ = timing(work, scene, "sdf", "auto", main_only=True)
        pcss, _, _ = timing(work, scene, "pcss", "off", main_only=True)
        if sdf and pcss:
            ratios.append(f"{scene} {sdf:.1f} / {pcss:.1f} ms = {sdf / pcss:.2f}x")
    if ratios:
        out.append("Main pass alone, `sdf` under `auto` against PCSS forward (median of the rounds): " +
                   "; ".join(ratios) + ".")
        out.append("")
    out.append("The sample scenes with their own lights and techniques (1280x720, same run):")
    out.append("")
    out.append("| scene | forward ms | auto ms | auto / forward |")
    out.append("|---|---:|---:|---:|")
    for row in data["samples"]:
        mark = " *s*" if row["staged"]["auto"] else ""
        out.append(f"| {row['scene']} | {ms(row['ms']['off'])} | {ms(row['ms']['auto'])}{mark} | "
                   f"{ratio(row['ms']['auto'], row['ms']['off'])} |")
    # The sample scene with a truth at the timed size: `contact`, each shadowed light over its lit
    # mask (its unshadowed fill light is lit by design where the truth has shadow).
    contact = {}
    for m in ("off", "auto"):
        path = os.path.join(work, "error", f"contact_{m}.json")
        stats = os.path.join(work, "error", f"contact_{m}", "stats.json")
        if os.path.exists(path) and os.path.exists(stats):
            with open(stats) as f:
                names = {l["index"]: l["node"] for l in json.load(f)["lights"] if l["technique"] != "none"}
            with open(path) as f:
                contact[m] = {names[l["index"]]: l["rmse"] for l in json.load(f)["lights"] if l["index"] in names}
    if len(contact) == 2:
        cells = "; ".join(f"{name}: {contact['off'][name]:.4f} forward, {contact['auto'][name]:.4f} auto"
                          for name in contact["off"])
        out.append("")
        out.append(f"`contact` against the truth at 1280x720, each shadowed light over its lit mask "
                   f"(`shadow_compare --mask lit`): {cells}.")
    print("\n".join(out))
    return 0


if __name__ == "__main__":
    sys.exit(main())
