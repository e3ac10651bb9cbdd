#pragma once
/// \file simplify.hpp
/// Fewer triangles where the surface is flat: half-edge collapses on a closed triangle mesh whose
/// vertices lie on f = 0 (the marching-tetrahedra mesh of polygonize.hpp). A vertex is merged
/// into a neighbour only when the mesh stays a 2-manifold (link condition), no changed triangle
/// turns by more than 60 degrees or away from the surface normal, and every changed triangle
/// stays within `tolerance` of f = 0 (first-order distance |f| / |grad f| at its centroid and
/// the midpoints of its new edges) and passes within it of the removed vertex. Vertices on the
/// box (`locked`) are kept.

#include <cstdint>
#include <vector>

#include "implicit/expression.hpp"
#include "mesh/polygon_mesh.hpp"

namespace sculpt::implicit::detail {

struct SimplifyOptions {
  double tolerance = 0.0;  ///< absolute
  int passes = 4;          ///< sweeps over all vertices
  /// Then triangles less high than this (2 area / longest edge) are collapsed away where the
  /// same checks allow it with the distance bound relaxed to 8/7 tolerance: slivers that
  /// snapping the vertices to a grid could turn over.
  double min_height = 0.0;
  /// Try every vertex in every sweep. Off (the default), a vertex is tried again only when a
  /// collapse changed its own triangles since its last try, or its neighbours' triangles and a
  /// try had failed on the topological checks (link condition, degrees), which skips only tries
  /// that would fail again; the result is the same (tests compare both), the work less.
  bool retry_all = false;
  /// For each vertex, the sides of the box it lies on (bit 2 axis + (0: lo, 1: hi)). A triangle
  /// made by a collapse or a flip whose three vertices share a side would lie in that face of the
  /// box, over the triangles that close the solid there: such a change is refused. Empty: none.
  std::vector<std::uint8_t> box_sides = {};
};

struct SimplifyResult {
  PolygonMesh mesh;        ///< the simplified mesh (removed vertices dropped, the rest renumbered)
  int collapses = 0;
  int thin_triangles = 0;  ///< triangles still below min_height
};

/// Collapses edges of a copy of `mesh` (faces stay triangles); `mesh` itself is not changed.
SimplifyResult simplify(const PolygonMesh& mesh, const std::vector<bool>& locked, const Expression& f, const SimplifyOptions& options);

}  // namespace sculpt::implicit::detail
