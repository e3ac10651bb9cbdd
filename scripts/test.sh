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
# ctest starts the slowest tests first from the times of earlier runs (CTestCostData.txt). A fresh
# clone has none, so the times are also kept beside ccache's cache: only the order of the tests
# depends on them, never what a test does or whether it passes.
costs="${XDG_CACHE_HOME:-$HOME/.cache}/sculpt/ctest-costs-$(basename "$build").txt"
if [ ! -s Testing/Temporary/CTestCostData.txt ] && [ -s "$costs" ]; then
  mkdir -p Testing/Temporary && cp "$costs" Testing/Temporary/CTestCostData.txt
fi
status=0
ctest --output-on-failure -j "$(nproc 2>/dev/null || echo 2)" "${ctest_args[@]}" || status=$?
if [ -s Testing/Temporary/CTestCostData.txt ] && mkdir -p "$(dirname "$costs")" 2> /dev/null; then
  cp Testing/Temporary/CTestCostData.txt "$costs.tmp" && mv "$costs.tmp" "$costs"
fi
exit "$status"
