#!/bin/sh
# Instructions per pixel (callgrind) of the adaptive stereo blend's parts on a real
# sequence: temporal filter (per eye and frame), consistency mask, stereo blend, masked
# blend (per eye). usage: bench/adaptive_ipp.sh [SCENE_DIR] [FRAME] [THRESHOLDS...]
#   make build/adaptive_ipp && sh bench/adaptive_ipp.sh ../shared/data/atrium 8 0.02 0.1
set -e
dir=${1:-../shared/data/atrium}; frame=${2:-8}; shift 2 2>/dev/null || true
thresholds=${*:-0.02}
bin=./build/adaptive_ipp
tmp=$(mktemp -d)
count() { # function threshold -> instructions
    valgrind --tool=callgrind --callgrind-out-file="$tmp/cg" --toggle-collect="$1" \
        $bin "$dir" "$frame" "$2" > "$tmp/out" 2>&1
    sed -n 's/.*Collected : \([0-9]*\).*/\1/p' "$tmp/out"
}
px=$($bin "$dir" "$frame" | sed -n 's/.*: \([0-9]*\) x \([0-9]*\),.*/\1 \2/p' | awk '{print $1 * $2}')
printf '| %s frame %s | threshold | marked %% | instr / px (per eye) |\n|---|---:|---:|---:|\n' "$(basename "$dir")" "$frame"
t=$(count sbl_temporal_filter_frame 0.02)
awk -v n=$t -v px=$px -v f=$((frame + 1)) 'BEGIN { printf "| temporal filter (Mono) | | | %.0f |\n", n / (px * 2 * f) }'
b=$(count sbl_stereo_blend 0.02)
awk -v n=$b -v px=$px 'BEGIN { printf "| stereo blend everywhere (FSA) | | | %.0f |\n", n / (px * 2) }'
for th in $thresholds; do
    m=$(count sbl_stereo_consistency "$th")
    k=$(count sbl_stereo_blend_masked "$th")
    f=$(count sbl_stereo_blend_adaptive "$th")
    share=$($bin "$dir" "$frame" "$th" | sed -n 's/.*marked \([0-9.]*\) %.*/\1/p')
    tiles=$($bin "$dir" "$frame" "$th" | sed -n 's/.*tiles \([0-9.]*\) %.*/\1/p')
    awk -v n=$m -v px=$px -v t=$th -v s=$share 'BEGIN { printf "| consistency mask | %.2f | %s | %.0f |\n", t, s, n / (px * 2) }'
    awk -v n=$k -v px=$px -v t=$th -v s=$share 'BEGIN { printf "| masked blend | %.2f | %s | %.0f |\n", t, s, n / (px * 2) }'
    awk -v n=$f -v px=$px -v t=$th -v s=$share -v tl=$tiles 'BEGIN { printf "| one-pass adaptive (tiles run %s %%) | %.2f | %s | %.0f |\n", tl, t, s, n / (px * 2) }'
done
rm -rf "$tmp"
