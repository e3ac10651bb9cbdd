#include "kernel/plane.hpp"

#include <algorithm>
#include <cassert>
#include <bit>
#include <cmath>
#include <sstream>

#include "base/errors.hpp"

namespace sculpt::kernel {
namespace {

__extension__ typedef unsigned __int128 UInt128;

UInt128 magnitude(Int128 v) { return v < 0 ? UInt128(-v) : UInt128(v); }

// Binary gcd with the trailing-zero count taken from the difference, so that it runs beside the
// minimum instead of after it (a shorter dependency chain per step), and min/abs compiled to
// conditional moves (std::gcd's branches are mispredicted on random operands). An odd part of 1
// (an operand that is a power of two: the largest component of plane_from_normal's normals) ends
// at once instead of after one subtraction per bit pair.
std::uint64_t gcd64(std::uint64_t u, std::uint64_t v) {
  if (u == 0) return v;
  if (v == 0) return u;
  const int uz = std::countr_zero(u), vz = std::countr_zero(v);
  const int shift = std::min(uz, vz);
  u >>= uz;
  v >>= vz;
  if (u == 1 || v == 1) return std::uint64_t(1) << shift;
  // Operands of very different sizes (a normal's gcd and an offset, a band's height and a slope):
  // one division brings the larger down to the smaller's size first (Euclid's step, odd parts).
  if (std::bit_width(u) > std::bit_width(v) + 12) std::swap(u, v);
  if (std::bit_width(v) > std::bit_width(u) + 12) {
    v %= u;
    if (v == 0) return u << shift;
    v >>= std::countr_zero(v);
  }
  while (u != v) {  // both odd
    const std::uint64_t diff = v - u;  // wraps; countr_zero(-x) == countr_zero(x)
    const int z = std::countr_zero(diff);
    const std::uint64_t lo = std::min(u, v);
    v = (u > v ? u - v : diff) >> z;
    u = lo;
  }
  return u << shift;
}

// |v| mod m for m > 0 below 2^64: one 64-bit division if v fits, else two 128-by-64 steps.
std::uint64_t mod64(UInt128 v, std::uint64_t m) {
  if ((v >> 64) == 0) return std::uint64_t(v) % m;
  return std::uint64_t(v % m);
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

// Division by g of multiples of g (|v| < 2^63) without a division instruction: the power of two
// shifted out (arithmetic shift, exact for multiples), then a product with the inverse of g's odd
// part modulo 2^64, which is exact for exact quotients (Hacker's Delight 10-15). The inverse by
// Newton's iteration x <- x (2 - odd x), which doubles the correct low bits (odd x = 1 mod 8 at x = odd).
struct ExactDivisor {
  explicit ExactDivisor(std::uint64_t g) : shift(std::countr_zero(g)) {
    const std::uint64_t odd = g >> shift;
    if (odd == 1) return;
    inverse = odd;
    for (int i = 0; i < 5; ++i) inverse *= 2 - odd * inverse;  // 3, 6, 12, 24, 48, 96 bits
  }
  [[nodiscard]] std::int64_t divide(std::int64_t v) const { return std::int64_t(std::uint64_t(v >> shift) * inverse); }
  int shift;
  std::uint64_t inverse = 1;
};

// The plane a, b, c, d divided by the gcd of all four, given g = gcd(|a|, |b|, |c|) > 0; checks
// the bit budget. The offset (up to 128 bits) only matters when the normal has a common factor:
// then |d| mod g first, so the binary gcd runs on values below g.
Plane divide_exactly(Int128 a, Int128 b, Int128 c, Int128 d, UInt128 g);

Plane divide_by_gcd(Int128 a, Int128 b, Int128 c, Int128 d, UInt128 g) {
  if (g != 1) g = (g >> 64) == 0 ? gcd64(std::uint64_t(g), mod64(magnitude(d), std::uint64_t(g))) : gcd(g, magnitude(d));
  return divide_exactly(a, b, c, d, g);
}

// The plane a, b, c, d divided by g, the gcd of all four; checks the bit budget.
Plane divide_exactly(Int128 a, Int128 b, Int128 c, Int128 d, UInt128 g) {
  if (g != 1) {
    if ((g >> 64) == 0 && ((magnitude(a) | magnitude(b) | magnitude(c)) >> 63) == 0) {
      const ExactDivisor by{std::uint64_t(g)};  // g divides the normal, so it fits 63 bits too
      a = by.divide(std::int64_t(a)), b = by.divide(std::int64_t(b)), c = by.divide(std::int64_t(c));
      d = magnitude(d) >> 63 == 0 ? Int128(by.divide(std::int64_t(d))) : d / Int128(g);
    } else {
      a /= Int128(g), b /= Int128(g), c /= Int128(g), d /= Int128(g);
    }
  }
  if (!fits(a, kNormalBits) || !fits(b, kNormalBits) || !fits(c, kNormalBits) ||
      !fits(d, kOffsetBits)) {
    std::ostringstream s;
    s << "plane coefficients exceed the exact kernel's budget (|a|,|b|,|c| <= 2^" << kNormalBits
      << ", |d| <= 2^" << kOffsetBits << " in grid units); coordinates must lie within 2^" << kCoordBits
      << " grid steps of the origin";
    throw RangeError(s.str());
  }
  return {std::int64_t(a), std::int64_t(b), std::int64_t(c), d};
}

}  // namespace

Plane make_plane(Int128 a, Int128 b, Int128 c, Int128 d) {
  if (a == 0 && b == 0 && c == 0) throw InvalidInput("plane with a zero normal");
  const UInt128 ma = magnitude(a), mb = magnitude(b), mc = magnitude(c);
  const bool narrow = ((ma | mb | mc) >> 63) == 0;  // the usual case: 64-bit arithmetic for the normal
  if (!narrow) return divide_by_gcd(a, b, c, d, gcd(gcd(ma, mb), mc));
  const std::uint64_t gab = gcd64(std::uint64_t(ma), std::uint64_t(mb));
  return divide_by_gcd(a, b, c, d, gab == 1 ? 1 : gcd64(gab, std::uint64_t(mc)));
}

Plane make_plane(Int128 a, Int128 b, Int128 c, Int128 d, const PlaneFactors& known) {
  const UInt128 ma = magnitude(a), mb = magnitude(b), mc = magnitude(c);
  if ((known.ab_gcd == 0 && known.gcd == 0) || ((ma | mb | mc) >> 63) != 0) return make_plane(a, b, c, d);
  if (a == 0 && b == 0 && c == 0) throw InvalidInput("plane with a zero normal");
  if (known.gcd != 0) {
    assert(UInt128(known.gcd) == gcd(gcd64(gcd64(std::uint64_t(ma), std::uint64_t(mb)), std::uint64_t(mc)), magnitude(d)));
    return divide_exactly(a, b, c, d, known.gcd);
  }
  assert(known.ab_gcd == gcd64(std::uint64_t(ma), std::uint64_t(mb)));
  return divide_by_gcd(a, b, c, d, known.ab_gcd == 1 ? 1 : gcd64(known.ab_gcd, std::uint64_t(mc)));
}

Plane plane_through(const GridPoint& p0, const GridPoint& p1, const GridPoint& p2) {
  for (const GridPoint* p : {&p0, &p1, &p2})
    if (std::abs(p->x) > kMaxCoord || std::abs(p->y) > kMaxCoord || std::abs(p->z) > kMaxCoord)
      throw RangeError("grid point outside the exact kernel's range (2^" + std::to_string(kCoordBits) +
                       " grid steps from the origin)");
  const Int128 ux = p1.x - p0.x, uy = p1.y - p0.y, uz = p1.z - p0.z;
  const Int128 vx = p2.x - p0.x, vy = p2.y - p0.y, vz = p2.z - p0.z;
  const Int128 a = uy * vz - uz * vy, b = uz * vx - ux * vz, c = ux * vy - uy * vx;
  if (a == 0 && b == 0 && c == 0) throw InvalidInput("plane through three collinear points");
  const Int128 d = -(a * p0.x + b * p0.y + c * p0.z);
  return make_plane(a, b, c, d);
}

ScaledNormal scale_normal(const Eigen::Vector3d& normal) {
  const double m = normal.cwiseAbs().maxCoeff();
  if (!(m > 0) || !std::isfinite(m)) throw InvalidInput("plane with a zero or non-finite normal");
  // Scale the normal so its largest component has kNormalBits - 1 bits, then round.
  ScaledNormal n;
  n.scale = std::ldexp(1.0, kNormalBits - 1) / m;
  n.a = std::int64_t(std::nearbyint(normal.x() * n.scale));
  n.b = std::int64_t(std::nearbyint(normal.y() * n.scale));
  n.c = std::int64_t(std::nearbyint(normal.z() * n.scale));
  // As make_plane finds it (the largest component is 2^(kNormalBits - 1), never zero).
  const std::uint64_t gab = gcd64(std::uint64_t(std::llabs(n.a)), std::uint64_t(std::llabs(n.b)));
  n.gcd = gab == 1 ? 1 : gcd64(gab, std::uint64_t(std::llabs(n.c)));
  return n;
}

Plane plane_from_scaled_normal(const ScaledNormal& n, double offset_world, const Grid& grid) {
  if (!std::isfinite(offset_world)) throw InvalidInput("plane with a zero or non-finite normal");
  // n.x + offset = 0 with x = g * step  =>  (n s) . g + offset * s / step = 0.
  const double d = grid.to_grid(offset_world * n.scale);
  if (!(std::fabs(d) < std::ldexp(1.0, kOffsetBits - 1))) {
    std::ostringstream what;
    what << "plane offset " << offset_world;
    // The offset's reach in world units: |d| / (|n s| ~ 2^(kNormalBits - 1)) grid units.
    throw RangeError(grid.out_of_range(what.str(), grid.to_world(std::fabs(d) / std::ldexp(1.0, kNormalBits - 1))));
  }
  // |a|, |b|, |c| <= 2^52 and most offsets convert through 64 bits (the 128-bit conversion is a
  // library call); the values are the same.
  const double rd = std::nearbyint(d);
  const Int128 id = std::fabs(rd) < 0x1p62 ? Int128(std::int64_t(rd)) : Int128(rd);
  return divide_by_gcd(n.a, n.b, n.c, id, n.gcd);
}

Plane plane_from_normal(const Eigen::Vector3d& normal, double offset_world, const Grid& grid) {
  return plane_from_scaled_normal(scale_normal(normal), offset_world, grid);  // the same message for either error
}

}  // namespace sculpt::kernel
