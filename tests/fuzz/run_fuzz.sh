#!/usr/bin/env bash
# Builds the fuzzers (libFuzzer with AddressSanitizer and UndefinedBehaviorSanitizer, clang) in
# BUILD_DIR and runs them for SECONDS in all, each over an accumulating corpus of its own:
#   gltf_fuzzer    half the time: the glTF loader, skins and clips posed, shadow planning;
#   image_fuzzer   a quarter: the image decoding a file's textures take (image_fuzz_target.h);
#   script_fuzzer  a quarter: the viewer's script language and the settings it writes.
#
#   tests/fuzz/run_fuzz.sh BUILD_DIR SECONDS [TARGET...]
#
# TARGETs are built as well (.ci/run builds the test programs here, shadow_tests, and runs the
# suite under the same sanitizers); SECONDS 0 configures and builds without fuzzing. Debug
# information is line tables only: enough for the sanitizers' and libFuzzer's stack traces, and
# an eighth less time to compile than full -g.
#
# The corpora are folders kept between runs: SHADOW_FUZZ_CORPUS (default BUILD_DIR/fuzz-corpus,
# kept as long as the build folder is; a CI points it at a folder it caches) holds gltf/, image/
# and script/. Each run starts from everything earlier runs found and adds each input that
# reaches new code. Every run first adds the seeds, named by their content so that none is held
# twice:
#   gltf/    the checked-in ones (tests/fuzz/corpus/), the inputs that once failed
#            (tests/fuzz/regressions/), a glTF per technique with a light of each type
#            (benchmarks/light_scenes.py), and the glTF files the importer's tests write, when a
#            test build is at hand (SHADOW_SEED_TESTS, default build/bin/shadow_core_tests);
#   image/   PNGs of one to four channels and a JPEG, encoded by the image target's test
#            (ImageFuzz.* of SHADOW_SEED_GL_TESTS, default BUILD_DIR/bin/shadow_gl_tests, then
#            build/bin/shadow_gl_tests), and every PNG image the repository holds that is small
#            enough;
#   script/  tests/fuzz/scripts/ (every command and every light setting).
# Past 4,000 files a corpus is merged down to the inputs that keep its coverage. The corpora are
# not committed; the checked-in seeds are never written.
#
# A crash leaves its input in BUILD_DIR/fuzz-artifacts/ and the script fails. Copy such an input
# into tests/fuzz/regressions/ (named after what it broke) once fixed: the ordinary test suite
# replays every file there through the glTF target (a script or image input: add it to
# tests/fuzz/scripts/, or as a case of image_fuzz_test.cpp). Exit code: libFuzzer's (0 when
# nothing was found).
set -euo pipefail

