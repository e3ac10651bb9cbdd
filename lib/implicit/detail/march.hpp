#pragma once
/// \file march.hpp
/// Predictor-corrector marching along one component of f = g = 0 (Ihm & Naylor sec. 5.1):
/// predictor along t = grad f x grad g, Newton corrector on the plane normal to t, step length
/// from the measured chord height (sagitta = kappa h^2 / 8 <= tol), stepping over singular points
/// along the incoming tangent.

#include <Eigen/Core>
#include <vector>

#include "implicit/detail/curve_system.hpp"
#include "implicit/trace.hpp"

namespace sculpt::implicit::detail {

struct MarchContext {
  const CurveSystem& system;
  Box box;
  double tolerance = 0.0;
  double diagonal = 0.0;  ///< box diagonal, the length scale
  long max_steps = 0;
  long steps = 0;  ///< steps used so far (across walks)
  std::vector<SingularPoint> singular_points;
};

enum class WalkEnd { Boundary, Closed, Singular, Budget };

struct Walk {
  std::vector<Eigen::Vector3d> points;  ///< starts with the start point
  WalkEnd end = WalkEnd::Budget;
};

/// Walks from `start` (on the curve) in `direction` until the box boundary, the start again
/// (only if allow_close), an impassable singular point or the end of the step budget.
[[nodiscard]] Walk walk(MarchContext& context, const CurvePoint& start, const Eigen::Vector3d& direction,
                        bool allow_close);

}  // namespace sculpt::implicit::detail
