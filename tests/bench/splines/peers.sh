#!/bin/sh
# Compares our SDM fit with scipy's least-squares spline fit (splprep(task=-1): fixed knots,
# chord-length parameters, periodic cubic, the same number of control points) on the star
# (500 points, 24 controls) and on 10^4 noisy points (50 controls). Distances of the data points
# to each curve are measured the same way for both: nearest of 200000 dense curve samples
# (KD-tree). Usage: tests/bench/splines/peers.sh [build dir]   (from the source directory)
set -e
BUILD=${1:-build/release}
PY=/usr/bin/python3  # Debian's python, where python3-scipy installs
$PY -c "import scipy" 2>/dev/null || apt-get install -y python3-scipy >/dev/null
cmake --build "$BUILD" -j2 --target splines_peers >/dev/null
OUT=$(mktemp -d)
"$BUILD"/tests/bench/splines/splines_peers "$OUT"
$PY - "$OUT" <<'PY'
import sys, time
import numpy as np
from scipy import interpolate
from scipy.spatial import cKDTree
out = sys.argv[1]
for name, controls in (("star", 24), ("star10k", 50)):
    data = np.loadtxt(f"{out}/{name}_data.txt")
    ours = np.loadtxt(f"{out}/{name}_sculpt.txt")
    closed = np.vstack([data, data[:1]])              # periodic: the first point repeated
    t0 = time.perf_counter()
    # chord-length parameters in [0, 1]; uniform knots i / controls (a periodic cubic with `controls`
    # spans and controls unique control points). With per=1, scipy 1.10 wants the full periodic knot
    # vector (the interior knots alone come back scrambled); the returned knots are checked below.
    chord = np.r_[0, np.cumsum(np.linalg.norm(np.diff(closed, axis=0), axis=1))]
    u = chord / chord[-1]
    knots = np.arange(-3, controls + 4) / controls
    tck, _ = interpolate.splprep([closed[:, 0], closed[:, 1]], u=u, t=knots, task=-1, per=1, k=3, s=0)
    ms = 1000 * (time.perf_counter() - t0)
    assert np.allclose(tck[0], knots) and len(tck[1][0]) == controls + 3
    dense = np.array(interpolate.splev(np.linspace(0, 1, 200000, endpoint=False), tck)).T
    for label, curve, extra in (("scipy splprep(task=-1)", dense, f"time_ms {ms:.1f}"), ("sculpt SDM", ours, "")):
        d, _ = cKDTree(curve).query(data)
        print(f"{name} {label}: dense max {d.max():.4e} rms {np.sqrt(np.mean(d**2)):.4e} {extra}")
PY
rm -rf "$OUT"
