#include "bsp/mesh_assembly.hpp"

#include "bsp/face_triangulation.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <numeric>
#include <limits>

#include <Eigen/Geometry>

namespace sculpt::detail {

using kernel::ApproxPoint;
using kernel::Sign;

namespace {

struct Occurrence {  // one corner of one fragment: the vertex s ∩ p ∩ q
  std::int32_t s, p, q;
  ApproxPoint at;
};

struct Face {
  std::vector<int> vertices;            // final orientation
  std::vector<std::int32_t> edge_line;  // plane E of edge k (from vertices[k] to [k+1]); line = support ∩ E
  std::int32_t support;
  bool flip;
};

class UnionFind {
 public:
  explicit UnionFind(std::size_t n) : parent_(n) { std::iota(parent_.begin(), parent_.end(), 0); }
  int find(int x) {
    while (parent_[std::size_t(x)] != x) x = parent_[std::size_t(x)] = parent_[std::size_t(parent_[std::size_t(x)])];
    return x;
  }
  void unite(int a, int b) {
    a = find(a), b = find(b);
    if (a != b) parent_[std::size_t(std::max(a, b))] = std::min(a, b);
  }

 private:
  std::vector<int> parent_;
};

class Assembler {
 public:
  explicit Assembler(const Fragments& f) : f_(f), planes_(f.planes) {}

  PolygonMesh run(bool triangulate) {
    collect();
    merge_vertices();
    build_faces();
    remove_t_junctions();
    merge_coplanar_faces();
    remove_straight_vertices();
    split_non_manifold();
    return output(triangulate);
  }

 private:
  bool on_plane(const Occurrence& o, std::int32_t plane) const {
    return kernel::orient(planes_[o.s], planes_[o.p], planes_[o.q], o.at, planes_[plane]) == Sign::Zero;
  }
  // Vertex v lies on `plane`: known without arithmetic when one of the occurrences merged into
  // v was made with that plane, else decided exactly.
  bool vertex_on_plane(int v, std::int32_t plane) const {
    for (int i = occ_start_[std::size_t(v)]; i < occ_start_[std::size_t(v) + 1]; ++i) {
      const Occurrence& o = occ_[std::size_t(occ_list_[std::size_t(i)])];
      if (o.s == plane || o.p == plane || o.q == plane) return true;
    }
    return on_plane(occ_[std::size_t(rep_[std::size_t(v)])], plane);
  }
  bool same_point(const Occurrence& a, const Occurrence& b) const {
    return on_plane(a, b.s) && on_plane(a, b.p) && on_plane(a, b.q);
  }

  void collect() {
    for (const Fragment& fr : f_.fragments) {
      start_.push_back(int(occ_.size()));
      for (const auto& c : fr.polygon.corners) occ_.push_back({fr.polygon.support, c.p, c.q, c.at});
    }
    start_.push_back(int(occ_.size()));
  }

