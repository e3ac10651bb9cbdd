// Edge splits towards f = 0 (refine.hpp).
#include "implicit/detail/refine.hpp"
#include "base/cancel.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>

#include <Eigen/Geometry>

namespace sculpt::implicit::detail {
namespace {

using Vec = Eigen::Vector3d;

std::uint64_t directed(int a, int b) { return (std::uint64_t(std::uint32_t(a)) << 32) | std::uint32_t(b); }

class Refiner {
 public:
  Refiner(PolygonMesh& m, std::vector<bool>& locked, const Expression& f, const RefineOptions& o)
      : m_(m), locked_(locked), f_(f), o_(o) {
    faces_.reserve(m.faces.size() * 2);
    for (const auto& face : m.faces) faces_.push_back({face[0], face[1], face[2]});
    // twins of the half-edges 3 t + k (f[k] -> f[k + 1]): sorted by their undirected edge
    std::vector<std::pair<std::uint64_t, int>> keyed;
    keyed.reserve(3 * faces_.size());
    for (int t = 0; t < int(faces_.size()); ++t)
      for (int k = 0; k < 3; ++k) {
        const int a = faces_[std::size_t(t)][k], b = faces_[std::size_t(t)][(k + 1) % 3];
        keyed.push_back({directed(std::min(a, b), std::max(a, b)), 3 * t + k});
      }
    std::sort(keyed.begin(), keyed.end());
    twin_.assign(keyed.size(), -1);
    for (std::size_t i = 0; i + 1 < keyed.size(); ++i) {
      if (keyed[i].first != keyed[i + 1].first) continue;
      if (i + 2 < keyed.size() && keyed[i + 2].first == keyed[i].first) {
        closed_ = false;  // an edge in more than two triangles: not a 2-manifold
        continue;
      }
      twin_[std::size_t(keyed[i].second)] = keyed[i + 1].second;
      twin_[std::size_t(keyed[i + 1].second)] = keyed[i].second;
      ++i;
    }
    for (int h : twin_) closed_ = closed_ && h >= 0;
    edge_distance_.assign(twin_.size(), -1.0);
    verified_.assign(faces_.size(), 0);
  }

  RefineResult run() {
    RefineResult r;
    if (!closed_) return r;
    std::vector<int> stack(faces_.size());
    for (int t = 0; t < int(faces_.size()); ++t) stack[std::size_t(t)] = int(faces_.size()) - 1 - t;
    CancelPoll poll;
    while (!stack.empty()) {
      poll.tick();  // Ctrl-C (base/cancel.hpp)
      const int t = stack.back();
      stack.pop_back();
      if (within(t, o_.tolerance)) {
        verified_[std::size_t(t)] = 1;
        continue;
      }
      // the longest edge, unless a corner is on the box or the edge is at the size floor; if
      // that split cannot be made, the next longer edge
      if (has_locked(t)) continue;
      std::array<std::pair<double, int>, 3> edges{};
      for (int k = 0; k < 3; ++k) {
        const auto& ft = faces_[std::size_t(t)];
        edges[std::size_t(k)] = {(m_.vertices[std::size_t(ft[(k + 1) % 3])] - m_.vertices[std::size_t(ft[k])]).norm(), k};
      }
      std::sort(edges.begin(), edges.end(), [](const auto& x, const auto& y) { return x.first > y.first; });
      for (const auto& [length, e] : edges) {
        if (length < o_.min_edge) break;
        const int n = twin_[std::size_t(3 * t + e)] / 3;
        if (has_locked(n)) continue;
        if (++r.splits > o_.max_splits) return r;
        int added = -1;
        if (!split(t, e, added)) {
          --r.splits;
          continue;
        }
        for (int s : {t, n, added, added + 1}) stack.push_back(s);
        break;
      }
      // a triangle no split could be made for stays as it is, judged against the limit below
    }
    // a triangle found within tolerance (<= limit) since its last change needs no second look
    for (int t = 0; t < int(faces_.size()); ++t) {
      if (!verified_[std::size_t(t)] && !has_locked(t) && !within(t, o_.limit)) return r;
    }
    m_.faces.clear();
    m_.faces.reserve(faces_.size());
    for (const auto& f : faces_) m_.faces.push_back({f[0], f[1], f[2]});
    r.ok = true;
    return r;
  }

