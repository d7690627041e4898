#!/bin/sh
# Instructions per stereo frame of each SSAO configuration of examples/ao_stereo.c
# (callgrind, which does not drift with the machine's load), and of the library's
# consistency mask alone.
# usage: [SAMPLES=N] bench/ao_ipp.sh [scene] [frames] [thresholds...]
#   make build/ao_stereo && sh bench/ao_ipp.sh atrium 1 0.01 0.02 0.05 0.1
#   SAMPLES=16 sh bench/ao_ipp.sh gallery 1 0.02   (obscurance samples per pixel, default 8)
set -e
scene=${1:-atrium}; frames=${2:-1}; shift 2 2>/dev/null || true
thresholds=${*:-0.02}
samples=${SAMPLES:-8}
bin=./build/ao_stereo
out=$(mktemp -d)
count() { # config threshold function
    valgrind --tool=callgrind --callgrind-out-file="$out/cg" --toggle-collect="$3" \
        $bin --only "$1" --scene "$scene" --frames "$frames" --threshold "$2" --samples "$samples" 2>&1 |
        sed -n 's/.*Collected : \([0-9]*\).*/\1/p'
}
printf '%s, %s obscurance samples per pixel, %s frame(s)\n\n' "$scene" "$samples" "$frames"
printf '| config | threshold | Minstr / stereo frame | x Mono | of which the mask (Minstr) |\n'
printf '|---|---:|---:|---:|---:|\n'
mono=$(count Mono 0.02 count_config)
for t in $thresholds; do
    for c in Mono FSA Variant1 Variant2; do
        [ "$c" = Mono ] && n=$mono || n=$(count $c "$t" count_config)
        m=0
        case $c in Variant*) m=$(count $c "$t" sbl_stereo_consistency) ;; esac
        awk -v c=$c -v t=$t -v n=$n -v mono=$mono -v m=$m -v f=$frames 'BEGIN {
            printf "| %s | %.2f | %.1f | %.2f | %.1f |\n", c, t, n / f / 1e6, n / mono, m / f / 1e6 }'
    done
done
rm -rf "$out"
