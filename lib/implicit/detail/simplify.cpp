// Half-edge collapses with a distance bound (simplify.hpp).
#include "implicit/detail/simplify.hpp"
#include "base/cancel.hpp"

#include <algorithm>
#include <array>
#include <cmath>

#include <Eigen/Geometry>

namespace sculpt::implicit::detail {
namespace {

using Vec = Eigen::Vector3d;
constexpr double kRelaxed = 8.0 / 7.0;  // the slivers' pass: 0.8 tol where the first pass keeps 0.7 tol

class Simplifier {
 public:
  Simplifier(const PolygonMesh& m, const std::vector<bool>& locked, const Expression& f, const SimplifyOptions& o)
      : m_(m), locked_(locked), f_(f), o_(o), incident_(m.vertices.size()), alive_(m.faces.size(), true),
        stamp_(m.vertices.size(), 0) {
    faces_.reserve(m.faces.size());
    for (const auto& face : m.faces) faces_.push_back({face[0], face[1], face[2]});
    for (int t = 0; t < int(faces_.size()); ++t)
      for (int v : faces_[t]) incident_[v].push_back(t);
  }

  SimplifyResult run() {
    int collapses = 0;
    // A vertex is tried again only when something changed that could turn one of its failed
    // tries around: a collapse's outcome depends only on the triangles around u and around its
    // neighbours (and the fixed vertex positions), so skipping skips tries that would fail again.
    // A collapse into v changes the triangles of v and of its neighbours (their "fans"). A try
    // of u can turn out differently only if u's fan changed since its last try (every check),
    // or a neighbour's fan did (only the topological checks: the link condition and the degrees
    // of the opposite vertices). A vertex whose tries all failed on geometry or distance, which
    // depend only on its own triangles, is therefore not tried again for a change among its
    // neighbours. Collapse counts serve as time stamps: a collapse stamps only the fans it
    // changed, and a vertex looks at its neighbours' stamps when its turn comes.
    std::vector<int> fan_changed(m_.vertices.size(), 0);  // stamp of the last change of the fan
    std::vector<int> tried(m_.vertices.size(), -1);       // stamp of the last try
    std::vector<char> topology_failed(m_.vertices.size(), 0);
    std::vector<int> ring;
    CancelPoll poll;
    for (int pass = 0; pass < o_.passes; ++pass) {
      int before = collapses;
      for (int u = 0; u < int(m_.vertices.size()); ++u) {
        poll.tick();  // Ctrl-C (base/cancel.hpp)
        if (locked_[u] || incident_[u].empty()) continue;
        neighbours(u, ring);
        if (!o_.retry_all && fan_changed[u] <= tried[u]) {
          bool again = false;
          if (topology_failed[u])
            for (int w : ring) again = again || fan_changed[w] > tried[u];
          if (!again) continue;
        }
        tried[u] = collapses;
        topology_failed[u] = 0;
        if (beyond_ring(u, ring)) continue;
        std::sort(ring.begin(), ring.end(), [&](int a, int b) {
          return (m_.vertices[a] - m_.vertices[u]).squaredNorm() < (m_.vertices[b] - m_.vertices[u]).squaredNorm();
        });
        for (int v : ring) {
          if (try_collapse(u, v)) {
            ++collapses;
            // the fans of v and of its neighbours changed
            for (int t : incident_[v])
              for (int w : faces_[t]) fan_changed[w] = collapses;
            break;
          }
          if (topology_failed_) topology_failed[u] = 1;
        }
      }
      if (collapses == before) break;
    }
    // slivers: try every collapse among the corners of each thin triangle
    relaxed_ = true;
    int thin = 0;
    for (int pass = 0; pass < 4; ++pass) {
      thin = 0;
      for (int t = 0; t < int(faces_.size()); ++t) {
        if (!alive_[t] || height(t) >= o_.min_height) continue;
        bool done = false;
        for (int a = 0; a < 3 && !done; ++a)
          for (int b = 0; b < 3 && !done; ++b) {
            const int u = faces_[t][a], v = faces_[t][b];
            if (u != v && !locked_[u] && try_collapse(u, v)) done = true;
          }
        if (!done) done = try_flip(t);
        if (done) ++collapses;
        else ++thin;
      }
      if (thin == 0) break;
    }
    compact();
    return {.mesh = std::move(out_), .collapses = collapses, .thin_triangles = thin};
  }

