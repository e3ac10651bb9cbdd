#!/usr/bin/env bash
# Set up, build and run every test.   scripts/test.sh [--sanitize] [--werror] [ctest options...]
#   --sanitize  in the ASan + UBSan build (build/sanitize); --werror: warnings are errors (CI)
#   other options go to ctest, e.g. -R mesh (only tests whose names match) or --rerun-failed
# Tests run in parallel, one per core; ctest starts the slowest first from the times it kept in earlier runs.
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
setup_args=(--tests) ctest_args=()
for a in "$@"; do
  case "$a" in
    --sanitize|--werror) setup_args+=("$a") ;;
    *) ctest_args+=("$a") ;;
  esac
done
build=$("$root/scripts/setup.sh" "${setup_args[@]}" | tail -n 1)
cd "$build"
ctest --output-on-failure -j "$(nproc 2>/dev/null || echo 2)" "${ctest_args[@]}"
