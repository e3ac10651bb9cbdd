#pragma once
/// \file triangle_fragment.hpp
/// Internal: a triangle of grid points as a plane-based convex polygon (Bernstein & Fussell 2009,
/// sec. 3), the fragments from_mesh and positive_winding_solid build their trees from.

#include <array>
#include <vector>

#include "kernel/convex_polygon.hpp"
#include "kernel/grid.hpp"

namespace sculpt::bsp::detail {

/// The triangle v[0], v[1], v[2] (not collinear, counter-clockwise about plane `support`, an index
/// in `planes`, which they lie on) as a polygon: each edge plane contains the edge and a grid point
/// off the support plane (transverse to it); the edge planes are added to `planes`.
kernel::ConvexPolygon triangle_polygon(kernel::PlaneTable& planes, std::int32_t support, const kernel::GridPoint* v);

/// The same on a plain list of planes (indices into it), for runs made in parallel and joined later.
kernel::ConvexPolygon triangle_polygon(std::vector<kernel::Plane>& planes, std::int32_t support,
                                       const kernel::GridPoint* v);

/// The edge plane triangle_polygon makes for the side from v[i] to v[i + 1]: it contains the side
/// and a grid point off the support plane, and the triangle lies on its negative side.
kernel::Plane transverse_edge_plane(const kernel::Plane& support, const kernel::GridPoint* v, int i);

/// The triangle v[0], v[1], v[2] on plane `support` whose side from v[i] to v[i + 1] lies on plane
/// `edges[i]` (planes that contain the side, with the triangle on their negative side, chosen by
/// the caller: the neighbouring face's support, say). Corner i is v[i] exactly (no arithmetic).
kernel::ConvexPolygon triangle_polygon(std::int32_t support, const kernel::GridPoint* v,
                                       const std::array<std::int32_t, 3>& edges);

}  // namespace sculpt::bsp::detail
