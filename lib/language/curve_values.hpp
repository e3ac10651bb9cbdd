#pragma once
/// \file curve_values.hpp
/// Script values of the curves area (builtins_curves.cpp).

#include <memory>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "curves/digitized_curve.hpp"
#include "curves/linearization.hpp"
#include "language/builtins.hpp"
#include "language/value.hpp"

namespace sculpt::language {

/// A digitized curve (type "curve").
struct CurveValue final : Object {
  explicit CurveValue(curves::DigitizedCurve c) : curve(std::move(c)) {}
  curves::DigitizedCurve curve;
  [[nodiscard]] std::string type_name() const override { return "curve"; }
  [[nodiscard]] std::string repr() const override;
};

/// A linearization together with its curve (type "linearization").
struct LinearizationValue final : Object {
  std::shared_ptr<const CurveValue> curve;
  curves::Linearization result;
  [[nodiscard]] std::string type_name() const override { return "linearization"; }
  [[nodiscard]] std::string repr() const override;
};

/// The open curve (named "list") of argument `name`, a list of [x, y] or [x, y, z] points with finite
/// coordinates, all of one kind; errors at the argument. Also used by the splines area.
[[nodiscard]] curves::DigitizedCurve curve_from_points(const Arguments& args, std::string_view name);

/// A polygon in a plane z = constant, read from a curve or a list of points (extrude, offset).
struct PlanePolygon {
  std::vector<Eigen::Vector2d> points;  ///< (x, y) of each point
  double z = 0;                         ///< the plane's height (0 for no points)
  int dimension = 2;                    ///< the curve's dimension
};

/// The plane polygon of argument `name`: a curve or a list of points whose z are all equal; fails
/// at the argument with `what` (the kinds accepted) or `not_plane` (z differs).
[[nodiscard]] PlanePolygon plane_polygon_arg(const Arguments& args, std::string_view name, const std::string& what,
                                             const std::string& not_plane);

}  // namespace sculpt::language
