#pragma once
/// \file transform.hpp
/// Affine transforms of solids (docs/kernel.md, "What transforms do"). Translations by grid
/// vectors and integer linear maps (quarter turns, mirrors, integer scales) map every plane
/// exactly and keep the tree. Other maps map the boundary's vertices, snap them to the grid (each
/// moves by at most sqrt(3)/2 grid steps) and rebuild the solid from them, so vertices stay single
/// (a rotated cone keeps one apex); where snapping would fold or flatten a face, or for unbounded
/// solids, each plane is mapped and re-quantized instead (slivers far below the grid step).

#include <Eigen/Geometry>

#include "bsp/solid.hpp"

namespace sculpt {

/// Translation by v (world units, snapped to the grid: exact).
Solid translate(const Solid& solid, const Eigen::Vector3d& v);
/// Rotation by `degrees` about the axis through the origin (right-handed). Multiples of 90°
/// about a coordinate axis are exact.
Solid rotate(const Solid& solid, const Eigen::Vector3d& axis, double degrees);
/// Scaling by per-axis factors (non-zero; negative factors mirror). Integer factors are exact.
Solid scale(const Solid& solid, const Eigen::Vector3d& factors);
/// General invertible affine map (world units). \throw InvalidInput if singular.
Solid transform(const Solid& solid, const Eigen::Affine3d& map);

}  // namespace sculpt
