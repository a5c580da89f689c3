#!/usr/bin/env bash
# Installs, builds everything (the program, the tests, the benchmarks, the manual page) and
# runs the whole test suite (ctest).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/check_standalone.sh   # the project carries every file it reads
bash scripts/deps.sh test
bash scripts/build.sh
cd build && ctest --output-on-failure -j"$(nproc)"
