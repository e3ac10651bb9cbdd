#include "reports/point_classifier.hpp"

#include <cmath>

#include "kernel/grid.hpp"

namespace sculpt::reports {

PointClassifier::PointClassifier(const Solid& solid) : root_(solid.root()) {
  nodes_.reserve(solid.nodes().size());
  for (const BspNode& n : solid.nodes()) {
    const kernel::Plane& p = solid.planes()[n.plane];
    // f(grid point) = a X + b Y + c Z + d with X = x / step: in world units divide d by step.
    const double a = double(p.a), b = double(p.b), c = double(p.c);
    const double d = double(p.d) * kernel::kGridStep;
    const double norm = std::sqrt(a * a + b * b + c * c);
    nodes_.push_back({a / norm, b / norm, c / norm, d / norm, {n.negative, n.positive}});
  }
}

void PointClassifier::classify(std::span<const Eigen::Vector3d> points, std::span<PointResult> out) const {
  constexpr std::size_t kLanes = 8;
  std::size_t i = 0;
  for (; i + kLanes <= points.size(); i += kLanes) {
    std::int32_t k[kLanes];
    int depth[kLanes] = {};
    for (std::size_t l = 0; l < kLanes; ++l) k[l] = root_;
    bool any = root_ >= 0;
    while (any) {
      any = false;
      for (std::size_t l = 0; l < kLanes; ++l) {
        if (k[l] < 0) continue;
        const FlatNode& n = nodes_[static_cast<std::size_t>(k[l])];
        const Eigen::Vector3d& p = points[i + l];
        k[l] = n.child[n.a * p.x() + n.b * p.y() + n.c * p.z() + n.d > 0.0];
        ++depth[l];
        any |= k[l] >= 0;
      }
    }
    for (std::size_t l = 0; l < kLanes; ++l) out[i + l] = {k[l] == kIn, depth[l]};
  }
  for (; i < points.size(); ++i) out[i] = classify(points[i]);
}

}  // namespace sculpt::reports
