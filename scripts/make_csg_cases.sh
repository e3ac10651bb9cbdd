#!/usr/bin/env bash
# Regenerates models/fuzz/csg_cases.txt: seeded random set operations over transformed primitives
# with manifold-3d's volumes (tests/bench/peers/csg_fuzz.mjs; installs the peers with npm).
#   scripts/make_csg_cases.sh [--count N] [--seed S] [--out FILE]
# A larger run, once:  scripts/make_csg_cases.sh --count 3000 --seed 7 --out /tmp/cases.txt
#   SCULPT_CSG_CASES=/tmp/cases.txt build/release/tests/language/test_language --gtest_filter='CleanOutput.*'
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
peers="$root/tests/bench/peers"
count=300 seed=1 out="$root/models/fuzz/csg_cases.txt"
while (($#)); do
  case "$1" in
    --count) count="$2"; shift 2 ;;
    --seed) seed="$2"; shift 2 ;;
    --out) out="$2"; shift 2 ;;
    *) echo "make_csg_cases.sh: unknown option '$1'" >&2; exit 2 ;;
  esac
done
command -v node >/dev/null || { echo "make_csg_cases.sh: node is not installed (apt-get install nodejs npm)" >&2; exit 1; }
[ -d "$peers/node_modules/manifold-3d" ] || (cd "$peers" && npm install --no-audit --no-fund --loglevel=error >&2)
mkdir -p "$(dirname "$out")"
node "$peers/csg_fuzz.mjs" --count "$count" --seed "$seed" > "$out.tmp"
mv "$out.tmp" "$out"
echo "wrote $out" >&2