  // Exact vertex merging. Candidates share a cell of a fine grid (1/64 grid unit, far above the
  // approximation errors; an occurrence within its error of a cell boundary is entered in every
  // cell it may belong to); equality is decided exactly (the first vertex lies on the three
  // planes of the second).
  void merge_vertices() {
    const std::size_t n = occ_.size();
    constexpr double kCell = 1.0 / 64, kShift = 0.3711 / 64;
    std::vector<std::pair<std::array<std::int64_t, 3>, int>> keyed;  // sorted: spatially coherent
    std::vector<int> wide;
    keyed.reserve(n + n / 8);
    for (std::size_t i = 0; i < n; ++i) {
      const ApproxPoint& a = occ_[i].at;
      const double v[3] = {a.x, a.y, a.z};
      std::int64_t lo[3], hi[3];
      for (int k = 0; k < 3; ++k) {  // shifted so that grid points never sit on a cell boundary
        lo[k] = std::int64_t(std::floor((v[k] - a.err + kShift) / kCell));
        hi[k] = std::int64_t(std::floor((v[k] + a.err + kShift) / kCell));
      }
      if (hi[0] - lo[0] > 2 || hi[1] - lo[1] > 2 || hi[2] - lo[2] > 2) {
        wide.push_back(int(i));  // a large error bound (nearly dependent planes): brute force
        continue;
      }
      for (std::int64_t x = lo[0]; x <= hi[0]; ++x)
        for (std::int64_t y = lo[1]; y <= hi[1]; ++y)
          for (std::int64_t z = lo[2]; z <= hi[2]; ++z) keyed.push_back({{x, y, z}, int(i)});
    }
    std::sort(keyed.begin(), keyed.end());
    UnionFind uf(n);
    for (const int ia : wide)
      for (std::size_t ib = 0; ib < n; ++ib) {
        const Occurrence& oa = occ_[std::size_t(ia)];
        const Occurrence& ob = occ_[ib];
        const double tol = oa.at.err + ob.at.err;
        if (std::size_t(ia) == ib || uf.find(ia) == uf.find(int(ib)) || std::fabs(ob.at.x - oa.at.x) > tol ||
            std::fabs(ob.at.y - oa.at.y) > tol || std::fabs(ob.at.z - oa.at.z) > tol)
          continue;
        if (same_point(oa, ob)) uf.unite(ia, int(ib));
      }
    for (std::size_t i = 0; i < keyed.size();) {
      std::size_t j = i;
      while (j < keyed.size() && keyed[j].first == keyed[i].first) ++j;
      for (std::size_t a = i; a < j; ++a)
        for (std::size_t b = a + 1; b < j; ++b) {
          const int ia = keyed[a].second, ib = keyed[b].second;
          if (uf.find(ia) == uf.find(ib)) continue;
          const Occurrence& oa = occ_[std::size_t(ia)];
          const Occurrence& ob = occ_[std::size_t(ib)];
          const double tol = oa.at.err + ob.at.err;
          if (std::fabs(ob.at.x - oa.at.x) > tol || std::fabs(ob.at.y - oa.at.y) > tol || std::fabs(ob.at.z - oa.at.z) > tol)
            continue;
          if (same_point(oa, ob)) uf.unite(ia, ib);
        }
      i = j;
    }
    vertex_of_.assign(n, -1);
    for (std::size_t i = 0; i < n; ++i) {
      const int r = uf.find(int(i));
      if (vertex_of_[std::size_t(r)] < 0) {
        vertex_of_[std::size_t(r)] = int(rep_.size());
        rep_.push_back(r);
        at_.push_back(occ_[std::size_t(r)].at);
      }
      vertex_of_[i] = vertex_of_[std::size_t(r)];
    }
    // Occurrences of each vertex (counting sort), for vertex_on_plane.
    occ_start_.assign(rep_.size() + 1, 0);
    for (std::size_t i = 0; i < n; ++i) ++occ_start_[std::size_t(vertex_of_[i]) + 1];
    for (std::size_t v = 0; v < rep_.size(); ++v) occ_start_[v + 1] += occ_start_[v];
    occ_list_.resize(n);
    std::vector<int> fill(occ_start_.begin(), occ_start_.end() - 1);
    for (std::size_t i = 0; i < n; ++i) occ_list_[std::size_t(fill[std::size_t(vertex_of_[i])]++)] = int(i);
  }

  void build_faces() {
    faces_.reserve(f_.fragments.size());
    for (std::size_t fi = 0; fi < f_.fragments.size(); ++fi) {
      const Fragment& fr = f_.fragments[fi];
      const int m = int(fr.polygon.corners.size());
      Face face;
      face.support = fr.polygon.support;
      face.flip = fr.flip;
      for (int k = 0; k < m; ++k) {
        const int ck = fr.flip ? m - 1 - k : k;              // corner at final position k
        const int edge_corner = fr.flip ? (ck - 1 + m) % m : ck;  // corner whose edge leads to k + 1
        face.vertices.push_back(vertex_of_[std::size_t(start_[fi] + ck)]);
        face.edge_line.push_back(fr.polygon.corners[std::size_t(edge_corner)].edge);
      }
      faces_.push_back(std::move(face));
    }
  }

  Eigen::Vector3d position(int v) const {
    const ApproxPoint& a = at_[std::size_t(v)];
    return {a.x, a.y, a.z};
  }

  double err(int v) const { return at_[std::size_t(v)].err; }

  // The axis along which the line support ∩ edge changes most, from the exact direction
  // n_support x n_edge (integers below 2^107, so the double of the largest is non-zero): two
  // distinct points of the line always differ in this coordinate.
  int line_axis(std::int32_t support, std::int32_t edge) const {
    const kernel::Plane& p = planes_[support];
    const kernel::Plane& q = planes_[edge];
    using kernel::Int128;
    const Int128 c[3] = {Int128(p.b) * q.c - Int128(p.c) * q.b, Int128(p.c) * q.a - Int128(p.a) * q.c,
                         Int128(p.a) * q.b - Int128(p.b) * q.a};
    int axis = 0;
    for (int k = 1; k < 3; ++k)
      if ((c[k] < 0 ? -c[k] : c[k]) > (c[axis] < 0 ? -c[axis] : c[axis])) axis = k;
    return axis;
  }

