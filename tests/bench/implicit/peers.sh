#!/bin/sh
# Side by side in one run on the torus R = 1, r = 0.4 at Hausdorff error 2e-3 (issue 16):
# implicit::polygonize and uniform marching cubes (tests/bench/implicit/solid.cpp), CGAL's surface
# mesher (cgal_peer.cpp: make_surface_mesh, Delaunay refinement, for several distance bounds) and
# manifold-3d's Manifold.levelSet (levelset_peer.mjs, for several edge lengths, interpolated or
# refined vertices). Every peer mesh is measured by the same error measurement as ours (both ways,
# against the analytic torus), and for each peer the setting with the fewest triangles within 2e-3
# is reported. Times: median of 5, thread CPU (CGAL, ours) or process CPU (node + WASM).
# Installs libcgal-dev (apt-get) and manifold-3d (npm, tests/bench/peers/package.json) if missing.
# Usage: tests/bench/implicit/peers.sh [build dir]   (from the source directory; as root for apt-get)
set -e
BUILD=${1:-build/release}
[ -f /usr/include/CGAL/make_surface_mesh.h ] || apt-get install -y --no-install-recommends libcgal-dev >/dev/null
if [ ! -d tests/bench/peers/node_modules/manifold-3d ]; then
  (cd tests/bench/peers && npm install --no-audit --no-fund --loglevel=error >&2)
fi
cmake --build "$BUILD" -j2 --target implicit_solid >/dev/null
OUT=$(mktemp -d)
g++ -O2 -std=c++17 -DNDEBUG -DCGAL_NDEBUG tests/bench/implicit/cgal_peer.cpp -o "$OUT/cgal_peer" -lgmp -lmpfr
echo "load average before: $(cut -d' ' -f1-3 /proc/loadavg); CGAL $(grep -m1 'define CGAL_VERSION ' /usr/include/CGAL/version.h | cut -d' ' -f3)," \
     "manifold-3d $(node -p "require('./tests/bench/peers/node_modules/manifold-3d/package.json').version"), node $(node --version)"
"$OUT/cgal_peer" "$OUT" 0.0015 0.0013 0.0012 0.0011 0.001
node tests/bench/implicit/levelset_peer.mjs "$OUT" 0.07 0.068 0.066 0.064 0.062 0.06
"$BUILD"/tests/bench/implicit/implicit_solid --peers "$OUT"
rm -rf "$OUT"
