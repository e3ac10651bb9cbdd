#include "bsp/assembly/junction_removal.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

#include <Eigen/Core>

namespace sculpt::bsp::detail {

namespace {

struct OpenEdge {
  int face, corner;    // the half-edge leaves corner `corner` of face `face`
  int u, w;            // from u to w
  std::uint64_t line;  // canonical ids of the support and the edge plane, sorted: the same key is the same line
};

class JunctionRemover {
 public:
  JunctionRemover(const FaceList& faces, const VertexGeometry& geometry, const PlaneIds& ids)
      : f_(faces), g_(geometry), ids_(ids), index_(faces, geometry.vertex_count()) {}

  // Finds the inserts; false if every half-edge has an opposite (nothing to do).
  bool run(const JunctionOptions& options, JunctionResult& result) {
    find_open();
    result.open = int(open_.size());
    if (open_.empty()) return false;
    ins_begin_.assign(open_.size(), 0);
    ins_end_.assign(open_.size(), 0);
    matched_.assign(open_.size(), 0);
    if (options.group_by_lines) group_by_lines();
    std::vector<int> failing;
    for (std::size_t i = 0; i < open_.size(); ++i)
      if (matched_[i] == 0) failing.push_back(int(i));
    result.by_search = int(failing.size());
    result.by_lines = result.open - result.by_search;
    if (!failing.empty()) search(failing);
    return true;
  }

  // Inserts the found vertices into `faces` (the face list this remover was built on), in
  // place: the arrays grow at the back and runs of corners between open edges move towards it,
  // the last face first (a run never moves onto corners not yet moved).
  void apply(FaceList& faces) const {
    const std::size_t total = faces.vertex.size() + ins_.size();
    faces.vertex.resize(total);
    faces.line.resize(total);
    auto move = [&](int from, int to, std::size_t end) {  // corners [from, to) to end at `end`
      std::copy_backward(faces.vertex.begin() + from, faces.vertex.begin() + to, faces.vertex.begin() + std::ptrdiff_t(end));
      std::copy_backward(faces.line.begin() + from, faces.line.begin() + to, faces.line.begin() + std::ptrdiff_t(end));
    };
    std::size_t o = open_.size(), at = total;  // open edges are in corner order
    int end = faces.start.back();              // the old end of face f
    faces.start.back() = int(total);
    for (int f = faces.size() - 1; f >= 0; --f) {
      const int begin = faces.start[std::size_t(f)];
      int c = end;  // corners [begin, c) not moved yet
      for (; o > 0 && open_[o - 1].corner >= begin; --o) {
        const int corner = open_[o - 1].corner;
        move(corner + 1, c, at);
        at -= std::size_t(c - corner - 1);
        c = corner + 1;
        const std::int32_t line = faces.line[std::size_t(corner)];
        for (int k = ins_end_[o - 1]; k > ins_begin_[o - 1]; --k) {
          --at;
          faces.vertex[at] = ins_[std::size_t(k) - 1];
          faces.line[at] = line;
        }
      }
      move(begin, c, at);
      at -= std::size_t(c - begin);
      faces.start[std::size_t(f)] = int(at);
      end = begin;
    }
  }

 private:
  int next_vertex(int f, int c) const { return f_.vertex[std::size_t(f_.next(f, c))]; }

  void find_open() {
    open_.reserve(f_.vertex.size() / 8 + 16);  // (a guess: growing from empty allocates often)
    for (int f = 0; f < f_.size(); ++f)
      for (int c = f_.begin(f); c < f_.end(f); ++c) {
        const int u = f_.vertex[std::size_t(c)], w = next_vertex(f, c);
        if (index_.find(w, u) >= 0) continue;
        std::uint32_t a = ids_.id[std::size_t(f_.support[std::size_t(f)])], b = ids_.id[std::size_t(f_.line[std::size_t(c)])];
        if (a > b) std::swap(a, b);
        open_.push_back({f, c, u, w, std::uint64_t(a) << 32 | b});
      }
  }

  // Exact: the far endpoint x of another half-edge lies on the line of open edge e. The
  // floating-point filter first: most vertices tested are clearly off the line.
  bool on_line(const OpenEdge& e, int x) const {
    return on_line(f_.support[std::size_t(e.face)], f_.line[std::size_t(e.corner)], x);
  }
  // Exact: vertex x lies on the line support ∩ line.
  bool on_line(std::int32_t support, std::int32_t line, int x) const {
    const kernel::ApproxPoint& at = g_.at(x);
    if (kernel::filtered_orient(at, g_.planes()[line]) != kernel::Sign::Zero ||
        kernel::filtered_orient(at, g_.planes()[support]) != kernel::Sign::Zero)
      return false;
    return g_.on_plane(x, line) && g_.on_plane(x, support);
  }

