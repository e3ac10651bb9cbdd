#pragma once
/// \file cell_clipper.hpp
/// Leaf-cell volumes by floating-point clipping (Ihm & Naylor 1990, sec. 6 needs v_C for every
/// leaf cell C): the halfspaces on each root-to-leaf path clip the sample box as a convex
/// polyhedron (Sutherland-Hodgman per face, the cut closed by a cap polygon); its volume is the sum
/// over faces of area x distance to an interior point / 3. Accurate to about 1e-12 relative. A test
/// oracle: it shares nothing with bsp/cells.hpp's exact cells but the tree, so the tests compare
/// the two.

#include <vector>

#include <Eigen/Geometry>

#include "bsp/solid.hpp"

namespace sculpt::reports {

struct ClippedCell {
  double volume;
  int depth;    ///< partitioning nodes from the root
  bool inside;
};

/// Leaf cells of `solid` meeting `box` with positive volume (explicit stack, no recursion).
std::vector<ClippedCell> clipped_cells(const Solid& solid, const Eigen::AlignedBox3d& box);

}  // namespace sculpt::reports
