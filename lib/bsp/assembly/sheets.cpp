#include "bsp/assembly/sheets.hpp"

#include <algorithm>
#include <cmath>

#include <Eigen/Geometry>

#include "base/parallel.hpp"
#include "mesh/triangulate.hpp"

namespace sculpt::bsp::detail {

namespace {

Eigen::Vector3d outward_normal(const FaceList& faces, int f, const kernel::PlaneTable& planes) {
  const Eigen::Vector3d n = planes[faces.support[std::size_t(f)]].normal().normalized();
  return faces.flip[std::size_t(f)] != 0 ? Eigen::Vector3d(-n) : n;
}

struct HalfEdge {  // in the run of its smaller vertex
  int other;        // the larger vertex (the undirected edge is smaller -> other)
  int face, corner;
  int forward;  // 1: from the smaller to the larger vertex id
};

class SheetSplitter {
 public:
  SheetSplitter(FaceList& faces, const AssemblyVertices& vertices, const kernel::PlaneTable& planes)
      : f_(faces), v_(vertices), planes_(planes), uf_(std::size_t(faces.corners())) {}

  std::vector<int> run() {
    // Half-edges grouped by undirected edge: counting sort by the smaller vertex (each run
    // filled from its end: no separate fill array; runs keep the corner order), then each run
    // sorted by the larger vertex (as before: insertion sort, std::sort above 16).
    const std::size_t nv = v_.at.size();
    std::vector<int> start(nv + 1, 0);
    for (int f = 0; f < f_.size(); ++f)
      for (int c = f_.begin(f); c < f_.end(f); ++c)
        ++start[std::size_t(std::min(f_.vertex[std::size_t(c)], f_.vertex[std::size_t(f_.next(f, c))]))];
    for (std::size_t v = 0; v < nv; ++v) start[v + 1] += start[v];  // start[v] = end of v's run
    std::vector<HalfEdge> hs(std::size_t(f_.corners()));
    for (int f = f_.size() - 1; f >= 0; --f)  // backwards, so each run keeps the corner order
      for (int c = f_.end(f) - 1; c >= f_.begin(f); --c) {
        const int u = f_.vertex[std::size_t(c)], w = f_.vertex[std::size_t(f_.next(f, c))];
        hs[std::size_t(--start[std::size_t(std::min(u, w))])] = {std::max(u, w), f, c, u < w ? 1 : 0};
      }
    for (std::size_t v = 0; v < nv; ++v) {
      const int b = start[v], e = start[v + 1];
      if (e - b > 16) {  // (std::sort sorts up to 16 elements by insertion too)
        std::sort(hs.begin() + b, hs.begin() + e, [](const HalfEdge& x, const HalfEdge& y) { return x.other < y.other; });
        continue;
      }
      for (int i = b + 1; i < e; ++i) {  // short runs: insertion sort inline
        const HalfEdge h = hs[std::size_t(i)];
        int j = i;
        for (; j > b && hs[std::size_t(j) - 1].other > h.other; --j) hs[std::size_t(j)] = hs[std::size_t(j) - 1];
        hs[std::size_t(j)] = h;
      }
    }
    // Edges with two half-edges pair directly; edges with more (the solid touches itself along
    // them) pair around the edge, across the solid's wedges by default. Where that leaves two
    // pairs of one edge between the same vertex classes at both ends (the sheets meet again at
    // both end vertices, so no duplication separates them), the edge pairs across the outside
    // wedges instead, and the classes are recomputed (a few rounds at most).
    std::vector<std::pair<std::size_t, std::size_t>> crowded;  // [begin, end) in hs
    for (std::size_t v = 0; v < nv; ++v)
      for (std::size_t i = std::size_t(start[v]), e = std::size_t(start[v + 1]); i < e;) {
        std::size_t j = i + 1;
        while (j < e && hs[j].other == hs[i].other) ++j;
        if (j - i == 2 && hs[i].forward != hs[i + 1].forward)
          pair(hs[i], hs[i + 1]);
        else if (j - i > 2)
          crowded.emplace_back(i, j);
        i = j;
      }
    if (!crowded.empty()) {
      const UnionFind manifold = uf_;  // the classes from the two-face edges alone
      std::vector<bool> outside(crowded.size(), false);
      for (int round = 0; round < 4; ++round) {
        uf_ = manifold;
        for (std::size_t k = 0; k < crowded.size(); ++k)
          pair_around_edge(std::vector<HalfEdge>(hs.begin() + std::ptrdiff_t(crowded[k].first),
                                                 hs.begin() + std::ptrdiff_t(crowded[k].second)),
                           outside[k]);
        bool changed = false;
        for (std::size_t k = 0; k < crowded.size(); ++k)
          if (pinched(hs, crowded[k])) outside[k] = !outside[k], changed = true;
        if (!changed) break;
      }
    }
    // One vertex per (vertex, corner class): the first class keeps the vertex id.
    std::vector<int> original(v_.at.size());
    for (std::size_t i = 0; i < original.size(); ++i) original[i] = int(i);
    std::vector<int> class_vertex(std::size_t(f_.corners()), -1);
    std::vector<std::uint8_t> taken(v_.at.size(), 0);
    for (std::size_t c = 0; c < f_.vertex.size(); ++c) {
      int& v = f_.vertex[c];
      int& mine = class_vertex[std::size_t(uf_.find(int(c)))];
      if (mine < 0) {
        if (taken[std::size_t(v)] == 0) {
          taken[std::size_t(v)] = 1;
          mine = v;
        } else {
          mine = int(original.size());
          original.push_back(v);
        }
      }
      v = mine;
    }
    return original;
  }

