#!/usr/bin/env bash
# Set up, build, and run every test.   scripts/test.sh [--sanitize]
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
build=$("$root/scripts/setup.sh" "$@" | tail -n 1)
cd "$build"
ctest --output-on-failure -j "$(nproc 2>/dev/null || echo 2)"
