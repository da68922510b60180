#!/usr/bin/env bash
# The README's gallery of real third-party glTF assets, each rendered exactly as its repository
# holds it: models of raylib's examples/ and bevy's assets/models/, read with git out of local
# snapshots of the two repositories (nothing is fetched, nothing is copied here), each with the
# files it names, into a temporary folder; then `shadow_render FILE` with no other setting than
# the size and, for an animated asset, the clip and a time in its middle. A file without lights
# gets the default rig (a pcss sun, a ground, a camera), one with lights its own. The list of
# assets, and of those left out and why, is in samples/asset_gallery.py.
#
#   bash samples/asset_gallery.sh [RAYLIB_GIT_DIR [BEVY_GIT_DIR]]
#
# The git directories (or RAYLIB_GIT, BEVY_GIT) default to the first /work/.mirror/*raylib* and
# *bevy* (or their repo/ folder) that are ones (samples/find_snapshot.sh); with either missing
# the run is skipped with a message, exit code 0. A directory given that is not a git directory
# is an error (exit code 2). Writes samples/images/assets/ (<name>.png per asset, <name>.apng.png
# per animated loop; the folder's old images replaced) and the README's "asset-gallery" section.
# Overrides: SIZE (400x225, the stills), APNG_SIZE (320x180, the loops). Builds shadow_render
# only when it is missing.
set -euo pipefail
cd "$(dirname "$0")/.."
source samples/find_snapshot.sh

usage="usage: bash samples/asset_gallery.sh [RAYLIB_GIT_DIR [BEVY_GIT_DIR]]"
case ${1:-} in
  -h | --help) echo "$usage"; exit 0 ;;
  -*) echo "asset_gallery: $1: unknown option; $usage" >&2; exit 2 ;;
esac
if [ $# -gt 2 ]; then
  echo "asset_gallery: $# arguments, at most 2; $usage" >&2
  exit 2
fi
# snapshot NAME GIVEN: the git directory, an error if GIVEN is not one, nothing if none is found.
snapshot() {
  if find_snapshot "$1" "$2"; then return 0; fi
  if [ -n "$2" ]; then
    echo "asset_gallery: $2: not a git directory (of the $1 repository)" >&2
    exit 2
  fi
}
raylib_git=$(snapshot raylib "${1:-${RAYLIB_GIT:-}}")
bevy_git=$(snapshot bevy "${2:-${BEVY_GIT:-}}")
missing=()
[ -n "$raylib_git" ] || missing+=(raylib)
[ -n "$bevy_git" ] || missing+=(bevy)
if [ ${#missing[@]} -gt 0 ]; then
  echo "asset_gallery: skipped: no git snapshot of ${missing[0]}${missing[1]:+ and ${missing[1]}} under" \
    "/work/.mirror/; give the raylib and bevy ones as arguments (or RAYLIB_GIT, BEVY_GIT)"
  exit 0
fi

[ -x build/bin/shadow_render ] || SHADOW_BUILD_TARGETS=shadow_render bash .ci/setup >/dev/null
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
python3 samples/asset_gallery.py build/bin/shadow_render "$raylib_git" "$bevy_git" "$work/images" \
  "${SIZE:-400x225}" "${APNG_SIZE:-320x180}" > "$work/section.md"
rm -rf samples/images/assets
mv "$work/images" samples/images/assets
python3 benchmarks/benchmarks_section.py asset-gallery "Real assets, as loaded" "$work/section.md" README.md
echo "asset_gallery: wrote samples/images/assets/ ($(find samples/images/assets -name '*.png' | wc -l) images)" \
  "and the README's asset gallery"
