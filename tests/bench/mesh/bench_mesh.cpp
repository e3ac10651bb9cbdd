// Validation and I/O of large meshes: a triangulated UV sphere with n segments (n^2 / 2 quads).
//   bench_mesh [segments=448] [dir=/tmp]
// Prints one "bench key=value ..." line per measurement (median of 3 runs).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <numbers>
#include <string>
#include <vector>

#include "mesh/mesh_io.hpp"
#include "mesh/mesh_validation.hpp"
#include "mesh/triangulate.hpp"
#include "mesh/shapes.hpp"  // tests/mesh: the test meshes

namespace {

using sculpt::PolygonMesh;

using sculpt::test_shapes::uv_sphere;

double median_ms(const std::function<void()>& f) {
  std::vector<double> t;
  for (int r = 0; r < 3; ++r) {
    const auto t0 = std::chrono::steady_clock::now();
    f();
    t.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
  }
  std::sort(t.begin(), t.end());
  return t[1];
}

}  // namespace

int main(int argc, char** argv) {
  const int segments = argc > 1 ? std::max(8, std::atoi(argv[1])) : 448;
  const std::filesystem::path dir = argc > 2 ? argv[2] : "/tmp";
  const PolygonMesh mesh = sculpt::triangulate(uv_sphere(segments));
  const size_t faces = mesh.faces.size();
  bool ok = false;
  double t = median_ms([&] { ok = sculpt::check_closed_manifold(mesh).ok(); });
  std::printf("bench case=validate faces=%zu time_ms=%.1f valid=%d\n", faces, t, ok ? 1 : 0);
  t = median_ms([&] { ok = sculpt::check_closed_manifold(mesh, {.check_self_intersections = false}).ok(); });
  std::printf("bench case=validate_topology_only faces=%zu time_ms=%.1f valid=%d\n", faces, t, ok ? 1 : 0);
  struct Format {
    const char* name;
    const char* ext;
    bool binary;
  };
  for (const Format& f : {Format{"off", ".off", false}, Format{"obj", ".obj", false}, Format{"ply", ".ply", false},
                          Format{"ply_binary", ".ply", true}, Format{"stl", ".stl", false},
                          Format{"stl_binary", ".stl", true}}) {
    const auto path = dir / (std::string("sculpt_bench_mesh_") + f.name + f.ext);
    const double w = median_ms([&] { sculpt::write_mesh(mesh, path, {.binary = f.binary}); });
    size_t vertices = 0;
    const double r = median_ms([&] { vertices = sculpt::read_mesh(path).vertices.size(); });
    std::printf("bench case=io format=%s faces=%zu write_ms=%.1f read_ms=%.1f bytes=%ju vertices_read=%zu\n", f.name,
                faces, w, r, static_cast<uintmax_t>(std::filesystem::file_size(path)), vertices);
    std::filesystem::remove(path);
  }
  return 0;
}
