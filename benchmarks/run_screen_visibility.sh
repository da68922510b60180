#!/usr/bin/env bash
# The renderer's screen-space visibility stage against its forward passes, in one run: frame
# time at 1280x720 on the two bunny spot scenes (one technique at a time) and the five sample
# scenes (their own lights), and error against the ray-traced truth on the bunny spots at
# 1280x720, for `--screen-visibility off` (forward), `auto` (what the CLIs run by default) and the
# stage forced at full, half and quarter resolution.
#   bash benchmarks/run_screen_visibility.sh
# Times: ROUNDS interleaved rounds (every configuration once per round), each a shadow_render
# run of FRAMES frames with every map redrawn (--no-cache); a run's time is the median over its
# frames after the first of shadow + main passes (wall clock between fences on llvmpipe); the
# table gives the median of the rounds and the ratio to forward of the same scene in the same
# round set. Errors: shadow_reference --samples SAMPLES at the same size, shadow_compare over
# the light's lit mask. Writes benchmarks/results/screen_visibility.{md,json} and the section
# between <!-- screen-visibility:begin --> and <!-- screen-visibility:end --> of BENCHMARKS.md.
#
# Environment (quick runs; the committed figures use the defaults):
#   ROUNDS=3  FRAMES=6  SAMPLES=128  WRITE_BENCHMARKS=1 (0 leaves BENCHMARKS.md alone)
set -euo pipefail
cd "$(dirname "$0")/.."

rounds=${ROUNDS:-3}
frames=${FRAMES:-6}
samples=${SAMPLES:-128}
bin=build/bin
if [ ! -x $bin/shadow_render ] || [ ! -x $bin/shadow_reference ] || [ ! -x $bin/shadow_compare ]; then
  SHADOW_BUILD_TARGETS="shadow_render shadow_reference shadow_compare" bash .ci/setup >/dev/null
fi
work=benchmarks/results/tmp/screen_visibility
rm -rf "$work"
mkdir -p "$work"
start=$SECONDS

modes=(off auto full half quarter)
spot_scenes=(builtin:bunny-spot builtin:bunny-spot-wide)
spot_techniques=(hard pcf pcss vssm msm-soft sdf)
sample_scenes=(courtyard contact character fence sunfield)

# One timed run: scene, technique ("" = the scene's own), mode, round.
timed() {
  local scene=$1 technique=$2 mode=$3 round=$4
  local name=${scene#builtin:}_${technique:-own}_${mode}_r$round
  local args=("$scene" --size 1280x720 --frames "$frames" --no-cache --aov color --screen-visibility "$mode"
    --out "$work/time/$name")
  [ -n "$technique" ] && args+=(--technique "$technique")
  $bin/shadow_render "${args[@]}" > "$work/time/$name.log" 2>&1 \
    || { echo "screen_visibility: shadow_render ${args[*]} failed:" >&2; cat "$work/time/$name.log" >&2; exit 1; }
}

mkdir -p "$work/time"
for r in $(seq 1 "$rounds"); do
  echo "screen_visibility: round $r/$rounds"
  for scene in "${spot_scenes[@]}"; do
    for t in "${spot_techniques[@]}"; do
      for m in "${modes[@]}"; do timed "$scene" "$t" "$m" "$r"; done
    done
  done
  for scene in "${sample_scenes[@]}"; do
    for m in off auto; do timed "$scene" "" "$m" "$r"; done
  done
done

# Errors against the truth (one render each: the images do not depend on the round).
mkdir -p "$work/error"
for scene in "${spot_scenes[@]}"; do
  ref=$work/error/${scene#builtin:}_reference
  echo "screen_visibility: reference of $scene"
  $bin/shadow_reference "$scene" --size 1280x720 --samples "$samples" --out "$ref" > "$ref.log" 2>&1
  for t in "${spot_techniques[@]}"; do
    for m in "${modes[@]}"; do
      out=$work/error/${scene#builtin:}_${t}_$m
      $bin/shadow_render "$scene" --technique "$t" --size 1280x720 --frames 2 --screen-visibility "$m" \
        --aov color,visibility,position --out "$out" > "$out.log" 2>&1
      $bin/shadow_compare "$out" "$ref" --mask "$ref/lit_0.exr" --out "$out" > "$out.json"
    done
  done
done

# The sample scene with a truth, at the timed size, forward and auto.
ref=$work/error/contact_reference
echo "screen_visibility: reference of contact"
$bin/shadow_reference contact --size 1280x720 --samples "$samples" --out "$ref" > "$ref.log" 2>&1
for m in off auto; do
  out=$work/error/contact_$m
  $bin/shadow_render contact --size 1280x720 --frames 2 --screen-visibility "$m" --aov color,visibility,position \
    --out "$out" > "$out.log" 2>&1
  $bin/shadow_compare "$out" "$ref" --mask lit --out "$out" > "$out.json"
done

python3 benchmarks/screen_visibility.py "$work" "$rounds" "$frames" "$samples" $((SECONDS - start)) \
  > benchmarks/results/screen_visibility.md
cat benchmarks/results/screen_visibility.md
if [ "${WRITE_BENCHMARKS:-1}" = 1 ]; then
  python3 benchmarks/benchmarks_section.py screen-visibility "Screen-space visibility" \
    benchmarks/results/screen_visibility.md
  echo "screen_visibility: wrote BENCHMARKS.md and benchmarks/results/screen_visibility.{md,json}"
fi
