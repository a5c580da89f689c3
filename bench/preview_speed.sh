#!/usr/bin/env bash
# Preview frame times against the targets, in one run: build/preview_frames_bench (the preview's
# drawing thread without a browser: bench/preview_frames_bench.cpp) on examples/volcano.asc
# (full frame target 0.5 s) and on jacksboro refined 5x (3.5 M cells, target 2 s), drag frames
# 0.5 s. The refined DEM is made with `gdal_translate -r cubic -outsize 500% 500% -ot Float32`
# into a private folder, or taken from $J5 when set (the caches of both are built by an untimed
# first run, in the private folder). Prints ratios (wall median / target) with the machine's
# load; no limit is asserted. Usage: bench/preview_speed.sh [path/to/preview_frames_bench]
# (RUNS=5 frames of each kind by default).
set -euo pipefail
cd "$(dirname "$0")/.."
BIN=$(realpath "${1:-build/preview_frames_bench}")
RUNS=${RUNS:-5}
TMP=$(mktemp -d)
trap 'rm -rf "$TMP"' EXIT
cp examples/volcano.asc examples/volcano.prj "$TMP/"
if [ -n "${J5:-}" ]; then
  cp "$J5" "$TMP/j5.tif"
elif command -v gdal_translate >/dev/null; then
  gdal_translate -q -r cubic -outsize 500% 500% -ot Float32 examples/jacksboro.tif "$TMP/j5.tif"
else
  echo "gdal_translate is not installed: set J5 to jacksboro refined 5x" >&2
  exit 2
fi
echo "machine: $(nproc) cores; $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2-)"
# untimed: the terrain caches and drainage databases built
"$BIN" --runs 1 --cache-dir "$TMP/cache" "$TMP/volcano.asc" 0.5 "$TMP/j5.tif" 2 >/dev/null
"$BIN" --runs "$RUNS" --cache-dir "$TMP/cache" "$TMP/volcano.asc" 0.5 "$TMP/j5.tif" 2
