// Tree-building micro-benchmark: sphere(1, {.segments = n}) only (TreeBuilder::build on a solid
// of revolution), no set operation, no boundary. Prints one parseable line per n:
//   bench impl=sculpt case=sphere_build n=<n> runs=<r> time_ms=<median> min_ms=<min> cpu_ms=<median>
//         tree_nodes=<nodes> planes=<planes> exact_predicates=<count> trivial_predicates=<count>
//         filtered_predicates=<count> checksum=<hash of the tree> planes_hash=<hash of the plane table>
//         boundary=<fragments> boundary_hash=<hash of the carried boundary>
// cpu_ms is the thread's CPU time (less disturbed than wall time on a shared machine).
// The checksums let two builds of the builder be compared for identical output: checksum covers
// the tree (nodes, their planes by value, children), planes_hash the whole plane table in order
// (values and auxiliary marks), boundary_hash the carried boundary bit for bit (each fragment's
// support, corners' edge/p/q plane indices and approximation bits, flip).
//   bench_build                  n = 32, 64, 128, 256, 15 runs each
//   bench_build N [RUNS [CASE]]  one n; CASE sphere (default), cylinder or cone (unit radius and
//                                height), to compare the outputs of every ring primitive
#include <algorithm>
#include <bit>
#include <chrono>
#include <ctime>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "bsp/primitives.hpp"

using namespace sculpt;

namespace {

std::uint64_t mix(std::uint64_t h, std::uint64_t v) {
  h ^= v + 0x9e3779b97f4a7c15ull + (h << 6) + (h >> 2);
  return h;
}

// Hash of the tree reachable from the root (depth-first, planes by value).
std::uint64_t tree_hash(const Solid& s) {
  std::uint64_t h = 0;
  std::vector<TreeRef> stack{s.root()};
  while (!stack.empty()) {
    const TreeRef t = stack.back();
    stack.pop_back();
    if (is_leaf(t)) {
      h = mix(h, std::uint64_t(t));
      continue;
    }
    const BspNode& n = s.nodes()[std::size_t(t)];
    const kernel::Plane& p = s.planes()[n.plane];
    h = mix(mix(mix(mix(h, std::uint64_t(p.a)), std::uint64_t(p.b)), std::uint64_t(p.c)), std::uint64_t(p.d));
    h = mix(h, s.planes().auxiliary(n.plane) ? 1 : 0);
    h = mix(h, s.polygons()[std::size_t(t)].corners.size());
    stack.push_back(n.positive);
    stack.push_back(n.negative);
  }
  return h;
}

// Hash of the plane table in order: every plane's coefficients and auxiliary mark.
std::uint64_t planes_hash(const Solid& s) {
  std::uint64_t h = 0;
  for (std::int32_t i = 0; i < s.planes().size(); ++i) {
    const kernel::Plane& p = s.planes()[i];
    __extension__ typedef unsigned __int128 U128;
    const auto d = static_cast<U128>(p.d);
    h = mix(mix(mix(h, std::uint64_t(p.a)), std::uint64_t(p.b)), std::uint64_t(p.c));
    h = mix(mix(h, std::uint64_t(d)), std::uint64_t(d >> 64));
    h = mix(mix(h, std::bit_cast<std::uint64_t>(p.d_nearest)), s.planes().auxiliary(i) ? 1 : 0);
  }
  return h;
}

// Hash of the carried boundary bit for bit (plane indices, approximation bits, flip).
std::uint64_t boundary_hash(const Solid& s) {
  std::uint64_t h = mix(0, s.has_boundary() ? 1 : 0);
  for (const FragmentRef f : s.boundary()) {
    h = mix(mix(mix(h, std::uint64_t(f.polygon.support)), f.flip ? 1 : 0), f.polygon.corners.size());
    for (const kernel::Corner& c : f.polygon.corners) {
      h = mix(mix(mix(h, std::uint64_t(c.edge)), std::uint64_t(c.p)), std::uint64_t(c.q));
      for (const double v : {c.at().x, c.at().y, c.at().z, c.at().err}) h = mix(h, std::bit_cast<std::uint64_t>(v));
    }
  }
  return h;
}

double cpu_ms() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return double(t.tv_sec) * 1e3 + double(t.tv_nsec) * 1e-6;
}

Solid make(const std::string& what, int n) {
  if (what == "cylinder") return cylinder(1.0, 1.0, {.segments = n});
  if (what == "cone") return cone(1.0, 1.0, {.segments = n});
  return sphere(1.0, {.segments = n});
}

void run(int n, int runs, const std::string& what = "sphere") {
  std::vector<double> times, cpu;
  Solid s;
  kernel::PredicateCounters pc;
  for (int i = 0; i < runs + 1; ++i) {  // one warm-up run
    kernel::predicate_counters() = {};
    const double c0 = cpu_ms();
    const auto t0 = std::chrono::steady_clock::now();
    s = make(what, n);
    const auto t1 = std::chrono::steady_clock::now();
    const double c1 = cpu_ms();
    pc = kernel::predicate_counters();
    if (i > 0) times.push_back(std::chrono::duration<double, std::milli>(t1 - t0).count());
    if (i > 0) cpu.push_back(c1 - c0);
  }
  std::sort(times.begin(), times.end());
  std::sort(cpu.begin(), cpu.end());
  std::printf("bench impl=sculpt case=%s_build n=%d runs=%d time_ms=%.4f min_ms=%.4f cpu_ms=%.4f tree_nodes=%d planes=%d "
              "exact_predicates=%llu trivial_predicates=%llu filtered_predicates=%llu checksum=%016llx "
              "planes_hash=%016llx boundary=%zu boundary_hash=%016llx\n",
              what.c_str(), n, runs, times[times.size() / 2], times.front(), cpu[cpu.size() / 2], tree_stats(s).nodes, s.planes().size(),
              (unsigned long long)pc.exact, (unsigned long long)pc.trivial, (unsigned long long)pc.filtered,
              (unsigned long long)tree_hash(s), (unsigned long long)planes_hash(s), s.boundary().size(),
              (unsigned long long)boundary_hash(s));
  std::fflush(stdout);
}

}  // namespace

int main(int argc, char** argv) {
  if (argc >= 2) {
    run(std::atoi(argv[1]), argc >= 3 ? std::atoi(argv[2]) : 15, argc >= 4 ? argv[3] : "sphere");
    return 0;
  }
  for (int n : {32, 64, 128, 256}) run(n, 15);
  return 0;
}
