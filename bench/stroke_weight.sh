#!/usr/bin/env bash
# Stroke weight (styles/README.md, "Weight"): per layer, the length-weighted mean width and CV of
# the widths, the share of paths tapered at both ends and the silhouette / crease width ratio, as
# `penink render -v` prints them, for the volcano and Jacksboro (perspective and plan view) in
# the technical and field-sketch styles; then the doubled silhouette length of each view.
# Usage: bench/stroke_weight.sh [path/to/penink]
set -euo pipefail
cd "$(dirname "$0")/.."
BIN=$(realpath "${1:-build/penink}")
TMP=$(mktemp -d)
trap 'rm -rf "$TMP"' EXIT
cp examples/volcano.toml examples/volcano.asc examples/volcano.prj examples/jacksboro.tif examples/jacksboro_panorama.toml "$TMP/"
for style in technical field-sketch; do
  for view in "volcano.toml" "volcano.toml --map" "jacksboro.tif --vertical-exaggeration 3" "jacksboro.tif --map" "jacksboro_panorama.toml"; do
    echo "== $view, $style"
    # shellcheck disable=SC2086
    "$BIN" render "$TMP"/$view --style "$style" -o "$TMP/out.svg" -v 2>&1 |
      grep -E "(ridges|creases|silhouettes): [0-9]+ paths|width ratio|silhouettes: .* % doubled" | sed 's/^penink: /  /'
  done
done
