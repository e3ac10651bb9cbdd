#pragma once
/// \file sweep.hpp
/// The volume swept by a tool translated along a polyline (SCULPT's strokes): along a straight
/// segment a -> b the swept volume of a convex tool T is exactly hull(T + a ∪ T + b); a
/// non-convex tool is split into the convex in-cells of its BSP tree and each cell is swept.
/// The sweep is the union of those hulls (bsp/merge/convex_union.hpp: no hull gets a tree of its
/// own; their faces are clipped by each other's planes and one tree is built from the union's
/// boundary), exact when the tool's vertices and the
/// path's points are grid points; otherwise each vertex is first rounded to the grid (it moves by
/// at most sqrt(3)/2 grid steps: the vertices of curved primitives are plane intersections).
/// A tool whose hull exceeds it by no more than that rounding counts as convex.

#include <Eigen/Core>
#include <span>

#include "bsp/solid.hpp"

namespace sculpt {

/// The tool (placed as given) moved along `path` (world units, snapped to the tool's grid): the union over
/// the path's segments of the tool swept along each. One point gives the tool moved there.
/// \throw InvalidInput if the path is empty.
Solid sweep(const Solid& tool, std::span<const Eigen::Vector3d> path);

/// `work` minus the tool swept along `path` (a carving stroke).
Solid carve(const Solid& work, const Solid& tool, std::span<const Eigen::Vector3d> path);

/// `work` united with the tool swept along `path` (an adding stroke).
Solid add(const Solid& work, const Solid& tool, std::span<const Eigen::Vector3d> path);

/// In place: `work` is consumed and its storage reused (set_operations.hpp, the in-place
/// variants), so a stroke costs what it touches instead of a copy of the workpiece's tree:
/// `work = carve(std::move(work), tool, path)`.
Solid carve(Solid&& work, const Solid& tool, std::span<const Eigen::Vector3d> path);
Solid add(Solid&& work, const Solid& tool, std::span<const Eigen::Vector3d> path);

}  // namespace sculpt