  // Exact comparison of two vertices' coordinate `axis`: the approximations decide when their
  // error boxes are apart, the exact homogeneous coordinates otherwise.
  bool less_along(int a, int b, int axis) const {
    const Eigen::Vector3d pa = position(a), pb = position(b);
    const double gap = err(a) + err(b);
    if (pa[axis] + gap < pb[axis]) return true;
    if (pb[axis] + gap < pa[axis]) return false;
    auto coordinate = [&](int v) {
      const Occurrence& o = occ_[std::size_t(rep_[std::size_t(v)])];
      const kernel::HomogeneousPoint h = kernel::exact_vertex(planes_[o.s], planes_[o.p], planes_[o.q]);
      return std::pair{axis == 0 ? h.x : (axis == 1 ? h.y : h.z), h.w};
    };
    using Big = boost::multiprecision::int512_t;
    const auto x = coordinate(a), y = coordinate(b);
    // x.first / x.second < y.first / y.second
    const Big l = Big(x.first) * Big(y.second), r = Big(y.first) * Big(x.second);
    return (x.second.sign() * y.second.sign() > 0) ? l < r : l > r;
  }

  // Exact test that collinear, distinct vertices satisfy u < c < w (or w < c < u) along `axis`.
  bool exactly_between(int u, int c, int w, int axis) const {
    return less_along(u, w, axis) ? (less_along(u, c, axis) && less_along(c, w, axis))
                                  : (less_along(w, c, axis) && less_along(c, u, axis));
  }

  static std::uint64_t key(int u, int w) { return (std::uint64_t(std::uint32_t(u)) << 32) | std::uint32_t(w); }

