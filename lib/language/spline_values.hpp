#pragma once
/// \file spline_values.hpp
/// Script values of the splines area (builtins_splines.cpp): a B-spline curve (type "spline"),
/// with the convergence history of the fit that made it, if one did.

#include <memory>
#include <vector>

#include "language/value.hpp"
#include "splines/bspline.hpp"
#include "splines/fit.hpp"

namespace sculpt::language {

struct SplineValue final : Object {
  explicit SplineValue(splines::BSpline s) : spline(std::move(s)) {}
  splines::BSpline spline;
  /// Rows of fit_curve / approximate / reduce_degree (row 0: the start); empty for a spline
  /// given by its control points or read from a file.
  std::vector<splines::FitIteration> history;
  bool converged = false;
  [[nodiscard]] std::string type_name() const override { return "spline"; }
  /// "<spline: degree 3, open, 2D, 8 controls, domain [0, 1]>", plus "fitted in 6 steps" if fitted.
  [[nodiscard]] std::string repr() const override;
};

/// A spline as a script value (no fit history).
inline Value spline_value(splines::BSpline s) {
  return Value(std::shared_ptr<const Object>(std::make_shared<SplineValue>(std::move(s))));
}

}  // namespace sculpt::language
