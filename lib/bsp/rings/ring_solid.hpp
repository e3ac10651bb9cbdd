#pragma once
/// \file ring_solid.hpp
/// Internal: solids of revolution of a convex path polygon along stacked rings, the construction
/// behind cylinders, cones and spheres (Ihm & Naylor 1990 sec. 6). Every face plane is exact:
/// ring polygons of one solid have parallel edges, so each band face is a planar quadrilateral.

#include <vector>

#include <Eigen/Core>

#include "bsp/solid.hpp"

namespace sculpt::bsp::detail {

/// One ring of a solid of revolution: height z and scale of the path polygon (0 = apex).
struct Ring {
  double z = 0;
  double scale = 1;
};
/// Stacked bands between consecutive rings (z strictly increasing): ring k is the convex path
/// polygon (counter-clockwise around the z axis, containing it) scaled by rings[k].scale; each
/// band face is an exact planar quadrilateral (or triangle at an apex), caps are flat. The tree
/// is Ihm & Naylor's sec. 6 structure: a balanced tree of the ring planes, in each band a
/// balanced tree of planes through the axis, then the face planes. Only the first and the last
/// ring may have scale 0. Heights and scales in world units of `grid`, which the solid carries.
/// With `snap_reference` (cylinders, cones), the first ring of largest scale has its vertices on
/// the grid points nearest to scale * path[k] and its edge planes through them, exactly, when that
/// snapped polygon is strictly convex around the axis (docs/kernel.md, "Primitives' vertices");
/// otherwise every ring's edge lines come from the path, rounded.
/// \throw InvalidInput for a bad path or rings, RangeError beyond the grid's range.
Solid revolve_rings(const std::vector<Eigen::Vector2d>& path, const std::vector<Ring>& rings,
                    const kernel::Grid& grid = {}, bool snap_reference = false);

}  // namespace sculpt::bsp::detail