  // A vertex lying inside another face's edge is an endpoint of an unmatched half-edge on the
  // other side; only those are candidates. On-the-line is decided exactly.
  void remove_t_junctions() {
    std::vector<std::uint64_t> edges;
    for (const Face& f : faces_)
      for (std::size_t k = 0; k < f.vertices.size(); ++k)
        edges.push_back(key(f.vertices[k], f.vertices[(k + 1) % f.vertices.size()]));
    std::sort(edges.begin(), edges.end());
    auto has = [&](int u, int w) { return std::binary_search(edges.begin(), edges.end(), key(u, w)); };
    struct Open {
      int face, k;
    };
    std::vector<Open> open;
    std::vector<int> candidates;
    for (std::size_t fi = 0; fi < faces_.size(); ++fi) {
      const Face& f = faces_[fi];
      for (std::size_t k = 0; k < f.vertices.size(); ++k) {
        const int u = f.vertices[k], w = f.vertices[(k + 1) % f.vertices.size()];
        if (has(w, u)) continue;
        open.push_back({int(fi), int(k)});
        candidates.push_back(u);
        candidates.push_back(w);
      }
    }
    if (open.empty()) return;
    std::vector<std::vector<std::tuple<int, double, int>>> inserts(faces_.size());  // (edge k, t, vertex)

    // First, walk the other side: the T-vertices of u -> w are the chain w -> x1 -> ... -> u of
    // open half-edges of other faces along the same line (exact on-line tests).
    std::vector<std::pair<int, int>> out_edges;  // (start vertex, index in open)
    for (std::size_t i = 0; i < open.size(); ++i) {
      const Face& f = faces_[std::size_t(open[i].face)];
      out_edges.push_back({f.vertices[std::size_t(open[i].k)], int(i)});
    }
    std::sort(out_edges.begin(), out_edges.end());
    std::vector<Open> unresolved;
    for (const Open& e : open) {
      const Face& f = faces_[std::size_t(e.face)];
      const int u = f.vertices[std::size_t(e.k)], w = f.vertices[(std::size_t(e.k) + 1) % f.vertices.size()];
      const Eigen::Vector3d pu = position(u), d = position(w) - pu;
      const double len2 = d.squaredNorm();
      std::vector<std::pair<double, int>> chain;
      int cur = w;
      double cur_t = 1;
      bool reached = false;
      for (std::size_t steps = 0; steps < 64 && !reached; ++steps) {
        int next = -1;
        double next_t = 0;
        auto range = std::equal_range(out_edges.begin(), out_edges.end(), std::pair{cur, -1},
                                      [](const auto& a, const auto& b) { return a.first < b.first; });
        for (auto it = range.first; it != range.second && next < 0; ++it) {
          const Open& o = open[std::size_t(it->second)];
          if (o.face == e.face) continue;
          const Face& g = faces_[std::size_t(o.face)];
          const int y = g.vertices[(std::size_t(o.k) + 1) % g.vertices.size()];
          if (y == u) {
            next = u;
            break;
          }
          const double t = (position(y) - pu).dot(d) / len2;
          const double slack = 4 * (err(u) + err(w) + err(y)) / std::sqrt(len2) + 1e-12;
          if (t >= cur_t + slack || t <= -slack) continue;  // must move towards u
          if (!vertex_on_plane(y, f.support) || !vertex_on_plane(y, f.edge_line[std::size_t(e.k)])) continue;
          if (!(t > slack && t < 1 - slack) && !exactly_between(u, y, w, line_axis(f.support, f.edge_line[std::size_t(e.k)]))) continue;
          next = y;
          next_t = t;
        }
        if (next < 0) break;
        if (next == u) {
          reached = true;
          break;
        }
        chain.push_back({next_t, next});
        cur = next;
        cur_t = next_t;
      }
      if (reached) {
        for (const auto& [t, v] : chain) inserts[std::size_t(e.face)].emplace_back(e.k, t, v);
      } else {
        unresolved.push_back(e);
      }
    }
    open = std::move(unresolved);
    if (open.empty()) {
      apply_inserts(inserts);
      return;
    }
    candidates.clear();
    for (const Open& e : open) {
      const Face& f = faces_[std::size_t(e.face)];
      candidates.push_back(f.vertices[std::size_t(e.k)]);
      candidates.push_back(f.vertices[(std::size_t(e.k) + 1) % f.vertices.size()]);
    }
    std::sort(candidates.begin(), candidates.end());
    candidates.erase(std::unique(candidates.begin(), candidates.end()), candidates.end());
    // Hash grid over the candidates with the median open-edge length as cell size.
    std::vector<double> lengths;
    for (const Open& e : open) {
      const Face& f = faces_[std::size_t(e.face)];
      lengths.push_back((position(f.vertices[(std::size_t(e.k) + 1) % f.vertices.size()]) - position(f.vertices[std::size_t(e.k)])).norm());
    }
    std::nth_element(lengths.begin(), lengths.begin() + std::ptrdiff_t(lengths.size() / 2), lengths.end());
    const double cell = std::max(lengths[lengths.size() / 2], 1e-6);
    auto cell_of = [cell](double x) { return std::int64_t(std::floor(x / cell)); };
    auto cell_key = [](std::int64_t x, std::int64_t y, std::int64_t z) {
      return std::uint64_t(x * 73856093) ^ std::uint64_t(y * 19349663) ^ std::uint64_t(z * 83492791);
    };
    std::vector<std::pair<std::uint64_t, int>> grid;  // (cell key, vertex), sorted
    grid.reserve(candidates.size());
    for (int c : candidates) {
      const Eigen::Vector3d p = position(c);
      grid.push_back({cell_key(cell_of(p.x()), cell_of(p.y()), cell_of(p.z())), c});
    }
    std::sort(grid.begin(), grid.end());
    // Open-addressing index: cell key -> its run [begin, end) in `grid` (one probe per cell
    // instead of a binary search through the whole grid).
    struct Slot {
      std::uint64_t key;
      std::uint32_t begin, end;  // end == 0: empty slot
    };
    std::size_t slots = 16;
    while (slots < 2 * grid.size()) slots *= 2;
    std::vector<Slot> index(slots, Slot{0, 0, 0});
    auto slot_of = [&](std::uint64_t k) { return std::size_t((k * 0x9E3779B97F4A7C15ull) >> 20) & (slots - 1); };
    for (std::size_t i = 0; i < grid.size();) {
      std::size_t j = i;
      while (j < grid.size() && grid[j].first == grid[i].first) ++j;
      std::size_t h = slot_of(grid[i].first);
      while (index[h].end != 0) h = (h + 1) & (slots - 1);
      index[h] = {grid[i].first, std::uint32_t(i), std::uint32_t(j)};
      i = j;
    }

    constexpr double kTol = 1e-3;  // grid units: a cheap prefilter only; the test is exact
    std::vector<int> near;
    for (const Open& e : open) {
      const Face& f = faces_[std::size_t(e.face)];
      const int u = f.vertices[std::size_t(e.k)], w = f.vertices[(std::size_t(e.k) + 1) % f.vertices.size()];
      const Eigen::Vector3d pu = position(u), pw = position(w), d = pw - pu;
      const double len2 = d.squaredNorm();
      const Eigen::Vector3d lo = pu.cwiseMin(pw).array() - kTol, hi = pu.cwiseMax(pw).array() + kTol;
      near.clear();
      const std::int64_t x0 = cell_of(lo.x()), x1 = cell_of(hi.x()), y0 = cell_of(lo.y()), y1 = cell_of(hi.y()),
                         z0 = cell_of(lo.z()), z1 = cell_of(hi.z());
      if ((x1 - x0 + 1) * (y1 - y0 + 1) * (z1 - z0 + 1) > std::int64_t(candidates.size())) {
        near = candidates;
      } else {
        for (std::int64_t x = x0; x <= x1; ++x)
          for (std::int64_t y = y0; y <= y1; ++y)
            for (std::int64_t z = z0; z <= z1; ++z) {
              const std::uint64_t ck = cell_key(x, y, z);
              for (std::size_t h = slot_of(ck); index[h].end != 0; h = (h + 1) & (slots - 1))
                if (index[h].key == ck) {
                  for (std::uint32_t g = index[h].begin; g < index[h].end; ++g) near.push_back(grid[g].second);
                  break;
                }
            }
        std::sort(near.begin(), near.end());
        near.erase(std::unique(near.begin(), near.end()), near.end());
      }
      for (const int c : near) {
        if (c == u || c == w) continue;
        const Eigen::Vector3d pc = position(c);
        const double t = (pc - pu).dot(d) / len2;
        const double slack = 4 * (err(u) + err(w) + err(c)) / std::sqrt(len2) + 1e-12;
        if (t <= -slack || t >= 1 + slack || (pu + t * d - pc).norm() > kTol) continue;
        if (!vertex_on_plane(c, f.support) || !vertex_on_plane(c, f.edge_line[std::size_t(e.k)])) continue;
        // On the line and distinct from u and w (exactly); strictly between them? Decide
        // exactly when the approximation is too close to call.
        if (!(t > slack && t < 1 - slack) && !exactly_between(u, c, w, line_axis(f.support, f.edge_line[std::size_t(e.k)]))) continue;
        inserts[std::size_t(e.face)].emplace_back(e.k, t, c);
      }
    }
    apply_inserts(inserts);
  }

