#!/bin/sh
# CI's watch on speed: instructions per pixel (callgrind, inside the public call, the
# 640x360 RGB cases of bench/ipp.c) of the SSE2 build, against the budgets in
# bench/ipp_budget.txt (one line per case and function: CASE FUNCTION BUDGET; every case
# named there is run). Instruction counts do not drift with machine load, so this can
# fail a change that makes the inner loops slower without timing anything; the budgets
# carry a margin for other compiler versions. usage: ipp_watch.sh IPP_SSE2_BINARY
set -e
bin=$1
here=$(dirname "$0")
budgets="$here/ipp_budget.txt"
if ! command -v valgrind >/dev/null 2>&1; then
  echo "SKIP  ipp watch (valgrind not installed)"; exit 0
fi
cases=$(awk '!/^#/ && NF == 3 && !seen[$1]++ { printf "%s ", $1 }' "$budgets")
[ -n "$cases" ] || { echo "FAIL  ipp watch: no budget lines in $budgets"; exit 1; }
status=0
out=$(sh "$here/ipp.sh" "$bin" -- $cases | tail -n +2)
echo "$out" | while read -r b c fn ipp; do
  budget=$(awk -v c="$c" -v f="$fn" '!/^#/ && $1 == c && $2 == f { print $3 }' "$budgets")
  [ -n "$budget" ] || continue # measured with its case, not watched
  if [ "$(echo "$ipp > $budget" | bc -l)" = 1 ]; then
    echo "FAIL  ipp watch: $c $fn $ipp instructions per pixel, budget $budget"; exit 1
  fi
  echo "PASS  ipp watch: $c $fn $ipp instructions per pixel (budget $budget)"
done || status=1
exit $status
