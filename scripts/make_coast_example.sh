#!/bin/sh
# Makes examples/coast.asc + coast.prj: a 180 x 140 node window of the Jacksboro DEM
# (examples/jacksboro.tif: USGS, 3 arc-second cells, WGS84; see examples/README.md) around
# the Powell valley south-east of the Cumberland escarpment, whose valley floor (236 m) lies
# below the 350 m sea level examples/coast.toml sets: a drowned valley coast under a mountain front.
# Usage: scripts/make_coast_example.sh [path/to/jacksboro.tif]   (needs gdal-bin)
set -eu
here=$(cd "$(dirname "$0")/.." && pwd)
src=${1:-$here/examples/jacksboro.tif}
gdal_translate -q -of AAIGrid -srcwin 200 170 180 140 "$src" "$here/examples/coast.asc"
rm -f "$here/examples/coast.asc.aux.xml"
