#!/usr/bin/env bash
# Speed target: the whole process `penink render examples/volcano.toml` at
# 1000x1000 with silhouettes, creases and ridges (drainage cache examples/volcano.asc.dv present),
# wall time per run (median and min of N runs, warm shader cache after the first), next to the
# process start-up alone (`penink --help`) and the shared libraries it loads. Then one -v run for
# the per-pass times. Usage: bench/speed_target.sh [path/to/penink] (N=10 by default).
set -euo pipefail
cd "$(dirname "$0")/.."
BIN=$(realpath "${1:-build-batchbench/penink}")
N=${N:-10}
TMP=$(mktemp -d)
trap 'rm -rf "$TMP"' EXIT

# median and min wall seconds of N runs of a command (output discarded)
wall() {
  local label=$1; shift
  "$@" >/dev/null 2>&1 || { echo "$label: command failed: $*" >&2; return 1; }  # untimed first run
  for _ in $(seq "$N"); do
    local s e
    s=$(date +%s%N); "$@" >/dev/null 2>&1; e=$(date +%s%N)
    echo $(( (e - s) / 1000 ))
  done | sort -n | awk -v l="$label" '{v[NR]=$1} END {printf "%-44s median %6.3f s  min %6.3f s  (%d runs)\n", l, v[int((NR+1)/2)]/1e6, v[1]/1e6, NR}'
}

# A private copy of the example, so its drainage cache (volcano.asc.dv) is built once by the
# untimed first run and not rewritten by other penink processes meanwhile.
cp examples/volcano.toml examples/volcano.asc examples/volcano.prj "$TMP/"
SCENE=$TMP/volcano.toml
SIZE=(--width 1000 --height 1000)
echo "machine: $(nproc) cores; $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2-)"
echo "shared libraries loaded by penink: $(LD_TRACE_LOADED_OBJECTS=1 "$BIN" | wc -l)"
wall "start-up: penink --help" "$BIN" --help
wall "render 1000x1000 -> svg" "$BIN" render "$SCENE" "${SIZE[@]}" -o "$TMP/v.svg"
wall "render 1000x1000 -> png" "$BIN" render "$SCENE" "${SIZE[@]}" -o "$TMP/v.png"
wall "render 1000x1000 -> svg + png" "$BIN" render "$SCENE" "${SIZE[@]}" -o "$TMP/v.svg" -o "$TMP/v.png"
echo "per-pass times of one run (-v):"
"$BIN" render "$SCENE" "${SIZE[@]}" -o "$TMP/v.svg" -v 2>&1 | sed 's/^/  /'
