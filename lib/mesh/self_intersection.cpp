#include "mesh/self_intersection.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numeric>
#include <set>
#include <tuple>
#include <utility>

#include <Eigen/Geometry>

#include "mesh/detail/box_grid.hpp"
#include "mesh/detail/point_copies.hpp"
#include "mesh/predicates.hpp"
#include "mesh/triangulate.hpp"

namespace sculpt {
namespace {

using Eigen::Vector2d;
using Eigen::Vector3d;

Vector2d drop(const Vector3d& v, int axis) { return {v[(axis + 1) % 3], v[(axis + 2) % 3]}; }

/// Closed 2D segments [a,b] and [c,d] meet.
bool segments_meet_2d(const Vector2d& a, const Vector2d& b, const Vector2d& c, const Vector2d& d) {
  const int o1 = orient2d(a, b, c), o2 = orient2d(a, b, d);
  const int o3 = orient2d(c, d, a), o4 = orient2d(c, d, b);
  if (o1 * o2 < 0 && o3 * o4 < 0) return true;
  auto on_segment = [](const Vector2d& s, const Vector2d& t, const Vector2d& q) {
    return std::min(s.x(), t.x()) <= q.x() && q.x() <= std::max(s.x(), t.x()) &&
           std::min(s.y(), t.y()) <= q.y() && q.y() <= std::max(s.y(), t.y());
  };
  return (o1 == 0 && on_segment(a, b, c)) || (o2 == 0 && on_segment(a, b, d)) ||
         (o3 == 0 && on_segment(c, d, a)) || (o4 == 0 && on_segment(c, d, b));
}

/// Point q in the closed 2D triangle (t0, t1, t2) of either orientation.
bool point_in_triangle_2d(const Vector2d& q, const Vector2d& t0, const Vector2d& t1,
                          const Vector2d& t2) {
  const int a = orient2d(t0, t1, q), b = orient2d(t1, t2, q), c = orient2d(t2, t0, q);
  return (a >= 0 && b >= 0 && c >= 0) || (a <= 0 && b <= 0 && c <= 0);
}

/// Closed segment [s0, s1] meets the closed, non-degenerate triangle t.
/// o0, o1: the sides of s0 and s1 of t's plane (orient3d(t.p[0], t.p[1], t.p[2], s_i)).
bool segment_meets_triangle(const Vector3d& s0, const Vector3d& s1, int o0, int o1, const PreparedTriangle& t) {
  if (o0 * o1 > 0) return false;
  if (o0 == 0 && o1 == 0) {  // coplanar: decide in the projection
    const Vector2d a = drop(s0, t.axis), b = drop(s1, t.axis);
    const Vector2d t0 = drop(t.p[0], t.axis), t1 = drop(t.p[1], t.axis), t2 = drop(t.p[2], t.axis);
    return point_in_triangle_2d(a, t0, t1, t2) || point_in_triangle_2d(b, t0, t1, t2) ||
           segments_meet_2d(a, b, t0, t1) || segments_meet_2d(a, b, t1, t2) ||
           segments_meet_2d(a, b, t2, t0);
  }
  // The segment reaches the plane: its line must pass through the closed triangle.
  const int a = orient3d(s0, s1, t.p[0], t.p[1]);
  const int b = orient3d(s0, s1, t.p[1], t.p[2]);
  const int c = orient3d(s0, s1, t.p[2], t.p[0]);
  return (a >= 0 && b >= 0 && c >= 0) || (a <= 0 && b <= 0 && c <= 0);
}

/// Some edge line of `a` has all of `b` strictly on the side away from `a`'s third corner, in
/// the projection along `axis` (none when `a` projects to a segment there). Then the projections
/// are disjoint, and so are the triangles.
bool edge_line_separates(const std::array<Vector2d, 3>& a, const std::array<Vector2d, 3>& b) {
  const int inside = orient2d(a[0], a[1], a[2]);  // the side of the third corner
  if (inside == 0) return false;
  for (int k = 0; k < 3; ++k) {
    const Vector2d &u = a[k], &v = a[(k + 1) % 3];
    if (orient2d(u, v, b[0]) == -inside && orient2d(u, v, b[1]) == -inside && orient2d(u, v, b[2]) == -inside)
      return true;
  }
  return false;
}

/// Triangles whose projections along `axis` are strictly separated by
/// an edge line of one of them (sufficient, not necessary, for disjoint triangles).
bool projections_separated(const PreparedTriangle& x, const PreparedTriangle& y, int axis) {
  const std::array<Vector2d, 3> p = {drop(x.p[0], axis), drop(x.p[1], axis), drop(x.p[2], axis)};
  const std::array<Vector2d, 3> q = {drop(y.p[0], axis), drop(y.p[1], axis), drop(y.p[2], axis)};
  return edge_line_separates(p, q) || edge_line_separates(q, p);
}

/// Coplanar closed triangles meet unless an edge line of one has the other triangle strictly
/// outside (separating axis theorem in the plane: disjoint compact convex polygons have a
/// strictly separating line along an edge of one of them), decided in the projection along
/// `axis`, along which both project without degeneracy.
bool coplanar_triangles_meet(const PreparedTriangle& x, const PreparedTriangle& y, int axis) { return !projections_separated(x, y, axis); }

/// orient3d(t.p[0], t.p[1], t.p[2], q): t's plane filter first, the exact predicate where it is
/// undecided.
int side(const PreparedTriangle& t, const Vector3d& q) {
  const int f = orient3d_filtered(t.plane, q);
  return f != kUndecided ? f : orient3d(t.p[0], t.p[1], t.p[2], q);
}

/// Any edge of `x` (among those listed) meets triangle `y`.
bool edges_meet(const PreparedTriangle& x, std::initializer_list<std::pair<int, int>> edges, const PreparedTriangle& y) {
  for (auto [i, j] : edges)
    if (segment_meets_triangle(x.p[i], x.p[j], side(y, x.p[i]), side(y, x.p[j]), y)) return true;
  return false;
}

/// Any edge of `x` meets triangle `y`, given the sides o[k] of x's corners of y's plane.
bool all_edges_meet(const PreparedTriangle& x, const std::array<int, 3>& o, const PreparedTriangle& y) {
  for (int k = 0; k < 3; ++k)
    if (segment_meets_triangle(x.p[k], x.p[(k + 1) % 3], o[k], o[(k + 1) % 3], y)) return true;
  return false;
}

/// Triangles s and t with one common corner, s[i] = t[j] = p: in the projection along s.axis
/// (where s does not degenerate) a line through p along an edge of one of them has the other's
/// two other corners strictly on the side away from its own third corner. Then the projections
/// meet only in p's image, and since the projection is one to one on s's plane, the triangles
/// meet only in p (sufficient, not necessary).
bool wedges_separated(const PreparedTriangle& s, int i, const PreparedTriangle& t, int j) {
  const int axis = s.axis;
  const Vector2d p = drop(s.p[i], axis);
  const Vector2d a = drop(s.p[(i + 1) % 3], axis), b = drop(s.p[(i + 2) % 3], axis);
  const Vector2d c = drop(t.p[(j + 1) % 3], axis), d = drop(t.p[(j + 2) % 3], axis);
  // Line p u, the own third corner w: the other two corners x, y strictly on the other side.
  auto separates = [&](const Vector2d& u, const Vector2d& w, const Vector2d& x, const Vector2d& y) {
    const int own = orient2d(p, u, w);
    return own != 0 && orient2d(p, u, x) == -own && orient2d(p, u, y) == -own;
  };
  return separates(a, b, c, d) || separates(b, a, c, d) || separates(c, d, a, b) || separates(d, c, a, b);
}

/// orient3d(a, b, c, d), given its filtered value (orient3d_filtered) when that was computed.
int decided(int filtered, const Vector3d& a, const Vector3d& b, const Vector3d& c, const Vector3d& d) {
  return filtered != kUndecided ? filtered : orient3d(a, b, c, d);
}

/// The two triangles meet beyond the vertices they share (and the edge they share).
/// Decided exactly; where the floating-point filter leaves a side of a plane undecided (nearly
/// coplanar triangles, whose exact signs are costly), a projection that separates them is tried
/// first: it only ever proves that they do not meet, so the decisions are those of the exact
/// tests alone.
bool triangles_conflict(const PreparedTriangle& s, const PreparedTriangle& t) {
  int shared = 0;
  int s_shared[3] = {-1, -1, -1};  // index in s of each shared corner, in s order
  int t_of[3] = {-1, -1, -1};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      if (s.ids[i] == t.ids[j]) {
        s_shared[shared] = i;
        t_of[i] = j;
        ++shared;
      }
  if (shared == 0) {
    // One triangle strictly on one side of the other's plane: they cannot meet (the same
    // decisions as the edge tests below, with fewer predicates).
    const int f0 = orient3d_filtered(t.plane, s.p[0]);
    const int f1 = orient3d_filtered(t.plane, s.p[1]);
    const int f2 = orient3d_filtered(t.plane, s.p[2]);
    const bool undecided = f0 == kUndecided || f1 == kUndecided || f2 == kUndecided;
    if (!undecided && ((f0 > 0 && f1 > 0 && f2 > 0) || (f0 < 0 && f1 < 0 && f2 < 0))) return false;
    if (undecided && projections_separated(s, t, t.axis)) return false;
    const int s0 = decided(f0, t.p[0], t.p[1], t.p[2], s.p[0]), s1 = decided(f1, t.p[0], t.p[1], t.p[2], s.p[1]);
    const int s2 = decided(f2, t.p[0], t.p[1], t.p[2], s.p[2]);
    if ((s0 > 0 && s1 > 0 && s2 > 0) || (s0 < 0 && s1 < 0 && s2 < 0)) return false;
    if (s0 == 0 && s1 == 0 && s2 == 0) return coplanar_triangles_meet(s, t, t.axis);
    const int t0 = side(s, t.p[0]), t1 = side(s, t.p[1]), t2 = side(s, t.p[2]);
    if ((t0 > 0 && t1 > 0 && t2 > 0) || (t0 < 0 && t1 < 0 && t2 < 0)) return false;
    return all_edges_meet(s, {s0, s1, s2}, t) || all_edges_meet(t, {t0, t1, t2}, s);
  }
  if (shared == 1) {
    // Convexity: beyond the shared corner p, the triangles can only meet if the edge opposite
    // p in one of them meets the other.
    // When s's other corners lie strictly on one side of t's plane, s meets that plane (and t)
    // only at p: no other test is needed.
    const int i = s_shared[0], j = t_of[i];
    const Vector3d &s1 = s.p[(i + 1) % 3], &s2 = s.p[(i + 2) % 3];
    const int f1 = orient3d_filtered(t.plane, s1), f2 = orient3d_filtered(t.plane, s2);
    const bool undecided = f1 == kUndecided || f2 == kUndecided;
    if (!undecided && f1 * f2 > 0) return false;
    // The same with the roles exchanged: t meets s's plane only at p.
    const int g1 = orient3d_filtered(s.plane, t.p[(j + 1) % 3]), g2 = orient3d_filtered(s.plane, t.p[(j + 2) % 3]);
    if (g1 != kUndecided && g2 != kUndecided && g1 * g2 > 0) return false;
    if (undecided && wedges_separated(s, i, t, j)) return false;
    const int o1 = decided(f1, t.p[0], t.p[1], t.p[2], s1), o2 = decided(f2, t.p[0], t.p[1], t.p[2], s2);
    if (o1 * o2 > 0) return false;
    return segment_meets_triangle(s1, s2, o1, o2, t) || edges_meet(t, {{(j + 1) % 3, (j + 2) % 3}}, s);
  }
  if (shared == 2) {
    // Shared edge pq: conflict only if coplanar with the third corners on the same side (the
    // sides in the projection first: for neighbours they differ, and the costly exact zero of
    // nearly coplanar corners is then not needed).
    const int i0 = s_shared[0], i1 = s_shared[1];
    const int ia = 3 - i0 - i1;
    int jb = 0;
    for (int j = 0; j < 3; ++j)
      if (j != t_of[i0] && j != t_of[i1]) jb = j;
    const Vector3d &p = s.p[i0], &q = s.p[i1], &a = s.p[ia], &b = t.p[jb];
    const int fb = orient3d_filtered(s.plane, b);
    if (fb != kUndecided) return false;  // not coplanar (the filter decides no zero)
    const int sa = orient2d(drop(p, s.axis), drop(q, s.axis), drop(a, s.axis));
    const int sb = orient2d(drop(p, s.axis), drop(q, s.axis), drop(b, s.axis));
    return sa == sb && orient3d(p, q, a, b) == 0;
  }
  return true;  // the same triangle twice
}

/// Coordinate axis along which the polygon's projection has the largest area (Newell normal, or
/// the widest corner triangle when the net area is zero); -1 when all corners are collinear.
int projection_axis(const PolygonMesh& mesh, const std::vector<int>& face) {
  const Vector3d origin = mesh.vertices[face[0]];
  Vector3d normal = Vector3d::Zero();
  for (size_t i = 0; i < face.size(); ++i)
    normal += (mesh.vertices[face[i]] - origin).cross(mesh.vertices[face[(i + 1) % face.size()]] - origin);
  if (normal.cwiseAbs().maxCoeff() == 0) {
    // Zero net area (a symmetric bow tie, say): take the plane of the widest corner triangle.
    for (size_t i = 1; i < face.size(); ++i)
      for (size_t k = i + 1; k < face.size(); ++k) {
        const Vector3d n = (mesh.vertices[face[i]] - origin).cross(mesh.vertices[face[k]] - origin);
        if (n.squaredNorm() > normal.squaredNorm()) normal = n;
      }
  }
  int axis = 0;
  normal.cwiseAbs().maxCoeff(&axis);
  return normal[axis] == 0 ? -1 : axis;
}

/// Vertex ids when every vertex is distinct (SelfIntersectionOptions::distinct_vertices); else
/// mesh::detail::first_copies gives copies of a point one id.
std::vector<int> identity_ids(size_t n) {
  std::vector<int> ids(n);
  std::iota(ids.begin(), ids.end(), 0);
  return ids;
}

/// x as a float, clamped to float's range: monotone (x <= y gives as_float(x) <= as_float(y)), so
/// boxes that overlap still do after this rounding.
float as_float(double x) {
  constexpr double kMax = std::numeric_limits<float>::max();
  return static_cast<float>(x < -kMax ? -kMax : x > kMax ? kMax : x);
}

/// Asks for t's cache lines ahead of its use (a hint; nothing where the compiler has none).
void prefetch(const PreparedTriangle& t) {
#if defined(__GNUC__)
  const char* p = reinterpret_cast<const char*>(&t);
  for (size_t at = 0; at < sizeof(PreparedTriangle); at += 64) __builtin_prefetch(p + at);
#else
  (void)t;
#endif
}

/// Whether the sign of plane.minor[axis] is certain: that minor is orient2d's filter value for the
/// projection of the plane's triangle along `axis` (differences to its first corner, Shewchuk's
/// form), so his orient2d bound applies.
bool certified_minor(const Orient3dPlane& plane, int axis) {
  const double m = plane.minor[axis], perm = plane.permanent[axis];
  return std::abs(m) > detail::kOrient2dFilterBound * perm && perm > detail::kFilterNoUnderflow && std::isfinite(m);
}

/// What certified_stars reads of a triangle: its corner ids, its plane's minors (an area vector,
/// used only to choose an axis) and the signs of its projections along each axis where the
/// filter decides them (kUndecided elsewhere).
struct StarTriangle {
  std::array<int, 3> ids{};
  std::array<double, 3> normal{};
  std::array<signed char, 3> sign{};
};

/// t's StarTriangle (the signs by certified_minor).
StarTriangle star_triangle(const PreparedTriangle& t) {
  StarTriangle r;
  r.ids = t.ids;
  for (int k = 0; k < 3; ++k) {
    const double m = t.plane.minor[k];
    r.normal[size_t(k)] = m;
    r.sign[size_t(k)] = static_cast<signed char>(certified_minor(t.plane, k) ? (m > 0 ? 1 : -1) : kUndecided);
  }
  return r;
}

/// The link edges a -> b of the triangles v a b round each vertex v, in the vertex's frame (where
/// the sectors turn left: turned round where the vertex's orientation is negative, which
/// `turned` records), as certified_stars finds them.
struct StarLinks {
  struct Link {
    int t, a, b;  // triangle t = v a b, or v b a where turned
  };
  std::vector<int> start;  // vertex v's links are link[start[v]] to link[start[v + 1]]
  std::vector<Link> link;
  std::vector<char> turned;
};

/// Per vertex id: whether its star is certified (0 if not, else 1 + 2 axis + (orientation > 0)
/// for the projection that certifies it), that is no two triangles round it meet beyond
/// the vertex and the edge they share. Certified when, projected along one coordinate axis, the
/// triangles' opposite edges a -> b (in the triangles' order) form one cycle through distinct
/// vertices, every triangle v a b is oriented the same way (strictly), and the cycle winds once
/// round v: the sectors at v then tile the plane round it, two sectors meet only in v or along a
/// common ray v b, and since each triangle projects one to one, the triangles meet only in v or
/// along the edge v b. The winding number of a cycle whose every sector turns left is the
/// number of its edges that cross v's horizontal line upwards (Sunday's crossing rule), so all
/// of this is decided with exact signs. `points` are the ids' positions.
/// `links` receives the link edges by vertex (StarLinks).
std::vector<signed char> certified_stars(const std::vector<StarTriangle>& tris, const std::vector<Vector3d>& points,
                                         StarLinks& links) {
  const size_t n = points.size();
  std::vector<int>& start = links.start;
  start.assign(n + 1, 0);
  std::vector<Vector3d> normal(n, Vector3d::Zero());  // only chooses the axis; the tests are exact
  for (const StarTriangle& t : tris)
    for (int id : t.ids) {
      ++start[size_t(id) + 1];
      normal[size_t(id)] += Vector3d(t.normal[0], t.normal[1], t.normal[2]);
    }
  for (size_t v = 0; v < n; ++v) start[v + 1] += start[v];
  std::vector<signed char> axis(n, 0), orientation(n, 0);
  for (size_t v = 0; v < n; ++v) {
    int k = 0;
    normal[v].cwiseAbs().maxCoeff(&k);
    axis[v] = static_cast<signed char>(k);
    orientation[v] = static_cast<signed char>(normal[v][k] > 0 ? 1 : normal[v][k] < 0 ? -1 : 0);
  }
  // The link edges a -> b grouped by vertex (turned round where the projection is mirrored, so
  // that the sectors turn left), each vertex's upward crossings counted, failures marked.
  std::vector<StarLinks::Link>& link = links.link;
  link.resize(static_cast<size_t>(start[n]));
  links.turned.resize(n);
  for (size_t v = 0; v < n; ++v) links.turned[v] = orientation[v] < 0;
  std::vector<int> upward(n, 0);
  std::vector<char> failed(n, 0);
  {
    std::vector<int> next(start.begin(), start.end() - 1);
    for (size_t ti = 0; ti < tris.size(); ++ti)
      for (int k = 0; k < 3; ++k) {
        const StarTriangle& t = tris[ti];
        const size_t v = size_t(t.ids[size_t(k)]);
        const int along = axis[v];
        int sign = t.sign[size_t(along)];
        const Vector3d &pv = points[v], &p1 = points[size_t(t.ids[size_t((k + 1) % 3)])],
                       &p2 = points[size_t(t.ids[size_t((k + 2) % 3)])];
        if (sign == kUndecided) sign = orient2d(drop(pv, along), drop(p1, along), drop(p2, along));
        failed[v] |= static_cast<char>(sign != orientation[v] || orientation[v] == 0);
        int a = t.ids[size_t((k + 1) % 3)], b = t.ids[size_t((k + 2) % 3)];
        const Vector3d *pa = &p1, *pb = &p2;
        if (orientation[v] < 0) std::swap(a, b), std::swap(pa, pb);
        const int height = (along + 2) % 3;  // drop()'s second coordinate
        upward[v] += ((*pa)[height] <= pv[height] && pv[height] < (*pb)[height]) ? 1 : 0;
        link[size_t(next[v]++)] = {int(ti), a, b};
      }
  }
  std::vector<signed char> certified(n, 0);
  std::vector<int> from, to;
  for (size_t v = 0; v < n; ++v) {
    if (failed[v] || upward[v] != 1 || start[v + 1] - start[v] < 3) continue;
    const std::span<const StarLinks::Link> edges(link.data() + start[v], link.data() + start[v + 1]);
    // One cycle through distinct vertices (with the winding number 1, several cycles are excluded
    // already): the starts are distinct and are the ends. Pairwise for short links, else sorted.
    bool cycle = true;
    if (edges.size() <= 16) {
      for (size_t i = 0; i < edges.size() && cycle; ++i) {
        int starts = 0, ends = 0;
        for (const StarLinks::Link& l : edges) starts += l.a == edges[i].a ? 1 : 0, ends += l.b == edges[i].a ? 1 : 0;
        cycle = starts == 1 && ends == 1;
      }
    } else {
      from.clear();
      to.clear();
      for (const StarLinks::Link& l : edges) from.push_back(l.a), to.push_back(l.b);
      std::sort(from.begin(), from.end());
      std::sort(to.begin(), to.end());
      cycle = from == to && std::adjacent_find(from.begin(), from.end()) == from.end();
    }
    if (cycle) certified[v] = static_cast<signed char>(1 + 2 * axis[v] + (orientation[v] > 0 ? 1 : 0));
  }
  return certified;
}

/// Per triangle: the id of the certified patch it belongs to, else -1 - (its index): two
/// triangles of one certified patch meet only in what they share. cls: per triangle 2 axis +
/// (sign > 0), the sign of its projection along its axis as the filter decides it, or -1. A patch
/// is a connected set of triangles of one class joined across edges they share with opposite
/// directions. It is certified when
///  - round each vertex its triangles form one fan, closed or open (distinct ends; a vertex
///    whose star certified_stars certified for this projection has one closed fan);
///  - the open fans' outer edges form one loop, which projects to a simple polygon (closed
///    segments, exact tests).
/// Then the projection is one to one on the patch (the degree of the map): a point of the
/// plane off the projected edges is covered once by each triangle over it, all oriented alike,
/// and as many times as the loop winds round it, at most once. So no two triangles' projections
/// overlap, and none touch but along shared edges and corners (a corner touching another
/// triangle would have its fan overlap a neighbour of that triangle or, on the loop, make the
/// loop touch itself), and the triangles meet only in their common vertices and edges.
/// Every decision is an exact sign or comparison. Unless three quarters of the vertices have
/// certified stars, no patch is looked for (they would be small).
std::vector<int> certified_patches(const std::vector<signed char>& cls, const StarLinks& links,
                                   const std::vector<signed char>& stars, const std::vector<Vector3d>& points) {
  const size_t nt = cls.size(), nv = points.size();
  std::vector<int> patch(nt);
  for (size_t t = 0; t < nt; ++t) patch[t] = -1 - int(t);
  // Patches grow across certified stars; where many are not certified (creases: boxes, the
  // plate drilled 100 times with half its stars certified) they stay small and spare less than
  // they cost, and are not looked for.
  size_t used = 0, certified = 0;
  for (size_t v = 0; v < nv; ++v) {
    used += links.start[v + 1] > links.start[v] ? 1 : 0;
    certified += stars[v] != 0 ? 1 : 0;
  }
  if (4 * certified < 3 * used) return patch;
  // Per vertex v, its classed triangles' link edges a -> b, turned round where the sign is
  // negative so that every sector v a b turns left in the projection.
  using Link = StarLinks::Link;
  auto oriented = [&](size_t v, Link l) {
    if ((links.turned[v] != 0) != ((cls[size_t(l.t)] & 1) == 0)) std::swap(l.a, l.b);
    return l;
  };
  auto fan = [&](size_t v) {
    return std::span<const Link>(links.link.data() + links.start[v], links.link.data() + links.start[v + 1]);
  };
  // Components: triangles of one class across an edge v a (one's link edge leaves a, the other's
  // arrives there). Round a vertex whose star is certified for the class of all its triangles,
  // those form one closed fan, consecutive ones sharing an edge: all are joined at once.
  std::vector<int> parent(nt);
  std::iota(parent.begin(), parent.end(), 0);
  auto find = [&](int x) {
    while (parent[size_t(x)] != x) x = parent[size_t(x)] = parent[size_t(parent[size_t(x)])];
    return x;
  };
  auto whole = [&](size_t v) {  // v's star certified, all its triangles of that class
    if (stars[v] == 0) return false;
    for (const Link& l : fan(v))
      if (cls[size_t(l.t)] != stars[v] - 1) return false;
    return true;
  };
  // Fans of more than kLongFan triangles are not examined (the tests below take the square of a
  // fan's size): the patches through such a vertex are not certified.
  constexpr size_t kLongFan = 64;
  for (size_t v = 0; v < nv; ++v) {
    const std::span<const Link> f = fan(v);
    if (whole(v)) {
      for (const Link& l : f) parent[size_t(find(l.t))] = find(f.front().t);
      continue;
    }
    if (f.size() > kLongFan) continue;
    for (const Link& raw : f) {  // each edge v a at its smaller end
      if (cls[size_t(raw.t)] < 0) continue;
      const Link x = oriented(v, raw);
      if (x.a < int(v)) continue;
      for (const Link& other : f)
        if (cls[size_t(other.t)] == cls[size_t(x.t)] && oriented(v, other).b == x.a) parent[size_t(find(x.t))] = find(other.t);
    }
  }
  std::vector<int> root(nt, -1);  // of each classed triangle's component
  std::vector<char> failed(nt, 0), bounded(nt, 0);  // by root
  for (size_t t = 0; t < nt; ++t)
    if (cls[t] >= 0) root[t] = find(int(t));
  struct Edge {  // a boundary edge from -> to of a patch, with the patch on its left
    int root, from, to;
  };
  std::vector<Edge> edges;
  std::vector<std::pair<int, Link>> group;
  for (size_t v = 0; v < nv; ++v) {
    // A certified star in one patch: one closed fan, nothing more to check (the usual case).
    if (whole(v)) {
      const int r = root[size_t(fan(v).front().t)];
      bool one = true;
      for (const Link& l : fan(v)) one = one && root[size_t(l.t)] == r;
      if (one) continue;
    }
    group.clear();
    bool one = true;  // one patch round v (no sort)
    for (const Link& l : fan(v)) {
      if (cls[size_t(l.t)] < 0) continue;
      group.push_back({root[size_t(l.t)], oriented(v, l)});
      one = one && group.back().first == group.front().first;
    }
    if (!one) std::sort(group.begin(), group.end(), [](const auto& x, const auto& y) { return x.first < y.first; });
    for (size_t g = 0; g < group.size();) {
      size_t e = g + 1;
      while (e < group.size() && group[e].first == group[g].first) ++e;
      const int r = group[g].first;
      if (e - g > kLongFan) {
        failed[size_t(r)] = 1;
        g = e;
        continue;
      }
      // One fan: starts distinct, ends distinct, at most one start that no edge arrives at (its
      // first corner; none: closed), and a walk from there takes every edge.
      bool ok = true;
      int first = -1, starts = 0;
      for (size_t i = g; i < e && ok; ++i) {
        bool arrives = false;
        for (size_t j = g; j < e; ++j) {
          if (j != i) ok = ok && group[j].second.a != group[i].second.a && group[j].second.b != group[i].second.b;
          arrives = arrives || group[j].second.b == group[i].second.a;
        }
        if (!arrives) first = group[i].second.a, ++starts;
      }
      ok = ok && starts <= 1;
      const int begin = starts == 0 ? group[g].second.a : first;
      size_t walked = 0;
      for (int at = begin; ok && walked < e - g;) {
        size_t i = g;
        while (i < e && group[i].second.a != at) ++i;
        if (i == e) break;
        ++walked;
        at = group[i].second.b;
        if (at == begin) break;
      }
      ok = ok && walked == e - g;
      if (ok && starts == 1) edges.push_back({r, int(v), first});  // open: v is on the boundary
      if (!ok) failed[size_t(r)] = 1;
      g = e;
    }
  }
  // One boundary loop per patch, and its projection simple.
  std::sort(edges.begin(), edges.end(), [](const Edge& x, const Edge& y) { return std::tie(x.root, x.from) < std::tie(y.root, y.from); });
  struct Segment {
    Vector2d p, q;
    int from, to;
  };
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
      const auto it = std::lower_bound(edges.begin() + std::ptrdiff_t(g), edges.begin() + std::ptrdiff_t(e), from_vertex,
                                       [](const Edge& x, int y) { return x.from < y; });
      return it != edges.begin() + std::ptrdiff_t(e) && it->from == from_vertex ? it->to : -1;
    };
    size_t steps = 0;
    for (int at = edges[g].from; ok;) {
      at = next_of(at);
      ++steps;
      if (at < 0 || steps > e - g) ok = false;
      else if (at == edges[g].from) break;
    }
    ok = ok && steps == e - g;
    if (ok) {
      // Simple: no two segments meet but consecutive ones at their common end, and those do not
      // fold back along each other. A sweep along the first coordinate.
      segments.clear();
      for (size_t i = g; i < e; ++i)
        segments.push_back({drop(points[size_t(edges[i].from)], axis), drop(points[size_t(edges[i].to)], axis), edges[i].from, edges[i].to});
      std::sort(segments.begin(), segments.end(), [](const Segment& x, const Segment& y) {
        return std::min(x.p.x(), x.q.x()) < std::min(y.p.x(), y.q.x());
      });
      size_t budget = 64 * segments.size() + 4096;  // pairs compared; beyond, not certified
      for (size_t i = 0; i < segments.size() && ok; ++i) {
        const Segment& s = segments[i];
        const double right = std::max(s.p.x(), s.q.x());
        for (size_t j = i + 1; j < segments.size() && ok && std::min(segments[j].p.x(), segments[j].q.x()) <= right; ++j) {
          const Segment& u = segments[j];
          if (budget-- == 0) {
            ok = false;
            break;
          }
          if (std::max(s.p.y(), s.q.y()) < std::min(u.p.y(), u.q.y()) || std::max(u.p.y(), u.q.y()) < std::min(s.p.y(), s.q.y()))
            continue;
          if (s.to == u.from || u.to == s.from) {
            // Consecutive: w -> m -> z meet only at m unless they run back along each other.
            const bool s_first = s.to == u.from;
            const Vector2d &w = s_first ? s.p : u.p, &m = s_first ? s.q : u.q, &z = s_first ? u.q : s.q;
            ok = orient2d(w, m, z) != 0 || (m - w).dot(z - m) > 0;
            if (s.to == u.from && u.to == s.from) ok = false;  // a loop of two edges
            continue;
          }
          ok = !segments_meet_2d(s.p, s.q, u.p, u.q);
        }
      }
    }
    if (!ok) failed[size_t(r)] = 1;
    g = e;
  }
  for (size_t t = 0; t < nt; ++t) {
    if (cls[t] < 0) continue;
    const int r = root[t];
    if (!failed[size_t(r)] && bounded[size_t(r)]) patch[t] = r;
  }
  return patch;
}

}  // namespace

