#pragma once
/// \file revolve.hpp
/// Solids of revolution as nearly balanced BSP trees (Ihm & Naylor 1990, section 6).
///
///   Solid goblet = revolve(profile, circular_path(32));             // profile: (r, z) points
///   Solid head = revolve(face, ellipse_path(1.0, 0.8, 32));
///   Solid ring = revolve({{1, 0}, {2, 0}, {2, 1}, {1, 1}}, circular_path(32), {.closed = true});
///   Solid half = revolve(profile, circular_path(32), {.angle = 180});
///
/// An open profile is a polyline in the half-plane r >= 0, monotone in z (see monotone_profile);
/// it is revolved along a convex path (path_polygon.hpp): profile point (r, z) and path vertex
/// (u, v) give the point (r u, r v, z). Where the profile does not end on the axis the solid is
/// closed by a flat cap. The tree is revolve_plane_tree()'s: horizontal planes through the
/// profile's vertices (balanced), then per slab the path's tree lifted (face planes only for the
/// last few faces). Size (partitioning nodes) about 1.4 n m for n path edges and m segments, height
/// O(log n + log m). Every plane is exact (see snap_revolution), so neighbouring slabs meet
/// without cracks and the solid is exactly the polytope of the snapped profile and path.
///
/// A closed profile is a simple polygon in r >= 0 (holes, overhangs, a hollow wall, a torus's
/// cross-section): its region is split into z-monotone pieces (profile_pieces.hpp), each revolved
/// as above (outer radius minus inner radius), and the pieces united. A partial revolution keeps
/// the part of the solid between the half-planes through the z axis at 0 and `angle` degrees.
/// See docs/revolution.md.

#include <vector>

#include <Eigen/Core>

#include "bsp/convex_path.hpp"
#include "bsp/solid.hpp"

namespace sculpt::revolution {

/// Options of the section 6 construction.
struct RevolveOptions {
  int face_only_below = 6;  ///< path sub-curves this short use face planes only (paper: "say 6")
  kernel::Grid grid{};      ///< the grid the profile is snapped to, carried by the solid (docs/kernel.md)
  /// The profile is a closed polygon: its last point joins its first. A profile whose last point
  /// equals its first (at least 3 points) is closed either way.
  bool closed = false;
  /// Degrees of revolution, 0 < angle <= 360, from the +x axis counter-clockwise about z (seen
  /// from +z), like OpenSCAD's rotate_extrude. Below 360 the solid is cut by the half-planes
  /// through the z axis at 0 and `angle` (where the path has a vertex in that direction, the cut
  /// runs exactly through the solid's edges there).
  double angle = 360;
};

/// Whether revolve() takes `profile` as closed (options.closed, or last point == first point).
bool is_closed_profile(const std::vector<Eigen::Vector2d>& profile, const RevolveOptions& options = {});

/// The inputs revolve() actually revolves: the profile snapped to the kernel grid, made monotone
/// (increasing z) if open, or counter-clockwise without a repeated point if closed, and the path
/// snapped to the dyadic lattice with `path_bits` bits (the largest, at most 18, for which the path
/// stays strictly convex and every lifted plane fits the kernel's bit budget). For an open profile
/// revolve_boundary() and revolved_volume() of these give the full revolution's exact shape.
struct SnappedRevolution {
  std::vector<Eigen::Vector2d> profile;
  ConvexPath path;
  int path_bits = 0;
  bool closed = false;  ///< profile is a closed polygon (closed_profile in trees/profile_pieces.hpp)
};

/// \throw InvalidInput (see monotone_profile and closed_profile: the message names the point or
///        the crossing edges; an angle outside (0, 360]), RangeError if a point of the solid would
///        lie outside the kernel's world range, GeometryError if the path is too fine to stay
///        convex on any representable lattice (more than about 500 edges per unit radius)
SnappedRevolution snap_revolution(const std::vector<Eigen::Vector2d>& profile, const ConvexPath& path,
                                  const RevolveOptions& options = {});

/// The solid of revolution of `profile` along `path` (section 6 construction, exact planes), over
/// options.angle degrees. A closed profile away from the axis (a piece with an inner radius) needs
/// a path around the axis (the origin inside or on it): its pieces are outer minus inner solids.
/// \throw as snap_revolution; InvalidInput for a closed profile with an inner radius and a path
///        that does not contain the axis
Solid revolve(const std::vector<Eigen::Vector2d>& profile, const ConvexPath& path, const RevolveOptions& options = {});

}  // namespace sculpt::revolution