  // Fragments of one oriented plane that share edges become one face when their union is a
  // simple polygon (one boundary loop); unions with holes keep their convex fragments.
  void merge_coplanar_faces() {
    // Group faces by oriented plane: equal planes may have several indices, so each plane index
    // gets a canonical id (planes sorted by value, the sign fixed by the first non-zero normal
    // coefficient) once, and faces are sorted by (id, orientation).
    const std::int32_t np = planes_.size();
    std::vector<kernel::Plane> normalized(static_cast<std::size_t>(np));
    std::vector<bool> negated(static_cast<std::size_t>(np), false);
    for (std::int32_t i = 0; i < np; ++i) {
      const kernel::Plane& p = planes_[i];
      const bool neg = p.a < 0 || (p.a == 0 && (p.b < 0 || (p.b == 0 && p.c < 0)));
      normalized[std::size_t(i)] = neg ? p.opposite() : p;
      negated[std::size_t(i)] = neg;
    }
    auto plane_less = [](const kernel::Plane& a, const kernel::Plane& b) {
      if (a.a != b.a) return a.a < b.a;
      if (a.b != b.b) return a.b < b.b;
      if (a.c != b.c) return a.c < b.c;
      return a.d < b.d;
    };
    std::vector<std::int32_t> order;  // the planes that support faces, by value
    {
      std::vector<bool> used(static_cast<std::size_t>(np), false);
      for (const Face& f : faces_) used[std::size_t(f.support)] = true;
      for (std::int32_t i = 0; i < np; ++i)
        if (used[std::size_t(i)]) order.push_back(i);
    }
    std::sort(order.begin(), order.end(), [&](std::int32_t x, std::int32_t y) {
      return plane_less(normalized[std::size_t(x)], normalized[std::size_t(y)]);
    });
    std::vector<std::uint32_t> canonical(static_cast<std::size_t>(np), 0);
    for (std::size_t k = 1; k < order.size(); ++k)
      canonical[std::size_t(order[k])] = canonical[std::size_t(order[k - 1])] +
          (normalized[std::size_t(order[k])] == normalized[std::size_t(order[k - 1])] ? 0 : 1);
    std::vector<std::pair<std::uint64_t, int>> by_plane;  // (2 id + orientation, face)
    by_plane.reserve(faces_.size());
    for (std::size_t fi = 0; fi < faces_.size(); ++fi) {
      const auto sp = std::size_t(faces_[fi].support);
      const bool orientation = negated[sp] != faces_[fi].flip;
      by_plane.push_back({2 * std::uint64_t(canonical[sp]) + (orientation ? 1 : 0), int(fi)});
    }
    std::sort(by_plane.begin(), by_plane.end());
    std::vector<bool> removed(faces_.size(), false);
    std::vector<Face> added;
    std::vector<std::pair<std::uint64_t, int>> edge;  // (u, w) -> local member index
    std::vector<int> members;
    for (std::size_t i = 0; i < by_plane.size();) {
      std::size_t j = i;
      while (j < by_plane.size() && by_plane[j].first == by_plane[i].first) ++j;
      if (j - i >= 2) {
        members.clear();
        for (std::size_t m = i; m < j; ++m) members.push_back(by_plane[m].second);
        merge_group(members, edge, removed, added);
      }
      i = j;
    }
    std::vector<Face> kept;
    kept.reserve(faces_.size());
    for (std::size_t fi = 0; fi < faces_.size(); ++fi)
      if (!removed[fi]) kept.push_back(std::move(faces_[fi]));
    for (Face& g : added) kept.push_back(std::move(g));
    faces_ = std::move(kept);
  }

