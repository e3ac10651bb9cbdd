#include "implicit/detail/coverage.hpp"

#include <algorithm>
#include <cmath>

namespace sculpt::implicit::detail {

using Vec = Eigen::Vector3d;

std::int64_t Coverage::key(long i, long j, long k) const {
  // Cells are within a few thousand of the origin; 21 bits per coordinate are plenty.
  const auto u = [](long v) { return static_cast<std::int64_t>(v + (1L << 20)) & ((1L << 21) - 1); };
  return (u(i) << 42) | (u(j) << 21) | u(k);
}

Eigen::Vector3i Coverage::cell_of(const Vec& p) const {
  const Vec c = ((p - origin_) / cell_).array().floor();
  return c.cast<int>();
}

void Coverage::add_polyline(const std::vector<Vec>& points, bool closed) {
  const std::size_t n = points.size();
  const std::size_t segments = closed ? n : (n == 0 ? 0 : n - 1);
  for (std::size_t s = 0; s < segments; ++s) {
    const Vec& a = points[s];
    const Vec& b = points[(s + 1) % n];
    const int index = static_cast<int>(segments_.size());
    segments_.emplace_back(a, b);
    // Register the segment in every cell its (cell-inflated) bounding box touches.
    const Eigen::Vector3i lo = cell_of(a.cwiseMin(b)), hi = cell_of(a.cwiseMax(b));
    for (long i = lo.x(); i <= hi.x(); ++i)
      for (long j = lo.y(); j <= hi.y(); ++j)
        for (long k = lo.z(); k <= hi.z(); ++k) grid_[key(i, j, k)].push_back(index);
  }
}

bool Coverage::covers(const Vec& p, double radius) const {
  const Eigen::Vector3i c = cell_of(p);
  for (long i = c.x() - 1; i <= c.x() + 1; ++i)
    for (long j = c.y() - 1; j <= c.y() + 1; ++j)
      for (long k = c.z() - 1; k <= c.z() + 1; ++k) {
        const auto it = grid_.find(key(i, j, k));
        if (it == grid_.end()) continue;
        for (const int s : it->second) {
          const Vec& a = segments_[s].first;
          const Vec ab = segments_[s].second - a;
          const double len2 = ab.squaredNorm();
          const double u = len2 > 0.0 ? std::clamp((p - a).dot(ab) / len2, 0.0, 1.0) : 0.0;
          if ((a + u * ab - p).norm() <= radius) return true;
        }
      }
  return false;
}

}  // namespace sculpt::implicit::detail
