#!/usr/bin/env bash
# Real closed meshes of 5k-89k triangles that nobody here made: the data set shipped with CGAL's
# demos (Debian's libcgal-demo, data.tar.gz: scanned and modelled surfaces from public
# repositories). The package is only downloaded and unpacked into DIR, never installed.
#   tests/bench/meshes/cgal_meshes.sh DIR
# Prints the paths of the chosen meshes, one per line (smallest first). Already unpacked: no
# download. Chosen: closed, oriented and free of self-intersections, since the benchmark job
# imports strictly (bench_mesh_job). Bull, camel, cow, diplodocus and man in the same set touch
# themselves: the language's import takes those as the region of positive winding number.
set -euo pipefail
dir=${1:?usage: cgal_meshes.sh DIR}
meshes=(elephant homer fandisk turbine bear armadillo bunny00 refined_elephant)
mkdir -p "$dir"
missing=0
for m in "${meshes[@]}"; do [ -s "$dir/$m.off" ] || missing=1; done
if ((missing)); then
  work=$(mktemp -d)
  trap 'rm -rf "$work"' EXIT
  (cd "$work" && apt-get download libcgal-demo > "$work/apt.log" 2>&1) ||
    { echo "cgal_meshes: apt-get download libcgal-demo failed (log: $work/apt.log)" >&2; cat "$work/apt.log" >&2; exit 1; }
  dpkg-deb -x "$work"/libcgal-demo_*.deb "$work/pkg"
  members=()
  for m in "${meshes[@]}"; do members+=("data/meshes/$m.off"); done
  tar -xzf "$work/pkg/usr/share/doc/libcgal-dev/data.tar.gz" -C "$work" "${members[@]}"
  for m in "${meshes[@]}"; do mv "$work/data/meshes/$m.off" "$dir/$m.off"; done
fi
for m in "${meshes[@]}"; do echo "$dir/$m.off"; done
