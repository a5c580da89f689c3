#!/usr/bin/env bash
# CTest Scripts.DemoBuildsOnlyWhatItRuns. Usage: demo_build_test.sh SOURCE_DIR BUILD_DIR
# scripts/demo.sh builds the target `penink` alone; this checks that it does so, and that the
# target (from scratch: make's dry run with -B) compiles the program and its raster and MPI modules and
# no test, test support, fuzz or benchmark source, while the whole build (scripts/test.sh)
# compiles those too.
set -euo pipefail
src=$1 build=$2
fail() { echo "FAIL: $*" >&2; exit 1; }
grep -qx 'bash scripts/build.sh penink' "$src/scripts/demo.sh" || fail "demo.sh does not build the target penink alone"
grep -qx 'bash scripts/build.sh' "$src/scripts/test.sh" || fail "test.sh does not build everything"
program=$(make -C "$build" -n -B penink 2>/dev/null | grep -oE '[^ ]+\.cpp\.o' | sort -u)
all=$(make -C "$build" -n -B all 2>/dev/null | grep -oE '[^ ]+\.cpp\.o' | sort -u)
grep -q 'penink_oiio.cpp.o' <<<"$program" || fail "the target penink does not build the raster module"
grep -q 'penink_mpi.cpp.o' <<<"$program" || fail "the target penink does not build the MPI module"
grep -q 'src/cli/main.cpp.o' <<<"$program" || fail "the target penink does not build main.cpp"
! grep -qE '(tests|fuzz|bench)/' <<<"$program" || fail "the target penink builds $(grep -E '(tests|fuzz|bench)/' <<<"$program" | head -1)"
grep -q 'tests/cli/' <<<"$all" || fail "the whole build does not build the tests"
echo "demo build: $(wc -l <<<"$program") objects; whole build: $(wc -l <<<"$all")"
