#!/usr/bin/env bash
# Issue 33's stroke into a workpiece of 10^6 triangles, side by side with native Manifold
# (../shared/peers) in one run: ours is bench_sculpt --sphere-workpiece (sphere(1, 1000), 999,996
# triangles; in-place strokes on one thread: thread CPU per stroke), the peer
# tests/bench/native/manifold_stroke.cpp (Sphere(1, 1414), 1,002,528 triangles; wall clock per
# stroke, with THREADS threads). Both carve the same 20-segment arcs with the same ball.
#   tests/bench/native_stroke.sh [--rounds R] [--strokes S] [--threads "1 2"]
# Prints each side's median stroke per round. Needs the benchmark build (scripts/bench.sh).
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)
rounds=3
strokes=30
threads="1 2"
while (($#)); do
  case "$1" in
    --rounds) rounds="$2"; shift 2 ;;
    --strokes) strokes="$2"; shift 2 ;;
    --threads) threads="$2"; shift 2 ;;
    *) echo "native_stroke: unknown option $1" >&2; exit 2 ;;
  esac
done
ours="$root/build/release/tests/bench/bsp/bench_sculpt"
[ -x "$ours" ] || { echo "native_stroke: build the benchmarks first (bash scripts/bench.sh)" >&2; exit 1; }
mkdir -p "$root/build/peers"
peer_dir=$(bash "$root/../shared/peers/build_manifold.sh" "$root/build/peers/manifold" 2>"$root/build/peers.log" | tail -n 1)
peer="$root/build/peers/manifold_stroke"
if [ ! -x "$peer" ] || [ "$root/tests/bench/native/manifold_stroke.cpp" -nt "$peer" ]; then
  g++ -O2 -std=c++17 -I"$peer_dir/include" "$root/tests/bench/native/manifold_stroke.cpp" "$peer_dir/lib/libmanifold.a" \
    -ltbb -lpthread -o "$peer"
fi
for ((round = 1; round <= rounds; ++round)); do
  line=$("$ours" --sphere-workpiece 1000 --strokes "$strokes" | grep "case=strokes")
  echo "round $round sculpt: $(echo "$line" | grep -o 'median_cpu_ms=[0-9.]*\|max_cpu_ms=[0-9.]*' | tr '\n' ' ')"
  for t in $threads; do
    line=$("$peer" 1414 "$strokes" "$t")
    echo "round $round Manifold threads=$t: $(echo "$line" | grep -o 'median_ms=[0-9.]*\|max_ms=[0-9.]*' | tr '\n' ' ')"
  done
done