  // Groups of collinear open edges; each edge gets the group's vertices strictly inside it.
  void group_by_lines() {
    const std::size_t n = open_.size();
    UnionFind uf(n);
    {  // the same pair of planes: the same line
      EdgeIndex by_line(n);
      for (std::size_t i = 0; i < n; ++i) {
        const int first = by_line.find(open_[i].line);
        if (first >= 0) uf.unite(first, int(i));
        by_line.insert(open_[i].line, int(i));
      }
    }
    // Open edges at a common vertex on different plane pairs: joined when exactly collinear.
    const std::size_t nv = std::size_t(g_.vertex_count());
    std::vector<int> at_start(nv + 1, 0);
    for (const OpenEdge& e : open_) ++at_start[std::size_t(e.u) + 1], ++at_start[std::size_t(e.w) + 1];
    for (std::size_t v = 0; v < nv; ++v) at_start[v + 1] += at_start[v];
    struct Incident {  // an open edge at a vertex, with what the joins at that vertex read
      std::uint64_t line;
      int edge, far;  // the open edge, and its endpoint other than the vertex
      std::int32_t support, plane;
    };
    std::vector<Incident> at(static_cast<std::size_t>(at_start[nv]));  // contiguous per vertex
    {
      std::vector<int> fill(at_start.begin(), at_start.end() - 1);
      for (std::size_t i = 0; i < n; ++i) {
        const OpenEdge& e = open_[i];
        const std::int32_t support = f_.support[std::size_t(e.face)], plane = f_.line[std::size_t(e.corner)];
        at[std::size_t(fill[std::size_t(e.u)]++)] = {e.line, int(i), e.w, support, plane};
        at[std::size_t(fill[std::size_t(e.w)]++)] = {e.line, int(i), e.u, support, plane};
      }
    }
    // Edges of one plane pair are one group already: one test per pair of distinct plane pairs
    // at v (all edges of a pair lie on one line through v, so any of them decides).
    // (An edge from v to v, if one ever occurs, lies on every line through v: its vertex falls
    // back to testing every pair.)
    std::vector<int> lines;  // one entry of `at` per distinct plane pair at v
    lines.reserve(16);
    for (std::size_t v = 0; v < nv; ++v) {
      lines.clear();
      bool degenerate = false;
      for (int a = at_start[v]; a < at_start[v + 1]; ++a) {
        const Incident& x = at[std::size_t(a)];
        degenerate = degenerate || x.far == int(v);
        bool seen = false;
        for (const int j : lines) seen = seen || at[std::size_t(j)].line == x.line;
        if (!seen) lines.push_back(a);
      }
      if (degenerate) {
        lines.clear();
        for (int a = at_start[v]; a < at_start[v + 1]; ++a) lines.push_back(a);
      }
      for (std::size_t a = 0; a + 1 < lines.size(); ++a) {
        const Incident& x = at[std::size_t(lines[a])];
        // x's two planes read once for all its tests (the plane table is larger than the caches).
        const kernel::Plane &support = g_.planes()[x.support], &plane = g_.planes()[x.plane];
        for (std::size_t b = a + 1; b < lines.size(); ++b) {
          const Incident& y = at[std::size_t(lines[b])];
          if (uf.find(x.edge) == uf.find(y.edge)) continue;
          // The floating-point filter first: most far endpoints are clearly off x's line.
          const kernel::ApproxPoint& p = g_.at(y.far);
          if (kernel::filtered_orient(p, plane) != kernel::Sign::Zero || kernel::filtered_orient(p, support) != kernel::Sign::Zero)
            continue;
          if (g_.on_plane(y.far, x.plane) && g_.on_plane(y.far, x.support)) uf.unite(x.edge, y.edge);
        }
      }
    }
    // Each group: its vertices sorted along the line (exactly), then the inserts of its edges.
    std::vector<int> member_start(n + 1, 0);
    for (std::size_t i = 0; i < n; ++i) ++member_start[std::size_t(uf.find(int(i))) + 1];
    for (std::size_t i = 0; i < n; ++i) member_start[i + 1] += member_start[i];
    struct Member {  // an open edge of the group, its endpoints and (once sorted) their ranks
      int i, u, w, ru, rw;
    };
    std::vector<Member> members(n);  // in group order: each group's passes read one contiguous run
    {
      std::vector<int> fill(member_start.begin(), member_start.end() - 1);
      for (std::size_t i = 0; i < n; ++i)
        members[std::size_t(fill[std::size_t(uf.find(int(i)))]++)] = {int(i), open_[i].u, open_[i].w, 0, 0};
    }
    std::vector<int> rank(nv, -1), verts;
    struct Along {  // a vertex with its coordinate along the line's axis, for sorting
      double x, err;
      int v;
    };
    std::vector<Along> along;
    verts.reserve(16);
    along.reserve(16);
    ins_.reserve(n);
    std::vector<std::uint8_t> up, down;  // a piece from rank k to k + 1 (k + 1 to k) exists
    for (std::size_t r = 0; r < n; ++r) {
      const int b = member_start[r], e = member_start[r + 1];
      if (e - b < 2) continue;
      verts.clear();
      for (int m = b; m < e; ++m) {
        const Member& x = members[std::size_t(m)];
        for (const int v : {x.u, x.w})
          if (rank[std::size_t(v)] < 0) {
            rank[std::size_t(v)] = 0;
            verts.push_back(v);
          }
      }
      // An axis along which the line's direction has a non-zero component (two distinct points
      // of the line differ in it, so sorting along it orders the line, one way round or the
      // other: the inserts and the matches are the same). Proved by the first edge's endpoints
      // when their approximations differ in it by more than twice their errors (rounding of
      // the difference included), else decided exactly from the planes (line_axis).
      int axis = -1;
      {
        const kernel::ApproxPoint &pu = g_.at(members[std::size_t(b)].u), &pw = g_.at(members[std::size_t(b)].w);
        const double gap[3] = {std::fabs(pw.x - pu.x), std::fabs(pw.y - pu.y), std::fabs(pw.z - pu.z)};
        const int k = gap[0] >= gap[1] ? (gap[0] >= gap[2] ? 0 : 2) : (gap[1] >= gap[2] ? 1 : 2);
        if (pu.err >= 0 && pw.err >= 0 && gap[k] > 2 * (pu.err + pw.err)) axis = k;
      }
      if (axis < 0) {
        const OpenEdge& first = open_[std::size_t(members[std::size_t(b)].i)];
        axis = g_.line_axis(f_.support[std::size_t(first.face)], f_.line[std::size_t(first.corner)]);
      }
      // Sorted exactly (VertexGeometry::less_along), its floating-point test inline.
      along.clear();
      for (const int v : verts) {
        const kernel::ApproxPoint& a = g_.at(v);
        along.push_back({axis == 0 ? a.x : (axis == 1 ? a.y : a.z), a.err, v});
      }
      std::sort(along.begin(), along.end(), [&](const Along& x, const Along& y) {
        if (x.err >= 0 && y.err >= 0) {
          const double gap = x.err + y.err;
          if (x.x + gap < y.x) return true;
          if (y.x + gap < x.x) return false;
        }
        return g_.less_along(x.v, y.v, axis);
      });
      for (std::size_t k = 0; k < verts.size(); ++k) verts[k] = along[k].v;
      for (std::size_t k = 0; k < verts.size(); ++k) rank[std::size_t(verts[k])] = int(k);
      for (int m = b; m < e; ++m) {
        Member& x = members[std::size_t(m)];
        const int i = x.i;
        const int ru = x.ru = rank[std::size_t(x.u)], rw = x.rw = rank[std::size_t(x.w)];
        ins_begin_[std::size_t(i)] = int(ins_.size());
        if (ru < rw)
          for (int k = ru + 1; k < rw; ++k) ins_.push_back(verts[std::size_t(k)]);
        else
          for (int k = ru - 1; k > rw; --k) ins_.push_back(verts[std::size_t(k)]);
        ins_end_[std::size_t(i)] = int(ins_.size());
      }
      // Each piece needs an opposite: a piece of another edge of the group (pieces of other
      // groups are not on this line through these vertices, or the groups would have been
      // joined at a shared vertex) or a half-edge of the faces.
      up.assign(verts.size(), 0);
      down.assign(verts.size(), 0);
      for (int m = b; m < e; ++m) {
        const int ru = members[std::size_t(m)].ru, rw = members[std::size_t(m)].rw;
        for (int k = std::min(ru, rw); k < std::max(ru, rw); ++k) (ru < rw ? up : down)[std::size_t(k)] = 1;
      }
      for (int m = b; m < e; ++m) {
        const int i = members[std::size_t(m)].i;
        const int ru = members[std::size_t(m)].ru, rw = members[std::size_t(m)].rw;
        bool ok = true;
        for (int k = std::min(ru, rw); k < std::max(ru, rw) && ok; ++k) {
          const int lo = verts[std::size_t(k)], hi = verts[std::size_t(k) + 1];
          ok = ru < rw ? (down[std::size_t(k)] != 0 || index_.find(hi, lo) >= 0) : (up[std::size_t(k)] != 0 || index_.find(lo, hi) >= 0);
        }
        matched_[std::size_t(i)] = ok ? 1 : 0;
      }
      for (const int v : verts) rank[std::size_t(v)] = -1;
    }
  }

