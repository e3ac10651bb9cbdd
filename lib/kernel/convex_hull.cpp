#include "kernel/convex_hull.hpp"

#include <algorithm>
#include <stdexcept>
#include <tuple>

#include "kernel/exact_int.hpp"

namespace sculpt::kernel {
namespace {

struct Vec {
  std::int64_t x = 0, y = 0, z = 0;
};

Vec operator-(const GridPoint& a, const GridPoint& b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
// |components| <= 2^(kCoordBits + 1): products <= 2^52, the cross product's components <= 2^53.
Vec cross(const Vec& a, const Vec& b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
Int128 dot(const Vec& n, const Vec& v) { return Int128(n.x) * v.x + Int128(n.y) * v.y + Int128(n.z) * v.z; }
Int128 dot(const Vec& n, const GridPoint& p) { return Int128(n.x) * p.x + Int128(n.y) * p.y + Int128(n.z) * p.z; }
Int128 squared(const Vec& v) { return dot(v, v); }
static_assert(2 * (kCoordBits + 1) + 1 <= 63, "a face normal must fit 64 bits");
static_assert(2 * (kCoordBits + 1) + 1 + kCoordBits + 3 <= 126, "a signed distance must fit 128 bits");

/// A triangle of the hull: corners counter-clockwise from outside, the neighbour across each edge
/// v[i] -> v[i+1], and the plane n.p + d = 0 with n pointing outwards.
struct Face {
  std::array<int, 3> v{};
  std::array<int, 3> next{-1, -1, -1};
  Vec n;
  Int128 d = 0;
  std::vector<int> outside;  ///< points strictly outside this face, not yet on the hull
  int seen = -1;             ///< the step that last found this face visible
  bool alive = true;
};

class Quickhull {
 public:
  explicit Quickhull(std::vector<GridPoint> points) : p_(std::move(points)) {}

  ConvexHull run() {
    ConvexHull out;
    std::sort(p_.begin(), p_.end(), [](const GridPoint& a, const GridPoint& b) {
      return std::tie(a.x, a.y, a.z) < std::tie(b.x, b.y, b.z);
    });
    p_.erase(std::unique(p_.begin(), p_.end()), p_.end());
    const auto simplex = initial_simplex(out.dimension);
    if (out.dimension < 3) return out;
    build_tetrahedron(simplex);
    while (!work_.empty()) {
      const int f = work_.back();
      work_.pop_back();
      if (faces_[f].alive && !faces_[f].outside.empty()) add_furthest_point(f);
    }
    std::vector<int> index(p_.size(), -1);
    std::vector<int> face_index(faces_.size(), -1);
    for (std::size_t g = 0; g < faces_.size(); ++g)
      if (faces_[g].alive) face_index[g] = static_cast<int>(out.neighbours.size()), out.neighbours.push_back({});
    for (const Face& f : faces_) {
      if (!f.alive) continue;
      std::array<int, 3>& across = out.neighbours[out.triangles.size()];
      for (int k = 0; k < 3; ++k) {
        across[k] = f.next[k] < 0 ? -1 : face_index[std::size_t(f.next[k])];
        if (across[k] < 0) throw std::logic_error("convex_hull: a triangle's neighbour is not on the hull");
      }
      std::array<int, 3> t{};
      for (int k = 0; k < 3; ++k) {
        int& i = index[f.v[k]];
        if (i < 0) {
          i = static_cast<int>(out.vertices.size());
          out.vertices.push_back(p_[f.v[k]]);
        }
        t[k] = i;
      }
      out.triangles.push_back(t);
    }
    return out;
  }

 private:
  Int128 distance(const Face& f, int point) const { return dot(f.n, p_[point]) + f.d; }

  /// Four points spanning a tetrahedron, or the dimension of the set if there are none.
  std::array<int, 4> initial_simplex(int& dimension) const {
    const int n = static_cast<int>(p_.size());
    dimension = 0;
    if (n < 2) return {};
    auto argmax = [&](auto&& measure) {
      int best = 0;
      Int128 value = 0;
      for (int i = 0; i < n; ++i)
        if (const Int128 m = measure(i); m > value) value = m, best = i;
      return std::pair{best, value};
    };
    const int a = 0;  // the lexicographically smallest point is a corner
    const auto [b, ab] = argmax([&](int i) { return squared(p_[i] - p_[a]); });
    dimension = 1;
    const Vec u = p_[b] - p_[a];
    const auto [c, area] = argmax([&](int i) { return squared(cross(u, p_[i] - p_[a])); });
    if (area == 0) return {};
    dimension = 2;
    const Vec normal = cross(u, p_[c] - p_[a]);
    const auto [d, height] = argmax([&](int i) {
      const Int128 h = dot(normal, p_[i] - p_[a]);
      return h < 0 ? -h : h;
    });
    if (height == 0) return {};
    dimension = 3;
    return {a, b, c, d};
  }

  int add_face(int a, int b, int c) {
    Face f;
    f.v = {a, b, c};
    f.n = cross(p_[b] - p_[a], p_[c] - p_[a]);
    f.d = -dot(f.n, p_[a]);
    faces_.push_back(std::move(f));
    return static_cast<int>(faces_.size()) - 1;
  }

  void build_tetrahedron(const std::array<int, 4>& s) {
    const int sides[4][4] = {{0, 1, 2, 3}, {0, 1, 3, 2}, {0, 2, 3, 1}, {1, 2, 3, 0}};
    for (const auto& side : sides) {
      int f = add_face(s[side[0]], s[side[1]], s[side[2]]);
      if (distance(faces_[f], s[side[3]]) > 0) {  // the fourth corner must be inside
        faces_.pop_back();
        f = add_face(s[side[0]], s[side[2]], s[side[1]]);
      }
    }
    for (int f = 0; f < 4; ++f)
      for (int i = 0; i < 3; ++i)
        for (int g = 0; g < 4; ++g)
          for (int j = 0; j < 3; ++j)
            if (faces_[g].v[j] == faces_[f].v[(i + 1) % 3] && faces_[g].v[(j + 1) % 3] == faces_[f].v[i])
              faces_[f].next[i] = g;
    for (int i = 0; i < static_cast<int>(p_.size()); ++i) {
      if (i == s[0] || i == s[1] || i == s[2] || i == s[3]) continue;
      assign(i, 0, 4);
    }
    for (int f = 0; f < 4; ++f) work_.push_back(f);
  }

  /// Puts `point` into the outside set of the first face in [first, last) that it is strictly
  /// outside of; a point outside none of them is inside the hull (or on it) and is dropped.
  void assign(int point, int first, int last) {
    for (int f = first; f < last; ++f)
      if (distance(faces_[f], point) > 0) {
        faces_[f].outside.push_back(point);
        return;
      }
  }

  /// One Quickhull step: the point of face f's outside set furthest from its plane is a corner of
  /// the hull; the faces it sees strictly are replaced by a cone from it to their horizon.
  void add_furthest_point(int f0) {
    const std::vector<int>& candidates = faces_[f0].outside;
    int apex = candidates.front();
    Int128 far = distance(faces_[f0], apex);
    for (int q : candidates)
      if (const Int128 h = distance(faces_[f0], q); h > far) far = h, apex = q;
    ++step_;

    // The faces that see the apex (connected, found by a walk over neighbours).
    visible_.assign(1, f0);
    faces_[f0].seen = step_;
    for (size_t k = 0; k < visible_.size(); ++k)
      for (int g : faces_[visible_[k]].next)
        if (faces_[g].seen != step_ && distance(faces_[g], apex) > 0) {
          faces_[g].seen = step_;
          visible_.push_back(g);
        }

    // The horizon: edges between a visible face and one that is not; a cone face on each.
    const int first_new = static_cast<int>(faces_.size());
    if (from_.size() != p_.size()) from_.assign(p_.size(), {-1, -1}), to_.assign(p_.size(), {-1, -1});
    for (int vf : visible_)
      for (int i = 0; i < 3; ++i) {
        const int outer = faces_[vf].next[i];
        if (faces_[outer].seen == step_) continue;
        const int a = faces_[vf].v[i], b = faces_[vf].v[(i + 1) % 3];
        const int nf = add_face(a, b, apex);
        faces_[nf].next[0] = outer;
        Face& o = faces_[outer];
        for (int j = 0; j < 3; ++j)
          if (o.v[j] == b && o.v[(j + 1) % 3] == a) o.next[j] = nf;
        if (from_[std::size_t(a)].step == step_ || to_[std::size_t(b)].step == step_)
          throw std::logic_error("convex_hull: the horizon is not a simple cycle");
        from_[std::size_t(a)] = {step_, nf};
        to_[std::size_t(b)] = {step_, nf};
      }
    const int last_new = static_cast<int>(faces_.size());
    for (int nf = first_new; nf < last_new; ++nf) {
      Face& f = faces_[nf];
      f.next[1] = cone_face(from_, f.v[1]);  // the cone face on the horizon edge that starts at b
      f.next[2] = cone_face(to_, f.v[0]);    // ... and the one that ends at a
    }
    for (int vf : visible_) {
      Face& f = faces_[vf];
      f.alive = false;
      for (int q : f.outside)
        if (q != apex) assign(q, first_new, last_new);
      std::vector<int>().swap(f.outside);
    }
    for (int nf = first_new; nf < last_new; ++nf)
      if (!faces_[nf].outside.empty()) work_.push_back(nf);
  }

  /// The cone face made in step `step` on the horizon edge that starts (from_) or ends (to_) at
  /// a point, indexed by point.
  struct Mark {
    int step, face;
  };
  int cone_face(const std::vector<Mark>& marks, int point) const {
    const Mark& m = marks[std::size_t(point)];
    if (m.step != step_) throw std::logic_error("convex_hull: the horizon is not a closed cycle");
    return m.face;
  }

  std::vector<GridPoint> p_;
  std::vector<Face> faces_;
  std::vector<int> work_;
  std::vector<int> visible_;
  std::vector<Mark> from_, to_;
  int step_ = 0;
};

}  // namespace

ConvexHull convex_hull(std::span<const GridPoint> points) {
  return Quickhull(std::vector<GridPoint>(points.begin(), points.end())).run();
}

}  // namespace sculpt::kernel
