#pragma once
// Analytic test curves and exact point-to-curve distances, written independently of the library:
// bracketing over a fine uniform sampling of the curve parameter and Newton on (c(t) - x) . c'(t).
#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <numbers>
#include <vector>

#include <Eigen/LU>

#include "splines/bspline.hpp"

namespace sculpt::splines::testing {

using Curve3 = std::function<std::array<Eigen::Vector3d, 3>(double)>;  // point, first, second derivative

inline Curve3 ellipse(double a, double b) {
  return [a, b](double t) {
    return std::array<Eigen::Vector3d, 3>{Eigen::Vector3d(a * std::cos(t), b * std::sin(t), 0),
                                          Eigen::Vector3d(-a * std::sin(t), b * std::cos(t), 0),
                                          Eigen::Vector3d(-a * std::cos(t), -b * std::sin(t), 0)};
  };
}

inline Curve3 helix(double pitch) {
  return [pitch](double t) {
    return std::array<Eigen::Vector3d, 3>{Eigen::Vector3d(std::cos(t), std::sin(t), pitch * t),
                                          Eigen::Vector3d(-std::sin(t), std::cos(t), pitch),
                                          Eigen::Vector3d(-std::cos(t), -std::sin(t), 0)};
  };
}

/// Star r = 1 + amp cos(k t) in polar form.
inline Curve3 star(double amp, int k) {
  return [amp, k](double t) {
    const double r = 1 + amp * std::cos(k * t), r1 = -amp * k * std::sin(k * t), r2 = -amp * k * k * std::cos(k * t);
    const double c = std::cos(t), s = std::sin(t);
    return std::array<Eigen::Vector3d, 3>{Eigen::Vector3d(r * c, r * s, 0), Eigen::Vector3d(r1 * c - r * s, r1 * s + r * c, 0),
                                          Eigen::Vector3d(r2 * c - 2 * r1 * s - r * c, r2 * s + 2 * r1 * c - r * s, 0)};
  };
}

/// Exact distance from x to the curve over [t0, t1]: the best of Newton refinements started at
/// every local minimum of a 2000-sample scan, and the end points when `open`.
inline double exact_distance(const Curve3& c, const Eigen::Vector3d& x, double t0, double t1, bool open, int samples = 2000) {
  std::vector<double> d(samples + 1);
  const double h = (t1 - t0) / samples;
  for (int i = 0; i <= samples; ++i) d[i] = (c(t0 + i * h)[0] - x).norm();
  double best = open ? std::min(d.front(), d.back()) : d.front();
  for (int i = 0; i <= samples; ++i) {
    const bool left_ok = i == 0 ? !open : d[i] <= d[i - 1];
    const bool right_ok = i == samples ? !open : d[i] <= d[i + 1];
    if (!(left_ok && right_ok)) continue;
    double t = t0 + i * h, lo = t - h, hi = t + h;
    if (open) { lo = std::max(lo, t0); hi = std::min(hi, t1); }
    for (int it = 0; it < 50; ++it) {
      const auto e = c(t);
      const Eigen::Vector3d r = e[0] - x;
      const double f = r.dot(e[1]), fp = e[1].squaredNorm() + r.dot(e[2]);
      if (f > 0) hi = t; else lo = t;
      double next = fp > 0 ? t - f / fp : 0.5 * (lo + hi);
      if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
      if (std::abs(next - t) < 1e-15) break;
      t = next;
    }
    best = std::min({best, d[i], (c(t)[0] - x).norm()});
  }
  return best;
}

/// The exact offset of the ellipse (a cos t, b sin t) at d along the outward normal; derivatives by
/// central differences (only Newton's steps use them; the distance is |x - o(t)|).
inline Curve3 ellipse_offset(double a, double b, double d) {
  const auto o = [a, b, d](double s) {
    const double w = std::hypot(b * std::cos(s), a * std::sin(s));
    return Eigen::Vector3d(a * std::cos(s) + d * b * std::cos(s) / w, b * std::sin(s) + d * a * std::sin(s) / w, 0);
  };
  return [o](double s) {
    const double h = 1e-4;
    const Eigen::Vector3d m = o(s - h), c = o(s), p = o(s + h);
    return std::array<Eigen::Vector3d, 3>{c, (p - m) / (2 * h), (p - 2 * c + m) / (h * h)};
  };
}

/// An input built with the library (not a reference): the periodic cubic interpolating a closed
/// planar analytic curve at n uniform parameters over [0, 2 pi).
inline BSpline interpolant(const Curve3& c, int n) {
  const BSpline shape = BSpline::periodic(3, std::vector<Eigen::Vector3d>(n, Eigen::Vector3d::Zero()));
  Eigen::MatrixXd A = Eigen::MatrixXd::Zero(n, n), X(n, 2);
  for (int i = 0; i < n; ++i) {
    const Basis b = shape.basis(i, 0);
    for (int j = 0; j < 4; ++j) A(i, b.index[j]) += b.value(0, j);
    const Eigen::Vector3d x = c(2 * std::numbers::pi * i / n)[0];
    X.row(i) << x.x(), x.y();
  }
  const Eigen::MatrixXd P = A.partialPivLu().solve(X);
  std::vector<Eigen::Vector3d> controls(n);
  for (int i = 0; i < n; ++i) controls[i] = Eigen::Vector3d(P(i, 0), P(i, 1), 0);
  return BSpline::periodic(3, controls, 2);
}

}  // namespace sculpt::splines::testing
