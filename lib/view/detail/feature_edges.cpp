#include "view/detail/feature_edges.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

#include "mesh/edge_incidence.hpp"

namespace sculpt::view::detail {
namespace {

/// The unit normal of a face by Newell's method (exact for planar polygons up to rounding), or
/// zero for a face without area.
Eigen::Vector3d unit_normal(const PolygonMesh& mesh, const std::vector<int>& face) {
  Eigen::Vector3d n = Eigen::Vector3d::Zero();
  const Eigen::Vector3d& origin = mesh.vertices[face[0]];
  for (std::size_t k = 1; k + 1 < face.size(); ++k)
    n += (mesh.vertices[face[k]] - origin).cross(mesh.vertices[face[k + 1]] - origin);
  const double length = n.norm();
  return length > 0 ? Eigen::Vector3d(n / length) : Eigen::Vector3d::Zero();
}

}  // namespace

ClassifiedEdges classified_feature_edges(const PolygonMesh& mesh, const FeatureEdgeOptions& options) {
  std::vector<Eigen::Vector3d> normals;
  normals.reserve(mesh.faces.size());
  for (const auto& face : mesh.faces) normals.push_back(unit_normal(mesh, face));
  const std::vector<HalfEdgeRecord> records = sorted_edge_records(mesh);
  const double crease_cosine = std::cos(options.crease_angle);
  std::vector<std::array<int, 2>> creases, smooth;
  for (std::size_t begin = 0; begin < records.size();) {
    std::size_t end = begin + 1;
    while (end < records.size() && records[end].lo == records[begin].lo && records[end].hi == records[begin].hi) ++end;
    const std::array<int, 2> edge{records[begin].lo, records[begin].hi};
    if (end - begin != 2) {
      creases.push_back(edge);  // a border or a non-manifold edge
    } else {
      const Eigen::Vector3d& a = normals[records[begin].face];
      const Eigen::Vector3d& b = normals[records[begin + 1].face];
      // A face without area lies in any plane; else the two planes must agree in direction.
      const bool flat = a.isZero() || b.isZero() || (a.dot(b) > 0 && a.cross(b).norm() <= options.coplanar_tolerance);
      if (!flat) (a.dot(b) < crease_cosine ? creases : smooth).push_back(edge);
    }
    begin = end;
  }
  ClassifiedEdges out;
  out.creases = creases.size();
  out.edges = std::move(creases);
  out.edges.insert(out.edges.end(), smooth.begin(), smooth.end());
  return out;
}

std::vector<std::array<int, 2>> feature_edges(const PolygonMesh& mesh, const FeatureEdgeOptions& options) {
  std::vector<std::array<int, 2>> edges = classified_feature_edges(mesh, options).edges;
  std::sort(edges.begin(), edges.end());
  return edges;
}

}  // namespace sculpt::view::detail
