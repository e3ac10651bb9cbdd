#pragma once
/// \file extrude.hpp
/// Prisms over simple polygons, convex or not: the polygon's boundary swept straight up, built as
/// a solid from that closed mesh (bsp/from_mesh.hpp). Vertices are snapped to the grid first.

#include <Eigen/Core>
#include <vector>

#include "bsp/solid.hpp"

namespace sculpt {

/// The right prism over `polygon` (x, y, in either orientation; a repeated closing point is
/// dropped) from z = z0 to z = z1, snapped to `grid`.
/// \throw InvalidInput for fewer than 3 distinct points, zero area, or z0 >= z1 after snapping;
/// GeometryError if the polygon's boundary crosses or touches itself (named where).
Solid extrude(const std::vector<Eigen::Vector2d>& polygon, double z0, double z1, const kernel::Grid& grid = {});

}  // namespace sculpt