if [ $# -lt 2 ]; then
  echo "usage: $0 BUILD_DIR SECONDS [TARGET...]" >&2
  exit 2
fi
build=$1
seconds=$2
shift 2
src=$(cd "$(dirname "$0")/../.." && pwd)
corpora=${SHADOW_FUZZ_CORPUS:-$build/fuzz-corpus}
seed_tests=${SHADOW_SEED_TESTS:-$src/build/bin/shadow_core_tests}

flags="-O2 -gline-tables-only -DNDEBUG"
generator=()  # Ninja for a new folder, as .ci/setup
[ -f "$build/CMakeCache.txt" ] || generator=(-G Ninja)
cmake -S "$src" -B "$build" "${generator[@]}" -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++ -DSHADOW_FUZZ=ON \
  "-DCMAKE_C_FLAGS_RELWITHDEBINFO=$flags" "-DCMAKE_CXX_FLAGS_RELWITHDEBINFO=$flags" \
  -DSHADOW_BUILD_BENCHMARKS=OFF -DSHADOW_BUILD_VIEWER=OFF >/dev/null
cmake --build "$build" -j"$(nproc)" --target gltf_fuzzer image_fuzzer script_fuzzer "$@"
[ "$seconds" -gt 0 ] || exit 0

mkdir -p "$build/fuzz-artifacts"
seeds=$(mktemp -d)
trap 'rm -rf "$seeds"' EXIT

# add_seeds MAX_LEN CORPUS FILE...: adds each FILE to CORPUS under the SHA-1 of its content
# (libFuzzer's own naming); files longer than MAX_LEN would only be cut.
add_seeds() {
  local max=$1 corpus=$2 f
  shift 2
  for f in "$@"; do
    if [ -f "$f" ] && [ "$(stat -c %s "$f")" -le "$max" ]; then
      cp "$f" "$corpus/$(sha1sum "$f" | cut -c1-40)"
    fi
  done
}

# fuzz NAME MAX_LEN SECONDS [libFuzzer options...]: merges NAME's corpus when it has grown past
# 4,000 inputs, then runs NAME_fuzzer over it. -timeout: any single input taking 10 s is a hang
# worth a report.
fuzz() {
  local name=$1 max=$2 time=$3
  shift 3
  local fuzzer=$build/bin/${name}_fuzzer corpus=$corpora/$name held
  held=$(find "$corpus" -maxdepth 1 -type f | wc -l)
  if [ "$held" -gt 4000 ]; then
    echo "fuzz: merging the $name corpus of $held inputs"
    rm -rf "$corpus.merged"
    mkdir "$corpus.merged"
    "$fuzzer" -merge=1 -max_len="$max" -rss_limit_mb=2048 "$corpus.merged" "$corpus"
    mv "$corpus" "$corpus.old"
    mv "$corpus.merged" "$corpus"
    rm -rf "$corpus.old"
  fi
  echo "fuzz: $name, corpus $corpus, $(find "$corpus" -maxdepth 1 -type f | wc -l) inputs, $time s"
  "$fuzzer" -max_total_time="$time" -max_len="$max" -timeout=10 -rss_limit_mb=2048 -print_final_stats=1 \
    -artifact_prefix="$build/fuzz-artifacts/${name}-" "$@" "$corpus"
}
mkdir -p "$corpora/gltf" "$corpora/image" "$corpora/script"
# An older layout kept the glTF inputs at the top: they join gltf/.
find "$corpora" -maxdepth 1 -type f -exec mv -t "$corpora/gltf" {} +

gltf_len=8192  # glTF documents need a few kB to reach the importer's later stages
add_seeds $gltf_len "$corpora/gltf" "$src"/tests/fuzz/corpus/* "$src"/tests/fuzz/regressions/*.gl*
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
add_seeds $gltf_len "$corpora/gltf" "${generated[@]}"

image_len=16384  # a small PNG or JPEG with its headers, tables and a few blocks
mkdir -p "$seeds/images"
gl_tests=${SHADOW_SEED_GL_TESTS:-}
if [ -z "$gl_tests" ]; then
  for candidate in "$build/bin/shadow_gl_tests" "$src/build/bin/shadow_gl_tests"; do
    if [ -x "$candidate" ]; then gl_tests=$candidate; break; fi
  done
fi
if [ -n "$gl_tests" ] && [ -x "$gl_tests" ]; then
  SHADOW_FUZZ_SEED_DIR="$seeds/images" "$gl_tests" --gtest_filter='ImageFuzz.*' >/dev/null 2>&1 ||
    echo "fuzz: $gl_tests failed; its images are seeds all the same"
else
  echo "fuzz: no shadow_gl_tests: the encoded images are not among the seeds this run"
fi
mapfile -t images < <(find "$seeds/images" "$src/samples" "$src/docs" -type f -name '*.png' 2>/dev/null)
add_seeds $image_len "$corpora/image" "${images[@]}"

script_len=4096
add_seeds $script_len "$corpora/script" "$src"/tests/fuzz/scripts/*.script

# The time: half to the glTF loader, a quarter to each of the others (at least a second each).
image_time=$(( seconds / 4 > 0 ? seconds / 4 : 1 ))
script_time=$image_time
gltf_time=$(( seconds - image_time - script_time > 0 ? seconds - image_time - script_time : 1 ))
status=0
fuzz gltf $gltf_len $gltf_time -dict="$src/tests/fuzz/gltf.dict" || status=$?
fuzz image $image_len $image_time || status=$?
fuzz script $script_len $script_time -dict="$src/tests/fuzz/script.dict" || status=$?
exit $status
