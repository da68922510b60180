#!/usr/bin/env bash
# Frame time against penumbra width: builtin:plates with the disk light's radius set so that the
# high plate's penumbra spans 2-64 texels of its map, with PCSS, the textbook PCSS, VSSM and VSM
# (build/bin/penumbra_sweep, interleaved rounds). Writes benchmarks/results/penumbra_sweep.md and
# its section of BENCHMARKS.md.
#   bash benchmarks/run_penumbra_sweep.sh        (ROUNDS=3 FRAMES=5 to override)
set -euo pipefail
cd "$(dirname "$0")/.."
bash .ci/setup >/dev/null
results=benchmarks/results
mkdir -p "$results"
{
  ./build/bin/penumbra_sweep --size 320x240 --rounds "${ROUNDS:-3}" --frames "${FRAMES:-5}"
  cat <<'MD'

PCSS spends taps where the penumbra is (one tap per texel of its disk's area, up to
`pcfSamples`, none where the min/max pyramid shows the region lit or in umbra); VSM reads one
mip level of the moments for its fixed `pcfRadius`, VSSM two (search cone and penumbra) whatever
the width, MSM-soft the same on four moments. The moment techniques pay for their moments chain,
a full-resolution mip chain (RG32F, RGBA32F for four moments) built by compute every time the
layer is redrawn (here every frame: caching off): that is most of their frame at a 2048² map on
this CPU rasteriser, and it does not depend on the width (VSM's frame, whose filter is fixed,
varies as much from run to run).

```sh
bash benchmarks/run_penumbra_sweep.sh
```
MD
} > "$results/penumbra_sweep.md.tmp"
mv "$results/penumbra_sweep.md.tmp" "$results/penumbra_sweep.md"
cat "$results/penumbra_sweep.md"
python3 benchmarks/benchmarks_section.py penumbra-sweep "Frame time against penumbra width" "$results/penumbra_sweep.md"
