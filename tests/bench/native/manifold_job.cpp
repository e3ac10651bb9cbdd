// One run of the real-mesh job of issue 33 with native Manifold (the peer; ours is
// tests/bench/bsp/bench_mesh_job.cpp, which describes the job and the printed line). Manifold
// evaluates its CSG lazily: `difference` holds the evaluation of the whole tree, forced by
// GetMeshGL64() (the result as a mesh, as ours ends with to_mesh) and Volume(); only `total`
// compares with ours phase for phase.
//   manifold_job [--threads T] [--moved-copy] (--mesh FILE.off | --sphere N)
// Built by tests/bench/native_compare.sh against ../shared/peers' library.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <memory>
#include <sstream>
#include <string>

#include <tbb/global_control.h>
#include <tbb/info.h>

#include "manifold/manifold.h"

namespace {

using Clock = std::chrono::steady_clock;
double since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

// A triangle OFF file (as models/ and native_compare.sh's conversions write them).
bool read_off(const std::string& path, manifold::MeshGL64& mesh) {
  std::ifstream in(path);
  std::string magic;
  std::size_t nv = 0, nf = 0, ne = 0;
  if (!(in >> magic >> nv >> nf >> ne) || magic != "OFF") return false;
  mesh.numProp = 3;
  mesh.vertProperties.resize(3 * nv);
  for (auto& x : mesh.vertProperties)
    if (!(in >> x)) return false;
  for (std::size_t f = 0; f < nf; ++f) {
    std::size_t k = 0, a = 0, b = 0, c = 0;
    if (!(in >> k >> a >> b >> c) || k != 3) return false;
    mesh.triVerts.insert(mesh.triVerts.end(), {a, b, c});
  }
  return true;
}

}  // namespace

int main(int argc, char** argv) {
  using namespace manifold;
  int threads = 0, n = 0;
  bool moved_copy = false;
  std::string file;
  for (int i = 1; i < argc; i += 2) {
    const std::string a = argv[i];
    if (a == "--moved-copy") {
      moved_copy = true;
      --i;
      continue;
    }
    if (i + 1 >= argc) return 2;
    if (a == "--threads")
      threads = std::atoi(argv[i + 1]);
    else if (a == "--mesh")
      file = argv[i + 1];
    else if (a == "--sphere")
      n = std::atoi(argv[i + 1]);
    else
      return 2;
  }
  if (file.empty() == (n == 0)) return 2;
  std::unique_ptr<tbb::global_control> limit;
  if (threads > 0) limit = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism, threads);
  const int used = threads > 0 ? threads : tbb::info::default_concurrency();
  const auto start = Clock::now();
  double t_import = 0, t_turn = 0, t_union = 0, t_difference = 0;
  Manifold result;
  std::size_t in_triangles = 0;
  std::string name;
  if (!file.empty()) {
    name = file.substr(file.find_last_of('/') + 1);
    name = name.substr(0, name.rfind('.'));
    auto t = Clock::now();
    MeshGL64 mesh;
    if (!read_off(file, mesh)) {
      std::fprintf(stderr, "manifold_job: cannot read %s\n", file.c_str());
      return 1;
    }
    mesh.Merge();
    const Manifold m(mesh);
    if (m.Status() != Manifold::Error::NoError) {
      std::fprintf(stderr, "manifold_job: %s is not a manifold for Manifold\n", file.c_str());
      return 1;
    }
    t_import = since(t);
    in_triangles = mesh.NumTri();
    const Box box = m.BoundingBox();
    const vec3 c = (box.min + box.max) / 2.0;
    if (moved_copy) {
      name += "_minus_moved";
      t = Clock::now();
      const Manifold moved = m.Translate((box.max - box.min) / 10.0);
      t_turn = since(t);
      result = m - moved;
    } else {
      t = Clock::now();
      // Rotation by 33 degrees about (1, 1, 0) / sqrt(2) (Rodrigues), around c.
      const double a = 33 * M_PI / 180, s = std::sin(a), k = 1 - std::cos(a), u = 1 / std::sqrt(2.0);
      const mat3x4 r({1 - k * u * u, k * u * u, -s * u}, {k * u * u, 1 - k * u * u, s * u},
                     {s * u, -s * u, 1 - 2 * k * u * u}, {0.0, 0.0, 0.0});  // columns
      const Manifold turned = m.Translate(-c).Transform(r).Translate(c);
      t_turn = since(t);
      t = Clock::now();
      const Manifold un = m + turned;
      t_union = since(t);
      t = Clock::now();
      const vec3 size = box.max - box.min;
      const double radius = std::max(size.x, std::max(size.y, size.z)) / 4;
      result = un - Manifold::Sphere(radius, 48).Translate(c + 0.75 * (box.max - c));
    }
  } else {
    name = "sphere_minus_moved";
    auto t = Clock::now();
    const Manifold a = Manifold::Sphere(1.0, n), b = Manifold::Sphere(1.0, n).Translate({0.3, 0.2, 0.1});
    t_import = since(t);
    result = a - b;
  }
  // The result as a mesh, as our side's to_mesh gives it (what an export or a viewer needs).
  const auto t = Clock::now();
  const MeshGL64 out = result.GetMeshGL64();
  const double v = result.Volume();
  t_difference += since(t);
  std::printf(
      "bench case=%s n=%zu threads=%d import=%.4f turn=%.4f union=%.4f difference=%.4f total=%.4f volume=%.10g "
      "triangles_out=%zu\n",
      name.c_str(), file.empty() ? std::size_t(n) : in_triangles, used, t_import, t_turn, t_union, t_difference,
      since(start), v, out.NumTri());
  return 0;
}
