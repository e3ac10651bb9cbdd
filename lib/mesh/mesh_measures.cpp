#include "mesh/mesh_measures.hpp"

#include <cmath>
#include <numeric>
#include <string>

#include "base/errors.hpp"
#include "mesh/edge_incidence.hpp"

namespace sculpt {
namespace {

/// Neumaier's compensated sum.
class Sum {
 public:
  void add(double x) {
    const double t = sum_ + x;
    comp_ += std::abs(sum_) >= std::abs(x) ? (sum_ - t) + x : (x - t) + sum_;
    sum_ = t;
  }
  [[nodiscard]] double value() const { return sum_ + comp_; }

 private:
  double sum_ = 0, comp_ = 0;
};

struct UnionFind {
  explicit UnionFind(size_t n) : parent(n) { std::iota(parent.begin(), parent.end(), 0); }
  int find(int x) {
    while (parent[x] != x) x = parent[x] = parent[parent[x]];  // path halving, no recursion
    return x;
  }
  void unite(int a, int b) { parent[find(a)] = find(b); }
  std::vector<int> parent;
};

}  // namespace

double mesh_volume(const PolygonMesh& mesh) {
  check_face_indices(mesh, "mesh_volume");
  const Eigen::AlignedBox3d box = mesh_bounding_box(mesh);
  if (box.isEmpty()) return 0;
  const Eigen::Vector3d ref = box.center();  // reduces cancellation far from the origin
  Sum sum;
  for (const auto& f : mesh.faces) {
    const Eigen::Vector3d a = mesh.vertices[f[0]] - ref;
    for (size_t i = 1; i + 1 < f.size(); ++i) {
      const Eigen::Vector3d b = mesh.vertices[f[i]] - ref;
      const Eigen::Vector3d c = mesh.vertices[f[i + 1]] - ref;
      sum.add(a.dot(b.cross(c)));
    }
  }
  return sum.value() / 6.0;
}

double mesh_surface_area(const PolygonMesh& mesh) {
  check_face_indices(mesh, "mesh_surface_area");
  Sum sum;
  for (const auto& f : mesh.faces) {
    const Eigen::Vector3d o = mesh.vertices[f[0]];
    Eigen::Vector3d n = Eigen::Vector3d::Zero();
    for (size_t i = 1; i + 1 < f.size(); ++i)
      n += (mesh.vertices[f[i]] - o).cross(mesh.vertices[f[i + 1]] - o);
    sum.add(0.5 * n.norm());
  }
  return sum.value();
}

Eigen::AlignedBox3d mesh_bounding_box(const PolygonMesh& mesh) {
  check_face_indices(mesh, "mesh_bounding_box");
  Eigen::AlignedBox3d box;  // empty
  for (const auto& f : mesh.faces)
    for (int id : f) box.extend(mesh.vertices[id]);
  return box;
}

int euler_characteristic(const PolygonMesh& mesh) {
  check_face_indices(mesh, "euler_characteristic");
  std::vector<char> used(mesh.vertices.size(), 0);
  for (const auto& f : mesh.faces)
    for (int id : f) used[id] = 1;
  const long long v = std::count(used.begin(), used.end(), 1);
  const auto records = sorted_edge_records(mesh);
  long long e = 0;
  for (size_t i = 0; i < records.size(); ++i)
    if (i == 0 || records[i].lo != records[i - 1].lo || records[i].hi != records[i - 1].hi) ++e;
  return static_cast<int>(v - e + static_cast<long long>(mesh.faces.size()));
}

std::vector<int> face_components(const PolygonMesh& mesh) {
  check_face_indices(mesh, "face_components");
  UnionFind uf(mesh.vertices.size());
  for (const auto& f : mesh.faces)
    for (size_t k = 1; k < f.size(); ++k) uf.unite(f[0], f[k]);
  std::vector<int> label(mesh.vertices.size(), -1);
  std::vector<int> out;
  out.reserve(mesh.faces.size());
  int next = 0;
  for (const auto& f : mesh.faces) {
    int& l = label[uf.find(f[0])];
    if (l < 0) l = next++;
    out.push_back(l);
  }
  return out;
}

int component_count(const PolygonMesh& mesh) {
  const auto labels = face_components(mesh);
  int n = 0;
  for (int l : labels) n = std::max(n, l + 1);
  return n;
}

int genus(const PolygonMesh& mesh) {
  const auto records = sorted_edge_records(mesh);  // indices checked below by euler_characteristic
  const int chi = euler_characteristic(mesh);
  for (size_t i = 0; i < records.size();) {
    size_t j = i;
    while (j < records.size() && records[j].lo == records[i].lo && records[j].hi == records[i].hi)
      ++j;
    if (j - i != 2)
      throw GeometryError("genus: the mesh is not closed: edge (" + std::to_string(records[i].lo) +
                          ", " + std::to_string(records[i].hi) + ") has " +
                          std::to_string(j - i) + " faces instead of 2");
    i = j;
  }
  const int twice = 2 * component_count(mesh) - chi;
  if (twice % 2 != 0)
    throw GeometryError("genus: 2 * components - Euler characteristic = " + std::to_string(twice) +
                        " is odd (the mesh is not an orientable closed surface)");
  return twice / 2;
}

}  // namespace sculpt
