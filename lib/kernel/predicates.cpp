#include "kernel/predicates.hpp"

#include "kernel/vertex_approximation.hpp"
#include "kernel/wide_int.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <tuple>
#include <utility>

namespace sculpt::kernel {
namespace {

using approximation::kEps;

Int128 i128(std::int64_t v) { return Int128(v); }

struct ExactCross {
  Int128 x, y, z;
};
ExactCross exact_cross(const Plane& p, const Plane& q) {
  return {i128(p.b) * q.c - i128(p.c) * q.b, i128(p.c) * q.a - i128(p.a) * q.c,
          i128(p.a) * q.b - i128(p.b) * q.a};
}

Int256 big(Int128 v) {
  // Boost builds from 64-bit halves portably.
  const bool neg = v < 0;
  __extension__ typedef unsigned __int128 U;
  U m = neg ? U(-v) : U(v);
  Int256 r = Int256(std::uint64_t(m >> 64));
  r <<= 64;
  r += Int256(std::uint64_t(m));
  return neg ? Int256(-r) : r;
}

bool trivially_on(const Plane& p, const Plane& q, const Plane& r, const Plane& s) {
  return same_or_opposite(s, p) || same_or_opposite(s, q) || same_or_opposite(s, r);
}

}  // namespace

PredicateCounters& predicate_counters() {
  thread_local PredicateCounters counters;
  return counters;
}

ApproxPoint approximate_vertex(const Plane& p, const Plane& q, const Plane& r) {
  // x = -(d_p (n_q x n_r) + d_q (n_r x n_p) + d_r (n_p x n_q)) / (n_p . (n_q x n_r)), with the
  // error bounds of kernel/vertex_approximation.hpp.
  namespace va = approximation;
  const va::Approximation<double> v = va::approximate(va::normal_of(p), va::normal_of(q), va::normal_of(r));
  ApproxPoint a;
  if (!v.usable) {
    // Nearly dependent planes: round the exact homogeneous coordinates instead.
    const HomogeneousPoint h = exact_vertex(p, q, r);
    if (h.w == 0) return a;  // err = -1: dependent planes, no vertex
    const double hw = h.w.convert_to<double>();
    a.x = h.x.convert_to<double>() / hw;
    a.y = h.y.convert_to<double>() / hw;
    a.z = h.z.convert_to<double>() / hw;
    a.err = 8.0 * kEps * std::max(std::max(std::fabs(a.x), std::fabs(a.y)), std::fabs(a.z)) + 1e-300;
    return a;
  }
  a.x = v.x, a.y = v.y, a.z = v.z;
  a.err = va::error_bound(v.x, v.y, v.z, v.eV, v.eW, v.aW);
  return a;
}

bool independent(const Plane& p, const Plane& q, const Plane& r) {
  const ExactCross u = exact_cross(q, r);
  return big(u.x) * p.a + big(u.y) * p.b + big(u.z) * p.c != 0;
}

HomogeneousPoint exact_vertex(const Plane& p, const Plane& q, const Plane& r) {
  const ExactCross u = exact_cross(q, r), v = exact_cross(r, p), w = exact_cross(p, q);
  HomogeneousPoint h;
  h.w = big(u.x) * p.a + big(u.y) * p.b + big(u.z) * p.c;
  const Int256 dp = big(p.d), dq = big(q.d), dr = big(r.d);
  h.x = -(dp * big(u.x) + dq * big(v.x) + dr * big(w.x));
  h.y = -(dp * big(u.y) + dq * big(v.y) + dr * big(w.y));
  h.z = -(dp * big(u.z) + dq * big(v.z) + dr * big(w.z));
  return h;
}

namespace {

__extension__ typedef unsigned __int128 U128;

/// A non-zero integer n as (hi + lo) 2^exponent with |n - (hi + lo) 2^exponent| < 2^-104 |n|:
/// the 128 bits from n's leading bit down ("top", 2^127 <= top < 2^128) as the nearest double hi
/// and the nearest double lo to their exact rest; the bits below top are less than 2^-127 of n.
struct Split {
  double hi = 0, lo = 0;
  int exponent = 0;
};

/// Split of sign * (upper 2^128 + lower), a magnitude below 2^256; false for zero.
bool split_magnitude(bool negative, U128 upper, U128 lower, Split& out) {
  U128 top = 0;
  if (upper != 0) {
    const int lead = std::countl_zero(std::uint64_t(upper >> 64)) + ((upper >> 64) == 0 ? std::countl_zero(std::uint64_t(upper)) : 0);
    top = lead == 0 ? upper : (upper << lead) | (lower >> (128 - lead));
    out.exponent = 128 - lead;
  } else {
    if (lower == 0) return false;
    const int lead = std::countl_zero(std::uint64_t(lower >> 64)) + ((lower >> 64) == 0 ? std::countl_zero(std::uint64_t(lower)) : 0);
    top = lower << lead;
    out.exponent = -lead;
  }
  // Without the 128-bit conversions (library calls): top / 2^64 rounded to nearest from its upper
  // half and a sticky bit for the lower (64 - 53 >= 2 bits dropped, so no false tie), then
  // top - h (at most 2^74 in magnitude; h may be 2^128, beyond U128) as two exact parts and one
  // rounding: the same h and l as double(top) and double(top - h).
  const std::uint64_t upper_half = std::uint64_t(top >> 64), lower_half = std::uint64_t(top);
  const double h64 = double(upper_half | (lower_half != 0 ? 1u : 0u));
  const Int128 rest = h64 == 0x1p64 ? Int128(top) : Int128(top - (U128(std::uint64_t(h64)) << 64));
  const double h = h64 * 0x1p64;
  const double l = double(std::int64_t(rest >> 22)) * 0x1p22 + double(std::int64_t(rest & 0x3fffff));
  out.hi = negative ? -h : h;
  out.lo = negative ? -l : l;
  return true;
}

/// Split of a Boost Int256 (sign and magnitude limbs).
bool split(const Int256& n, Split& out) {
  const auto& backend = n.backend();
  const auto* limb = backend.limbs();  // the magnitude, least significant first
  const unsigned size = backend.size();
  auto at = [&](unsigned i) { return i < size ? U128(limb[i]) : U128(0); };
  return split_magnitude(backend.sign(), (at(3) << 64) | at(2), (at(1) << 64) | at(0), out);
}

/// Split of a ProductSum256 (two's complement).
bool split(const ProductSum256& n, Split& out) {
  const bool negative = (n.hi >> 127) != 0;
  U128 hi = n.hi, lo = n.lo;
  if (negative) {  // magnitude: -(hi, lo)
    lo = U128(0) - n.lo;
    hi = ~n.hi + (n.lo == 0 ? 1 : 0);
  }
  return split_magnitude(negative, hi, lo, out);
}

/// n / d correctly rounded, when a double-double quotient (error below 2^-101 of it, with the
/// splits' errors) stays clear of the two midpoints to the neighbouring doubles by more than
/// that error: then the nearest double to the exact quotient is the one nearest the
/// approximation. Returns false otherwise (a quotient at or very near a midpoint, a tie
/// included, or outside [2^-900, 2^900] in magnitude).
bool filtered_quotient(const Split& n, const Split& d, double& out) {
  // A power of two, 2^-255 to 2^255, built from its exponent bits (std::ldexp is a library call).
  const double scale = std::bit_cast<double>(std::uint64_t(1023 + n.exponent - d.exponent) << 52);
  const double q1 = n.hi / d.hi;  // about 1 in magnitude
  const double r = std::fma(-q1, d.hi, n.hi);  // n.hi - q1 d.hi, exact (remainder of a rounded division)
  const double q2 = ((r + n.lo) - q1 * d.lo) / d.hi;
  const double y = (q1 + q2) * scale;
  const double t = ((q1 * scale - y) + q2 * scale);  // the approximation minus y (Sterbenz: exact difference)
  const double m = std::fabs(y);
  if (!(m >= 0x1p-900 && m <= 0x1p900)) return false;
  // The smaller gap, toward zero: the next double toward zero has the magnitude's bits less one.
  const double half_gap = 0.5 * std::fabs(y - std::bit_cast<double>(std::bit_cast<std::uint64_t>(y) - 1));
  if (!(std::fabs(t) * (1 + 0x1p-50) + 0x1p-95 * m < half_gap)) return false;
  out = y;
  return true;
}

/// n / d correctly rounded by exact integer division.
double exact_rounded_quotient(const Int256& n, const Int256& d) {
  using boost::multiprecision::cpp_int;
  const bool negative = (n < 0) != (d < 0);
  cpp_int a = boost::multiprecision::abs(cpp_int(n)), b = boost::multiprecision::abs(cpp_int(d));
  // Scale so that the integer quotient q has 62 or 63 bits: q and a sticky bit for the remainder
  // fit a uint64, whose conversion to double rounds once, correctly (9+ bits below the last).
  const long shift = 62 - (long(boost::multiprecision::msb(a)) - long(boost::multiprecision::msb(b)));
  if (shift > 0) a <<= unsigned(shift);
  else b <<= unsigned(-shift);
  cpp_int q, rem;
  boost::multiprecision::divide_qr(a, b, q, rem);
  const std::uint64_t bits = q.convert_to<std::uint64_t>() | (rem != 0 ? 1u : 0u);
  const double v = std::ldexp(double(bits), int(-shift));
  return negative ? -v : v;
}

}  // namespace

double rounded_quotient(const Int256& n, const Int256& d) {
  if (n == 0) return 0.0;
  // Almost every quotient is decided by a double-double approximation; the rest (ties, near
  // ties) by the exact division.
  Split sn, sd;
  double v = 0;
  if (split(n, sn) && split(d, sd) && filtered_quotient(sn, sd, v)) return v;
  return exact_rounded_quotient(n, d);
}

Eigen::Vector3d rounded_vertex(const Plane& p, const Plane& q, const Plane& r, const ApproxPoint& approx) {
  const double largest = std::max(std::max(std::fabs(approx.x), std::fabs(approx.y)), std::fabs(approx.z));
  if (approx.err >= 0 && approx.err <= 0x1p-50 * largest) return {approx.x, approx.y, approx.z};
  // The homogeneous coordinates of exact_vertex as 256-bit sums of products (offsets below
  // 2^100, so every sum stays below 2^230), each quotient by filtered_quotient; what that
  // cannot decide, from exact_vertex and the exact division.
  constexpr Int128 kOffsetLimit = Int128(1) << 100;
  auto small = [&](const Plane& e) { return e.d < kOffsetLimit && e.d > -kOffsetLimit; };
  if (small(p) && small(q) && small(r)) {
    const ExactCross u = exact_cross(q, r), v = exact_cross(r, p), w = exact_cross(p, q);
    ProductSum256 hw, hx, hy, hz;
    hw.add_product(u.x, p.a, false);
    hw.add_product(u.y, p.b, false);
    hw.add_product(u.z, p.c, false);
    for (const auto& [sum, uk, vk, wk] : {std::tuple{&hx, u.x, v.x, w.x}, std::tuple{&hy, u.y, v.y, w.y}, std::tuple{&hz, u.z, v.z, w.z}}) {
      sum->add_product(p.d, uk, true);
      sum->add_product(q.d, vk, true);
      sum->add_product(r.d, wk, true);
    }
    Split sw, sx, sy, sz;
    Eigen::Vector3d out;
    if (split(hw, sw)) {
      bool decided = true;
      const std::array<std::pair<const ProductSum256*, Split*>, 3> coords = {{{&hx, &sx}, {&hy, &sy}, {&hz, &sz}}};
      for (int k = 0; k < 3 && decided; ++k) {
        if (!split(*coords[size_t(k)].first, *coords[size_t(k)].second)) out[k] = 0.0;  // zero numerator
        else decided = filtered_quotient(*coords[size_t(k)].second, sw, out[k]);
      }
      if (decided) return out;
    }
  }
  const HomogeneousPoint h = exact_vertex(p, q, r);
  return {rounded_quotient(h.x, h.w), rounded_quotient(h.y, h.w), rounded_quotient(h.z, h.w)};
}

Sign orient(const Plane& p, const Plane& q, const Plane& r, const ApproxPoint& at, const Plane& s) {
  PredicateCounters& counters = predicate_counters();
  if (const Sign quick = filtered_orient(at, s); quick != Sign::Zero) {
    ++counters.filtered;
    return quick;
  }
  if (trivially_on(p, q, r, s)) {
    ++counters.trivial;
    return Sign::Zero;
  }
  ++counters.exact;
  // A vertex whose approximation is exact and a grid point (error bound 0, integer coordinates
  // within the world box: the corners of convex hull faces, bsp/merge/convex_union.cpp): the
  // plane's value there in integers (Plane::eval's bit budget), without the determinant.
  constexpr double kWorldBox = double(4 * kMaxCoord);
  if (at.err == 0 && std::fabs(at.x) <= kWorldBox && std::fabs(at.y) <= kWorldBox && std::fabs(at.z) <= kWorldBox &&
      at.x == std::trunc(at.x) && at.y == std::trunc(at.y) && at.z == std::trunc(at.z)) {
    const Sign sign = orient(GridPoint{std::int64_t(at.x), std::int64_t(at.y), std::int64_t(at.z)}, s);
    if (sign == Sign::Zero) ++counters.exact_zero;
    return sign;
  }
  // Fast exact path (Bernstein & Fussell 2009, sec. 4: the orientation is a 4x4 determinant):
  // W f_s(vertex) = det[p; q; r; s] with rows (a, b, c, d), expanded by the 2x2 minors of the
  // (a, b) and (c, d) column pairs. m_ij < 2^107; n_ij = c_i d_j - c_j d_i < 2^126 fits Int128
  // when every |d| < 2^72 (planes of solids within about 2^19 grid units of the origin); each
  // product < 2^233, the sum < 2^236 fits Wide. W = det of the normals has the same minors.
  constexpr Int128 kSmallOffset = Int128(1) << 72;
  auto small = [&](const Plane& e) { return e.d < kSmallOffset && e.d > -kSmallOffset; };
  if (small(p) && small(q) && small(r) && small(s)) {
    const Plane* rows[4] = {&p, &q, &r, &s};
    auto m = [&](int i, int j) { return i128(rows[i]->a) * rows[j]->b - i128(rows[j]->a) * rows[i]->b; };
    auto n = [&](int i, int j) { return i128(rows[i]->c) * rows[j]->d - i128(rows[j]->c) * rows[i]->d; };
    const Int128 m01 = m(0, 1), m02 = m(0, 2), m12 = m(1, 2);
    ProductSum256 det, W;
    det.add_product(m01, n(2, 3), false);
    det.add_product(m02, n(1, 3), true);
    det.add_product(m(0, 3), n(1, 2), false);
    det.add_product(m12, n(0, 3), false);
    det.add_product(m(1, 3), n(0, 2), true);
    det.add_product(m(2, 3), n(0, 1), false);
    W.add_product(m12, p.c, false);
    W.add_product(m02, q.c, true);
    W.add_product(m01, r.c, false);
    const int sign = det.sign() * W.sign();
    if (sign == 0) ++counters.exact_zero;
    return sign > 0 ? Sign::Positive : (sign < 0 ? Sign::Negative : Sign::Zero);
  }
  // General exact path: with u = n_q x n_r, v = n_r x n_p, w = n_p x n_q (Int128, exact), the vertex is
  // (X, Y, Z) / W with W = n_p . u, X = -(d_p u + d_q v + d_r w), and
  // W f_s(vertex) = d_s W - d_p (n_s . u) - d_q (n_s . v) - d_r (n_s . w). Bits: exact_int.hpp.
  const ExactCross u = exact_cross(q, r), v = exact_cross(r, p), w = exact_cross(p, q);
  auto dot = [](const Plane& n, const ExactCross& c) {
    return Wide::mul(n.a, c.x) + Wide::mul(n.b, c.y) + Wide::mul(n.c, c.z);
  };
  const Wide W = dot(p, u);
  const Wide t = W * s.d - (dot(s, u) * p.d + dot(s, v) * q.d + dot(s, w) * r.d);
  const int sign = t.sign() * W.sign();
  if (sign == 0) ++counters.exact_zero;
  return sign > 0 ? Sign::Positive : (sign < 0 ? Sign::Negative : Sign::Zero);
}

Sign orient(const GridPoint& point, const Plane& s) {
  const Int128 v = s.eval(point);
  return v > 0 ? Sign::Positive : (v < 0 ? Sign::Negative : Sign::Zero);
}

}  // namespace sculpt::kernel
