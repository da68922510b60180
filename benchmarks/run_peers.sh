#!/usr/bin/env bash
# Peer comparison against OpenSceneGraph on two scenes, `builtin:bunny-spot` (the Stanford bunny
# on an 8 m ground under one 2048^2-mapped spot light, a 0.08 m emitter) and
# `builtin:bunny-spot-wide` (the same with a 0.15 m emitter: penumbrae about twice as wide), both
# engines on llvmpipe.
#   bash benchmarks/run_peers.sh
# Installs what is missing (Debian: openscenegraph, xvfb, ...), builds the OSG program
# (benchmarks/peers, into build-peers/; never part of the main build) and ours (.ci/setup), then
# runs ROUNDS interleaved rounds of, per scene: OSG none/sm/vdsm/soft under Xvfb and ours
# none/hard/pcf/pcss/sdf headless (sdf, which OSG has no counterpart of, after the four pairs). Writes benchmarks/results/peers.md, a crop per scene
# (benchmarks/results/peers_crop.png, peers_crop_wide.png), and the section between
# <!-- peers:begin --> and <!-- peers:end --> of BENCHMARKS.md.
#
# Environment (for quick runs; the committed figures use the defaults):
#   ROUNDS=3        interleaved rounds; the table gives the median of the rounds' medians
#   FRAMES=30       timed frames per run (ours renders one more: its first frame is warm-up)
#   WARMUP=5        OSG warm-up frames (shader compilation, first uploads)
#   OSG_GRID=64     OSG ground grid (N x N quads): its lighting is per vertex, so the spot cone
#                   needs vertices (64: 12.5 cm apart, 8,192 triangles, an eighth of the bunny's);
#                   each of the 2 N^2 triangles costs OSG vertex work
#   SHADOW_RENDER=  our binary; when set, ours is not built (default: build/bin/shadow_render)
set -euo pipefail
cd "$(dirname "$0")/.."

rounds=${ROUNDS:-3}
frames=${FRAMES:-30}
warmup=${WARMUP:-5}
grid=${OSG_GRID:-64}
size=1280x720
# Scene names, and OSG soft's penumbra width for each (shadow-map units; in proportion to the
# emitter: 0.005 for 0.08 m).
scenes=(bunny-spot bunny-spot-wide)
osg_softness=(0.005 0.0094)
results=benchmarks/results
work=$results/tmp/peers
osg_modes=(none sm vdsm soft)
our_techniques=(none hard pcf pcss)
# Ours alone: no OSG mode of their kind (compared with vdsm in the table).
our_extra=(sdf)

as_root() {
  if [ "$(id -u)" -eq 0 ]; then "$@"; else sudo "$@"; fi
}

