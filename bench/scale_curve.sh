#!/usr/bin/env bash
# Scale: time, peak memory and cache size of one `penink render DEM --width 1000 --height 750 -o
# x.svg` (silhouettes, creases, ridges, hachures; auto-framed camera) against the DEM's size, cold
# (no caches: the terrain cache and the drainage database are built and written) and warm (both
# present), next to the bundled volcano measured in the same run, alternately, so that a slow
# spell of the machine moves both. DEMs: examples/volcano.asc (5 k cells), examples/jacksboro.tif
# (139 k, a geographic DEM projected to UTM) and jacksboro refined with GDAL's cubic resampling
# (`gdal_translate -r cubic -outsize F% F% -ot Float32`) at SIZES percent (default 200 500 1000:
# 0.55 M, 3.5 M, 13.9 M cells). Without gdal-bin, bench/dem_refine.cpp (the same GDAL call) is
# built with the system compiler and gdal-config.
# Prints the machine's load (uptime) and a Markdown table: wall seconds and CPU seconds (user +
# system; steadier than the wall on a shared machine) of one cold run and the best of N warm
# runs, peak resident memory (/usr/bin/time's maximum RSS, MiB) cold and warm, the caches' size on
# disk (MiB: .lod, .dv and the crease tiles the renders wrote, .dv.tiles/), the warm wall and CPU time as multiples of the volcano's,
# and the wall seconds and peak MiB of `penink fill DEM -o filled.tif` (the depression fill read,
# filled and written a band of rows at a time: bounded memory at any size).
# LINES=0: creases and ridges off (a scene file per DEM with `[creases] enabled = false` and
# `[ridges] enabled = false`, the volcano's too): no drainage database is built, so DEMs whose
# drainage build does not fit the memory (a billion cells: SIZES=8500, a 4 GB DEM) are drawn.
# Usage: bench/scale_curve.sh [path/to/penink] (N=3, SIZES="200 500 1000", LINES=1 by default)
set -euo pipefail
cd "$(dirname "$0")/.."
BIN=$(realpath "${1:-build/penink}")
N=${N:-3}
SIZES=${SIZES:-200 500 1000}
LINES=${LINES:-1}
DATA=$(realpath examples)
SRC=$(pwd)
TMP=$(mktemp -d)
trap 'rm -rf "$TMP"' EXIT

cp examples/volcano.asc examples/volcano.prj "$TMP/"
cp "$DATA/jacksboro.tif" "$TMP/jacksboro.tif"
if command -v gdal_translate >/dev/null; then
  refine() { gdal_translate -q -r cubic -outsize "$3%" "$3%" -ot Float32 "$1" "$2"; }
else
  command -v gdal-config >/dev/null || { echo "scale_curve.sh: needs gdal_translate or gdal-config" >&2; exit 2; }
  # shellcheck disable=SC2046
  c++ -O2 -o "$TMP/dem_refine" "$SRC/bench/dem_refine.cpp" $(gdal-config --cflags) $(gdal-config --libs)
  refine() { "$TMP/dem_refine" "$1" "$2" "$3"; }
fi
DEMS="volcano.asc jacksboro.tif"
for f in $SIZES; do
  refine "$DATA/jacksboro.tif" "$TMP/jacksboro_$f.tif" "$f"
  DEMS="$DEMS jacksboro_$f.tif"
done

# What is rendered for DEM $1: the DEM, or with LINES=0 a scene of it without creases and ridges.
input() {
  if [ "$LINES" = 1 ]; then echo "$1"; return; fi
  printf '[terrain]\ndem = "%s"\n[creases]\nenabled = false\n[ridges]\nenabled = false\n' "$1" >"$1.toml"
  echo "$1.toml"
}

# "wall_s cpu_s max_rss_MiB" of one run of DEM $1 with its caches in $TMP/cache-<name>
run() {
  /usr/bin/time -f "%e %U %S %M" -o "$TMP/time" "$BIN" render "$(input "$1")" --width 1000 --height 750 \
    --cache-dir "$TMP/cache-$(basename "$1")" -v -o "$TMP/out.svg" >"$TMP/log" 2>&1
  awk '{printf "%.2f %.2f %.0f\n", $1, $2 + $3, $4 / 1024}' "$TMP/time"
}
min() { awk -v a="$1" -v b="$2" 'BEGIN {print (b < a) ? b : a}'; }

# best warm wall and CPU seconds of N runs of DEM $1 alternated with the volcano;
# "dem_s dem_cpu dem_MiB volcano_s volcano_cpu"
warm() {
  local best=1e9 cbest=1e9 mb=0 vbest=1e9 vcbest=1e9 s c m
  for _ in $(seq "$N"); do
    read -r s c m < <(run "$TMP/volcano.asc")
    vbest=$(min "$vbest" "$s"); vcbest=$(min "$vcbest" "$c")
    read -r s c m < <(run "$1")
    best=$(min "$best" "$s"); cbest=$(min "$cbest" "$c")
    mb=$m
  done
  echo "$best $cbest $mb $vbest $vcbest"
}

echo "machine: $(nproc) cores, $(uptime | sed 's/.*load/load/'); $("$BIN" render "$TMP/volcano.asc" -o "$TMP/v.svg" \
  --cache-dir "$TMP/cache-v" --verbose 2>&1 | grep -m1 -o 'OSMesa.*\|EGL.*')"
echo
echo "| DEM | cells | cold s | cold CPU s | cold peak MiB | warm s | warm CPU s | warm peak MiB | caches MiB | warm / volcano (wall, CPU) | fill s | fill peak MiB |"
echo "|---|---|---|---|---|---|---|---|---|---|---|---|"
for dem in $DEMS; do
  path="$TMP/$dem"
  rm -rf "$TMP/cache-$dem"
  read -r cs cc cm < <(run "$path")
  cells=$(grep -o -m1 'of [0-9]* DEM cells' "$TMP/log" | awk '{print $2}')
  read -r ws wc wm vs vc < <(warm "$path")
  caches=$(du -sb "$TMP/cache-$dem" | awk '{printf "%.0f", $1 / 1048576}')
  /usr/bin/time -f "%e %M" -o "$TMP/time" "$BIN" fill "$path" -o "$TMP/filled.tif" -q
  read -r fs fm < <(awk '{printf "%.2f %.0f\n", $1, $2 / 1024}' "$TMP/time")
  rm -f "$TMP/filled.tif"
  echo "| $dem | $cells | $cs | $cc | $cm | $ws | $wc | $wm | $caches |" \
    "$(awk -v a="$ws" -v b="$vs" -v c="$wc" -v d="$vc" 'BEGIN {printf "%.1f, %.1f", a / b, c / d}') | $fs | $fm |"
done
echo
echo "after: $(uptime | sed 's/.*load/load/')"
