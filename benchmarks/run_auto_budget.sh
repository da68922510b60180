#!/usr/bin/env bash
# Technique auto against PCSS at its defaults, on a few scenes at 320x240 (llvmpipe):
#   bash benchmarks/run_auto_budget.sh [SCENE...]   (default: plates bunny plates-boxes)
# Per scene: the ray-traced truth (shadow_reference), PCSS at its defaults, then --technique auto
# with the budget equal to PCSS's measured frame time (its shadow passes + main passes, median)
# and with half of it. Every run redraws its layers every frame (--no-cache) and times 39 frames
# after a warm-up one (40 frames at 30 per second: the calibration settles and the 1 s hold passes). Prints one line per run: frame ms, each auto light's choice, predicted and
# measured shadow-pass ms, and the visibility RMSE of every light's receiver pixels pooled against the truth
# (shadow_compare's allLights).
# Uses build/bin; results in benchmarks/results/tmp/auto.
set -euo pipefail
cd "$(dirname "$0")/.."
bin=build/bin
out=benchmarks/results/tmp/auto
size=320x240
scenes=("$@")
[ ${#scenes[@]} -gt 0 ] || scenes=(plates bunny plates-boxes)
mkdir -p "$out"
summary() {  # run dir, truth dir
  python3 - "$1" "$2" "$bin" <<'PY'
import json, subprocess, sys
run, truth, b = sys.argv[1:4]
s = json.load(open(run + "/stats.json"))
t = s["timingsMs"]
frame = t["shadowPassesTotal"]["median"] + t["mainPassesTotal"]["median"]
cmp = json.loads(subprocess.run([b + "/shadow_compare", run, truth], check=True, capture_output=True, text=True).stdout)
rmse = cmp["allLights"]["rmse"]
choices = []
for l in s["lights"]:
    a = l.get("auto")
    if a:
        choices.append(f'{l["node"]}:{a["technique"]}{a["mapSize"]}/{a["blockerSamples"]} '
                       f'pred {a["predictedMs"]:.2f} (pass {a["predictedShadowPassMs"]:.2f}, meas {a["measuredShadowPassMs"]:.2f})')
print(f"frame {frame:.2f} ms  shadow {t['shadowPassesTotal']['median']:.2f}  main {t['mainPassesTotal']['median']:.2f}  "
      f"rmse {rmse:.4f}  " + "; ".join(choices))
print(f"FRAME {frame:.4f}", file=sys.stderr)
PY
}
for scene in "${scenes[@]}"; do
  ref="$out/$scene/ref"
  [ -f "$ref/reference.json" ] || "$bin/shadow_reference" "builtin:$scene" --out "$ref" --size "$size" --samples 256 >/dev/null
  common=(--size "$size" --frames 40 --no-cache --aov visibility,position)
  "$bin/shadow_render" "builtin:$scene" "${common[@]}" --technique pcss --out "$out/$scene/pcss" 2>/dev/null
  echo "$scene pcss default: $(summary "$out/$scene/pcss" "$ref" 2>"$out/$scene/frame.txt")"
  budget=$(awk '{print $2}' "$out/$scene/frame.txt")
  for share in 1 0.5; do
    b=$(python3 -c "print($budget * $share)")
    "$bin/shadow_render" "builtin:$scene" "${common[@]}" --technique auto --shadow-budget-ms "$b" \
      --out "$out/$scene/auto$share" 2>/dev/null
    echo "$scene auto budget ${b} ms: $(summary "$out/$scene/auto$share" "$ref" 2>/dev/null)"
  done
done