install_missing() {
  local missing=() p
  for p in "$@"; do dpkg -s "$p" >/dev/null 2>&1 || missing+=("$p"); done
  [ ${#missing[@]} -eq 0 ] && return 0
  echo "peers: installing ${missing[*]}"
  as_root apt-get update -qq
  # Through env: sudo would drop a variable set in front of it.
  as_root env DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
}

# libgl1-mesa-dri is llvmpipe for GLX; xauth is what xvfb-run needs besides Xvfb.
install_missing openscenegraph libopenscenegraph-dev xvfb xauth libgl1-mesa-dri \
  cmake g++ python3 glmark2-data

# The crop is drawn with PIL if python3 has it, else with ImageMagick. Some systems put a
# stand-in script named `convert` on PATH: only a binary that reports ImageMagick will do.
imagemagick=""
find_imagemagick() {
  local c
  for c in magick convert-im6.q16 /usr/bin/convert; do
    if command -v "$c" >/dev/null 2>&1 && "$c" -version 2>/dev/null | head -1 | grep -q 'ImageMagick'; then
      imagemagick=$(command -v "$c")
      return 0
    fi
  done
  return 1
}
if ! python3 -c 'import PIL' 2>/dev/null; then
  if ! find_imagemagick; then
    install_missing imagemagick
    find_imagemagick || { echo "peers: no working ImageMagick after installing it" >&2; exit 1; }
  fi
fi

# --- Build ---------------------------------------------------------------------------------------
if [ -n "${SHADOW_RENDER:-}" ]; then
  ours=$SHADOW_RENDER
else
  bash .ci/setup >/dev/null
  ours=build/bin/shadow_render
fi
[ -x "$ours" ] || { echo "peers: $ours is not an executable" >&2; exit 1; }
cmake -S benchmarks/peers -B build-peers -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build build-peers >/dev/null
osg=build-peers/osg_bunny

# --- Runs ----------------------------------------------------------------------------------------
rm -rf "$work"
mkdir -p "$work"
# llvmpipe for OSG too, whatever GL the X server offers.
export LIBGL_ALWAYS_SOFTWARE=1
# Both processes keep up to 512 MiB of freed heap (glibc's trim threshold), as shadow_render sets
# for itself (samples/cli_common.h, keepFreedHeap): llvmpipe allocates each draw's vertex buffers
# anew, and with glibc's default a frame of one pass gave them back to the kernel every frame.
export GLIBC_TUNABLES=glibc.malloc.trim_threshold=536870912

run_osg() {  # scene-index mode round
  local scene=${scenes[$1]}
  local out="$work/osg_${scene}_$2_r$3"
  # The image of the last round is kept for the crop.
  local png=()
  [ "$3" -eq "$rounds" ] && png=(--png "$work/osg_${scene}_$2.png")
  xvfb-run -a -s "-screen 0 ${size}x24" "$osg" "$2" --warmup "$warmup" --frames "$frames" \
    --size "$size" --grid "$grid" --softness "${osg_softness[$1]}" "${png[@]}" >"$out.json" 2>"$out.log" \
    || { echo "peers: osg_bunny $2 ($scene) failed:" >&2; cat "$out.log" >&2; exit 1; }
}

run_ours() {  # scene-index technique round
  local scene=${scenes[$1]}
  local out="$work/ours_${scene}_$2_r$3"
  "$ours" "builtin:$scene" --size "$size" --frames $((frames + 1)) --no-cache --technique "$2" --aov color \
    --out "$out" >"$out.log" 2>&1 \
    || { echo "peers: shadow_render builtin:$scene --technique $2 failed:" >&2; cat "$out.log" >&2; exit 1; }
  [ "$3" -eq "$rounds" ] && cp "$out/color.png" "$work/ours_${scene}_$2.png"
  return 0
}

start=$(date +%s)
for ((r = 1; r <= rounds; r++)); do
  # Interleaved, engine by engine within each mode, so a drift of the machine's load (2 shared
  # cores here) falls on both engines alike.
  for s in "${!scenes[@]}"; do
    for k in 0 1 2 3; do
      echo "peers: round $r/$rounds, ${scenes[s]}: OSG ${osg_modes[k]}, ours ${our_techniques[k]}"
      run_osg "$s" "${osg_modes[k]}" "$r"
      run_ours "$s" "${our_techniques[k]}" "$r"
    done
    for t in "${our_extra[@]}"; do
      echo "peers: round $r/$rounds, ${scenes[s]}: ours $t"
      run_ours "$s" "$t" "$r"
    done
  done
done
elapsed=$(($(date +%s) - start))

# --- Report --------------------------------------------------------------------------------------
cpu=$(grep -m1 'model name' /proc/cpuinfo | sed 's/.*: //')
cores=$(nproc)
# The command as run: overrides included, so a quick run is never taken for the full one.
command_line="bash benchmarks/run_peers.sh"
for v in ROUNDS FRAMES WARMUP OSG_GRID SHADOW_RENDER; do
  if [ -n "${!v:-}" ]; then command_line="$v=${!v} $command_line"; fi
done

python3 - "$work" "$rounds" "$frames" "$warmup" "$size" "$cpu" "$cores" "$elapsed" "$command_line" \
  "${scenes[*]}" "${osg_softness[*]}" <<'PY'
import json, os, statistics, sys

work, rounds, frames, warmup, size, cpu, cores, elapsed, command, scenes, softness = sys.argv[1:]
rounds, frames, warmup, cores, elapsed = int(rounds), int(frames), int(warmup), int(cores), int(elapsed)
scenes, softness = scenes.split(), softness.split()
osg_modes = ["none", "sm", "vdsm", "soft"]
ours_modes = ["none", "hard", "pcf", "pcss", "sdf"]
pairs = [("none", "none"), ("hard", "sm"), ("pcf", "vdsm"), ("pcss", "vdsm"), ("pcss", "soft"), ("sdf", "vdsm")]
emitter = {"bunny-spot": "0.08 m", "bunny-spot-wide": "0.15 m"}
crops = {"bunny-spot": "peers_crop.png", "bunny-spot-wide": "peers_crop_wide.png"}
med = statistics.median

def load(path):
    with open(path) as f:
        return json.load(f)

def spread(v):
    return f"{min(v):.1f}–{max(v):.1f}"

def measure(scene):
    """Per engine and mode: one figure per round, each the median over that run's timed frames."""
    osg, osg_draw, ours, ours_main, ours_wall = {}, {}, {}, {}, {}
    for m in osg_modes:
        runs = [load(f"{work}/osg_{scene}_{m}_r{r}.json") for r in range(1, rounds + 1)]
        osg[m] = [run["frameMs"]["median"] for run in runs]
        osg_draw[m] = [run["drawMs"]["median"] for run in runs]
    for t in ours_modes:
        runs = [load(f"{work}/ours_{scene}_{t}_r{r}/stats.json") for r in range(1, rounds + 1)]
        # stats.json holds no single per-frame total, but per frame the wall-clock time of the
        # shadow passes and of the main passes (each pass bracketed by glFinish): their sum, median
        # over the frames after the first (the warm-up frame stats.json also leaves out).
        ours[t] = [med(f["shadowMs"] + f["mainMs"] for f in run["perFrame"][1:]) for run in runs]
        ours_main[t] = [med(f["mainMs"] for f in run["perFrame"][1:]) for run in runs]
        # Cross-check, the whole frame: the medians of the CPU phases; the last (render submit)
        # spans every pass with its glFinish.
        cpu_ms = lambda run: sum(run["timingsMs"]["cpu"][k]["median"]
                                 for k in ("animate", "transforms", "shadowPrepare", "renderSubmit"))
        ours_wall[t] = [cpu_ms(run) for run in runs]
    return osg, osg_draw, ours, ours_main, ours_wall, runs[-1], load(f"{work}/osg_{scene}_none_r{rounds}.json")

plural = "s" if rounds > 1 else ""
out = []
results = {scene: measure(scene) for scene in scenes}
ours_info, osg_info = results[scenes[0]][5], results[scenes[0]][6]
out.append(f"Scenes `builtin:bunny-spot` and `builtin:bunny-spot-wide`: the Stanford bunny (glmark2-data, "
           f"{osg_info['bunny']['triangles']} triangles), 1.2 m tall on an 8 m ground, one spot light (cone 0.7 rad), "
           f"a 2048² shadow map drawn every frame, {size.replace('x', '×')} pixels, the same camera; the light's "
           "emitter is a disk of radius 0.08 m, or 0.15 m in the wide scene (penumbrae about twice as wide, so "
           f"more of the screen is penumbra). {rounds} round{plural}, each scene, engine and mode interleaved; a run "
           f"times {frames} frames (OSG after {warmup} warm-up frames, ours after 1) and gives its median; a cell is "
           "the median over the rounds.")
out.append("")
out.append(f"- **Ours**: `shadow_render --no-cache` (OSMesa, headless), `{ours_info['renderer']}`. Frame = the shadow "
           "passes plus the main passes of one frame, by wall clock, each pass bracketed by `glFinish` "
           "(`stats.json` has no single per-frame total). 'Main pass' is the main passes alone; the last column is "
           "the whole frame (the CPU phases' medians summed), as a check.")
out.append(f"- **{osg_info['engine']}**: `build-peers/osg_bunny` (benchmarks/peers), a {size.replace('x', '×')} "
           f"window under Xvfb, `{osg_info['renderer']}`, {osg_info['glVersion']}. Frame = `viewer.frame()` "
           "(event, update, cull, draw, swap) then `glFinish`; 'before swap' stops at a `glFinish` in the camera's "
           "final draw callback. Fixed-function lighting is per vertex, so the ground is a "
           f"{osg_info['ground']['triangles']}-triangle grid (ours: per pixel on a 512-triangle plane); it only "
           "receives shadows (as a caster it changes no pixel). `sm` and `soft` get ambient bias (0, 1), so "
           "shadowed means unlit as in ours (OSG's default (0.5, 0.5) leaves shadows half lit); `soft` is OSG's "
           "fixed-width jittered filter (up to 64 taps), its width in proportion to the emitter "
           f"({' and '.join(softness)} of the map); `sm` and `vdsm` have no emitter and compare with GL_LINEAR "
           "(2×2 hardware PCF). Our shading is Lambert + GGX per pixel; OSG's fixed-function Blinn-Phong. Our "
           "`sdf` (soft shadows marched through the bunny's distance field, no map) has no OSG counterpart: its row "
           "is set against `vdsm`, as PCF's and PCSS's are. `shadow_render`'s default screen-space visibility is "
           "`auto`: at 1280×720, `pcf`, `pcss` and `sdf` run the stage at quarter resolution, `hard` forward.")
out.append(f"- CPU: {cpu}, {cores} cores, shared with other work while measured: compare rows of one run. Both "
           "processes keep up to 512 MiB of freed heap (`GLIBC_TUNABLES=glibc.malloc.trim_threshold=536870912`, "
           "what shadow_render sets for itself): with glibc's default, llvmpipe's per-draw vertex buffers went "
           "back to the kernel every frame in which nothing else kept the heap's top in use.")
for scene in scenes:
    osg, osg_draw, ours, ours_main, ours_wall, _, _ = results[scene]
    out.append("")
    out.append(f"### `builtin:{scene}` (emitter radius {emitter.get(scene, '?')})")
    out.append("")
    out.append("| engine | mode | frame ms | rounds, lowest–highest | OSG: before swap ms | ours: main pass ms "
               "| ours: whole frame ms |")
    out.append("|---|---|---|---|---|---|---|")
    for m in osg_modes:
        out.append(f"| OSG | {m} | {med(osg[m]):.1f} | {spread(osg[m])} | {med(osg_draw[m]):.1f} | | |")
    for t in ours_modes:
        out.append(f"| ours | {t} | {med(ours[t]):.1f} | {spread(ours[t])} | | {med(ours_main[t]):.1f} "
                   f"| {med(ours_wall[t]):.1f} |")
    out.append("")
    out.append("| ours vs OSG | ours ms | OSG ms | ours / OSG |")
    out.append("|---|---|---|---|")
    for t, m in pairs:
        a, b = med(ours[t]), med(osg[m])
        out.append(f"| {t} vs {m} | {a:.1f} | {b:.1f} | {a / b:.2f} |")
    out.append("")
    out.append(f"Ours, main pass of `none` over `hard`'s: {med(ours_main['none']) / med(ours_main['hard']):.2f}.")
    out.append("")
    out.append(f"![OSG (top) and ours (bottom), crop of builtin:{scene}](CROPDIR{crops.get(scene, scene + '.png')})")
out.append("")
out.append("Crops: the same pixels around the bunny's shadow from each engine's last-round image: top row OSG "
           "`none`, `sm`, `vdsm`, `soft`; bottom row ours `none`, `hard`, `pcf`, `pcss`. Geometry, camera, cone, "
           "map size and which pixels are shadowed match; brightness does not, by design: OSG's light is "
           "fixed-function (per vertex, a hard cutoff with a cos^e falloff, no tone curve), ours physically based "
           "and tone-mapped.")
out.append("")
out.append(f"Runs took {elapsed} s (builds excluded). Reproduce (rewrites `benchmarks/results/peers.md`, "
           "the crops and this section):")
out.append("")
out.append("```sh")
out.append(command)
out.append("```")
body = "\n".join(out) + "\n"

with open("benchmarks/results/peers.md", "w") as f:
    f.write("# Peer comparison: OpenSceneGraph\n\n" + body.replace("CROPDIR", ""))
with open("benchmarks/results/tmp/peers_section.md", "w") as f:
    f.write(body.replace("CROPDIR", "benchmarks/results/"))

PY

# --- The crops: the same rectangle around the bunny's shadow from every image ---------------------
crop_x=440 crop_y=170 crop_w=520 crop_h=380
for scene in "${scenes[@]}"; do
  crop="$results/peers_crop.png"
  [ "$scene" = bunny-spot ] || crop="$results/peers_crop_${scene#bunny-spot-}.png"
  top=() bottom=()
  for m in "${osg_modes[@]}"; do top+=("$work/osg_${scene}_$m.png"); done
  for t in "${our_techniques[@]}"; do bottom+=("$work/ours_${scene}_$t.png"); done
  if [ -z "$imagemagick" ]; then
    python3 - "$crop_x" "$crop_y" "$crop_w" "$crop_h" "$crop" "${top[@]}" "${bottom[@]}" <<'PY'
import sys
from PIL import Image
x, y, w, h = map(int, sys.argv[1:5])
out, paths = sys.argv[5], sys.argv[6:]
gap = 4
sheet = Image.new("RGB", (4 * w + 3 * gap, 2 * h + gap), "white")
for i, p in enumerate(paths):
    tile = Image.open(p).convert("RGB").crop((x, y, x + w, y + h))
    sheet.paste(tile, ((i % 4) * (w + gap), (i // 4) * (h + gap)))
sheet.save(out)
PY
  else
    geometry="${crop_w}x${crop_h}+${crop_x}+${crop_y}"
    row() {  # out images...
      local out=$1
      shift
      "$imagemagick" "$@" -crop "$geometry" +repage -bordercolor white -border 2 +append "$out"
    }
    row "$work/row_osg.png" "${top[@]}"
    row "$work/row_ours.png" "${bottom[@]}"
    "$imagemagick" "$work/row_osg.png" "$work/row_ours.png" -append "$crop"
  fi
done
python3 benchmarks/benchmarks_section.py peers "Peer comparison: OpenSceneGraph" "$results/tmp/peers_section.md"
echo "peers: wrote $results/peers.md, the crops and the peers section of BENCHMARKS.md (${elapsed} s of runs)"
