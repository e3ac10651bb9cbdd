#pragma once
/// \file fit_surface.hpp
/// Fitting a B-spline surface with a fixed control grid to a point cloud: the active surface of
/// Pottmann, Leopoldseder & Hofer 2002, sec. 4 (Wang, Pottmann & Liu 2006 for the curve case).
/// Each step
///   1. finds the foot points of the data points on the current surface (exact, warm-started),
///   2. models each squared distance by a quadratic form: SDM, the curvature-based second-order
///      approximant of the seed's Proposition 1 (eq. 6), made nonnegative as in eq. 7,
///          F(x) ~ c1 (x.e1)^2 + c2 (x.e2)^2 + (x.n)^2,  c_i = d k_i / (d k_i - 1) if d k_i < 0, else 0,
///      in the principal frame (e1, e2, n) at the foot point, d = (p - f).n, k_i the principal
///      curvatures signed with respect to n; or PDM (the squared distance to the foot point) or
///      TDM (the tangent plane, c_i = 0). A foot point on an edge of an open direction takes the
///      edge curve's model (detail/distance_models.hpp), a corner PDM's;
///   3. solves one sparse linear system for the control points with a thin-plate smoothing term
///      whose weight falls by a constant factor per step; SDM and TDM halve a step that would
///      increase the objective.
/// Data points on the data's boundary pull the surface's edge curves instead (FitSurfaceOptions::fit_boundary).
/// The default start is the seed's: the bilinear patch through the data's four corners, which
/// stay fixed (sec. 4, "the vertices of the model patch have been fixed").

#include <Eigen/Core>
#include <array>
#include <optional>
#include <vector>

#include "splines/bspline_surface.hpp"
#include "splines/fit.hpp"

namespace sculpt::splines {

struct FitSurfaceOptions {
  std::array<int, 2> controls{8, 8};  ///< control grid (ignored with `start`)
  std::array<int, 2> degree{3, 3};    ///< (ignored with `start`)
  Method method = Method::SDM;
  int iterations = 20;               ///< at most this many steps
  double smoothing = 1e-2;           ///< relative thin-plate weight in the first step (then times smoothing_decay per step)
  double smoothing_decay = 0.1;      ///< factor per step
  /// Stop when a step changes the objective (mean squared distance) by less than this fraction.
  double tolerance = 1e-4;
  bool fix_corners = true;    ///< keep the four corner control points (open-open surfaces) in place
  bool fix_boundary = false;  ///< keep every control point of an open direction's boundary rows in place
  /// The seed's boundary approximation term (sec. 4, item 2): data points whose foot point on the
  /// start surface lies on an edge of an open direction are the data's boundary; each step they
  /// pull that edge curve (their distance to it, modelled by the curve SDM) instead of the surface.
  /// Off by default: on the benchmark patches it changes little (cap, 8 x 8, 7 steps: max 4.38e-7
  /// against 4.52e-7; wave 3.80e-4 against 3.78e-4; docs/splines.md).
  bool fit_boundary = false;
  /// Corners of the start patch in the order S(0,0), S(1,0), S(0,1), S(1,1); default corner_points(points).
  std::optional<std::array<Eigen::Vector3d, 4>> corners{};
  std::optional<BSplineSurface> start{};  ///< start surface instead of the bilinear patch (any closedness)
  std::vector<int> fixed{};               ///< further fixed control indices (i * columns + j)
};

/// One row of the history; row 0 describes the start surface.
struct FitSurfaceIteration {
  int iteration = 0;
  double objective = 0.0;  ///< mean squared distance of the data to the surface (exact foot points)
  double max_distance = 0.0;
  double rms_distance = 0.0;
  double smoothing = 0.0;  ///< relative thin-plate weight of the step that led here
  double step = 1.0;       ///< step length accepted (halved while the objective would grow; 0: no
                           ///< descent in 8 halvings, the surface is kept and the fit stops)
  double cpu_ms = 0.0;     ///< thread CPU time of the step (row 0: the start's foot points)
};

struct FitSurfaceResult {
  BSplineSurface surface;
  std::vector<FitSurfaceIteration> history;
  int iterations = 0;
  bool converged = false;  ///< the tolerance was met (false: the iteration limit stopped it)
};

/// Fits a surface to `points`. \throw InvalidInput for a degree outside [1, kMaxFastDegree], a
/// grid with fewer than degree + 1 controls per direction, fewer points than control points, a
/// non-finite point, or a bad fixed index.
[[nodiscard]] FitSurfaceResult fit_surface(const std::vector<Eigen::Vector3d>& points, const FitSurfaceOptions& options);

/// The four data points extreme in the directions -a-b, a-b, -a+b, a+b, with a and b the first two
/// principal axes of the data: the corners of a roughly rectangular patch, in the order
/// S(0,0), S(1,0), S(0,1), S(1,1). \throw InvalidInput for fewer than 4 points or a non-finite point.
[[nodiscard]] std::array<Eigen::Vector3d, 4> corner_points(const std::vector<Eigen::Vector3d>& points);

/// The bilinear patch through the corners (order as corner_points) as an open rows x columns
/// B-spline surface with clamped uniform knots: the controls sit at the Greville abscissae, so the
/// surface is exactly the bilinear patch.
[[nodiscard]] BSplineSurface bilinear_patch(const std::array<Eigen::Vector3d, 4>& corners, std::array<int, 2> controls,
                                            std::array<int, 2> degree = {3, 3});

}  // namespace sculpt::splines
