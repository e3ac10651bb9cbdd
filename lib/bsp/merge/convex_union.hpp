#pragma once
/// \file convex_union.hpp
/// Internal: the union of convex polytopes given by their vertices (the segment hulls of a sweep,
/// bsp/sweep.hpp). Where unite_by_boundaries (batch_union.hpp) needs every operand's tree to clip
/// the others' boundaries, a convex polytope is its face planes: a boundary piece of one polytope
/// is clipped by the planes of each other polytope whose box meets it, the parts in front of a
/// plane kept (outside), the rest dropped (inside), with the batch union's rule for shared plane
/// regions (Naylor et al. 1990 sec. 5: where two operands bound the same plane region with the
/// same orientation, the one listed first keeps it; with opposite orientations neither). The face
/// polygons are read off the hull's triangles and their adjacency (corners at hull vertices, exact
/// grid points), so no polytope's tree is built; one tree is built from the union's boundary
/// (autopartition.hpp). Quick tests come first: a piece inside another hull's inscribed capsule
/// is inside it, and a piece that is still a whole face is decided from its corners' sides of the
/// other hull where they decide it. Every decision is an exact predicate (the capsule's with a
/// margin for rounding).

#include <array>
#include <span>
#include <vector>

#include "bsp/solid.hpp"
#include "kernel/grid.hpp"

namespace sculpt::bsp::detail {

/// A segment inside a hull (grid units; its ends may coincide), about which the hull's inscribed
/// capsule is taken: a piece of another hull's boundary inside that capsule is strictly inside
/// the hull and is dropped without a test against each of its planes. Only a quick test: any
/// segment gives the same union (a core outside the hull, or on its boundary, gives no capsule).
/// For a convex tool T swept from a to b, the segment from c + a to c + b for a point c well
/// inside T.
struct HullCore {
  std::array<double, 3> ends[2] = {};
};

struct ConvexUnionOptions {
  /// One per point set, or empty: each hull's core is then the centroid of its vertices.
  std::span<const HullCore> cores = {};
};

/// The regularized union of the convex hulls of `point_sets` (grid units of `grid`). A set whose
/// hull has no volume (all points in one plane) adds nothing. The solid carries its boundary.
/// \throw std::invalid_argument if `options.cores` is neither empty nor one per point set.
Solid unite_convex_hulls(const std::vector<std::vector<kernel::GridPoint>>& point_sets, const kernel::Grid& grid,
                         const ConvexUnionOptions& options = {});

}  // namespace sculpt::bsp::detail
