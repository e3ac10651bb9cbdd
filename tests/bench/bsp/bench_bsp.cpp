// BSP set-operation benchmarks (tests/bench/bsp/CASES.md). Prints one parseable line per case:
//   bench impl=sculpt case=<case> n=<n> runs=<r> warmup=<0|1> time_ms=<median> min_ms=<min>
//         volume=<v> expected=<v|na> faces=<f> vertices=<v> peak_rss_kb=<k> base_rss_kb=<k>
//         tree_nodes=<nodes> tree_height=<h> exact_predicates=<count> filtered_predicates=<count>
//         boundary_fragments=<count carried by the result solid>
// Without arguments it runs every case, each in its own process (so peak RSS is per case):
//   bench_bsp                 all cases
//   bench_bsp CASE N [RUNS]   one case (sphere_minus_cube 32|64|128|256, menger 3, boxes 1000,
//                             boxes_pairwise 1000: the same union one box at a time)
#include <sys/resource.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <functional>
#include <numbers>
#include <string>
#include <utility>
#include <vector>

#include "bsp/boundary.hpp"
#include "bsp/primitives.hpp"
#include "bsp/set_operations.hpp"
#include "support/bench_solids.hpp"

using namespace sculpt;

namespace {

long rss_kb() {
  std::ifstream f("/proc/self/status");
  std::string line;
  while (std::getline(f, line))
    if (line.rfind("VmRSS:", 0) == 0) return std::atol(line.c_str() + 6);
  return 0;
}

long peak_rss_kb() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return u.ru_maxrss;
}

struct Result {
  Solid solid;
  PolygonMesh mesh;
};

// Sphere of radius 1 with n segments minus the unit cube with a corner at the centre.
Result sphere_minus_cube(int n) {
  Solid s = sphere(1.0, {.segments = n}) - box({0, 0, 0}, {1, 1, 1});
  PolygonMesh mesh = to_mesh(s);
  return {std::move(s), std::move(mesh)};  // moved: a copy of the tree is not part of the case
}

// Menger sponge by 273 differences (tests/support/bench_solids.hpp): built in units of 1/27, since
// 1/27 is not on the kernel grid (2^-15); volumes are reported for the unit cube.
Result menger(int level) {
  Solid s = checks::menger_sponge(level);
  PolygonMesh mesh = to_mesh(s);
  return {std::move(s), std::move(mesh)};
}

// Union of `count` boxes from the 32-bit LCG of CASES.md by the batch union, unite_all, as the
// peers use theirs (Manifold.union(list), JSCAD union(...boxes)).
Result boxes(int count) {
  Solid s = unite_all(checks::lcg_box_list(count));
  PolygonMesh mesh = to_mesh(s);
  return {std::move(s), std::move(mesh)};
}

// The same union accumulated in place one box at a time (acc = std::move(acc) | box).
Result boxes_pairwise(int count) {
  Solid s = checks::lcg_boxes(count);
  PolygonMesh mesh = to_mesh(s);
  return {std::move(s), std::move(mesh)};
}

double mesh_volume(const PolygonMesh& m) {
  double v = 0;
  for (const auto& f : m.faces)
    for (std::size_t i = 1; i + 1 < f.size(); ++i)
      v += m.vertices[std::size_t(f[0])].dot(m.vertices[std::size_t(f[i])].cross(m.vertices[std::size_t(f[i + 1])])) / 6.0;
  return v;
}

int run_case(const std::string& name, int n, int runs) {
  std::function<Result()> f;
  double scale = 1;  // volume factor to unit-cube units
  std::string expected = "na";
  if (name == "sphere_minus_cube") {
    f = [n] { return sphere_minus_cube(n); };
  } else if (name == "menger") {
    f = [n] { return menger(n); };
    scale = 1.0 / std::pow(27.0, n);
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.12g", std::pow(20.0 / 27.0, 3 * n / 3.0 * 1.0) );
    expected = buf;
  } else if (name == "boxes") {
    f = [n] { return boxes(n); };
  } else if (name == "boxes_pairwise") {
    f = [n] { return boxes_pairwise(n); };
  } else {
    std::fprintf(stderr, "unknown case %s\n", name.c_str());
    return 2;
  }
  const long base = rss_kb();
  std::vector<double> times;
  Result r;
  const int warmup = 1;
  for (int i = 0; i < runs + warmup; ++i) {
    kernel::predicate_counters() = {};
    const auto t0 = std::chrono::steady_clock::now();
    r = f();
    const auto t1 = std::chrono::steady_clock::now();
    if (i >= warmup) times.push_back(std::chrono::duration<double, std::milli>(t1 - t0).count());
  }
  std::sort(times.begin(), times.end());
  const kernel::PredicateCounters pc = kernel::predicate_counters();
  double volume = mesh_volume(r.mesh);
  if (name == "menger") volume *= scale;
  if (name == "sphere_minus_cube") {
    // Expected: 7/8 of this implementation's own sphere (octant symmetry).
    const double vs = mesh_volume(to_mesh(sphere(1.0, {.segments = n})));
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.12g", vs * 7.0 / 8.0);
    expected = buf;
  }
  const TreeStats st = tree_stats(r.solid);
  std::printf("bench impl=sculpt case=%s n=%d runs=%d warmup=%d time_ms=%.3f min_ms=%.3f volume=%.12g expected=%s "
              "faces=%zu vertices=%zu peak_rss_kb=%ld base_rss_kb=%ld tree_nodes=%d tree_height=%d "
              "exact_predicates=%llu filtered_predicates=%llu boundary_fragments=%zu\n",
              name.c_str(), n, runs, warmup, times[times.size() / 2], times.front(), volume, expected.c_str(),
              r.mesh.faces.size(), r.mesh.vertices.size(), peak_rss_kb(), base, st.nodes, st.height,
              (unsigned long long)pc.exact, (unsigned long long)pc.filtered, r.solid.boundary().size());
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  // 7 runs by default, as the peers' harness (tests/bench/peers/run.sh).
  if (argc >= 3) return run_case(argv[1], std::atoi(argv[2]), argc >= 4 ? std::atoi(argv[3]) : 7);
  const std::vector<std::pair<std::string, int>> cases = {{"sphere_minus_cube", 32}, {"sphere_minus_cube", 64},
                                                          {"sphere_minus_cube", 128}, {"sphere_minus_cube", 256},
                                                          {"menger", 3}, {"boxes", 1000}};
  int status = 0;
  for (const auto& [name, n] : cases) {
    const std::string cmd = std::string("'") + argv[0] + "' " + name + " " + std::to_string(n);
    std::fflush(stdout);
    status |= std::system(cmd.c_str());
  }
  return status == 0 ? 0 : 1;
}
