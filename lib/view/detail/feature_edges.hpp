#pragma once
/// \file feature_edges.hpp
/// The feature edges of a polygon mesh (internal): the edges between two faces that do not lie in
/// one plane, and the edges that do not join exactly two faces (borders of open meshes,
/// non-manifold edges). Edges inside a flat region made of many faces (a carved block's top, 723
/// coplanar pieces) are not features, and since the faces are the exact boundary's polygons, not
/// their triangles, no triangulation diagonal is one.
///
/// Among the features, the creases are those where the surface turns by more than a crease
/// angle (and the borders): a faceted curved surface (every facet of a sphere is its own plane)
/// has feature edges between all its facets but no crease, so the page shades it smooth and
/// splits its vertex normals only at creases.

#include <array>
#include <cstddef>
#include <vector>

#include "mesh/polygon_mesh.hpp"

namespace sculpt::view::detail {

struct FeatureEdgeOptions {
  /// Faces whose unit normals differ by at most this (about the angle in radians) count as one
  /// plane: the mesh's double coordinates are rounded from exact ones, so the faces of one exact
  /// plane may tilt by rounding (far below anything visible).
  double coplanar_tolerance = 1e-7;
  /// Two faces meeting at an angle between their normals above this (radians; 35 degrees) meet
  /// at a crease: a 10-sided prism's sides still do, a 12-sided one's and a 32-segment sphere's
  /// facets (11.25 degrees) do not.
  double crease_angle = 0.6108652381980153;
};

/// The feature edges as vertex index pairs (lo < hi), sorted. \pre face indices are valid.
std::vector<std::array<int, 2>> feature_edges(const PolygonMesh& mesh, const FeatureEdgeOptions& options = {});

/// The feature edges with the creases first.
struct ClassifiedEdges {
  std::vector<std::array<int, 2>> edges;  ///< creases (sorted), then the other features (sorted)
  std::size_t creases = 0;                ///< how many of `edges` are creases
};

/// feature_edges(mesh, options), creases first. \pre face indices are valid.
ClassifiedEdges classified_feature_edges(const PolygonMesh& mesh, const FeatureEdgeOptions& options = {});

}  // namespace sculpt::view::detail
