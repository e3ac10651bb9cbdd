// Trees built from meshes (B-rep to BSP, lib/bsp/from_mesh.hpp): for each input mesh, the time of
// from_mesh (median of RUNS, thread CPU time and wall time) and the tree's size, height, expected
// depth and entropy bound (Ihm & Naylor 1990 sec. 6; lib/reports/depth_cost.hpp) in the rebuilt
// solid's bounding box. docs/benchmarks.md, "Trees from meshes". One parseable line per case:
//   bench impl=sculpt case=<name> faces=<mesh faces> runs=<r> time_ms=<median wall> cpu_ms=<median cpu>
//         nodes=<partitioning nodes> height=<h> expected_depth=<E> entropy_bound=<H> ratio=<E/H>
//         volume=<V(solid)> mesh_volume=<V(mesh)>
// For the bunny also the whole of the language's `import` (read, validate, the snapped
// self-intersection check, from_mesh): case=bunny_import, time only.
//   bench_from_mesh [RUNS [CASE]]   CASE: goblet, bunny, menger, implicit_torus, implicit_blend,
//   implicit_shell, sphere64 (default: all; RUNS 15)
//   models are read from SCULPT_MODELS_DIR (the source tree's models/)
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <functional>
#include <string>
#include <vector>

#include "bsp/boundary.hpp"
#include "bsp/from_mesh.hpp"
#include "bsp/primitives.hpp"
#include "curves/digitized_curve.hpp"
#include "curves/profiles.hpp"
#include "implicit/polygonize.hpp"
#include "kernel/grid.hpp"
#include "mesh/mesh_io.hpp"
#include "mesh/mesh_measures.hpp"
#include "mesh/mesh_validation.hpp"
#include "mesh/self_intersection.hpp"
#include "reports/depth_cost.hpp"
#include "revolution/revolve.hpp"
#include "bench/bench_timing.hpp"
#include "support/bench_solids.hpp"

using namespace sculpt;

