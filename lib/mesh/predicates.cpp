#include "mesh/predicates.hpp"

#include <boost/multiprecision/cpp_int.hpp>
#include <cmath>
#include <limits>

namespace sculpt::mesh_predicates {
namespace {

using Rational = boost::multiprecision::cpp_rational;

constexpr double kEps = std::numeric_limits<double>::epsilon() / 2;  // unit roundoff 2^-53
// Shewchuk's first-stage bounds (ccwerrboundA, o3derrboundA).
constexpr double kOrient2dBound = (3.0 + 16.0 * kEps) * kEps;
constexpr double kOrient3dBound = (7.0 + 56.0 * kEps) * kEps;

int sign_of(const Rational& r) { return r.sign(); }

int orient2d_exact(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c) {
  const Rational acx = Rational(a.x()) - Rational(c.x());
  const Rational bcx = Rational(b.x()) - Rational(c.x());
  const Rational acy = Rational(a.y()) - Rational(c.y());
  const Rational bcy = Rational(b.y()) - Rational(c.y());
  return sign_of(acx * bcy - acy * bcx);
}

int orient3d_exact(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c,
                   const Eigen::Vector3d& d) {
  Rational m[3][3];
  for (int k = 0; k < 3; ++k) {
    m[0][k] = Rational(b[k]) - Rational(a[k]);
    m[1][k] = Rational(c[k]) - Rational(a[k]);
    m[2][k] = Rational(d[k]) - Rational(a[k]);
  }
  const Rational det = m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) -
                       m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
                       m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
  return sign_of(det);
}

}  // namespace

int orient2d(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c) {
  // Same expression as Shewchuk's orient2dfast, so that his error bound applies.
  const double detleft = (a.x() - c.x()) * (b.y() - c.y());
  const double detright = (a.y() - c.y()) * (b.x() - c.x());
  const double det = detleft - detright;
  const double detsum = std::abs(detleft) + std::abs(detright);
  const double bound = kOrient2dBound * detsum;
  if (std::isfinite(det) && std::isfinite(bound) && (det > bound || -det > bound))
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
  if (std::isfinite(det) && std::isfinite(bound) && (det > bound || -det > bound))
    return det > 0 ? -1 : 1;
  return orient3d_exact(a, b, c, d);
}

}  // namespace sculpt::mesh_predicates
