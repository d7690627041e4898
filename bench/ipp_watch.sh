#!/bin/sh
# CI's watch on speed: instructions per pixel (callgrind, inside the public call, the
# 640x360 RGB cases of bench/ipp.c) of the SSE2 build, against the budgets in
# bench/ipp_budget.txt (one line per case and function: CASE FUNCTION BUDGET; every case
# named there is run). Instruction counts do not drift with machine load, so this can
# fail a change that makes the inner loops slower without timing anything; the budgets
# carry a margin for other compiler versions. usage: ipp_watch.sh IPP_SSE2_BINARY
# Fails if a run fails (valgrind, the binary) or a budget line has no measured figure:
# a watch that cannot measure must not pass.
set -e
bin=$1
here=$(dirname "$0")
budgets="$here/ipp_budget.txt"
if ! command -v valgrind >/dev/null 2>&1; then
  echo "SKIP  ipp watch (valgrind not installed)"; exit 0
fi
cases=$(awk '!/^#/ && NF == 3 && !seen[$1]++ { printf "%s ", $1 }' "$budgets")
[ -n "$cases" ] || { echo "FAIL  ipp watch: no budget lines in $budgets"; exit 1; }
tmp=$(mktemp)
out=$(mktemp)
trap 'rm -f "$tmp" "$out"' EXIT
# each function on the cases that budget it (a callgrind run per case and function)
for fn in sbl_temporal_filter sbl_temporal_display sbl_stereo_blend; do
  fcases=$(awk -v f="$fn" '!/^#/ && NF == 3 && $2 == f { printf "%s ", $1 }' "$budgets")
  [ -n "$fcases" ] || continue
  if ! IPP_FUNCTIONS=$fn sh "$here/ipp.sh" "$bin" -- $fcases >"$out" 2>&1; then
    cat "$out"; echo "FAIL  ipp watch: bench/ipp.sh failed"; exit 1
  fi
  cat "$out" >>"$tmp"
done
status=0
# every budget line against its measured figure (ipp.sh prints: binary case function ipp)
while read -r c fn budget; do
  case "$c" in '#'*|'') continue ;; esac
  [ -n "$budget" ] || continue
  ipp=$(awk -v c="$c" -v f="$fn" 'NR > 1 && $2 == c && $3 == f { print $4 }' "$tmp")
  case "$ipp" in
    ''|*[!0-9.]*) echo "FAIL  ipp watch: $c $fn not measured (budget $budget)"; status=1; continue ;;
  esac
  if [ "$(echo "$ipp > $budget" | bc -l)" = 1 ]; then
    echo "FAIL  ipp watch: $c $fn $ipp instructions per pixel, budget $budget"; status=1
  else
    echo "PASS  ipp watch: $c $fn $ipp instructions per pixel (budget $budget)"
  fi
done <"$budgets"
exit $status