 private:
  /// First-order distance of p from f = 0; infinite where it cannot be told.
  double distance(const Vec& p) const {
    try {
      const ValueGradient vg = f_.value_gradient(p);
      const double g = vg.gradient.norm();
      return g > 0 ? std::abs(vg.value) / g : INFINITY;
    } catch (const NonFiniteValue&) {
      return INFINITY;
    }
  }

  [[nodiscard]] bool has_locked(int t) const {
    const auto& f = faces_[std::size_t(t)];
    return locked_[std::size_t(f[0])] || locked_[std::size_t(f[1])] || locked_[std::size_t(f[2])];
  }

  /// Whether the centroid of t and its edges' midpoints are within bound of f = 0. An edge's
  /// midpoint distance is kept with both its half-edges (0.5 (a + b) is the same number from
  /// either side), so each edge is evaluated once until a split replaces it.
  bool within(int t, double bound) {
    const auto& f = faces_[std::size_t(t)];
    const Vec &a = m_.vertices[std::size_t(f[0])], &b = m_.vertices[std::size_t(f[1])], &c = m_.vertices[std::size_t(f[2])];
    for (int k = 0; k < 3; ++k) {
      const std::size_t h = std::size_t(3 * t + k);
      if (!(edge_distance_[h] >= 0)) {
        const Vec& p = m_.vertices[std::size_t(f[k])];
        const Vec& q = m_.vertices[std::size_t(f[(k + 1) % 3])];
        edge_distance_[h] = distance(0.5 * (p + q));
        edge_distance_[std::size_t(twin_[h])] = edge_distance_[h];
      }
      if (edge_distance_[h] > bound) return false;
    }
    return distance((a + b + c) / 3.0) <= bound;
  }

  /// The midpoint of a b moved onto f = 0 along the gradient (Newton); false when it does not
  /// converge within a quarter of the edge's length.
  bool project(const Vec& a, const Vec& b, Vec& out) const {
    const Vec mid = 0.5 * (a + b);
    const double reach = 0.25 * (b - a).norm();
    Vec p = mid;
    try {
      for (int iter = 0; iter < 8; ++iter) {
        const ValueGradient vg = f_.value_gradient(p);
        const double gg = vg.gradient.squaredNorm();
        if (!(gg > 0)) return false;
        const Vec step = vg.gradient * (vg.value / gg);
        p -= step;
        if ((p - mid).norm() > reach) return false;
        if (step.norm() <= 1e-13 * reach) break;
      }
      out = p;
      if ((o_.box.lo.array() <= o_.box.hi.array()).all() &&
          ((p.array() < o_.box.lo.array()).any() || (p.array() > o_.box.hi.array()).any()))
        return false;  // outside the solid's box
      return distance(p) <= 1e-10 * reach;
    } catch (const NonFiniteValue&) {
      return false;
    }
  }

