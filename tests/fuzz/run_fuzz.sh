#!/usr/bin/env bash
# Builds gltf_fuzzer (libFuzzer with AddressSanitizer and UndefinedBehaviorSanitizer, clang) in
# BUILD_DIR and runs it for SECONDS over the seed corpus tests/fuzz/corpus/.
#
#   tests/fuzz/run_fuzz.sh BUILD_DIR SECONDS
#
# New coverage goes to BUILD_DIR/fuzz-corpus/ (the checked-in seeds are never written); a crash
# leaves its input in BUILD_DIR/fuzz-artifacts/ and the script fails. Copy such an input into
# tests/fuzz/regressions/ (named after what it broke) once fixed: the ordinary test suite replays
# every file there. Exit code: libFuzzer's (0 when nothing was found).
set -euo pipefail

if [ $# -ne 2 ]; then
  echo "usage: $0 BUILD_DIR SECONDS" >&2
  exit 2
fi
build=$1
seconds=$2
src=$(cd "$(dirname "$0")/../.." && pwd)

cmake -S "$src" -B "$build" -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++ -DSHADOW_FUZZ=ON \
  -DSHADOW_BUILD_BENCHMARKS=OFF -DSHADOW_BUILD_VIEWER=OFF
cmake --build "$build" -j"$(nproc)" --target gltf_fuzzer

mkdir -p "$build/fuzz-corpus" "$build/fuzz-artifacts"
# -max_len: glTF documents need a few kB to reach the importer's later stages.
# -timeout: any single input taking 10 s is a hang worth a report.
"$build/bin/gltf_fuzzer" \
  -max_total_time="$seconds" -max_len=8192 -timeout=10 -rss_limit_mb=2048 -print_final_stats=1 \
  -dict="$src/tests/fuzz/gltf.dict" -artifact_prefix="$build/fuzz-artifacts/" \
  "$build/fuzz-corpus" "$src/tests/fuzz/corpus"
