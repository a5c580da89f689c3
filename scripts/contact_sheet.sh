#!/usr/bin/env bash
# A contact sheet (one PNG) of frames: `contact_sheet.sh OUT.png COLUMNS WIDTH FRAME:LABEL...`.
# Each FRAME (a PNG, e.g. from `penink batch`) is scaled to WIDTH pixels wide and laid out in
# COLUMNS columns, left to right, top to bottom, with LABEL printed under it; the frames go into an
# SVG as data URIs and librsvg's rsvg-convert (Debian librsvg2-bin, already in scripts/deps.sh)
# draws the sheet. Example: docs/reproduction.md (Figures 15 and 16).
set -euo pipefail
if [ $# -lt 4 ]; then
  echo "usage: contact_sheet.sh OUT.png COLUMNS WIDTH FRAME.png:LABEL..." >&2
  exit 2
fi
out=$1 cols=$2 width=$3
shift 3
first=${1%%:*}
# Frame size from the PNG header (bytes 16-23: width, height, big-endian).
read -r fw fh < <(od -An -tu1 -j16 -N8 "$first" | awk '{print $1*16777216+$2*65536+$3*256+$4, $5*16777216+$6*65536+$7*256+$8}')
height=$(( width * fh / fw ))
label_h=18
n=$#
rows=$(( (n + cols - 1) / cols ))
sheet_w=$(( cols * width ))
sheet_h=$(( rows * (height + label_h) ))
svg=$(mktemp --suffix=.svg)
trap 'rm -f "$svg"' EXIT
{
  echo "<svg xmlns=\"http://www.w3.org/2000/svg\" xmlns:xlink=\"http://www.w3.org/1999/xlink\" width=\"$sheet_w\" height=\"$sheet_h\">"
  echo "<rect width=\"100%\" height=\"100%\" fill=\"#ffffff\"/>"
  i=0
  for item in "$@"; do
    frame=${item%%:*} label=${item#*:}
    x=$(( (i % cols) * width )) y=$(( (i / cols) * (height + label_h) ))
    echo "<image x=\"$x\" y=\"$y\" width=\"$width\" height=\"$height\" xlink:href=\"data:image/png;base64,$(base64 -w0 "$frame")\"/>"
    echo "<rect x=\"$x\" y=\"$y\" width=\"$width\" height=\"$height\" fill=\"none\" stroke=\"#999999\"/>"
    echo "<text x=\"$(( x + width / 2 ))\" y=\"$(( y + height + label_h - 5 ))\" font-family=\"sans-serif\" font-size=\"13\" text-anchor=\"middle\">$label</text>"
    i=$(( i + 1 ))
  done
  echo "</svg>"
} > "$svg"
rsvg-convert -o "$out" "$svg"
