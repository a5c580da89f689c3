#!/usr/bin/env bash
# Fails when any tracked file names the folder beside a developer's checkout ("../shared"): a
# user's clone has none, so the project must carry every file its tests, examples, benchmarks and
# README read. Binary files are searched too (a PNG's metadata can hold the path of its source).
set -euo pipefail
cd "$(dirname "$0")/.."
pattern='\.\./shared'
if hits=$(git grep -n -a -E "$pattern" -- . ':!scripts/check_standalone.sh' 2>/dev/null); then
  echo "penink: check: these files refer to ../shared, which a user's clone does not have:" >&2
  printf '%s\n' "$hits" | cut -c1-200 >&2
  exit 1
fi
