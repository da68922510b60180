#!/usr/bin/env bash
# Renders every scene of samples/scenes/ with shadow_render: one still (color.png and the
# rest of shadow_render's outputs) and a short animation (24 frames, 0.125 s apart, as
# frames/color_<k>.png) per scene.
#
#   bash samples/scenes/render_all.sh OUTDIR [SIZE]
#
# SIZE is WxH (default 480x270). Writes OUTDIR/<scene>/ (the still) and OUTDIR/<scene>/anim/
# (the animation). The program is $SHADOW_RENDER if set, else build/bin/shadow_render of this
# repository. Exits non-zero on the first scene that fails to render.
set -euo pipefail

if [[ $# -lt 1 || $# -gt 2 ]]; then
    echo "usage: $0 OUTDIR [SIZE]" >&2
    exit 2
fi
out=$1
size=${2:-480x270}
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
render=${SHADOW_RENDER:-$here/../../build/bin/shadow_render}
if [[ ! -x $render ]]; then
    echo "$0: no shadow_render at $render (build first, or set SHADOW_RENDER)" >&2
    exit 2
fi

shopt -s nullglob
scenes=("$here"/*.gltf)
if [[ ${#scenes[@]} -eq 0 ]]; then
    echo "$0: no scenes in $here (run python3 $here/generate.py)" >&2
    exit 2
fi

for scene in "${scenes[@]}"; do
    name=$(basename "$scene" .gltf)
    echo "== $name"
    "$render" "$scene" --out "$out/$name" --size "$size" --aov color
    "$render" "$scene" --out "$out/$name/anim" --size "$size" --aov color \
        --frames 24 --dt 0.125 --frame-images
done
echo "wrote $out/<scene>/color.png and $out/<scene>/anim/frames/ for ${#scenes[@]} scenes"