 private:
  void pair(const HalfEdge& a, const HalfEdge& b) {  // a: u -> w, b: w -> u
    uf_.unite(a.corner, f_.next(b.face, b.corner));
    uf_.unite(f_.next(a.face, a.corner), b.corner);
  }

  // True if two half-edges of the group join the same vertex classes (the edge would appear twice).
  bool pinched(const std::vector<HalfEdge>& hs, std::pair<std::size_t, std::size_t> range) {
    std::vector<std::uint64_t> keys;
    for (std::size_t i = range.first; i < range.second; ++i) {
      const HalfEdge& h = hs[i];
      const int from = uf_.find(h.corner), to = uf_.find(f_.next(h.face, h.corner));
      keys.push_back(edge_key(from, to));
    }
    std::sort(keys.begin(), keys.end());
    return std::adjacent_find(keys.begin(), keys.end()) != keys.end();
  }

  // Pairs the faces around an edge with more than two: each face with its neighbour across a
  // wedge inside the solid, or (`outside`) across a wedge outside it.
  void pair_around_edge(const std::vector<HalfEdge>& group, bool outside) {
    // Directions from the planes alone: an edge can be shorter than the doubles' resolution (two
    // exact vertices of re-quantized planes that round to the same coordinates), so no vertex
    // position is used. Near the edge, each face lies in its support plane on the negative side
    // of its edge's line plane; the edge runs along support x line.
    const HalfEdge& h0 = group[0];
    const Eigen::Vector3d axis =
        unit_normal(f_.support[std::size_t(h0.face)]).cross(unit_normal(f_.line[std::size_t(h0.corner)])).normalized();
    const Eigen::Vector3d e1 = axis.unitOrthogonal(), e2 = axis.cross(e1);
    struct Item {
      double angle;
      bool in_after;
      std::size_t index;
    };
    std::vector<Item> items;
    for (std::size_t i = 0; i < group.size(); ++i) {
      const int f = group[i].face;
      const Eigen::Vector3d n = outward_normal(f_, f, planes_);
      const Eigen::Vector3d s = unit_normal(f_.support[std::size_t(f)]), l = unit_normal(f_.line[std::size_t(group[i].corner)]);
      const Eigen::Vector3d r = (s * l.dot(s) - l).normalized();  // in the face plane, into the face
      const double angle = std::atan2(r.dot(e2), r.dot(e1));
      items.push_back({angle, n.dot(axis.cross(r)) < 0, i});
    }
    std::sort(items.begin(), items.end(), [](const Item& x, const Item& y) { return x.angle < y.angle; });
    const std::size_t m = items.size();
    std::vector<bool> used(m, false);
    for (std::size_t i = 0; i < m; ++i) {
      if (items[i].in_after == outside || used[i]) continue;
      const std::size_t j = (i + 1) % m;
      if (used[j] || items[j].in_after != outside) continue;
      const HalfEdge& x = group[items[i].index];
      const HalfEdge& y = group[items[j].index];
      if (x.forward == y.forward) continue;
      used[i] = used[j] = true;
      pair(x, y);
    }
  }

  Eigen::Vector3d unit_normal(std::int32_t plane) const { return planes_[plane].normal().normalized(); }

