#!/usr/bin/env bash
# Peer benchmarks: manifold-3d (WASM) and @jscad/modeling on the BSP cases of
# tests/bench/bsp/CASES.md. Installs the pinned packages into tests/bench/peers/node_modules
# on first use (npm; never committed), then prints one "bench key=value ..." line per case.
#   tests/bench/peers/run.sh [--impl manifold|jscad] [--case NAME] [--n N] [--runs R] [--budget-ms B] [--timeout S]
# --case / --n: only the cases of that name / that size.
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
impls=(manifold jscad)
only_case=""
only_n=""
runs=7
budget=30000
timeout_s=600
while (($#)); do
  case "$1" in
    --impl) impls=("$2"); shift 2 ;;
    --case) only_case="$2"; shift 2 ;;
    --n) only_n="$2"; shift 2 ;;
    --runs) runs="$2"; shift 2 ;;
    --budget-ms) budget="$2"; shift 2 ;;
    --timeout) timeout_s="$2"; shift 2 ;;
    *) echo "run.sh: unknown option '$1'" >&2; exit 2 ;;
  esac
done

command -v node >/dev/null || { echo "run.sh: node is not installed (apt-get install nodejs npm)" >&2; exit 1; }
if [ ! -d "$here/node_modules/manifold-3d" ] || [ ! -d "$here/node_modules/@jscad/modeling" ]; then
  echo "run.sh: installing the peers (npm install in $here)" >&2
  (cd "$here" && npm install --no-audit --no-fund --loglevel=error >&2)
fi
echo "# node $(node --version), manifold-3d $(node -p "require('$here/node_modules/manifold-3d/package.json').version")," \
     "@jscad/modeling $(node -p "require('$here/node_modules/@jscad/modeling/package.json').version"), $(nproc) cores"

node "$here/selftest.mjs"

cases=("sphere_minus_cube 32" "sphere_minus_cube 64" "sphere_minus_cube 128" "sphere_minus_cube 256"
       "menger 3" "boxes 1000" "sphere_minus_sphere 32" "sphere_minus_sphere 64" "sphere_minus_sphere 128"
       "sphere_minus_tilted_cube 64" "drilled_plate 100" "rotated_boxes 200")
for impl in "${impls[@]}"; do
  for c in "${cases[@]}"; do
    set -- $c
    [ -n "$only_case" ] && [ "$only_case" != "$1" ] && continue
    [ -n "$only_n" ] && [ "$only_n" != "$2" ] && continue
    # One process per case, so that peak_rss_kb belongs to that case alone.
    if ! (cd "$here" && timeout "$timeout_s" node peer.mjs "$impl" "$1" "$2" --runs "$runs" --budget-ms "$budget"); then
      echo "bench impl=$impl case=$1 n=$2 status=failed_or_timeout timeout_s=$timeout_s"
    fi
  done
done
