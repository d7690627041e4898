#!/bin/sh
# CI's watch on speed: instructions per pixel (callgrind, inside the public call, the
# easy 640x360 RGB case of bench/ipp.c) of the SSE2 build, against the budgets in
# bench/ipp_budget.txt. Instruction counts do not drift with machine load, so this can
# fail a change that makes the inner loops slower without timing anything; the budgets
# carry a margin for other compiler versions. usage: ipp_watch.sh IPP_SSE2_BINARY
set -e
bin=$1
here=$(dirname "$0")
if ! command -v valgrind >/dev/null 2>&1; then
  echo "SKIP  ipp watch (valgrind not installed)"; exit 0
fi
status=0
out=$(sh "$here/ipp.sh" "$bin" -- easy | tail -n +2)
echo "$out" | while read -r b c fn ipp; do
  budget=$(awk -v f="$fn" '$1 == f { print $2 }' "$here/ipp_budget.txt")
  [ -n "$budget" ] || { echo "FAIL  ipp watch: no budget for $fn in bench/ipp_budget.txt"; exit 1; }
  if [ "$(echo "$ipp > $budget" | bc -l)" = 1 ]; then
    echo "FAIL  ipp watch: $fn $ipp instructions per pixel, budget $budget"; exit 1
  fi
  echo "PASS  ipp watch: $fn $ipp instructions per pixel (budget $budget)"
done || status=1
exit $status
