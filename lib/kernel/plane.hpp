#pragma once
/// \file plane.hpp
/// Planes with bounded-bit integer coefficients (Bernstein & Fussell 2009, sec. 3).
/// f(p) = a x + b y + c z + d with p in grid units; f > 0 is the positive side. A solid's face
/// plane has the solid on its negative side (the normal (a, b, c) points outwards).
/// Planes are kept normalized (gcd of the coefficients is 1), so equal planes compare equal.

#include <Eigen/Core>

#include "kernel/exact_int.hpp"
#include "kernel/grid.hpp"

namespace sculpt::kernel {

struct Plane {
  std::int64_t a = 0, b = 0, c = 0;  ///< |a|, |b|, |c| <= 2^kNormalBits, not all zero
  double d_nearest = 0;              ///< d rounded to the nearest double, for the filters
                                     ///< (converting an Int128 is slow; this fills padding).
                                     ///< Set by the constructor: build planes, never assign d.
  Int128 d = 0;                      ///< |d| <= 2^kOffsetBits

  Plane() = default;
  Plane(std::int64_t a_, std::int64_t b_, std::int64_t c_, Int128 d_)
      : a(a_), b(b_), c(c_), d_nearest(double(d_)), d(d_) {}

  friend bool operator==(const Plane&, const Plane&) = default;
  [[nodiscard]] Plane opposite() const { return {-a, -b, -c, -d}; }
  /// Exact value of f at a grid point (fits Int128 by the bit budget).
  [[nodiscard]] Int128 eval(const GridPoint& p) const {
    return Int128(a) * p.x + Int128(b) * p.y + Int128(c) * p.z + d;
  }
  [[nodiscard]] Eigen::Vector3d normal() const { return {double(a), double(b), double(c)}; }
};

/// A plane from integer coefficients, divided by their gcd. \throw RangeError if a coefficient
/// exceeds the bit budget (or the normal is zero: InvalidInput).
Plane make_plane(Int128 a, Int128 b, Int128 c, Int128 d);
/// What a caller knows about a plane's coefficients before normalization (make_plane's shortcuts).
struct PlaneFactors {
  std::uint64_t ab_gcd = 0;  ///< gcd(|a|, |b|) exactly (0: unknown, or a = b = 0)
  std::uint64_t gcd = 0;     ///< gcd(|a|, |b|, |c|, |d|) exactly (0: unknown); ab_gcd is then not used
};
/// make_plane(a, b, c, d) for a caller that knows gcd(|a|, |b|) or the gcd of all four: the same
/// plane, one or all gcds less. For families of planes whose x, y normals are multiples of a few
/// directions (the faces of a solid of revolution over one path edge: a, b = height * (nx, ny), so
/// gcd(|a|, |b|) = height * gcd(nx, ny)).
/// \pre known.ab_gcd and known.gcd are 0 or exact (asserted in debug builds).
Plane make_plane(Int128 a, Int128 b, Int128 c, Int128 d, const PlaneFactors& known);
/// The plane through three grid points, positive side where (p1-p0) x (p2-p0) points
/// (counter-clockwise seen from the positive side). \throw InvalidInput if they are collinear.
Plane plane_through(const GridPoint& p0, const GridPoint& p1, const GridPoint& p2);
/// The nearest representable plane n.x + offset = 0 (world units of `grid`), with the normal
/// scaled to kNormalBits - 1 bits before rounding. Used after rotations and for analytic planes;
/// moves the plane by at most about 2^-50 of the range. \throw RangeError if out of range.
Plane plane_from_normal(const Eigen::Vector3d& normal, double offset_world, const Grid& grid = {});
/// What plane_from_normal computes from the normal alone, for many planes with one normal and
/// different offsets (the axial planes of a solid of revolution: the same directions in every band).
struct ScaledNormal {
  std::int64_t a = 0, b = 0, c = 0;  ///< the normal scaled to kNormalBits - 1 bits and rounded
  double scale = 0;                  ///< the scale: 2^(kNormalBits - 1) / max |component|
  std::uint64_t gcd = 0;             ///< gcd(|a|, |b|, |c|)
};
/// \throw InvalidInput for a zero or non-finite normal.
ScaledNormal scale_normal(const Eigen::Vector3d& normal);
/// plane_from_normal(normal, offset_world, grid) for n = scale_normal(normal): the same plane,
/// the same errors for the offset. \throw RangeError, InvalidInput (non-finite offset).
Plane plane_from_scaled_normal(const ScaledNormal& n, double offset_world, const Grid& grid = {});
/// True if p and q are the same plane with the same or with opposite orientation.
inline bool same_or_opposite(const Plane& p, const Plane& q) { return p == q || p == q.opposite(); }

}  // namespace sculpt::kernel
