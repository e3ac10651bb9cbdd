#include "curves/segment_error.hpp"

#include <algorithm>
#include <cmath>

namespace sculpt::curves {

double segment_error(const std::vector<Eigen::Vector3d>& points, int i, int j, Norm norm) {
  const ChordDistance distance(points[i], points[j]);
  double result = 0.0;
  if (norm == Norm::LInf) {
    // Only the farthest point needs the full ChordDistance: find it by the squared cross product
    // (same order, since sqrt and division are monotone), then measure it exactly as everyone does.
    if (j - i < 2) return 0.0;
    if (distance.degenerate()) {
      for (int k = i + 1; k < j; ++k) result = std::max(result, distance(points[k]));
      return result;
    }
    const Eigen::Vector3d& a = points[i];
    const Eigen::Vector3d d = points[j] - a;
    int farthest = i + 1;
    double largest = -1.0;
    for (int k = i + 1; k < j; ++k) {
      const double s = (points[k] - a).cross(d).squaredNorm();
      if (s > largest) {
        largest = s;
        farthest = k;
      }
    }
    return distance(points[farthest]);
  }
  for (int k = i + 1; k < j; ++k) {
    const double d = distance(points[k]);
    result += d * d;  // summed in index order: every method sees the same value
  }
  return std::sqrt(result);
}

double approximation_error(const std::vector<Eigen::Vector3d>& points, const std::vector<int>& indices, Norm norm) {
  double result = 0.0;
  for (std::size_t k = 0; k + 1 < indices.size(); ++k)
    result = std::max(result, segment_error(points, indices[k], indices[k + 1], norm));
  return result;
}

}  // namespace sculpt::curves
