#include "splines/offset.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <numeric>
#include <optional>
#include <string>

#include "base/errors.hpp"
#include "splines/approximate.hpp"
#include "splines/detail/foot_point_search.hpp"
#include "splines/detail/normal_equations.hpp"
#include "splines/foot_point.hpp"

namespace sculpt::splines {

namespace {

using V = Eigen::Vector3d;
using Derivs = std::array<V, 3>;

double cross2(const V& u, const V& w) { return u.x() * w.y() - u.y() * w.x(); }

// The exact offset o = c + d n (n the right normal) and its first two derivatives:
// o' = c' (1 + d k), o'' = c'' (1 + d k) + c' d k' with k the signed curvature.
Derivs raw_offset(const BSpline& c, double d, double t) {
  const auto e = c.derivatives(t, 3);
  const double s2 = e[1].squaredNorm();
  if (!(s2 > 1e-300)) return {e[0], e[1], e[2]};
  const double s = std::sqrt(s2), s3 = s2 * s;
  const double k = cross2(e[1], e[2]) / s3;
  const double dk = cross2(e[1], e[3]) / s3 - 3.0 * cross2(e[1], e[2]) * e[1].dot(e[2]) / (s3 * s2);
  const V n(e[1].y() / s, -e[1].x() / s, 0.0);
  return {e[0] + d * n, e[1] * (1.0 + d * k), e[2] * (1.0 + d * k) + e[1] * (d * dk)};
}

// A self-intersection of the raw offset: parameters t1 < t2 (unrolled) meeting at `point`.
struct Crossing {
  double t1 = 0.0, t2 = 0.0;
  V point = V::Zero();
};

// A piece of the raw offset between consecutive cuts; nodes are crossing indices, -1 an open end.
struct Piece {
  double t0 = 0.0, t1 = 0.0;
  int from = -1, to = -1;
  bool valid = false;
};

// Newton on o(t1) = o(t2) from the polyline crossing (a 2x2 system); keeps the start if it fails.
Crossing refine_crossing(const BSpline& c, double d, double t1, double t2, double h) {
  Crossing x{t1, t2, raw_offset(c, d, t1)[0]};
  double a = t1, b = t2;
  for (int it = 0; it < 20; ++it) {
    const Derivs p = raw_offset(c, d, a), q = raw_offset(c, d, b);
    const V r = p[0] - q[0];
    if (r.norm() < 1e-14) break;
    // Solve [o'(a), -o'(b)] (da, db) = -r by Cramer's rule.
    const double det = cross2(p[1], -q[1]);
    if (!(std::abs(det) > 1e-300)) return x;
    a += cross2(-r, -q[1]) / det;
    b += cross2(p[1], -r) / det;
    if (!(std::abs(a - t1) < 2 * h && std::abs(b - t2) < 2 * h)) return x;
  }
  x.t1 = a;
  x.t2 = b;
  x.point = raw_offset(c, d, a)[0];
  return x;
}

// Self-intersections of the polyline through the samples (closed: cyclic), by a sweep over x.
std::vector<Crossing> self_intersections(const BSpline& c, double d, const std::vector<double>& t,
                                         const std::vector<V>& p, bool closed, double period) {
  const int K = static_cast<int>(p.size()), segs = closed ? K : K - 1;
  const auto end = [&](int i) { return (i + 1) % K; };
  const auto t_end = [&](int i) { return i + 1 < K ? t[i + 1] : t[0] + period; };
  std::vector<int> order(segs);
  std::iota(order.begin(), order.end(), 0);
  const auto lo_x = [&](int i) { return std::min(p[i].x(), p[end(i)].x()); };
  std::sort(order.begin(), order.end(), [&](int i, int j) { return lo_x(i) < lo_x(j); });
  double h = 0.0;
  for (int i = 0; i < segs; ++i) h = std::max(h, t_end(i) - t[i]);
  std::vector<Crossing> out;
  for (int oi = 0; oi < segs; ++oi) {
    const int i = order[oi];
    const V &a0 = p[i], &a1 = p[end(i)];
    const double hi_x = std::max(a0.x(), a1.x());
    for (int oj = oi + 1; oj < segs && lo_x(order[oj]) <= hi_x; ++oj) {
      const int j = order[oj];
      if (std::abs(i - j) <= 1 || (closed && std::abs(i - j) == segs - 1)) continue;
      const V &b0 = p[j], &b1 = p[end(j)];
      if (std::max(b0.y(), b1.y()) < std::min(a0.y(), a1.y()) || std::max(a0.y(), a1.y()) < std::min(b0.y(), b1.y()))
        continue;
      const V u = a1 - a0, w = b1 - b0, r = b0 - a0;
      const double den = cross2(u, w);
      if (den == 0.0) continue;
      const double alpha = cross2(r, w) / den, beta = cross2(r, u) / den;
      if (!(alpha >= 0 && alpha < 1 && beta >= 0 && beta < 1)) continue;
      const int first = std::min(i, j), second = std::max(i, j);
      const double fa = first == i ? alpha : beta, fb = first == i ? beta : alpha;
      out.push_back(refine_crossing(c, d, t[first] + fa * (t_end(first) - t[first]),
                                    t[second] + fb * (t_end(second) - t[second]), h));
    }
  }
  return out;
}

// The trimmed offset as pieces of the raw one in order along it; corners between consecutive
// pieces (for a closed curve also between the last and the first when there are several).
struct Trimmed {
  std::vector<Piece> pieces;
  std::vector<V> corners;  // corners[k] joins pieces[k] and pieces[k + 1] (cyclic when closed)
};

Trimmed trim(const BSpline& c, double d, int samples) {
  const auto [a, b] = c.domain();
  const bool closed = c.closed();
  const double period = b - a;
  std::vector<double> t;
  const std::vector<double> br = c.breaks();
  const int per_span = std::max(64, (samples + static_cast<int>(br.size()) - 2) / static_cast<int>(br.size() - 1));
  for (std::size_t s = 0; s + 1 < br.size(); ++s)
    for (int j = 0; j < per_span; ++j) t.push_back(br[s] + (br[s + 1] - br[s]) * j / per_span);
  if (!closed) t.push_back(b);
  std::vector<V> p(t.size());
  for (std::size_t i = 0; i < t.size(); ++i) p[i] = raw_offset(c, d, t[i])[0];
  const std::vector<Crossing> crossings = d == 0.0 ? std::vector<Crossing>{} : self_intersections(c, d, t, p, closed, period);

  // Cuts along the parameter; each crossing cuts twice.
  struct Cut {
    double t;
    int node;
  };
  std::vector<Cut> cuts;
  for (std::size_t k = 0; k < crossings.size(); ++k) {
    cuts.push_back({crossings[k].t1, static_cast<int>(k)});
    cuts.push_back({crossings[k].t2, static_cast<int>(k)});
  }
  if (closed)
    for (Cut& cut : cuts) cut.t = a + std::fmod(std::fmod(cut.t - a, period) + period, period);
  std::sort(cuts.begin(), cuts.end(), [](const Cut& x, const Cut& y) { return x.t < y.t; });
  std::vector<Piece> pieces;
  if (cuts.empty()) {
    pieces.push_back({a, b, -1, -1, false});
  } else if (closed) {
    for (std::size_t k = 0; k < cuts.size(); ++k) {
      const Cut& next = cuts[(k + 1) % cuts.size()];
      pieces.push_back({cuts[k].t, k + 1 < cuts.size() ? next.t : next.t + period, cuts[k].node, next.node, false});
    }
  } else {
    pieces.push_back({a, cuts.front().t, -1, cuts.front().node, false});
    for (std::size_t k = 0; k + 1 < cuts.size(); ++k) pieces.push_back({cuts[k].t, cuts[k + 1].t, cuts[k].node, cuts[k + 1].node, false});
    pieces.push_back({cuts.back().t, b, cuts.back().node, -1, false});
  }
  // A piece is part of the offset iff its points are |d| from c (the others are closer).
  const detail::FootPointSearch on_curve(c, 16);
  const double slack = 1e-7 * std::max(1.0, std::abs(d));
  for (Piece& piece : pieces) {
    if (!(piece.t1 > piece.t0)) continue;
    const V mid = raw_offset(c, d, 0.5 * (piece.t0 + piece.t1))[0];
    piece.valid = on_curve.global(mid).distance >= std::abs(d) - slack;
  }
  std::vector<int> valid;
  for (std::size_t k = 0; k < pieces.size(); ++k)
    if (pieces[k].valid) valid.push_back(static_cast<int>(k));
  if (valid.empty())
    throw GeometryError("offset: nothing is left of the offset at distance " + std::to_string(d) +
                        " (it lies closer than |d| to the curve everywhere: the offset vanishes)");
  // Follow the valid pieces from crossing to crossing; they must form one loop (closed) or one chain (open).
  const int nodes = static_cast<int>(crossings.size());
  std::vector<int> in(nodes, 0), out(nodes, 0), leaving(nodes, -1);
  for (int k : valid) {
    if (pieces[k].to >= 0) ++in[pieces[k].to];
    if (pieces[k].from >= 0) {
      ++out[pieces[k].from];
      leaving[pieces[k].from] = k;
    }
  }
  for (int v = 0; v < nodes; ++v)
    if (in[v] > 1 || out[v] > 1 || in[v] != out[v])
      throw GeometryError("offset: the offset at distance " + std::to_string(d) + " changes topology near (" +
                          std::to_string(crossings[v].point.x()) + ", " + std::to_string(crossings[v].point.y()) +
                          "): it would split into several parts");
  int head = valid.front();
  if (!closed) {
    head = -1;
    for (int k : valid)
      if (pieces[k].from < 0) head = k;
    if (head < 0) throw GeometryError("offset: the offset of the open curve has no start (it changes topology)");
  }
  Trimmed result;
  std::vector<char> seen(pieces.size(), 0);
  for (int k = head; k >= 0 && !seen[k];) {
    seen[k] = 1;
    result.pieces.push_back(pieces[k]);
    if (pieces[k].to < 0) break;
    result.corners.push_back(crossings[pieces[k].to].point);
    k = leaving[pieces[k].to];
  }
  if (result.pieces.size() != valid.size())
    throw GeometryError("offset: the offset at distance " + std::to_string(d) + " falls into several loops");
  // Make the pieces' parameters increase along the chain.
  for (std::size_t k = 1; k < result.pieces.size(); ++k)
    while (result.pieces[k].t0 < result.pieces[k - 1].t1 - 0.5 * period) {
      result.pieces[k].t0 += period;
      result.pieces[k].t1 += period;
    }
  if (!closed && result.corners.size() == result.pieces.size()) result.corners.pop_back();
  return result;
}

// The trimmed offset as one curve: segments (parameter ranges of the raw offset) laid end to end.
struct Target {
  std::vector<double> t0, t1, start;  // segment k covers target parameters [start[k], start[k + 1]]
  std::vector<double> length;         // arc length of each segment
  std::vector<V> corners;             // corners[k] joins segments k and k + 1
  bool closed = false;
  [[nodiscard]] double total() const { return start.back(); }
  [[nodiscard]] std::pair<int, double> locate(double u) const {
    const int k = std::clamp(static_cast<int>(std::upper_bound(start.begin(), start.end(), u) - start.begin()) - 1, 0,
                             static_cast<int>(t0.size()) - 1);
    return {k, t0[k] + (u - start[k])};
  }
};

Target target_of(const BSpline& c, double d, const Trimmed& trimmed) {
  Target tg;
  tg.closed = c.closed();
  tg.corners = trimmed.corners;
  std::vector<std::pair<double, double>> segs;
  for (const Piece& p : trimmed.pieces) segs.emplace_back(p.t0, p.t1);
  if (tg.closed && !trimmed.corners.empty()) {  // start mid-piece so that the seam is smooth
    const double mid = 0.5 * (segs[0].first + segs[0].second);
    const double period = c.domain().second - c.domain().first;
    const std::pair<double, double> first_half{segs[0].first + period, mid + period};
    segs[0].first = mid;
    segs.push_back(first_half);
  }
  tg.start.push_back(0.0);
  for (const auto& [a, b] : segs) {
    tg.t0.push_back(a);
    tg.t1.push_back(b);
    tg.start.push_back(tg.start.back() + (b - a));
    double len = 0.0;
    V prev = raw_offset(c, d, a)[0];
    for (int j = 1; j <= 256; ++j) {
      const V q = raw_offset(c, d, a + (b - a) * j / 256)[0];
      len += (q - prev).norm();
      prev = q;
    }
    tg.length.push_back(len);
  }
  return tg;
}

// Knots by arc length: `spans` nonzero spans shared by the segments (at least one each), and a
// knot of multiplicity p at every junction between segments (the corners).
struct Layout {
  std::vector<double> knots;
  std::vector<double> corner_at;  // active parameters of the corners
  std::vector<double> seg_start;  // active parameter where each segment starts (and the end)
};

Layout layout(const Target& tg, int n, int p) {
  const int q = static_cast<int>(tg.length.size()), corners = q - 1;
  const int spans = tg.closed ? n - corners * (p - 1) : n - p - corners * (p - 1);
  const double total = std::accumulate(tg.length.begin(), tg.length.end(), 0.0);
  std::vector<int> k(q, 1);
  int left = spans - q;
  std::vector<double> share(q);
  for (int s = 0; s < q; ++s) share[s] = tg.length[s] / total * spans;
  while (left > 0) {  // give the next span to the segment furthest below its share
    int best = 0;
    for (int s = 1; s < q; ++s)
      if (share[s] - k[s] > share[best] - k[best]) best = s;
    ++k[best];
    --left;
  }
  Layout L;
  std::vector<double> interior;
  double pos = 0.0;
  L.seg_start.push_back(0.0);
  for (int s = 0; s < q; ++s) {
    for (int j = 1; j < k[s]; ++j) interior.push_back(pos + tg.length[s] * j / k[s]);
    pos += tg.length[s];
    L.seg_start.push_back(pos);
    if (s + 1 < q) {
      L.corner_at.push_back(pos);
      for (int m = 0; m < p; ++m) interior.push_back(pos);
    }
  }
  std::sort(interior.begin(), interior.end());
  if (tg.closed) {
    L.knots.push_back(0.0);
    L.knots.insert(L.knots.end(), interior.begin(), interior.end());
    L.knots.push_back(pos);
  } else {
    L.knots.assign(p + 1, 0.0);
    L.knots.insert(L.knots.end(), interior.begin(), interior.end());
    L.knots.insert(L.knots.end(), p + 1, pos);
  }
  return L;
}

struct Attempt {
  std::optional<FitResult> fit;
  double error = 0.0;
  std::vector<double> corner_at;
};

Attempt fit_offset(const BSpline& c, double d, const Target& tg, const TargetCurve& target, int n,
                   const OffsetOptions& options) {
  const int p = options.degree;
  const Layout L = layout(tg, n, p);
  // Start: least squares to target samples at their arc-length parameters.
  std::vector<V> zero(n, V::Zero());
  BSpline shape(p, L.knots, zero, tg.closed, 2);
  detail::NormalEquations system(n, p, 2, tg.closed);
  for (std::size_t s = 0; s < tg.length.size(); ++s) {
    const double total = std::accumulate(tg.length.begin(), tg.length.end(), 0.0);
    const int m = 32 + static_cast<int>(8.0 * n * tg.length[s] / total);
    double along = 0.0;
    V prev = raw_offset(c, d, tg.t0[s])[0];
    for (int j = 0; j <= m; ++j) {
      const V x = raw_offset(c, d, tg.t0[s] + (tg.t1[s] - tg.t0[s]) * j / m)[0];
      along += (x - prev).norm();
      prev = x;
      const double u = std::min(L.seg_start[s] + along, L.seg_start[s + 1]);
      const Basis b = shape.basis(u, 0);
      system.add_term(b.index, b.value.row(0).transpose(), Eigen::Matrix3d::Identity(), x);
    }
  }
  system.add_smoothing(1e-8);
  std::vector<V> controls = system.solve(zero, {});
  for (V& v : controls) v.z() = 0.0;
  // Pin the ends of an open offset and the corners (control points the curve passes through).
  std::vector<int> fixed;
  const auto pin = [&](double u, const V& x) {
    const Basis b = shape.basis(u, 0);
    for (int j = 0; j <= p; ++j)
      if (b.value(0, j) > 1 - 1e-12) {
        controls[b.index[j]] = x;
        fixed.push_back(b.index[j]);
      }
  };
  for (std::size_t k = 0; k < L.corner_at.size(); ++k) pin(L.corner_at[k], tg.corners[k]);
  if (!tg.closed) {
    pin(0.0, raw_offset(c, d, tg.t0.front())[0]);
    pin(L.seg_start.back(), raw_offset(c, d, tg.t1.back())[0]);
  }
  const BSpline start = shape.with_controls(controls);
  Attempt a;
  a.fit = approximate(target, start, {.iterations = options.iterations, .smoothing = 1e-6, .tolerance = 1e-7, .fixed = fixed});
  a.corner_at = L.corner_at;
  // Two-sided error against the exact target.
  const detail::FootPointSearch on_target(target.evaluate, target.t0, target.t1, target.closed, target.samples);
  for (const V& x : sample(a.fit->curve, 2000)) a.error = std::max(a.error, on_target.global(x).distance);
  const detail::FootPointSearch on_fit(a.fit->curve);
  for (int j = 0; j <= 2000; ++j)
    a.error = std::max(a.error, on_fit.global(target.evaluate(target.t0 + (target.t1 - target.t0) * j / 2000)[0]).distance);
  return a;
}

}  // namespace

OffsetResult offset_curve(const BSpline& curve, double d, const OffsetOptions& options) {
  if (curve.dimension() != 2) throw InvalidInput("offset: the curve must be planar (dimension 2)");
  if (!std::isfinite(d)) throw InvalidInput("offset: the distance is not finite");
  if (options.degree < 1) throw InvalidInput("offset: degree must be at least 1");
  if (options.controls < 0 || options.max_controls < 1 || options.iterations < 0 || !(options.tolerance > 0) ||
      options.samples < 0)
    throw InvalidInput("offset: controls >= 0, max_controls >= 1, iterations >= 0, tolerance > 0, samples >= 0");
  const int spans = static_cast<int>(curve.breaks().size()) - 1;
  const int samples = options.samples > 0 ? std::max(options.samples, 64) : std::max(2048, 64 * spans);
  const Trimmed trimmed = trim(curve, d, samples);
  const Target tg = target_of(curve, d, trimmed);
  const TargetCurve target{.evaluate = [&curve, d, &tg](double u) {
                             const auto [k, t] = tg.locate(u);
                             (void)k;
                             return raw_offset(curve, d, t);
                           },
                           .t0 = 0.0,
                           .t1 = tg.total(),
                           .closed = tg.closed,
                           .samples = samples};
  const int p = options.degree, q = static_cast<int>(tg.length.size()), corners = q - 1;
  const int least = q + corners * (p - 1) + (tg.closed ? 0 : p);       // one span per segment
  const int comfortable = std::max(2 * q + corners * (p - 1) + (tg.closed ? 0 : p), 2 * p + 2);
  if (options.controls > 0 && options.controls < std::max(least, p + 1))
    throw InvalidInput("offset: " + std::to_string(options.controls) + " control points are too few for " +
                       std::to_string(corners) + " corners of degree " + std::to_string(p) + " (need at least " +
                       std::to_string(std::max(least, p + 1)) + ")");
  Attempt best;
  bool have = false;
  if (options.controls > 0) {
    best = fit_offset(curve, d, tg, target, options.controls, options);
    have = true;
  } else {
    for (int n = std::max(comfortable, 8);; n = std::max(n + 1, n * 5 / 4)) {
      n = std::min(n, std::max(options.max_controls, comfortable));
      Attempt a = fit_offset(curve, d, tg, target, n, options);
      if (!have || a.error < best.error) {
        best = std::move(a);
        have = true;
      }
      if (best.error <= options.tolerance || n >= options.max_controls) break;
    }
  }
  OffsetResult r{best.fit->curve, best.fit->history, best.error, {}};
  for (std::size_t k = 0; k < best.corner_at.size(); ++k) r.corners.push_back({tg.corners[k], best.corner_at[k]});
  return r;
}

}  // namespace sculpt::splines
