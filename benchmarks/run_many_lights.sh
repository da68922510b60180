#!/usr/bin/env bash
# Many lights: builtin:many-lights (a 40 m floor, 64 boxes, 64 shadowed spot and point lights of
# 4 m range) against builtin:many-lights-1 (the same scene with one of the lights), and the 64
# lights unshadowed (`--technique none`), at 1280x720, shadow maps cached as the engine does
# (static lights: drawn once). Interleaved rounds; writes benchmarks/results/many_lights.md and
# its section of BENCHMARKS.md.
#   bash benchmarks/run_many_lights.sh        (ROUNDS=3 FRAMES=20 to override)
set -euo pipefail
cd "$(dirname "$0")/.."
bash .ci/setup >/dev/null
rounds=${ROUNDS:-3}
frames=${FRAMES:-20}
results=benchmarks/results
work=$results/tmp/many_lights
mkdir -p "$work"
for round in $(seq 1 "$rounds"); do
  for scene in many-lights-1 many-lights; do
    ./build/bin/shadow_render "builtin:$scene" --out "$work/$scene-$round" --size 1280x720 \
      --frames $((frames + 1)) --aov color >/dev/null
  done
  ./build/bin/shadow_render builtin:many-lights --technique none --out "$work/many-lights-none-$round" \
    --size 1280x720 --frames $((frames + 1)) --aov color >/dev/null
done
python3 - "$work" "$rounds" "$frames" > "$results/many_lights.md" <<'PY'
import json, statistics, sys
work, rounds, frames = sys.argv[1], int(sys.argv[2]), int(sys.argv[3])
def frame_ms(scene):
    medians = []
    for r in range(1, rounds + 1):
        s = json.load(open(f"{work}/{scene}-{r}/stats.json"))
        t = s["timingsMs"]
        medians.append(t["shadowPassesTotal"]["median"] + t["mainPassesTotal"]["median"])
    return statistics.median(medians), min(medians), max(medians), s
one, one_lo, one_hi, s1 = frame_ms("many-lights-1")
many, many_lo, many_hi, s64 = frame_ms("many-lights")
none, none_lo, none_hi, s0 = frame_ms("many-lights-none")
print(f"Renderer `{s64['renderer']}` ({s64['timingMethod']}), 1280x720, {rounds} interleaved rounds of "
      f"{frames} frames after one warm-up frame; frame = shadow passes + main passes (median of the "
      f"frames, then of the rounds). Shadow maps of static lights are drawn once and reused.")
print()
print("| scene | lights | main passes | frame ms | rounds, lowest-highest |")
print("|---|---|---|---|---|")
print(f"| `builtin:many-lights-1` | 1 | {s1['counters']['mainPasses']} | {one:.1f} | {one_lo:.1f}-{one_hi:.1f} |")
print(f"| `builtin:many-lights` | 64 | {s64['counters']['mainPasses']} | {many:.1f} | {many_lo:.1f}-{many_hi:.1f} |")
print(f"| `builtin:many-lights --technique none` | 64, unshadowed | {s0['counters']['mainPasses']} | {none:.1f} "
      f"| {none_lo:.1f}-{none_hi:.1f} |")
print()
print(f"64 lights cost **{many / one:.2f}x** the frame of one light. Each light with a range gets a pass")
print("bounded by its reach (scissor to its sphere on screen, meshes outside the sphere not drawn), so a")
print("pixel pays for the lights that can reach it. The same 64 lights without shadows cost "
      f"**{none / many:.2f}x** the shadowed frame: an unshadowed light is packed, bounded and shaded like a")
print("shadowed one, without its map lookups.")
print()
print("```sh\nbash benchmarks/run_many_lights.sh\n```")
PY
cat "$results/many_lights.md"
python3 benchmarks/benchmarks_section.py many-lights "Many lights" "$results/many_lights.md"
