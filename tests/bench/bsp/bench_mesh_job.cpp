// One run of the real-mesh job of issue 33, our side (the peer's is tests/bench/native/
// manifold_job.cpp; both print the same line, tests/bench/native_compare.sh runs them side by side):
//   m = import(FILE); r = m turned 33 degrees about (1, 1, 0) around its box centre;
//   u = m | r; d = u - sphere(radius = a quarter of the box's largest side, 48 segments, centred
//   three quarters of the way from the box centre to its upper corner); volume(d)
// or, with --moved-copy, m = import(FILE); d = m - m moved by a tenth of its box's size
// (issue 33's 10^6-triangle case; `turn` times the move, `union` is 0),
// or, with --sphere N, sphere(1, N) - sphere(1, N) moved by (0.3, 0.2, 0.1).
//   bench_mesh_job [--threads T] [--classic] [--moved-copy] (--mesh FILE.off | --sphere N)
// --classic: set operations by merging whole trees, never by cells (bsp/local/cell_merge.hpp).
// Prints: bench case=NAME n=TRIANGLES threads=T import=S turn=S union=S difference=S total=S
//         volume=V triangles_out=N to_mesh=S (seconds, wall clock; difference includes to_mesh and the
//         volume of its mesh), then the process's peak resident memory so far (MB, Linux's VmHWM)
//         at the end of each phase: peak_import= peak_turn= peak_union= peak_difference= (before
//         to_mesh) peak_to_mesh=, which says which phase sets the peak (measured outside as well); 0 for
//         the phases the sphere case has not.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <optional>
#include <string>

#include <Eigen/Geometry>

#include "base/memory_policy.hpp"
#include "base/parallel.hpp"
#include "bsp/boundary.hpp"
#include "bsp/from_mesh.hpp"
#include "bsp/local/cell_merge.hpp"
#include "bsp/primitives.hpp"
#include "bsp/set_operations.hpp"
#include "bsp/transform.hpp"
#include "mesh/mesh_io.hpp"
#include "mesh/mesh_measures.hpp"
#include "mesh/mesh_validation.hpp"
#include "mesh/self_intersection.hpp"

namespace {

using Clock = std::chrono::steady_clock;
double since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

// The process's peak resident memory so far in MB (VmHWM of /proc/self/status; 0 where there is none).
double peak_rss_mb() {
  FILE* f = std::fopen("/proc/self/status", "r");
  if (!f) return 0;
  char line[256];
  double kb = 0;
  while (std::fgets(line, sizeof line, f))
    if (std::strncmp(line, "VmHWM:", 6) == 0) kb = std::atof(line + 6);
  std::fclose(f);
  return kb / 1024;
}

// The result's mesh and volume (part of `difference`), then the line (see the top).
int finish(const std::string& name, std::size_t n, int used, Clock::time_point start, const sculpt::Solid& result,
           double t_import, double t_turn, double t_union, double t_difference, double (&peak)[5]) {
  using namespace sculpt;
  const auto t = Clock::now();
  const PolygonMesh out = to_mesh(result);
  const double v = mesh_volume(out);
  const double t_to_mesh = since(t);
  peak[4] = peak_rss_mb();
  t_difference += t_to_mesh;
  std::size_t triangles = 0;
  for (const auto& f : out.faces) triangles += f.size() - 2;
  std::printf(
      "bench case=%s n=%zu threads=%d import=%.4f turn=%.4f union=%.4f difference=%.4f total=%.4f volume=%.10g "
      "triangles_out=%zu to_mesh=%.4f peak_import=%.1f peak_turn=%.1f peak_union=%.1f peak_difference=%.1f "
      "peak_to_mesh=%.1f\n",
      name.c_str(), n, used, t_import, t_turn, t_union, t_difference, since(start), v, triangles, t_to_mesh, peak[0],
      peak[1], peak[2], peak[3], peak[4]);
  return 0;
}

int usage() {
  std::fprintf(stderr, "usage: bench_mesh_job [--threads T] [--classic] (--mesh FILE | --sphere N)\n");
  return 2;
}

}  // namespace

