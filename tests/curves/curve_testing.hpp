#pragma once
// Helpers shared by the curve tests: random curves and a brute-force optimum (Alg. 3.1 NAIVE).
#include <Eigen/Core>
#include <functional>
#include <limits>
#include <random>
#include <vector>

#include "curves/digitized_curve.hpp"
#include "curves/segment_error.hpp"

namespace sculpt::curves::curve_testing {

/// Random walk with some smoothness; dimension 2 keeps z = 0.
inline DigitizedCurve random_curve(std::mt19937_64& rng, int n, int dimension, bool closed = false) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  DigitizedCurve c;
  c.dimension = dimension;
  c.closed = closed;
  c.name = "random";
  Eigen::Vector3d p = Eigen::Vector3d::Zero(), v(1, 0, 0);
  for (int k = 0; k < n; ++k) {
    c.points.push_back(p);
    v += 0.8 * Eigen::Vector3d(u(rng), u(rng), dimension == 3 ? u(rng) : 0.0);
    p += v;
  }
  return c;
}

/// NAIVE (Alg. 3.1): the best of all C(n-2, m-1) approximations with exactly m segments.
inline double brute_force_optimum(const std::vector<Eigen::Vector3d>& points, int m, Norm norm) {
  const int last = static_cast<int>(points.size()) - 1;
  double best = std::numeric_limits<double>::infinity();
  std::vector<int> q(m + 1);
  q[0] = 0;
  q[m] = last;
  // Enumerate increasing q[1..m-1] in (0, last) iteratively (odometer).
  for (int k = 1; k < m; ++k) q[k] = k;
  while (true) {
    if (m == 1 || q[m - 1] < last) best = std::min(best, approximation_error(points, q, norm));
    int k = m - 1;
    while (k >= 1 && q[k] == last - (m - k)) --k;
    if (k < 1) break;
    ++q[k];
    for (int t = k + 1; t < m; ++t) q[t] = q[t - 1] + 1;
  }
  return best;
}

/// Fewest segments with error <= tol by brute force over all index subsets (n <= ~16).
inline int brute_force_min_count(const std::vector<Eigen::Vector3d>& points, double tol, Norm norm) {
  const int last = static_cast<int>(points.size()) - 1;
  for (int m = 1; m <= last; ++m)
    if (brute_force_optimum(points, m, norm) <= tol) return m;
  return last;
}

}  // namespace sculpt::curves::curve_testing
