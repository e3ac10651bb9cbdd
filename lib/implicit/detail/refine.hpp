#pragma once
/// \file refine.hpp
/// More triangles where a closed triangle mesh with its vertices on f = 0 is too far from the
/// surface: edge splits with the new vertex moved onto f = 0 by Newton steps along the gradient.
/// polygonize.hpp marches a coarse octree (cells sized for a flat piece within a few tol) and
/// lets this put back the vertices the coarse cells lack, far fewer than a fine octree marches;
/// the edge collapses (simplify.hpp) then run on a mesh already close to final. An edge split
/// keeps a mesh closed, oriented and 2-manifold; a split whose triangles would turn over (the
/// projection landed elsewhere, or a sliver's new triangle) is not made, and the refinement fails
/// (the caller falls back) when a triangle left so is farther from f = 0 than the limit.

#include <vector>

#include "implicit/expression.hpp"
#include "mesh/polygon_mesh.hpp"

namespace sculpt::implicit::detail {

struct RefineOptions {
  double tolerance = 0.0;    ///< absolute: a triangle is split while its centroid or an edge midpoint is farther
  /// A split that cannot be made (the projection fails, or a new triangle would face against
  /// grad f) leaves its triangle; the refinement fails if any triangle is then farther than this
  /// (same points; triangles at the box are not judged).
  double limit = 0.0;
  double min_edge = 0.0;     ///< edges shorter than this are not split (creases of f never meet the bound)
  long max_splits = 0;       ///< work budget; running out fails the refinement
  /// New vertices must lie in this box (the solid's): a midpoint whose projection onto f = 0
  /// leaves it is not split there. Empty (lo > hi, the default): no bound.
  Box box{.lo = Eigen::Vector3d::Constant(1.0), .hi = Eigen::Vector3d::Constant(-1.0)};
};

struct RefineResult {
  bool ok = false;        ///< false: a triangle beyond the limit, a mesh not closed, or the budget ran out
  long splits = 0;
};

/// Splits edges of `mesh` (triangles, closed, counter-clockwise from outside) in place until every
/// triangle is within options.tolerance of f = 0 at its centroid and edge midpoints (first-order
/// distance |f| / |grad f|), where splits can be made. Triangles with a `locked` vertex (on the
/// box) are not split.
/// `locked` grows with the mesh (new vertices are not locked).
RefineResult refine(PolygonMesh& mesh, std::vector<bool>& locked, const Expression& f, const RefineOptions& options);

}  // namespace sculpt::implicit::detail
