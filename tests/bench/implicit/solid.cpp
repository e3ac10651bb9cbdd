// Implicit solids: the torus R = 1, r = 0.4 meshed by implicit::polygonize at tol 2e-3 against
// uniform marching cubes (written here: classic MC, vertices by linear interpolation, or by root
// finding on the edges) at the grid size where MC reaches the same measured error. The error of
// every mesh is measured the same way, against the analytic torus, both ways: mesh vertices and
// points spread over each triangle to the torus (closed-form distance), and 600 x 300 points
// of the parametrization to the mesh. Times are thread CPU time, median of 5 runs.
//   implicit_solid               the table
//   implicit_solid --peers DIR   the table plus the peers' meshes and times that
//                                tests/bench/implicit/peers.sh left in DIR (run that script)
//   implicit_solid --blend       the blend of two spheres of scripts/implicit.bsp: time, coarse or fallback
//   implicit_solid --ours        only polygonize, 20 times (OURS_REPS=n: n times), and a fingerprint
//                                of its mesh (profiling; old and new code compared run against run)
// See docs/implicit.md, "Implicit solids", and docs/benchmarks.md.
#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <fstream>
#include <functional>
#include <numbers>
#include <string>
#include <unordered_map>
#include <vector>

#include "implicit/polygonize.hpp"
#include "bench/bench_timing.hpp"
#include "support/point_triangle.hpp"

using namespace sculpt;
using namespace sculpt::implicit;
using Vec = Eigen::Vector3d;

namespace {

constexpr double kR = 1.0, kr = 0.4, kTol = 2e-3;
constexpr double kPi = std::numbers::pi;
const Box kBox{.lo = Vec(-1.5, -1.5, -0.5), .hi = Vec(1.5, 1.5, 0.5)};

double torus_f(const Vec& p) {
  const double q = std::hypot(p.x(), p.y()) - kR;
  return q * q + p.z() * p.z() - kr * kr;
}

Expression torus() {
  ExpressionBuilder b;
  const Term rho = b.sqrt(b.add(b.pow(b.x(), 2), b.pow(b.y(), 2)));
  return b.finish(b.sub(b.add(b.pow(b.sub(rho, b.constant(kR)), 2), b.pow(b.z(), 2)), b.constant(kr * kr)));
}

/// The blend of two spheres in scripts/implicit.bsp: radius 0.6, centres (+-0.5, 0, 0), a smooth
/// minimum (k = 0.3) of their distances.
Expression blend() {
  ExpressionBuilder b;
  const Term y2 = b.add(b.pow(b.y(), 2), b.pow(b.z(), 2));
  const Term a = b.sub(b.sqrt(b.add(b.pow(b.add(b.x(), b.constant(0.5)), 2), y2)), b.constant(0.6));
  const Term c = b.sub(b.sqrt(b.add(b.pow(b.sub(b.x(), b.constant(0.5)), 2), y2)), b.constant(0.6));
  const Term k = b.constant(0.3);
  const Term h = b.div(b.max(b.sub(k, b.abs(b.sub(a, c))), b.constant(0.0)), k);
  return b.finish(b.sub(b.min(a, c), b.div(b.mul(b.mul(h, h), k), b.constant(4.0))));
}
const Box kBlendBox{.lo = Vec(-1.2, -0.8, -0.8), .hi = Vec(1.2, 0.8, 0.8)};

double torus_distance(const Vec& p) { return std::abs(std::hypot(std::hypot(p.x(), p.y()) - kR, p.z()) - kr); }

// ---- the error, both ways ------------------------------------------------------------------

struct Error {
  double to_surface = 0, to_mesh = 0;
  [[nodiscard]] double hausdorff() const { return std::max(to_surface, to_mesh); }
};

Error measure(const PolygonMesh& m) {
  Error e;
  for (const Vec& v : m.vertices) e.to_surface = std::max(e.to_surface, torus_distance(v));
  for (const auto& f : m.faces) {
    const Vec &a = m.vertices[f[0]], &b = m.vertices[f[1]], &c = m.vertices[f[2]];
    for (int i = 0; i <= 4; ++i)
      for (int j = 0; i + j <= 4; ++j)
        e.to_surface = std::max(e.to_surface, torus_distance((a * (4 - i - j) + b * i + c * j) / 4.0));
  }
  // triangles bucketed in a grid of cells 0.02 wide; a query looks one cell around
  const double cell = 0.02;
  auto key = [](long x, long y, long z) { return ((x + 1000) * 4000 + (y + 1000)) * 4000 + (z + 1000); };
  std::unordered_map<long, std::vector<int>> grid;
  for (int t = 0; t < int(m.faces.size()); ++t) {
    Eigen::AlignedBox3d box;
    for (int v : m.faces[t]) box.extend(m.vertices[v]);
    for (long x = long(std::floor(box.min().x() / cell)); x <= long(std::floor(box.max().x() / cell)); ++x)
      for (long y = long(std::floor(box.min().y() / cell)); y <= long(std::floor(box.max().y() / cell)); ++y)
        for (long z = long(std::floor(box.min().z() / cell)); z <= long(std::floor(box.max().z() / cell)); ++z)
          grid[key(x, y, z)].push_back(t);
  }
  const int n = 600;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n / 2; ++j) {
      const double u = 2 * kPi * (i + 0.37) / n, v = 2 * kPi * (j + 0.61) / (n / 2);
      const Vec p((kR + kr * std::cos(v)) * std::cos(u), (kR + kr * std::cos(v)) * std::sin(u), kr * std::sin(v));
      double best = cell;
      const long cx = long(std::floor(p.x() / cell)), cy = long(std::floor(p.y() / cell)), cz = long(std::floor(p.z() / cell));
      for (long x = cx - 1; x <= cx + 1; ++x)
        for (long y = cy - 1; y <= cy + 1; ++y)
          for (long z = cz - 1; z <= cz + 1; ++z) {
            const auto it = grid.find(key(x, y, z));
            if (it == grid.end()) continue;
            for (int t : it->second) {
              const auto& f = m.faces[t];
              best = std::min(best, test_support::point_triangle_distance(p, m.vertices[f[0]], m.vertices[f[1]], m.vertices[f[2]]));
            }
          }
      e.to_mesh = std::max(e.to_mesh, best);
    }
  return e;
}

