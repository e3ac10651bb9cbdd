#pragma once
/// \file convex_union.hpp
/// Internal: the union of convex polytopes given by their vertices (the segment hulls of a sweep,
/// bsp/sweep.hpp). Where unite_by_boundaries (batch_union.hpp) needs every operand's tree to clip
/// the others' boundaries, a convex polytope is its face planes: a boundary piece of one polytope
/// is clipped by the planes of each other polytope whose box meets it, the parts in front of a
/// plane kept (outside), the rest dropped (inside), with the batch union's rule for shared plane
/// regions (Naylor et al. 1990 sec. 5: where two operands bound the same plane region with the
/// same orientation, the one listed first keeps it; with opposite orientations neither). The face
/// polygons are built from the hull's triangles (each face clipped by its neighbours' planes
/// only), so no polytope's tree is built; one tree is built from the union's boundary
/// (autopartition.hpp). Every decision is an exact predicate.

#include <vector>

#include "bsp/solid.hpp"
#include "kernel/grid.hpp"

namespace sculpt::bsp::detail {

/// The regularized union of the convex hulls of `point_sets` (grid units of `grid`). A set whose
/// hull has no volume (all points in one plane) adds nothing. The solid carries its boundary.
Solid unite_convex_hulls(const std::vector<std::vector<kernel::GridPoint>>& point_sets, const kernel::Grid& grid);

}  // namespace sculpt::bsp::detail
