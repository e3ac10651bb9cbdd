#pragma once
/// \file predicates.hpp
/// Exact predicates on implicit vertices (Bernstein & Fussell 2009, sec. 4): a vertex is the
/// intersection of three planes and is never rounded; its side of a fourth plane is the sign
/// of an integer determinant. A floating-point filter with a rigorous error bound decides
/// almost every case; the exact Int256 evaluation runs only when the filter cannot.

#include <cmath>
#include <cstdint>

#include "kernel/plane.hpp"

namespace sculpt::kernel {

enum class Sign : std::int8_t { Negative = -1, Zero = 0, Positive = 1 };

/// Floating-point approximation of a vertex with a bound on the error of each coordinate.
/// err < 0 means "no usable approximation": every test on this vertex goes to the exact path.
struct ApproxPoint {
  double x = 0, y = 0, z = 0;
  double err = -1;
};

/// Approximation of the vertex p ∩ q ∩ r (grid units); err < 0 only if the planes are dependent.
ApproxPoint approximate_vertex(const Plane& p, const Plane& q, const Plane& r);
/// True if the three planes meet in exactly one point (exact).
bool independent(const Plane& p, const Plane& q, const Plane& r);
/// Side of the vertex p ∩ q ∩ r with respect to plane s: sign of f_s at the vertex (exact).
/// `approx` must be approximate_vertex(p, q, r). \pre independent(p, q, r).
Sign orient(const Plane& p, const Plane& q, const Plane& r, const ApproxPoint& approx, const Plane& s);
/// The floating-point filter of orient() alone, for callers that test many corners inline:
/// the sign of f_s at the vertex if `approx` decides it, else Zero (undecided: call orient).
/// Does not count; callers add their decided tests to predicate_counters().filtered.
inline Sign filtered_orient(const ApproxPoint& at, const Plane& s) {
  if (!(at.err >= 0)) return Sign::Zero;
  constexpr double kUnit = 1.1102230246251565e-16;  // 2^-53
  const double sa = double(s.a), sb = double(s.b), sc = double(s.c), sd = s.d_nearest;
  const double t1 = sa * at.x, t2 = sb * at.y, t3 = sc * at.z;
  const double value = t1 + t2 + t3 + sd;
  const double bound = 1.001 * ((std::fabs(sa) + std::fabs(sb) + std::fabs(sc)) * at.err +
                                6.0 * kUnit * (std::fabs(t1) + std::fabs(t2) + std::fabs(t3) + std::fabs(sd)));
  return value > bound ? Sign::Positive : (value < -bound ? Sign::Negative : Sign::Zero);
}
/// Side of a grid point with respect to a plane (exact).
Sign orient(const GridPoint& point, const Plane& s);
/// Exact homogeneous coordinates (X, Y, Z, W) of p ∩ q ∩ r: the vertex is (X/W, Y/W, Z/W).
struct HomogeneousPoint { Int256 x, y, z, w; };
HomogeneousPoint exact_vertex(const Plane& p, const Plane& q, const Plane& r);
/// The vertex p ∩ q ∩ r in grid units as doubles for output (docs/kernel.md, "Mesh coordinates"):
/// `approx` itself when its error bound is at most 2^-50 of its largest coordinate (then every
/// coordinate is within a few units in the last place), else each coordinate of the exact vertex
/// correctly rounded (round to nearest, ties to even). So a vertex that is a grid point, however
/// ill-conditioned its defining planes, is written as exactly that grid point.
/// `approx` must be approximate_vertex(p, q, r). \pre independent(p, q, r).
Eigen::Vector3d rounded_vertex(const Plane& p, const Plane& q, const Plane& r, const ApproxPoint& approx);
/// n / d correctly rounded to the nearest double (ties to even). \pre d != 0.
double rounded_quotient(const Int256& n, const Int256& d);

/// How often each path of the predicates ran in this thread (visible to tests, cork-style).
struct PredicateCounters {
  std::uint64_t filtered = 0;  ///< decided by the floating-point filter
  std::uint64_t exact = 0;     ///< decided by the exact integer evaluation
  std::uint64_t exact_zero = 0;  ///< ... of which found the vertex exactly on the plane
  std::uint64_t trivial = 0;   ///< s equal (or opposite) to one of p, q, r: zero without arithmetic
};
PredicateCounters& predicate_counters();

}  // namespace sculpt::kernel
