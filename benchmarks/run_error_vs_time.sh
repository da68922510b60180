#!/usr/bin/env bash
# Error against time for every technique on three scenes, and BENCHMARKS.md from the results.
#   bash benchmarks/run_error_vs_time.sh [--quick]
# Sets up and builds (.ci/setup), traces the references with shadow_reference (Embree), runs the
# sweep (build/bin/error_vs_time), plots with gnuplot, and rewrites its section of BENCHMARKS.md. --quick uses
# fewer reference samples and timed frames (for a smoke run; the committed figures are full).
set -euo pipefail
cd "$(dirname "$0")/.."
bash .ci/setup >/dev/null

size=320x240
samples=1024
frames=5
if [ "${1:-}" = "--quick" ]; then samples=64; frames=1; fi
results=benchmarks/results
refs=$results/tmp/references
mkdir -p "$refs" "$results/tmp"
for scene in plates bunny default; do
  ./build/bin/shadow_reference "builtin:$scene" --out "$refs/$scene" --size "$size" --samples "$samples"
done
./build/bin/error_vs_time --scenes builtin:plates,builtin:bunny,builtin:default --references "$refs" \
  --out "$results" --size "$size" --frames "$frames"
(cd "$results" && gnuplot error_vs_time.gp)

{
  cat <<'MD'
Every shadow technique and setting, on three scenes — `builtin:plates` (a disk light over two
square plates: the scene whose visibility has a closed form), `builtin:bunny` (the Stanford
bunny from Debian's glmark2-data on a plane under a PCSS sun, a PCF spot and a hard point
light) and `builtin:default` (the animated default scene at t = 0, three lights) — against the
ray-traced truth of `shadow_reference` (Embree, stratified samples over each light's emitter).
Error is the visibility error, pooled over the scene's lights, over the pixels where each
light shades the surface (the reference's `lit_<i>.exr`: the surface faces the light, inside a
spot's cone and the light's range); elsewhere visibility × shading is 0 and never reaches the
image. The penumbra RMSE counts only pixels whose true visibility is strictly between 0 and 1.
Timings on llvmpipe (a CPU rasteriser) are noisy from run to run; compare rows of one run. One
configuration sets every shadowed light of the scene. `pcss-textbook` is the seeds' PCSS (fixed
Poisson taps around the receiver's UV), kept so our PCSS is measured against it in the same run.
`vsm` is the variance shadow map (one trilinear fetch of prefiltered depth moments over the light's
`pcfRadius`, Chebyshev's bound, `bleed` its lightBleedReduction): a fixed-width filter like PCF.
`vssm` reads two squares of its summed-area table of the moments (exact integer sums), the
blocker search cone (average blocker depth from the region's mean and Chebyshev's lit fraction)
and the penumbra by similar triangles: PCSS's contact hardening for the same 16 fetches per
square whatever the width. `msm` is the hard-edged moment shadow map (four moments, the
Hamburger bound over one texel), `msm-soft` VSSM's blocker search and penumbra on the mip chain
of four moments (one fetch for the search, four for the penumbra) with the four-moment bound
over it. The moment techniques' shadow column includes their chain, built every frame here
(caching off): VSM's and MSM-soft's from level 1 (their lookups take level 0 from a gather of
the depth map, as hard-edged MSM takes its one texel: it keeps no chain), or from VSM's first
level read (log2 of `pcfRadius` in the layer's largest receiver texel), drawn from the depth
map, up to VSM's last level read (a cascade's two levels); VSSM's table by two compute passes
along rows (two per gather) and columns, none for a layer without casters. Rows `... midpoint` are
second-depth maps (`depthMode` midpoint: each layer drawn twice, the mean of the first two
surfaces stored) with zero constant and slope bias; rows `sdf fieldN stepsM` the distance-field
march through fields of N voxels along the edge (`ShadowLimits::distanceFieldVoxels` = N³) at M
steps, which draws no map (its shadow column is 0; its fields are baked once, before the timed
frames). Rows ending `screen-full`, `screen-half` and `screen-quarter` run the same setting
through the renderer's screen-space visibility stage (`--screen-visibility`): the visibility
computed over the screen at that resolution, upsampled along surfaces and refined at full
resolution where the samples disagree; their main column includes the stage's surface pass
and full-screen lit pass, and their error is the upsample's as well as the technique's.
Every configuration of a scene draws the same depth layers, so no technique's frame can be shorter
than the scene's fastest frame of all configurations (a hard shadow from the smallest map): the
last column, textbook time over that frame, bounds the speed-up any filter could show.

Reproduce (2-7 minutes here after the build, with the machine's load: `time bash benchmarks/run_error_vs_time.sh`; rewrites this section and `benchmarks/results/`):

```sh
bash benchmarks/run_error_vs_time.sh
```

![error against time](benchmarks/results/error_vs_time.png)

Data: `benchmarks/results/error_vs_time.csv` and `.json`.

MD
  cat "$results/error_vs_time.md"
} > "$results/tmp/error_vs_time_section.md"
python3 benchmarks/benchmarks_section.py error-vs-time "Error against time" "$results/tmp/error_vs_time_section.md"
echo "wrote BENCHMARKS.md and $results/"
