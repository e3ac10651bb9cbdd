#pragma once
/// \file triangle_pairs.hpp
/// The exact test of two triangles of a mesh (the narrow phase of search_self_intersections and
/// of the output rounding's crossing search): triangles prepared once (corner ids, corners, plane
/// filter, projection axis), then decided with orient3d, a triangle strictly on one side of the
/// other's plane rejected first, coplanar pairs by separating edge lines, otherwise by
/// segment-triangle tests (Guigue & Devillers 2003 give the same decisions). Corners with equal
/// ids are one corner: what two triangles share is not a meeting.

#include <array>
#include <cmath>

#include <Eigen/Core>

#include "mesh/predicates.hpp"

namespace sculpt::mesh::detail {

/// v projected along the coordinate axis `axis` (the other two coordinates, in cyclic order).
inline Eigen::Vector2d drop(const Eigen::Vector3d& v, int axis) { return {v[(axis + 1) % 3], v[(axis + 2) % 3]}; }

/// Closed 2D segments [a,b] and [c,d] meet (exact).
bool segments_meet_2d(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c,
                      const Eigen::Vector2d& d);

/// Whether the sign of plane.minor[axis] is certain: that minor is orient2d's filter value for the
/// projection of the plane's triangle along `axis` (differences to its first corner, Shewchuk's
/// form), so his orient2d bound applies. (Inline: prepare_triangle and star_triangle call it
/// per axis of every triangle.)
inline bool certified_minor(const Orient3dPlane& plane, int axis) {
  const double m = plane.minor[axis], perm = plane.permanent[axis];
  return std::abs(m) > sculpt::detail::kOrient2dFilterBound * perm && perm > sculpt::detail::kFilterNoUnderflow &&
         std::isfinite(m);
}

/// A triangle as triangles_meet reads it: corner ids, corners, and a coordinate axis along which
/// it projects without degeneracy (-1: its corners are collinear). The plane part of orient3d's
/// filter for its plane (plane_of) is made where a test needs it rather than kept: on a million
/// triangles it would be 72 MB at the peak of the output check, for a few dozen flops per pair.
struct PreparedTriangle {
  std::array<int, 3> ids{};
  std::array<Eigen::Vector3d, 3> p;
  int axis = 0;
};

/// orient3d_plane(t.p[0], t.p[1], t.p[2]): the same values every time (no contraction).
inline Orient3dPlane plane_of(const PreparedTriangle& t) { return orient3d_plane(t.p[0], t.p[1], t.p[2]); }

/// The triangle with these ids and corners, its plane filter computed and its axis found: that of
/// the largest projected area when the filter certifies it non-zero, else the first along which an
/// exact orient2d is non-zero.
PreparedTriangle prepare_triangle(const std::array<int, 3>& ids, const std::array<Eigen::Vector3d, 3>& p);

/// The two triangles meet beyond the corners they share and the edge they share, decided exactly.
/// \pre neither is degenerate (axis >= 0).
bool triangles_meet(const PreparedTriangle& a, const PreparedTriangle& b);

}  // namespace sculpt::mesh::detail
