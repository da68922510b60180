#!/usr/bin/env bash
# Technique auto against PCSS at the module's defaults and against every fixed configuration it
# chooses from (benchmarks/auto_budget.py says how each figure is measured):
#   bash benchmarks/run_auto_budget.sh [SCENE...]
# Default scenes: builtin:plates builtin:bunny builtin:default (the error model was fitted on
# them) and builtin:plates-boxes and the sample scene fence (it was not). About 2 minutes a scene
# per round. ROUNDS (1): interleaved rounds, medians; SIZE (320x240); WRITE_BENCHMARKS=0 leaves
# BENCHMARKS.md alone (otherwise its "Technique auto" section is rewritten). Work files in
# benchmarks/results/tmp/auto (each scene's results.json feeds benchmarks/fit_auto_error.py
# --auto-work). Builds the three programs only when one is missing.
set -euo pipefail
cd "$(dirname "$0")/.."
scenes=("$@")
[ ${#scenes[@]} -gt 0 ] || scenes=(builtin:plates builtin:bunny builtin:default builtin:plates-boxes fence)
for p in shadow_render shadow_reference shadow_compare; do
  [ -x "build/bin/$p" ] || cmake --build build -j2 --target "$p"
done
work=benchmarks/results/tmp/auto
rm -rf "$work"
start=$(date +%s)
report=$(mktemp)
trap 'rm -f "$report" "$report.body"' EXIT
python3 benchmarks/auto_budget.py "${scenes[@]}" --work "$work" --rounds "${ROUNDS:-1}" --size "${SIZE:-320x240}" \
  --markdown "$report"
if [ "${WRITE_BENCHMARKS:-1}" != 0 ]; then
  {
    echo "Produced by \`${ROUNDS:+ROUNDS=$ROUNDS }bash benchmarks/run_auto_budget.sh\` ($(($(date +%s) - start)) s, load average" \
      "$(cut -d' ' -f1 /proc/loadavg) at the end). The checks are those of docs/auto_technique.md" \
      "\"Measured\": at B, auto's RMSE against PCSS's; at B/2, auto's cost against B/2 and its RMSE" \
      "against the best fixed configuration (one for every light) whose cost is within B/2; time =" \
      "predicted / measured cost of auto's choices."
    echo
    cat "$report"
  } > "$report.body"
  python3 benchmarks/benchmarks_section.py auto-budget "Technique auto against fixed configurations" "$report.body"
fi
