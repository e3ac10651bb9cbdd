#pragma once
/// \file predicates.hpp
/// Exact orientation predicates on double coordinates for the mesh layer (validation,
/// triangulation). A floating-point filter with Shewchuk's static error bounds
/// ("Adaptive precision floating-point arithmetic and fast robust geometric predicates",
/// 1997) answers almost every call; the rest are computed exactly in 256- or 512-bit integers
/// (inputs rescaled to a common exponent), or in rationals for extreme exponent spreads.
/// The result is the exact sign of the determinant for every finite input.

#include <Eigen/Core>

namespace sculpt {

/// Sign (-1, 0, +1) of det[b-a, c-a]: +1 when a, b, c turn counter-clockwise.
int orient2d(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c);

/// Sign (-1, 0, +1) of det[b-a, c-a, d-a]: +1 when d lies on the side of the plane (a, b, c)
/// that the normal (b-a) x (c-a) points to.
int orient3d(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c,
             const Eigen::Vector3d& d);

/// What orient3d_filtered returns when its floating-point filter cannot decide.
inline constexpr int kUndecided = 2;

/// orient3d's first stage alone: the sign when the floating-point filter (Shewchuk's error bound)
/// certifies it, else kUndecided (in particular for every zero determinant). Where a cheaper
/// argument can settle what an undecided sign was needed for, callers try it before orient3d.
int orient3d_filtered(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c,
                      const Eigen::Vector3d& d);

}  // namespace sculpt
