#pragma once
/// \file boundary_fragments.hpp
/// Internal: the boundary of a solid as convex plane-based fragments (Thibault & Naylor 1987;
/// Naylor et al. 1990 sec. 5): each node's sub-hyperplane is pushed down both subtrees and the
/// pieces with an in-cell on exactly one side are kept.

#include <span>
#include <vector>

#include "bsp/tree/tree_arena.hpp"

namespace sculpt::bsp::detail {

/// A boundary piece on a node plane, corners counter-clockwise about its normal.
using Fragment = BoundaryFragment;

struct Fragments {
  kernel::PlaneTable planes;  ///< the solid's planes plus opposites created while splitting
  FragmentList fragments;
};

/// Fragments read where they are (a solid's carried boundary, say), without a copy.
struct FragmentsView {
  const kernel::PlaneTable& planes;
  const FragmentList& fragments;
  FragmentsView(const kernel::PlaneTable& p, const FragmentList& f) : planes(p), fragments(f) {}
  FragmentsView(const Fragments& f) : planes(f.planes), fragments(f.fragments) {}  // NOLINT: implicit on purpose
};

Fragments boundary_fragments(const Solid& solid);

/// The boundary of the solid in arena inside the cell of the subtree at `root`, whose path from
/// the tree's root is `path` (plane indices, root first, the cell on their negative sides): the
/// pieces of the subtree's node polygons (pending ones computed from their paths) with an in-cell
/// on exactly one side. On arena planes (opposites are added); the arena's nodes are not changed.
FragmentList subtree_boundary(Arena& arena, TreeRef root, std::span<const std::int32_t> path);

}  // namespace sculpt::bsp::detail
