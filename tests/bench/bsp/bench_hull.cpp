// hull() of random point sets (issue target: 10^5 random points in at most 100 ms): median thread
// CPU and wall time of the exact Quickhull alone and of the whole hull() (Quickhull plus the
// balanced tree), with the hull's size and the tree's height.
//   bench_hull [--runs N] [--write DIR]   (--write: the point sets as DIR/<case>.xyz for peers)
// Prints one line per case:
//   bench impl=sculpt case=<name> points=<n> faces=<hull triangles> runs=<r> quickhull_cpu_ms=<m>
//         hull_ms=<median wall> hull_cpu_ms=<median cpu> nodes=<tree nodes> height=<tree height>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <fstream>
#include <functional>
#include <random>
#include <string>
#include <vector>

#include "bsp/boundary.hpp"
#include "bsp/hull.hpp"
#include "kernel/convex_hull.hpp"
#include "bench/bench_timing.hpp"

using namespace sculpt;
using bench::median_ms;
using bench::Timing;

namespace {

std::vector<Eigen::Vector3d> points(const std::string& kind, int n) {
  std::mt19937_64 rng(12345);
  std::uniform_real_distribution<double> u(-1, 1);
  std::normal_distribution<double> g;
  std::vector<Eigen::Vector3d> out;
  while (static_cast<int>(out.size()) < n) {
    if (kind == "cube") {
      out.emplace_back(u(rng), u(rng), u(rng));
    } else if (kind == "ball") {
      const Eigen::Vector3d p(u(rng), u(rng), u(rng));
      if (p.squaredNorm() <= 1) out.push_back(p);
    } else {  // sphere: every point a corner of the hull (the worst case for its size)
      const Eigen::Vector3d p(g(rng), g(rng), g(rng));
      out.push_back(p.normalized());
    }
  }
  return out;
}

}  // namespace

int main(int argc, char** argv) {
  int runs = 5;
  std::string write_dir;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--runs" && i + 1 < argc) runs = std::stoi(argv[++i]);
    else if (a == "--write" && i + 1 < argc) write_dir = argv[++i];
    else {
      std::fprintf(stderr, "usage: bench_hull [--runs N] [--write DIR]\n");
      return 2;
    }
  }
  const std::pair<const char*, int> cases[] = {{"cube", 100000}, {"ball", 100000}, {"sphere", 10000}, {"sphere", 100000}};
  for (const auto& [kind, n] : cases) {
    const auto pts = points(kind, n);
    const std::string name = std::string(kind) + "_" + std::to_string(n);
    if (!write_dir.empty()) {
      std::ofstream f(write_dir + "/" + name + ".xyz");
      f.precision(17);
      for (const auto& p : pts) f << p.x() << ' ' << p.y() << ' ' << p.z() << '\n';
    }
    std::vector<kernel::GridPoint> grid;
    for (const auto& p : pts) grid.push_back(kernel::snap(p));
    std::size_t faces = 0;
    const Timing quick = median_ms(runs, [&] { faces = kernel::convex_hull(grid).triangles.size(); });
    Solid h;
    const Timing whole = median_ms(runs, [&] { h = hull(pts); });
    const TreeStats t = tree_stats(h);
    std::printf("bench impl=sculpt case=%s points=%d faces=%zu runs=%d quickhull_cpu_ms=%.2f hull_ms=%.2f "
                "hull_cpu_ms=%.2f nodes=%d height=%d volume=%.6f\n",
                name.c_str(), n, faces, runs, quick.cpu, whole.wall, whole.cpu, t.nodes, t.height, volume(h));
    std::fflush(stdout);
  }
}
