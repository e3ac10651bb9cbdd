#pragma once
/// \file hull.hpp
/// Convex hulls as solids: a convex polytope with one plane per face, every plane exact through
/// three corners of the hull (kernel/convex_hull.hpp: exact Quickhull on grid points).

#include <Eigen/Core>
#include <span>
#include <vector>

#include "bsp/solid.hpp"

namespace sculpt {

/// The convex hull of `points` (world units, snapped to `grid` first). Coplanar, collinear and
/// repeated points are fine; points that all lie in one plane give the empty solid (no volume).
/// \throw RangeError for a coordinate outside the grid's range.
Solid hull(std::span<const Eigen::Vector3d> points, const kernel::Grid& grid = {});

/// The convex hull of solids: the hull of their boundary vertices. Exact when those vertices are
/// grid points (primitives, transformed solids, imported meshes); a vertex made by a set operation
/// is first rounded to the nearest grid point (it moves by at most sqrt(3)/2 grid steps).
/// The result is at the solids' common grid. \throw GridMismatch for solids of different grids.
Solid hull(std::span<const Solid> solids);

}  // namespace sculpt
