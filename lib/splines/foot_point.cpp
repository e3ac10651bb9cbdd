#include "splines/foot_point.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "base/errors.hpp"
#include "splines/detail/foot_point_search.hpp"

namespace sculpt::splines {

namespace detail {

FootPointSearch::FootPointSearch(const BSpline& curve, int samples_per_span)
    : evaluate_([&curve](double t) {
        const auto d = curve.derivatives(t, 2);
        return std::array<Eigen::Vector3d, 3>{d[0], d[1], d[2]};
      }),
      a_(curve.domain().first),
      b_(curve.domain().second),
      closed_(curve.closed()) {
  const std::vector<double> b = curve.breaks();
  for (std::size_t s = 0; s + 1 < b.size(); ++s)
    for (int j = 0; j < samples_per_span; ++j) params_.push_back(b[s] + (b[s + 1] - b[s]) * j / samples_per_span);
  if (!closed_) params_.push_back(b.back());
  points_.reserve(params_.size());
  for (double t : params_) points_.push_back(curve.point(t));
}

FootPointSearch::FootPointSearch(Evaluator evaluate, double a, double b, bool closed, int samples)
    : evaluate_(std::move(evaluate)), a_(a), b_(b), closed_(closed) {
  if (!(b > a) || samples < 2) throw InvalidInput("foot point search: empty domain or fewer than 2 samples");
  for (int j = 0; j < samples; ++j) params_.push_back(a + (b - a) * j / samples);
  if (!closed_) params_.push_back(b);
  for (double t : params_) points_.push_back(evaluate_(t)[0]);
}

double FootPointSearch::wrap(double t) const {
  if (!closed_) return std::clamp(t, a_, b_);
  const double period = b_ - a_;
  double s = a_ + std::fmod(t - a_, period);
  if (s < a_) s += period;
  if (s >= b_) s = a_;
  return s;
}

FootPoint FootPointSearch::refine(const Eigen::Vector3d& x, double t0, double lo, double hi) const {
  // Minimize g(t) = |c(t) - x|^2 / 2 on [lo, hi]: Newton on g' = (c - x) . c', falling back to
  // bisection of the bracket whenever the step leaves it or g'' <= 0.
  const double scale = std::max({1.0, std::abs(lo), std::abs(hi)});
  double t = std::clamp(t0, lo, hi);
  for (int it = 0; it < 60; ++it) {
    const auto d = evaluate_(wrap(t));
    const Eigen::Vector3d r = d[0] - x;
    const double f = r.dot(d[1]), fp = d[1].squaredNorm() + r.dot(d[2]);
    if (f > 0)
      hi = t;
    else
      lo = t;
    if (f == 0.0 || hi - lo < 1e-15 * scale) break;
    double next = fp > 0 ? t - f / fp : 0.5 * (lo + hi);
    if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
    if (std::abs(next - t) < 1e-15 * scale) {
      t = next;
      break;
    }
    t = next;
  }
  FootPoint fp;
  fp.parameter = t;
  fp.point = evaluate_(wrap(t))[0];
  fp.distance = (fp.point - x).norm();
  return fp;
}

FootPoint FootPointSearch::global(const Eigen::Vector3d& x) const {
  const int m = static_cast<int>(params_.size());
  const bool closed = closed_;
  const double a = a_, b = b_;
  std::vector<double> d2(m);
  for (int i = 0; i < m; ++i) d2[i] = (points_[i] - x).squaredNorm();
  // Local minima of the sampled distance, best first; refine a few of them.
  std::vector<int> minima;
  for (int i = 0; i < m; ++i) {
    const double left = (i > 0) ? d2[i - 1] : closed ? d2[m - 1] : INFINITY;
    const double right = (i + 1 < m) ? d2[i + 1] : closed ? d2[0] : INFINITY;
    if (d2[i] <= left && d2[i] <= right) minima.push_back(i);
  }
  std::sort(minima.begin(), minima.end(), [&](int i, int j) { return d2[i] < d2[j]; });
  // Refine the best local minimum and the ones that could still beat it (sampled distance
  // within twice the best: a curve coming close to itself); at most four.
  std::size_t keep = 1;
  while (keep < minima.size() && keep < 4 && d2[minima[keep]] <= 4.0 * d2[minima[0]] + 1e-300) ++keep;
  minima.resize(std::min(keep, minima.size()));
  FootPoint best;
  best.distance = INFINITY;
  for (int i : minima) {
    double lo = i > 0 ? params_[i - 1] : closed ? params_[m - 1] - (b - a) : a;
    double hi = i + 1 < m ? params_[i + 1] : closed ? b : params_[i];
    if (!closed && i + 1 == m) hi = b;
    const FootPoint f = refine(x, params_[i], lo, hi);
    if (f.distance < best.distance) best = f;
    if (!closed) {  // an end point may be the minimum (the bracket is one-sided there)
      for (double e : {a, b}) {
        if ((e == a && i <= 1) || (e == b && i >= m - 2)) {
          const Eigen::Vector3d pe = evaluate_(e)[0];
          const double de = (pe - x).norm();
          if (de < best.distance) best = {e, pe, de};
        }
      }
    }
  }
  best.parameter = wrap(best.parameter);
  return best;
}

FootPoint FootPointSearch::local(const Eigen::Vector3d& x, double t0, double radius) const {
  double lo = t0 - radius, hi = t0 + radius;
  if (!closed_) {
    lo = std::max(lo, a_);
    hi = std::min(hi, b_);
  }
  FootPoint f = refine(x, t0, lo, hi);
  f.parameter = wrap(f.parameter);
  return f;
}

}  // namespace detail

namespace {
void check_point(const Eigen::Vector3d& x, std::size_t i) {
  if (!x.allFinite()) throw InvalidInput("foot point: point " + std::to_string(i) + " is not finite");
}
}  // namespace

FootPoint closest_point(const BSpline& curve, const Eigen::Vector3d& x) {
  check_point(x, 0);
  return detail::FootPointSearch(curve).global(x);
}

std::vector<FootPoint> closest_points(const BSpline& curve, const std::vector<Eigen::Vector3d>& points) {
  const detail::FootPointSearch search(curve);
  std::vector<FootPoint> out;
  out.reserve(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) {
    check_point(points[i], i);
    out.push_back(search.global(points[i]));
  }
  return out;
}

DistanceSummary distance(const BSpline& curve, const std::vector<Eigen::Vector3d>& points) {
  if (points.empty()) throw InvalidInput("distance: the point set is empty");
  DistanceSummary s;
  double sum = 0.0;
  for (const FootPoint& f : closest_points(curve, points)) {
    s.max = std::max(s.max, f.distance);
    sum += f.distance * f.distance;
  }
  s.rms = std::sqrt(sum / static_cast<double>(points.size()));
  return s;
}

std::vector<Eigen::Vector3d> sample(const BSpline& curve, int n) {
  const int minimum = curve.closed() ? 1 : 2;
  if (n < minimum) throw InvalidInput("sample: needs at least " + std::to_string(minimum) + " points, got " + std::to_string(n));
  const auto [a, b] = curve.domain();
  std::vector<Eigen::Vector3d> out(n);
  const int steps = curve.closed() ? n : n - 1;
  for (int i = 0; i < n; ++i) out[i] = curve.point(i == steps ? b : a + (b - a) * i / steps);
  return out;
}

}  // namespace sculpt::splines
