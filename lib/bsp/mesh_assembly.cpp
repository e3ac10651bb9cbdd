#include "bsp/mesh_assembly.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>

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
    split_non_manifold();
    return output(triangulate);
  }

 private:
  bool on_plane(const Occurrence& o, std::int32_t plane) const {
    return kernel::orient(planes_[o.s], planes_[o.p], planes_[o.q], o.at, planes_[plane]) == Sign::Zero;
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

  // Exact vertex merging: candidates by a sweep over x within the approximation error bounds,
  // equality decided exactly (the first vertex lies on the three planes of the second).
  void merge_vertices() {
    const std::size_t n = occ_.size();
    std::vector<int> order(n);
    std::iota(order.begin(), order.end(), 0);
    std::sort(order.begin(), order.end(), [&](int a, int b) { return occ_[std::size_t(a)].at.x < occ_[std::size_t(b)].at.x; });
    double max_err = 0;
    for (const auto& o : occ_) max_err = std::max(max_err, o.at.err);
    UnionFind uf(n);
    for (std::size_t ii = 0; ii < n; ++ii) {
      const Occurrence& a = occ_[std::size_t(order[ii])];
      for (std::size_t jj = ii + 1; jj < n; ++jj) {
        const Occurrence& b = occ_[std::size_t(order[jj])];
        const double tol = a.at.err + b.at.err;
        if (b.at.x - a.at.x > a.at.err + max_err) break;
        if (std::fabs(b.at.x - a.at.x) > tol || std::fabs(b.at.y - a.at.y) > tol || std::fabs(b.at.z - a.at.z) > tol)
          continue;
        if (uf.find(order[ii]) == uf.find(order[jj])) continue;
        if (same_point(a, b)) uf.unite(order[ii], order[jj]);
      }
    }
    vertex_of_.assign(n, -1);
    for (std::size_t i = 0; i < n; ++i) {
      const int r = uf.find(int(i));
      if (vertex_of_[std::size_t(r)] < 0) {
        vertex_of_[std::size_t(r)] = int(rep_.size());
        rep_.push_back(r);
      }
      vertex_of_[i] = vertex_of_[std::size_t(r)];
    }
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
    const ApproxPoint& a = occ_[std::size_t(rep_[std::size_t(v)])].at;
    return {a.x, a.y, a.z};
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
    std::sort(candidates.begin(), candidates.end());
    candidates.erase(std::unique(candidates.begin(), candidates.end()), candidates.end());
    std::sort(candidates.begin(), candidates.end(), [&](int a, int b) { return position(a).x() < position(b).x(); });
    std::vector<double> xs;
    for (int c : candidates) xs.push_back(position(c).x());

    // inserts[face] = list of (edge k, t, vertex)
    std::vector<std::vector<std::tuple<int, double, int>>> inserts(faces_.size());
    constexpr double kTol = 1e-3;  // grid units: a cheap prefilter only; the test is exact
    for (const Open& e : open) {
      const Face& f = faces_[std::size_t(e.face)];
      const int u = f.vertices[std::size_t(e.k)], w = f.vertices[(std::size_t(e.k) + 1) % f.vertices.size()];
      const Eigen::Vector3d pu = position(u), pw = position(w), d = pw - pu;
      const double len2 = d.squaredNorm();
      const double lo = std::min(pu.x(), pw.x()) - kTol, hi = std::max(pu.x(), pw.x()) + kTol;
      for (auto it = std::lower_bound(xs.begin(), xs.end(), lo); it != xs.end() && *it <= hi; ++it) {
        const int c = candidates[std::size_t(it - xs.begin())];
        if (c == u || c == w) continue;
        const Eigen::Vector3d pc = position(c);
        const double t = (pc - pu).dot(d) / len2;
        if (!(t > 0 && t < 1) || (pu + t * d - pc).norm() > kTol) continue;
        const Occurrence& o = occ_[std::size_t(rep_[std::size_t(c)])];
        if (on_plane(o, f.support) && on_plane(o, f.edge_line[std::size_t(e.k)]))
          inserts[std::size_t(e.face)].emplace_back(e.k, t, c);
      }
    }
    for (std::size_t fi = 0; fi < faces_.size(); ++fi) {
      auto& ins = inserts[fi];
      if (ins.empty()) continue;
      std::sort(ins.begin(), ins.end());
      Face& f = faces_[fi];
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
    mesh.vertices.reserve(rep_.size());
    for (std::size_t v = 0; v < rep_.size(); ++v) mesh.vertices.push_back(position(int(v)) * kernel::kGridStep);
    for (const Face& f : faces_) {
      if (!triangulate || f.vertices.size() == 3) {
        mesh.faces.push_back(f.vertices);
        continue;
      }
      // Convex polygon, possibly with collinear vertices: clip strictly convex ears only.
      const Eigen::Vector3d n = outward_normal(f);
      std::vector<int> poly = f.vertices;
      while (poly.size() > 3) {
        bool clipped = false;
        for (std::size_t i = 0; i < poly.size() && !clipped; ++i) {
          const std::size_t m = poly.size();
          const Eigen::Vector3d a = position(poly[(i + m - 1) % m]), b = position(poly[i]), c = position(poly[(i + 1) % m]);
          const Eigen::Vector3d cr = (b - a).cross(c - b);
          if (cr.dot(n) > 1e-9 * (b - a).norm() * (c - b).norm()) {
            mesh.faces.push_back({poly[(i + m - 1) % m], poly[i], poly[(i + 1) % m]});
            poly.erase(poly.begin() + std::ptrdiff_t(i));
            clipped = true;
          }
        }
        if (!clipped) break;
      }
      mesh.faces.push_back(poly);
    }
    return mesh;
  }

  const Fragments& f_;
  const kernel::PlaneTable& planes_;
  std::vector<Occurrence> occ_;
  std::vector<int> start_;
  std::vector<int> vertex_of_;  // occurrence -> vertex
  std::vector<int> rep_;        // vertex -> representative occurrence
  std::vector<Face> faces_;
  std::vector<int> corner_start_;
  int unpaired_ = 0;
};

}  // namespace

PolygonMesh assemble_mesh(const Fragments& fragments, const AssemblyOptions& options) {
  return Assembler(fragments).run(options.triangulate);
}

}  // namespace sculpt::detail
