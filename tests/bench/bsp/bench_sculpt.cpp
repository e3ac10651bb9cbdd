// Interactive sculpting (issue target: a stroke of a ball tool, 16 segments, along a 20-segment path
// carved into the goblet in at most 50 ms, and still at most 50 ms per stroke after 100 strokes):
// 100 carving strokes, each along a different 20-segment arc around the goblet's bowl, with the
// time per stroke (thread CPU and wall) and the tree's growth every 10 strokes.
//   bench_sculpt [--strokes N] [--no-tidy] [--tidy-nodes N] [--tidy-above R] [--repeat-stroke K] [--system-malloc]
//   [--rebuild-every K] [--compare-old] [--script]
//                [--sphere-workpiece N]
//   (--sphere-workpiece N: carve sphere(1, N) instead of the goblet, N = 1000 for issue 33's workpiece of 10^6
//   triangles; the same arcs, which cut into its upper half; case=workpiece_ready times its tree's first build)
//   (--no-tidy: without the stroke's last step, the rebuild of the subtrees it touched
//   (rebuild_region), which carve and add do; --tidy-nodes N: its max_nodes and max_subtree_nodes; --tidy-above R: its
//   above_nodes_per_fragment;
//   --system-malloc: glibc's allocation defaults instead of the executable's keep_freed_memory();
//   --repeat-stroke K: stroke K's sweep and its subtraction (on copies of the workpiece) 20 more times each, for a
//   profiler; K: rebuild the tree from the boundary every K strokes; --script: the same strokes also through the
//   interpreter, `work = carve(work, ball, path)` (handed over, in place) and, with another variable holding the
//   workpiece during the stroke, the copying path, side by side per stroke)
// Prints:  bench impl=sculpt case=stroke_<k> cpu_ms=<m> sweep_cpu_ms=<m> subtract_cpu_ms=<m> tidy_cpu_ms=<m>
// wall_ms=<m> nodes=<tree nodes> height=<h>
//            storage_nodes=<node slots> planes=<plane table size> fragments=<boundary fragments> volume=<v>
//          bench impl=sculpt|subtract case=distribution ... (whole strokes; the subtraction alone)
//          bench impl=sculpt case=strokes median_cpu_ms=<m> max_cpu_ms=<m> first10_cpu_ms=<m> last10_cpu_ms=<m> ...
//          strokes_over_50ms=<n>
//          (--rebuild-every: case=rebuild_after_<k> per rebuild; --compare-old: impl=old lines and the median ratio;
//           --script: impl=script / impl=script_copy distributions and ratios to the library's in-place carve)
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

#include "bsp/boundary.hpp"
#include "bsp/convex_path.hpp"
#include "bsp/hull.hpp"
#include "bsp/primitives.hpp"
#include "bsp/rebuild.hpp"
#include "bsp/set_operations.hpp"
#include "bsp/sweep.hpp"
#include "curves/digitized_curve.hpp"
#include "curves/profiles.hpp"
#include "revolution/revolve.hpp"
#include "base/memory_policy.hpp"
#include "bench/bench_timing.hpp"
#include "language/interpreter.hpp"
#include "language/solid_values.hpp"

using namespace sculpt;
using Clock = std::chrono::steady_clock;
using bench::cpu_ms;

