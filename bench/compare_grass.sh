#!/usr/bin/env bash
# Compares penink's D8 flow directions and accumulation with GRASS GIS `r.watershed -s` (single
# flow direction) on a DEM (default examples/volcano.asc, NZTM EPSG:2193), on the cells that are
# neither flat (they have a strictly lower 8-neighbour in the DEM) nor on the edge (border or next
# to nodata), and times both tools on it.
# Usage: bench/compare_grass.sh [DEM] [EPSG]   env: PENINK=path/to/penink (default build/penink)
# GRASS drainage codes are 1..8 counter-clockwise from north-east (negative: flow leaves the
# region); mapped to ESRI D8: |1|=NE->128, 2=N->64, 3=NW->32, 4=W->16, 5=SW->8, 6=S->4, 7=SE->2,
# 8=E->1. GRASS accumulation is negative where upstream area may lie outside the region: |acc|.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
dem=$(realpath "${1:-$root/examples/volcano.asc}")
epsg=${2:-2193}
penink=${PENINK:-$root/build/penink}
if ! command -v grass >/dev/null; then
    echo "installing grass-core (apt)..." >&2
    DEBIAN_FRONTEND=noninteractive apt-get install -y --no-install-recommends grass-core >&2
fi
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

t0=$(date +%s.%N)
"$penink" drainage "$dem" --resample 1 -o "$tmp/ours.dv" --rasters "$tmp/ours" >"$tmp/penink.log" 2>&1 \
    || { cat "$tmp/penink.log" >&2; exit 1; }
t1=$(date +%s.%N)

cat >"$tmp/inside.sh" <<INSIDE
set -e
r.in.gdal -o --quiet input="$dem" output=dem
g.region raster=dem
s=\$(date +%s.%N)
r.watershed -s --quiet elevation=dem drainage=gdrain accumulation=gacc
e=\$(date +%s.%N)
echo "grass_seconds \$(echo "\$e - \$s" | bc -l)"
r.in.gdal -o --quiet input="$tmp/ours/flow_direction.tif" output=odir
r.in.gdal -o --quiet input="$tmp/ours/accumulation.tif" output=oacc
r.mapcalc --quiet expression="gesri = int(graph(abs(gdrain), 1,128, 2,64, 3,32, 4,16, 5,8, 6,4, 7,2, 8,1))"
r.mapcalc --quiet expression="lower = dem[0,1] < dem || dem[1,1] < dem || dem[1,0] < dem || dem[1,-1] < dem || dem[0,-1] < dem || dem[-1,-1] < dem || dem[-1,0] < dem || dem[-1,1] < dem"
r.mapcalc --quiet expression="inner = !isnull(dem[0,1]) && !isnull(dem[1,1]) && !isnull(dem[1,0]) && !isnull(dem[1,-1]) && !isnull(dem[0,-1]) && !isnull(dem[-1,-1]) && !isnull(dem[-1,0]) && !isnull(dem[-1,1]) && row() > 1 && col() > 1 && row() < nrows() && col() < ncols()"
r.mapcalc --quiet expression="cmp_dir = if(lower && inner, odir == gesri, null())"
r.mapcalc --quiet expression="cmp_acc = if(lower && inner, abs(round(abs(gacc)) - oacc) < 0.5, null())"
r.mapcalc --quiet expression="cmp_acc10 = if(lower && inner, abs(abs(gacc) - oacc) <= 0.1 * abs(gacc), null())"
for m in cmp_dir cmp_acc cmp_acc10; do
    echo "\$m \$(r.univar -g map=\$m | grep -E '^(n|sum)=' | tr '\n' ' ')"
done
INSIDE
grass --tmp-location "EPSG:$epsg" --exec bash "$tmp/inside.sh" >"$tmp/grass.out" 2>"$tmp/grass.err" \
    || { cat "$tmp/grass.err" >&2; exit 1; }

ours=$(echo "$t1 - $t0" | bc -l)
awk -v ours="$ours" '
/^grass_seconds/ { g = $2 }
/^cmp_/ { split($2, a, "="); split($3, b, "="); n[$1] = a[2]; s[$1] = b[2] }
END {
    printf "cells compared (non-flat, non-edge): %d\n", n["cmp_dir"]
    printf "flow direction agreement:          %.2f %%\n", 100 * s["cmp_dir"] / n["cmp_dir"]
    printf "accumulation agreement (exact):    %.2f %%\n", 100 * s["cmp_acc"] / n["cmp_acc"]
    printf "accumulation agreement (<= 10 %%):  %.2f %%\n", 100 * s["cmp_acc10"] / n["cmp_acc10"]
    printf "time: penink drainage %.3f s (whole command), r.watershed -s %.3f s\n", ours, g
}' "$tmp/grass.out"
