#pragma once
/// \file cells.hpp
/// Leaf-cell enumeration for statistics (Ihm & Naylor 1990 sec. 6: the expected cost of point
/// classification is the sum over cells C of depth(C) * volume(C) / V). Every leaf cell of the
/// tree is clipped to an axis-aligned sample box and returned as a convex polytope.

#include <Eigen/Geometry>
#include <functional>
#include <vector>

#include "bsp/solid.hpp"

namespace sculpt {

struct LeafCell {
  std::vector<Eigen::Vector3d> vertices;   ///< world units, from the exact vertices
  std::vector<std::vector<int>> faces;     ///< counter-clockwise from outside the cell
  double volume = 0;                       ///< world units^3
  int depth = 0;                           ///< nodes on the path from the root
  bool inside = false;                     ///< in-cell or out-cell
};

/// Calls `visit` with every leaf cell ∩ box (cells not meeting the box are skipped), one at a
/// time, depth first: a caller that only sums (depth_cost) keeps no list of the millions of cells
/// a large tree has. The volumes add up to the box volume. Checks for Ctrl-C (base/cancel.hpp).
/// \throw InvalidInput for an empty box or one thinner than the grid step; Cancelled
void for_each_leaf_cell(const Solid& solid, const Eigen::AlignedBox3d& box, const std::function<void(LeafCell)>& visit);

/// The cells of for_each_leaf_cell as a list.
std::vector<LeafCell> leaf_cells(const Solid& solid, const Eigen::AlignedBox3d& box);

}  // namespace sculpt
