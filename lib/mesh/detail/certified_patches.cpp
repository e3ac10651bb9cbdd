#include "mesh/detail/certified_patches.hpp"

#include <algorithm>
#include <numeric>
#include <span>
#include <tuple>
#include <utility>
#include "base/cancel.hpp"

namespace sculpt::mesh::detail {
namespace {

using Eigen::Vector2d;
using Eigen::Vector3d;
using Link = StarLinks::Link;

/// Fans of more than kLongFan triangles are not examined (the tests below take the square of a
/// fan's size): the patches through such a vertex are not certified.
constexpr size_t kLongFan = 64;

/// The triangles' classes and links as the steps below read them.
struct Fans {
  const std::vector<signed char>& cls;
  const StarLinks& links;
  const std::vector<signed char>& stars;  ///< CertifiedStars::certified

  /// Link l of vertex v turned round where its triangle's sign is negative, so that every sector
  /// v a b turns left in the projection.
  [[nodiscard]] Link oriented(size_t v, Link l) const {
    if ((links.turned[v] != 0) != ((cls[size_t(l.t)] & 1) == 0)) std::swap(l.a, l.b);
    return l;
  }
  [[nodiscard]] std::span<const Link> fan(size_t v) const {
    return {links.link.data() + links.start[v], links.link.data() + links.start[v + 1]};
  }
  /// v's star certified, all its triangles of that class.
  [[nodiscard]] bool whole(size_t v) const {
    if (stars[v] == 0) return false;
    for (const Link& l : fan(v))
      if (cls[size_t(l.t)] != stars[v] - 1) return false;
    return true;
  }
};

/// Per classed triangle, the root of its component (-1 for the others). Components: triangles
/// of one class across an edge v a (one's link edge leaves a, the other's arrives there). Round a
/// vertex whose star is certified for the class of all its triangles, those form one closed fan,
/// consecutive ones sharing an edge: all are joined at once.
std::vector<int> component_roots(const Fans& fans, size_t nv) {
  const size_t nt = fans.cls.size();
  const std::vector<signed char>& cls = fans.cls;
  std::vector<int> parent(nt);
  std::iota(parent.begin(), parent.end(), 0);
  auto find = [&](int x) {
    while (parent[size_t(x)] != x) x = parent[size_t(x)] = parent[size_t(parent[size_t(x)])];
    return x;
  };
  CancelPoll poll;  // Ctrl-C (base/cancel.hpp)
  for (size_t v = 0; v < nv; ++v) {
    poll.tick();
    const std::span<const Link> f = fans.fan(v);
    if (fans.whole(v)) {
      for (const Link& l : f) parent[size_t(find(l.t))] = find(f.front().t);
      continue;
    }
    if (f.size() > kLongFan) continue;
    for (const Link& raw : f) {  // each edge v a at its smaller end
      if (cls[size_t(raw.t)] < 0) continue;
      const Link x = fans.oriented(v, raw);
      if (x.a < int(v)) continue;
      for (const Link& other : f)
        if (cls[size_t(other.t)] == cls[size_t(x.t)] && fans.oriented(v, other).b == x.a)
          parent[size_t(find(x.t))] = find(other.t);
    }
  }
  std::vector<int> root(nt, -1);
  for (size_t t = 0; t < nt; ++t)
    if (cls[t] >= 0) root[t] = find(int(t));
  return root;
}

struct Edge {  // a boundary edge from -> to of a patch, with the patch on its left
  int root, from, to;
};

/// Whether the oriented links `group` round v (one patch's) form one fan: starts distinct, ends
/// distinct, at most one start that no edge arrives at (its first corner; none: closed), and a
/// walk from there takes every edge. `first`: that start, or -1 when the fan is closed.
bool one_fan(std::span<const std::pair<int, Link>> group, int& first) {
  bool ok = true;
  int starts = 0;
  first = -1;
  for (size_t i = 0; i < group.size() && ok; ++i) {
    bool arrives = false;
    for (size_t j = 0; j < group.size(); ++j) {
      if (j != i) ok = ok && group[j].second.a != group[i].second.a && group[j].second.b != group[i].second.b;
      arrives = arrives || group[j].second.b == group[i].second.a;
    }
    if (!arrives) first = group[i].second.a, ++starts;
  }
  ok = ok && starts <= 1;
  if (starts == 0) first = -1;
  const int begin = first < 0 ? group.front().second.a : first;
  size_t walked = 0;
  for (int at = begin; ok && walked < group.size();) {
    size_t i = 0;
    while (i < group.size() && group[i].second.a != at) ++i;
    if (i == group.size()) break;
    ++walked;
    at = group[i].second.b;
    if (at == begin) break;
  }
  return ok && walked == group.size();
}

/// Round each vertex, each patch's triangles as one fan (a patch where they are not: `failed`
/// by root); the outer edges of the open fans, the patches' boundary edges.
std::vector<Edge> boundary_edges(const Fans& fans, const std::vector<int>& root, size_t nv, std::vector<char>& failed) {
  std::vector<Edge> edges;
  std::vector<std::pair<int, Link>> group;
  CancelPoll poll;  // Ctrl-C (base/cancel.hpp)
  for (size_t v = 0; v < nv; ++v) {
    poll.tick();
    // A certified star in one patch: one closed fan, nothing more to check (the usual case).
    if (fans.whole(v)) {
      const int r = root[size_t(fans.fan(v).front().t)];
      bool one = true;
      for (const Link& l : fans.fan(v)) one = one && root[size_t(l.t)] == r;
      if (one) continue;
    }
    group.clear();
    bool one = true;  // one patch round v (no sort)
    for (const Link& l : fans.fan(v)) {
      if (fans.cls[size_t(l.t)] < 0) continue;
      group.push_back({root[size_t(l.t)], fans.oriented(v, l)});
      one = one && group.back().first == group.front().first;
    }
    if (!one) std::sort(group.begin(), group.end(), [](const auto& x, const auto& y) { return x.first < y.first; });
    for (size_t g = 0; g < group.size();) {
      size_t e = g + 1;
      while (e < group.size() && group[e].first == group[g].first) ++e;
      const int r = group[g].first;
      int first = -1;
      if (e - g > kLongFan || !one_fan({group.data() + g, e - g}, first))
        failed[size_t(r)] = 1;
      else if (first >= 0)
        edges.push_back({r, int(v), first});  // open: v is on the boundary
      g = e;
    }
  }
  return edges;
}

struct Segment {
  Vector2d p, q;
  int from, to;
};

/// The closed loop `segments` (in any order) is simple: no two segments meet but consecutive
/// ones at their common end, and those do not fold back along each other. A sweep along the
/// first coordinate; beyond a budget of pairs compared, not certified (false).
bool simple_loop(std::vector<Segment>& segments) {
  std::sort(segments.begin(), segments.end(),
            [](const Segment& x, const Segment& y) { return std::min(x.p.x(), x.q.x()) < std::min(y.p.x(), y.q.x()); });
  size_t budget = 64 * segments.size() + 4096;
  for (size_t i = 0; i < segments.size(); ++i) {
    const Segment& s = segments[i];
    const double right = std::max(s.p.x(), s.q.x());
    for (size_t j = i + 1; j < segments.size() && std::min(segments[j].p.x(), segments[j].q.x()) <= right; ++j) {
      const Segment& u = segments[j];
      if (budget-- == 0) return false;
      if (std::max(s.p.y(), s.q.y()) < std::min(u.p.y(), u.q.y()) ||
          std::max(u.p.y(), u.q.y()) < std::min(s.p.y(), s.q.y()))
        continue;
      if (s.to == u.from || u.to == s.from) {
        // Consecutive: w -> m -> z meet only at m unless they run back along each other.
        const bool s_first = s.to == u.from;
        const Vector2d &w = s_first ? s.p : u.p, &m = s_first ? s.q : u.q, &z = s_first ? u.q : s.q;
        if (orient2d(w, m, z) == 0 && !((m - w).dot(z - m) > 0)) return false;
        if (s.to == u.from && u.to == s.from) return false;  // a loop of two edges
        continue;
      }
      if (segments_meet_2d(s.p, s.q, u.p, u.q)) return false;
    }
  }
  return true;
}

/// Each patch with boundary edges (`bounded`, by root): one boundary loop, whose projection is
/// simple, else `failed`. `edges` are sorted here.
void check_loops(std::vector<Edge>& edges, const std::vector<signed char>& cls, const std::vector<Vector3d>& points,
                 std::vector<char>& failed, std::vector<char>& bounded) {
  std::sort(edges.begin(), edges.end(),
            [](const Edge& x, const Edge& y) { return std::tie(x.root, x.from) < std::tie(y.root, y.from); });
  std::vector<Segment> segments;
  for (size_t g = 0; g < edges.size();) {
    size_t e = g + 1;
    while (e < edges.size() && edges[e].root == edges[g].root) ++e;
    const int r = edges[g].root;
    const int axis = cls[size_t(r)] / 2;
    bool ok = !failed[size_t(r)];
    bounded[size_t(r)] = 1;
    // The loop: from each boundary vertex to the next, once round.
    auto next_of = [&](int from_vertex) {
      const auto it = std::lower_bound(edges.begin() + std::ptrdiff_t(g), edges.begin() + std::ptrdiff_t(e),
                                       from_vertex, [](const Edge& x, int y) { return x.from < y; });
      return it != edges.begin() + std::ptrdiff_t(e) && it->from == from_vertex ? it->to : -1;
    };
    size_t steps = 0;
    for (int at = edges[g].from; ok;) {
      at = next_of(at);
      ++steps;
      if (at < 0 || steps > e - g)
        ok = false;
      else if (at == edges[g].from)
        break;
    }
    ok = ok && steps == e - g;
    if (ok) {
      segments.clear();
      for (size_t i = g; i < e; ++i)
        segments.push_back({drop(points[size_t(edges[i].from)], axis), drop(points[size_t(edges[i].to)], axis),
                            edges[i].from, edges[i].to});
      ok = simple_loop(segments);
    }
    if (!ok) failed[size_t(r)] = 1;
    g = e;
  }
}

}  // namespace

std::vector<int> certified_patches(const std::vector<signed char>& cls, const CertifiedStars& stars,
                                   const std::vector<Vector3d>& points) {
  const size_t nt = cls.size(), nv = points.size();
  const StarLinks& links = stars.links;
  std::vector<int> patch(nt);
  for (size_t t = 0; t < nt; ++t) patch[t] = -1 - int(t);
  // Patches grow across certified stars; where many are not certified (creases: boxes, the
  // plate drilled 100 times with half its stars certified) they stay small and spare less than
  // they cost, and are not looked for.
  size_t used = 0, certified = 0;
  for (size_t v = 0; v < nv; ++v) {
    used += links.start[v + 1] > links.start[v] ? 1 : 0;
    certified += stars.certified[v] != 0 ? 1 : 0;
  }
  if (4 * certified < 3 * used) return patch;
  const Fans fans{cls, links, stars.certified};
  const std::vector<int> root = component_roots(fans, nv);
  std::vector<char> failed(nt, 0), bounded(nt, 0);  // by root
  std::vector<Edge> edges = boundary_edges(fans, root, nv, failed);
  check_loops(edges, cls, points, failed, bounded);
  for (size_t t = 0; t < nt; ++t) {
    if (cls[t] < 0) continue;
    const int r = root[t];
    if (!failed[size_t(r)] && bounded[size_t(r)]) patch[t] = r;
  }
  return patch;
}

}  // namespace sculpt::mesh::detail