  double height(int t) const {
    const auto& f = faces_[t];
    const Vec &a = m_.vertices[f[0]], &b = m_.vertices[f[1]], &c = m_.vertices[f[2]];
    const double longest = std::max({(b - a).norm(), (c - b).norm(), (a - c).norm()});
    return longest > 0 ? (b - a).cross(c - a).norm() / longest : 0.0;
  }

 private:
  std::vector<int> neighbours(int u) const {
    std::vector<int> out;
    neighbours(u, out);
    return out;
  }

  void neighbours(int u, std::vector<int>& out) const {
    out.clear();
    const int stamp = ++stamp_counter_;
    for (int t : incident_[u])
      for (int w : faces_[t])
        if (w != u && stamp_[w] != stamp) {
          stamp_[w] = stamp;
          out.push_back(w);
        }
  }

  /// True when u cannot pass the check that it stays within tol of the changed triangles, for
  /// any neighbour it could be merged into: its neighbours all lie on one side of the plane
  /// through u across the mean normal of its triangles, farther from it than tol. The changed
  /// triangles span only neighbours of u, so every point of them is then farther than tol from
  /// u. That check depends only on u's triangles, so skipping u until they change is exact.
  [[nodiscard]] bool beyond_ring(int u, const std::vector<int>& ring) const {
    const Vec& pu = m_.vertices[u];
    Vec n = Vec::Zero();
    for (int t : incident_[u]) {
      const auto& f = faces_[t];
      n += (m_.vertices[f[1]] - m_.vertices[f[0]]).cross(m_.vertices[f[2]] - m_.vertices[f[0]]);
    }
    const double length = n.norm();
    if (!(length > 0)) return false;
    const double limit = o_.tolerance * (1 + 1e-9) * length;  // the first passes' tol (not relaxed)
    int above = 0, below = 0;
    for (int w : ring) {
      const double h = (m_.vertices[w] - pu).dot(n);
      above += h > limit ? 1 : 0;
      below += h < -limit ? 1 : 0;
    }
    return above == int(ring.size()) || below == int(ring.size());
  }

  /// The number of neighbours of u: on a closed 2-manifold (the marched mesh, and every
  /// collapse keeps it one) a vertex has as many neighbours as triangles around it.
  [[nodiscard]] int degree(int u) const { return int(incident_[u].size()); }

  /// A new edge (a, b) would lie in a face of the box (SimplifyOptions::box_sides). The mesh's
  /// edges there are the surface's trace on the box, which bounds the closing triangles; a new
  /// one would cut across them (and a triangle with three vertices on one side would lie on them).
  [[nodiscard]] bool on_one_box_side(int a, int b) const {
    const auto& sides = o_.box_sides;
    return !sides.empty() && (sides[std::size_t(a)] & sides[std::size_t(b)]) != 0;
  }

  [[nodiscard]] Vec normal(const std::array<Vec, 3>& p) const { return (p[1] - p[0]).cross(p[2] - p[0]); }

  /// First-order distance of p from f = 0; infinite where it cannot be told.
  double distance(const Vec& p) const {
    try {
      const ValueGradient vg = f_.value_gradient(p);
      const double g = vg.gradient.norm();
      if (!(g > 0)) return INFINITY;
      return std::abs(vg.value) / g;
    } catch (const NonFiniteValue&) {
      return INFINITY;
    }
  }

