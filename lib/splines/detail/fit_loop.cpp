#include "splines/detail/fit_loop.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "base/errors.hpp"
#include "splines/detail/foot_point_search.hpp"
#include "splines/detail/normal_equations.hpp"

namespace sculpt::splines::detail {

FitResult run_active_curve(const BSpline& start, const Evaluate& evaluate, const LoopOptions& options) {
  const int n = start.control_count();
  for (int f : options.fixed)
    if (f < 0 || f >= n) throw InvalidInput("fit: fixed control index " + std::to_string(f) + " out of range");
  BSpline curve = start;
  Evaluation current = evaluate(curve, nullptr, 0);
  FitResult result{curve, {}, 0, false};
  result.history.push_back({0, current.objective, current.max, current.rms, 0.0, 1.0});
  double lambda = options.smoothing;
  for (int k = 1; k <= options.iterations; ++k) {
    NormalEquations system(n, curve.degree(), curve.dimension(), curve.closed());
    for (const Term& term : current.terms) {
      if (curve.degree() <= kMaxFastDegree) {
        const SmallBasis b = curve.small_basis(term.t);
        system.add_term(b.count, b.index.data(), b.value.data(), term.M, term.x);
      } else {
        const Basis b = curve.basis(term.t, 0);
        system.add_term(b.index, b.value.row(0).transpose(), term.M, term.x);
      }
    }
    // Noise-aware floor of the decaying weight: noise_smoothing * (rms / size)^2 keeps a fairing
    // term proportional to the residual (WPL 2006 fair with a small fixed weight).
    Eigen::Vector3d lo = curve.controls()[0], hi = lo;
    for (const auto& c : curve.controls()) {
      lo = lo.cwiseMin(c);
      hi = hi.cwiseMax(c);
    }
    const double size = (hi - lo).norm();
    const double floor = size > 0 ? options.noise_smoothing * std::pow(current.rms / size, 2) : 0.0;
    const double weight = std::max(lambda, std::min(floor, options.smoothing));
    system.add_smoothing(weight);
    const std::vector<Eigen::Vector3d> solved = system.solve(curve.controls(), options.fixed);
    double step = 1.0;
    BSpline candidate = curve;
    Evaluation next;
    for (int halvings = 0;; ++halvings) {
      std::vector<Eigen::Vector3d> c(n);
      for (int i = 0; i < n; ++i) c[i] = curve.controls()[i] + step * (solved[i] - curve.controls()[i]);
      if (curve.dimension() == 2)
        for (auto& q : c) q.z() = 0.0;
      candidate = curve.with_controls(std::move(c));
      next = evaluate(candidate, &current, k);
      if (!options.line_search || next.objective <= current.objective || halvings >= 8) break;
      step *= 0.5;
    }
    if (!std::isfinite(next.objective)) throw GeometryError("fit: the objective is not finite (diverged)");
    curve = candidate;
    result.history.push_back({k, next.objective, next.max, next.rms, weight, step});
    result.iterations = k;
    const double change = std::abs(current.objective - next.objective);
    current = std::move(next);
    lambda *= options.smoothing_decay;
    if (change <= options.tolerance * std::max(current.objective, 1e-300) || current.objective == 0.0) {
      result.converged = true;
      break;
    }
  }
  result.curve = curve;
  return result;
}

FitResult fit_points(const std::vector<Eigen::Vector3d>& points, const BSpline& start, const LoopOptions& options) {
  const Model model = options.model;
  const Evaluate evaluate = [&points, model](const BSpline& curve, const Evaluation* previous, int) {
    const FootPointSearch search(curve);
    const auto [a, b] = curve.domain();
    Evaluation e;
    e.terms.resize(points.size());
    double sum = 0.0;
    for (std::size_t k = 0; k < points.size(); ++k) {
      // A warm start from the previous foot parameter is checked globally (no sample of the curve
      // closer): SDM and TDM slide control points along the curve, and a warm start alone can land
      // on a wrong local minimum.
      const FootPointJet j = previous && previous->terms.size() == points.size() ? search.warm_jet(points[k], previous->terms[k].t)
                                                                                 : search.global_jet(points[k]);
      const FootPoint& f = j.foot;
      const bool at_end = !curve.closed() && (f.parameter <= a || f.parameter >= b);
      e.terms[k] = {f.parameter, distance_hessian(model, points[k], f.point, j.d1, j.d2, at_end), points[k]};
      sum += f.distance * f.distance;
      e.max = std::max(e.max, f.distance);
    }
    e.objective = sum / static_cast<double>(points.size());
    e.rms = std::sqrt(e.objective);
    return e;
  };
  return run_active_curve(start, evaluate, options);
}

}  // namespace sculpt::splines::detail