  void merge_group(const std::vector<int>& members, std::vector<std::pair<std::uint64_t, int>>& edge,
                   std::vector<bool>& removed, std::vector<Face>& added) {
    edge.clear();
    for (std::size_t l = 0; l < members.size(); ++l) {
      const auto& v = faces_[std::size_t(members[l])].vertices;
      for (std::size_t k = 0; k < v.size(); ++k) edge.push_back({key(v[k], v[(k + 1) % v.size()]), int(l)});
    }
    std::sort(edge.begin(), edge.end());
    auto find = [&](std::uint64_t k) {
      auto it = std::lower_bound(edge.begin(), edge.end(), std::pair{k, -1});
      return it != edge.end() && it->first == k ? it->second : -1;
    };
    UnionFind uf(members.size());
    bool any = false;
    for (std::size_t l = 0; l < members.size(); ++l) {
      const auto& v = faces_[std::size_t(members[l])].vertices;
      for (std::size_t k = 0; k < v.size(); ++k) {
        const int other = find(key(v[(k + 1) % v.size()], v[k]));
        if (other >= 0) {
          uf.unite(int(l), other);
          any = true;
        }
      }
    }
    if (!any) return;
    std::vector<std::pair<int, int>> by_root;  // (root, local index)
    for (std::size_t l = 0; l < members.size(); ++l) by_root.push_back({uf.find(int(l)), int(l)});
    std::sort(by_root.begin(), by_root.end());
    struct Boundary {
      int u, w;
      std::int32_t line;
      bool operator<(const Boundary& o) const { return u < o.u; }
    };
    std::vector<Boundary> next;
    for (std::size_t a = 0; a < by_root.size();) {
      std::size_t b = a;
      while (b < by_root.size() && by_root[b].first == by_root[a].first) ++b;
      if (b - a >= 2) {
        next.clear();
        for (std::size_t c = a; c < b; ++c) {
          const Face& f = faces_[std::size_t(members[std::size_t(by_root[c].second)])];
          for (std::size_t k = 0; k < f.vertices.size(); ++k) {
            const int u = f.vertices[k], w = f.vertices[(k + 1) % f.vertices.size()];
            if (find(key(w, u)) < 0) next.push_back({u, w, f.edge_line[k]});
          }
        }
        std::sort(next.begin(), next.end());
        bool simple = next.size() >= 3;
        for (std::size_t c = 1; c < next.size() && simple; ++c) simple = next[c].u != next[c - 1].u;
        if (simple) {
          const Face& first_face = faces_[std::size_t(members[std::size_t(by_root[a].second)])];
          Face g;
          g.support = first_face.support;
          g.flip = first_face.flip;
          int u = next.front().u;
          do {
            const auto it = std::lower_bound(next.begin(), next.end(), Boundary{u, 0, 0});
            if (it == next.end() || it->u != u) break;
            g.vertices.push_back(u);
            g.edge_line.push_back(it->line);
            u = it->w;
          } while (u != next.front().u && g.vertices.size() <= next.size());
          if (g.vertices.size() == next.size()) {  // one loop: a simple polygon
            for (std::size_t c = a; c < b; ++c) removed[std::size_t(members[std::size_t(by_root[c].second)])] = true;
            added.push_back(std::move(g));
          }
        }
      }
      a = b;
    }
  }

  // A vertex with exactly two neighbours, lying exactly on the line of its two edges, is a
  // leftover of fragmentation: removed from both faces that use it.
  void remove_straight_vertices() {
    // Exactly two distinct neighbours per vertex: keep the first two seen, mark a third.
    std::vector<std::array<int, 2>> seen(rep_.size(), {-1, -1});
    std::vector<bool> more(rep_.size(), false);
    auto link = [&](int v, int w) {
      auto& sv = seen[std::size_t(v)];
      if (sv[0] == w || sv[1] == w) return;
      if (sv[0] < 0)
        sv[0] = w;
      else if (sv[1] < 0)
        sv[1] = w;
      else
        more[std::size_t(v)] = true;
    };
    for (const Face& f : faces_)
      for (std::size_t k = 0; k < f.vertices.size(); ++k) {
        const int u = f.vertices[k], w = f.vertices[(k + 1) % f.vertices.size()];
        link(u, w);
        link(w, u);
      }
    std::vector<bool> removable(rep_.size(), false);
    for (std::size_t v = 0; v < rep_.size(); ++v) removable[v] = seen[v][1] >= 0 && !more[v];
    // A vertex goes only if it is straight in every face that uses it (both faces agree).
    auto straight = [&](const Face& f, std::size_t k) {
      const std::size_t m = f.vertices.size();
      if (m <= 3) return false;
      const int w = f.vertices[(k + 1) % m];
      const std::int32_t in_line = f.edge_line[(k + m - 1) % m];
      return vertex_on_plane(w, in_line) && vertex_on_plane(w, f.support);
    };
    for (const Face& f : faces_)
      for (std::size_t k = 0; k < f.vertices.size(); ++k)
        if (removable[std::size_t(f.vertices[k])] && !straight(f, k)) removable[std::size_t(f.vertices[k])] = false;
    for (Face& f : faces_) {
      if (std::none_of(f.vertices.begin(), f.vertices.end(), [&](int v) { return removable[std::size_t(v)]; })) continue;
      Face g;
      g.support = f.support;
      g.flip = f.flip;
      for (std::size_t k = 0; k < f.vertices.size(); ++k) {
        if (removable[std::size_t(f.vertices[k])]) continue;  // the incoming edge line goes on
        g.vertices.push_back(f.vertices[k]);
        g.edge_line.push_back(f.edge_line[k]);
      }
      if (g.vertices.size() >= 3) f = std::move(g);
    }
  }

