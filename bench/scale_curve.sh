#!/usr/bin/env bash
# Scale: time and peak memory of one `penink render DEM --width 1000 --height 750 -o x.svg`
# (silhouettes, creases, ridges; auto-framed camera) against the DEM's size, cold (no caches:
# the terrain cache and the drainage database are built and written) and warm (both present), next to the bundled
# volcano measured in the same run, alternately, so that a slow spell of the machine moves
# both. DEMs: examples/volcano.asc (5 k cells), examples/jacksboro.tif (139 k, a geographic
# DEM projected to UTM) and jacksboro refined with GDAL's cubic resampling (`gdal_translate -r
# cubic -outsize F% F% -ot Float32`) at 200 %, 500 % and 1000 % (0.55 M, 3.5 M, 13.9 M cells).
# Prints a Markdown table: wall seconds (best of N warm runs, one cold run) and peak resident
# memory (/usr/bin/time's maximum RSS), and the warm time as a multiple of the volcano's.
# Usage: bench/scale_curve.sh [path/to/penink] (N=3 by default; needs gdal-bin for gdal_translate)
set -euo pipefail
cd "$(dirname "$0")/.."
BIN=$(realpath "${1:-build/penink}")
N=${N:-3}
DATA=$(realpath examples)
TMP=$(mktemp -d)
trap 'rm -rf "$TMP"' EXIT
command -v gdal_translate >/dev/null || { echo "scale_curve.sh: needs gdal_translate (apt-get install gdal-bin)" >&2; exit 2; }

cp examples/volcano.asc examples/volcano.prj "$TMP/"
cp "$DATA/jacksboro.tif" "$TMP/jacksboro.tif"
for f in 200 500 1000; do
  gdal_translate -q -r cubic -outsize "$f%" "$f%" -ot Float32 "$DATA/jacksboro.tif" "$TMP/jacksboro_$f.tif"
done

# "seconds max_rss_MB" of one run
run() {
  /usr/bin/time -f "%e %M" -o "$TMP/time" "$BIN" render "$1" --width 1000 --height 750 -o "$TMP/out.svg" \
    >/dev/null 2>&1
  awk '{printf "%.3f %.0f\n", $1, $2 / 1024}' "$TMP/time"
}

# best warm seconds of N runs of DEM $1 alternated with the volcano; "dem_s dem_MB volcano_s"
warm() {
  local best=1e9 mb=0 vbest=1e9 s m
  for _ in $(seq "$N"); do
    read -r s m < <(run "$TMP/volcano.asc")
    vbest=$(awk -v a="$vbest" -v b="$s" 'BEGIN {print (b < a) ? b : a}')
    read -r s m < <(run "$1")
    best=$(awk -v a="$best" -v b="$s" 'BEGIN {print (b < a) ? b : a}')
    mb=$m
  done
  echo "$best $mb $vbest"
}

echo "machine: $(nproc) cores; $("$BIN" render "$TMP/volcano.asc" -o "$TMP/v.svg" --verbose 2>&1 | grep -m1 -o 'OSMesa.*\|EGL.*')"
echo
echo "| DEM | cells | cold s | cold peak MB | warm s | warm peak MB | warm / volcano |"
echo "|---|---|---|---|---|---|---|"
for dem in volcano.asc jacksboro.tif jacksboro_200.tif jacksboro_500.tif jacksboro_1000.tif; do
  path="$TMP/$dem"
  cells=$(gdalinfo "$path" 2>/dev/null | awk '/^Size is/ {gsub(",", ""); print ($3 - 1) * ($4 - 1)}')
  rm -f "$path.dv" "$path.lod"
  read -r cs cm < <(run "$path")
  read -r ws wm vs < <(warm "$path")
  echo "| $dem | $cells | $cs | $cm | $ws | $wm | $(awk -v a="$ws" -v b="$vs" 'BEGIN {printf "%.2f", a / b}') |"
done
