#!/usr/bin/env bash
# The primitive cases of tests/bench/bsp/CASES.md (compare.sh's, which runs the npm peers) side by
# side with native Manifold (../shared/peers: C++, its oneTBB backend), issue 33's peer, in one run:
# ours is bench_bsp (SCULPT_THREADS=T), the peer tests/bench/native/manifold_cases.cpp. Both build
# the operands inside the timing and end with the result's mesh.
#   tests/bench/native_cases.sh [--rounds R] [--runs K] [--threads "1 2"] [--case "NAME N"]...
# Defaults: 3 rounds of 5 runs per process, threads 1 and 2, every case. Each (case, threads, side)
# is its own process per round (peak memory from the process); rounds are interleaved, ours then
# the peer, case by case. Prints a Markdown table: medians over the rounds of each process's
# median time, and the largest peak memory. Needs the benchmark build (scripts/bench.sh); builds
# Manifold into build/peers/manifold once.
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)
rounds=3
runs=5
threads="1 2"
cases=()
while (($#)); do
  case "$1" in
    --rounds) rounds="$2"; shift 2 ;;
    --runs) runs="$2"; shift 2 ;;
    --threads) threads="$2"; shift 2 ;;
    --case) cases+=("$2"); shift 2 ;;
    *) echo "native_cases: unknown option $1" >&2; exit 2 ;;
  esac
done
((${#cases[@]})) || cases=("sphere_minus_cube 32" "sphere_minus_cube 64" "sphere_minus_cube 128" "sphere_minus_cube 256"
                         "menger 3" "boxes 1000" "sphere_minus_sphere 32" "sphere_minus_sphere 64"
                         "sphere_minus_sphere 128" "sphere_minus_tilted_cube 64" "drilled_plate 100" "rotated_boxes 200")

ours="$root/build/release/tests/bench/bsp/bench_bsp"
[ -x "$ours" ] || { echo "native_cases: build the benchmarks first (bash scripts/bench.sh)" >&2; exit 1; }
mkdir -p "$root/build/peers"
peer_dir=$(bash "$root/../shared/peers/build_manifold.sh" "$root/build/peers/manifold" 2>"$root/build/peers.log" | tail -n 1)
peer="$root/build/peers/manifold_cases"
if [ ! -x "$peer" ] || [ "$root/tests/bench/native/manifold_cases.cpp" -nt "$peer" ] || [ "$root/tests/bench/peers/cases.hpp" -nt "$peer" ]; then
  g++ -O2 -std=c++20 -I"$peer_dir/include" -I"$root/tests/bench" "$root/tests/bench/native/manifold_cases.cpp" \
    "$peer_dir/lib/libmanifold.a" -ltbb -lpthread -o "$peer"
fi

tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
for ((round = 0; round < rounds; ++round)); do
  for c in "${cases[@]}"; do
    for t in $threads; do
      # shellcheck disable=SC2086
      line=$(SCULPT_THREADS=$t "$ours" $c "$runs") || { echo "native_cases: ours failed on $c" >&2; continue; }
      echo "side=ours threads=$t $line" >> "$tmp/all"
      # shellcheck disable=SC2086
      line=$("$peer" --threads "$t" $c "$runs") || { echo "native_cases: the peer failed on $c" >&2; continue; }
      echo "side=peer $line" >> "$tmp/all"
    done
  done
done

python3 - "$tmp/all" <<'PY'
import sys, statistics, collections
rows = collections.defaultdict(list)
for line in open(sys.argv[1]):
    kv = dict(x.split('=', 1) for x in line.split() if '=' in x)
    rows[(kv['case'], int(kv['n']), int(kv['threads']), kv['side'])].append(kv)
print('| case | n | threads | sculpt (ms) | Manifold (ms) | time sculpt/Manifold | peak MB sculpt / Manifold | memory sculpt/Manifold | volumes sculpt / Manifold |')
print('|---|---|---|---|---|---|---|---|---|')
for (case, n, t, side) in sorted(k for k in rows if k[3] == 'ours'):
    o, p = rows[(case, n, t, 'ours')], rows.get((case, n, t, 'peer'), [])
    ot = statistics.median(float(r['time_ms']) for r in o)
    om = max(float(r['peak_rss_kb']) for r in o) / 1024
    if not p:
        print('| %s | %d | %d | %.1f | failed | | %.0f / - | | |' % (case, n, t, ot, om))
        continue
    pt = statistics.median(float(r['time_ms']) for r in p)
    pm = max(float(r['peak_rss_kb']) for r in p) / 1024
    print('| %s | %d | %d | %.1f | %.1f | %.2fx | %.0f / %.0f | %.1fx | %s / %s |' % (
        case, n, t, ot, pt, ot / pt, om, pm, om / pm, o[0]['volume'], p[0]['volume']))
print()
print('%d rounds; per process the median of its runs; the table: medians over rounds (time), largest (memory).' % len(next(iter(rows.values()))))
PY
