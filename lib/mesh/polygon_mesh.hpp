#pragma once
/// \file polygon_mesh.hpp
/// The plain polygon mesh that flows out of solids (boundary extraction) and through
/// mesh I/O. Faces are counter-clockwise seen from outside (outward normals).

#include <Eigen/Core>
#include <vector>

namespace sculpt {

struct PolygonMesh {
  std::vector<Eigen::Vector3d> vertices;
  std::vector<std::vector<int>> faces;  ///< vertex indices, counter-clockwise from outside
};

}  // namespace sculpt
