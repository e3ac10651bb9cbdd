#pragma once
/// \file tessellate_surface.hpp
/// A triangle mesh of a B-spline surface at a chosen tolerance, as plain data (the splines layer
/// sees no mesh type; a layer above turns it into one). Uniform refinement of every knot span:
/// for linear interpolation on the triangles of an hu x hv parameter grid cell, a Taylor argument
/// (the interpolation error at x is -1/2 sum_i l_i D^2S(x_i - x, x_i - x) with barycentric l_i,
/// and sum_i l_i (x_i - x)_a^2 <= 1/4 on the half cell) bounds the chord error by
///     (A hu^2 + 2 C hu hv + B hv^2) / 8,   A >= |S_uu|, B >= |S_vv|, C >= |S_uv|,
/// and the cell sizes are chosen so that this is at most the tolerance. A, B and C are the largest
/// second derivatives on 9 x 9 samples per span, times 1.25: an estimate, not a
/// certified bound (tests measure the error at cell centres). Closed directions share the seam's
/// vertices, so a surface closed in both directions gives a closed mesh.

#include <Eigen/Core>
#include <array>
#include <vector>

#include "splines/bspline_surface.hpp"

namespace sculpt::splines {

struct TessellateOptions {
  double tolerance = 1e-3;  ///< chord error bound (same unit as the control points), > 0
  int max_cells = 1024;     ///< per direction; the bound is reported when this caps the refinement
};

struct SurfaceTriangles {
  std::vector<Eigen::Vector3d> points;
  std::vector<Eigen::Vector2d> parameters;      ///< (u, v) of each point
  std::vector<std::array<int, 3>> triangles;    ///< counter-clockwise about S_u x S_v
  std::array<int, 2> cells{0, 0};               ///< grid cells per direction
  double error_bound = 0.0;                     ///< the estimate above for the chosen cells
};

/// \throw InvalidInput for a tolerance that is not a positive finite number or max_cells < 1.
[[nodiscard]] SurfaceTriangles tessellate(const BSplineSurface& surface, const TessellateOptions& options);

}  // namespace sculpt::splines