  FaceList& f_;
  const AssemblyVertices& v_;
  const kernel::PlaneTable& planes_;
  UnionFind uf_;  // over corners
};

}  // namespace

Sheets split_non_manifold(FaceList faces, const AssemblyVertices& vertices, const kernel::PlaneTable& planes) {
  std::vector<int> original = SheetSplitter(faces, vertices, planes).run();
  return {std::move(faces), std::move(original)};
}

bool exactly_represented(const kernel::Plane& p, const kernel::Plane& q, const kernel::Plane& r,
                         const Eigen::Vector3d& at) {
  const kernel::ApproxPoint point{.x = at.x(), .y = at.y(), .z = at.z(), .err = 0};
  for (const kernel::Plane* s : {&p, &q, &r})  // off a plane for sure: not the vertex
    if (kernel::filtered_orient(point, *s) != kernel::Sign::Zero) return false;
  constexpr double kLimit = 0x1p53;
  for (int axis = 0; axis < 3; ++axis)
    if (!(std::fabs(at[axis]) < kLimit) || std::floor(at[axis]) != at[axis]) return false;
  const kernel::GridPoint g{.x = std::int64_t(at.x()), .y = std::int64_t(at.y()), .z = std::int64_t(at.z())};
  return kernel::orient(g, p) == kernel::Sign::Zero && kernel::orient(g, q) == kernel::Sign::Zero &&
         kernel::orient(g, r) == kernel::Sign::Zero;
}

PolygonMesh output_mesh(const Sheets& sheets, const AssemblyVertices& vertices, const kernel::PlaneTable& planes,
                        const OutputMeshOptions& options) {
  const FaceList& faces = sheets.faces;
  const bool triangulate = options.triangulate;
  const kernel::Grid& grid = options.grid;
  std::vector<char>* const exact = options.exact;
  PolygonMesh mesh;
  if (exact != nullptr) exact->clear();
  // Only referenced vertices are written, numbered in the order of their first corner.
  std::vector<int> index(sheets.original.size(), -1);
  std::vector<int> written;  // output vertex -> sheet vertex
  written.reserve(sheets.original.size());
  for (const int v : faces.vertex)
    if (index[std::size_t(v)] < 0) {
      index[std::size_t(v)] = int(written.size());
      written.push_back(v);
    }
  // Each vertex correctly rounded, independently of the others: in parallel, the same values for
  // any thread count.
  mesh.vertices.resize(written.size());
  if (exact != nullptr) exact->assign(written.size(), 0);
  parallel_chunks(written.size(), 8192, [&](std::size_t begin, std::size_t end) {
    for (std::size_t i = begin; i < end; ++i) {
      const std::size_t o = std::size_t(sheets.original[std::size_t(written[i])]);
      const PlaneTriple& t = vertices.triple[o];
      const kernel::ApproxPoint& a = vertices.at[o];
      const bool approximated = options.approximate && a.err >= 0 && a.err <= kDisplayError;
      const Eigen::Vector3d at = approximated ? Eigen::Vector3d(a.x, a.y, a.z)
                                              : kernel::rounded_vertex(planes[t.s], planes[t.p], planes[t.q], a);
      // World units = grid units times a power of two: exact (the grid's range is far from
      // overflow and underflow), so a vertex exact in grid units is exact in world units.
      mesh.vertices[i] = grid.to_world(at);
      if (exact != nullptr)
        (*exact)[i] = (!approximated || a.err == 0) && exactly_represented(planes[t.s], planes[t.p], planes[t.q], at);
    }
  });
  mesh.faces.reserve(std::size_t(faces.size()));
  std::vector<int> face;
  for (int f = 0; f < faces.size(); ++f) {
    if (!triangulate || faces.count(f) == 3) {  // written in place (allocates exactly the face's size)
      std::vector<int>& out = mesh.faces.emplace_back(std::size_t(faces.count(f)));
      for (int c = faces.begin(f), k = 0; c < faces.end(f); ++c, ++k) out[std::size_t(k)] = index[std::size_t(faces.vertex[std::size_t(c)])];
      continue;
    }
    face.clear();
    for (int c = faces.begin(f); c < faces.end(f); ++c) face.push_back(index[std::size_t(faces.vertex[std::size_t(c)])]);
    // An ear of the rounded polygon can reach outside the exact face even when its own corners
    // are exact: a triangle is taken for a piece of the exact face only when the whole polygon is
    // exact (its triangulation is then that of the exact face), so a rounded corner unmarks all.
    if (exact != nullptr && std::any_of(face.begin(), face.end(), [&](int v) { return (*exact)[std::size_t(v)] == 0; }))
      for (const int v : face) (*exact)[std::size_t(v)] = 0;
    for (const IndexTriangle& t : triangulate_polygon(mesh.vertices, face))
      mesh.faces.push_back({t[0], t[1], t[2]});
  }
  return mesh;
}

}  // namespace sculpt::bsp::detail
