#pragma once
/// \file foot_point_search.hpp
/// The foot point machinery behind foot_point.hpp, shared with the fitters: a sampling of the
/// curve (several samples per knot span) for the global search, and a safeguarded Newton
/// refinement inside a bracket for warm starts from a previous parameter.

#include <Eigen/Core>
#include <array>
#include <functional>
#include <vector>

#include "splines/bspline.hpp"
#include "splines/foot_point.hpp"

namespace sculpt::splines::detail {

/// Samples per knot span of the global search (enough for the few wiggles a span of degree <= 5 can have).
inline constexpr int kSamplesPerSpan = 8;

/// Point, first and second derivative of a parametric curve at t.
using Evaluator = std::function<std::array<Eigen::Vector3d, 3>(double)>;

class FootPointSearch {
 public:
  explicit FootPointSearch(const BSpline& curve, int samples_per_span = kSamplesPerSpan);
  /// Any twice differentiable curve over [a, b] (periodic when closed), sampled `samples` times.
  FootPointSearch(Evaluator evaluate, double a, double b, bool closed, int samples);
  /// Global search: every local minimum of the sampled distance is refined; the best wins.
  [[nodiscard]] FootPoint global(const Eigen::Vector3d& x) const;
  /// Local search from t0 within [t0 - radius, t0 + radius] (clamped to the domain of an open curve).
  [[nodiscard]] FootPoint local(const Eigen::Vector3d& x, double t0, double radius) const;

 private:
  [[nodiscard]] FootPoint refine(const Eigen::Vector3d& x, double t0, double lo, double hi) const;
  [[nodiscard]] double wrap(double t) const;
  Evaluator evaluate_;
  double a_ = 0.0, b_ = 1.0;
  bool closed_ = false;
  std::vector<double> params_;
  std::vector<Eigen::Vector3d> points_;
};

}  // namespace sculpt::splines::detail
