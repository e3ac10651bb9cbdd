#pragma once
/// \file cell_depths.hpp
/// The depth mode's numbers (internal): for each triangle of a solid's boundary, the depth of the
/// leaf cell behind it, that is the number of partitioning nodes a point just inside the triangle
/// visits on its way down the tree (Ihm & Naylor 1990 sec. 6: the cost of classifying that point;
/// the expected depth of reports/depth_cost.hpp averages the same numbers over the cells'
/// volumes). Reading the tree builds a deferred one (bsp/solid.hpp).

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include <Eigen/Core>

#include "bsp/solid.hpp"

namespace sculpt::view::detail {

/// The depth behind each triangle (corners `points[t[0]]`, ... counter-clockwise from outside,
/// world units; float32-rounded corners of the exact boundary, as a GLB holds them). A node whose
/// plane holds the triangle (within the corners' rounding) sends the point to the side behind the
/// triangle. \pre every index is below points.size().
std::vector<int> cell_depths_behind(const Solid& solid, std::span<const Eigen::Vector3d> points,
                                    std::span<const std::array<std::uint32_t, 3>> triangles);

}  // namespace sculpt::view::detail
