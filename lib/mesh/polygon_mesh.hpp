#pragma once
/// \file polygon_mesh.hpp
/// The plain polygon mesh that flows out of solids (boundary extraction) and through
/// mesh I/O. Faces are counter-clockwise seen from outside (outward normals).

#include <Eigen/Core>
#include <array>
#include <vector>

namespace sculpt {

struct PolygonMesh {
  std::vector<Eigen::Vector3d> vertices;
  std::vector<std::vector<int>> faces;  ///< vertex indices, counter-clockwise from outside
};

/// A mesh of triangles only, each face three indices in place (12 bytes a face, where a
/// PolygonMesh face is a vector of its own: 56 bytes with its allocation). What a solid made
/// from a triangle mesh keeps of it (bsp/tree/deferred_tree.hpp).
struct TriangleMesh {
  std::vector<Eigen::Vector3d> vertices;
  std::vector<std::array<int, 3>> triangles;  ///< vertex indices, counter-clockwise from outside
};

/// The same faces as a PolygonMesh.
inline PolygonMesh to_polygon_mesh(const TriangleMesh& mesh) {
  PolygonMesh out;
  out.vertices = mesh.vertices;
  out.faces.reserve(mesh.triangles.size());
  for (const auto& t : mesh.triangles) out.faces.push_back({t[0], t[1], t[2]});
  return out;
}

}  // namespace sculpt
