#!/usr/bin/env bash
# The game-facing screen-space mask (ShadowSystem::renderMask) at full, half and quarter
# resolution (ShadowMaskRequest::resolution), one light at a time: builtin:bunny-spot-wide's spot
# with PCF, PCSS and sdf at 1280x720 (benchmarks/mask_bench.cpp, Google Benchmark: wall clock of
# one renderMask and a glFinish). Writes benchmarks/results/mask.md and the section between
# <!-- mask:begin --> and <!-- mask:end --> of BENCHMARKS.md.
#   bash benchmarks/run_mask.sh
# Environment: REPETITIONS=3 (the table gives their median), WRITE_BENCHMARKS=1 (0 leaves
# BENCHMARKS.md alone).
set -euo pipefail
cd "$(dirname "$0")/.."

repetitions=${REPETITIONS:-3}
SHADOW_BUILD_TARGETS="mask_bench" bash .ci/setup >/dev/null
work=benchmarks/results/tmp/mask
mkdir -p "$work"
start=$SECONDS
build/bin/mask_bench --benchmark_repetitions="$repetitions" --benchmark_format=json \
  --benchmark_out="$work/mask.json" --benchmark_out_format=json >/dev/null

python3 - "$work/mask.json" "$repetitions" $((SECONDS - start)) > benchmarks/results/mask.md <<'PY'
import json, statistics, sys
path, repetitions, seconds = sys.argv[1], int(sys.argv[2]), int(sys.argv[3])
data = json.load(open(path))
names = {0: "full", 1: "half", 2: "quarter"}
runs = {}
for b in data["benchmarks"]:
    if b.get("run_type") != "iteration":
        continue
    args = dict(part.split(":") for part in b["run_name"].split("/")[1:3])
    key = (b["label"], names[int(args["resolution"])])
    runs.setdefault(key, []).append((b["real_time"], b.get("vsFull", 0.0)))
techniques = sorted({t for t, _ in runs}, key=["pcf", "pcss", "sdf"].index)
ctx = data["context"]
print("The game-facing mask (`ShadowSystem::renderMask`, `ShadowMaskRequest::resolution`) of "
      "`builtin:bunny-spot-wide`'s spot at 1280x720, one light, over the renderer's own depth: full "
      "resolution (every pixel runs the technique), half and quarter (one sample per 2x2 or 4x4 block, "
      "the resolve along surfaces, the refine of the pixels whose samples disagree). Time: one renderMask "
      f"and a glFinish, wall clock, median of {repetitions} repetitions (Google Benchmark, each at least "
      "1 s). Difference: the mean |mask - full-resolution mask| over the covered pixels. Renderer llvmpipe "
      f"on {ctx.get('num_cpus', '?')} CPUs; the run took {seconds} s.")
print()
print("```sh\nbash benchmarks/run_mask.sh\n```")
print()
print("| technique | full ms | half ms (ratio) | quarter ms (ratio) | difference half | difference quarter |")
print("|---|---:|---:|---:|---:|---:|")
for t in techniques:
    med = {r: statistics.median(v[0] for v in runs[(t, r)]) for r in names.values()}
    diff = {r: statistics.median(v[1] for v in runs[(t, r)]) for r in ("half", "quarter")}
    print(f"| {t} | {med['full']:.1f} | {med['half']:.1f} ({med['half'] / med['full']:.2f}) | "
          f"{med['quarter']:.1f} ({med['quarter'] / med['full']:.2f}) | {diff['half']:.4f} | {diff['quarter']:.4f} |")
PY
cat benchmarks/results/mask.md
if [ "${WRITE_BENCHMARKS:-1}" = 1 ]; then
  python3 benchmarks/benchmarks_section.py mask "The game-facing mask at reduced resolution" benchmarks/results/mask.md
  echo "run_mask: wrote BENCHMARKS.md and benchmarks/results/mask.md"
fi
