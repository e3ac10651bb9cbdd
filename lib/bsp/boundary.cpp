#include "bsp/boundary.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "bsp/tree/boundary_fragments.hpp"
#include "bsp/assembly/mesh_assembly.hpp"

namespace sculpt {

PolygonMesh to_mesh(const Solid& solid, const MeshOptions& options) {
  if (is_leaf(solid.root())) return {};
  // A carried boundary (set operation results) is used as is; otherwise it is extracted.
  detail::Fragments f = solid.has_boundary() ? detail::Fragments{solid.planes(), solid.boundary()}
                                             : detail::boundary_fragments(solid);
  return detail::assemble_mesh(f, {.triangulate = options.triangulate});
}

namespace {

struct Measures {
  double volume = 0, area = 0;
};

Measures measure(const PolygonMesh& m) {
  Measures r;
  if (m.vertices.empty()) return r;
  Eigen::Vector3d c = Eigen::Vector3d::Zero();
  for (const auto& v : m.vertices) c += v;
  c /= double(m.vertices.size());
  for (const auto& face : m.faces) {
    // Faces may be non-convex: the area is the norm of the summed (signed) fan vector areas.
    const Eigen::Vector3d a = m.vertices[std::size_t(face[0])] - c;
    Eigen::Vector3d vector_area = Eigen::Vector3d::Zero();
    for (std::size_t i = 1; i + 1 < face.size(); ++i) {
      const Eigen::Vector3d b = m.vertices[std::size_t(face[i])] - c;
      const Eigen::Vector3d d = m.vertices[std::size_t(face[i + 1])] - c;
      r.volume += a.dot(b.cross(d)) / 6.0;
      vector_area += (b - a).cross(d - a);
    }
    r.area += 0.5 * vector_area.norm();
  }
  return r;
}

}  // namespace

double volume(const Solid& solid) { return measure(to_mesh(solid)).volume; }
double surface_area(const Solid& solid) { return measure(to_mesh(solid)).area; }

Eigen::AlignedBox3d bounding_box(const Solid& solid) {
  Eigen::AlignedBox3d box;
  for (const auto& v : to_mesh(solid).vertices) box.extend(v);
  return box;
}

}  // namespace sculpt
