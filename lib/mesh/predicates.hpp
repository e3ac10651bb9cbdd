#pragma once
/// \file predicates.hpp
/// Exact orientation predicates on double coordinates for the mesh layer (validation,
/// triangulation). A floating-point filter with Shewchuk's static error bounds
/// ("Adaptive precision floating-point arithmetic and fast robust geometric predicates",
/// 1997) answers almost every call; the rest are computed exactly in 256- or 512-bit integers
/// (inputs rescaled to a common exponent), or in rationals for extreme exponent spreads.
/// The result is the exact sign of the determinant for every finite input.

#include <cmath>
#include <limits>

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

namespace detail {
inline constexpr double kUnitRoundoff = std::numeric_limits<double>::epsilon() / 2;  // 2^-53
/// Shewchuk's first-stage bounds for orient2d and orient3d (ccwerrboundA, o3derrboundA), and the
/// magnitude of the permanent below which an underflow could void them (the exact path decides).
inline constexpr double kOrient2dFilterBound = (3.0 + 16.0 * kUnitRoundoff) * kUnitRoundoff;
inline constexpr double kOrient3dFilterBound = (7.0 + 56.0 * kUnitRoundoff) * kUnitRoundoff;
inline constexpr double kFilterNoUnderflow = 1e-280;
}  // namespace detail

/// The part of orient3d's floating-point filter that depends on the plane (a, b, c) alone, kept
/// for many queries (the self-intersection searches test each triangle's corners against the
/// other triangle's plane). With u = b - a, v = c - a, w = q - a, Shewchuk's orient3d evaluates
/// det[u, v, w] expanded along the third row (w) as along a column, with the same rounded
/// differences and 2x2 minors in the same form, so his bound holds unchanged; the minors and
/// their absolute parts are what is stored here.
struct Orient3dPlane {
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();  ///< a
  double minor[3] = {0, 0, 0};     ///< (u x v) by coordinate, each a rounded difference of products
  double permanent[3] = {0, 0, 0};  ///< |u_j v_k| + |u_k v_j|, the matching absolute parts
};

/// The plane part of the filter for orient3d(a, b, c, .).
inline Orient3dPlane orient3d_plane(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
  Orient3dPlane p;
  p.origin = a;
  const double ux = b.x() - a.x(), uy = b.y() - a.y(), uz = b.z() - a.z();
  const double vx = c.x() - a.x(), vy = c.y() - a.y(), vz = c.z() - a.z();
  const double yz = uy * vz, zy = uz * vy, zx = uz * vx, xz = ux * vz, xy = ux * vy, yx = uy * vx;
  p.minor[0] = yz - zy;
  p.minor[1] = zx - xz;
  p.minor[2] = xy - yx;
  p.permanent[0] = std::abs(yz) + std::abs(zy);
  p.permanent[1] = std::abs(zx) + std::abs(xz);
  p.permanent[2] = std::abs(xy) + std::abs(yx);
  return p;
}

/// orient3d_filtered(a, b, c, q) for the plane p = orient3d_plane(a, b, c): the sign of
/// det[b - a, c - a, q - a] when the filter certifies it, else kUndecided (the filter may decide a
/// slightly different set of inputs than orient3d_filtered's; every sign it gives is exact).
inline int orient3d_filtered(const Orient3dPlane& p, const Eigen::Vector3d& q) {
  const double wx = q.x() - p.origin.x(), wy = q.y() - p.origin.y(), wz = q.z() - p.origin.z();
  const double det = (wx * p.minor[0] + wy * p.minor[1]) + wz * p.minor[2];
  const double permanent = (std::abs(wx) * p.permanent[0] + std::abs(wy) * p.permanent[1]) + std::abs(wz) * p.permanent[2];
  const double bound = detail::kOrient3dFilterBound * permanent;
  if (std::isfinite(det) && std::isfinite(bound) && permanent > detail::kFilterNoUnderflow && (det > bound || -det > bound))
    return det > 0 ? 1 : -1;
  return kUndecided;
}

}  // namespace sculpt
