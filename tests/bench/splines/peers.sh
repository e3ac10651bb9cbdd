#!/bin/sh
# Side by side in one run: our SDM fit, scipy's least-squares spline with the same knots and
# chord-length parameters (splprep(task=-1), periodic cubic) and OpenCascade's fixed-knot
# approximation (AppDef_BSplineCompute, occt_peer.cpp: clamped, closed by C1 end conditions), each
# with the same number of control points, on the star (500 points, 24 controls) and on 10^4 noisy
# points (50 controls). Every curve is written as spline text and its distance to the data measured
# by our exact foot points. Times: median of 5 fits, CPU time of the fitting thread (scipy:
# process time, one BLAS thread). Installs python3-scipy and libocct-modeling-algorithms-dev if missing.
# Usage: tests/bench/splines/peers.sh [build dir]   (from the source directory; as root for apt-get)
set -e
BUILD=${1:-build/release}
PY=/usr/bin/python3  # Debian's python, where python3-scipy installs
$PY -c "import scipy" 2>/dev/null || apt-get install -y python3-scipy >/dev/null
[ -f /usr/include/opencascade/AppDef_BSplineCompute.hxx ] || apt-get install -y --no-install-recommends libocct-modeling-algorithms-dev >/dev/null
cmake --build "$BUILD" -j2 --target splines_peers >/dev/null
OUT=$(mktemp -d)
g++ -O2 -std=c++17 -Wno-deprecated-declarations -I/usr/include/opencascade tests/bench/splines/occt_peer.cpp -o "$OUT/occt_peer" \
  -lTKGeomAlgo -lTKG2d -lTKG3d -lTKGeomBase -lTKMath -lTKernel
echo "load average: $(cut -d' ' -f1-3 /proc/loadavg)"
PEERS="$BUILD"/tests/bench/splines/splines_peers
"$PEERS" fit "$OUT"
OPENBLAS_NUM_THREADS=1 OMP_NUM_THREADS=1 $PY - "$OUT" <<'PY'
import sys, time
import numpy as np
from scipy import interpolate
out = sys.argv[1]
for name, controls in (("star", 24), ("star10k", 50)):
    data = np.loadtxt(f"{out}/{name}_data.txt")
    closed = np.vstack([data, data[:1]])              # periodic: the first point repeated
    # chord-length parameters in [0, 1]; uniform knots i / controls (a periodic cubic with `controls`
    # spans and controls unique control points). With per=1, scipy 1.10 wants the full periodic knot
    # vector (the interior knots alone come back scrambled); the returned knots are checked below.
    times = []
    for run in range(5):
        t0 = time.process_time()
        chord = np.r_[0, np.cumsum(np.linalg.norm(np.diff(closed, axis=0), axis=1))]
        u = chord / chord[-1]
        knots = np.arange(-3, controls + 4) / controls
        tck, _ = interpolate.splprep([closed[:, 0], closed[:, 1]], u=u, t=knots, task=-1, per=1, k=3, s=0)
        times.append(1000 * (time.process_time() - t0))
    assert np.allclose(tck[0], knots) and len(tck[1][0]) == controls + 3
    # Our text form: an open (unclamped) cubic with the full knot vector; its domain is [0, 1].
    with open(f"{out}/{name}_scipy.txt", "w") as f:
        f.write("degree 3\nclosed false\ndimension 2\nknots " + " ".join(repr(float(k)) for k in tck[0]) + "\ncontrols\n")
        for x, y in zip(tck[1][0], tck[1][1]):
            f.write(f"{x!r} {y!r}\n")
    print(f"{name} scipy splprep(task=-1): controls {controls} median_cpu_ms {sorted(times)[2]:.2f}")
PY
for c in "star 24" "star10k 50"; do
  set -- $c
  printf "%s " "$1"; "$OUT/occt_peer" "$OUT/$1_data.txt" "$2" "$OUT/$1_occt.txt"
done
for name in star star10k; do
  "$PEERS" measure "$OUT" $name "sculpt SDM" "$OUT/${name}_sculpt.txt" "scipy splprep(task=-1)" "$OUT/${name}_scipy.txt" \
    "occt AppDef_BSplineCompute" "$OUT/${name}_occt.txt"
done
# Active surfaces (issue 18): our SDM fit (8 x 8 bicubic controls, at most 7 steps, corners fixed)
# and OpenCascade's GeomAPI_PointsToBSplineSurface (occt_surface_peer.cpp: bicubic C2, chord-length
# parameters, the smallest Tol3D that keeps at most 8 x 8 poles) on 40 x 40 grids of a spherical cap
# and a wave; every surface measured by our exact foot points. Then the timing target (10^4 points).
g++ -O2 -std=c++17 -Wno-deprecated-declarations -I/usr/include/opencascade tests/bench/splines/occt_surface_peer.cpp \
  -o "$OUT/occt_surface_peer" -lTKGeomAlgo -lTKG3d -lTKGeomBase -lTKMath -lTKernel
cmake --build "$BUILD" -j2 --target splines_surfaces >/dev/null
SURF="$BUILD"/tests/bench/splines/splines_surfaces
mkdir -p "$OUT/s"
"$SURF" fit "$OUT/s"
for name in sphere wave; do
  printf "%s " $name; "$OUT/occt_surface_peer" "$OUT/s/${name}_data.txt" 40 40 8 "$OUT/s/${name}_occt.txt"
  "$SURF" measure "$OUT/s" $name "sculpt SDM" "$OUT/s/${name}_sculpt.txt" "occt GeomAPI_PointsToBSplineSurface" "$OUT/s/${name}_occt.txt"
done
"$SURF" timing
rm -rf "$OUT"
