#include "splines/detail/surface_foot_point_search.hpp"

#include <Eigen/Cholesky>
#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

namespace sculpt::splines::detail {

namespace {
double box_distance2(const Eigen::Vector3d& x, const Eigen::Vector3d& lo, const Eigen::Vector3d& hi) {
  return (lo - x).cwiseMax(x - hi).cwiseMax(0.0).squaredNorm();
}
}  // namespace

SurfaceFootPointSearch::SurfaceFootPointSearch(const BSplineSurface& surface, int samples_per_span)
    : surface_(&surface), k_(std::clamp(samples_per_span, 1, kMaxSamplesPerSpan)) {
  const std::vector<double> bu = surface.breaks(0), bv = surface.breaks(1);
  const int m = surface.count(1);
  for (std::size_t i = 0; i + 1 < bu.size(); ++i)
    for (std::size_t j = 0; j + 1 < bv.size(); ++j) {
      Span s{bu[i], bu[i + 1], bv[j], bv[j + 1], Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero(),
             static_cast<int>(samples_.size())};
      // The controls whose basis functions are nonzero inside the span (those at its midpoint).
      const BasisJet nu = surface.basis(0).basis_jet(0.5 * (s.u0 + s.u1), 0), nv = surface.basis(1).basis_jet(0.5 * (s.v0 + s.v1), 0);
      s.lo = s.hi = surface.controls()[static_cast<std::size_t>(nu.index[0]) * m + nv.index[0]];
      for (int a = 0; a < nu.count; ++a)
        for (int b = 0; b < nv.count; ++b) {
          const Eigen::Vector3d& P = surface.controls()[static_cast<std::size_t>(nu.index[a]) * m + nv.index[b]];
          s.lo = s.lo.cwiseMin(P);
          s.hi = s.hi.cwiseMax(P);
        }
      for (int a = 0; a <= k_; ++a)
        for (int b = 0; b <= k_; ++b) {
          const double u = s.u0 + (s.u1 - s.u0) * a / k_, v = s.v0 + (s.v1 - s.v0) * b / k_;
          sample_uv_.emplace_back(u, v);
          samples_.push_back(surface.point(u, v));
        }
      for (int a = 0; a < k_; ++a)
        for (int b = 0; b < k_; ++b) {
          const int i00 = s.first_sample + a * (k_ + 1) + b;
          s.reach = std::max({s.reach, (samples_[i00] - samples_[i00 + k_ + 2]).norm(),
                              (samples_[i00 + 1] - samples_[i00 + k_ + 1]).norm()});
        }
      spans_.push_back(s);
    }
}

SurfaceFootJet SurfaceFootPointSearch::newton(const Eigen::Vector3d& x, double u, double v, double u0, double u1, double v0,
                                              double v1, bool wrap) const {
  const bool wrap_dir[2] = {wrap && surface_->closed(0), wrap && surface_->closed(1)};
  const double lo[2] = {u0, v0}, hi[2] = {u1, v1};
  const auto place = [&](double t, int d) {
    if (wrap_dir[d]) {
      const double period = hi[d] - lo[d];
      double s = lo[d] + std::fmod(t - lo[d], period);
      if (s < lo[d]) s += period;
      return s >= hi[d] ? lo[d] : s;
    }
    return std::clamp(t, lo[d], hi[d]);
  };
  double p[2] = {place(u, 0), place(v, 1)};
  SurfaceJet J = surface_->jet(p[0], p[1], 2);
  double f = (J.point - x).squaredNorm();
  for (int iteration = 0; iteration < 50; ++iteration) {
    const Eigen::Vector3d r = J.point - x;
    const Eigen::Vector2d g(r.dot(J.du), r.dot(J.dv));
    Eigen::Matrix2d H;
    H << J.du.dot(J.du) + r.dot(J.duu), J.du.dot(J.dv) + r.dot(J.duv), J.du.dot(J.dv) + r.dot(J.duv), J.dv.dot(J.dv) + r.dot(J.dvv);
    if (!(H(0, 0) > 0 && H.determinant() > 0))  // not convex here: Gauss-Newton's model instead
      H << J.du.dot(J.du), J.du.dot(J.dv), J.du.dot(J.dv), J.dv.dot(J.dv);
    H.diagonal().array() += 1e-14 * H.trace() + 1e-300;
    // Projected Newton: a coordinate at a bound whose gradient pushes outwards stays there.
    bool free[2];
    for (int d = 0; d < 2; ++d) free[d] = wrap_dir[d] || !((p[d] <= lo[d] && g[d] > 0) || (p[d] >= hi[d] && g[d] < 0));
    Eigen::Vector2d step = Eigen::Vector2d::Zero();
    if (free[0] && free[1])
      step = -H.ldlt().solve(g);
    else if (free[0])
      step[0] = -g[0] / H(0, 0);
    else if (free[1])
      step[1] = -g[1] / H(1, 1);
    if (!step.allFinite() || step.isZero(0.0)) break;
    double t = 1.0;
    bool accepted = false;
    double q[2] = {p[0], p[1]};
    SurfaceJet trial;
    for (int halving = 0; halving < 40; ++halving, t *= 0.5) {
      q[0] = place(p[0] + t * step[0], 0);
      q[1] = place(p[1] + t * step[1], 1);
      // The full step is usually taken: evaluate its derivatives at once (the next iteration's).
      trial = halving == 0 ? surface_->jet(q[0], q[1], 2) : SurfaceJet{surface_->point(q[0], q[1])};
      const double fq = (trial.point - x).squaredNorm();
      if (fq <= f) {
        accepted = true;
        f = fq;
        break;
      }
    }
    if (!accepted) break;
    const double moved = std::max(std::abs(q[0] - p[0]) / std::max(hi[0] - lo[0], 1e-300),
                                  std::abs(q[1] - p[1]) / std::max(hi[1] - lo[1], 1e-300));
    const bool full = t == 1.0;
    p[0] = q[0];
    p[1] = q[1];
    J = full ? trial : surface_->jet(p[0], p[1], 2);
    if (moved < 1e-12) break;  // quadratic convergence: the next step would be below rounding
  }
  return {{p[0], p[1], J.point, (J.point - x).norm()}, J};
}

SurfaceFootJet SurfaceFootPointSearch::search_span(const Eigen::Vector3d& x, const Span& s) const {
  // Newton from every local minimum of the distance over the span's sample grid (usually one).
  const int w = k_ + 1;
  double d2[(kMaxSamplesPerSpan + 1) * (kMaxSamplesPerSpan + 1)];
  for (int i = 0; i < w * w; ++i) d2[i] = (samples_[s.first_sample + i] - x).squaredNorm();
  SurfaceFootJet best;
  best.foot.distance = std::numeric_limits<double>::infinity();
  for (int a = 0; a < w; ++a)
    for (int b = 0; b < w; ++b) {
      const double v = d2[a * w + b];
      bool minimum = true;
      // Against the 4 edge neighbours (not the diagonal ones: a fold can hide a valley between them).
      const int steps[4][2] = {{-1, 0}, {1, 0}, {0, -1}, {0, 1}};
      for (const auto& st : steps) {
        const int a2 = a + st[0], b2 = b + st[1];
        if (a2 >= 0 && a2 < w && b2 >= 0 && b2 < w && d2[a2 * w + b2] < v) minimum = false;
      }
      if (!minimum) continue;
      const Eigen::Vector2d& uv = sample_uv_[s.first_sample + a * w + b];
      SurfaceFootJet c = newton(x, uv[0], uv[1], s.u0, s.u1, s.v0, s.v1, false);
      if (c.foot.distance < best.foot.distance) best = c;
    }
  return best;
}

SurfaceFootJet SurfaceFootPointSearch::global(const Eigen::Vector3d& x) const {
  std::vector<std::pair<double, int>> order(spans_.size());
  for (std::size_t i = 0; i < spans_.size(); ++i) order[i] = {box_distance2(x, spans_[i].lo, spans_[i].hi), static_cast<int>(i)};
  std::sort(order.begin(), order.end());
  SurfaceFootJet best;
  best.foot.distance = std::numeric_limits<double>::infinity();
  for (const auto& [lb, i] : order) {
    if (lb >= best.foot.distance * best.foot.distance) break;  // this box, and all after it, are farther
    SurfaceFootJet c = search_span(x, spans_[i]);
    if (c.foot.distance < best.foot.distance) best = c;
  }
  return best;
}

SurfaceFootJet SurfaceFootPointSearch::warm(const Eigen::Vector3d& x, double u0, double v0) const {
  const auto [a0, a1] = surface_->domain(0);
  const auto [b0, b1] = surface_->domain(1);
  SurfaceFootJet best = newton(x, u0, v0, a0, a1, b0, b1, true);
  const int count = (k_ + 1) * (k_ + 1);
  const double u_found = best.foot.u, v_found = best.foot.v;
  for (const Span& s : spans_) {
    const double d = best.foot.distance;
    if (box_distance2(x, s.lo, s.hi) >= d * d) continue;
    double ds2 = std::numeric_limits<double>::infinity();
    for (int i = s.first_sample; i < s.first_sample + count; ++i) ds2 = std::min(ds2, (samples_[i] - x).squaredNorm());
    const double ds = std::sqrt(ds2);
    if (ds - 0.5 * s.reach >= d) continue;  // no point of the span is closer
    // The span of the Newton result itself needs another look only if a sample beats it.
    const bool home = u_found >= s.u0 && u_found <= s.u1 && v_found >= s.v0 && v_found <= s.v1;
    if (home && ds >= d * (1.0 - 1e-12)) continue;
    SurfaceFootJet c = search_span(x, s);
    if (c.foot.distance < best.foot.distance) best = c;
  }
  return best;
}

SurfaceFootJet SurfaceFootPointSearch::along_edge(const Eigen::Vector3d& x, int direction, double at, double t0) const {
  const auto [a0, a1] = surface_->domain(0);
  const auto [b0, b1] = surface_->domain(1);
  // Sampled start along the edge (a closer sample than t0 wins), then Newton with the other parameter pinned.
  const auto [c0, c1] = direction == 0 ? std::pair{b0, b1} : std::pair{a0, a1};
  const auto at_t = [&](double t) { return direction == 0 ? surface_->point(at, t) : surface_->point(t, at); };
  double best_t = t0, best = (at_t(t0) - x).squaredNorm();
  const int n = 4 * static_cast<int>(surface_->breaks(1 - direction).size());
  for (int i = 0; i <= n; ++i) {
    const double t = c0 + (c1 - c0) * i / n, d = (at_t(t) - x).squaredNorm();
    if (d < best) {
      best = d;
      best_t = t;
    }
  }
  return direction == 0 ? newton(x, at, best_t, at, at, b0, b1, true) : newton(x, best_t, at, a0, a1, at, at, true);
}

}  // namespace sculpt::splines::detail
