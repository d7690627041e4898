#!/bin/sh
# The cost of `make check`, command by command: a SHELL for make that runs each recipe
# command under GNU time and appends "USER SYS WALL<tab>COMMAND" (seconds) to $CHECK_TIMES.
#   make -j2 check SHELL=mk/timed.sh CHECK_TIMES=/tmp/times.log
#   sh mk/timed.sh --table /tmp/times.log     # the commands by CPU seconds, and the total
if [ "$1" = --table ]; then
  awk -F '\t' 'NF >= 2 { split($1, t, " "); c = t[1] + t[2]; cmd = $2
                 if (cmd ~ /check-results|--summary/) next
                 if (match(cmd, /-o [^ ]+/)) what = "cc  " substr(cmd, RSTART + 3, RLENGTH - 3)
                 else if (cmd ~ /run_test.sh/) { split(cmd, w, " "); what = "run " w[4] }
                 else what = "    " substr(cmd, 1, 60)
                 total += c; if (what ~ /^cc/) cc += c
                 printf "%7.1f %7.1f  %s\n", c, t[3], what }
       END { printf "%7.1f CPU seconds in all: %.1f compiling, %.1f running\n", total, cc, total - cc }' "$2" |
    sort -rn
  exit
fi
shift # make passes -c
what=$(printf '%s' "$1" | tr '\n\t' '  ' | sed 's/%/%%/g') # one line; % is time's
exec /usr/bin/time -a -o "${CHECK_TIMES:-/dev/stderr}" -f "%U %S %e	$what" /bin/sh -c "$1"