PreparedTriangle prepare_triangle(const std::array<int, 3>& ids, const std::array<Vector3d, 3>& p) {
  PreparedTriangle t;
  t.ids = ids;
  t.p = p;
  t.plane = orient3d_plane(p[0], p[1], p[2]);
  // The projection along axis k has the signed area plane.minor[k] (certified_minor): the axis
  // of the largest certified area, else the first whose exact orient2d is non-zero.
  t.axis = -1;
  double best = 0;
  for (int axis = 0; axis < 3; ++axis) {
    const double area = std::abs(t.plane.minor[axis]);
    if (certified_minor(t.plane, axis) && area > best) t.axis = axis, best = area;
  }
  for (int axis = 0; axis < 3 && t.axis < 0; ++axis)
    if (orient2d(drop(p[0], axis), drop(p[1], axis), drop(p[2], axis)) != 0) t.axis = axis;
  return t;
}

bool triangles_meet(const PreparedTriangle& a, const PreparedTriangle& b) { return triangles_conflict(a, b); }

bool triangles_meet(const std::array<int, 3>& ids_a, const std::array<Vector3d, 3>& a,
                    const std::array<int, 3>& ids_b, const std::array<Vector3d, 3>& b) {
  PreparedTriangle s = prepare_triangle(ids_a, a), t = prepare_triangle(ids_b, b);
  s.axis = std::max(s.axis, 0);  // degenerate (excluded by the precondition): axis 0, as before
  t.axis = std::max(t.axis, 0);
  return triangles_conflict(s, t);
}

