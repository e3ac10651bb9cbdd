#pragma once
/// \file boundary_fragments.hpp
/// Internal: the boundary of a solid as convex plane-based fragments (Thibault & Naylor 1987;
/// Naylor et al. 1990 sec. 5): each node's sub-hyperplane is pushed down both subtrees and the
/// pieces with an in-cell on exactly one side are kept.

#include <vector>

#include "bsp/tree_arena.hpp"

namespace sculpt::detail {

struct Fragment {
  kernel::ConvexPolygon polygon;  ///< on a node plane, corners counter-clockwise about its normal
  bool flip;                      ///< true: the outward normal is the plane's negative normal
};

struct Fragments {
  kernel::PlaneTable planes;  ///< the solid's planes plus opposites created while splitting
  std::vector<Fragment> fragments;
};

Fragments boundary_fragments(const Solid& solid);

}  // namespace sculpt::detail
