#pragma once
/// \file rational_orientation.hpp
/// Independent references for the orientation predicates (mesh/predicates.hpp): the determinant's
/// sign in exact rationals (Boost.Multiprecision), expanded in another order than the code under test.

#include <boost/multiprecision/cpp_int.hpp>

#include <Eigen/Core>

namespace sculpt::checks {

/// Sign of orient2d(a, b, c), exactly.
inline int rational_orient2d(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c) {
  using boost::multiprecision::cpp_rational;
  const cpp_rational det = (cpp_rational(b.x()) - a.x()) * (cpp_rational(c.y()) - a.y()) -
                           (cpp_rational(b.y()) - a.y()) * (cpp_rational(c.x()) - a.x());
  return det.sign();
}

/// Sign of orient3d(a, b, c, d), exactly (expansion along the last row).
inline int rational_orient3d(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c,
                             const Eigen::Vector3d& d) {
  using boost::multiprecision::cpp_rational;
  cpp_rational m[3][3];
  for (int k = 0; k < 3; ++k) {
    m[0][k] = cpp_rational(b[k]) - a[k];
    m[1][k] = cpp_rational(c[k]) - a[k];
    m[2][k] = cpp_rational(d[k]) - a[k];
  }
  const cpp_rational det = m[2][0] * (m[0][1] * m[1][2] - m[0][2] * m[1][1]) -
                           m[2][1] * (m[0][0] * m[1][2] - m[0][2] * m[1][0]) +
                           m[2][2] * (m[0][0] * m[1][1] - m[0][1] * m[1][0]);
  return det.sign();
}

}  // namespace sculpt::checks
