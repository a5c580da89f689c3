#!/usr/bin/env bash
# What tapered, weighted strokes cost a render (styles/README.md, "Weight"): for each DEM, the
# wall time of `penink render DEM -o out.svg` (perspective and --map) in the technical style
# against the same style with every layer's taper off and one weight (`[all] taper = 0,
# weight_min = weight_max = 1`: single-width strokes, what was drawn before), measured in one run,
# interleaved, median of REPEAT runs each (default 5); the drainage cache is built first and
# not timed. Prints each time, the ratio and the SVG sizes.
# Usage: bench/stroke_cost.sh [path/to/penink] [DEM...] (default examples/volcano.asc; a 5 x
# refined Jacksboro, not in the repository:
#   gdal_translate -r cubic -outsize 500% 500% -ot Float32 examples/jacksboro.tif /tmp/j5.tif)
set -euo pipefail
cd "$(dirname "$0")/.."
BIN=$(realpath "${1:-build/penink}")
shift || true
DEMS=("$@")
[ ${#DEMS[@]} -gt 0 ] || DEMS=(examples/volcano.asc)
REPEAT=${REPEAT:-5}
TMP=$(mktemp -d)
trap 'rm -rf "$TMP"' EXIT
printf '[all]\ntaper = 0.0\nweight_min = 1.0\nweight_max = 1.0\n' >"$TMP/plain.toml"
median() { sort -n | awk '{a[NR]=$1} END {print a[int((NR+1)/2)]}'; }
printf '%-16s %-12s %10s %10s %7s %11s %11s\n' DEM view "plain s" "tapered s" ratio "plain KB" "tapered KB"
for dem in "${DEMS[@]}"; do
  base=$(basename "$dem")
  cp "$dem" "$TMP/$base"
  for side in prj tfw aux.xml; do [ -e "${dem%.*}.$side" ] && cp "${dem%.*}.$side" "$TMP/" || true; done
  "$BIN" render "$TMP/$base" -o "$TMP/warm.svg" >/dev/null 2>&1  # builds the drainage cache
  for view in "" "--map"; do
    : >"$TMP/plain.t"
    : >"$TMP/tapered.t"
    for _ in $(seq "$REPEAT"); do
      for style in plain technical; do
        s=$style
        [ "$style" = plain ] && s="$TMP/plain.toml"
        t0=$(date +%s.%N)
        # shellcheck disable=SC2086
        "$BIN" render "$TMP/$base" $view --style "$s" -o "$TMP/$style.svg" >/dev/null 2>&1
        t1=$(date +%s.%N)
        echo "$t1 - $t0" | bc >>"$TMP/$([ "$style" = plain ] && echo plain || echo tapered).t"
      done
    done
    p=$(median <"$TMP/plain.t")
    t=$(median <"$TMP/tapered.t")
    printf '%-16s %-12s %10.3f %10.3f %7.2f %11d %11d\n' "$base" "${view:-perspective}" "$p" "$t" "$(echo "$t / $p" | bc -l)" \
      "$(($(stat -c %s "$TMP/plain.svg") / 1024))" "$(($(stat -c %s "$TMP/technical.svg") / 1024))"
  done
done
