#pragma once
/// \file approximate.hpp
/// Approximation of a known target curve by an active B-spline curve (Pottmann, Leopoldseder &
/// Hofer 2002, sec. 3): sample points s_j = c(tau_j) of the active curve at fixed parameters
/// move under local quadratic approximants of the target's squared distance function, evaluated
/// at their foot points on the target (eq. 4; the objective of eq. 11), plus a smoothing term.
/// Degree reduction (sec. 3.1) and the helix (sec. 3.3) are applications; offsets are in offset.hpp.

#include <Eigen/Core>
#include <array>
#include <functional>
#include <vector>

#include "splines/bspline.hpp"
#include "splines/fit.hpp"

namespace sculpt::splines {

/// A target curve given by a twice differentiable parametrization over [t0, t1].
struct TargetCurve {
  std::function<std::array<Eigen::Vector3d, 3>(double)> evaluate;  ///< point, c', c''
  double t0 = 0.0, t1 = 1.0;
  bool closed = false;
  int samples = 512;  ///< samples of the foot point search's bracketing
};

/// The target form of a spline (its foot point search samples every knot span 8 times).
/// The spline must outlive the returned target.
[[nodiscard]] TargetCurve target_of(const BSpline& curve);

struct ApproximateOptions {
  Method method = Method::SDM;
  int iterations = 30;
  int samples_per_span = 16;      ///< active sample points per knot span
  double smoothing = 1e-4;        ///< relative weight of the bending term in the first step
  double smoothing_decay = 0.5;
  double tolerance = 1e-6;        ///< relative change of the objective that stops the iteration
  std::vector<int> fixed{};       ///< control points kept in place (e.g. the ends)
  /// Also let target sample points pull on their foot points on the active curve (the point
  /// cloud direction, fit.hpp), as many as there are active samples. Without it a start far from
  /// the target (the helix's straight chord) sees only foot points near the target's ends and stalls.
  bool two_sided = true;
};

/// Moves `start` towards the target. The history's objective is the mean squared distance of the
/// active sample points to the target (the seed's one-sided error, eq. 12, divided by their count)
/// and, when two-sided, of the target samples to the active curve; max is the largest of either.
/// \throw InvalidInput for a bad option or fixed index, GeometryError if a step diverges.
[[nodiscard]] FitResult approximate(const TargetCurve& target, const BSpline& start, const ApproximateOptions& options = {});

/// The seed's one-sided error (eq. 12): squared distances from `samples` uniform parameter
/// samples of `active` to the target; sum and max.
struct OneSidedError {
  double sum = 0.0;
  double max = 0.0;
};
[[nodiscard]] OneSidedError one_sided_error(const BSpline& active, const TargetCurve& target, int samples = 200);

/// Two-sided Hausdorff distance between two curves, from `samples` samples of each to the other (exact foot points).
[[nodiscard]] double hausdorff_distance(const BSpline& a, const BSpline& b, int samples = 1000);

}  // namespace sculpt::splines
