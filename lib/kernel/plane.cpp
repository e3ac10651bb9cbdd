#include "kernel/plane.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <numeric>
#include <sstream>

#include "base/errors.hpp"

namespace sculpt::kernel {
namespace {

__extension__ typedef unsigned __int128 UInt128;

UInt128 magnitude(Int128 v) { return v < 0 ? UInt128(-v) : UInt128(v); }

// Binary gcd without data-dependent branches in the loop (min/max compile to conditional moves):
// the branches of std::gcd's loop are mispredicted on random operands.
std::uint64_t gcd64(std::uint64_t a, std::uint64_t b) {
  if (a == 0) return b;
  if (b == 0) return a;
  const int shift = std::countr_zero(a | b);
  a >>= std::countr_zero(a);
  do {
    b >>= std::countr_zero(b);
    const std::uint64_t lo = std::min(a, b), hi = std::max(a, b);
    a = lo;
    b = hi - lo;
  } while (b != 0);
  return a << shift;
}

UInt128 gcd(UInt128 a, UInt128 b) {
  // 128-bit remainders only while a value needs them, then the 64-bit binary gcd.
  while (b != 0 && ((a | b) >> 64) != 0) {
    UInt128 t = a % b;
    a = b;
    b = t;
  }
  if (b == 0) return a;
  return gcd64(std::uint64_t(a), std::uint64_t(b));
}

bool fits(Int128 v, int bits) { return magnitude(v) <= (UInt128(1) << bits); }

}  // namespace

Plane make_plane(Int128 a, Int128 b, Int128 c, Int128 d) {
  if (a == 0 && b == 0 && c == 0) throw InvalidInput("plane with a zero normal");
  const UInt128 ma = magnitude(a), mb = magnitude(b), mc = magnitude(c);
  const bool narrow = ((ma | mb | mc) >> 63) == 0;  // the usual case: 64-bit arithmetic for the normal
  UInt128 g = narrow ? UInt128(gcd64(gcd64(std::uint64_t(ma), std::uint64_t(mb)), std::uint64_t(mc)))
                     : gcd(gcd(ma, mb), mc);
  // The offset (up to 128 bits, the slow part) only matters when the normal has a common factor.
  if (g != 1) g = gcd(g, magnitude(d));
  if (g != 1) {
    if (narrow) {  // g divides the normal, so it fits 63 bits too
      const auto g64 = std::int64_t(g);
      a = std::int64_t(a) / g64, b = std::int64_t(b) / g64, c = std::int64_t(c) / g64;
    } else {
      a /= Int128(g), b /= Int128(g), c /= Int128(g);
    }
    d /= Int128(g);
  }
  if (!fits(a, kNormalBits) || !fits(b, kNormalBits) || !fits(c, kNormalBits) ||
      !fits(d, kOffsetBits)) {
    std::ostringstream s;
    s << "plane coefficients exceed the exact kernel's budget (|a|,|b|,|c| <= 2^" << kNormalBits
      << ", |d| <= 2^" << kOffsetBits << " in grid units); coordinates must lie in "
      << range_text();
    throw RangeError(s.str());
  }
  return {std::int64_t(a), std::int64_t(b), std::int64_t(c), d};
}

Plane plane_through(const GridPoint& p0, const GridPoint& p1, const GridPoint& p2) {
  for (const GridPoint* p : {&p0, &p1, &p2})
    if (std::abs(p->x) > kMaxCoord || std::abs(p->y) > kMaxCoord || std::abs(p->z) > kMaxCoord)
      throw RangeError("grid point outside the exact kernel's range " + range_text());
  const Int128 ux = p1.x - p0.x, uy = p1.y - p0.y, uz = p1.z - p0.z;
  const Int128 vx = p2.x - p0.x, vy = p2.y - p0.y, vz = p2.z - p0.z;
  const Int128 a = uy * vz - uz * vy, b = uz * vx - ux * vz, c = ux * vy - uy * vx;
  if (a == 0 && b == 0 && c == 0) throw InvalidInput("plane through three collinear points");
  const Int128 d = -(a * p0.x + b * p0.y + c * p0.z);
  return make_plane(a, b, c, d);
}

Plane plane_from_normal(const Eigen::Vector3d& normal, double offset_world) {
  const double m = normal.cwiseAbs().maxCoeff();
  if (!(m > 0) || !std::isfinite(m) || !std::isfinite(offset_world))
    throw InvalidInput("plane with a zero or non-finite normal");
  // Scale the normal so its largest component has kNormalBits - 1 bits, then round.
  const double s = std::ldexp(1.0, kNormalBits - 1) / m;
  const double a = std::nearbyint(normal.x() * s), b = std::nearbyint(normal.y() * s),
               c = std::nearbyint(normal.z() * s);
  // n.x + offset = 0 with x = g * step  =>  (n s) . g + offset * s / step = 0.
  const double d = offset_world * s / kGridStep;
  if (!(std::fabs(d) < std::ldexp(1.0, kOffsetBits - 1))) {
    std::ostringstream msg;
    msg << "plane offset " << offset_world << " is outside the exact kernel's range " << range_text();
    throw RangeError(msg.str());
  }
  return make_plane(Int128(a), Int128(b), Int128(c), Int128(std::nearbyint(d)));
}

}  // namespace sculpt::kernel
