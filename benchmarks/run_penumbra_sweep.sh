#!/usr/bin/env bash
# Frame time against penumbra width: builtin:plates with the disk light's radius set so that the
# high plate's penumbra spans 2-64 texels of its map, with PCSS, the textbook PCSS, VSSM, VSM,
# MSM-soft and the distance-field march (sdf)
# (build/bin/penumbra_sweep, interleaved rounds). Writes benchmarks/results/penumbra_sweep.md and
# its section of BENCHMARKS.md.
#   bash benchmarks/run_penumbra_sweep.sh        (ROUNDS=5 FRAMES=5 to override)
set -euo pipefail
cd "$(dirname "$0")/.."
bash .ci/setup >/dev/null
results=benchmarks/results
mkdir -p "$results"
{
  ./build/bin/penumbra_sweep --size 320x240 --rounds "${ROUNDS:-5}" --frames "${FRAMES:-5}"
  cat <<'MD'

PCSS spends taps where the penumbra is (one tap per texel of its disk's area, up to
`pcfSamples`, none where the min/max pyramid shows the region lit or in umbra); VSM reads one
mip level of the moments for its fixed `pcfRadius`; VSSM reads two squares (search cone and
penumbra) of its summed-area table, 16 fetches each whatever the width, and a third where the
search found a penumbra under half its cone (the search again over the narrower cone); MSM-soft
one trilinear fetch of its four-moment mip chain for the search (two where it searches again)
and four for the penumbra. The moment
techniques pay for their chain every time the layer is redrawn (here every frame: caching off):
a mip chain of the moments (RG32F, RGBA32F for four moments; a full-screen draw per level from
level 1 up, the first from the depth map, which the lookups gather as level 0) or VSSM's table (RGBA32F, one level, a compute pass
along the rows and one along the columns). That is most of
their frame at a 2048² map on this CPU rasteriser, and it does not depend on the width (VSM's
frame, whose filter is fixed, varies as much from run to run). `sdf` draws no caster into its
map and marches from every pixel through the plates' fields: the same steps at every emitter
size, since a step is the distance to the nearest caster, not a tap of a filter region (the
first of the widest cones' rays sample both plates where the narrow ones sample one).

```sh
bash benchmarks/run_penumbra_sweep.sh
```
MD
} > "$results/penumbra_sweep.md.tmp"
mv "$results/penumbra_sweep.md.tmp" "$results/penumbra_sweep.md"
cat "$results/penumbra_sweep.md"
python3 benchmarks/benchmarks_section.py penumbra-sweep "Frame time against penumbra width" "$results/penumbra_sweep.md"
