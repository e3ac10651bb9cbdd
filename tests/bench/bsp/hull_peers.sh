#!/bin/sh
# hull() side by side with scipy's ConvexHull (Qhull, double precision, not exact) on the same
# point sets, in one run: median thread CPU times and their ratio (> 1: ours is faster).
# Usage: tests/bench/bsp/hull_peers.sh [build dir]   (from the source directory)
set -e
BUILD=${1:-build/release}
PY=/usr/bin/python3  # Debian's python, where python3-scipy installs
$PY -c "import scipy" 2>/dev/null || apt-get install -y python3-scipy >/dev/null
cmake --build "$BUILD" -j2 --target bench_hull >/dev/null
OUT=$(mktemp -d)
"$BUILD"/tests/bench/bsp/bench_hull --write "$OUT" > "$OUT/ours.txt"
cat "$OUT/ours.txt"
$PY - "$OUT" <<'PY'
import sys, time
import numpy as np
from scipy.spatial import ConvexHull
out = sys.argv[1]
for line in open(f"{out}/ours.txt"):
    f = dict(kv.split("=") for kv in line.split()[1:])
    pts = np.loadtxt(f"{out}/{f['case']}.xyz")
    times = []
    for _ in range(5):
        t0 = time.thread_time()
        h = ConvexHull(pts)
        times.append(1000 * (time.thread_time() - t0))
    ms = sorted(times)[2]
    ours = float(f["hull_cpu_ms"])
    print(f"{f['case']}: scipy ConvexHull {ms:.2f} ms ({len(h.simplices)} triangles, volume {h.volume:.6f}); "
          f"sculpt hull {ours:.2f} ms (quickhull alone {float(f['quickhull_cpu_ms']):.2f} ms, {f['faces']} triangles, "
          f"volume {float(f['volume']):.6f}); scipy/sculpt = {ms / ours:.2f}")
PY
rm -rf "$OUT"
