#pragma once
/// \file revolve_boundary.hpp
/// The boundary of a revolved solid built directly from profile and path (no BSP tree), and its
/// analytic volume: the independent reference the revolution tree is checked against, and the
/// input of a B-rep tree build for side-by-side depth-cost comparisons (docs/depth_cost.md).
/// Open (monotone) profiles and full revolutions only; closed profiles and partial revolutions are
/// checked against Pappus's theorem instead (tests/revolution/revolve_closed_test.cpp).

#include <vector>

#include <Eigen/Core>

#include "bsp/convex_path.hpp"
#include "mesh/polygon_mesh.hpp"

namespace sculpt::revolution {

/// Closed polygon mesh of the revolved polytope: one planar trapezoid (a triangle where the profile
/// touches the axis) per slab and path edge, an annulus of trapezoids or a flat cap (one polygon)
/// at each level where the radius jumps (caps where the profile does not end on the axis).
/// Faces counter-clockwise from outside. \throw InvalidInput (see monotone_profile)
PolygonMesh revolve_boundary(const std::vector<Eigen::Vector2d>& profile, const ConvexPath& path);

/// Exact volume of that polytope: the sum over slabs of the frustum volumes
/// h/3 (A0 + A1 + sqrt(A0 A1)), A = r^2 area(path).   \throw InvalidInput
double revolved_volume(const std::vector<Eigen::Vector2d>& profile, const ConvexPath& path);

}  // namespace sculpt::revolution