  Eigen::Vector3d position(int v) const {
    const kernel::ApproxPoint& a = g_.at(v);
    return {a.x, a.y, a.z};
  }
  double err(int v) const { return g_.at(v).err; }

  // Spatial search for the failing edges: every endpoint of an open edge near the edge (hash
  // grid, the median open-edge length as cell size) is tested exactly for lying on its line
  // strictly between its endpoints.
  void search(const std::vector<int>& failing) {
    std::vector<int> candidates;
    std::vector<double> lengths;
    for (const OpenEdge& e : open_) candidates.push_back(e.u), candidates.push_back(e.w);
    for (const int i : failing) lengths.push_back((position(open_[std::size_t(i)].w) - position(open_[std::size_t(i)].u)).norm());
    std::sort(candidates.begin(), candidates.end());
    candidates.erase(std::unique(candidates.begin(), candidates.end()), candidates.end());
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
    EdgeIndex runs(grid.size());  // cell key -> first entry of its run in `grid`
    for (std::size_t i = 0; i < grid.size(); ++i)
      if (i == 0 || grid[i].first != grid[i - 1].first) runs.insert(grid[i].first, int(i));

    constexpr double kTol = 1e-3;  // grid units: a cheap prefilter only; the test is exact
    std::vector<int> near;
    std::vector<std::pair<double, int>> found;
    for (const int i : failing) {
      const OpenEdge& e = open_[std::size_t(i)];
      const std::int32_t support = f_.support[std::size_t(e.face)], line = f_.line[std::size_t(e.corner)];
      const Eigen::Vector3d pu = position(e.u), pw = position(e.w), d = pw - pu;
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
              const int first = runs.find(ck);
              if (first < 0) continue;
              for (std::size_t k = std::size_t(first); k < grid.size() && grid[k].first == ck; ++k) near.push_back(grid[k].second);
            }
        std::sort(near.begin(), near.end());
        near.erase(std::unique(near.begin(), near.end()), near.end());
      }
      found.clear();
      int axis = -1;
      for (const int c : near) {
        if (c == e.u || c == e.w) continue;
        const Eigen::Vector3d pc = position(c);
        const double t = (pc - pu).dot(d) / len2;
        const double slack = 4 * (err(e.u) + err(e.w) + err(c)) / std::sqrt(len2) + 1e-12;
        if (t <= -slack || t >= 1 + slack || (pu + t * d - pc).norm() > kTol) continue;
        if (!on_line(e, c)) continue;
        // On the line and distinct from u and w (exactly); strictly between them? Decided
        // exactly when the approximation is too close to call.
        if (axis < 0) axis = g_.line_axis(support, line);
        if (!(t > slack && t < 1 - slack) && !g_.between(e.u, c, e.w, axis)) continue;
        found.push_back({t, c});
      }
      if (found.empty() && ins_begin_[std::size_t(i)] == ins_end_[std::size_t(i)]) continue;
      // Order along the edge exactly (vertices closer than their approximation errors occur
      // with re-quantized planes), from u to w.
      if (axis < 0) axis = g_.line_axis(support, line);
      const bool ascending = g_.less_along(e.u, e.w, axis);
      std::sort(found.begin(), found.end(), [&](const auto& x, const auto& y) {
        return ascending ? g_.less_along(x.second, y.second, axis) : g_.less_along(y.second, x.second, axis);
      });
      ins_begin_[std::size_t(i)] = int(ins_.size());
      for (const auto& [t, c] : found) ins_.push_back(c);
      ins_end_[std::size_t(i)] = int(ins_.size());
    }
  }

  const FaceList& f_;
  const VertexGeometry& g_;
  const PlaneIds& ids_;
  OutgoingEdges index_;          // every half-edge by (u, w)
  std::vector<OpenEdge> open_;   // half-edges without an opposite, in corner order
  std::vector<int> ins_begin_, ins_end_, ins_;  // inserted vertices of each open edge, from u to w
  std::vector<std::uint8_t> matched_;            // 1: every piece of the open edge has an opposite
};

}  // namespace

JunctionResult remove_t_junctions(FaceList faces, const VertexGeometry& geometry, const PlaneIds& ids,
                                  const JunctionOptions& options) {
  JunctionResult result;
  JunctionRemover remover(faces, geometry, ids);
  if (remover.run(options, result)) remover.apply(faces);
  result.faces = std::move(faces);
  return result;
}

}  // namespace sculpt::bsp::detail
