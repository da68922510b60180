#!/usr/bin/env bash
# Builds gltf_fuzzer (libFuzzer with AddressSanitizer and UndefinedBehaviorSanitizer, clang) in
# BUILD_DIR and runs it for SECONDS over an accumulating corpus.
#
#   tests/fuzz/run_fuzz.sh BUILD_DIR SECONDS [TARGET...]
#
# TARGETs are built as well (.ci/run builds the test programs here, shadow_tests, and runs the
# suite under the same sanitizers); SECONDS 0 configures and builds without fuzzing. Debug
# information is line tables only: enough for the sanitizers' and libFuzzer's stack traces, and
# an eighth less time to compile than full -g.
#
# The corpus is a folder kept between runs: SHADOW_FUZZ_CORPUS, default BUILD_DIR/fuzz-corpus
# (kept as long as the build folder is; a CI points it at a folder it caches). Each run starts
# from everything earlier runs found and adds each input that reaches new code. Every run first
# adds the seeds, named by their content so that none is held twice: the checked-in ones
# (tests/fuzz/corpus/), the inputs that once failed (tests/fuzz/regressions/), a glTF per
# technique with a light of each type (benchmarks/light_scenes.py), and the glTF files the
# importer's tests write, when a test build is at hand (SHADOW_SEED_TESTS, default
# build/bin/shadow_core_tests). Past 4,000 files the corpus is merged down to the inputs that
# keep its coverage. The corpus is not committed; the checked-in seeds are never written.
#
# A crash leaves its input in BUILD_DIR/fuzz-artifacts/ and the script fails. Copy such an input
# into tests/fuzz/regressions/ (named after what it broke) once fixed: the ordinary test suite
# replays every file there. Exit code: libFuzzer's (0 when nothing was found).
set -euo pipefail

if [ $# -lt 2 ]; then
  echo "usage: $0 BUILD_DIR SECONDS [TARGET...]" >&2
  exit 2
fi
build=$1
seconds=$2
shift 2
src=$(cd "$(dirname "$0")/../.." && pwd)
corpus=${SHADOW_FUZZ_CORPUS:-$build/fuzz-corpus}
seed_tests=${SHADOW_SEED_TESTS:-$src/build/bin/shadow_core_tests}
max_len=8192  # glTF documents need a few kB to reach the importer's later stages

flags="-O2 -gline-tables-only -DNDEBUG"
generator=()  # Ninja for a new folder, as .ci/setup
[ -f "$build/CMakeCache.txt" ] || generator=(-G Ninja)
cmake -S "$src" -B "$build" "${generator[@]}" -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++ -DSHADOW_FUZZ=ON \
  "-DCMAKE_C_FLAGS_RELWITHDEBINFO=$flags" "-DCMAKE_CXX_FLAGS_RELWITHDEBINFO=$flags" \
  -DSHADOW_BUILD_BENCHMARKS=OFF -DSHADOW_BUILD_VIEWER=OFF >/dev/null
cmake --build "$build" -j"$(nproc)" --target gltf_fuzzer "$@"
[ "$seconds" -gt 0 ] || exit 0
fuzzer=$build/bin/gltf_fuzzer

mkdir -p "$corpus" "$build/fuzz-artifacts"
seeds=$(mktemp -d)
trap 'rm -rf "$seeds"' EXIT

# Adds FILE... to the corpus under the SHA-1 of its content (libFuzzer's own naming); files
# longer than max_len would only be cut.
add_seeds() {
  local f
  for f in "$@"; do
    if [ -f "$f" ] && [ "$(stat -c %s "$f")" -le "$max_len" ]; then
      cp "$f" "$corpus/$(sha1sum "$f" | cut -c1-40)"
    fi
  done
}
add_seeds "$src"/tests/fuzz/corpus/* "$src"/tests/fuzz/regressions/*.gl*
for technique in hard pcf pcss vsm vssm msm msm-soft sdf; do
  python3 "$src/benchmarks/light_scenes.py" "$seeds/$technique.gltf" \
    "spot:$technique" "point:$technique" "directional:$technique:vogel:2" >/dev/null
done
if [ -x "$seed_tests" ]; then
  SHADOW_KEEP_TEST_FILES=1 SHADOW_TEST_TMP="$seeds/tests" "$seed_tests" --gtest_filter='Gltf*:ErrorCodes.*' \
    >/dev/null 2>&1 || echo "fuzz: $seed_tests failed; its files are seeds all the same"
else
  echo "fuzz: no $seed_tests: the importer's tests' glTF files are not among the seeds this run"
fi
mapfile -t generated < <(find "$seeds" -type f \( -name '*.gltf' -o -name '*.glb' \))
add_seeds "${generated[@]}"

held=$(find "$corpus" -maxdepth 1 -type f | wc -l)
if [ "$held" -gt 4000 ]; then
  echo "fuzz: merging the corpus of $held inputs"
  rm -rf "$corpus.merged"
  mkdir "$corpus.merged"
  "$fuzzer" -merge=1 -max_len="$max_len" -rss_limit_mb=2048 "$corpus.merged" "$corpus"
  mv "$corpus" "$corpus.old"
  mv "$corpus.merged" "$corpus"
  rm -rf "$corpus.old"
fi
echo "fuzz: corpus $corpus, $(find "$corpus" -maxdepth 1 -type f | wc -l) inputs"

# -timeout: any single input taking 10 s is a hang worth a report.
"$fuzzer" \
  -max_total_time="$seconds" -max_len="$max_len" -timeout=10 -rss_limit_mb=2048 -print_final_stats=1 \
  -dict="$src/tests/fuzz/gltf.dict" -artifact_prefix="$build/fuzz-artifacts/" "$corpus"
