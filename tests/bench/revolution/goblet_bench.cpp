// The goblet of Ihm & Naylor 1990, Figure 11, as a C++ program (the same job as scripts/goblet.bsp):
// the goblet profile (20 segments) revolved around a 32-gon, a cavity carved by difference, a ball
// joined by union, a depth-cost report comparing the trees, OFF and OBJ export; then the targets of
// docs/benchmarks.md ("Solids of revolution and depth cost") are measured and checked.
//   goblet_bench [models-dir] [out-dir]      (defaults: models, out)
#include <algorithm>
#include <chrono>
#include <ctime>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <random>
#include <string>
#include <vector>

#include "bsp/boundary.hpp"
#include "bsp/classify.hpp"
#include "bsp/point_classifier.hpp"
#include "revolution/revolve.hpp"
#include "bsp/set_operations.hpp"
#include "curves/digitized_curve.hpp"
#include "curves/profiles.hpp"
#include "mesh/mesh_io.hpp"
#include "mesh/mesh_validation.hpp"
#include "reports/tree_report.hpp"
#include "bsp/from_mesh.hpp"

using namespace sculpt;
using namespace sculpt::revolution;
using Clock = std::chrono::steady_clock;

namespace {

double ms_since(Clock::time_point t) { return std::chrono::duration<double, std::milli>(Clock::now() - t).count(); }

/// CPU time of this thread in ms: the machine is shared, so wall time includes other processes.
double cpu_ms() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return t.tv_sec * 1e3 + t.tv_nsec * 1e-6;
}

std::vector<Eigen::Vector2d> load(const std::string& path) {
  return curves::planar_points(curves::load_curve(path).points);
}

struct Goblet {
  Solid outer, cavity, ball, cup, goblet;
  std::vector<reports::TreeReport> report;
  PolygonMesh mesh;
};

/// The whole job; `report` and `out` may be switched off for timing the parts.
Goblet run(const std::string& models, const std::string& out, bool report, bool export_meshes) {
  Goblet g;
  const ConvexPath path = circular_path(32);
  g.outer = revolve(load(models + "/goblet_profile_20.txt"), path);
  g.cavity = revolve(load(models + "/goblet_cavity_profile_12.txt"), path);
  g.ball = revolve(load(models + "/ball_profile_16.txt"), path);
  g.cup = g.outer - g.cavity;
  g.goblet = g.cup | g.ball;
  if (report) {
    g.report = reports::compare_trees({{"goblet (revolution)", g.outer}, {"cup - cavity | ball", g.goblet}},
                                      {.query_samples = 1000});
  }
  if (export_meshes) {
    g.mesh = to_mesh(g.goblet);
    std::filesystem::create_directories(out);
    write_mesh(g.mesh, out + "/goblet.off");
    write_mesh(g.mesh, out + "/goblet.obj");
  }
  return g;
}

/// Median over runs of the CPU time (ms) of f; the median wall time goes to *wall if given.
double median_ms(int runs, const std::function<void()>& f, double* wall = nullptr) {
  std::vector<double> t, w;
  for (int i = 0; i < runs; ++i) {
    const auto start = Clock::now();
    const double cpu = cpu_ms();
    f();
    t.push_back(cpu_ms() - cpu);
    w.push_back(ms_since(start));
  }
  std::sort(t.begin(), t.end());
  std::sort(w.begin(), w.end());
  if (wall) *wall = w[w.size() / 2];
  return t[t.size() / 2];
}

int failures = 0;
void check(bool ok, const char* what) {
  std::printf("  [%s] %s\n", ok ? "ok" : "FAIL", what);
  failures += !ok;
}

}  // namespace

