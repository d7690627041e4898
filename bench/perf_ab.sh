#!/bin/sh
# Wall time of two versions of the header, side by side (issue 9's reports):
#   sh bench/perf_ab.sh REV_A REV_B [ROUNDS] [-- PERF_ARGS...]
# REV_A / REV_B: git revisions, or WORKTREE to take this tree's stereoblend.h as it is.
# Builds bench/perf.c against each header (PERF_FLAGS, default -march=native), then runs
# the two binaries alternately ROUNDS times (default 3) with PERF_ARGS (default
# --reps 9 --size 1080 --only temporal --only stereo), so that the machine's drift falls
# on both alike, and prints each run's rows (ms, the same run's floor, their ratio).
# Compare ratios to the floor within a run, not ms across runs: on a shared machine the
# floor itself moves between runs.
set -e
[ $# -ge 2 ] || { echo "usage: $0 REV_A REV_B [ROUNDS] [-- PERF_ARGS...]" >&2; exit 2; }
a=$1; b=$2; shift 2
rounds=3
if [ $# -gt 0 ] && [ "$1" != "--" ]; then rounds=$1; shift; fi
[ "${1:-}" = "--" ] && shift
args="$*"
[ -n "$args" ] || args="--reps 9 --size 1080 --only temporal --only stereo"
flags=${PERF_FLAGS:--march=native}
top=$(git rev-parse --show-toplevel)
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
for v in a b; do
  eval rev=\$$v
  mkdir -p "$tmp/$v/bench"
  if [ "$rev" = WORKTREE ]; then cp "$top/stereoblend.h" "$tmp/$v/"
  else git -C "$top" show "$rev:stereoblend.h" > "$tmp/$v/stereoblend.h"; fi
  cp "$top/bench/perf.c" "$tmp/$v/bench/"
  # perf_opencv.cpp is left out: the A/B compares the library, not OpenCV
  ${CC:-cc} -std=c99 -O2 $flags "$tmp/$v/bench/perf.c" -o "$tmp/$v/perf" -lpthread -lm
done
r=1
while [ "$r" -le "$rounds" ]; do
  for v in a b; do
    eval rev=\$$v
    echo "## round $r, $v = $rev"
    (cd "$tmp/$v" && ./perf --out "$tmp/$v/out" $args) | grep '^|' | grep -v -- '---'
  done
  r=$((r + 1))
done
