#pragma once
/// \file transform.hpp
/// Affine transforms of solids: every plane of the tree is mapped and the tree is kept.
/// Translations by grid vectors are exact. Other maps re-quantize each plane to the bit budget
/// (kernel::plane_from_normal), moving it by about 2^-50 of the world range, and the tree is
/// rebuilt so that the no-empty-cell invariant holds again (docs/kernel.md, "Transforms").

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
