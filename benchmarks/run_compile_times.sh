#!/usr/bin/env bash
# Compile time, measured as a first run on a fresh machine compiles: with the driver's shader
# cache off, (1) the CPU time of each case of shadow_compile_tests (the worst light
# configurations a pass can hold, and the game shader's forms), (2) whole-process first frames
# of generated scenes of many lights (benchmarks/light_scenes.py) at 160x90, and (3) the program
# binary cache on builtin:default. Writes benchmarks/results/compile_times.md and its section of
# BENCHMARKS.md. About five minutes on two cores.
#   bash benchmarks/run_compile_times.sh        (ROUNDS=3 to override the rounds of (2) and (3))
set -euo pipefail
cd "$(dirname "$0")/.."
bash .ci/setup >/dev/null
rounds=${ROUNDS:-3}
results=benchmarks/results
work=$results/tmp/compile
rm -rf "$work"
mkdir -p "$work"

# (1) The compile tests print one line per case with its CPU time and its target (2 s for one
# light, 10 s for a pass); the table says which are met.
./build/bin/shadow_compile_tests > "$work/tests.log" 2>&1 || { cat "$work/tests.log"; exit 1; }

# (2) Scenes of many lights: name|specs.
scenes=(
  "three cascaded suns, PCF|3xdirectional:pcf:vogel:3"
  "three cascaded suns, PCSS|3xdirectional:pcss:vogel:4"
  "16 lights: each type with hard, PCF, PCSS, VSSM, MSM-soft|directional:hard directional:pcf directional:pcss:vogel:3 directional:vssm directional:msm-soft spot:hard spot:pcf spot:pcss spot:vssm spot:msm-soft point:hard point:pcf point:pcss point:vssm point:msm-soft spot:vsm"
)
specs300=""
for type in directional spot point; do
  for technique in hard pcf pcss vsm vssm msm msm-soft; do
    n=14; [ "$technique" = hard ] && n=16
    specs300="$specs300 ${n}x$type:$technique"
  done
done
scenes+=("300 lights: 100 suns, 100 spots, 100 points, 7 techniques|$specs300")
for i in "${!scenes[@]}"; do
  IFS='|' read -r _ specs <<< "${scenes[$i]}"
  # shellcheck disable=SC2086
  python3 benchmarks/light_scenes.py "$work/scene_$i.gltf" $specs
done
run_scene() {  # index round: wall and user seconds of a whole first run, cache off
  local out="$work/scene_$1_$2"
  MESA_SHADER_CACHE_DISABLE=true /usr/bin/time -f "%e %U" -o "$out.time" \
    ./build/bin/shadow_render "$work/scene_$1.gltf" --size 160x90 --aov color --out "$out" >/dev/null
}
for round in $(seq 1 "$rounds"); do
  for i in "${!scenes[@]}"; do run_scene "$i" "$round"; done
done

# (3) The program binary cache on builtin:default (640x360, one frame): the driver's cache off;
# on and empty; on and warm; on and empty with the program folder warm.
run_default() {  # mode round
  local out="$work/default_$1_$2" mesa="$work/mesa_$1_$2" programs="$work/programs_$2"
  local env=(env -u MESA_SHADER_CACHE_DISABLE "MESA_SHADER_CACHE_DIR=$mesa")
  local args=(builtin:default --size 640x360 --aov color --out "$out")
  case "$1" in
    off) env=(env MESA_SHADER_CACHE_DISABLE=true) ;;
    cold) rm -rf "$mesa" ;;
    warm) mesa="$work/mesa_cold_$2"; env=(env -u MESA_SHADER_CACHE_DISABLE "MESA_SHADER_CACHE_DIR=$mesa") ;;
    programs) rm -rf "$mesa"; args+=(--shader-cache "$programs") ;;
  esac
  "${env[@]}" /usr/bin/time -f "%e %U" -o "$out.time" ./build/bin/shadow_render "${args[@]}" >/dev/null
}
for round in $(seq 1 "$rounds"); do
  rm -rf "$work/programs_$round"
  # Fill the program folder first (its run is not counted), then the four modes.
  env -u MESA_SHADER_CACHE_DISABLE "MESA_SHADER_CACHE_DIR=$work/mesa_fill_$round" ./build/bin/shadow_render \
    builtin:default --size 640x360 --aov color --shader-cache "$work/programs_$round" --out "$work/fill_$round" >/dev/null
  for mode in off cold warm programs; do run_default "$mode" "$round"; done