namespace {

using bench::cpu_ms;
using bench::median_ms;
using bench::Timing;

const std::string kModels = SCULPT_MODELS_DIR;

PolygonMesh goblet_mesh() {  // the outer goblet of Figure 11 (20 profile segments, 32-gon)
  const auto profile = curves::planar_points(curves::load_curve(kModels + "/goblet_profile_20.txt").points);
  return to_mesh(revolution::revolve(profile, circular_path(32)));
}

// The language's import (lib/language/builtins_solids.cpp) without the interpreter.
Solid import_mesh(const std::string& path) {
  const PolygonMesh mesh = read_mesh(path);
  if (!check_closed_manifold(mesh).ok()) throw std::runtime_error(path + " is not a closed manifold");
  PolygonMesh snapped = mesh;
  for (Eigen::Vector3d& v : snapped.vertices) v = kernel::to_world(kernel::snap(v));
  if (!find_self_intersections(snapped, {.max_pairs = 1}).empty()) throw std::runtime_error(path + ": snapped mesh self-intersects");
  return from_mesh(mesh);
}

// Meshes of the language's implicit() (polygonize with min_height 8 grid steps, as there;
// docs/implicit.md): the torus R = 1, r = 0.4 at tol 2e-3 (7,936 triangles), two spheres of
// radius 0.6 blended (k = 0.3) at tol 5e-3, a spherical shell 0.3 thick at tol 4e-3 (two shells).
PolygonMesh implicit_mesh(const std::string& name) {
  implicit::ExpressionBuilder b;
  const auto sq = [&](implicit::Term t) { return b.pow(t, 2); };
  const auto ball = [&](double cx, double r) {
    return b.sub(b.sqrt(b.add(b.add(sq(b.sub(b.x(), b.constant(cx))), sq(b.y())), sq(b.z()))), b.constant(r));
  };
  const double step = kernel::Grid{}.step();
  if (name == "torus") {
    const implicit::Term rho = b.sqrt(b.add(sq(b.x()), sq(b.y())));
    const implicit::Expression f = b.finish(b.sub(b.add(sq(b.sub(rho, b.constant(1.0))), sq(b.z())), b.constant(0.16)));
    return implicit::polygonize(f, {.box = {.lo = {-1.5, -1.5, -0.5}, .hi = {1.5, 1.5, 0.5}}, .tolerance = 2e-3, .min_height = 8 * step}).mesh;
  }
  if (name == "blend") {  // min(a, b) - h^2 k / 4, h = max(k - |a - b|, 0) / k
    const implicit::Term a = ball(-0.5, 0.6), c = ball(0.5, 0.6), k = b.constant(0.3);
    const implicit::Term h = b.div(b.max(b.sub(k, b.abs(b.sub(a, c))), b.constant(0.0)), k);
    const implicit::Expression f = b.finish(b.sub(b.min(a, c), b.div(b.mul(sq(h), k), b.constant(4.0))));
    return implicit::polygonize(f, {.box = {.lo = {-1.4, -0.9, -0.9}, .hi = {1.4, 0.9, 0.9}}, .tolerance = 5e-3, .min_height = 8 * step}).mesh;
  }
  const implicit::Expression f = b.finish(b.sub(b.abs(ball(0.0, 0.6)), b.constant(0.15)));  // "shell"
  return implicit::polygonize(f, {.box = {.lo = {-1, -1, -1}, .hi = {1, 1, 1}}, .tolerance = 4e-3, .min_height = 8 * step}).mesh;
}

// Options from the environment (FROM_MESH_CANDIDATES etc.), for trying settings.
FromMeshOptions options_from_env() {
  FromMeshOptions o;
  o.skip_degenerate_faces = true;  // as implicit() and the transforms (the other meshes have none)
  auto get = [](const char* name, double fallback) {
    const char* v = std::getenv(name);
    return v ? std::atof(v) : fallback;
  };
  o.candidates = int(get("FROM_MESH_CANDIDATES", o.candidates));
  o.sample = int(get("FROM_MESH_SAMPLE", o.sample));
  o.split_weight = get("FROM_MESH_SPLIT_WEIGHT", o.split_weight);
  o.volume_samples = int(get("FROM_MESH_VOLUME_SAMPLES", o.volume_samples));
  o.point_sample = int(get("FROM_MESH_POINT_SAMPLE", o.point_sample));
  o.auxiliary_planes = get("FROM_MESH_AUXILIARY_PLANES", o.auxiliary_planes) != 0;
  o.auxiliary_cost = get("FROM_MESH_AUXILIARY_COST", o.auxiliary_cost);
  o.separating_planes = get("FROM_MESH_SEPARATING_PLANES", o.separating_planes) != 0;
  return o;
}

void run_case(const std::string& name, const PolygonMesh& mesh, int runs) {
  Solid s;
  const FromMeshOptions options = options_from_env();
  const Timing t = median_ms(runs, [&] { s = from_mesh(mesh, options); });
  const reports::DepthCost d = reports::depth_cost(s);
  std::printf("bench impl=sculpt case=%s faces=%zu runs=%d time_ms=%.2f cpu_ms=%.2f nodes=%d height=%d "
              "expected_depth=%.4f entropy_bound=%.4f ratio=%.3f volume=%.10g mesh_volume=%.10g\n",
              name.c_str(), mesh.faces.size(), runs, t.wall, t.cpu, d.nodes, d.height, d.expected_depth,
              d.entropy_bound, d.ratio, volume(s), mesh_volume(mesh));
  if (std::getenv("BENCH_HISTOGRAM"))
    for (const reports::DepthBin& b : d.histogram)
      std::printf("  depth %3d: in %5d cells p %.4f, out %5d cells p %.4f\n", b.depth, b.in_cells, b.in_probability,
                  b.out_cells, b.out_probability);
  std::fflush(stdout);
}

}  // namespace

int main(int argc, char** argv) {
  const int runs = argc > 1 ? std::max(1, std::atoi(argv[1])) : 15;
  const std::string only = argc > 2 ? argv[2] : "";
  try {
    if (only.empty() || only == "goblet") run_case("goblet", goblet_mesh(), runs);
    if (only.empty() || only == "bunny") {
      run_case("bunny", read_mesh(kModels + "/bunny.off"), runs);
      const Timing t = median_ms(runs, [&] { (void)import_mesh(kModels + "/bunny.off"); });
      std::printf("bench impl=sculpt case=bunny_import runs=%d time_ms=%.2f cpu_ms=%.2f\n", runs, t.wall, t.cpu);
    }
    if (only.empty() || only == "menger") run_case("menger", to_mesh(checks::menger_sponge(3)), runs);
    for (const char* shape : {"torus", "blend", "shell"})
      if (only.empty() || only == std::string("implicit_") + shape) run_case(std::string("implicit_") + shape, implicit_mesh(shape), runs);
    if (only.empty() || only == "sphere64") run_case("sphere64", to_mesh(sphere(1.0, {.segments = 64})), runs);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bench_from_mesh: %s\n", e.what());
    return 1;
  }
  return 0;
}