int main(int argc, char** argv) {
  using namespace sculpt;
  int threads = 0, n = 0;
  bool moved_copy = false;
  std::string file;
  for (int i = 1; i < argc; i += 2) {
    const std::string a = argv[i];
    if (a == "--classic") {
      bsp::detail::set_cell_merge_threshold(bsp::detail::kClassicMergeOnly);
      --i;
      continue;
    }
    if (a == "--moved-copy") {
      moved_copy = true;
      --i;
      continue;
    }
    if (i + 1 >= argc) return usage();
    if (a == "--threads")
      threads = std::atoi(argv[i + 1]);
    else if (a == "--mesh")
      file = argv[i + 1];
    else if (a == "--sphere")
      n = std::atoi(argv[i + 1]);
    else
      return usage();
  }
  if (file.empty() == (n == 0)) return usage();
  use_huge_pages(argv);  // as the sculpt executable does (base/memory_policy.hpp); may restart
  keep_freed_memory();
  std::optional<ThreadLimit> limit;
  if (threads > 0) limit.emplace(threads);
  const int used = thread_count();
  const auto start = Clock::now();
  double t_import = 0, t_turn = 0, t_union = 0, t_difference = 0;
  double peak[5] = {0, 0, 0, 0, 0};  // peak_rss_mb() after import, turn, union, difference, to_mesh
  Solid result;
  std::size_t in_triangles = 0;
  std::string name;
  if (!file.empty()) {
    name = std::filesystem::path(file).stem().string();
    auto t = Clock::now();
    // As the language's import: read, validate the topology (closed, manifold, oriented) and,
    // side by side with it, check that the faces snapped to the grid do not cross; build with the
    // faces as the boundary.
    const PolygonMesh mesh = read_mesh(file);
    ValidationReport report;
    bool crosses = false;
    parallel_invoke([&] { report = check_closed_manifold(mesh, {.check_self_intersections = false}); },
                    [&] {  // the snapped copy is the check's alone (the language's import does not keep it either)
                      PolygonMesh snapped = mesh;
                      const kernel::Grid grid;
                      for (auto& v : snapped.vertices) v = grid.to_world(grid.snap(v));
                      crosses = !find_self_intersections(snapped, {.max_pairs = 1}).empty();
                    });
    if (!report.ok()) {
      std::fprintf(stderr, "bench_mesh_job: %s: %s\n", file.c_str(), report.summary(3).c_str());
      return 1;
    }
    if (crosses) {
      std::fprintf(stderr, "bench_mesh_job: %s: faces meet once snapped to the grid\n", file.c_str());
      return 1;
    }
    const Solid m = from_mesh(mesh, {.snapped_mesh_is_clean = true});
    t_import = since(t);
    peak[0] = peak_rss_mb();
    in_triangles = mesh.faces.size();
    Eigen::Vector3d lo = mesh.vertices[0], hi = lo;
    for (const auto& v : mesh.vertices) lo = lo.cwiseMin(v), hi = hi.cwiseMax(v);
    const Eigen::Vector3d c = (lo + hi) / 2;
    if (moved_copy) {
      name += "_minus_moved";
      t = Clock::now();
      const Solid moved = translate(m, (hi - lo) / 10);
      t_turn = since(t);
      peak[1] = peak[2] = peak_rss_mb();
      t = Clock::now();
      result = m - moved;
      t_difference = since(t);
      peak[3] = peak_rss_mb();
      return finish(name, in_triangles, used, start, result, t_import, t_turn, t_union, t_difference, peak);
    }
    t = Clock::now();
    const Eigen::Affine3d turn = Eigen::Translation3d(c) *
                                 Eigen::AngleAxisd(33 * M_PI / 180, Eigen::Vector3d(1, 1, 0).normalized()) *
                                 Eigen::Translation3d(-c);
    const Solid r = transform(m, turn);
    t_turn = since(t);
    peak[1] = peak_rss_mb();
    t = Clock::now();
    // The union's boundary is computed here (its tree is deferred until something reads it;
    // nothing in this job does). No volume of it: Manifold's side computes none either.
    const Solid u = m | r;
    t_union = since(t);
    peak[2] = peak_rss_mb();
    t = Clock::now();
    const double radius = (hi - lo).maxCoeff() / 4;
    const Solid ball = translate(sphere(radius, {.segments = 48}), c + 0.75 * (hi - c));
    result = u - ball;
    t_difference = since(t);
    peak[3] = peak_rss_mb();
  } else {
    name = "sphere_minus_moved";
    const auto t = Clock::now();
    const Solid a = sphere(1.0, {.segments = n});
    const Solid b = translate(sphere(1.0, {.segments = n}), {0.3, 0.2, 0.1});
    t_import = since(t);
    peak[0] = peak_rss_mb();
    in_triangles = 0;
    const auto d = Clock::now();
    result = a - b;
    t_difference = since(d);
    peak[3] = peak_rss_mb();
  }
  return finish(name, file.empty() ? std::size_t(n) : in_triangles, used, start, result, t_import, t_turn, t_union,
                t_difference, peak);
}
