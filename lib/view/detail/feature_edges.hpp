#pragma once
/// \file feature_edges.hpp
/// The feature edges of a polygon mesh (internal): the edges between two faces that do not lie in
/// one plane, and the edges that do not join exactly two faces (borders of open meshes,
/// non-manifold edges). Edges inside a flat region made of many faces (a carved block's top, 723
/// coplanar pieces) are not features, and since the faces are the exact boundary's polygons, not
/// their triangles, no triangulation diagonal is one.

#include <array>
#include <vector>

#include "mesh/polygon_mesh.hpp"

namespace sculpt::view::detail {

struct FeatureEdgeOptions {
  /// Faces whose unit normals differ by at most this (about the angle in radians) count as one
  /// plane: the mesh's double coordinates are rounded from exact ones, so the faces of one exact
  /// plane may tilt by rounding (far below anything visible).
  double coplanar_tolerance = 1e-7;
};

/// The feature edges as vertex index pairs (lo < hi), sorted. \pre face indices are valid.
std::vector<std::array<int, 2>> feature_edges(const PolygonMesh& mesh, const FeatureEdgeOptions& options = {});

}  // namespace sculpt::view::detail
