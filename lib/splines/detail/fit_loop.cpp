#include "splines/detail/fit_loop.hpp"
#include "base/cancel.hpp"

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
  const auto finish = [&](FitResult& r) {
    if (options.final_smoothing) *options.final_smoothing = lambda;
    r.curve = curve;
    return r;
  };
  for (int k = 1; k <= options.iterations; ++k) {
    check_cancel();  // Ctrl-C (base/cancel.hpp): one iteration solves the whole fit
    const auto& h = result.history;
    // The second-order phase starts once a step gained less than half of the objective: the foot
    // points then move little, and SDM's missing terms (of the same order as its tangential
    // stiffness) are what slows the tail.
    const bool newton = options.second_order && (options.second_order_from_start ||
                                                 (k > 1 && h[k - 1].objective > 0.5 * h[k - 2].objective));
    if (newton && options.stop_at_second_order) return finish(result);
    NormalEquations system(n, curve.degree(), curve.dimension(), curve.closed());
    for (const Term& term : current.terms) {
      const bool second_order = newton && term.newton_weight != 0.0;
      if (curve.degree() <= kMaxFastDegree) {
        const SmallBasis b = curve.small_basis(term.t, second_order);
        system.add_term(b.count, b.index.data(), b.value.data(), second_order ? Eigen::Matrix3d::Identity() : term.M, term.x);
        if (second_order)
          system.add_newton_correction(b.count, b.index.data(), b.value.data(), b.derivative.data(),
                                       term.x + term.residual, term.velocity, term.residual, term.newton_weight);
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
    // The bending term only steadies the first steps; in the second-order phase it falls faster.
    if (newton) lambda *= options.smoothing_decay * options.smoothing_decay;
    const double weight = std::max(lambda, std::min(floor, options.smoothing));
    system.add_smoothing(weight);
    const std::vector<Eigen::Vector3d> solved = system.solve(curve.controls(), options.fixed);
    double step = 1.0;
    BSpline candidate = curve;
    Evaluation next;
    bool at_optimum = false;
    for (int halvings = 0;; ++halvings) {
      std::vector<Eigen::Vector3d> c(n);
      for (int i = 0; i < n; ++i) c[i] = curve.controls()[i] + step * (solved[i] - curve.controls()[i]);
      if (curve.dimension() == 2)
        for (auto& q : c) q.z() = 0.0;
      candidate = curve.with_controls(std::move(c));
      next = evaluate(candidate, &current, k);
      if (!options.line_search || next.objective <= current.objective || halvings >= 8) break;
      // A full step that changes the objective by less than the tolerance, up or down, finds the
      // curve converged: halving it would only spend foot point searches on nothing.
      if (halvings == 0 && next.objective - current.objective <= options.tolerance * current.objective) {
        at_optimum = true;
        break;
      }
      step *= 0.5;
    }
    if (at_optimum) {
      result.history.push_back({k, current.objective, current.max, current.rms, weight, 0.0});
      result.iterations = k;
      result.converged = true;
      break;
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
  return finish(result);
}

namespace {
FitResult fit_all(const std::vector<Eigen::Vector3d>& points, const BSpline& start, const LoopOptions& options) {
  const Model model = options.model;
  const Evaluate evaluate = [&points, model, &options](const BSpline& curve, const Evaluation* previous, int) {
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
      // Newton's model of |x - c|^2 for the moving curve (see LoopOptions::second_order): the point
      // distance minus ((c'.a)^2 + 2 (c'.a)(r.b)) / D, with a and b the displacements of c(t) and
      // c'(t), r = c - x and D = |c'|^2 + r.c''. Newton's (r.b)^2 / D, second order in the distance
      // and negative, is left out: on noisy data it makes the model indefinite (halved steps).
      // Used only while D > |c'|^2 / 2 (x not near its curvature centre).
      if (options.second_order && model == Model::SDM && !at_end) {
        const Eigen::Vector3d r = f.point - points[k];
        const double speed2 = j.d1.squaredNorm(), D = speed2 + r.dot(j.d2);
        if (D > 0.5 * speed2) {
          Term& t = e.terms[k];
          t.newton_weight = -1.0 / D;
          t.velocity = j.d1;
          t.residual = r;
        }
      }
      sum += f.distance * f.distance;
      e.max = std::max(e.max, f.distance);
    }
    e.objective = sum / static_cast<double>(points.size());
    e.rms = std::sqrt(e.objective);
    return e;
  };
  FitResult r = run_active_curve(start, evaluate, options);
  for (auto& row : r.history) row.points = static_cast<int>(points.size());
  return r;
}
}  // namespace

FitResult fit_points(const std::vector<Eigen::Vector3d>& points, const BSpline& start, const LoopOptions& options) {
  const std::size_t n = static_cast<std::size_t>(start.control_count());
  if (!(options.second_order && options.model == Model::SDM && start.closed() && points.size() >= 4000 &&
        points.size() >= 64 * n) || options.stop_at_second_order || options.second_order_from_start)
    return fit_all(points, start, options);
  const std::size_t stride = points.size() / (16 * n);
  std::vector<Eigen::Vector3d> subset;
  for (std::size_t i = 0; i < points.size(); i += stride) subset.push_back(points[i]);
  double lambda = options.smoothing;
  LoopOptions coarse = options;
  coarse.stop_at_second_order = true;
  coarse.final_smoothing = &lambda;
  FitResult first = fit_all(subset, start, coarse);
  // (With no steps left, the second pass only measures the curve on all points.)
  LoopOptions fine = options;
  fine.iterations = options.iterations - first.iterations;
  fine.smoothing = lambda;
  fine.second_order_from_start = true;
  FitResult second = fit_all(points, first.curve, fine);
  // One history: the subset's rows, then the full data's; the last subset row and the full data's
  // row 0 describe the same curve, and the latter's figures (all points) replace the former's.
  FitIteration& joint = first.history.back();
  joint.objective = second.history[0].objective;
  joint.max_distance = second.history[0].max_distance;
  joint.rms_distance = second.history[0].rms_distance;
  joint.points = second.history[0].points;
  for (std::size_t i = 1; i < second.history.size(); ++i) {
    FitIteration row = second.history[i];
    row.iteration += first.iterations;
    first.history.push_back(row);
  }
  first.curve = second.curve;
  first.iterations += second.iterations;
  first.converged = second.converged;
  return first;
}

}  // namespace sculpt::splines::detail