// ---- uniform marching cubes ----------------------------------------------------------------

/// Classic marching cubes on a uniform grid of cubes of side h over kBox. Per cube, the crossed
/// edges get a vertex; on each face the crossings are paired (two per face, or four on an
/// ambiguous face, paired around its inside corners, the same rule from both cubes), the pairs
/// close into loops, and a loop of k vertices gives k - 2 triangles: the same triangles per case
/// as the 256-case table. Vertices by linear interpolation, or (roots) by Illinois on the edge.
PolygonMesh marching_cubes(double h, bool roots, const Expression* compiled = nullptr) {
  auto f_at = [&](const Vec& p) { return compiled ? compiled->value(p) : torus_f(p); };
  const Vec extent = kBox.hi - kBox.lo;
  const long nx = long(std::ceil(extent.x() / h)), ny = long(std::ceil(extent.y() / h)), nz = long(std::ceil(extent.z() / h));
  auto at = [&](long i, long j, long k) -> Vec { return kBox.lo + Vec(double(i), double(j), double(k)) * h; };
  std::vector<double> value(std::size_t((nx + 1) * (ny + 1) * (nz + 1)));
  auto index = [&](long i, long j, long k) { return std::size_t((i * (ny + 1) + j) * (nz + 1) + k); };
  for (long i = 0; i <= nx; ++i)
    for (long j = 0; j <= ny; ++j)
      for (long k = 0; k <= nz; ++k) value[index(i, j, k)] = f_at(at(i, j, k));
  PolygonMesh mesh;
  std::unordered_map<std::uint64_t, int> vertex_of_edge;
  // corners: bit 0 x, bit 1 y, bit 2 z; edges as corner pairs; faces as 4 corners in a cycle
  static constexpr std::array<std::array<int, 2>, 12> kEdges = {
      {{0, 1}, {2, 3}, {4, 5}, {6, 7}, {0, 2}, {1, 3}, {4, 6}, {5, 7}, {0, 4}, {1, 5}, {2, 6}, {3, 7}}};
  static constexpr std::array<std::array<int, 4>, 6> kFaces = {
      {{0, 2, 6, 4}, {1, 3, 7, 5}, {0, 1, 5, 4}, {2, 3, 7, 6}, {0, 1, 3, 2}, {4, 5, 7, 6}}};
  auto edge_of = [](int a, int b) {
    for (int e = 0; e < 12; ++e)
      if ((kEdges[e][0] == a && kEdges[e][1] == b) || (kEdges[e][0] == b && kEdges[e][1] == a)) return e;
    return -1;
  };
  for (long i = 0; i < nx; ++i)
    for (long j = 0; j < ny; ++j)
      for (long k = 0; k < nz; ++k) {
        std::array<long, 8> id{};
        std::array<double, 8> f{};
        std::array<bool, 8> in{};
        int count = 0;
        for (int c = 0; c < 8; ++c) {
          id[c] = long(index(i + (c & 1), j + ((c >> 1) & 1), k + (c >> 2)));
          f[c] = value[std::size_t(id[c])];
          count += (in[c] = f[c] <= 0) ? 1 : 0;
        }
        if (count == 0 || count == 8) continue;
        std::array<int, 12> vertex{};
        vertex.fill(-1);
        for (int e = 0; e < 12; ++e) {
          const int a = kEdges[e][0], b = kEdges[e][1];
          if (in[a] == in[b]) continue;
          const std::uint64_t key = std::uint64_t(std::min(id[a], id[b])) * 1000003ull + std::uint64_t(std::max(id[a], id[b]));
          auto it = vertex_of_edge.find(key);
          if (it == vertex_of_edge.end()) {
            const Vec pa = at(i + (a & 1), j + ((a >> 1) & 1), k + (a >> 2)), pb = at(i + (b & 1), j + ((b >> 1) & 1), k + (b >> 2));
            double ta = 0, tb = 1, fa = f[a], fb = f[b];
            double t = fa / (fa - fb);
            if (roots) {
              for (int it2 = 0; it2 < 50 && tb - ta > 1e-12; ++it2) {
                t = ta + (tb - ta) * fa / (fa - fb);
                const double ft = f_at(pa + t * (pb - pa));
                if ((ft <= 0) == (fa <= 0)) ta = t, fa = ft, fb *= 0.5;
                else tb = t, fb = ft, fa *= 0.5;
              }
            }
            it = vertex_of_edge.emplace(key, int(mesh.vertices.size())).first;
            mesh.vertices.push_back(pa + t * (pb - pa));
          }
          vertex[e] = it->second;
        }
        // segments on the faces, then loops (every crossed edge lies on two faces: two segments)
        std::array<std::vector<int>, 12> adjacent;
        for (const auto& face : kFaces) {
          std::array<int, 4> crossed{};
          int n = 0;
          for (int s = 0; s < 4; ++s) {
            const int e = edge_of(face[s], face[(s + 1) % 4]);
            if (vertex[e] >= 0) crossed[n++] = s;
          }
          auto link = [&](int s0, int s1) {
            const int e0 = edge_of(face[s0], face[(s0 + 1) % 4]), e1 = edge_of(face[s1], face[(s1 + 1) % 4]);
            adjacent[std::size_t(e0)].push_back(e1);
            adjacent[std::size_t(e1)].push_back(e0);
          };
          if (n == 2) link(crossed[0], crossed[1]);
          if (n == 4) {
            if (in[face[0]]) link(3, 0), link(1, 2);  // around corners 0 and 2
            else link(0, 1), link(2, 3);              // around corners 1 and 3
          }
        }
        std::array<bool, 12> used{};
        for (int start = 0; start < 12; ++start) {
          if (vertex[start] < 0 || used[start]) continue;
          std::vector<int> loop{start};
          used[start] = true;
          int previous = -1, current = start;
          while (true) {
            int step = -1;
            for (int e : adjacent[current])
              if (e != previous && !used[e]) step = e;
            if (step < 0) break;
            used[step] = true;
            loop.push_back(step);
            previous = current;
            current = step;
          }
          for (std::size_t t = 1; t + 1 < loop.size(); ++t)
            mesh.faces.push_back({vertex[loop[0]], vertex[loop[t]], vertex[loop[t + 1]]});
        }
      }
  return mesh;
}

