#!/usr/bin/env bash
# Builds the GL-free unit tests (tests/{core,input,surface,drainage,lines,export}) with
# AddressSanitizer and UndefinedBehaviorSanitizer into build-sanitize/ (-O1: the sanitizers'
# usual level, and a quicker build on 2 cores) and runs them; any report fails the run.
# The GL tests (render, scene, cli) stay out: Mesa's llvmpipe is not built with the sanitizers.
# Usage: scripts/sanitize.sh   (after scripts/deps.sh; .ci/run calls it before the suite)
set -euo pipefail
cd "$(dirname "$0")/.."
folders=(core input surface drainage lines export)
cmake -S . -B build-sanitize -DCMAKE_BUILD_TYPE=None -DCMAKE_CXX_FLAGS="-O1 -g1" \
      -DPENINK_SANITIZE=address,undefined >/dev/null
targets=(--target penink_oiio)
for f in "${folders[@]}"; do targets+=(--target "test_$f"); done
cmake --build build-sanitize -j"$(nproc)" "${targets[@]}"
export ASAN_OPTIONS=detect_leaks=1:abort_on_error=0:halt_on_error=1
export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
export PENINK_SOURCE_DIR=$PWD
failed=0
for f in "${folders[@]}"; do
  (cd build-sanitize && "./test_$f" --gtest_brief=1) >"build-sanitize/test_$f.log" 2>&1 || {
    failed=1; echo "penink: sanitize: test_$f failed:"; tail -n 40 "build-sanitize/test_$f.log"; }
  echo "sanitized test_$f: $(grep -E '^\[  PASSED  \]' "build-sanitize/test_$f.log" || echo 'not passed')"
done
exit $failed
