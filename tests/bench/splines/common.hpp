#pragma once
// Shared by the spline benchmarks: an interpolated input ellipse and its exact offset.
#include <Eigen/Dense>
#include <array>
#include <cmath>
#include <numbers>
#include <vector>

#include "splines/analytic.hpp"
#include "splines/bspline.hpp"

namespace sculpt::splines::bench {
using V = Eigen::Vector3d;
namespace t = sculpt::splines::testing;
inline constexpr double kPi = std::numbers::pi;

// A periodic cubic interpolating a closed analytic curve at n uniform parameters.
inline BSpline interpolant(const t::Curve3& c, int n) {
  const BSpline shape = BSpline::periodic(3, std::vector<V>(n, V::Zero()));
  Eigen::MatrixXd A = Eigen::MatrixXd::Zero(n, n), X(n, 2);
  for (int i = 0; i < n; ++i) {
    const Basis b = shape.basis(i, 0);
    for (int j = 0; j < 4; ++j) A(i, b.index[j]) += b.value(0, j);
    const V x = c(2 * kPi * i / n)[0];
    X.row(i) << x.x(), x.y();
  }
  const Eigen::MatrixXd P = A.partialPivLu().solve(X);
  std::vector<V> controls(n);
  for (int i = 0; i < n; ++i) controls[i] = V(P(i, 0), P(i, 1), 0);
  return BSpline::periodic(3, controls, 2);
}
// The exact offset of the ellipse (2 cos t, sin t) along the outward normal (derivatives by differences).
inline t::Curve3 ellipse_offset(double d) {
  const auto o = [d](double s) {
    const double w = std::hypot(std::cos(s), 2 * std::sin(s));
    return V(2 * std::cos(s) + d * std::cos(s) / w, std::sin(s) + d * 2 * std::sin(s) / w, 0);
  };
  return [o](double s) {
    const double h = 1e-4;
    const V m = o(s - h), c = o(s), p = o(s + h);
    return std::array<V, 3>{c, (p - m) / (2 * h), (p - 2 * c + m) / (h * h)};
  };
}

}  // namespace sculpt::splines::bench
