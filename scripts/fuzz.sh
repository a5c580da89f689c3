#!/usr/bin/env bash
# Fuzzes one target for SECONDS with libFuzzer, AddressSanitizer and UndefinedBehaviorSanitizer:
#   bash scripts/fuzz.sh TARGET [SECONDS]     (default 60 s)
# TARGET: scene style mesh_obj mesh_ply mesh_off dv flight_csv ascii_grid (fuzz/<TARGET>_fuzz.cpp).
# Builds the fuzz binaries with clang into $PENINK_FUZZ_BUILD (default build-fuzz/, configured
# with -DPENINK_FUZZ=ON), grows fuzz/corpus/TARGET with the inputs that reach new code, and
# writes any crash, leak, timeout or out-of-memory input to fuzz/findings/TARGET/ (not
# committed: fix the bug, then add the input to the corpus so the replay test keeps it fixed).
# Needs clang (Debian: clang, which brings libFuzzer); the normal build and tests do not.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
target=${1:?usage: fuzz.sh TARGET [SECONDS]}
seconds=${2:-60}
build=${PENINK_FUZZ_BUILD:-$root/build-fuzz}
[ -f "$root/fuzz/${target}_fuzz.cpp" ] || { echo "fuzz.sh: no target $target (fuzz/*_fuzz.cpp)" >&2; exit 2; }
bash "$root/scripts/deps.sh" fuzz
if [ ! -f "$build/CMakeCache.txt" ]; then
  CC=clang CXX=clang++ cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DPENINK_FUZZ=ON
fi
cmake --build "$build" -j"$(nproc)" --target "fuzz_$target"
corpus=$root/fuzz/corpus/$target
findings=$root/fuzz/findings/$target
mkdir -p "$corpus" "$findings"
# -rss_limit_mb: an input that makes a reader take 2 GB is a finding (hostile sizes);
# -timeout: one input running 10 s is one too.
# UndefinedBehaviorSanitizer stops at the first report, but for those fuzz/ubsan.supp lists
# (known, reported, not ours to fix here).
ASAN_OPTIONS=${ASAN_OPTIONS:-detect_leaks=1} \
UBSAN_OPTIONS=${UBSAN_OPTIONS:-halt_on_error=1:print_stacktrace=1:suppressions=$root/fuzz/ubsan.supp} \
  "$build/fuzz_$target" -max_total_time="$seconds" -rss_limit_mb=2048 -timeout=10 -max_len=65536 \
  -artifact_prefix="$findings/" "$corpus"
