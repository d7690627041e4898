#!/bin/sh
# make bench-shortcuts-ipp: instructions per pixel of each shortcut build (bench/shortcuts.c
# built with -DSC_CALLGRIND), per scene and G-buffer, from one callgrind run each: the
# inclusive count of each build's two entry points (sc_temporal_MASK, sc_stereo_MASK)
# over the frames, divided by the pixels of both eyes. usage: shortcuts_ipp.sh BIN [SCENES]
# (the synthetic scenes work too, but their path tracer runs under valgrind first: an
# hour and more per scene on a loaded 2-core machine)
set -e
bin=$1
scenes=${2:-atrium,gallery}
if ! command -v valgrind >/dev/null 2>&1; then
  echo "bench-shortcuts-ipp: valgrind not found, nothing measured"; exit 0
fi
tmp=$(mktemp -d)
masks="31 30 29 27 23 15 0"
for scene in $(echo "$scenes" | tr ',' ' '); do
  for g in depth full; do
    out="$tmp/cg.$scene.$g"
    valgrind --tool=callgrind --instr-atstart=no --callgrind-out-file="$out" \
      "$bin" --reps 1 --scenes "$scene" --gbuffer "$g" >"$tmp/log" 2>"$tmp/err" ||
      { cat "$tmp/err"; exit 1; }
    # the scene's size and frame count from the program's own header line
    dims=$(sed -n 's/^[a-z-]*, \([0-9]*\)x\([0-9]*\), \([0-9]*\) frames.*/\1 \2 \3/p' "$tmp/log" | head -1)
    set -- $dims
    px=$(( $1 * $2 * 2 * $3 ))
    callgrind_annotate --inclusive=yes "$out" 2>/dev/null >"$tmp/ann"
    printf '%s, G-buffer %s (%s x %s, %s frames, instructions per pixel and eye)\n' "$scene" "$g" "$1" "$2" "$3"
    printf '| build (SBL_SHORTCUTS) | temporal | stereo blend |\n|---|---:|---:|\n'
    for m in $masks; do
      t=$(grep "sc_temporal_$m " "$tmp/ann" | head -1 | awk '{gsub(",", "", $1); print $1}')
      s=$(grep "sc_stereo_$m " "$tmp/ann" | head -1 | awk '{gsub(",", "", $1); print $1}')
      printf '| %s | %.1f | %.1f |\n' "$m" "$(echo "${t:-0} / $px" | bc -l)" "$(echo "${s:-0} / $px" | bc -l)"
    done
    echo
  done
done
rm -rf "$tmp"
