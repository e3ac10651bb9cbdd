#pragma once
/// \file curve_system.hpp
/// The two equations f = g = 0 of a space curve (Ihm & Naylor sec. 5.1) with the Newton
/// projections the tracer needs: minimum-norm Newton (two equations, three unknowns) for start
/// points, and Newton with a third, linear equation (a plane) for the corrector, the chord-height
/// check and the exit through a box face.

#include <Eigen/Core>
#include <optional>

#include "implicit/expression.hpp"

namespace sculpt::implicit::detail {

/// f, g and their gradients at a point, with the curve tangent grad f x grad g.
struct CurvePoint {
  Eigen::Vector3d p = Eigen::Vector3d::Zero();
  double f = 0.0, g = 0.0;
  Eigen::Vector3d grad_f = Eigen::Vector3d::Zero(), grad_g = Eigen::Vector3d::Zero();
  Eigen::Vector3d cross = Eigen::Vector3d::Zero();  ///< grad f x grad g
  bool on_curve = false;  ///< |f|/|grad f| and |g|/|grad g| within the residual target

  [[nodiscard]] double mu() const { return cross.norm(); }
  /// Unit tangent, oriented to agree with `direction`; zero at a singular point.
  [[nodiscard]] Eigen::Vector3d tangent(const Eigen::Vector3d& direction) const;
};

class CurveSystem {
 public:
  CurveSystem(const Expression& f, const Expression& g, double residual_target)
      : f_(f), g_(g), target_(residual_target) {}

  [[nodiscard]] CurvePoint eval(const Eigen::Vector3d& p) const;
  /// Minimum-norm Newton from `start`; fails if it moves further than max_move or does not converge.
  [[nodiscard]] std::optional<CurvePoint> project(const Eigen::Vector3d& start, double max_move,
                                                  int max_iterations = 40) const;
  /// Newton on f = g = 0 and normal . (q - start) = 0.
  [[nodiscard]] std::optional<CurvePoint> project_on_plane(const Eigen::Vector3d& start,
                                                           const Eigen::Vector3d& normal, double max_move,
                                                           int max_iterations = 16) const;
  /// A singular point near `start`: Gauss-Newton on f = g = 0 and grad f x grad g = 0 (the
  /// cross product's Jacobian by central differences of the exact gradients). Fails if it moves
  /// further than max_move or the result is not on the curve.
  [[nodiscard]] std::optional<CurvePoint> locate_singular(const Eigen::Vector3d& start, double max_move) const;
  [[nodiscard]] long evaluations() const { return evaluations_; }

 private:
  const Expression& f_;
  const Expression& g_;
  double target_;
  mutable long evaluations_ = 0;
};

}  // namespace sculpt::implicit::detail