/// Median thread CPU time of 5 runs (tests/bench/bench_timing.hpp).
double median_cpu_ms(const std::function<void()>& run) { return bench::median_ms(5, run).cpu; }

/// The coarsest grid (cells h = 3 / n) whose measured error is at most kTol.
double coarsest_within(bool roots, PolygonMesh& mesh, Error& error) {
  for (int n = 20; n <= 400; n += 2) {
    PolygonMesh m = marching_cubes(3.0 / n, roots);
    const Error e = measure(m);
    if (e.hausdorff() <= kTol) {
      mesh = std::move(m);
      error = e;
      return 3.0 / n;
    }
  }
  return 0;
}

/// A triangle mesh from an OFF file (the peers' output); empty when it cannot be read.
PolygonMesh read_off(const std::string& file) {
  PolygonMesh m;
  std::ifstream in(file);
  std::string magic;
  long nv = 0, nf = 0, ne = 0;
  if (!(in >> magic >> nv >> nf >> ne) || magic != "OFF") return {};
  m.vertices.resize(std::size_t(nv));
  for (Vec& v : m.vertices) in >> v.x() >> v.y() >> v.z();
  m.faces.resize(std::size_t(nf));
  for (auto& f : m.faces) {
    int k = 0;
    in >> k;
    f.resize(std::size_t(k));
    for (int& i : f) in >> i;
  }
  return in ? m : PolygonMesh{};
}

