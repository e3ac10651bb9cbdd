#pragma once
/// \file foot_point_search.hpp
/// The foot point machinery behind foot_point.hpp, shared with the fitters: a sampling of the
/// curve (several samples per knot span) for the global search, and a safeguarded Newton
/// refinement inside a bracket for warm starts from a previous parameter. The samples are grouped
/// in chunks of consecutive samples with bounding boxes, so a query scans only the chunks that can
/// hold a sample within twice the nearest sample's distance (the same candidates as a full scan).

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

/// A foot point with the curve's first and second derivative there (saves the caller an evaluation).
struct FootPointJet {
  FootPoint foot;
  Eigen::Vector3d d1 = Eigen::Vector3d::Zero(), d2 = Eigen::Vector3d::Zero();
};

class FootPointSearch {
 public:
  explicit FootPointSearch(const BSpline& curve, int samples_per_span = kSamplesPerSpan);
  /// Any twice differentiable curve over [a, b] (periodic when closed), sampled `samples` times.
  FootPointSearch(Evaluator evaluate, double a, double b, bool closed, int samples);
  /// Global search: every local minimum of the sampled distance is refined; the best wins.
  [[nodiscard]] FootPoint global(const Eigen::Vector3d& x) const { return global_jet(x).foot; }
  [[nodiscard]] FootPointJet global_jet(const Eigen::Vector3d& x) const;
  /// Warm start: Newton from the previous foot parameter t0 inside the samples around it, accepted
  /// only after a global check that no sample of the curve is closer (chunk boxes first); else global_jet.
  [[nodiscard]] FootPointJet warm_jet(const Eigen::Vector3d& x, double t0) const;
  /// Local search from t0 within [t0 - radius, t0 + radius] (clamped to the domain of an open curve).
  [[nodiscard]] FootPoint local(const Eigen::Vector3d& x, double t0, double radius) const;

 private:
  [[nodiscard]] FootPointJet refine(const Eigen::Vector3d& x, double t0, double lo, double hi) const;
  [[nodiscard]] double wrap(double t) const;
  [[nodiscard]] std::array<Eigen::Vector3d, 3> eval(double t) const;
  void build_chunks();
  static constexpr int kChunk = 8;
  const BSpline* curve_ = nullptr;  // the fast path (no std::function, no allocation)
  // Degree <= 3: the curve's polynomial pieces in Taylor form about each span's start (Horner).
  std::vector<double> span_start_;
  std::vector<std::array<Eigen::Vector3d, 4>> taylor_;
  Evaluator evaluate_;
  std::vector<Eigen::Vector3d> box_lo_, box_hi_;      // per chunk of kChunk samples
  std::vector<Eigen::Vector3d> group_lo_, group_hi_;  // per group of kChunk chunks (warm_jet's check)
  double a_ = 0.0, b_ = 1.0;
  bool closed_ = false;
  std::vector<double> params_;
  std::vector<Eigen::Vector3d> points_;
};

}  // namespace sculpt::splines::detail
