#pragma once
/// \file convex_polygon.hpp
/// Plane-based convex polygons (Bernstein & Fussell 2009, sec. 3; Naylor et al. 1990 "sub-
/// hyperplanes"): a support plane and a cycle of edge planes, no coordinates. Splitting by a
/// plane creates no new numbers, only new plane triples, so it is exact and never cracks.
/// Planes are referred to by index into a PlaneTable (kernel/plane_table.hpp) shared by all
/// polygons of one tree.

#include <algorithm>
#include <boost/container/small_vector.hpp>
#include <cmath>
#include <cstdint>
#include <limits>
#include <span>
#include <vector>

#include "base/assert.hpp"
#include "kernel/plane_table.hpp"
#include "kernel/predicates.hpp"

namespace sculpt::kernel {

/// An error bound as a float no smaller than `err` (a larger bound is still a bound); negative
/// (no approximation) stays negative.
inline float bound_up(double err) {
  if (!(err >= 0)) return err < 0 ? -1.0f : std::numeric_limits<float>::quiet_NaN();
  if (err > double(std::numeric_limits<float>::max())) return std::numeric_limits<float>::infinity();
  float f = float(err);
  if (double(f) < err) f = std::nextafter(f, std::numeric_limits<float>::infinity());
  return f;
}

/// Corner i of a polygon: the vertex support ∩ p ∩ q (approximated by at()) and the edge from
/// this corner to the next one, which lies on plane `edge` (the polygon is on its negative side).
/// The approximation's error bound is kept as a float rounded up, in the space after p and q:
/// a corner takes 40 bytes instead of 48 (fragments are most of a set operation's memory).
struct Corner {
  std::int32_t edge = 0;
  std::int32_t p = 0, q = 0;

  Corner() = default;
  Corner(std::int32_t edge_, std::int32_t p_, std::int32_t q_, const ApproxPoint& at_)
      : edge(edge_), p(p_), q(q_), err_(bound_up(at_.err)), x_(at_.x), y_(at_.y), z_(at_.z) {}
  [[nodiscard]] ApproxPoint at() const { return {x_, y_, z_, double(err_)}; }
  void set_at(const ApproxPoint& at_) {
    x_ = at_.x, y_ = at_.y, z_ = at_.z;
    err_ = bound_up(at_.err);
  }

