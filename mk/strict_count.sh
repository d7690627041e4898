#!/bin/sh
# Counts the warnings of strict compiles for `make check`: one check per compile (its log
# must hold no warning or error); prints the warnings of any that has some, then the
# harness's summary line. usage: mk/strict_count.sh LOG...
pass=0; fail=0
for f in "$@"; do
  n=$(grep -c -E '(warning|error):' "$f")
  if [ "$n" -eq 0 ]; then pass=$((pass + 1)); else
    fail=$((fail + 1)); echo "$f: $n warnings"; grep -E '(warning|error):' "$f" | head -n 20
  fi
done
echo "strict: $pass passed, $fail failed"
[ "$fail" -eq 0 ]
