#pragma once
/// \file fit.hpp
/// Fitting a B-spline curve with a given number of control points to a point cloud without
/// given parameters (Wang, Pottmann & Liu 2006, "Fitting B-spline curves to point clouds by
/// curvature-based squared distance minimization"): repeat
///   1. foot points of the data points on the current curve,
///   2. a local quadratic model of each squared distance (SDM, PDM or TDM; detail/distance_models.hpp),
///   3. one linear solve for the control points, with a smoothing term whose weight falls.
/// The active-contour view is Pottmann, Leopoldseder & Hofer 2002, sec. 3.

#include <Eigen/Core>
#include <optional>
#include <string>
#include <vector>

#include "splines/bspline.hpp"

namespace sculpt::splines {

/// The squared distance model of each step.
enum class Method {
  SDM,  ///< curvature-based squared distance (WPL 2006, eq. 8), truncated to TDM inside the curvature centre
  PDM,  ///< point distance: each data point pulls its foot point (classic parameter correction)
  TDM,  ///< tangent distance (Gauss-Newton), with step halving so the objective never grows
};

/// "sdm", "pdm", "tdm" (case-insensitive). \throw InvalidInput otherwise.
[[nodiscard]] Method method_from_name(const std::string& name);
[[nodiscard]] std::string method_name(Method method);

struct FitOptions {
  int controls = 0;  ///< control point count; 0 takes the start curve's
  int degree = 3;
  bool closed = false;
  Method method = Method::SDM;
  int iterations = 50;           ///< at most this many steps
  double smoothing = 1e-1;       ///< relative weight of the bending term in the first step
  double smoothing_decay = 0.5;  ///< factor per step
  /// The weight does not fall below noise_smoothing * (rms distance / curve size)^2 (at most
  /// `smoothing`): noisy data keep a fairing term that grows with their noise, clean data lose it.
  double noise_smoothing = 200.0;
  /// Stop when a step changes the objective by less than this fraction (1e-4: the rms distance
  /// by less than 5e-5 of itself; on noisy data the tail beyond that is noise).
  double tolerance = 1e-4;
  /// SDM only: once a step gains less than half of the objective, use the full Newton model of the
  /// squared distance of a data point to the moving curve. SDM's (untruncated) Hessian is that
  /// Newton model without the terms of the derivative of the curve's displacement (a quasi-Newton
  /// method; docs/splines.md); those terms are of the order of the distance, like SDM's tangential
  /// stiffness itself, so without them the tail converges only linearly (star target: 50 steps to
  /// within 1e-3 of the optimum instead of 11). false: plain SDM throughout. Closed curves only:
  /// the data-to-curve objective does not hold the ends of an open curve (running on past the last
  /// data point along the tangent costs nothing), and Newton's model, unlike SDM's, lets them drift
  /// (an open half ellipse: ends 2.5e-2 past the data after 50 steps, SDM 1.3e-3).
  bool second_order = true;
  std::optional<BSpline> start{};///< start curve; default initial_curve(...)
  std::vector<int> fixed{};      ///< indices of start-curve control points kept in place
  int dimension = 0;             ///< 0: 2 if every z is 0, else 3
};

/// One row of the convergence history; row 0 describes the start curve.
struct FitIteration {
  int iteration = 0;
  double objective = 0.0;     ///< mean squared distance of the data to the curve (exact foot points)
  double max_distance = 0.0;
  double rms_distance = 0.0;
  double smoothing = 0.0;     ///< relative smoothing weight used in the step that led here
  double step = 1.0;          ///< step length accepted (SDM and TDM halve it when the objective would grow;
                              ///< 0: the full step changed the objective by less than the tolerance, the curve is kept)
  int points = 0;             ///< data points the row was measured on (fewer: the coarse pass of a large fit)
};

struct FitResult {
  BSpline curve;
  std::vector<FitIteration> history;
  int iterations = 0;      ///< steps taken
  bool converged = false;  ///< the tolerance was met (false: the iteration limit stopped it)
};

/// Fits a curve to `points`. Parameters come from the foot points; nothing else is needed.
/// \throw InvalidInput for degree < 1, fewer than degree + 1 control points, more control points
///        than data points, a non-finite point, points that all coincide, fewer distinct points
///        than the degree + 1, a start curve whose closedness or dimension differs, or a bad fixed index.
[[nodiscard]] FitResult fit_curve(const std::vector<Eigen::Vector3d>& points, const FitOptions& options);

/// The default start: for a closed curve a uniform periodic spline close to the ellipse of the
/// data's principal axes (radii sqrt(2) times the standard deviations, i.e. exact for points spread
/// evenly on an ellipse); for an open curve a clamped spline on the chord between the extreme
/// projections onto the first principal axis.
[[nodiscard]] BSpline initial_curve(const std::vector<Eigen::Vector3d>& points, int controls, int degree, bool closed,
                                    int dimension = 0);

}  // namespace sculpt::splines
