#!/usr/bin/env bash
# The README's technique gallery: one scene (default `contact`, its light 0) under each technique
# beside the ray-traced truth, with each technique's signed-error heat map against it.
#
#   bash samples/scenes/technique_gallery.sh [OUTDIR] [SCENE] [SIZE]
#
# Writes OUTDIR (default samples/images): gallery_truth.png (the truth's visibility, grey),
# gallery_<technique>.png (the render) and gallery_<technique>_error.png (blue: too dark, red: too
# light, white: exact), and prints each technique's RMSE and penumbra RMSE of light 0. Programs
# from build/bin (run .ci/setup first).
set -euo pipefail
cd "$(dirname "$0")/../.."
out=${1:-samples/images}
scene=${2:-contact}
size=${3:-320x180}
bin=build/bin
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
mkdir -p "$out"

"$bin/shadow_reference" "$scene" --size "$size" --samples 256 --out "$work/truth" >/dev/null
cp "$work/truth/visibility_0.png" "$out/gallery_truth.png"
printf '| technique | RMSE | penumbra RMSE |\n|---|---:|---:|\n'
for t in hard pcf pcss vssm msm-soft sdf; do
  "$bin/shadow_render" "$scene" --technique "$t" --size "$size" --aov color,visibility,position \
    --out "$work/$t" >/dev/null
  "$bin/shadow_compare" "$work/$t" "$work/truth" --out "$work/$t" > "$work/$t/compare.json"
  cp "$work/$t/color.png" "$out/gallery_$t.png"
  cp "$work/$t/error_0.png" "$out/gallery_${t}_error.png"
  python3 - "$work/$t/compare.json" "$t" <<'PY'
import json, sys
light = next(l for l in json.load(open(sys.argv[1]))["lights"] if l["index"] == 0)
print(f"| `{sys.argv[2]}` | {light['rmse']:.4f} | {light['penumbraRmse']:.4f} |")
PY
done
