// Native Manifold's side of `bench_sculpt --sphere-workpiece N` (issue 33's stroke into a
// workpiece of 10^6 triangles): the same arcs and the same ball (radius 0.15, 16 segments); each
// stroke is the union of the 20 hulls of consecutive ball positions subtracted from the
// workpiece, evaluated (NumTri) before the clock stops. Manifold's Sphere(1, N) has about N^2 / 2
// triangles (N = 1414 for 10^6), sculpt's sphere(1, N) about N^2.
//   manifold_stroke [N [STROKES [THREADS]]]
// Prints: bench impl=manifold-native case=strokes segments= workpiece_triangles= strokes= median_ms= max_ms= volume=
// (wall clock per stroke). Built and run by tests/bench/native_stroke.sh.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <vector>

#include <tbb/global_control.h>

#include "manifold/manifold.h"

using namespace manifold;
using Clock = std::chrono::steady_clock;

int main(int argc, char** argv) {
  const int n = argc > 1 ? std::atoi(argv[1]) : 1000;
  const int strokes = argc > 2 ? std::atoi(argv[2]) : 30;
  const int threads = argc > 3 ? std::atoi(argv[3]) : 0;
  std::unique_ptr<tbb::global_control> limit;
  if (threads > 0) limit = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism, threads);
  Manifold work = Manifold::Sphere(1.0, n);
  const std::size_t tris = work.NumTri();
  const Box box = work.BoundingBox();
  const vec3 size = box.max - box.min;
  const Manifold ball = Manifold::Sphere(0.15, 16);
  std::vector<double> ms;
  for (int k = 0; k < strokes; ++k) {
    const double z = box.min.z + (0.55 + 0.4 * std::fmod(k * 0.618, 1.0)) * size.z;
    const double r = 0.5 * size.x * (0.85 + 0.1 * std::fmod(k * 0.377, 1.0));
    const double start = k * 0.9;
    std::vector<vec3> path;
    for (int i = 0; i <= 20; ++i) {
      const double t = start + 1.2 * i / 20;
      path.push_back({r * std::cos(t), r * std::sin(t), z + 0.05 * std::sin(3 * t)});
    }
    const auto t0 = Clock::now();
    std::vector<Manifold> hulls;
    for (int i = 0; i + 1 < int(path.size()); ++i)
      hulls.push_back(Manifold::Hull({ball.Translate(path[i]), ball.Translate(path[i + 1])}));
    const Manifold tool = Manifold::BatchBoolean(hulls, OpType::Add);
    work = work - tool;
    const std::size_t t = work.NumTri();  // forces the evaluation
    ms.push_back(std::chrono::duration<double, std::milli>(Clock::now() - t0).count());
    (void)t;
  }
  std::vector<double> sorted = ms;
  std::sort(sorted.begin(), sorted.end());
  std::printf(
      "bench impl=manifold-native case=strokes segments=%d workpiece_triangles=%zu strokes=%d median_ms=%.2f "
      "max_ms=%.2f volume=%.6f\n",
      n, tris, strokes, sorted[sorted.size() / 2], sorted.back(), work.Volume());
  return 0;
}
