#include "curves/rational_bezier.hpp"

#include <cmath>
#include <string>

#include "base/errors.hpp"

namespace sculpt::curves {

RationalBezier::RationalBezier(std::vector<Eigen::Vector2d> points, std::vector<double> weights)
    : points_(std::move(points)), weights_(std::move(weights)) {
  if (points_.size() < 2) throw InvalidInput("rational Bezier curve needs at least 2 control points");
  if (weights_.size() != points_.size())
    throw InvalidInput("rational Bezier curve has " + std::to_string(points_.size()) +
                       " control points but " + std::to_string(weights_.size()) + " weights");
  for (std::size_t i = 0; i < points_.size(); ++i) {
    if (!points_[i].allFinite())
      throw InvalidInput("rational Bezier control point " + std::to_string(i) + " is not finite");
    if (!std::isfinite(weights_[i]) || !(weights_[i] > 0.0))
      throw InvalidInput("rational Bezier weight " + std::to_string(i) + " must be finite and > 0");
  }
}

RationalBezier RationalBezier::polynomial(std::vector<Eigen::Vector2d> points) {
  std::vector<double> ones(points.size(), 1.0);
  return RationalBezier(std::move(points), std::move(ones));
}

Eigen::Vector2d RationalBezier::evaluate(double t) const {
  if (!(t >= 0.0 && t <= 1.0)) throw InvalidInput("rational Bezier parameter must lie in [0, 1]");
  // Homogeneous control points (w x, w y, w); convex combinations keep w > 0.
  std::vector<Eigen::Vector3d> h(points_.size());
  for (std::size_t i = 0; i < points_.size(); ++i)
    h[i] = Eigen::Vector3d(weights_[i] * points_[i].x(), weights_[i] * points_[i].y(), weights_[i]);
  for (std::size_t level = h.size() - 1; level > 0; --level)
    for (std::size_t i = 0; i < level; ++i) h[i] = (1.0 - t) * h[i] + t * h[i + 1];
  return {h[0].x() / h[0].z(), h[0].y() / h[0].z()};
}

}  // namespace sculpt::curves