int main(int argc, char** argv) {
  const std::string models = argc > 1 ? argv[1] : "models";
  const std::string out = argc > 2 ? argv[2] : "out";
  try {
    const Goblet g = run(models, out, true, true);
    std::fputs(reports::report_text(g.report).c_str(), stdout);
    {
      std::ofstream svg(out + "/goblet_depth.svg");
      svg << reports::depth_chart_svg(g.report);
    }
    std::printf("\nwrote %s/goblet.off, %s/goblet.obj, %s/goblet_depth.svg\n\n", out.c_str(), out.c_str(), out.c_str());

    // The same outer goblet, its tree built from its boundary (B-rep to BSP), side by side.
    const auto brep_start = Clock::now();
    const Solid brep = from_mesh(to_mesh(g.outer));
    const double brep_ms = ms_since(brep_start);
    const auto side = reports::compare_trees({{"revolution (sec. 6)", g.outer}, {"B-rep build", brep}},
                                             {.sample_box = g.report.front().depth.sample_box, .query_samples = 2000});
    std::printf("\nThe outer goblet built two ways (B-rep build took %.1f ms wall):\n", brep_ms);
    const std::string side_text = reports::report_text(side);
    std::fputs(side_text.substr(0, side_text.find("\ndepth histogram")).c_str(), stdout);
    std::printf("\n");
    const TreeStats outer = tree_stats(g.outer);
    const int size = outer.nodes + outer.in_leaves + outer.out_leaves;
    const double v_cup = volume(g.cup), v_ball = volume(g.ball), v_both = volume(g.cup & g.ball);
    const double v_goblet = volume(g.goblet);
    const double v_outer = volume(g.outer), v_carved = volume(g.outer & g.cavity);
    const auto& revolution = g.report.front().depth;

    std::printf("targets (Figure 11 goblet: 20 profile segments, 32-gon):\n");
    std::printf("  tree before set operations: %d partitioning nodes + %d leaves = %d (bound 3 x 20 x 32 = 1920), height %d\n",
                outer.nodes, outer.in_leaves + outer.out_leaves, size, outer.height);
    check(size <= 3 * 20 * 32, "tree size <= 3 x 20 x 32");
    std::printf("  expected depth %.4f, entropy bound %.4f, ratio %.4f\n", revolution.expected_depth,
                revolution.entropy_bound, revolution.ratio);
    check(revolution.ratio <= 1.25, "expected depth <= 1.25 x entropy bound");
    std::printf("  cup: V(outer) - V(outer & cavity) = %.12g, V(cup) = %.12g\n", v_outer - v_carved, v_cup);
    check(std::abs(v_cup - (v_outer - v_carved)) <= 1e-9 * v_outer, "carved cup = outer - cavity (1e-9 relative)");
    std::printf("  V(a|b) = %.12g, V(a)+V(b)-V(a&b) = %.12g\n", v_goblet, v_cup + v_ball - v_both);
    check(std::abs(v_goblet - (v_cup + v_ball - v_both)) <= 1e-9 * v_goblet, "V(a|b) = V(a)+V(b)-V(a&b) (1e-9 relative)");
    const ValidationReport closed = check_closed_manifold(g.mesh);
    std::printf("  exported mesh: %zu vertices, %zu faces; %s\n", g.mesh.vertices.size(), g.mesh.faces.size(),
                closed.ok() ? "closed 2-manifold" : closed.summary(3).c_str());
    check(closed.ok(), "exported mesh watertight");

    // Timings (median of 15 runs): the whole job, and its parts.
    double whole_wall = 0;
    const double whole = median_ms(15, [&] { run(models, out, true, true); }, &whole_wall);
    const double build = median_ms(15, [&] { run(models, out, false, false); });
    const double exporting = median_ms(15, [&] { run(models, out, false, true); }) - build;
    std::printf("\n  whole goblet job (load, revolve x3, set operations, report, export OFF+OBJ): %.2f ms CPU, %.2f ms wall "
                "(medians of 15; CPU time excludes waiting for the disk and for other processes)\n", whole, whole_wall);
    std::printf("    of which build + set operations %.2f ms, export %.2f ms, report %.2f ms\n", build, exporting,
                whole - build - exporting);
    const PolygonMesh mesh = to_mesh(g.goblet);
    const double extract = median_ms(15, [&] { (void)to_mesh(g.goblet); });
    const double encode = median_ms(15, [&] {
      (void)encode_mesh(mesh, MeshFormat::Off);
      (void)encode_mesh(mesh, MeshFormat::Obj);
    });
    double write_wall = 0;
    const double write = median_ms(15, [&] {
      write_mesh(mesh, out + "/goblet.off");
      write_mesh(mesh, out + "/goblet.obj");
    }, &write_wall);
    std::printf("    export parts (CPU): boundary extraction %.2f ms, OFF+OBJ text %.2f ms, writing both files %.2f ms "
                "(%.2f ms wall, atomic with fsync)\n", extract, encode, write, write_wall);
    check(whole <= 100.0, "whole goblet job <= 100 ms");

    // Point classification throughput on one core, points uniform in the goblet's bounding box.
    const Eigen::AlignedBox3d box = bounding_box(g.goblet);
    std::mt19937_64 rng(7);
    std::uniform_real_distribution<double> U(0, 1);
    std::vector<Eigen::Vector3d> points(1 << 20);
    for (auto& p : points)
      for (int a = 0; a < 3; ++a) p[a] = box.min()[a] + U(rng) * box.sizes()[a];
    const PointClassifier fast(g.goblet);
    long inside = 0;
    const int rounds = 10;
    double start = cpu_ms();
    for (int r = 0; r < rounds; ++r)
      for (const auto& p : points) inside += fast.classify(p).location == Location::Inside;
    const double fast_rate = double(rounds) * points.size() / ((cpu_ms() - start) / 1000);
    std::vector<Classification> results(points.size());
    long batch_inside = 0;
    start = cpu_ms();
    for (int r = 0; r < rounds; ++r) {
      fast.classify(points, results);
      for (const auto& x : results) batch_inside += x.location == Location::Inside;
    }
    const double batch_rate = double(rounds) * points.size() / ((cpu_ms() - start) / 1000);
    start = cpu_ms();
    long exact_inside = 0;
    for (const auto& p : points) exact_inside += classify(g.goblet, p).location == Location::Inside;
    const double exact_rate = double(points.size()) / ((cpu_ms() - start) / 1000);
    std::printf("  exact point classification, goblet after set operations (%d nodes), CPU time of one core:\n"
                "    %.1f M points/s PointClassifier, batches of 8 interleaved walks (bsp/point_classifier.hpp)\n"
                "    %.1f M points/s PointClassifier, one point at a time\n"
                "    %.1f M points/s classify(solid, point) (bsp/classify.hpp, no flattening)\n"
                "    inside fractions %.5f / %.5f / %.5f\n",
                tree_stats(g.goblet).nodes, batch_rate / 1e6, fast_rate / 1e6, exact_rate / 1e6,
                double(batch_inside) / rounds / points.size(), double(inside) / rounds / points.size(),
                double(exact_inside) / points.size());
    check(batch_inside == rounds * exact_inside && inside == rounds * exact_inside,
          "PointClassifier and classify() agree on every point");
    check(batch_rate >= 1e7, "point classification >= 10 million points/s on one core");
  } catch (const std::exception& e) {
    std::fprintf(stderr, "goblet_bench: %s\n", e.what());
    return 1;
  }
  return failures ? 1 : 0;
}
