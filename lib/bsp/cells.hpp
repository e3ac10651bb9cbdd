#pragma once
/// \file cells.hpp
/// Leaf-cell enumeration for statistics (Ihm & Naylor 1990 sec. 6: the expected cost of point
/// classification is the sum over cells C of depth(C) * volume(C) / V). Every leaf cell of the
/// tree is clipped to an axis-aligned sample box and returned as a convex polytope.

#include <Eigen/Geometry>
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

/// Every leaf cell ∩ box with positive volume (cells not meeting the box are skipped).
/// The volumes add up to the box volume.
std::vector<LeafCell> leaf_cells(const Solid& solid, const Eigen::AlignedBox3d& box);

}  // namespace sculpt
