# shellcheck shell=bash
# Finds the local git snapshot of a third-party repository, for the scripts that read real glTF
# assets out of one with git (benchmarks/run_real_assets.sh, samples/asset_gallery.sh): nothing
# is fetched and nothing is copied into this repository. Sourced, not run:
#
#   source samples/find_snapshot.sh
#   raylib_git=$(find_snapshot raylib "${1:-}") || echo "no raylib snapshot"
#
# find_snapshot NAME [GIVEN] prints the git directory to read: GIVEN when it is one (or
# GIVEN/.git, a clone's work tree); with no GIVEN, the first /work/.mirror/*NAME* (or its repo/
# folder) that is one. Prints nothing and fails when there is none.

# is_git_dir DIR: DIR is a git directory with a HEAD commit.
is_git_dir() { [ -n "$1" ] && git --git-dir="$1" rev-parse --verify -q HEAD >/dev/null 2>&1; }

find_snapshot() {
  local name=$1 given=${2:-} candidate candidates
  if [ -n "$given" ]; then
    candidates=("$given" "$given/.git")
  else
    candidates=(/work/.mirror/*"$name"* /work/.mirror/*"$name"*/repo)
  fi
  for candidate in "${candidates[@]}"; do
    if is_git_dir "$candidate"; then
      echo "$candidate"
      return 0
    fi
  done
  return 1
}