/// One peer result as tests/bench/implicit/peers.sh lists it: "name|setting|ms|file".
struct PeerRun {
  std::string name, setting, file;
  double ms = 0;
  PolygonMesh mesh;
  Error error;
};

std::vector<PeerRun> read_peers(const std::string& dir) {
  std::vector<PeerRun> out;
  std::ifstream list(dir + "/peers.txt");
  std::string line;
  while (std::getline(list, line)) {
    PeerRun r;
    std::size_t a = line.find('|'), b = line.find('|', a + 1), c = line.find('|', b + 1);
    if (c == std::string::npos) continue;
    r.name = line.substr(0, a);
    r.setting = line.substr(a + 1, b - a - 1);
    r.ms = std::stod(line.substr(b + 1, c - b - 1));
    r.file = line.substr(c + 1);
    r.mesh = read_off(r.file);
    if (r.mesh.faces.empty()) continue;
    r.error = measure(r.mesh);
    out.push_back(std::move(r));
  }
  return out;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc > 1 && std::string(argv[1]) == "--ours") {  // only polygonize, 20 times (for a profiler)
    const Expression f = torus();
    PolygonizeResult r;
    const int reps = std::getenv("OURS_REPS") ? std::atoi(std::getenv("OURS_REPS")) : 20;
    for (int i = 0; i < reps; ++i) r = polygonize(f, {.box = kBox, .tolerance = kTol});
    double sum = 0;  // a fingerprint of the mesh, to see that a change of speed changed nothing else
    for (const Vec& v : r.mesh.vertices) sum += v.x() + 2 * v.y() + 3 * v.z();
    std::printf("%zu triangles, %zu vertices, %ld marched, %ld edge splits, fingerprint %.17g\n", r.mesh.faces.size(),
                r.mesh.vertices.size(), r.marched_triangles, r.refinements, sum);
    return 0;
  }
  if (argc > 1 && std::string(argv[1]) == "--blend") {  // the blend of two spheres, as the language meshes it
    const Expression f = blend();
    // min_height as `implicit(...)` passes it: 8 steps of the kernel's grid (2^-15)
    const PolygonizeOptions o{.box = kBlendBox, .tolerance = kTol, .min_height = 8.0 / 32768.0};
    PolygonizeResult r;
    const double ms = median_cpu_ms([&] { r = polygonize(f, o); });
    std::printf("blend of two spheres at tol 2e-3: %zu triangles, %ld marched, %ld edge splits, %s octree, "
                "%.1f ms thread CPU (median of 5)\n",
                r.mesh.faces.size(), r.marched_triangles, r.refinements, r.coarse ? "coarse" : "fine (fallback)", ms);
    return 0;
  }
  // --peers DIR: also the peers' meshes and times that tests/bench/implicit/peers.sh left in DIR
  const std::string peers_dir = argc > 2 && std::string(argv[1]) == "--peers" ? argv[2] : "";
  double load[3] = {0, 0, 0};
  if (std::FILE* f = std::fopen("/proc/loadavg", "r")) {
    if (std::fscanf(f, "%lf %lf %lf", &load[0], &load[1], &load[2]) != 3) load[0] = -1;
    std::fclose(f);
  }
  std::printf("torus R = 1, r = 0.4, target Hausdorff %.0e; load average %.2f %.2f %.2f\n\n", kTol, load[0], load[1], load[2]);
  std::printf("| mesher | setting | triangles | vertices | mesh->surface | surface->mesh | CPU ms | triangles / ours | time / ours |\n");
  std::printf("|---|---|---|---|---|---|---|---|---|\n");
  const Expression f = torus();
  PolygonizeResult ours;
  const double ours_ms = median_cpu_ms([&] { ours = polygonize(f, {.box = kBox, .tolerance = kTol}); });
  const Error ours_error = measure(ours.mesh);
  auto row = [&](const char* name, const std::string& setting, const PolygonMesh& m, const Error& e, double ms) {
    std::printf("| %s | %s | %zu | %zu | %.2e | %.2e | %.1f | %.2f | %.2f |\n", name, setting.c_str(), m.faces.size(),
                m.vertices.size(), e.to_surface, e.to_mesh, ms, double(m.faces.size()) / double(ours.mesh.faces.size()),
                ms / ours_ms);
  };
  row("polygonize", "tol 2e-3", ours.mesh, ours_error, ours_ms);
  PolygonizeResult unsimplified;
  const double raw_ms = median_cpu_ms([&] { unsimplified = polygonize(f, {.box = kBox, .tolerance = kTol, .simplify = false}); });
  row("polygonize, no collapses", "tol 2e-3", unsimplified.mesh, measure(unsimplified.mesh), raw_ms);
  for (const bool roots : {false, true}) {
    PolygonMesh mc;
    Error e;
    const double h = coarsest_within(roots, mc, e);
    const double ms = median_cpu_ms([&] { mc = marching_cubes(h, roots); });
    char setting[64];
    std::snprintf(setting, sizeof setting, "cells %.4f (3/%d)", h, int(std::lround(3.0 / h)));
    row(roots ? "uniform MC, roots on edges" : "uniform MC, interpolated", setting, mc, e, ms);
    // the same grid evaluating the compiled expression, as polygonize does, instead of C++ code
    const double compiled_ms = median_cpu_ms([&] { mc = marching_cubes(h, roots, &f); });
    row(roots ? "uniform MC, roots, f compiled" : "uniform MC, interpolated, f compiled", setting, mc, e, compiled_ms);
  }
  if (!peers_dir.empty()) {
    // per peer, the setting with the fewest triangles whose measured error is within kTol
    const std::vector<PeerRun> peers = read_peers(peers_dir);
    std::vector<std::string> names;
    for (const PeerRun& p : peers)
      if (std::find(names.begin(), names.end(), p.name) == names.end()) names.push_back(p.name);
    for (const std::string& name : names) {
      const PeerRun* best = nullptr;
      for (const PeerRun& p : peers)
        if (p.name == name && p.error.hausdorff() <= kTol && (!best || p.mesh.faces.size() < best->mesh.faces.size())) best = &p;
      if (best) row(name.c_str(), best->setting, best->mesh, best->error, best->ms);
      else std::printf("| %s | no setting within %.0e | | | | | | | |\n", name.c_str(), kTol);
    }
    std::printf("\nall peer settings tried:\n\n| peer | setting | triangles | mesh->surface | surface->mesh | CPU ms |\n|---|---|---|---|---|---|\n");
    for (const PeerRun& p : peers)
      std::printf("| %s | %s | %zu | %.2e | %.2e | %.1f |\n", p.name.c_str(), p.setting.c_str(), p.mesh.faces.size(),
                  p.error.to_surface, p.error.to_mesh, p.ms);
  }
  std::printf("\npolygonize: %ld octree cells, %ld search cells, %ld leaves, depth %d, %ld tetrahedra marched, "
              "%ld triangles, %ld edge splits, then %ld collapses/flips (%s octree)\n",
              ours.cells, ours.search_cells, ours.leaves, ours.max_level, ours.tetrahedra, ours.marched_triangles,
              ours.refinements, ours.collapses, ours.coarse ? "coarse" : "fine");
  return 0;
}
