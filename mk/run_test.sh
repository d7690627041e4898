#!/bin/sh
# Runs one test command for `make check`, quietly.
#   usage: mk/run_test.sh RESULT_FILE LABEL COMMAND [ARG...]
#          mk/run_test.sh --summary "WHAT:WHY ..." RESULT_FILE...
# Writes RESULT_FILE: its first line is "PASS  LABEL  (N checks)" or "FAIL  LABEL  (...)";
# after a FAIL line comes the full output of the command. A run passes only if the
# command exits 0, prints a summary line the harness knows ("NAME: N passed, N failed",
# "N/M checks passed", "replayed N inputs") and that line reports no failure.
if [ "$1" = --summary ]; then
  # one line per run, then every failure in full, then "N passed, N failed" last.
  # A result file that is missing means its binary did not build (the compiler output
  # is above).
  skips=$2; shift 2
  pass=0; fail=0
  for s in $skips; do
    printf 'SKIP  %-34s (%s)\n' "${s%%:*}" "$(printf '%s' "${s#*:}" | tr '_' ' ')"
  done
  for r in "$@"; do
    label=${r#*/res/}; label=${label%.res}
    if [ ! -f "$r" ]; then
      printf 'FAIL  %-34s (did not build: see the compiler output above)\n' "$label"
      fail=$((fail + 1))
    elif head -n 1 "$r" | grep -q '^PASS'; then
      head -n 1 "$r"; pass=$((pass + 1))
    else
      head -n 1 "$r"; fail=$((fail + 1))
    fi
  done
  for r in "$@"; do
    if [ -f "$r" ] && ! head -n 1 "$r" | grep -q '^PASS'; then echo; cat "$r"; fi
  done
  echo "$pass passed, $fail failed"
  [ "$fail" -eq 0 ]
  exit
fi
res=$1; label=$2; shift 2
log=${res%.res}.log
mkdir -p "$(dirname "$res")"
"$@" >"$log" 2>&1
rc=$?
summary=$(grep -a -E '[0-9]+ passed, [0-9]+ failed$|^[0-9]+/[0-9]+ checks passed$|replayed [0-9]+ inputs' "$log" | tail -n 1)
count=
failed=0
case $summary in
  *" passed, "*" failed")
    count=$(printf '%s\n' "$summary" | sed -E 's/.* ([0-9]+) passed, ([0-9]+) failed$/\1/')
    failed=$(printf '%s\n' "$summary" | sed -E 's/.* ([0-9]+) failed$/\1/')
    count="$count checks" ;;
  *"checks passed")
    pass=$(printf '%s\n' "$summary" | sed -E 's|^([0-9]+)/([0-9]+).*|\1|')
    total=$(printf '%s\n' "$summary" | sed -E 's|^([0-9]+)/([0-9]+).*|\2|')
    failed=$((total - pass)); count="$total checks" ;;
  *replayed*)
    count=$(printf '%s\n' "$summary" | sed -E 's/.*replayed ([0-9]+) inputs.*/\1 inputs/') ;;
esac
if [ "$rc" -eq 0 ] && [ -n "$count" ] && [ "$failed" -eq 0 ]; then
  printf 'PASS  %-34s %s\n' "$label" "($count)" >"$res"
else
  why="exit status $rc"
  [ -n "$count" ] || why="$why, no summary line"
  [ "$failed" -eq 0 ] || why="$why, $failed failed"
  { printf 'FAIL  %-34s %s\n' "$label" "($why)"
    printf '      command: %s\n' "$*"
    grep -v '^PASS  ' "$log" | sed 's/^/      | /'; } >"$res"
fi
exit 0
