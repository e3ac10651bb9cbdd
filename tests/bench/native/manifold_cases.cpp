// The primitive cases of tests/bench/bsp/CASES.md with native Manifold (the peer of issue 33; C++,
// its oneTBB backend), as tests/bench/peers/peer.mjs runs them with the WASM build: the same
// inputs (tests/bench/peers/cases.hpp), the operands built inside the timing, and each run ending
// with the result's mesh (GetMeshGL64) and volume, as ours (bench_bsp) ends with to_mesh.
//   manifold_cases [--threads T] CASE N [RUNS]
// Prints: bench impl=manifold-native case=CASE n=N threads=T runs=R time_ms=<median> min_ms=<min>
//         volume=V faces=F vertices=V peak_rss_kb=K
// Built and run by tests/bench/native_cases.sh against ../shared/peers' library.
#include <sys/resource.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <string>
#include <vector>

#include <tbb/global_control.h>
#include <tbb/info.h>

#include "manifold/manifold.h"
#include "peers/cases.hpp"

namespace bc = sculpt::bench_cases;

namespace {

using namespace manifold;
using Clock = std::chrono::steady_clock;

Manifold box(const bc::Box& b) {
  return Manifold::Cube({b.hi[0] - b.lo[0], b.hi[1] - b.lo[1], b.hi[2] - b.lo[2]}, false)
      .Translate({b.lo[0], b.lo[1], b.lo[2]});
}

mat3x4 matrix(const std::array<double, 16>& m) {  // column-major 4x4 (cases.hpp) to Manifold's 3x4
  mat3x4 a;
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 3; ++r) a[c][r] = m[std::size_t(4 * c + r)];
  return a;
}

Manifold unit_cube() { return box({{0, 0, 0}, {1, 1, 1}}); }

Manifold hole(double x, double y) { return Manifold::Cylinder(2, 0.3, 0.3, 32, false).Translate({x, y, -0.5}); }

// One run of the case: its result, evaluated.
Manifold run(const std::string& name, int n) {
  if (name == "sphere_minus_cube") return Manifold::Sphere(1, n) - unit_cube();
  if (name == "sphere_minus_sphere") {
    const auto& o = bc::sphere_offset;
    return Manifold::Sphere(1, n) - Manifold::Sphere(1, n).Translate({o[0], o[1], o[2]});
  }
  if (name == "sphere_minus_tilted_cube")
    return Manifold::Sphere(1, n) - unit_cube().Transform(matrix(bc::tilted_cube()));
  if (name == "menger") {
    Manifold r = unit_cube();
    for (const auto& b : bc::menger_bars(n)) r = r - box(b);
    return r;
  }
  if (name == "drilled_plate") {
    Manifold r = box({{0, 0, 0}, {10, 10, 1}});
    for (const auto& c : bc::drill_centres(n)) r = r - hole(c[0], c[1]);
    return r;
  }
  std::vector<Manifold> parts;
  if (name == "boxes") {
    for (const auto& b : bc::random_boxes(n)) parts.push_back(box(b));
  } else if (name == "rotated_boxes") {
    for (const auto& b : bc::rotated_boxes(n)) parts.push_back(box(b.box).Transform(matrix(b.matrix)));
  } else {
    std::fprintf(stderr, "manifold_cases: unknown case %s\n", name.c_str());
    std::exit(2);
  }
  return Manifold::BatchBoolean(parts, OpType::Add);
}

}  // namespace

int main(int argc, char** argv) {
  int threads = 0, first = 1;
  if (argc > 2 && std::string(argv[1]) == "--threads") threads = std::atoi(argv[2]), first = 3;
  if (argc - first < 2) {
    std::fprintf(stderr, "usage: manifold_cases [--threads T] CASE N [RUNS]\n");
    return 2;
  }
  const std::string name = argv[first];
  const int n = std::atoi(argv[first + 1]);
  const int runs = argc - first > 2 ? std::max(1, std::atoi(argv[first + 2])) : 5;
  std::unique_ptr<tbb::global_control> limit;
  if (threads > 0) limit = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism, threads);
  const int used = threads > 0 ? threads : tbb::info::default_concurrency();
  std::vector<double> times;
  double volume = 0;
  std::size_t faces = 0, vertices = 0;
  for (int r = 0; r < runs; ++r) {
    const auto t0 = Clock::now();
    const Manifold result = run(name, n);
    const MeshGL64 mesh = result.GetMeshGL64();
    volume = result.Volume();
    times.push_back(std::chrono::duration<double, std::milli>(Clock::now() - t0).count());
    faces = mesh.NumTri(), vertices = mesh.NumVert();
  }
  std::vector<double> sorted = times;
  std::sort(sorted.begin(), sorted.end());
  const double median =
      sorted.size() % 2 ? sorted[sorted.size() / 2] : (sorted[sorted.size() / 2 - 1] + sorted[sorted.size() / 2]) / 2;
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  std::printf(
      "bench impl=manifold-native case=%s n=%d threads=%d runs=%d time_ms=%.3f min_ms=%.3f volume=%.15g faces=%zu "
      "vertices=%zu peak_rss_kb=%ld\n",
      name.c_str(), n, used, runs, median, sorted.front(), volume, faces, vertices, u.ru_maxrss);
  return 0;
}
