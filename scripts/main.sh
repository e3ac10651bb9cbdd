#!/usr/bin/env bash
# The main job: install what the sculpt executable needs, build it (Release), then run the goblet
# script (exports a mesh, prints its depth-cost report).
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
build=$("$root/scripts/setup.sh" --target sculpt | tail -n 1)
cd "$root"
exec "$build/sculpt" scripts/goblet.bsp "$@"