  static double point_segment(const Vec& p, const Vec& a, const Vec& b) {
    const Vec ab = b - a;
    const double t = std::clamp((p - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0);
    return (p - (a + t * ab)).norm();
  }

  static double point_triangle(const Vec& p, const std::array<Vec, 3>& t) {
    const Vec n = (t[1] - t[0]).cross(t[2] - t[0]);
    const double nn = n.squaredNorm();
    if (nn > 0) {
      const Vec q = p - n * ((p - t[0]).dot(n) / nn);
      bool inside = true;
      for (int e = 0; e < 3; ++e) inside = inside && (t[(e + 1) % 3] - t[e]).cross(q - t[e]).dot(n) >= 0;
      if (inside) return (p - q).norm();
    }
    return std::min({point_segment(p, t[0], t[1]), point_segment(p, t[1], t[2]), point_segment(p, t[2], t[0])});
  }

  /// Flips the longest edge of thin triangle t (a cap: a vertex near the middle of its longest
  /// edge) when both new triangles are higher than t, face along the surface normal and stay
  /// within the relaxed distance of f = 0.
  bool try_flip(int t) {
    auto& ft = faces_[t];
    int e = 0;
    double longest = -1;
    for (int k = 0; k < 3; ++k) {
      const double l = (m_.vertices[ft[(k + 1) % 3]] - m_.vertices[ft[k]]).squaredNorm();
      if (l > longest) longest = l, e = k;
    }
    const int a = ft[e], b = ft[(e + 1) % 3], c = ft[(e + 2) % 3];
    int n = -1, d = -1;
    for (int o : incident_[a]) {
      if (o == t) continue;
      const auto& fo = faces_[o];
      for (int k = 0; k < 3; ++k)
        if (fo[k] == b && fo[(k + 1) % 3] == a) n = o, d = fo[(k + 2) % 3];
    }
    if (n < 0 || d == c) return false;
    const std::vector<int> nc = neighbours(c);
    if (std::find(nc.begin(), nc.end(), d) != nc.end()) return false;  // edge cd exists already
    if (neighbours(a).size() <= 3 || neighbours(b).size() <= 3) return false;
    const std::array<std::array<int, 3>, 2> fresh = {{{c, a, d}, {d, b, c}}};
    if (on_one_box_side(c, d)) return false;
    const double before = std::min(height(t), height(n));
    std::array<Vec, 2> normals;
    for (int k = 0; k < 2; ++k) {
      const std::array<Vec, 3> p = {m_.vertices[fresh[k][0]], m_.vertices[fresh[k][1]], m_.vertices[fresh[k][2]]};
      normals[k] = normal(p);
      const double l = std::max({(p[1] - p[0]).norm(), (p[2] - p[1]).norm(), (p[0] - p[2]).norm()});
      if (!(normals[k].norm() / l > before)) return false;
      const Vec centroid = (p[0] + p[1] + p[2]) / 3.0;
      if (distance(centroid) > o_.tolerance * kRelaxed) return false;
      try {
        const Vec g = f_.value_gradient(centroid).gradient;
        if (!(normals[k].dot(g) > 0.5 * normals[k].norm() * g.norm())) return false;
      } catch (const NonFiniteValue&) {
        return false;
      }
    }
    if (normals[0].dot(normals[1]) < 0.5 * normals[0].norm() * normals[1].norm()) return false;
    ft = {fresh[0][0], fresh[0][1], fresh[0][2]};
    faces_[n] = {fresh[1][0], fresh[1][1], fresh[1][2]};
    auto drop = [&](int v, int face) {
      auto& list = incident_[v];
      list.erase(std::remove(list.begin(), list.end(), face), list.end());
    };
    drop(a, n);
    drop(b, t);
    incident_[c].push_back(n);
    incident_[d].push_back(t);
    return true;
  }

  bool try_collapse(int u, int v) {
    topology_failed_ = false;
    // the two triangles on edge uv, and the link condition: u and v share exactly their third vertices
    std::array<int, 2> shared{};
    int shared_count = 0;
    for (int t : incident_[u]) {
      const auto& f = faces_[t];
      if (std::find(f.begin(), f.end(), v) != f.end()) {
        if (shared_count < 2) shared[shared_count] = t;
        ++shared_count;
      }
    }
    if (shared_count != 2) return false;
    std::array<int, 2> opposite{};
    int opposite_count = 0;
    for (int t : shared)
      for (int w : faces_[t])
        if (w != u && w != v) {
          if (opposite_count < 2) opposite[opposite_count] = w;
          ++opposite_count;
        }
    if (opposite_count != 2 || opposite[0] == opposite[1]) return false;
    // the opposite vertices lose an edge: none may be left with two
    if (degree(opposite[0]) <= 3 || degree(opposite[1]) <= 3) return topology_failed_ = true, false;

    // Geometry first (cheap), then f: every check must pass, so their order does not matter.
    const Vec& pu = m_.vertices[u];
    const Vec& pv = m_.vertices[v];
    const double tol = relaxed_ ? o_.tolerance * kRelaxed : o_.tolerance;
    changed_.clear();
    for (int t : incident_[u]) {
      if (t == shared[0] || t == shared[1]) continue;
      const auto& ft = faces_[t];
      const int k = ft[0] == u ? 0 : ft[1] == u ? 1 : 2;  // u's corner; the others stay
      // new edges from v (those to the opposite vertices exist already)
      for (const int w : {ft[(k + 1) % 3], ft[(k + 2) % 3]})
        if (w != opposite[0] && w != opposite[1] && on_one_box_side(v, w)) return false;
      const Vec& b = m_.vertices[ft[(k + 1) % 3]];
      const Vec& c = m_.vertices[ft[(k + 2) % 3]];
      const Vec n0 = (b - pu).cross(c - pu), n1 = (b - pv).cross(c - pv);
      const double l0 = n0.norm(), l1 = n1.norm();
      const double scale = std::max({(b - pv).squaredNorm(), (c - b).squaredNorm(), (pv - c).squaredNorm()});
      if (!(l1 > 1e-6 * scale)) return false;  // would make a sliver
      // turns by more than 60 degrees (a sliver's own normal is not trusted)
      if (l0 > 1e-6 * scale && n0.dot(n1) < 0.5 * l0 * l1) return false;
      changed_.push_back({.centroid = (pv + b + c) / 3.0, .normal = n1, .b = &b, .c = &c,
                          .plane = std::abs((pu - pv).dot(n1)) / l1});
    }
    // u within tol of a changed triangle; the distance from its plane is a lower bound, so a
    // triangle whose plane is farther (with a margin for rounding) need not be looked at
    bool near_removed = false;
    for (const Changed& x : changed_)
      if (x.plane <= tol * (1 + 1e-9) && point_triangle(pu, {pv, *x.b, *x.c}) <= tol) {
        near_removed = true;
        break;
      }
    if (!near_removed) return false;
    // the link condition (after the geometry, which fails far more often)
    neighbours(v, nv_);
    neighbours(u, nu_);  // leaves u's neighbours stamped
    int common = 0;
    for (int w : nv_) common += stamp_[w] == stamp_counter_ ? 1 : 0;
    if (common != 2) return topology_failed_ = true, false;
    for (const Changed& x : changed_) {
      try {
        const ValueGradient vg = f_.value_gradient(x.centroid);
        const double g = vg.gradient.norm();
        const Vec& n1 = x.normal;
        if (!(n1.dot(vg.gradient) > 0.5 * n1.norm() * g)) return false;  // faces away from the surface normal
        if (!(std::abs(vg.value) <= tol * g)) return false;               // centroid farther than tol
      } catch (const NonFiniteValue&) {
        return false;
      }
    }
    // the new edges' midpoints: v with every other vertex of u's remaining triangles (each once)
    for (int w : nu_) {
      if (w == v) continue;
      if (distance(0.5 * (pv + m_.vertices[w])) > tol) return false;
    }

    for (int t : shared) alive_[t] = false;
    for (int w : {u, v, opposite[0], opposite[1]}) {
      auto& list = incident_[w];
      list.erase(std::remove_if(list.begin(), list.end(), [&](int t) { return !alive_[t]; }), list.end());
    }
    for (int t : incident_[u]) {
      for (int& w : faces_[t])
        if (w == u) w = v;
      incident_[v].push_back(t);
    }
    incident_[u].clear();
    return true;
  }

  void compact() {
    std::vector<int> index(m_.vertices.size(), -1);
    std::vector<Vec> vertices;
    std::vector<std::vector<int>> faces;
    for (int t = 0; t < int(faces_.size()); ++t) {
      if (!alive_[t]) continue;
      for (int& w : faces_[t]) {
        if (index[w] < 0) {
          index[w] = int(vertices.size());
          vertices.push_back(m_.vertices[w]);
        }
        w = index[w];
      }
      faces.push_back({faces_[t][0], faces_[t][1], faces_[t][2]});
    }
    out_.vertices = std::move(vertices);
    out_.faces = std::move(faces);
  }

  const PolygonMesh& m_;
  PolygonMesh out_;
  const std::vector<bool>& locked_;
  const Expression& f_;
  const SimplifyOptions& o_;
  std::vector<std::vector<int>> incident_;
  std::vector<bool> alive_;
  bool relaxed_ = false;
  bool topology_failed_ = false;  // the last try_collapse failed on the degrees or the link condition
  std::vector<std::array<int, 3>> faces_;               // m_.faces while simplifying
  mutable std::vector<int> stamp_;                       // neighbours(): seen in the current call
  mutable int stamp_counter_ = 0;
  std::vector<int> nu_, nv_;           // scratch of try_collapse
  struct Changed {  // a triangle at u after the collapse: v, b, c
    Vec centroid, normal;
    const Vec *b, *c;
    double plane;  // distance of u from its plane
  };
  std::vector<Changed> changed_;  // scratch of try_collapse

};

}  // namespace

SimplifyResult simplify(const PolygonMesh& mesh, const std::vector<bool>& locked, const Expression& f, const SimplifyOptions& options) {
  return Simplifier(mesh, locked, f, options).run();
}

}  // namespace sculpt::implicit::detail
