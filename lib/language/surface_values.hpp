#pragma once
/// \file surface_values.hpp
/// Script values of the surfaces area (builtins_surfaces.cpp): a tensor-product B-spline surface
/// (type "surface"), with the convergence history of the fit that made it, if one did.

#include <vector>

#include "language/value.hpp"
#include "splines/bspline_surface.hpp"
#include "splines/fit_surface.hpp"

namespace sculpt::language {

struct SurfaceValue final : Object {
  explicit SurfaceValue(splines::BSplineSurface s) : surface(std::move(s)) {}
  splines::BSplineSurface surface;
  std::vector<splines::FitSurfaceIteration> history;  ///< fit_surface's rows (row 0: the start); else empty
  bool converged = false;
  [[nodiscard]] std::string type_name() const override { return "surface"; }
  /// "<surface: degree 3 x 3, open x open, 8 x 8 controls>", plus "fitted in k steps" if fitted.
  [[nodiscard]] std::string repr() const override;
};

}  // namespace sculpt::language