std::vector<int> find_self_crossing_faces(const PolygonMesh& mesh, size_t max_faces) {
  std::vector<int> out;
  for (size_t fi = 0; fi < mesh.faces.size() && out.size() < max_faces; ++fi) {
    const auto& f = mesh.faces[fi];
    const size_t n = f.size();
    if (n <= 3) continue;
    const int axis = projection_axis(mesh, f);
    if (axis < 0) continue;
    std::vector<Vector2d> p;
    for (int v : f) p.push_back(drop(mesh.vertices[v], axis));
    bool crossing = false;
    for (size_t i = 0; i < n && !crossing; ++i)
      for (size_t j = i + 2; j < n && !crossing; ++j) {
        if (i == 0 && j == n - 1) continue;  // neighbours through the closing edge
        crossing = segments_meet_2d(p[i], p[(i + 1) % n], p[j], p[(j + 1) % n]);
      }
    if (crossing) out.push_back(static_cast<int>(fi));
  }
  return out;
}

std::vector<FacePair> find_self_intersections(const PolygonMesh& mesh, SelfIntersectionOptions options) {
  return search_self_intersections(mesh, options).pairs;
}

SelfIntersectionSearch search_self_intersections(const PolygonMesh& mesh, SelfIntersectionOptions options) {
  SelfIntersectionSearch result;
  const size_t nv = mesh.vertices.size();
  const std::vector<int> canon = options.distinct_vertices ? identity_ids(nv) : mesh::detail::first_copies(mesh.vertices);

  // Faces with every corner marked exact (the flags are used only when there is one per vertex):
  // pairs of their triangles are not examined (see SelfIntersectionOptions::exact_vertices).
  const bool marked = !options.exact_vertices.empty() && options.exact_vertices.size() == nv;
  auto exact_face = [&](const std::vector<int>& f) {
    return marked && std::all_of(f.begin(), f.end(), [&](int v) { return options.exact_vertices[size_t(v)] != 0; });
  };
  if (marked && std::all_of(mesh.faces.begin(), mesh.faces.end(), exact_face)) return result;
  // Per triangle: what the exact tests read, its box, what the stars' certification reads, and
  // what the scan reads (Slot).
  struct Slot {
    std::array<float, 6> box{};  // min x, y, z, max x, y, z, as_float
    int face = 0;
    bool exact = false;  // every corner of its face is marked exact (SelfIntersectionOptions)
    // Per corner: its id where the vertex's star is certified, else -1 - (its triangle): no
    // corner of another triangle has that number.
    std::array<int, 3> star{};
    int patch = 0;  // certified_patches
  };
  std::vector<PreparedTriangle> tris;
  std::vector<Eigen::AlignedBox3d> boxes;
  std::vector<StarTriangle> stars;
  std::vector<signed char> cls;
  std::vector<Slot> slots;
  {
    size_t corners = 0;
    for (const auto& f : mesh.faces) corners += f.size() >= 2 ? f.size() - 2 : 0;
    tris.reserve(corners);
    boxes.reserve(corners);
    stars.reserve(corners);
    cls.reserve(corners);
    slots.reserve(corners);
  }
  size_t moved = 0;  // triangles of faces with a corner not marked exact
  PolygonTriangulator triangulator;
  std::vector<IndexTriangle> face_tris;
  for (size_t fi = 0; fi < mesh.faces.size(); ++fi) {
    const bool exact = exact_face(mesh.faces[fi]);
    face_tris.clear();
    triangulator.append(mesh.vertices, mesh.faces[fi], face_tris, EarOrder::Spread);
    for (const IndexTriangle& it : face_tris) {
      const PreparedTriangle t = prepare_triangle({canon[it[0]], canon[it[1]], canon[it[2]]},
                                                  {mesh.vertices[it[0]], mesh.vertices[it[1]], mesh.vertices[it[2]]});
      if (t.axis < 0) continue;  // collinear corners: degenerate, reported elsewhere
      Eigen::AlignedBox3d box;
      for (int k = 0; k < 3; ++k) box.extend(t.p[k]);
      Slot slot;
      for (int k = 0; k < 3; ++k) {
        slot.box[size_t(k)] = as_float(box.min()[k]);
        slot.box[size_t(k) + 3] = as_float(box.max()[k]);
      }
      slot.face = static_cast<int>(fi);
      slot.exact = exact;
      slot.star = t.ids;
      tris.push_back(t);
      boxes.push_back(box);
      stars.push_back(star_triangle(t));
      // Its class for certified_patches: its axis and the sign of its projection there, or -1
      // where the filter leaves that sign open.
      const int sign = stars.back().sign[size_t(t.axis)];
      cls.push_back(static_cast<signed char>(sign == 1 || sign == -1 ? 2 * t.axis + (sign > 0 ? 1 : 0) : -1));
      slots.push_back(slot);
      moved += exact ? 0 : 1;
    }
  }
  if (moved == 0) return result;
  // Pairs that share a vertex whose star is certified are not examined (certified_stars), nor
  // pairs of one certified patch (certified_patches).
  {
    StarLinks links;
    const std::vector<signed char> certified = certified_stars(stars, mesh.vertices, links);
    const std::vector<int> patch = certified_patches(cls, links, certified, mesh.vertices);
    for (size_t i = 0; i < slots.size(); ++i) slots[i].patch = patch[i];
    for (size_t i = 0; i < slots.size(); ++i)
      for (int& id : slots[i].star) id = certified[size_t(id)] != 0 ? id : -1 - int(i);
  }
  // Broad phase (mesh/detail/box_grid.hpp): a uniform grid over the triangles' boxes; a pair
  // whose boxes overlap is examined in the one cell that owns it, so once. The scan compares the
  // boxes rounded to floats: they overlap where the boxes do, and a pair that overlaps only after
  // rounding has triangles that do not meet, so the cell that examines it does not matter.
  std::set<std::pair<int, int>> found;
  const mesh::detail::BoxGrid grid(boxes);
  size_t candidates = 0, scanned = 0;
  // Per cell: its members gathered field by field, then for each member the later members whose
  // boxes overlap its own collected without branching (the box tests are unpredictable; the
  // compiler runs several at a time), then those examined. mask: bits 0-2
  // BoxGrid::first_cell_masks, bit 3 an exact triangle.
  std::array<std::vector<float>, 6> lo_hi;
  std::vector<int> face, patch, keep, hits;
  std::vector<unsigned> mask;
  std::vector<std::array<int, 3>> star;
  for (size_t k = 0; k < grid.cells() && found.size() < options.max_pairs && result.complete; ++k) {
    const std::span<const int> here = grid.cell(k);
    if (moved < tris.size() && std::all_of(here.begin(), here.end(), [&](int i) { return slots[size_t(i)].exact; }))
      continue;  // only exact triangles here: nothing to examine
    const size_t m = here.size();
    for (auto& v : lo_hi) v.resize(m);
    face.resize(m);
    patch.resize(m);
    keep.resize(m);
    hits.resize(m);
    mask.resize(m);
    star.resize(m);
    const std::span<const unsigned char> first = grid.first_cell_masks(k);
    for (size_t i = 0; i < m; ++i) {
      const Slot& slot = slots[size_t(here[i])];
      for (size_t c = 0; c < 6; ++c) lo_hi[c][i] = slot.box[c];
      face[i] = slot.face;
      patch[i] = slot.patch;
      mask[i] = first[i] | (slot.exact ? 8u : 0u);
      star[i] = slot.star;
    }
    const float *x0 = lo_hi[0].data(), *y0 = lo_hi[1].data(), *z0 = lo_hi[2].data();
    const float *x1 = lo_hi[3].data(), *y1 = lo_hi[4].data(), *z1 = lo_hi[5].data();
    for (size_t i = 0; i < m && found.size() < options.max_pairs && result.complete; ++i) {
      scanned += m - i - 1;
      if (scanned / 64 > options.max_candidates) {  // the sweep itself is cheap, not free
        result.complete = false;
        break;
      }
      // Examined: a triangle of another face and another patch whose box overlaps, in the cell
      // that owns the pair, not both exact.
      const float sx0 = x0[i], sy0 = y0[i], sz0 = z0[i], sx1 = x1[i], sy1 = y1[i], sz1 = z1[i];
      const int sf = face[i], sp = patch[i];
      const unsigned sm = mask[i];
      for (size_t j = i + 1; j < m; ++j)
        keep[j] = int(face[j] != sf) & int(patch[j] != sp) & int(x0[j] <= sx1) & int(sx0 <= x1[j]) & int(y0[j] <= sy1) & int(sy0 <= y1[j]) &
                  int(z0[j] <= sz1) & int(sz0 <= z1[j]) & int(((mask[j] | sm) & 7u) == 7u) & int((mask[j] & sm & 8u) == 0u);
      size_t count = 0;
      for (size_t j = i + 1; j < m; ++j) {
        hits[count] = int(j);
        count += size_t(keep[j]);
      }
      // Pairs that share a vertex whose star is certified meet only in what they share; the rest
      // are decided exactly, their triangles fetched ahead.
      const std::array<int, 3>& x = star[i];
      size_t left = 0;
      for (size_t h = 0; h < count; ++h) {
        const std::array<int, 3>& y = star[size_t(hits[h])];
        const bool shared = (x[0] == y[0]) | (x[0] == y[1]) | (x[0] == y[2]) | (x[1] == y[0]) | (x[1] == y[1]) |
                            (x[1] == y[2]) | (x[2] == y[0]) | (x[2] == y[1]) | (x[2] == y[2]);
        hits[left] = hits[h];
        left += shared ? 0 : 1;
      }
      for (size_t h = 0; h < left; ++h) prefetch(tris[size_t(here[size_t(hits[h])])]);
      for (size_t h = 0; h < left; ++h) {
        const size_t j = size_t(hits[h]);
        if (++candidates > options.max_candidates) {
          result.complete = false;
          break;
        }
        const auto face_pair = std::minmax(sf, face[j]);
        if (!found.empty() && found.count(face_pair)) continue;
        if (triangles_conflict(tris[size_t(here[i])], tris[size_t(here[j])])) {
          found.insert(face_pair);
          if (found.size() >= options.max_pairs) break;
        }
      }
    }
  }
  for (auto [a, b] : found) result.pairs.push_back({a, b});
  return result;
}

}  // namespace sculpt
