#pragma once
/// \file fit_loop.hpp
/// The active-curve iteration shared by both directions of the method:
/// - fit_points: data points fixed, foot points on the moving curve (Wang, Pottmann & Liu 2006);
/// - the target direction (approximate.hpp): sample points of the moving curve at fixed
///   parameters, foot points on a fixed target (Pottmann, Leopoldseder & Hofer 2002, sec. 3).
/// Each step builds the terms (parameter on the active curve, Hessian M, point x) of the quadratic
/// objective, solves, and for SDM and TDM halves the step until the objective does not grow.

#include <Eigen/Core>
#include <functional>
#include <vector>

#include "splines/bspline.hpp"
#include "splines/detail/distance_models.hpp"
#include "splines/fit.hpp"

namespace sculpt::splines::detail {

struct Term {
  double t = 0.0;  ///< parameter on the active curve
  Eigen::Matrix3d M = Eigen::Matrix3d::Identity();
  Eigen::Vector3d x = Eigen::Vector3d::Zero();
  /// Newton's correction (fit_points, SDM; NormalEquations::add_newton_correction): its weight
  /// -1/D (0: none), the curve's velocity at t and the residual c(t) - x.
  double newton_weight = 0.0;
  Eigen::Vector3d velocity = Eigen::Vector3d::Zero(), residual = Eigen::Vector3d::Zero();
};

struct Evaluation {
  std::vector<Term> terms;
  double objective = 0.0, max = 0.0, rms = 0.0;
};

/// Terms and objective for a curve; `previous` (may be null) offers warm-start parameters.
using Evaluate = std::function<Evaluation(const BSpline& curve, const Evaluation* previous, int iteration)>;

struct LoopOptions {
  Model model = Model::SDM;
  int iterations = 50;
  double smoothing = 1e-1;
  double smoothing_decay = 0.5;
  double tolerance = 1e-5;
  std::vector<int> fixed{};
  bool line_search = false;
  double noise_smoothing = 0.0;  ///< see FitOptions::noise_smoothing
  /// SDM on a point cloud: near convergence, replace the model by Newton's (FitOptions::second_order).
  bool second_order = false;
  /// With second_order: stop when the second-order phase would start (coarse_to_fine's first pass),
  /// or be in it from the first step (its second pass).
  bool stop_at_second_order = false, second_order_from_start = false;
  /// Out: the smoothing weight the next step would have used (coarse_to_fine carries it over).
  double* final_smoothing = nullptr;
};

[[nodiscard]] FitResult run_active_curve(const BSpline& start, const Evaluate& evaluate, const LoopOptions& options);

/// Wang-Pottmann-Liu direction on a point cloud. A closed second-order fit of many points
/// (at least 4000 and 64 per control point) runs coarse to fine: the first-order steps on every
/// k-th point (16 per control point), the second-order phase on all of them; the history's rows of
/// the first pass describe the subset (FitIteration::points).
[[nodiscard]] FitResult fit_points(const std::vector<Eigen::Vector3d>& points, const BSpline& start,
                                   const LoopOptions& options);

}  // namespace sculpt::splines::detail
