#!/bin/sh
# make bench-ipp: instructions per pixel (callgrind, counted inside the public call
# only) for each ipp binary given, for each case. usage: ipp.sh BIN... [-- CASES...]
# Prints one line per (binary, case, function); IPP_FUNCTIONS (default both public calls)
# names the functions to count.
set -e
bins=""
cases="easy"
while [ $# -gt 0 ]; do
  if [ "$1" = "--" ]; then shift; cases="$*"; break; fi
  bins="$bins $1"; shift
done
if ! command -v valgrind >/dev/null 2>&1; then
  echo "bench-ipp: valgrind not found, nothing measured"; exit 0
fi
tmp=$(mktemp -d)
pixels=$((640 * 360))
printf '%-22s %-7s %-20s %8s\n' binary case function ipp
for b in $bins; do
  for c in $cases; do
    for fn in ${IPP_FUNCTIONS:-sbl_temporal_filter sbl_stereo_blend}; do
      out="$tmp/cg.out"
      valgrind --tool=callgrind --toggle-collect="$fn" --callgrind-out-file="$out" \
        "$b" "$c" >/dev/null 2>"$tmp/log" || { cat "$tmp/log"; exit 1; }
      ir=$(sed -n 's/^totals: *\([0-9]*\).*/\1/p' "$out")
      [ -n "$ir" ] || ir=$(sed -n 's/^summary: *\([0-9]*\).*/\1/p' "$out")
      calls=1; [ "$fn" = sbl_temporal_filter ] || [ "$fn" = sbl_temporal_display ] && calls=2
      [ "$c" = two-eyes ] && calls=2 # (both eyes' blends)
      printf '%-22s %-7s %-20s %8.1f\n' "$b" "$c" "$fn" "$(echo "$ir / ($pixels * $calls)" | bc -l)"
    done
  done
done
rm -rf "$tmp"
