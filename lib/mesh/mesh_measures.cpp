#include "mesh/mesh_measures.hpp"

#include <cmath>
#include <numeric>
#include <string>
#include <string_view>

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

namespace {

// The faces of a mesh, or of a soup, as point cycles: face(i) calls f(point k) for k < size(i).
struct MeshFaces {
  const PolygonMesh& mesh;
  [[nodiscard]] std::size_t count() const { return mesh.faces.size(); }
  [[nodiscard]] std::size_t size(std::size_t i) const { return mesh.faces[i].size(); }
  [[nodiscard]] const Eigen::Vector3d& point(std::size_t i, std::size_t k) const {
    return mesh.vertices[std::size_t(mesh.faces[i][k])];
  }
};
/// \throw InvalidInput naming `who` if a triangle refers to a vertex the mesh does not have.
void check_triangle_indices(const TriangleMesh& mesh, std::string_view who) {
  const auto n = static_cast<long long>(mesh.vertices.size());
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t)
    for (int id : mesh.triangles[t])
      if (id < 0 || id >= n)
        throw InvalidInput(std::string(who) + ": triangle " + std::to_string(t) + " refers to vertex " +
                           std::to_string(id) + " but the mesh has " + std::to_string(n) + " vertices");
}

struct TriangleFaces {
  const TriangleMesh& mesh;
  [[nodiscard]] std::size_t count() const { return mesh.triangles.size(); }
  [[nodiscard]] static std::size_t size(std::size_t) { return 3; }
  [[nodiscard]] const Eigen::Vector3d& point(std::size_t i, std::size_t k) const {
    return mesh.vertices[std::size_t(mesh.triangles[i][k])];
  }
};
struct SoupFaces {
  const PolygonSoup& soup;
  [[nodiscard]] std::size_t count() const { return soup.offsets.size() - 1; }
  [[nodiscard]] std::size_t size(std::size_t i) const { return soup.offsets[i + 1] - soup.offsets[i]; }
  [[nodiscard]] const Eigen::Vector3d& point(std::size_t i, std::size_t k) const {
    return soup.points[soup.offsets[i] + k];
  }
};

// Fan tetrahedra (v0, vi, vi+1) against the box centre (reduces cancellation far from the origin).
template <class Faces>
double volume_of(const Faces& faces) {
  Eigen::AlignedBox3d box;
  for (std::size_t i = 0; i < faces.count(); ++i)
    for (std::size_t k = 0; k < faces.size(i); ++k) box.extend(faces.point(i, k));
  if (box.isEmpty()) return 0;
  const Eigen::Vector3d ref = box.center();
  Sum sum;
  for (std::size_t i = 0; i < faces.count(); ++i) {
    const Eigen::Vector3d a = faces.point(i, 0) - ref;
    for (std::size_t k = 1; k + 1 < faces.size(i); ++k) {
      const Eigen::Vector3d b = faces.point(i, k) - ref;
      const Eigen::Vector3d c = faces.point(i, k + 1) - ref;
      sum.add(a.dot(b.cross(c)));
    }
  }
  return sum.value() / 6.0;
}

// Half the norm of each face's fan normal.
template <class Faces>
double area_of(const Faces& faces) {
  Sum sum;
  for (std::size_t i = 0; i < faces.count(); ++i) {
    if (faces.size(i) == 0) continue;
    const Eigen::Vector3d o = faces.point(i, 0);
    Eigen::Vector3d n = Eigen::Vector3d::Zero();
    for (std::size_t k = 1; k + 1 < faces.size(i); ++k) n += (faces.point(i, k) - o).cross(faces.point(i, k + 1) - o);
    sum.add(0.5 * n.norm());
  }
  return sum.value();
}

}  // namespace

double mesh_volume(const PolygonMesh& mesh) {
  check_face_indices(mesh, "mesh_volume");
  return volume_of(MeshFaces{mesh});
}

double mesh_surface_area(const PolygonMesh& mesh) {
  check_face_indices(mesh, "mesh_surface_area");
  return area_of(MeshFaces{mesh});
}

double mesh_volume(const TriangleMesh& mesh) {
  check_triangle_indices(mesh, "mesh_volume");
  return volume_of(TriangleFaces{mesh});
}

double mesh_surface_area(const TriangleMesh& mesh) {
  check_triangle_indices(mesh, "mesh_surface_area");
  return area_of(TriangleFaces{mesh});
}

double soup_volume(const PolygonSoup& soup) { return volume_of(SoupFaces{soup}); }
double soup_surface_area(const PolygonSoup& soup) { return area_of(SoupFaces{soup}); }

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
