#pragma once
/// \file point_copies.hpp
/// Copies of one point among a mesh's vertices, found by hashing the coordinates (one pass in
/// index order, no sort): the output check's duplicate-vertex test and the self-intersection
/// search's vertex ids.

#include <span>
#include <vector>

#include <Eigen/Core>

namespace sculpt::mesh::detail {

/// Per point, the smallest index of a point with the same coordinates (compared with ==, so -0
/// and +0 are one point); itself when it is the first. Points not taken (take[v] == 0, when
/// `take` is not empty) and points with a coordinate that is not finite are never matched and map to themselves.
std::vector<int> first_copies(std::span<const Eigen::Vector3d> points, std::span<const char> take = {});

}  // namespace sculpt::mesh::detail
