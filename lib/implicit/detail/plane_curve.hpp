#pragma once
/// \file plane_curve.hpp
/// Tracing the curve f = 0 on a plane from one of its points to another (Ihm & Naylor 1990,
/// sec. 5.2: the boundary curves of a surface patch are "decided by f and h_i", h_i a clipping
/// plane, and every new edge of the refinement is traced on a plane through averaged normals).
///
/// The walk works in the plane's own coordinates (u, v), with points o + u e1 + v e2, so that
/// every point lies on the plane to rounding; for a plane normal to a coordinate axis it lies on
/// it exactly (the frame has zeros in that coordinate). Predictor-corrector marching as in
/// march.hpp: predictor along the in-plane tangent (second order once the curvature is known),
/// Newton corrector on f = 0 and the line normal to the tangent, step length from the measured
/// chord height (kappa h^2 / 8 <= tol) and at most max_step.

#include <Eigen/Core>
#include <vector>

#include "implicit/expression.hpp"

namespace sculpt::implicit::detail {

/// An orthonormal frame of the plane normal . p = offset (|normal| = 1).
struct PlaneFrame {
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();
  double offset = 0.0;
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();
  Eigen::Vector3d e1 = Eigen::Vector3d::UnitX(), e2 = Eigen::Vector3d::UnitY();

  /// The frame of a plane; `normal` must be a unit vector. A normal along a coordinate axis
  /// (the other two components exactly 0) gets the other two axes as e1, e2.
  [[nodiscard]] static PlaneFrame make(const Eigen::Vector3d& normal, double offset);
  [[nodiscard]] Eigen::Vector3d at(const Eigen::Vector2d& uv) const { return origin + uv.x() * e1 + uv.y() * e2; }
  [[nodiscard]] Eigen::Vector2d coords(const Eigen::Vector3d& p) const {
    const Eigen::Vector3d d = p - origin;
    return {d.dot(e1), d.dot(e2)};
  }
};

struct PlaneCurveOptions {
  double tolerance = 1e-3;        ///< chord height: every chord within this distance of the curve
  double max_step = 1.0;          ///< longest chord
  double residual_target = 0.0;   ///< every point: |f| / |grad f| <= this (absolute)
  Box box;                        ///< the walk fails when it leaves this box
  long max_steps = 100'000;       ///< steps (tried or accepted) for this curve
};

enum class PlaneCurveEnd {
  Reached,  ///< the walk arrived at `to`
  LeftBox,  ///< it left the box first
  Closed,   ///< it came back to `from` without passing `to` (a closed curve not through `to`)
  Stuck,    ///< the corrector kept failing (a singular point of f = 0 on the plane)
  Budget,   ///< max_steps ran out
};

struct PlaneCurve {
  std::vector<Eigen::Vector3d> points;  ///< from `from` (exactly) to `to` (exactly) when Reached
  PlaneCurveEnd end = PlaneCurveEnd::Budget;
  Eigen::Vector3d last = Eigen::Vector3d::Zero();  ///< where the walk ended
  long steps = 0;
};

/// Walks along f = 0 on `plane` from `from` to `to` (both on the curve, up to rounding, and on
/// the plane), leaving `from` in the direction of the in-plane tangent that points towards `to`.
/// The first and last points are `from` and `to` themselves, bit for bit.
/// \throw NonFiniteValue if f or its gradient is not finite at a visited point.
[[nodiscard]] PlaneCurve trace_on_plane(const Expression& f, const PlaneFrame& plane, const Eigen::Vector3d& from,
                                        const Eigen::Vector3d& to, const PlaneCurveOptions& options);

}  // namespace sculpt::implicit::detail
