#pragma once
/// \file pending_sides.hpp
/// Internal (autopartition, ExpectedDepth): the sides of auxiliary planes that have no piece.

#include <vector>

#include "bsp/partition/autopartition.hpp"

namespace sculpt::bsp::detail {

/// An auxiliary plane with no piece on one side: that side's status is not known when the node is
/// made. The cell has no boundary there, and the plane carries none, so the side has the status of
/// the cells just across the plane: the node's polygon (plane ∩ cell), pushed down the other
/// child's subtree, reaches a leaf with that status.
struct PendingSide {
  TreeRef node;
  int empty_side;  ///< 0: negative, 1: positive
  kernel::ConvexPolygon polygon;
};

/// Gives each pending side its status, children first (they have larger indices, and a walk may
/// reach them): `nodes` must be complete.
void resolve_pending_sides(Arena& arena, std::vector<PartitionNode>& nodes, std::vector<PendingSide>& pending);

}  // namespace sculpt::bsp::detail
