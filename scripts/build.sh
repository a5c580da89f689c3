#!/usr/bin/env bash
# Configures and builds penink (Release) into build/. Usage: build.sh [TARGET...]
# No target: everything (the program, its raster module, the manual page, every test and
# benchmark). scripts/demo.sh builds only `penink` (which brings its raster module penink_oiio).
set -euo pipefail
cd "$(dirname "$0")/.."
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release >/dev/null
targets=()
for t in "$@"; do targets+=(--target "$t"); done
cmake --build build -j"$(nproc)" "${targets[@]}"