done

python3 - "$work" "$rounds" "${scenes[@]}" > "$results/compile_times.md" <<'PY'
import json, re, statistics, sys
work, rounds, scenes = sys.argv[1], int(sys.argv[2]), sys.argv[3:]
def times(path):
    wall, user = open(path).read().split()[-2:]
    return float(wall), float(user)
first = json.load(open(f"{work}/default_off_1/stats.json"))
print(f"Renderer `{first['renderer']}`; the driver's shader cache off unless a row says otherwise. "
      "CPU time is the compiling thread's (llvmpipe generates a program's machine code at its "
      "first draw, on the thread that draws); whole-process figures are wall clock and user CPU "
      f"of `shadow_render`, median of {rounds} interleaved rounds.")
print()
print("### Worst configurations of one pass (shadow_compile_tests)")
print()
print("| case | CPU s | target s | met |")
print("|---|---:|---:|---|")
for line in open(f"{work}/tests.log"):
    m = re.match(r"\[ compile  \] (.*?)\s+(\d+\.\d+) s, target (\d+) s\s*$", line)
    if m:
        seconds, target = float(m.group(2)), float(m.group(3))
        print(f"| {m.group(1).strip()} | {m.group(2)} | {m.group(3)} | {'yes' if seconds <= target else '**no**'} |")
print()
print("### First run of a scene of many lights, 160x90 (whole process)")
print()
print("| scene | lights | main passes | programs compiled | wall s | user CPU s |")
print("|---|---:|---:|---:|---:|---:|")
for i, entry in enumerate(scenes):
    name = entry.split("|")[0]
    runs = [times(f"{work}/scene_{i}_{r}.time") for r in range(1, rounds + 1)]
    s = json.load(open(f"{work}/scene_{i}_1/stats.json"))
    print(f"| {name} | {len(s['lights'])} | {s['counters']['mainPasses']} | {s['counters']['programsCompiled']} | "
          f"{statistics.median(w for w, _ in runs):.1f} | {statistics.median(u for _, u in runs):.1f} |")
print()
print("### Program binary cache, `builtin:default` at 640x360, one frame (whole process)")
print()
print("| driver's cache | program folder (`--shader-cache`) | programs loaded | wall s | user CPU s |")
print("|---|---|---:|---:|---:|")
labels = {"off": ("off", "none"), "cold": ("on, empty", "none"), "warm": ("on, warm", "none"),
          "programs": ("on, empty", "warm")}
for mode, (driver, folder) in labels.items():
    runs = [times(f"{work}/default_{mode}_{r}.time") for r in range(1, rounds + 1)]
    s = json.load(open(f"{work}/default_{mode}_1/stats.json"))
    print(f"| {driver} | {folder} | {s['programCache']['loaded']} | {statistics.median(w for w, _ in runs):.2f} | "
          f"{statistics.median(u for _, u in runs):.2f} |")
PY
cat "$results/compile_times.md"
{
  echo "Reproduce (about five minutes here after the build; rewrites this section and"
  echo "\`benchmarks/results/compile_times.md\`):"
  echo
  echo '```sh'
  echo "bash benchmarks/run_compile_times.sh"
  echo '```'
  echo
  cat "$results/compile_times.md"
} > "$work/section.md"
python3 benchmarks/benchmarks_section.py compile-times "Compile time" "$work/section.md"
