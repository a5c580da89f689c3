#!/usr/bin/env bash
# Ranks: wall seconds of `penink fill DEM -o filled.tif` and `penink drainage DEM --resample 1 -o
# x.dv` in one process and under `mpirun --bind-to none -n N` for each N of RANKS, on jacksboro
# refined SIZE percent with GDAL's cubic resampling (default 1000: 13.9 M cells; 2900 is the 117 M
# cells of a 1/3" NED tile), the one-process run measured in the same loop, alternately, best of
# REPEAT runs each. Prints a Markdown table: seconds, the one-process time over the ranks' (above
# 1: the ranks are faster), and whether the ranks wrote the one process's bytes (`cmp`). On one
# machine the ranks share its cores (each takes cores / ranks threads): they pay where they bring
# cores or memory one process does not have, as the nodes of a cluster do.
# Usage: bench/mpi_ranks.sh [path/to/penink] (SIZE=1000, RANKS="2 4", REPEAT=2)
set -euo pipefail
cd "$(dirname "$0")/.."
BIN=$(realpath "${1:-build/penink}")
SIZE=${SIZE:-1000}
RANKS=${RANKS:-2 4}
REPEAT=${REPEAT:-2}
command -v mpirun >/dev/null || { echo "mpi_ranks.sh: needs mpirun (openmpi-bin)" >&2; exit 2; }
command -v gdal_translate >/dev/null || { echo "mpi_ranks.sh: needs gdal_translate (gdal-bin)" >&2; exit 2; }
TMP=$(mktemp -d)
trap 'rm -rf "$TMP"' EXIT
# as root Open MPI asks for both variables; more ranks than cores need --oversubscribe
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
MPIRUN="mpirun --bind-to none --oversubscribe"
gdal_translate -q -r cubic -outsize "$SIZE%" "$SIZE%" -ot Float32 examples/jacksboro.tif "$TMP/dem.tif"

# "seconds" of the best of REPEAT runs of command "$@" (its output to $TMP/out.*)
best() {
  local best_s=""
  for _ in $(seq "$REPEAT"); do
    /usr/bin/time -f "%e" -o "$TMP/time" "$@" >/dev/null 2>"$TMP/log" || { cat "$TMP/log" >&2; exit 1; }
    local s
    s=$(cat "$TMP/time")
    if [ -z "$best_s" ] || awk -v a="$s" -v b="$best_s" 'BEGIN { exit !(a < b) }'; then best_s=$s; fi
  done
  echo "$best_s"
}

echo "machine: $(nproc) cores, $(uptime | sed 's/.*load/load/'); DEM jacksboro ${SIZE}% ($(gdalinfo "$TMP/dem.tif" | grep -m1 'Size is'))"
echo
echo "| command | ranks | s | one process / ranks | same bytes |"
echo "|---|---|---|---|---|"
for cmd in fill drainage; do
  if [ "$cmd" = fill ]; then args=(fill "$TMP/dem.tif" -q -o); ext=tif; else args=(drainage "$TMP/dem.tif" --resample 1 -q -o); ext=dv; fi
  one=$(best "$BIN" "${args[@]}" "$TMP/one.$ext")
  echo "| $cmd | 1 process | $one | 1.00 | |"
  for n in $RANKS; do
    s=$(best $MPIRUN -n "$n" "$BIN" "${args[@]}" "$TMP/ranks.$ext")
    same=no
    cmp -s "$TMP/one.$ext" "$TMP/ranks.$ext" && same=yes
    echo "| $cmd | $n | $s | $(awk -v a="$one" -v b="$s" 'BEGIN { printf "%.2f", a / b }') | $same |"
  done
done