namespace {

const std::string kModels = SCULPT_MODELS_DIR;

Solid revolved(const std::string& file) {
  const auto profile = curves::planar_points(curves::load_curve(kModels + "/" + file).points);
  return revolution::revolve(profile, circular_path(32));
}

/// The construction before issue 17's rework, for side-by-side ratios (--compare-old): each
/// segment's hull as a solid with its own tree (bsp/hull.hpp), united by unite_all, subtracted
/// from a copy of the workpiece (carve took it by const reference).
Solid old_carve(const Solid& work, const Solid& ball, const std::vector<Eigen::Vector3d>& path) {
  const kernel::Grid& grid = ball.grid();
  std::vector<Eigen::Vector3d> at;
  for (const Eigen::Vector3d& p : path) {
    const Eigen::Vector3d g = grid.to_world(grid.snap(p));
    if (at.empty() || g != at.back()) at.push_back(g);
  }
  const std::vector<Eigen::Vector3d> vertices = to_mesh(ball).vertices;
  (void)hull(vertices, grid);  // the old convexity test built the tool's hull
  std::vector<Solid> parts;
  for (std::size_t i = 0; i + 1 < at.size(); ++i) {
    std::vector<Eigen::Vector3d> ends;
    for (const Eigen::Vector3d& v : vertices) {
      ends.push_back(v + at[i]);
      ends.push_back(v + at[i + 1]);
    }
    parts.push_back(hull(ends, grid));
  }
  return work - unite_all(std::move(parts));
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

/// The q-quantile (nearest rank) of v.
double quantile(std::vector<double> v, double q) {
  std::sort(v.begin(), v.end());
  const auto i = std::size_t(std::ceil(q * double(v.size()))) - 1;
  return v[std::min(i, v.size() - 1)];
}

void distribution(const char* impl, const std::vector<double>& cpu) {
  std::printf("bench impl=%s case=distribution strokes=%zu median_cpu_ms=%.2f p90_cpu_ms=%.2f max_cpu_ms=%.2f "
              "strokes_over_50ms=%d\n",
              impl, cpu.size(), median(cpu), quantile(cpu, 0.9), *std::max_element(cpu.begin(), cpu.end()),
              int(std::count_if(cpu.begin(), cpu.end(), [](double c) { return c > 50; })));
}

/// Runs one statement in `session`; its thread CPU time.
double run_statement(language::Interpreter& session, const std::string& text) {
  auto source = std::make_shared<language::SourceFile>();
  source->name = "stroke.bsp";
  source->text = text;
  const double c0 = cpu_ms();
  session.run(source);
  return cpu_ms() - c0;
}

language::Value point_list(const std::vector<Eigen::Vector3d>& path) {
  language::List points;
  for (const Eigen::Vector3d& p : path) points.emplace_back(language::List{p.x(), p.y(), p.z()});
  return {std::move(points)};
}

}  // namespace

int main(int argc, char** argv) {
  // The allocation policy of the `sculpt` executable, whose interactive session this models
  // (base/memory_policy.hpp); --system-malloc: glibc's defaults.
  bool system_malloc = false;
  for (int i = 1; i < argc; ++i) system_malloc |= std::string(argv[i]) == "--system-malloc";
  if (!system_malloc) keep_freed_memory();
  int strokes = 100;
  int rebuild_every = 0;  // 0: never
  bool compare_old = false;
  bool script = false;
  bool tidy = true;
  RegionRebuildOptions tidy_options;
  int repeat_stroke = 0;  // --repeat-stroke K: stroke K's subtraction again 20 times on copies (for profilers)
  int sphere_workpiece = 0;  // --sphere-workpiece N: sphere(1, N) instead of the goblet
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--strokes" && i + 1 < argc) strokes = std::stoi(argv[++i]);
    else if (a == "--rebuild-every" && i + 1 < argc) rebuild_every = std::stoi(argv[++i]);
    else if (a == "--compare-old") compare_old = true;
    else if (a == "--script") script = true;
    else if (a == "--no-tidy") tidy = false;
    else if (a == "--system-malloc") continue;
    else if (a == "--repeat-stroke" && i + 1 < argc) repeat_stroke = std::stoi(argv[++i]);
    else if (a == "--sphere-workpiece" && i + 1 < argc)
      sphere_workpiece = std::stoi(argv[++i]);
    else if (a == "--tidy-nodes" && i + 1 < argc) tidy_options.max_nodes = tidy_options.max_subtree_nodes = std::stoi(argv[++i]);
    else if (a == "--tidy-above" && i + 1 < argc) tidy_options.above_nodes_per_fragment = std::stod(argv[++i]);
    else {
      std::fprintf(stderr,
                   "usage: bench_sculpt [--strokes N] [--no-tidy] [--tidy-nodes N] [--tidy-above R] [--repeat-stroke "
                   "K] [--system-malloc] [--rebuild-every K] [--compare-old] [--script] [--sphere-workpiece N]\n");
      return 2;
    }
  }
  // The goblet of scripts/goblet.bsp: the outer profile (20 segments) minus the cavity (12).
  Solid work = sphere_workpiece > 0 ? sphere(1.0, {.segments = sphere_workpiece})
                                    : revolved("goblet_profile_20.txt") - revolved("goblet_cavity_profile_12.txt");
  if (sphere_workpiece > 0) {  // its tree, built on first use: before the strokes, timed on its own
    const auto w0 = Clock::now();
    const double c0 = cpu_ms();
    (void)work.root();
    std::printf("bench impl=sculpt case=workpiece_ready segments=%d cpu_ms=%.1f wall_ms=%.1f nodes=%zu fragments=%zu\n",
                sphere_workpiece, cpu_ms() - c0, std::chrono::duration<double, std::milli>(Clock::now() - w0).count(),
                work.nodes().size(), work.has_boundary() ? work.boundary().size() : std::size_t(0));
  }
  Solid work_old = work;  // carved the old way with --compare-old
  const Eigen::AlignedBox3d box = bounding_box(work);
  const Solid ball = sphere(0.15, {.segments = 16});
  std::vector<double> cpu, sweep_cpu, subtract_cpu, tidy_cpu, rebuild_cpu, old_cpu, script_cpu, copy_cpu;
  // --script: two sessions, each with the goblet in `work` and the ball in `ball`.
  std::ostringstream script_out;
  language::Interpreter session({.out = &script_out}), copying({.out = &script_out});
  if (script) {
    for (language::Interpreter* i : {&session, &copying}) {
      i->define("work", language::solid_value(work));
      i->define("ball", language::solid_value(ball));
    }
  }
  for (int k = 0; k < strokes; ++k) {
    // An arc of 20 segments at a height and radius that cut into the bowl's wall.
    const double z = box.min().z() + (0.55 + 0.4 * std::fmod(k * 0.618, 1.0)) * box.sizes().z();
    const double r = 0.5 * box.sizes().x() * (0.85 + 0.1 * std::fmod(k * 0.377, 1.0));
    const double start = k * 0.9;
    std::vector<Eigen::Vector3d> path;
    for (int i = 0; i <= 20; ++i) {
      const double t = start + 1.2 * i / 20;
      path.emplace_back(r * std::cos(t), r * std::sin(t), z + 0.05 * std::sin(3 * t));
    }
    if (k + 1 == repeat_stroke) {
      for (int rep = 0; rep < 20; ++rep) {
        const double c0 = cpu_ms();
        const Solid again = sweep(ball, path);
        std::printf("bench impl=sculpt case=repeat_%d sweep_cpu_ms=%.2f\n", k + 1, cpu_ms() - c0);
      }
      const Solid swept = sweep(ball, path);
      for (int rep = 0; rep < 20; ++rep) {
        Solid copy = work;
        const double c0 = cpu_ms();
        copy = std::move(copy) - swept;
        std::printf("bench impl=sculpt case=repeat_%d subtract_cpu_ms=%.2f\n", k + 1, cpu_ms() - c0);
      }
    }
    const std::size_t capacity_before = work.polygons().capacity();
    const auto wall0 = Clock::now();
    const double cpu0 = cpu_ms();
    // carve(std::move(work), ball, path), in its three steps, timed separately.
    const Solid swept = sweep(ball, path);
    const double cpu1 = cpu_ms();
    work = std::move(work) - swept;
    const double cpu2 = cpu_ms();
    RegionRebuildStats tidied;
    if (tidy) work = rebuild_region(std::move(work), swept, tidy_options, &tidied);
    const double c = cpu_ms() - cpu0;
    sweep_cpu.push_back(cpu1 - cpu0);
    subtract_cpu.push_back(cpu2 - cpu1);
    tidy_cpu.push_back(c - (cpu2 - cpu0));
    const double w = std::chrono::duration<double, std::milli>(Clock::now() - wall0).count();
    cpu.push_back(c);
    if (c > 50 || std::getenv("SCULPT_BENCH_EVERY_STROKE"))
      std::printf("bench impl=sculpt case=slow_stroke_%d cpu_ms=%.2f sweep_cpu_ms=%.2f subtract_cpu_ms=%.2f tidy_cpu_ms=%.2f storage_nodes=%zu planes=%d capacity=%zu->%zu\n",
                  k + 1, c, sweep_cpu.back(), subtract_cpu.back(), tidy_cpu.back(), work.nodes().size(), work.planes().size(),
                  capacity_before, work.polygons().capacity());
    if (script) {
      session.define("path", point_list(path));
      copying.define("path", point_list(path));
      script_cpu.push_back(run_statement(session, "work = carve(work, ball, path)"));
      // `before` holds the workpiece during the stroke: carve copies it (as every stroke did
      // before the handover); the time includes dropping the old value at the next stroke's start.
      copy_cpu.push_back(run_statement(copying, "before = work\nwork = carve(work, ball, path)\nbefore = 0"));
    }
    if (compare_old) {
      const double o0 = cpu_ms();
      work_old = old_carve(work_old, ball, path);
      old_cpu.push_back(cpu_ms() - o0);
    }
    if (rebuild_every > 0 && (k + 1) % rebuild_every == 0) {
      // A new tree from the workpiece's boundary (bsp/rebuild.hpp), timed on its own.
      const TreeStats before = tree_stats(work);
      const double r0 = cpu_ms();
      work = rebuild_from_boundary(work);
      const double rebuild_ms = cpu_ms() - r0;
      const TreeStats after = tree_stats(work);
      std::printf("bench impl=sculpt case=rebuild_after_%d cpu_ms=%.2f nodes=%d->%d height=%d->%d\n", k + 1, rebuild_ms, before.nodes,
                  after.nodes, before.height, after.height);
      rebuild_cpu.push_back(rebuild_ms);
    }
    if (k % 10 == 0 || k + 1 == strokes) {
      const TreeStats t = tree_stats(work);
      std::printf("bench impl=sculpt case=stroke_%d cpu_ms=%.2f sweep_cpu_ms=%.2f subtract_cpu_ms=%.2f tidy_cpu_ms=%.2f wall_ms=%.2f nodes=%d height=%d "
                  "storage_nodes=%zu planes=%d fragments=%zu volume=%.6f rebuilt=%d/%d rebuilt_nodes=%d->%d\n",
                  k + 1, c, sweep_cpu.back(), subtract_cpu.back(), tidy_cpu.back(), w, t.nodes, t.height, work.nodes().size(),
                  work.planes().size(), work.boundary().size(), volume(work), tidied.rebuilt, tidied.candidates, tidied.nodes_before,
                  tidied.nodes_after);
      if (compare_old) {
        const TreeStats o = tree_stats(work_old);
        std::printf("bench impl=old case=stroke_%d cpu_ms=%.2f nodes=%d height=%d volume=%.6f\n", k + 1, old_cpu.back(), o.nodes,
                    o.height, volume(work_old));
      }
      std::fflush(stdout);
    }
  }
  const std::vector<double> first(cpu.begin(), cpu.begin() + std::min<std::size_t>(10, cpu.size()));
  const std::vector<double> last(cpu.end() - std::min<std::size_t>(10, cpu.size()), cpu.end());
  const auto over_50 = std::count_if(cpu.begin(), cpu.end(), [](double c) { return c > 50; });
  std::printf("bench impl=sculpt case=strokes strokes=%d median_cpu_ms=%.2f max_cpu_ms=%.2f first10_cpu_ms=%.2f last10_cpu_ms=%.2f "
              "median_sweep_cpu_ms=%.2f median_subtract_cpu_ms=%.2f median_tidy_cpu_ms=%.2f strokes_over_50ms=%d\n",
              strokes, median(cpu), *std::max_element(cpu.begin(), cpu.end()), median(first), median(last), median(sweep_cpu),
              median(subtract_cpu), median(tidy_cpu), int(over_50));
  if (!rebuild_cpu.empty())
    std::printf("bench impl=sculpt case=rebuilds count=%zu median_cpu_ms=%.2f max_cpu_ms=%.2f\n", rebuild_cpu.size(), median(rebuild_cpu),
                *std::max_element(rebuild_cpu.begin(), rebuild_cpu.end()));
  distribution("sculpt", cpu);
  distribution("sweep", sweep_cpu);
  distribution("subtract", subtract_cpu);
  distribution("tidy", tidy_cpu);
  if (script) {
    distribution("script", script_cpu);
    distribution("script_copy", copy_cpu);
    std::vector<double> in_place_ratio, copy_ratio;
    for (std::size_t i = 0; i < cpu.size(); ++i) {
      in_place_ratio.push_back(script_cpu[i] / cpu[i]);
      copy_ratio.push_back(copy_cpu[i] / cpu[i]);
    }
    const std::vector<double> s_last(script_cpu.end() - std::min<std::size_t>(10, script_cpu.size()), script_cpu.end());
    const std::vector<double> c_last(copy_cpu.end() - std::min<std::size_t>(10, copy_cpu.size()), copy_cpu.end());
    const Solid& by_script = session.global("work")->object<language::SolidValue>()->solid;
    const Solid& by_copy = copying.global("work")->object<language::SolidValue>()->solid;
    std::printf("bench impl=script case=strokes median_ratio_script_over_library=%.2f median_ratio_copy_over_library=%.2f "
                "last10_script_cpu_ms=%.2f last10_copy_cpu_ms=%.2f same_set=%d\n",
                median(in_place_ratio), median(copy_ratio), median(s_last), median(c_last),
                int((work - by_script).is_empty() && (by_script - work).is_empty() && (by_copy - work).is_empty() &&
                    (work - by_copy).is_empty()));
  }
  if (compare_old) {
    std::vector<double> ratio;
    for (std::size_t i = 0; i < cpu.size(); ++i) ratio.push_back(old_cpu[i] / cpu[i]);
    const std::vector<double> old_last(old_cpu.end() - std::min<std::size_t>(10, old_cpu.size()), old_cpu.end());
    std::printf("bench impl=old case=strokes median_cpu_ms=%.2f last10_cpu_ms=%.2f median_ratio_old_over_new=%.2f same_volume=%d\n",
                median(old_cpu), median(old_last), median(ratio), int((work - work_old).is_empty() && (work_old - work).is_empty()));
  }
}