  void apply_inserts(std::vector<std::vector<std::tuple<int, double, int>>>& inserts) {
    for (std::size_t fi = 0; fi < faces_.size(); ++fi) {
      auto& ins = inserts[fi];
      if (ins.empty()) continue;
      Face& f = faces_[fi];
      // Order along each edge exactly (vertices closer than their approximation errors occur
      // with re-quantized planes): by edge, then by the coordinate along the line's main axis.
      std::sort(ins.begin(), ins.end(), [&](const auto& x, const auto& y) {
        const int kx = std::get<0>(x), ky = std::get<0>(y);
        if (kx != ky) return kx < ky;
        const int vx = std::get<2>(x), vy = std::get<2>(y);
        if (vx == vy) return false;
        const int axis = line_axis(f.support, f.edge_line[std::size_t(kx)]);
        const int u = f.vertices[std::size_t(kx)], w = f.vertices[(std::size_t(kx) + 1) % f.vertices.size()];
        return less_along(u, w, axis) ? less_along(vx, vy, axis) : less_along(vy, vx, axis);
      });
      ins.erase(std::unique(ins.begin(), ins.end(), [](const auto& x, const auto& y) {
                  return std::get<0>(x) == std::get<0>(y) && std::get<2>(x) == std::get<2>(y);
                }), ins.end());
      Face g;
      g.support = f.support;
      g.flip = f.flip;
      std::size_t next = 0;
      for (std::size_t k = 0; k < f.vertices.size(); ++k) {
        g.vertices.push_back(f.vertices[k]);
        g.edge_line.push_back(f.edge_line[k]);
        for (; next < ins.size() && std::get<0>(ins[next]) == int(k); ++next) {
          g.vertices.push_back(std::get<2>(ins[next]));
          g.edge_line.push_back(f.edge_line[k]);
        }
      }
      f = std::move(g);
    }
  }

  Eigen::Vector3d outward_normal(const Face& f) const {
    const Eigen::Vector3d n = planes_[f.support].normal().normalized();
    return f.flip ? Eigen::Vector3d(-n) : n;
  }

  // Pairs each half-edge with its opposite; around an edge shared by more than two faces, the
  // pairs are the faces bounding the same inside wedge (angular order about the edge). Then
  // corners connected through paired edges share a vertex; other corners get a copy.
  void split_non_manifold() {
    struct HalfEdge {
      std::uint64_t undirected;
      int face, k;
      bool forward;  // from the smaller to the larger vertex id
    };
    std::vector<HalfEdge> hs;
    corner_start_.clear();
    int corners = 0;
    for (std::size_t fi = 0; fi < faces_.size(); ++fi) {
      corner_start_.push_back(corners);
      const auto& v = faces_[fi].vertices;
      corners += int(v.size());
      for (std::size_t k = 0; k < v.size(); ++k) {
        const int u = v[k], w = v[(k + 1) % v.size()];
        hs.push_back({key(std::min(u, w), std::max(u, w)), int(fi), int(k), u < w});
      }
    }
    std::sort(hs.begin(), hs.end(), [](const HalfEdge& a, const HalfEdge& b) { return a.undirected < b.undirected; });
    UnionFind uf{static_cast<std::size_t>(corners)};
    auto corner = [&](int face, int k) {
      const int m = int(faces_[std::size_t(face)].vertices.size());
      return corner_start_[std::size_t(face)] + ((k % m) + m) % m;
    };
    auto pair = [&](const HalfEdge& a, const HalfEdge& b) {  // a: u -> w, b: w -> u
      uf.unite(corner(a.face, a.k), corner(b.face, b.k + 1));
      uf.unite(corner(a.face, a.k + 1), corner(b.face, b.k));
    };
    for (std::size_t i = 0; i < hs.size();) {
      std::size_t j = i;
      while (j < hs.size() && hs[j].undirected == hs[i].undirected) ++j;
      if (j - i == 2 && hs[i].forward != hs[i + 1].forward) {
        pair(hs[i], hs[i + 1]);
      } else if (j - i > 2) {
        pair_around_edge(std::vector<HalfEdge>(hs.begin() + std::ptrdiff_t(i), hs.begin() + std::ptrdiff_t(j)), pair);
      } else {
        ++unpaired_;
      }
      i = j;
    }
    // One vertex per (vertex, corner class).
    std::vector<int> class_vertex(std::size_t(corners), -1);
    std::vector<int> first_class(rep_.size(), -1);
    for (std::size_t fi = 0; fi < faces_.size(); ++fi) {
      auto& v = faces_[fi].vertices;
      for (std::size_t k = 0; k < v.size(); ++k) {
        const int root = uf.find(corner_start_[fi] + int(k));
        if (class_vertex[std::size_t(root)] < 0) {
          if (first_class[std::size_t(v[k])] < 0) {
            first_class[std::size_t(v[k])] = root;
            class_vertex[std::size_t(root)] = v[k];
          } else {
            class_vertex[std::size_t(root)] = int(rep_.size());
            rep_.push_back(rep_[std::size_t(v[k])]);
            at_.push_back(at_[std::size_t(v[k])]);
          }
        }
        v[k] = class_vertex[std::size_t(root)];
      }
    }
  }

