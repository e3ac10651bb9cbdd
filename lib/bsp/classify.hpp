#pragma once
/// \file classify.hpp
/// Exact point classification (Ihm & Naylor 1990 sec. 6): descend the tree by the side of the
/// point; a point on a node's plane descends both sides and is on the boundary iff they disagree.

#include <span>

#include <Eigen/Core>

#include "bsp/solid.hpp"

namespace sculpt {

enum class Location { Outside, Inside, Boundary };

struct Classification {
  Location location;
  int path_length;  ///< nodes visited (the cost of the query)
};

/// Classifies a point (world units, snapped to the grid first). \throw RangeError if out of range.
Classification classify(const Solid& solid, const Eigen::Vector3d& point);

/// The same walk for a grid point over a tree given by its parts (a solid's, or a copy of them).
Classification classify(const kernel::GridPoint& point, TreeRef root, std::span<const BspNode> nodes,
                        const kernel::PlaneTable& planes);

}  // namespace sculpt
