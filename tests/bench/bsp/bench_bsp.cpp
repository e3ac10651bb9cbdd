// BSP set-operation benchmarks (tests/bench/bsp/CASES.md). Prints one parseable line per case:
//   bench impl=sculpt case=<case> n=<n> runs=<r> warmup=<0|1> time_ms=<median> min_ms=<min>
//         volume=<v> expected=<v|na> faces=<f> vertices=<v> peak_rss_kb=<k> base_rss_kb=<k>
//         tree_nodes=<nodes> tree_height=<h> exact_predicates=<count> filtered_predicates=<count>
//         boundary_fragments=<count carried by the result solid>
//         to_mesh_ms=<min of to_mesh on the result> to_mesh_unclean_ms=<the same with {.clean = false}>
//         operands_ms=<min, building the two operands> operation_ms=<min, the set operation alone>
//         operation_boundary_ms=<min, the set operation before its tree is built (solid.hpp,
//         "Deferred trees"): what an output needs> with_tree_cpu_ms / with_tree_min_cpu_ms=<median /
//         min thread CPU of the case plus building its result's tree> tree_deferred=<yes|no: the
//         case's result still had its tree to build> malloc=<kept|system>
// The predicate counts include building the result's tree.
// cpu_ms / min_cpu_ms: median / min of this thread's CPU time per run (less sensitive to a busy
// machine than the wall clock); to_mesh_ms and to_mesh_unclean_ms are thread CPU times.
// Without arguments it runs every case, each in its own process (so peak RSS is per case):
//   bench_bsp                 all cases
//   bench_bsp CASE N [RUNS]   one case (sphere_minus_cube 32|64|128|256, menger 3, boxes 1000,
//                             boxes_pairwise 1000: the same union one box at a time,
//                             sphere_minus_sphere 32|64|128, sphere_minus_tilted_cube 64,
//                             drilled_plate 100, rotated_boxes 200)
//   --system-malloc (anywhere): glibc's allocation defaults instead of the `sculpt` executable's
//                             keep_freed_memory() (base/memory_policy.hpp), which the cases use
//                             by default, as a session of the executable would; the line says
//                             malloc=kept or malloc=system.
//   --profile (anywhere):     the case's timed runs only (no tree build after each run, no
//                             reference volumes or extra timings), for a profiler; prints the times.
#include <sys/resource.h>
#include <time.h>

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

#include "base/memory_policy.hpp"
#include "bsp/boundary.hpp"
#include "bsp/primitives.hpp"
#include "bsp/set_operations.hpp"
#include "bsp/transform.hpp"
#include "bench/peers/cases.hpp"
#include "support/bench_solids.hpp"

using namespace sculpt;

namespace {

bool system_malloc = false;  // --system-malloc: glibc's defaults (see main)
bool profile_only = false;   // --profile: the timed runs alone (see main)

long rss_kb() {
  std::ifstream f("/proc/self/status");
  std::string line;
  while (std::getline(f, line))
    if (line.rfind("VmRSS:", 0) == 0) return std::atol(line.c_str() + 6);
  return 0;
}

double thread_cpu_ms() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return double(t.tv_sec) * 1e3 + double(t.tv_nsec) * 1e-6;
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

Eigen::Affine3d affine(const std::array<double, 16>& m) {  // column-major 4x4 (cases.hpp)
  Eigen::Affine3d a = Eigen::Affine3d::Identity();
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 3; ++r) a.matrix()(r, c) = m[std::size_t(4 * c + r)];
  return a;
}

// The two operands of the cases that subtract one solid from another (sphere radius 1, n segments).
std::pair<Solid, Solid> operands(const std::string& name, int n) {
  Solid s = sphere(1.0, {.segments = n});
  if (name == "sphere_minus_sphere") {
    const auto& o = bench_cases::sphere_offset;
    return {s, translate(s, {o[0], o[1], o[2]})};
  }
  if (name == "sphere_minus_tilted_cube") return {std::move(s), transform(box({0, 0, 0}, {1, 1, 1}), affine(bench_cases::tilted_cube()))};
  return {std::move(s), box({0, 0, 0}, {1, 1, 1})};
}

