#!/usr/bin/env bash
# Builds the benchmark programs (tests/bench, Release, build/release) and lists them; the test
# command does not build them. docs/benchmarks.md says how each is run and what it measured.
#   scripts/bench.sh [--werror]
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
build=$("$root/scripts/setup.sh" --tests --bench "$@" | tail -n 1)
echo "benchmark programs in $build/tests/bench:"
find "$build/tests/bench" -maxdepth 2 -type f -executable -printf '  %P\n' | sort
