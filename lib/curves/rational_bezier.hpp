#pragma once
/// \file rational_bezier.hpp
/// Planar rational Bezier curves (Piegl 1987; Farin, "Curves and Surfaces for CAGD", ch. 15),
/// the pieces the goblet and human profiles of Ihm & Naylor 1990 (Figure 5) are made of.
/// Evaluation is de Casteljau's algorithm on the homogeneous points (w_i x_i, w_i y_i, w_i).

#include <Eigen/Core>
#include <vector>

namespace sculpt::curves {

/// A rational Bezier curve of degree n = points.size() - 1 over t in [0, 1].
class RationalBezier {
 public:
  /// \pre at least 2 control points, as many weights, all finite, every weight > 0
  /// \throw InvalidInput otherwise (the message names the offending index)
  RationalBezier(std::vector<Eigen::Vector2d> points, std::vector<double> weights);

  /// A polynomial Bezier curve: every weight 1.
  static RationalBezier polynomial(std::vector<Eigen::Vector2d> points);

  /// The point at parameter t (de Casteljau in homogeneous coordinates).
  /// \throw InvalidInput if t is not in [0, 1] or not finite
  [[nodiscard]] Eigen::Vector2d evaluate(double t) const;

  [[nodiscard]] int degree() const { return static_cast<int>(points_.size()) - 1; }
  [[nodiscard]] const std::vector<Eigen::Vector2d>& points() const { return points_; }
  [[nodiscard]] const std::vector<double>& weights() const { return weights_; }

 private:
  std::vector<Eigen::Vector2d> points_;
  std::vector<double> weights_;
};

}  // namespace sculpt::curves
