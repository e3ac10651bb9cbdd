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

}  // namespace sculpt::splines::testing