// Sphere minus a second solid (operands above), built inside the timing as in sphere_minus_cube.
Result sphere_minus(const std::string& name, int n) {
  auto [a, b] = operands(name, n);
  Solid s = std::move(a) - b;
  PolygonMesh mesh = to_mesh(s);
  return {std::move(s), std::move(mesh)};
}

Solid plate_hole(double x, double y) { return translate(cylinder(0.3, 2.0, {.segments = 32}), {x, y, -0.5}); }

// The plate [0,10] x [0,10] x [0,1] minus `count` cylinders one at a time, in place.
Result drilled_plate(int count) {
  Solid s = box({0, 0, 0}, {10, 10, 1});
  for (const auto& c : bench_cases::drill_centres(count)) s = std::move(s) - plate_hole(c[0], c[1]);
  PolygonMesh mesh = to_mesh(s);
  return {std::move(s), std::move(mesh)};
}

// Union of `count` rotated boxes by the batch union.
Result rotated_boxes(int count) {
  std::vector<Solid> parts;
  for (const auto& b : bench_cases::rotated_boxes(count))
    parts.push_back(transform(box({b.box.lo[0], b.box.lo[1], b.box.lo[2]}, {b.box.hi[0], b.box.hi[1], b.box.hi[2]}),
                              affine(b.matrix)));
  Solid s = unite_all(std::move(parts));
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
  } else if (name == "sphere_minus_sphere" || name == "sphere_minus_tilted_cube") {
    f = [n, name] { return sphere_minus(name, n); };
  } else if (name == "drilled_plate") {
    f = [n] { return drilled_plate(n); };
  } else if (name == "rotated_boxes") {
    f = [n] { return rotated_boxes(n); };
  } else {
    std::fprintf(stderr, "unknown case %s\n", name.c_str());
    return 2;
  }
  const long base = rss_kb();
  std::vector<double> times, cpu_times;  // wall clock and this thread's CPU time (a loaded machine)
  std::vector<double> tree_cpu_times;        // the same with the result's tree built (see below)
  Result r;
  bool deferred = false;
  const int warmup = 1;
  for (int i = 0; i < runs + warmup; ++i) {
    r = Result{};  // the previous result is freed outside the timing
    kernel::predicate_counters() = {};
    const double c0 = thread_cpu_ms();
    const auto t0 = std::chrono::steady_clock::now();
    r = f();
    const auto t1 = std::chrono::steady_clock::now();
    const double c1 = thread_cpu_ms();
    // The case's output (a mesh) does not need the result's tree, which a set operation builds on
    // first use (bsp/solid.hpp, "Deferred trees"); with_tree_*: the case plus that tree.
    deferred = r.solid.tree_deferred();
    if (!profile_only) (void)r.solid.nodes();
    const double c2 = thread_cpu_ms();
    if (i >= warmup) {
      times.push_back(std::chrono::duration<double, std::milli>(t1 - t0).count());
      cpu_times.push_back(c1 - c0);
      tree_cpu_times.push_back(c2 - c0);
    }
  }
  std::sort(times.begin(), times.end());
  std::sort(cpu_times.begin(), cpu_times.end());
  std::sort(tree_cpu_times.begin(), tree_cpu_times.end());
  if (profile_only) {
    std::printf("bench impl=sculpt case=%s n=%d runs=%d time_ms=%.3f min_ms=%.3f cpu_ms=%.3f profile=yes\n",
                name.c_str(), n, runs, times[times.size() / 2], times.front(), cpu_times[cpu_times.size() / 2]);
    return 0;
  }
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
  if (name == "sphere_minus_sphere" || name == "sphere_minus_tilted_cube") {
    // Expected: vol(a) - vol(a ∩ b), the intersection computed by the other set operation.
    const auto [a, b] = operands(name, n);
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.12g", mesh_volume(to_mesh(a)) - mesh_volume(to_mesh(a & b)));
    expected = buf;
  }
  if (name == "drilled_plate") {  // each hole removes half of its cylinder (height 2, plate 1 thick)
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.12g", 100.0 - n * mesh_volume(to_mesh(plate_hole(0.5, 0.5))) / 2);
    expected = buf;
  }
  // For the differences of two solids: building the operands alone and the set operation alone
  // (operands built untimed, copied untimed), min thread CPU time over the runs.
  double operands_ms = -1, operation_ms = -1, boundary_ms = -1;
  if (name == "sphere_minus_sphere" || name == "sphere_minus_tilted_cube" || name == "sphere_minus_cube") {
    operands_ms = operation_ms = boundary_ms = 1e300;
    for (int i = 0; i < std::max(3, runs); ++i) {
      double t0 = thread_cpu_ms();
      auto [a, b] = operands(name, n);
      operands_ms = std::min(operands_ms, thread_cpu_ms() - t0);
      t0 = thread_cpu_ms();
      const Solid d = std::move(a) - b;
      boundary_ms = std::min(boundary_ms, thread_cpu_ms() - t0);  // the tree may still be deferred
      (void)d.nodes();
      operation_ms = std::min(operation_ms, thread_cpu_ms() - t0);
    }
  }
  // The clean step's share: to_mesh alone on the result, with and without it (min over the runs).
  double mesh_ms = 1e300, unclean_ms = 1e300;
  for (int i = 0; i < std::max(3, runs); ++i) {
    for (const bool clean : {true, false}) {
      const double t0 = thread_cpu_ms();
      const PolygonMesh m = to_mesh(r.solid, {.clean = clean});
      const double t = thread_cpu_ms() - t0;
      (clean ? mesh_ms : unclean_ms) = std::min(clean ? mesh_ms : unclean_ms, t);
    }
  }
  const TreeStats st = tree_stats(r.solid);
  std::printf("bench impl=sculpt case=%s n=%d runs=%d warmup=%d time_ms=%.3f min_ms=%.3f cpu_ms=%.3f min_cpu_ms=%.3f "
              "volume=%.12g expected=%s "
              "faces=%zu vertices=%zu peak_rss_kb=%ld base_rss_kb=%ld tree_nodes=%d tree_height=%d "
              "exact_predicates=%llu filtered_predicates=%llu boundary_fragments=%zu to_mesh_ms=%.3f to_mesh_unclean_ms=%.3f "
              "operands_ms=%.3f operation_ms=%.3f operation_boundary_ms=%.3f with_tree_cpu_ms=%.3f "
              "with_tree_min_cpu_ms=%.3f tree_deferred=%s malloc=%s\n",
              name.c_str(), n, runs, warmup, times[times.size() / 2], times.front(), cpu_times[cpu_times.size() / 2],
              cpu_times.front(), volume, expected.c_str(),
              r.mesh.faces.size(), r.mesh.vertices.size(), peak_rss_kb(), base, st.nodes, st.height,
              (unsigned long long)pc.exact, (unsigned long long)pc.filtered, r.solid.boundary().size(), mesh_ms, unclean_ms,
              operands_ms, operation_ms, boundary_ms, tree_cpu_times[tree_cpu_times.size() / 2], tree_cpu_times.front(),
              deferred ? "yes" : "no", system_malloc ? "system" : "kept");
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<std::string> args;
  for (int i = 1; i < argc; ++i) {
    if (std::string(argv[i]) == "--system-malloc")
      system_malloc = true;
    else if (std::string(argv[i]) == "--profile")
      profile_only = true;
    else
      args.emplace_back(argv[i]);
  }
  if (!system_malloc) keep_freed_memory();
  // 7 runs by default, as the peers' harness (tests/bench/peers/run.sh).
  if (args.size() >= 2)
    return run_case(args[0], std::atoi(args[1].c_str()), args.size() >= 3 ? std::atoi(args[2].c_str()) : 7);
  const std::vector<std::pair<std::string, int>> cases = {{"sphere_minus_cube", 32}, {"sphere_minus_cube", 64},
                                                          {"sphere_minus_cube", 128}, {"sphere_minus_cube", 256},
                                                          {"menger", 3}, {"boxes", 1000},
                                                          {"sphere_minus_sphere", 32}, {"sphere_minus_sphere", 64},
                                                          {"sphere_minus_sphere", 128}, {"sphere_minus_tilted_cube", 64},
                                                          {"drilled_plate", 100}, {"rotated_boxes", 200}};
  int status = 0;
  for (const auto& [name, n] : cases) {
    const std::string cmd = std::string("'") + argv[0] + "' " + name + " " + std::to_string(n) +
                            (system_malloc ? " --system-malloc" : "");
    std::fflush(stdout);
    status |= std::system(cmd.c_str());
  }
  return status == 0 ? 0 : 1;
}