 private:
  float err_ = -1;
  double x_ = 0, y_ = 0, z_ = 0;
};
static_assert(sizeof(Corner) == 40);

/// A convex polygon read where it is stored (a ConvexPolygon, or a fragment of a solid's compact
/// boundary list, bsp/fragment_list.hpp): what the functions below that only read take.
struct PolygonView {
  std::int32_t support = -1;
  std::span<const Corner> corners;
  [[nodiscard]] bool empty() const { return corners.empty(); }
};

/// A convex polygon on plane `support`, corners counter-clockwise seen from the support's
/// positive side. An empty corner list is the empty polygon. Four corners are stored inline:
/// triangles and quadrilaterals (97 % of a set operation's fragments on meshes and spheres) take
/// no allocation.
struct ConvexPolygon {
  std::int32_t support = -1;
  boost::container::small_vector<Corner, 4> corners;
  [[nodiscard]] bool empty() const { return corners.empty(); }
  operator PolygonView() const { return {support, {corners.data(), corners.size()}}; }  // NOLINT: implicit
  /// This polygon becomes a copy of `view` (which must not be this polygon's own corners).
  void assign(PolygonView view) {
    support = view.support;
    corners.assign(view.corners.begin(), view.corners.end());
  }
  /// A polygon of its own with the corners of `view`.
  static ConvexPolygon copy_of(PolygonView view) {
    ConvexPolygon poly;
    poly.assign(view);
    return poly;
  }
};

/// Number of world-box planes: indices 0..5 of every PlaneTable (+x, -x, +y, -y, +z, -z faces).
inline constexpr std::int32_t kWorldPlanes = 6;

struct WorldPolygonOptions {
  /// Corner approximations from a cheaper closed formula: rigorous error bounds, but not the
  /// bits approximate_vertex gives. For polygons about to be clipped (most world corners are
  /// cut away); refresh_world_corners() then restores the usual values on the survivors.
  bool quick_corners = false;
};
/// The polygon support ∩ world box (a quadrilateral whose edges are world-box planes).
ConvexPolygon world_polygon(const PlaneTable& planes, std::int32_t support, const WorldPolygonOptions& options = {});
/// Recomputes the approximation of every corner made of two world-box planes as
/// approximate_vertex(support, p, q): what world_polygon() without quick corners gives.
void refresh_world_corners(const PlaneTable& planes, ConvexPolygon& poly);

/// Where a polygon lies with respect to a plane.
enum class Side : std::int8_t { Negative, Positive, Both, On };

/// Bounding box of a polygon's corners widened by their approximation errors (grid units), for a
/// quick exact-safe side test that callers can keep while a polygon is tested against many
/// planes. `valid` is false for an empty polygon or a corner without a usable approximation.
struct CornerBox {
  double lo[3] = {0, 0, 0}, hi[3] = {0, 0, 0};
  bool valid = false;
};
CornerBox corner_box(PolygonView poly);
/// Negative or Positive if the whole box lies strictly on that side of the plane (beyond the
/// rounding error of the evaluation), else Both (undecided: use classify or split).
/// The plane's largest and smallest values over the box are compared with the bound of the
/// rounding error of their evaluation.
inline Side box_side(const CornerBox& box, const Plane& plane) {
  if (!box.valid) return Side::Both;
  const double n[3] = {double(plane.a), double(plane.b), double(plane.c)};
  const double d = plane.d_nearest;
  double vmax = d, vmin = d, mag = std::fabs(d);
  for (int i = 0; i < 3; ++i) {
    const double p = n[i] * box.lo[i], q = n[i] * box.hi[i];
    vmax += std::max(p, q);
    vmin += std::min(p, q);
    mag += std::max(std::fabs(p), std::fabs(q));
  }
  const double tol = 16.0 * 1.1102230246251565e-16 * mag;  // 16 units of roundoff (2^-53)
  if (vmax < -tol) return Side::Negative;
  if (vmin > tol) return Side::Positive;
  return Side::Both;
}
/// Classification only (no new polygons).
Side classify(const PlaneTable& planes, PolygonView poly, std::int32_t plane);

/// The two parts of a polygon cut by a plane, filled only when `side` is Both (otherwise the
/// whole polygon lies on that side, or on the plane for On, and both parts are left empty).
struct PolygonSplit {
  Side side;
  ConvexPolygon negative, positive;
};
/// Splits `poly` by plane `cut`; `cut_opposite` is the index of the opposite plane (used as
/// the new edge of the positive part).
PolygonSplit split(const PlaneTable& planes, PolygonView poly, std::int32_t cut, std::int32_t cut_opposite);
/// split() into polygons the caller owns (loops that reuse their storage): `negative` and
/// `positive` are written only when the result is Both. Neither may be `poly`.
Side split(const PlaneTable& planes, PolygonView poly, std::int32_t cut, std::int32_t cut_opposite,
           ConvexPolygon& negative, ConvexPolygon& positive);

/// The negative part of split() for loops that clip one polygon by many planes (TreeBuilder):
/// `in` clipped to the closed negative side of plane `cut`. `box` must be corner_box(in). Returns
/// the side as split() would; only for Both is `out` written (exactly split().negative, corner
/// for corner) and `box` set to corner_box(out). Negative, Positive and On leave both alone:
/// `in` is the result (the caller decides what Positive and On mean). `out` must not be `in`.
/// clip_to_negative_exact skips the box test (for callers that made it).
Side clip_to_negative_exact(const PlaneTable& planes, PolygonView in, ConvexPolygon& out, CornerBox& box,
                            std::int32_t cut);
inline Side clip_to_negative(const PlaneTable& planes, PolygonView in, ConvexPolygon& out, CornerBox& box,
                             std::int32_t cut) {
  const Side quick = box_side(box, planes[cut]);  // most far planes end here
  return quick != Side::Both ? quick : clip_to_negative_exact(planes, in, out, box, cut);
}

/// Approximate vertex positions (grid units) of a polygon, for output and measures.
std::vector<Eigen::Vector3d> approximate_corners(PolygonView poly);

}  // namespace sculpt::kernel
