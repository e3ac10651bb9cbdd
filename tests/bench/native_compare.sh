#!/usr/bin/env bash
# Side by side with native Manifold (../shared/peers: C++, its oneTBB backend) in one run: the
# real-mesh job of issue 33 (import, a general turn, the union with the turned copy, the difference
# with a sphere; tests/bench/bsp/bench_mesh_job.cpp) and sphere(1, N) - moved copy.
#   tests/bench/native_compare.sh [--runs R] [--threads "1 2"] [--mesh FILE.off]... [--real-meshes] [--sphere N]...
#                                 [--moved-copy FILE.off]... [--sphere-matched N]...
# --moved-copy: the mesh minus a copy moved by a tenth of its box's size (bench_mesh_job --moved-copy;
# issue 33's 10^6-triangle case: tests/bench/meshes/loop_subdivide.py models/bunny.off 4 OUT.off).
# --real-meshes adds eight real closed meshes of 5k-89k triangles (CGAL's data set, downloaded once
# into build/meshes/cgal by tests/bench/meshes/cgal_meshes.sh).
# --sphere-matched: ours sphere(1, N) - moved copy against Manifold's with the segment count that
# gives its sphere as many triangles (round(N sqrt 2) to a multiple of 4): our sphere(1, N) has
# N rings of N segments' quads (N^2 triangles, as OpenSCAD's), Manifold's Sphere(1, N) a subdivided
# octahedron of N^2 / 2 triangles with edges as long, so --sphere compares inputs of twice the size.
# Defaults: 5 runs, threads 1 and 2, models/bunny.off, spheres 128 256 512. Each run is its own
# process (peak memory from /usr/bin/time); rounds are interleaved (ours, then the peer, case by
# case) so a change in the machine's speed falls on both. Prints a Markdown table of medians, with
# each side's peak memory per triangle of its output mesh.
# Needs the benchmark build (scripts/bench.sh); builds Manifold into build/peers/manifold once.
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)
runs=5
threads="1 2"
meshes=()
moved=()
spheres=()
matched=()
while (($#)); do
  case "$1" in
    --runs) runs="$2"; shift 2 ;;
    --threads) threads="$2"; shift 2 ;;
    --mesh) meshes+=("$2"); shift 2 ;;
    --sphere) spheres+=("$2"); shift 2 ;;
    --sphere-matched) matched+=("$2"); shift 2 ;;
    --moved-copy) moved+=("$2"); shift 2 ;;
    --real-meshes)
      mapfile -t found < <(bash "$root/tests/bench/meshes/cgal_meshes.sh" "$root/build/meshes/cgal")
      meshes+=("${found[@]}")
      shift ;;
    *) echo "native_compare: unknown option $1" >&2; exit 2 ;;
  esac
done
((${#meshes[@]} + ${#spheres[@]} + ${#moved[@]} + ${#matched[@]})) || { meshes=("$root/models/bunny.off"); spheres=(128 256 512); }

ours="$root/build/release/tests/bench/bsp/bench_mesh_job"
[ -x "$ours" ] || { echo "native_compare: build the benchmarks first (bash scripts/bench.sh)" >&2; exit 1; }
[ -x /usr/bin/time ] || { echo "native_compare: needs /usr/bin/time (Debian package time)" >&2; exit 1; }
peer_dir=$(bash "$root/../shared/peers/build_manifold.sh" "$root/build/peers/manifold" 2>"$root/build/peers.log" | tail -n 1)
peer="$root/build/peers/manifold_job"
if [ ! -x "$peer" ] || [ "$root/tests/bench/native/manifold_job.cpp" -nt "$peer" ]; then
  g++ -O2 -std=c++17 -I"$peer_dir/include" "$root/tests/bench/native/manifold_job.cpp" "$peer_dir/lib/libmanifold.a" \
    -ltbb -lpthread -o "$peer"
fi

tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
jobs=()       # our arguments
peer_jobs=()  # the peer's (the same but for --sphere-matched)
for m in "${meshes[@]}"; do jobs+=("--mesh $m"); peer_jobs+=("--mesh $m"); done
for m in "${moved[@]}"; do jobs+=("--moved-copy --mesh $m"); peer_jobs+=("--moved-copy --mesh $m"); done
for n in "${spheres[@]}"; do jobs+=("--sphere $n"); peer_jobs+=("--sphere $n"); done
for n in "${matched[@]}"; do
  jobs+=("--sphere $n")
  peer_jobs+=("--sphere $(python3 -c "print(4 * round($n * 2 ** 0.5 / 4))")")
done
for ((round = 0; round < runs; ++round)); do
  for j in "${!jobs[@]}"; do
    for t in $threads; do
      for side in ours peer; do
        program=$ours job=${jobs[$j]}
        [ $side = peer ] && program=$peer job=${peer_jobs[$j]}
        # shellcheck disable=SC2086
        /usr/bin/time -f "peak_kb=%M" -o "$tmp/time" "$program" --threads "$t" $job > "$tmp/line" ||
          { echo "native_compare: $side failed on $job" >&2; cat "$tmp/line" >&2; continue; }
        echo "side=$side job=$j $(cat "$tmp/line") $(tail -n 1 "$tmp/time")" >> "$tmp/all"
      done
    done
  done
done

python3 - "$tmp/all" <<'PY'
import sys, statistics, collections
rows = collections.defaultdict(list)
for line in open(sys.argv[1]):
    kv = dict(x.split('=', 1) for x in line.split() if '=' in x)
    rows[(int(kv['job']), int(kv['threads']), kv['side'])].append(kv)
def med(rs, k): return statistics.median(float(r[k]) for r in rs)
print('| case | n | threads | sculpt import / turn / union / difference (s) | sculpt total (s) | Manifold total (s) | time sculpt/Manifold | peak MB sculpt / Manifold | memory sculpt/Manifold | output triangles sculpt / Manifold | peak bytes per output triangle sculpt / Manifold | volumes |')
print('|---|---|---|---|---|---|---|---|---|---|---|---|')
# The process's peak divided by the triangles of the result's mesh (each side's own count).
def per_triangle(rs): return med(rs, 'peak_kb') * 1024 / max(1.0, med(rs, 'triangles_out'))
for (j, t, side) in sorted(k for k in rows if k[2] == 'ours'):
    o, p = rows[(j, t, 'ours')], rows.get((j, t, 'peer'), [])
    case, n = o[0]['case'], int(o[0]['n'])
    if p and int(p[0]['n']) != n: case += ' (Manifold n=%s)' % p[0]['n']
    phases = ' / '.join('%.3f' % med(o, k) for k in ('import', 'turn', 'union', 'difference'))
    ot, om = med(o, 'total'), med(o, 'peak_kb') / 1024
    if p:
        pt, pm = med(p, 'total'), med(p, 'peak_kb') / 1024
        print('| %s | %d | %d | %s | %.3f | %.3f | %.1fx | %.0f / %.0f | %.1fx | %d / %d | %.0f / %.0f | %s / %s |' % (
            case, n, t, phases, ot, pt, ot / pt, om, pm, om / pm, med(o, 'triangles_out'), med(p, 'triangles_out'),
            per_triangle(o), per_triangle(p), o[0]['volume'], p[0]['volume']))
    else:
        print('| %s | %d | %d | %s | %.3f | failed | | %.0f / - | | %d / - | %.0f / - | %s |' % (
            case, n, t, phases, ot, om, med(o, 'triangles_out'), per_triangle(o), o[0]['volume']))
print()
print('%d runs each, medians; times are wall clock of the whole job in one process.' % len(next(iter(rows.values()))))
PY
