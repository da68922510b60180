#!/usr/bin/env bash
# The shadow techniques on real third-party glTF assets: the .glb models under examples/ of a
# local git snapshot of the raylib repository (an animated robot with 14 clips, a skinned
# character and its props, a car, a logo). Nothing is fetched from the network and nothing is
# copied into this repository: each model is read out of the snapshot with git into a temporary
# folder and wrapped there by benchmarks/real_assets.py (a ground quad 4x the model's size just
# below it, a directional PCSS sun 45 degrees from vertical with a 0.02 rad emitter, a camera
# framing the model and its shadow; all placed relative to the model's bounds, whatever its
# scale). Then, per asset, the ray-traced truth once (shadow_reference) and every technique in
# turn (shadow_render --technique, at the same animation time: the middle of one clip), each
# compared with the truth over the sun's lit mask (shadow_compare --mask lit_0.exr).
# Prints a Markdown table (RMSE, penumbra RMSE, light in the umbra, false shadow, shadow-pass and
# main-pass median ms) and the results that look wrong, and writes it as the "Real assets"
# section of BENCHMARKS.md. Results (images, error maps, JSON) go to the work folder.
#
#   bash benchmarks/run_real_assets.sh [RAYLIB_GIT_DIR [WORK_DIR]]
#
# RAYLIB_GIT_DIR (or RAYLIB_GIT): a bare git directory of the raylib repository; default, the
# first /work/.mirror/*raylib* (or its repo/ folder) that is one. Absent: the run is skipped
# with a message, exit code 0. WORK_DIR (or WORK): default out/real_assets. Overrides: SIZE
# (320x240), SAMPLES (64 rays per pixel), FRAMES (5: one warm-up, 4 timed, maps redrawn every
# frame), TECHNIQUES ("hard pcf pcss vsm vssm msm-soft sdf", those the build offers), SCREEN_VISIBILITY
# (auto, as the CLIs; off/full/half/quarter: --screen-visibility), GROUND_CASTS=1 makes the ground
# cast (so that it is in the shadow maps: the moment techniques' check, docs/tuning.md; implies
# WRITE_BENCHMARKS=0), KEEP_SCENES=1 keeps the wrapped scenes (printed path), WRITE_BENCHMARKS=0
# leaves BENCHMARKS.md alone. Builds the three programs only when one is missing.
set -euo pipefail
cd "$(dirname "$0")/.."

source samples/find_snapshot.sh
given=${1:-${RAYLIB_GIT:-}}
if ! raylib_git=$(find_snapshot raylib "$given"); then
  echo "run_real_assets: skipped: no git directory of the raylib repository" \
    "(${given:-none found under /work/.mirror/}); give it as the first argument or RAYLIB_GIT"
  exit 0
fi
work=${2:-${WORK:-out/real_assets}}
size=${SIZE:-320x240}
# The ground casts: a check, not the table BENCHMARKS.md describes (its ground does not cast).
ground_casts=()
if [ "${GROUND_CASTS:-0}" = 1 ]; then
  ground_casts=(--ground-casts)
  WRITE_BENCHMARKS=0
fi
samples=${SAMPLES:-64}
frames=${FRAMES:-5}
wanted=${TECHNIQUES:-hard pcf pcss vsm vssm msm-soft sdf}
screen=${SCREEN_VISIBILITY:-auto}

bin=build/bin
if [ ! -x $bin/shadow_render ] || [ ! -x $bin/shadow_reference ] || [ ! -x $bin/shadow_compare ]; then
  SHADOW_BUILD_TARGETS="shadow_render shadow_reference shadow_compare" bash .ci/setup >/dev/null
fi
# The techniques the build offers, in the order asked for.
offered=$($bin/shadow_render --help | sed -n 's/.*override every shadowed light: //p' | tr -d ',')
techniques=()
for t in $wanted; do
  if [[ " $offered " == *" $t "* ]]; then techniques+=("$t"); else echo "run_real_assets: $t: not offered by this build"; fi