  template <typename HalfEdge, typename Pair>
  void pair_around_edge(std::vector<HalfEdge> group, Pair&& pair) {
    // Axis from the smaller to the larger vertex id.
    const HalfEdge& h0 = group[0];
    const auto& v0 = faces_[std::size_t(h0.face)].vertices;
    const int a = v0[std::size_t(h0.k)], b = v0[(std::size_t(h0.k) + 1) % v0.size()];
    const int lo = std::min(a, b), hi = std::max(a, b);
    const Eigen::Vector3d p = position(lo), axis = (position(hi) - p).normalized();
    Eigen::Vector3d e1 = axis.unitOrthogonal(), e2 = axis.cross(e1);
    struct Item {
      double angle;
      bool in_after;
      std::size_t index;
    };
    std::vector<Item> items;
    for (std::size_t i = 0; i < group.size(); ++i) {
      const Face& f = faces_[std::size_t(group[i].face)];
      const Eigen::Vector3d n = outward_normal(f);
      Eigen::Vector3d r = axis.cross(n);  // in the face plane, perpendicular to the edge
      // Orient r into the face: the face interior is to the left of its directed edge.
      const auto& v = f.vertices;
      const Eigen::Vector3d dir = position(v[(std::size_t(group[i].k) + 1) % v.size()]) - position(v[std::size_t(group[i].k)]);
      const Eigen::Vector3d left = n.cross(dir);
      if (r.dot(left) < 0) r = -r;
      const double angle = std::atan2(r.dot(e2), r.dot(e1));
      const Eigen::Vector3d t = axis.cross(r);
      items.push_back({angle, n.dot(t) < 0, i});
    }
    std::sort(items.begin(), items.end(), [](const Item& x, const Item& y) { return x.angle < y.angle; });
    const std::size_t m = items.size();
    std::vector<bool> used(m, false);
    for (std::size_t i = 0; i < m; ++i) {
      if (!items[i].in_after || used[i]) continue;
      const std::size_t j = (i + 1) % m;
      if (used[j] || items[j].in_after) {
        ++unpaired_;
        continue;
      }
      const HalfEdge& x = group[items[i].index];
      const HalfEdge& y = group[items[j].index];
      if (x.forward == y.forward) {
        ++unpaired_;
        continue;
      }
      used[i] = used[j] = true;
      pair(x, y);
    }
  }

  PolygonMesh output(bool triangulate) const {
    PolygonMesh mesh;
    std::vector<int> index(rep_.size(), -1);  // only referenced vertices are written
    for (const Face& f : faces_)
      for (int v : f.vertices)
        if (index[std::size_t(v)] < 0) {
          index[std::size_t(v)] = int(mesh.vertices.size());
          mesh.vertices.push_back(position(v) * kernel::kGridStep);
        }
    for (Face f : faces_) {
      for (int& v : f.vertices) v = index[std::size_t(v)];
      if (!triangulate || f.vertices.size() == 3) {
        mesh.faces.push_back(f.vertices);
        continue;
      }
      for (const auto& t : triangulate_face(mesh.vertices, f.vertices, outward_normal(f)))
        mesh.faces.push_back({t[0], t[1], t[2]});
    }
    return mesh;
  }

  const Fragments& f_;
  const kernel::PlaneTable& planes_;
  std::vector<Occurrence> occ_;
  std::vector<int> start_;
  std::vector<int> vertex_of_;  // occurrence -> vertex
  std::vector<int> rep_;        // vertex -> representative occurrence
  std::vector<ApproxPoint> at_;  // vertex -> approximation (that of its representative)
  std::vector<int> occ_start_, occ_list_;  // occurrences of each vertex (before duplication)
  std::vector<Face> faces_;
  std::vector<int> corner_start_;
  int unpaired_ = 0;
};

}  // namespace

PolygonMesh assemble_mesh(const Fragments& fragments, const AssemblyOptions& options) {
  return Assembler(fragments).run(options.triangulate);
}

}  // namespace sculpt::detail
