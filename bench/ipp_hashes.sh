#!/bin/sh
# Bit-for-bit check of the outputs across a code change: prints one line per
# (binary, case, IPP_SHARED_BIAS) with bench/ipp.c's FNV-1a hash of every output.
# usage: sh bench/ipp_hashes.sh BIN... > after.txt; diff before.txt after.txt
set -e
cases="easy hard tiny static normals two-eyes easy-ev hard-ev normals-ev slant uv camera offset far toed"
for b in "$@"; do
  for c in $cases; do
    h0=$(env -u IPP_SHARED_BIAS "$b" "$c" hash | sed -n 's/^hash //p')
    h1=$(IPP_SHARED_BIAS=1 "$b" "$c" hash | sed -n 's/^hash //p')
    printf '%s %s unset %s\n' "$(basename "$b")" "$c" "$h0"
    printf '%s %s 1 %s\n' "$(basename "$b")" "$c" "$h1"
  done
done
