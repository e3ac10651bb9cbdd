#include "mesh/predicates.hpp"

#include <boost/multiprecision/cpp_int.hpp>
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

namespace sculpt {
namespace {

using Rational = boost::multiprecision::cpp_rational;
using Int256 = boost::multiprecision::int256_t;
using Int512 = boost::multiprecision::int512_t;

constexpr double kEps = std::numeric_limits<double>::epsilon() / 2;  // unit roundoff 2^-53
// Shewchuk's first-stage bounds (ccwerrboundA, o3derrboundA).
constexpr double kOrient2dBound = (3.0 + 16.0 * kEps) * kEps;
constexpr double kOrient3dBound = (7.0 + 56.0 * kEps) * kEps;
// The bounds assume no underflow; below this magnitude the exact path decides (each underflow
// loses at most 2^-1074, far below kOrient*Bound * 1e-280).
constexpr double kNoUnderflow = 1e-280;

/// Finite doubles as integers times a common power of two: x_i = m_i * 2^(e_i) with |m_i| < 2^53,
/// and `shift` = max e_i - min e_i over the non-zero inputs. All inputs scaled by 2^-min(e) are
/// integers of at most 53 + shift bits, so sums and products in fixed-width integers are exact
/// when the width covers the bit count of the determinant.
template <size_t N>
struct Scaled {
  std::array<long long, N> mantissa{};
  std::array<int, N> exponent{};
  int min_exponent = 0;
  int shift = 0;

  explicit Scaled(const std::array<double, N>& x) {
    int lo = std::numeric_limits<int>::max(), hi = std::numeric_limits<int>::min();
    for (size_t i = 0; i < N; ++i) {
      if (x[i] == 0) continue;
      int e = 0;
      const double f = std::frexp(x[i], &e);  // x = f 2^e, 0.5 <= |f| < 1
      mantissa[i] = static_cast<long long>(std::ldexp(f, 53));
      exponent[i] = e - 53;
      lo = std::min(lo, exponent[i]);
      hi = std::max(hi, exponent[i]);
    }
    min_exponent = lo == std::numeric_limits<int>::max() ? 0 : lo;
    shift = lo == std::numeric_limits<int>::max() ? 0 : hi - lo;
  }

  template <typename Int>
  [[nodiscard]] Int value(size_t i) const {
    if (mantissa[i] == 0) return Int(0);
    const Int magnitude = Int(mantissa[i] < 0 ? -mantissa[i] : mantissa[i]) << (exponent[i] - min_exponent);
    return mantissa[i] < 0 ? Int(-magnitude) : magnitude;
  }
};

template <typename Num, typename Get>
int orient2d_sign(Get get) {
  const Num acx = get(0) - get(4), bcx = get(2) - get(4);
  const Num acy = get(1) - get(5), bcy = get(3) - get(5);
  const Num det = acx * bcy - acy * bcx;
  return det > 0 ? 1 : (det < 0 ? -1 : 0);
}

int orient2d_exact(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c) {
  const std::array<double, 6> x = {a.x(), a.y(), b.x(), b.y(), c.x(), c.y()};
  const Scaled<6> s(x);
  // |det| < 2 (2^(54 + shift))^2: 2 * (54 + shift) + 2 bits.
  if (2 * (54 + s.shift) + 2 < 255) return orient2d_sign<Int256>([&](size_t i) { return s.value<Int256>(i); });
  if (2 * (54 + s.shift) + 2 < 511) return orient2d_sign<Int512>([&](size_t i) { return s.value<Int512>(i); });
  return orient2d_sign<Rational>([&](size_t i) { return Rational(x[i]); });
}

template <typename Num, typename Get>
int orient3d_sign(Get get) {
  // det[b-a, c-a, d-a] with a, b, c, d at indices 0, 3, 6, 9.
  Num m[3][3];
  for (int k = 0; k < 3; ++k) {
    m[0][k] = get(3 + k) - get(k);
    m[1][k] = get(6 + k) - get(k);
    m[2][k] = get(9 + k) - get(k);
  }
  const Num det = m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) -
                  m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
                  m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
  return det > 0 ? 1 : (det < 0 ? -1 : 0);
}

int orient3d_exact(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c,
                   const Eigen::Vector3d& d) {
  const std::array<double, 12> x = {a.x(), a.y(), a.z(), b.x(), b.y(), b.z(),
                                    c.x(), c.y(), c.z(), d.x(), d.y(), d.z()};
  const Scaled<12> s(x);
  // |det| < 6 (2^(54 + shift))^3: 3 * (54 + shift) + 3 bits.
  if (3 * (54 + s.shift) + 3 < 255) return orient3d_sign<Int256>([&](size_t i) { return s.value<Int256>(i); });
  if (3 * (54 + s.shift) + 3 < 511) return orient3d_sign<Int512>([&](size_t i) { return s.value<Int512>(i); });
  return orient3d_sign<Rational>([&](size_t i) { return Rational(x[i]); });
}

}  // namespace

int orient2d(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c) {
  // Same expression as Shewchuk's orient2dfast, so that his error bound applies.
  const double detleft = (a.x() - c.x()) * (b.y() - c.y());
  const double detright = (a.y() - c.y()) * (b.x() - c.x());
  const double det = detleft - detright;
  const double detsum = std::abs(detleft) + std::abs(detright);
  const double bound = kOrient2dBound * detsum;
  if (std::isfinite(det) && std::isfinite(bound) && detsum > kNoUnderflow && (det > bound || -det > bound))
    return det > 0 ? 1 : -1;
  return orient2d_exact(a, b, c);
}

int orient3d(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c,
             const Eigen::Vector3d& d) {
  // Shewchuk's orient3d evaluates det[a-d, b-d, c-d], which is -det[b-a, c-a, d-a].
  const double adx = a.x() - d.x(), bdx = b.x() - d.x(), cdx = c.x() - d.x();
  const double ady = a.y() - d.y(), bdy = b.y() - d.y(), cdy = c.y() - d.y();
  const double adz = a.z() - d.z(), bdz = b.z() - d.z(), cdz = c.z() - d.z();
  const double bdxcdy = bdx * cdy, cdxbdy = cdx * bdy;
  const double cdxady = cdx * ady, adxcdy = adx * cdy;
  const double adxbdy = adx * bdy, bdxady = bdx * ady;
  const double det = adz * (bdxcdy - cdxbdy) + bdz * (cdxady - adxcdy) + cdz * (adxbdy - bdxady);
  const double permanent = (std::abs(bdxcdy) + std::abs(cdxbdy)) * std::abs(adz) +
                           (std::abs(cdxady) + std::abs(adxcdy)) * std::abs(bdz) +
                           (std::abs(adxbdy) + std::abs(bdxady)) * std::abs(cdz);
  const double bound = kOrient3dBound * permanent;
  if (std::isfinite(det) && std::isfinite(bound) && permanent > kNoUnderflow && (det > bound || -det > bound))
    return det > 0 ? -1 : 1;
  return orient3d_exact(a, b, c, d);
}

}  // namespace sculpt
