#include "splines/foot_point.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "base/errors.hpp"
#include "splines/detail/foot_point_search.hpp"

namespace sculpt::splines {

namespace detail {

FootPointSearch::FootPointSearch(const BSpline& curve, int samples_per_span)
    : curve_(&curve), a_(curve.domain().first), b_(curve.domain().second), closed_(curve.closed()) {
  const std::vector<double> b = curve.breaks();
  for (std::size_t s = 0; s + 1 < b.size(); ++s)
    for (int j = 0; j < samples_per_span; ++j) params_.push_back(b[s] + (b[s + 1] - b[s]) * j / samples_per_span);
  if (!closed_) params_.push_back(b.back());
  points_.reserve(params_.size());
  for (double t : params_) points_.push_back(curve.point(t));
  if (curve.degree() <= 3) {
    for (std::size_t s = 0; s + 1 < b.size(); ++s) {
      const auto j = curve.jet(b[s], 3);  // right derivatives: the piece of span s
      span_start_.push_back(b[s]);
      taylor_.push_back({j[0], j[1], j[2] / 2.0, j[3] / 6.0});
    }
  }
  build_chunks();
}

FootPointSearch::FootPointSearch(Evaluator evaluate, double a, double b, bool closed, int samples)
    : evaluate_(std::move(evaluate)), a_(a), b_(b), closed_(closed) {
  if (!(b > a) || samples < 2) throw InvalidInput("foot point search: empty domain or fewer than 2 samples");
  for (int j = 0; j < samples; ++j) params_.push_back(a + (b - a) * j / samples);
  if (!closed_) params_.push_back(b);
  for (double t : params_) points_.push_back(evaluate_(t)[0]);
  build_chunks();
}

void FootPointSearch::build_chunks() {
  const int m = static_cast<int>(points_.size());
  for (int c = 0; c < m; c += kChunk) {
    Eigen::Vector3d lo = points_[c], hi = points_[c];
    for (int i = c; i < std::min(m, c + kChunk); ++i) {
      lo = lo.cwiseMin(points_[i]);
      hi = hi.cwiseMax(points_[i]);
    }
    box_lo_.push_back(lo);
    box_hi_.push_back(hi);
  }
  const int chunks = static_cast<int>(box_lo_.size());
  for (int c = 0; c < chunks; c += kChunk) {
    Eigen::Vector3d lo = box_lo_[c], hi = box_hi_[c];
    for (int i = c; i < std::min(chunks, c + kChunk); ++i) {
      lo = lo.cwiseMin(box_lo_[i]);
      hi = hi.cwiseMax(box_hi_[i]);
    }
    group_lo_.push_back(lo);
    group_hi_.push_back(hi);
  }
}

std::array<Eigen::Vector3d, 3> FootPointSearch::eval(double t) const {
  if (!taylor_.empty()) {
    const int s = std::max(0, static_cast<int>(std::upper_bound(span_start_.begin(), span_start_.end(), t) -
                                               span_start_.begin()) - 1);
    const auto& c = taylor_[s];
    const double u = t - span_start_[s];
    return {((c[3] * u + c[2]) * u + c[1]) * u + c[0], (3.0 * c[3] * u + 2.0 * c[2]) * u + c[1], 6.0 * c[3] * u + 2.0 * c[2]};
  }
  if (curve_) {
    const auto j = curve_->jet(t, 2);
    return {j[0], j[1], j[2]};
  }
  return evaluate_(t);
}

double FootPointSearch::wrap(double t) const {
  if (!closed_) return std::clamp(t, a_, b_);
  if (t >= a_ && t < b_) return t;
  const double period = b_ - a_;
  double s = a_ + std::fmod(t - a_, period);
  if (s < a_) s += period;
  if (s >= b_) s = a_;
  return s;
}

FootPointJet FootPointSearch::refine(const Eigen::Vector3d& x, double t0, double lo, double hi) const {
  // Minimize g(t) = |c(t) - x|^2 / 2 on [lo, hi]: Newton on g' = (c - x) . c', falling back to
  // bisection of the bracket whenever the step leaves it or g'' <= 0.
  const double scale = std::max({1.0, std::abs(lo), std::abs(hi)});
  double t = std::clamp(t0, lo, hi);
  std::array<Eigen::Vector3d, 3> d = eval(wrap(t));
  for (int it = 0; it < 60; ++it) {
    const Eigen::Vector3d r = d[0] - x;
    const double f = r.dot(d[1]), fp = d[1].squaredNorm() + r.dot(d[2]);
    if (f > 0)
      hi = t;
    else
      lo = t;
    if (f == 0.0 || hi - lo < 1e-15 * scale) break;
    // Converged when the Newton step is below the resolution (checked before the bracket test:
    // a step that rounds to t itself must not fall back to bisection).
    if (fp > 0 && std::abs(f / fp) < 1e-15 * scale) break;
    double next = fp > 0 ? t - f / fp : 0.5 * (lo + hi);
    if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
    const bool done = std::abs(next - t) < 1e-15 * scale;
    t = next;
    d = eval(wrap(t));
    if (done) break;
  }
  FootPointJet fp;
  fp.foot.parameter = t;
  fp.foot.point = d[0];
  fp.foot.distance = (d[0] - x).norm();
  fp.d1 = d[1];
  fp.d2 = d[2];
  return fp;
}

FootPointJet FootPointSearch::global_jet(const Eigen::Vector3d& x) const {
  const int m = static_cast<int>(params_.size()), chunks = static_cast<int>(box_lo_.size());
  const bool closed = closed_;
  const double a = a_, b = b_;
  const auto d2 = [&](int i) { return (points_[i] - x).squaredNorm(); };
  const auto box_d2 = [&](int c) {
    return (box_lo_[c] - x).cwiseMax(x - box_hi_[c]).cwiseMax(0.0).squaredNorm();
  };
  // The nearest sample: chunks in any order, skipping those whose box is farther than the best so far.
  std::vector<double> lb(chunks);
  int first = 0;
  for (int c = 0; c < chunks; ++c) {
    lb[c] = box_d2(c);
    if (lb[c] < lb[first]) first = c;
  }
  double best2 = INFINITY;
  for (int pass = 0; pass < 2; ++pass)
    for (int c = pass == 0 ? first : 0; c < (pass == 0 ? first + 1 : chunks); ++c) {
      if (pass == 1 && (c == first || lb[c] >= best2)) continue;
      for (int i = c * kChunk; i < std::min(m, (c + 1) * kChunk); ++i) best2 = std::min(best2, d2(i));
    }
  // Local minima of the sampled distance within twice the nearest sample's distance (a curve
  // coming close to itself), best first; refine at most four.
  std::array<std::pair<double, int>, 4> minima;
  int count = 0;
  const double limit = 4.0 * best2 + 1e-300;
  for (int c = 0; c < chunks; ++c) {
    if (lb[c] > limit) continue;
    for (int i = c * kChunk; i < std::min(m, (c + 1) * kChunk); ++i) {
      const double di = d2(i);
      if (di > limit) continue;
      const double left = (i > 0) ? d2(i - 1) : closed ? d2(m - 1) : INFINITY;
      const double right = (i + 1 < m) ? d2(i + 1) : closed ? d2(0) : INFINITY;
      if (!(di <= left && di <= right)) continue;
      std::pair<double, int> item{di, i};
      if (count < 4) minima[count++] = item;
      else if (item < minima[3]) minima[3] = item;
      else continue;
      for (int k = count - 1; k > 0 && minima[k] < minima[k - 1]; --k) std::swap(minima[k], minima[k - 1]);
    }
  }
  FootPointJet best;
  best.foot.distance = INFINITY;
  for (int k = 0; k < count; ++k) {
    const int i = minima[k].second;
    double lo = i > 0 ? params_[i - 1] : closed ? params_[m - 1] - (b - a) : a;
    double hi = i + 1 < m ? params_[i + 1] : closed ? b : params_[i];
    if (!closed && i + 1 == m) hi = b;
    // Start Newton at the projection onto the sampled polyline next to sample i (closer than the sample).
    double t0 = params_[i], t0_d2 = minima[k].first;
    for (int side : {-1, 1}) {
      const int j = i + side;
      if (!closed && (j < 0 || j >= m)) continue;
      const int jw = (j + m) % m;
      const double tj = side < 0 ? lo : (i + 1 < m ? params_[i + 1] : b);
      const Eigen::Vector3d e = points_[jw] - points_[i];
      const double len2 = e.squaredNorm();
      if (!(len2 > 0)) continue;
      const double u = std::clamp((x - points_[i]).dot(e) / len2, 0.0, 1.0);
      const double du2 = (points_[i] + u * e - x).squaredNorm();
      if (du2 < t0_d2) {
        t0_d2 = du2;
        t0 = params_[i] + u * (tj - params_[i]);
      }
    }
    const FootPointJet f = refine(x, t0, lo, hi);
    if (f.foot.distance < best.foot.distance) best = f;
    if (!closed) {  // an end point may be the minimum (the bracket is one-sided there)
      for (double e : {a, b}) {
        if ((e == a && i <= 1) || (e == b && i >= m - 2)) {
          const auto pe = eval(e);
          const double de = (pe[0] - x).norm();
          if (de < best.foot.distance) best = {{e, pe[0], de}, pe[1], pe[2]};
        }
      }
    }
  }
  best.foot.parameter = wrap(best.foot.parameter);
  return best;
}

FootPointJet FootPointSearch::warm_jet(const Eigen::Vector3d& x, double t0) const {
  const int m = static_cast<int>(params_.size());
  if (!std::isfinite(t0)) return global_jet(x);
  t0 = wrap(t0);
  const int i = std::clamp(static_cast<int>(std::upper_bound(params_.begin(), params_.end(), t0) - params_.begin()) - 1, 0, m - 1);
  // Bracket: from the sample before i to the second sample after it (periodic parameters unrolled).
  const double period = b_ - a_;
  const auto param = [&](int j) {
    if (j < 0) return closed_ ? params_[j + m] - period : a_;
    if (j >= m) return closed_ ? params_[j - m] + period : b_;
    return params_[j];
  };
  const double lo = param(i - 1), hi = param(i + 2);
  const FootPointJet f = refine(x, t0, lo, hi);
  const double t = f.foot.parameter;
  // Only an interior stationary point counts (Newton may end on the bracket's edge).
  const double margin = 1e-9 * (hi - lo);
  const Eigen::Vector3d r = f.foot.point - x;
  if (!(t > lo + margin && t < hi - margin) || (!closed_ && (t <= a_ || t >= b_)) ||
      !(std::abs(r.dot(f.d1)) <= 1e-8 * r.norm() * f.d1.norm()))
    return global_jet(x);
  // Global check, the rule of global_jet: no sample closer than the foot point found, and none
  // outside the bracket within twice its distance (another branch global_jet would refine too).
  const double d2 = f.foot.distance * f.foot.distance * (1 - 1e-12), far2 = 4.0 * d2;
  const int chunks = static_cast<int>(box_lo_.size());
  for (int c = 0; c < chunks; ++c) {
    if (c % kChunk == 0 && (group_lo_[c / kChunk] - x).cwiseMax(x - group_hi_[c / kChunk]).cwiseMax(0.0).squaredNorm() >= far2) {
      c += kChunk - 1;  // the whole group of chunks is too far
      continue;
    }
    if ((box_lo_[c] - x).cwiseMax(x - box_hi_[c]).cwiseMax(0.0).squaredNorm() >= far2) continue;
    for (int j = static_cast<int>(c) * kChunk; j < std::min(m, static_cast<int>(c + 1) * kChunk); ++j) {
      const double dj = (points_[j] - x).squaredNorm();
      const int offset = closed_ ? ((j - i) % m + m + 1) % m - 1 : j - i;  // in [-1, m - 2] when closed
      const bool inside = offset >= -1 && offset <= 2;
      if (dj < d2 || (!inside && dj < far2)) return global_jet(x);
    }
  }
  FootPointJet out = f;
  out.foot.parameter = wrap(t);
  return out;
}

FootPoint FootPointSearch::local(const Eigen::Vector3d& x, double t0, double radius) const {
  double lo = t0 - radius, hi = t0 + radius;
  if (!closed_) {
    lo = std::max(lo, a_);
    hi = std::min(hi, b_);
  }
  FootPoint f = refine(x, t0, lo, hi).foot;
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
