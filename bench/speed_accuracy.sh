#!/usr/bin/env bash
# The speed/accuracy charts of docs/timings.md and the coherence figures, each from `penink bench`:
#  - three analytic terrains (two hills one behind the other, a smooth cliff, a saddle; closed-form
#    reference): --analytic NAME;
#  - examples/volcano.toml (61 x 87 nodes) and jacksboro refined to 3.5 M cells with GDAL's cubic
#    resampling (`gdal_translate -r cubic -outsize 500% 500%`, 2015 x 1720 nodes; never committed),
#    both against the ray-cast reference (4 x 4 rays a pixel); jacksboro with the four methods at
#    the default tolerance, and with the level-of-detail tolerance as an axis (--tolerances);
#  - frame-to-frame coherence along examples/volcano_flight.csv (--flight).
# Every time is the median of FRAMES (>= 5) timed frames with their min-max bar.
# Writes OUT/<name>/{bench.csv,speed_accuracy.svg}, OUT/flight/coherence.csv and copies the charts
# to docs/images/<name>-speed-accuracy.svg when COPY=1.
# Usage: bench/speed_accuracy.sh [path/to/penink] [OUT=bench-out]  (needs gdal-bin)
set -euo pipefail
cd "$(dirname "$0")/.."
BIN=$(realpath "${1:-build/penink}")
OUT=$(realpath -m "${2:-bench-out}")
FRAMES=${FRAMES:-5}
LEVELS=${LEVELS:-1,4}
DATA=$(realpath examples)
TMP=$(mktemp -d)
trap 'rm -rf "$TMP"' EXIT
command -v gdal_translate >/dev/null || { echo "speed_accuracy.sh: needs gdal_translate (apt-get install gdal-bin)" >&2; exit 2; }
mkdir -p "$OUT"
common=(--frames "$FRAMES" --warmup 1 --levels "$LEVELS" -q)

for name in two-hills smooth-cliff saddle; do
  "$BIN" bench --analytic "$name" --out "$OUT/$name" --sizes 500x375 --no-needs "${common[@]}" >"$OUT/$name.txt"
done
"$BIN" bench examples/volcano.toml --out "$OUT/volcano" --sizes 500x375,1000x750 --needs-size 500x375 "${common[@]}" \
  >"$OUT/volcano.txt"

gdal_translate -q -r cubic -outsize 500% 500% -ot Float32 "$DATA/jacksboro.tif" "$TMP/jacksboro5.tif"
printf '[terrain]\ndem = "%s"\nvertical_exaggeration = 3\n' "$TMP/jacksboro5.tif" >"$TMP/j5.toml"
"$BIN" bench "$TMP/j5.toml" --out "$OUT/jacksboro5-tolerance" --sizes 1000x750 --levels 1,4 \
  --tolerances 0.5,1,2,4 --methods toward-away --no-needs --frames "$FRAMES" --warmup 1 -q \
  >"$OUT/jacksboro5-tolerance.txt"

"$BIN" bench "$TMP/j5.toml" --out "$OUT/jacksboro5" --sizes 1000x750 --levels 4 --no-needs \
  --methods toward-away,adjacency,edge-walk,object-space --frames "$FRAMES" --warmup 1 -q >"$OUT/jacksboro5.txt"

"$BIN" bench examples/volcano.toml --flight examples/volcano_flight.csv --out "$OUT/flight" -q >"$OUT/flight.txt"

if [ "${COPY:-0}" = 1 ]; then
  for name in two-hills smooth-cliff saddle volcano jacksboro5 jacksboro5-tolerance; do
    cp "$OUT/$name/speed_accuracy.svg" "docs/images/$name-speed-accuracy.svg"
  done
fi
