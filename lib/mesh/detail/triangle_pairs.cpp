#include "mesh/detail/triangle_pairs.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <initializer_list>
#include <utility>

namespace sculpt::mesh::detail {
namespace {

using Eigen::Vector2d;
using Eigen::Vector3d;

/// Point q in the closed 2D triangle (t0, t1, t2) of either orientation.
bool point_in_triangle_2d(const Vector2d& q, const Vector2d& t0, const Vector2d& t1, const Vector2d& t2) {
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
           segments_meet_2d(a, b, t0, t1) || segments_meet_2d(a, b, t1, t2) || segments_meet_2d(a, b, t2, t0);
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
bool coplanar_triangles_meet(const PreparedTriangle& x, const PreparedTriangle& y, int axis) {
  return !projections_separated(x, y, axis);
}

/// orient3d(t.p[0], t.p[1], t.p[2], q): t's plane filter first (tp = plane_of(t)), the exact
/// predicate where it is undecided.
int side(const PreparedTriangle& t, const Orient3dPlane& tp, const Vector3d& q) {
  const int f = orient3d_filtered(tp, q);
  return f != kUndecided ? f : orient3d(t.p[0], t.p[1], t.p[2], q);
}

/// Any edge of `x` (among those listed) meets triangle `y` (yp = plane_of(y)).
bool edges_meet(const PreparedTriangle& x, std::initializer_list<std::pair<int, int>> edges, const PreparedTriangle& y,
                const Orient3dPlane& yp) {
  for (auto [i, j] : edges)
    if (segment_meets_triangle(x.p[i], x.p[j], side(y, yp, x.p[i]), side(y, yp, x.p[j]), y)) return true;
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

}  // namespace

bool segments_meet_2d(const Vector2d& a, const Vector2d& b, const Vector2d& c, const Vector2d& d) {
  const int o1 = orient2d(a, b, c), o2 = orient2d(a, b, d);
  const int o3 = orient2d(c, d, a), o4 = orient2d(c, d, b);
  if (o1 * o2 < 0 && o3 * o4 < 0) return true;
  auto on_segment = [](const Vector2d& s, const Vector2d& t, const Vector2d& q) {
    return std::min(s.x(), t.x()) <= q.x() && q.x() <= std::max(s.x(), t.x()) && std::min(s.y(), t.y()) <= q.y() &&
           q.y() <= std::max(s.y(), t.y());
  };
  return (o1 == 0 && on_segment(a, b, c)) || (o2 == 0 && on_segment(a, b, d)) || (o3 == 0 && on_segment(c, d, a)) ||
         (o4 == 0 && on_segment(c, d, b));
}

PreparedTriangle prepare_triangle(const std::array<int, 3>& ids, const std::array<Vector3d, 3>& p) {
  PreparedTriangle t;
  t.ids = ids;
  t.p = p;
  const Orient3dPlane plane = plane_of(t);
  // The projection along axis k has the signed area plane.minor[k] (certified_minor): the axis
  // of the largest certified area, else the first whose exact orient2d is non-zero.
  t.axis = -1;
  double best = 0;
  for (int axis = 0; axis < 3; ++axis) {
    const double area = std::abs(plane.minor[axis]);
    if (certified_minor(plane, axis) && area > best) t.axis = axis, best = area;
  }
  for (int axis = 0; axis < 3 && t.axis < 0; ++axis)
    if (orient2d(drop(p[0], axis), drop(p[1], axis), drop(p[2], axis)) != 0) t.axis = axis;
  return t;
}

// Decided exactly; where the floating-point filter leaves a side of a plane undecided (nearly
// coplanar triangles, whose exact signs are costly), a projection that separates them is tried
// first: it only ever proves that they do not meet, so the decisions are those of the exact
// tests alone.
bool triangles_meet(const PreparedTriangle& s, const PreparedTriangle& t) {
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
    const Orient3dPlane tp = plane_of(t);
    const int f0 = orient3d_filtered(tp, s.p[0]);
    const int f1 = orient3d_filtered(tp, s.p[1]);
    const int f2 = orient3d_filtered(tp, s.p[2]);
    const bool undecided = f0 == kUndecided || f1 == kUndecided || f2 == kUndecided;
    if (!undecided && ((f0 > 0 && f1 > 0 && f2 > 0) || (f0 < 0 && f1 < 0 && f2 < 0))) return false;
    if (undecided && projections_separated(s, t, t.axis)) return false;
    const int s0 = decided(f0, t.p[0], t.p[1], t.p[2], s.p[0]), s1 = decided(f1, t.p[0], t.p[1], t.p[2], s.p[1]);
    const int s2 = decided(f2, t.p[0], t.p[1], t.p[2], s.p[2]);
    if ((s0 > 0 && s1 > 0 && s2 > 0) || (s0 < 0 && s1 < 0 && s2 < 0)) return false;
    if (s0 == 0 && s1 == 0 && s2 == 0) return coplanar_triangles_meet(s, t, t.axis);
    const Orient3dPlane sp = plane_of(s);
    const int t0 = side(s, sp, t.p[0]), t1 = side(s, sp, t.p[1]), t2 = side(s, sp, t.p[2]);
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
    const Orient3dPlane tp = plane_of(t), sp = plane_of(s);
    const int f1 = orient3d_filtered(tp, s1), f2 = orient3d_filtered(tp, s2);
    const bool undecided = f1 == kUndecided || f2 == kUndecided;
    if (!undecided && f1 * f2 > 0) return false;
    // The same with the roles exchanged: t meets s's plane only at p.
    const int g1 = orient3d_filtered(sp, t.p[(j + 1) % 3]), g2 = orient3d_filtered(sp, t.p[(j + 2) % 3]);
    if (g1 != kUndecided && g2 != kUndecided && g1 * g2 > 0) return false;
    if (undecided && wedges_separated(s, i, t, j)) return false;
    const int o1 = decided(f1, t.p[0], t.p[1], t.p[2], s1), o2 = decided(f2, t.p[0], t.p[1], t.p[2], s2);
    if (o1 * o2 > 0) return false;
    return segment_meets_triangle(s1, s2, o1, o2, t) || edges_meet(t, {{(j + 1) % 3, (j + 2) % 3}}, s, sp);
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
    const int fb = orient3d_filtered(plane_of(s), b);
    if (fb != kUndecided) return false;  // not coplanar (the filter decides no zero)
    const int sa = orient2d(drop(p, s.axis), drop(q, s.axis), drop(a, s.axis));
    const int sb = orient2d(drop(p, s.axis), drop(q, s.axis), drop(b, s.axis));
    return sa == sb && orient3d(p, q, a, b) == 0;
  }
  return true;  // the same triangle twice
}

}  // namespace sculpt::mesh::detail
