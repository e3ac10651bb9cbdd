#include "splines/approximate.hpp"

#include <algorithm>
#include <cmath>

#include "base/errors.hpp"
#include "splines/detail/fit_loop.hpp"
#include "splines/detail/foot_point_search.hpp"
#include "splines/foot_point.hpp"

namespace sculpt::splines {

TargetCurve target_of(const BSpline& curve) {
  TargetCurve t;
  t.evaluate = [&curve](double s) {
    const auto d = curve.jet(s, 2);
    return std::array<Eigen::Vector3d, 3>{d[0], d[1], d[2]};
  };
  std::tie(t.t0, t.t1) = curve.domain();
  t.closed = curve.closed();
  t.samples = 8 * static_cast<int>(curve.breaks().size() - 1);
  return t;
}

namespace {

detail::FootPointSearch search_of(const TargetCurve& target) {
  if (!target.evaluate) throw InvalidInput("approximate: the target has no parametrization");
  if (!(target.t1 > target.t0) || !std::isfinite(target.t0) || !std::isfinite(target.t1))
    throw InvalidInput("approximate: the target's parameter interval is empty or not finite");
  return detail::FootPointSearch(target.evaluate, target.t0, target.t1, target.closed, std::max(target.samples, 16));
}

std::vector<double> active_parameters(const BSpline& curve, int per_span) {
  const std::vector<double> b = curve.breaks();
  std::vector<double> tau;
  for (std::size_t s = 0; s + 1 < b.size(); ++s)
    for (int j = 0; j < per_span; ++j) tau.push_back(b[s] + (b[s + 1] - b[s]) * (j + 0.5) / per_span);
  return tau;
}

}  // namespace

FitResult approximate(const TargetCurve& target, const BSpline& start, const ApproximateOptions& options) {
  if (options.samples_per_span < 1 || options.iterations < 0 || !(options.smoothing >= 0) ||
      !(options.smoothing_decay >= 0) || !(options.smoothing_decay <= 1) || !(options.tolerance >= 0))
    throw InvalidInput("approximate: samples_per_span >= 1, iterations >= 0, smoothing >= 0, decay in [0, 1], tolerance >= 0");
  const detail::FootPointSearch search = search_of(target);
  const std::vector<double> tau = active_parameters(start, options.samples_per_span);
  const auto model = static_cast<detail::Model>(options.method);
  std::vector<Eigen::Vector3d> target_points;
  const int m = static_cast<int>(tau.size());
  for (int i = 0; i < m; ++i)
    target_points.push_back(target.evaluate(target.t0 + (target.t1 - target.t0) * (i + 0.5) / m)[0]);
  const detail::Evaluate evaluate = [&](const BSpline& curve, const detail::Evaluation*, int) {
    detail::Evaluation e;
    e.terms.resize(tau.size());
    double sum = 0.0;
    for (std::size_t j = 0; j < tau.size(); ++j) {
      const Eigen::Vector3d s = curve.point(tau[j]);
      const detail::FootPointJet fj = search.global_jet(s);
      const FootPoint& f = fj.foot;
      const bool at_end = !target.closed && (f.parameter <= target.t0 || f.parameter >= target.t1);
      e.terms[j] = {tau[j], detail::distance_hessian(model, s, f.point, fj.d1, fj.d2, at_end), f.point};
      sum += f.distance * f.distance;
      e.max = std::max(e.max, f.distance);
    }
    std::size_t count = tau.size();
    if (options.two_sided) {
      const detail::FootPointSearch on_active(curve);
      const auto [a, b] = curve.domain();
      for (const Eigen::Vector3d& x : target_points) {
        const detail::FootPointJet fj = on_active.global_jet(x);
        const FootPoint& f = fj.foot;
        const bool at_end = !curve.closed() && (f.parameter <= a || f.parameter >= b);
        e.terms.push_back({f.parameter, detail::distance_hessian(model, x, f.point, fj.d1, fj.d2, at_end), x});
        sum += f.distance * f.distance;
        e.max = std::max(e.max, f.distance);
      }
      count += target_points.size();
    }
    e.objective = sum / static_cast<double>(count);
    e.rms = std::sqrt(e.objective);
    return e;
  };
  return detail::run_active_curve(start, evaluate,
                                  {.model = model,
                                   .iterations = options.iterations,
                                   .smoothing = options.smoothing,
                                   .smoothing_decay = options.smoothing_decay,
                                   .tolerance = options.tolerance,
                                   .fixed = options.fixed,
                                   .line_search = options.method == Method::TDM});
}

OneSidedError one_sided_error(const BSpline& active, const TargetCurve& target, int samples) {
  const detail::FootPointSearch search = search_of(target);
  OneSidedError e;
  for (const Eigen::Vector3d& s : sample(active, samples)) {
    const double d2 = std::pow(search.global(s).distance, 2);
    e.sum += d2;
    e.max = std::max(e.max, d2);
  }
  return e;
}

double hausdorff_distance(const BSpline& a, const BSpline& b, int samples) {
  return std::max(distance(b, sample(a, samples)).max, distance(a, sample(b, samples)).max);
}

}  // namespace sculpt::splines
