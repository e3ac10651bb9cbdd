#include "bsp/point_classifier.hpp"

#include <cmath>
#include <limits>

#include "kernel/grid.hpp"

namespace sculpt {
namespace {

/// Grid coordinates of a point as exact doubles: the rounding of Grid::snap (half away from
/// zero) on an exact power-of-two scaling. False if a coordinate is out of range or not finite.
bool to_grid(const kernel::Grid& grid, const Eigen::Vector3d& p, double g[3]) {
  for (int a = 0; a < 3; ++a) {
    if (!(std::fabs(p[a]) <= grid.max_world())) return false;
    // |t| <= 2^25: adding and subtracting 1.5 * 2^52 rounds to the nearest integer, ties to
    // even (default rounding mode); ties then go away from zero as in std::llround.
    const double t = grid.to_grid(p[a]);
    double r = (t + 0x1.8p52) - 0x1.8p52;
    if (std::fabs(t - r) == 0.5) r = t + std::copysign(0.5, t);
    g[a] = r;
  }
  return true;
}

}  // namespace

PointClassifier::PointClassifier(const Solid& solid)
    : root_(solid.root()), tree_(solid.nodes()), planes_(solid.planes()), grid_(solid.grid()) {
  // Error bound (Higham, Accuracy and Stability, sec. 3.1): with |X|, |Y|, |Z| <= M (grid units,
  // exact), a, b, c exact and d rounded once, the left-to-right evaluation of aX + bY + cZ + d
  // errs by at most gamma_4 (|a| + |b| + |c|) M + (gamma_4 + u) |d| < 5.001 u S with
  // S = (|a| + |b| + |c|) M + |d| and u = 2^-53. We use 8 u S: the slack covers the rounding of
  // S itself. Every term is an integer below 2^82, so nothing overflows or underflows.
  constexpr double u = std::numeric_limits<double>::epsilon() / 2;
  const double m = double(kernel::kMaxCoord);
  nodes_.reserve(solid.nodes().size());
  for (const BspNode& n : solid.nodes()) {
    const kernel::Plane& p = solid.planes()[std::size_t(n.plane)];
    const double a = double(p.a), b = double(p.b), c = double(p.c), d = double(p.d);
    const double s = (std::fabs(a) + std::fabs(b) + std::fabs(c)) * m + std::fabs(d);
    nodes_.push_back({a, b, c, d, 8 * u * s, {n.negative, n.positive}});
  }
}

Classification PointClassifier::exact(const Eigen::Vector3d& point) const {
  return sculpt::classify(grid_.snap(point), root_, tree_, planes_);  // snap throws RangeError
}

Classification PointClassifier::classify(const Eigen::Vector3d& point) const {
  double g[3];
  if (!to_grid(grid_, point, g)) return exact(point);
  TreeRef k = root_;
  int visited = 0;
  while (k >= 0) {
    const Node& n = nodes_[std::size_t(k)];
    const double f = n.a * g[0] + n.b * g[1] + n.c * g[2] + n.d;
    if (!(std::fabs(f) > n.bound)) return exact(point);  // near the plane: decide exactly
    k = n.child[f > 0.0];
    ++visited;
  }
  return {k == kIn ? Location::Inside : Location::Outside, visited};
}

void PointClassifier::classify(std::span<const Eigen::Vector3d> points, std::span<Classification> out) const {
  constexpr std::size_t kLanes = 8;
  constexpr TreeRef kNotYetReached = std::numeric_limits<TreeRef>::min();
  std::size_t i = 0;
  for (; i + kLanes <= points.size(); i += kLanes) {
    TreeRef k[kLanes];
    int visited[kLanes] = {};
    double g[kLanes][3];
    bool any = root_ >= 0;
    for (std::size_t l = 0; l < kLanes; ++l) k[l] = to_grid(grid_, points[i + l], g[l]) ? root_ : kNotYetReached;
    while (any) {
      any = false;
      for (std::size_t l = 0; l < kLanes; ++l) {
        if (k[l] < 0) continue;
        const Node& n = nodes_[std::size_t(k[l])];
        const double f = n.a * g[l][0] + n.b * g[l][1] + n.c * g[l][2] + n.d;
        k[l] = std::fabs(f) > n.bound ? n.child[f > 0.0] : kNotYetReached;
        ++visited[l];
        any |= k[l] >= 0;
      }
    }
    for (std::size_t l = 0; l < kLanes; ++l)
      out[i + l] = k[l] == kNotYetReached
                       ? exact(points[i + l])
                       : Classification{k[l] == kIn ? Location::Inside : Location::Outside, visited[l]};
  }
  for (; i < points.size(); ++i) out[i] = classify(points[i]);
}

}  // namespace sculpt
