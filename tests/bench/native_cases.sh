#!/usr/bin/env bash
# The primitive cases of tests/bench/bsp/CASES.md (compare.sh's, which runs the npm peers) side by
# side with native Manifold (../shared/peers: C++, its oneTBB backend), issue 33's peer, in one run:
# ours is bench_bsp (SCULPT_THREADS=T), the peer tests/bench/native/manifold_cases.cpp. Both build
# the operands inside the timing and end with the result's mesh.
#   tests/bench/native_cases.sh [--rounds R] [--runs K] [--threads "1 2"] [--case "NAME N"]... [--matched]
# --matched: in the sphere cases the peer's sphere gets round(N sqrt 2) segments (to a multiple of
# 4), as many triangles as our sphere(1, N) (N^2; Manifold's Sphere(1, N) has N^2 / 2, with edges as
# long: native_compare.sh --sphere-matched); the table names the peer's N.
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
matched=0
while (($#)); do
  case "$1" in
    --rounds) rounds="$2"; shift 2 ;;
    --runs) runs="$2"; shift 2 ;;
    --threads) threads="$2"; shift 2 ;;
    --case) cases+=("$2"); shift 2 ;;
    --matched) matched=1; shift ;;
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
  for j in "${!cases[@]}"; do
    c=${cases[$j]} peer_case=${cases[$j]}
    if ((matched)) && [[ $c == sphere_* ]]; then
      read -r name n <<< "$c"
      peer_case="$name $(python3 -c "print(4 * round($n * 2 ** 0.5 / 4))")"
    fi
    for t in $threads; do
      # shellcheck disable=SC2086
      line=$(SCULPT_THREADS=$t "$ours" $c "$runs") || { echo "native_cases: ours failed on $c" >&2; continue; }
      echo "side=ours job=$j threads=$t $line" >> "$tmp/all"
      # shellcheck disable=SC2086
      line=$("$peer" --threads "$t" $peer_case "$runs") || { echo "native_cases: the peer failed on $peer_case" >&2; continue; }
      echo "side=peer job=$j $line" >> "$tmp/all"
    done
  done
done

python3 - "$tmp/all" <<'PY'
import sys, statistics, collections
rows = collections.defaultdict(list)
for line in open(sys.argv[1]):
    kv = dict(x.split('=', 1) for x in line.split() if '=' in x)
    rows[(int(kv['job']), int(kv['threads']), kv['side'])].append(kv)
print('| case | n | threads | sculpt (ms) | Manifold (ms) | time sculpt/Manifold | peak MB sculpt / Manifold | memory sculpt/Manifold | volumes sculpt / Manifold |')
print('|---|---|---|---|---|---|---|---|---|')
for (j, t, side) in sorted(k for k in rows if k[2] == 'ours'):
    o, p = rows[(j, t, 'ours')], rows.get((j, t, 'peer'), [])
    case, n = o[0]['case'], int(o[0]['n'])
    if p and int(p[0]['n']) != n: case += ' (Manifold n=%s)' % p[0]['n']
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