  /// Splits edge a b (half-edge 3 t + e) of triangles t (a b c) and n (b a d) at its projected
  /// midpoint m: t becomes (a m c), n (b m d), and two triangles are added, (m b c) and (m a d),
  /// at `added` and added + 1.
  bool split(int t, int e, int& added) {
    const int hn = twin_[std::size_t(3 * t + e)], n = hn / 3, en = hn % 3;
    const auto& ft = faces_[std::size_t(t)];
    const auto& fn = faces_[std::size_t(n)];
    const int a = ft[e], b = ft[(e + 1) % 3], c = ft[(e + 2) % 3], d = fn[(en + 2) % 3];
    if (c == d) return false;
    // the outer half-edges' twins: b c and c a of t, a d and d b of n
    const int out_bc = twin_[std::size_t(3 * t + (e + 1) % 3)], out_ca = twin_[std::size_t(3 * t + (e + 2) % 3)];
    const int out_ad = twin_[std::size_t(3 * n + (en + 1) % 3)], out_db = twin_[std::size_t(3 * n + (en + 2) % 3)];
    Vec pm;
    if (!project(m_.vertices[std::size_t(a)], m_.vertices[std::size_t(b)], pm)) return false;
    const auto normal = [&](int x, int y, int z, const Vec* px) {
      const Vec& p = x < 0 ? *px : m_.vertices[std::size_t(x)];
      const Vec& q = y < 0 ? *px : m_.vertices[std::size_t(y)];
      const Vec& r = z < 0 ? *px : m_.vertices[std::size_t(z)];
      return Vec((q - p).cross(r - p));
    };
    // the four new triangles must face outwards, along grad f at their centroids (-1 stands for m)
    for (const auto& tri : {std::array<int, 3>{a, -1, c}, std::array<int, 3>{-1, b, c}, std::array<int, 3>{b, -1, d},
                            std::array<int, 3>{-1, a, d}}) {
      const Vec nw = normal(tri[0], tri[1], tri[2], &pm);
      Vec centroid = Vec::Zero();
      for (int v : tri) centroid += v < 0 ? pm : m_.vertices[std::size_t(v)];
      try {
        if (!(nw.dot(f_.value_gradient(centroid / 3.0).gradient) > 0.0)) return false;
      } catch (const NonFiniteValue&) {
        return false;
      }
    }
    const int m = int(m_.vertices.size());
    m_.vertices.push_back(pm);
    locked_.push_back(false);
    added = int(faces_.size());
    const int p = added, q = added + 1;
    faces_[std::size_t(t)] = {a, m, c};  // a->m, m->c, c->a
    faces_[std::size_t(n)] = {b, m, d};  // b->m, m->d, d->b
    faces_.push_back({m, b, c});         // m->b, b->c, c->m
    faces_.push_back({m, a, d});         // m->a, a->d, d->m
    twin_.resize(3 * faces_.size(), -1);
    edge_distance_.resize(twin_.size());
    verified_.resize(faces_.size());
    for (int x : {t, n, p, q}) verified_[std::size_t(x)] = 0;
    auto pair = [&](int x, int y) {
      twin_[std::size_t(x)] = y;
      twin_[std::size_t(y)] = x;
    };
    pair(3 * t + 0, 3 * q + 0);  // a->m, m->a
    pair(3 * t + 1, 3 * p + 2);  // m->c, c->m
    pair(3 * t + 2, out_ca);
    pair(3 * n + 0, 3 * p + 0);  // b->m, m->b
    pair(3 * n + 1, 3 * q + 2);  // m->d, d->m
    pair(3 * n + 2, out_db);
    pair(3 * p + 1, out_bc);
    pair(3 * q + 1, out_ad);
    // the cut edge's halves and the two new edges are unknown; an outer edge keeps its distance
    for (int x : {t, n, p, q})
      for (int k = 0; k < 3; ++k) {
        const std::size_t h = std::size_t(3 * x + k);
        edge_distance_[h] = edge_distance_[std::size_t(twin_[h])];
      }
    for (int h : {3 * t + 0, 3 * q + 0, 3 * n + 0, 3 * p + 0, 3 * t + 1, 3 * p + 2, 3 * n + 1, 3 * q + 2})
      edge_distance_[std::size_t(h)] = -1.0;
    return true;
  }

  PolygonMesh& m_;
  std::vector<bool>& locked_;
  const Expression& f_;
  const RefineOptions& o_;
  std::vector<std::array<int, 3>> faces_;
  std::vector<int> twin_;  // half-edge 3 t + k -> the opposite half-edge
  std::vector<double> edge_distance_;  // per half-edge: its midpoint's distance from f = 0; < 0: not known
  std::vector<char> verified_;         // per triangle: found within tolerance since its last change
  bool closed_ = true;
};

}  // namespace

RefineResult refine(PolygonMesh& mesh, std::vector<bool>& locked, const Expression& f, const RefineOptions& options) {
  return Refiner(mesh, locked, f, options).run();
}

}  // namespace sculpt::implicit::detail
