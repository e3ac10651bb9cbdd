// Half-edge collapses with a distance bound (simplify.hpp).
#include "implicit/detail/simplify.hpp"

#include <algorithm>
#include <array>
#include <cmath>

#include <Eigen/Geometry>

namespace sculpt::implicit::detail {
namespace {

using Vec = Eigen::Vector3d;

class Simplifier {
 public:
  Simplifier(PolygonMesh& m, const std::vector<bool>& locked, const Expression& f, const SimplifyOptions& o)
      : m_(m), locked_(locked), f_(f), o_(o), incident_(m.vertices.size()), alive_(m.faces.size(), true) {
    for (int t = 0; t < int(m.faces.size()); ++t)
      for (int v : m.faces[t]) incident_[v].push_back(t);
  }

  int run() {
    int collapses = 0;
    for (int pass = 0; pass < o_.passes; ++pass) {
      int before = collapses;
      for (int u = 0; u < int(m_.vertices.size()); ++u) {
        if (locked_[u] || incident_[u].empty()) continue;
        std::vector<int> ring = neighbours(u);
        std::sort(ring.begin(), ring.end(), [&](int a, int b) {
          return (m_.vertices[a] - m_.vertices[u]).squaredNorm() < (m_.vertices[b] - m_.vertices[u]).squaredNorm();
        });
        for (int v : ring) {
          if (try_collapse(u, v)) {
            ++collapses;
            break;
          }
        }
      }
      if (collapses == before) break;
    }
    compact();
    return collapses;
  }

 private:
  std::vector<int> neighbours(int u) const {
    std::vector<int> out;
    for (int t : incident_[u])
      for (int w : m_.faces[t])
        if (w != u && std::find(out.begin(), out.end(), w) == out.end()) out.push_back(w);
    return out;
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

  bool try_collapse(int u, int v) {
    // the two triangles on edge uv, and the link condition: u and v share exactly their third vertices
    std::vector<int> shared;
    for (int t : incident_[u]) {
      const auto& f = m_.faces[t];
      if (std::find(f.begin(), f.end(), v) != f.end()) shared.push_back(t);
    }
    if (shared.size() != 2) return false;
    std::vector<int> opposite;
    for (int t : shared)
      for (int w : m_.faces[t])
        if (w != u && w != v) opposite.push_back(w);
    const std::vector<int> nu = neighbours(u), nv = neighbours(v);
    int common = 0;
    for (int w : nu) common += std::find(nv.begin(), nv.end(), w) != nv.end() ? 1 : 0;
    if (common != 2 || opposite.size() != 2 || opposite[0] == opposite[1]) return false;
    if (nu.size() <= 3 || nv.size() <= 3) return false;  // would leave a vertex of degree 2

    const Vec& pu = m_.vertices[u];
    bool near_removed = false;
    for (int t : incident_[u]) {
      if (std::find(shared.begin(), shared.end(), t) != shared.end()) continue;
      std::array<Vec, 3> before, after;
      for (int c = 0; c < 3; ++c) {
        const int w = m_.faces[t][c];
        before[c] = m_.vertices[w];
        after[c] = w == u ? m_.vertices[v] : m_.vertices[w];
      }
      const Vec n0 = normal(before), n1 = normal(after);
      const double l0 = n0.norm(), l1 = n1.norm();
      if (!(l1 > 1e-14 * (after[1] - after[0]).squaredNorm() + 1e-300)) return false;
      if (n0.dot(n1) < 0.5 * l0 * l1) return false;  // turns by more than 60 degrees
      const Vec centroid = (after[0] + after[1] + after[2]) / 3.0;
      try {
        const Vec g = f_.value_gradient(centroid).gradient;
        if (!(n1.dot(g) > 0.5 * l1 * g.norm())) return false;  // faces away from the surface normal
      } catch (const NonFiniteValue&) {
        return false;
      }
      if (distance(centroid) > o_.tolerance) return false;
      for (int c = 0; c < 3; ++c) {
        if (m_.faces[t][c] != u) continue;
        if (distance(0.5 * (after[c] + after[(c + 1) % 3])) > o_.tolerance) return false;
        if (distance(0.5 * (after[c] + after[(c + 2) % 3])) > o_.tolerance) return false;
      }
      near_removed = near_removed || point_triangle(pu, after) <= o_.tolerance;
    }
    if (!near_removed) return false;

    for (int t : shared) alive_[t] = false;
    for (int w : {u, v, opposite[0], opposite[1]}) {
      auto& list = incident_[w];
      list.erase(std::remove_if(list.begin(), list.end(), [&](int t) { return !alive_[t]; }), list.end());
    }
    for (int t : incident_[u]) {
      for (int& w : m_.faces[t])
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
    for (int t = 0; t < int(m_.faces.size()); ++t) {
      if (!alive_[t]) continue;
      for (int& w : m_.faces[t]) {
        if (index[w] < 0) {
          index[w] = int(vertices.size());
          vertices.push_back(m_.vertices[w]);
        }
        w = index[w];
      }
      faces.push_back(std::move(m_.faces[t]));
    }
    m_.vertices = std::move(vertices);
    m_.faces = std::move(faces);
  }

  PolygonMesh& m_;
  const std::vector<bool>& locked_;
  const Expression& f_;
  const SimplifyOptions& o_;
  std::vector<std::vector<int>> incident_;
  std::vector<bool> alive_;
};

}  // namespace

int simplify(PolygonMesh& mesh, const std::vector<bool>& locked, const Expression& f, const SimplifyOptions& options) {
  return Simplifier(mesh, locked, f, options).run();
}

}  // namespace sculpt::implicit::detail
