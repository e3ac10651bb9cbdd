#pragma once
/// \file solid_checks.hpp
/// Small helpers the bsp tests share: a cube, a solid's volume by the reference formula, and the
/// same tree without its carried boundary (so to_mesh extracts the boundary from the tree).

#include "bsp/boundary.hpp"
#include "bsp/primitives.hpp"
#include "bsp/tree/solid_access.hpp"
#include "support/mesh_checks.hpp"

namespace sculpt::checks {

/// The axis-aligned cube [x, x + s] x [y, y + s] x [z, z + s].
inline Solid cube(double x, double y, double z, double s) { return box({x, y, z}, {x + s, y + s, z + s}); }

/// The signed volume of a mesh, or of a solid's unrepaired boundary, by the reference formula.
inline double vol(const PolygonMesh& m) { return double(reference_signed_volume(m)); }
inline double vol(const Solid& s) { return vol(to_mesh(s, {.clean = false})); }

/// The same tree without its carried boundary: to_mesh extracts it from the tree.
inline Solid without_boundary(const Solid& s) {
  if (is_leaf(s.root())) return s;
  return bsp::detail::SolidAccess::make(s.planes(), s.nodes(), s.polygons(), s.root());
}

}  // namespace sculpt::checks
