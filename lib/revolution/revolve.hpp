#pragma once
/// \file revolve.hpp
/// Solids of revolution as nearly balanced BSP trees (Ihm & Naylor 1990, section 6).
///
///   Solid goblet = revolve(profile, circular_path(32));             // profile: (r, z) points
///   Solid head = revolve(face, ellipse_path(1.0, 0.8, 32));
///
/// The profile is a polyline in the half-plane r >= 0, monotone in z (see monotone_profile); it
/// is revolved along a convex path (path_polygon.hpp): profile point (r, z) and path vertex (u, v)
/// give the point (r u, r v, z). Where the profile does not end on the axis the solid is closed
/// by a flat cap. The tree is revolve_plane_tree()'s: horizontal planes through the profile's
/// vertices (balanced), then per slab the path's tree lifted (face planes only for the last few
/// faces). Size (partitioning nodes) about 1.4 n m for n path edges and m segments, height
/// O(log n + log m). Every plane is exact (see snap_revolution), so neighbouring slabs meet
/// without cracks and the solid is exactly the polytope of the snapped profile and path.

#include <vector>

#include <Eigen/Core>

#include "bsp/convex_path.hpp"
#include "bsp/solid.hpp"

namespace sculpt::revolution {

/// Options of the section 6 construction.
struct RevolveOptions {
  int face_only_below = 6;  ///< path sub-curves this short use face planes only (paper: "say 6")
  kernel::Grid grid{};      ///< the grid the profile is snapped to, carried by the solid (docs/kernel.md)
};

/// The inputs revolve() actually revolves: the profile made monotone (increasing z) and snapped to
/// the kernel grid, and the path snapped to the dyadic lattice with `path_bits` bits (the largest,
/// at most 18, for which the path stays strictly convex and every lifted plane fits the kernel's
/// bit budget). revolve_boundary() and revolved_volume() of these give the solid's exact shape.
struct SnappedRevolution {
  std::vector<Eigen::Vector2d> profile;
  ConvexPath path;
  int path_bits = 0;
};

/// \throw InvalidInput (see monotone_profile), RangeError if a point of the solid would lie
///        outside the kernel's world range, GeometryError if the path is too fine to stay convex
///        on any representable lattice (more than about 500 edges per unit radius)
SnappedRevolution snap_revolution(const std::vector<Eigen::Vector2d>& profile, const ConvexPath& path,
                                  const RevolveOptions& options = {});

/// The solid of revolution of `profile` along `path` (section 6 construction, exact planes).
/// \throw as snap_revolution
Solid revolve(const std::vector<Eigen::Vector2d>& profile, const ConvexPath& path, const RevolveOptions& options = {});

}  // namespace sculpt::revolution