done
[ ${#techniques[@]} -gt 0 ] || { echo "run_real_assets: no technique to run" >&2; exit 2; }

scenes=$(mktemp -d)
if [ "${KEEP_SCENES:-0}" = 1 ]; then
  echo "run_real_assets: wrapped scenes kept in $scenes"
else
  trap 'rm -rf "$scenes"' EXIT
fi
# The work folder is emptied: only one this script made (its marker file), or a new or empty one.
if [ -d "$work" ] && [ -n "$(ls -A "$work")" ] && [ ! -f "$work/.real_assets" ]; then
  echo "run_real_assets: $work: not empty and not a work folder of this script; give a new one" >&2
  exit 2
fi
rm -rf "$work"
mkdir -p "$work"
touch "$work/.real_assets"
commit=$(git --git-dir="$raylib_git" rev-parse HEAD)
start=$SECONDS

# The .glb files under examples/, one per distinct blob (the robot is there twice), named by
# their file name (with the parent folder's when two differ only in folder).
assets=()
declare -A seen_blob=() seen_name=()
while read -r _ type blob path; do
  [ "$type" = blob ] || continue
  [ -z "${seen_blob[$blob]:-}" ] || { echo "run_real_assets: $path: the same file as ${seen_blob[$blob]}"; continue; }
  seen_blob[$blob]=$path
  name=$(basename "$path" .glb)
  [ -z "${seen_name[$name]:-}" ] || name=$(basename "$(dirname "$path")")_$name
  seen_name[$name]=1
  assets+=("$name")
  mkdir -p "$work/$name" "$scenes/$name"
  echo "$path" > "$work/$name/source"
  git --git-dir="$raylib_git" cat-file blob "$blob" > "$scenes/$name/source.glb"
done < <(git --git-dir="$raylib_git" ls-tree -r HEAD -- examples | grep -i '\.glb$' || true)
[ ${#assets[@]} -gt 0 ] || { echo "run_real_assets: no .glb under examples/ at $commit" >&2; exit 2; }

for name in "${assets[@]}"; do
  dir=$work/$name
  scene=$scenes/$name/scene.gltf
  printf '%s\n' "${techniques[@]}" > "$dir/techniques"
  code=0
  python3 benchmarks/real_assets.py wrap "$scenes/$name/source.glb" "$scene" "${ground_casts[@]}" \
    > "$dir/info.json" 2> "$dir/wrap.log" || code=$?
  if [ $code -ne 0 ]; then
    verdict=failed
    [ $code -eq 3 ] && verdict=skipped
    echo "$verdict: $(tail -n 1 "$dir/wrap.log")" > "$dir/status"
    echo "run_real_assets: $name: $(cat "$dir/status")"
    continue
  fi
  time=$(python3 -c 'import json, sys; print(json.load(open(sys.argv[1]))["time"])' "$dir/info.json")
  echo "run_real_assets: $name (time $time s)"
  if ! $bin/shadow_reference "$scene" --size "$size" --samples "$samples" --time "$time" \
      --out "$dir/reference" > "$dir/reference.log" 2>&1; then
    echo "failed: shadow_reference: $(grep -v '^\s*$' "$dir/reference.log" | tail -n 1)" > "$dir/status"
    echo "run_real_assets: $name: $(cat "$dir/status")"
    continue
  fi
  echo ok > "$dir/status"
  for technique in "${techniques[@]}"; do
    # Frames at one time (--dt 0), every map redrawn every frame: the timings of a moving scene.
    if ! $bin/shadow_render "$scene" --technique "$technique" --size "$size" --time "$time" --frames "$frames" \
        --dt 0 --no-cache --aov color,visibility,position --screen-visibility "$screen" --out "$dir/$technique" \
        > "$dir/$technique.log" 2>&1; then
      echo "run_real_assets: $name / $technique: shadow_render failed: $(tail -n 1 "$dir/$technique.log")"
      continue
    fi
    if ! $bin/shadow_compare "$dir/$technique" "$dir/reference" --mask "$dir/reference/lit_0.exr" \
        --out "$dir/$technique" > "$dir/$technique.json.tmp" 2>> "$dir/$technique.log"; then
      echo "run_real_assets: $name / $technique: shadow_compare failed: $(tail -n 1 "$dir/$technique.log")"
      continue
    fi
    mv "$dir/$technique.json.tmp" "$dir/$technique.json"
  done
done

python3 benchmarks/real_assets.py table "$work" "${assets[@]}" > "$work/table.md"
elapsed=$((SECONDS - start))
renderer=$(python3 - "$work" <<'PY'
import glob, json, sys
names = [json.load(open(p)).get("renderer", "") for p in sorted(glob.glob(f"{sys.argv[1]}/*/*/stats.json"))]
print(names[0] if names else "unknown")
PY
)
{
  cat <<MD
The techniques on third-party models: every \`.glb\` under \`examples/\` of the raylib repository
(commit \`${commit:0:12}\`), each wrapped by \`benchmarks/real_assets.py\` into a scene of its own
nodes, a ground quad 4x its size just below its bounds (receives, does not cast), one directional
sun 45 degrees from vertical (\`extras.shadow\`: \`pcss\`, 2048² map, \`angularRadius\` 0.02 rad;
every other setting at the engine's defaults, whose lengths follow the scene) and a camera
framing the model and its shadow, all placed relative to the model's bounds (their largest edge
is its size). Animated models keep one clip (the engine plays every clip of a file at once) and
are taken at its middle. Per technique \`shadow_render --technique T --size $size --frames $frames
--dt 0 --no-cache\` (the maps redrawn every frame; ms: median shadow-pass and main-pass time of
the frames after the first, renderer \`$renderer\`), against \`shadow_reference
--samples $samples\` at the same time, over the sun's lit mask (\`shadow_compare --mask
lit_0.exr\`). Umbra leak: pixels of the true umbra above 0.5; false shadow: lit pixels below 0.5
(both as in the Light in the umbra section). Bounds: the posed model's box, in the file's units.
\`sdf\` draws no map (its march is in the main pass), except for skinned casters, which it casts
through the light's map (\`CasterWithoutField\`).
The whole run took ${elapsed} s here.

\`\`\`sh
bash benchmarks/run_real_assets.sh /path/to/raylib.git
\`\`\`

MD
  cat "$work/table.md"
  echo
  echo "Sources (raylib \`examples/\`), clip and time:"
  echo
  for name in "${assets[@]}"; do
    python3 - "$work/$name" "$name" <<'PY'
import json, os, sys
base, name = sys.argv[1], sys.argv[2]
source = open(os.path.join(base, "source")).read().strip()
line = f"- {name}: `{source}`"
if os.path.exists(os.path.join(base, "status")) and open(os.path.join(base, "status")).read().strip() == "ok":
    info = json.load(open(os.path.join(base, "info.json")))
    if info["clip"]:
        line += f", clip `{info['clip']}` of {len(info['clips'])}, t = {info['time']:.3f} s"
print(line)
PY
  done
} > "$work/section.md"
cat "$work/section.md"
if [ "${WRITE_BENCHMARKS:-1}" = 1 ]; then
  python3 benchmarks/benchmarks_section.py real-assets "Real assets" "$work/section.md"
  echo "run_real_assets: wrote BENCHMARKS.md (section Real assets) and $work/ in ${elapsed} s"
else
  echo "run_real_assets: wrote $work/ in ${elapsed} s (BENCHMARKS.md left alone: WRITE_BENCHMARKS=0)"
fi
