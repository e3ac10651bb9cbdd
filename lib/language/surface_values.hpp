#pragma once
/// \file surface_values.hpp
/// Script values of the surfaces area (builtins_surfaces.cpp): a tensor-product B-spline surface
/// (type "surface"), with the convergence history of the fit that made it, if one did.

#include <vector>

#include "language/value.hpp"
#include "mesh/polygon_mesh.hpp"
#include "splines/bspline_surface.hpp"
#include "splines/fit_surface.hpp"

namespace sculpt::language {

class Arguments;

struct SurfaceValue final : Object {
  explicit SurfaceValue(splines::BSplineSurface s) : surface(std::move(s)) {}
  splines::BSplineSurface surface;
  std::vector<splines::FitSurfaceIteration> history;  ///< fit_surface's rows (row 0: the start); else empty
  bool converged = false;
  [[nodiscard]] std::string type_name() const override { return "surface"; }
  /// "<surface: degree 3 x 3, open x open, 8 x 8 controls>", plus "fitted in k steps" if fitted.
  [[nodiscard]] std::string repr() const override;
};

/// The triangle mesh of a surface at chord tolerance `tol` (splines::tessellate; surface_mesh,
/// export and render draw it), counter-clockwise about S_u x S_v; charges the points made.
/// \throw InvalidInput for a bad tolerance.
PolygonMesh surface_triangle_mesh(const Arguments& args, const splines::BSplineSurface& s, double tol);

/// Default chord tolerance of surface_mesh, thicken, surface_solid and export.
inline constexpr double kDefaultSurfaceTolerance = 1e-3;

}  // namespace sculpt::language
