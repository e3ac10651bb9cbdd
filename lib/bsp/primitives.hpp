#pragma once
/// \file primitives.hpp
/// Primitive solids built directly as nearly balanced BSP trees (Ihm & Naylor 1990 sec. 6):
/// horizontal planes through the rings first (a balanced tree over the rings), then, in each
/// band, planes through the axis (a balanced tree over the sectors), then the face planes.
/// Curved primitives are exact polyhedra whose faces are planar quadrilaterals between rings
/// (ring polygons of one solid have parallel edges, so every face plane is exact).
/// All sizes in world units of the grid given (a parameter or the options' `grid`, default step
/// 2^-15); coordinates are snapped to it and the solid carries it (docs/kernel.md, "World range").

#include <Eigen/Core>
#include <vector>

#include "bsp/solid.hpp"

namespace sculpt {

/// Axis-aligned box [min, max]. \throw InvalidInput if min >= max in some axis (after snapping).
Solid box(const Eigen::Vector3d& min, const Eigen::Vector3d& max, const kernel::Grid& grid = {});

/// Half-space n.x + offset <= 0 in world units.
struct HalfSpace {
  Eigen::Vector3d normal;
  double offset = 0;
};
/// The convex polytope ∩ half-spaces; redundant half-spaces are dropped. \throw InvalidInput if
/// the intersection is unbounded (it is clipped by the world box otherwise) — empty gives Solid().
Solid convex_polytope(const std::vector<HalfSpace>& half_spaces, const kernel::Grid& grid = {});

/// Right prism over a convex polygon (x, y, counter-clockwise) from z0 to z1.
Solid prism(const std::vector<Eigen::Vector2d>& polygon, double z0, double z1, const kernel::Grid& grid = {});

struct CircularOptions {
  int segments = 32;     ///< edges around the equator / rim (like manifold-3d circularSegments), >= 3
  bool center = false;   ///< cylinder/cone: centre the height on z = 0 instead of z in [0, h]
  kernel::Grid grid{};   ///< the grid of the solid (docs/kernel.md, "World range")
};
/// Cylinder of radius r around the z axis, z in [0, h]: the regular polygon inscribed in the circle,
/// its vertices snapped to the grid points nearest to (r cos 2 pi k / n, r sin 2 pi k / n), the
/// planes through them exact (docs/kernel.md, "Primitives' vertices").
Solid cylinder(double radius, double height, const CircularOptions& options = {});
struct ConeOptions {
  int segments = 32;        ///< as CircularOptions::segments
  bool center = false;      ///< centre the height on z = 0 instead of z in [0, h]
  double top_radius = 0;    ///< > 0: a frustum with this radius at the top
  kernel::Grid grid{};      ///< as CircularOptions::grid
};
/// Cone (frustum if top_radius > 0) around the z axis, base radius r at z = 0, apex at z = h. The
/// larger ring's vertices are grid points as a cylinder's; the apex is on the axis; a frustum's
/// smaller ring is that polygon scaled (its vertices need not be grid points).
Solid cone(double radius, double height, const ConeOptions& options = {});
/// Sphere of radius r centred at the origin: segments edges around the equator,
/// (segments + 1) / 2 rings like OpenSCAD, and a vertex at each pole, (0, 0, ±r) snapped to the
/// grid; the ring vertices on the sphere within the rounding of the planes' integer normals (not
/// grid points). Where a ring and a pole snap to one height, a flat cap at the pole's height.
Solid sphere(double radius, const CircularOptions& options = {});

}  // namespace sculpt
