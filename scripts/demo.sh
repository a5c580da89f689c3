#!/usr/bin/env bash
# Installs, builds the program alone (not the tests: scripts/test.sh builds those) and renders
# the bundled example DEM to out/example.{svg,ps,pdf,png}.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/deps.sh
bash scripts/build.sh penink
mkdir -p out
./build/penink render examples/volcano.toml \
  -o out/example.svg -o out/example.ps -o out/example.pdf -o out/example.png --verbose
