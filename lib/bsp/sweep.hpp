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
#include <Eigen/Geometry>
#include <span>

#include "bsp/solid.hpp"

namespace sculpt {

/// The tool (placed as given) moved along `path` (world units, snapped to the tool's grid): the union over
/// the path's segments of the tool swept along each. One point gives the tool moved there.
/// \throw InvalidInput if the path is empty.
Solid sweep(const Solid& tool, std::span<const Eigen::Vector3d> path);

/// `work` minus the tool swept along `path` (a carving stroke). Strokes (carve and add, every
/// variant) then rebuild the subtrees of the result that the sweep's extent meets where that
/// makes them smaller (rebuild.hpp, rebuild_region, default options), so the tree of a workpiece
/// carved stroke by stroke stays closer to its boundary's size; the set is exactly the same.
Solid carve(const Solid& work, const Solid& tool, std::span<const Eigen::Vector3d> path);

/// `work` united with the tool swept along `path` (an adding stroke).
Solid add(const Solid& work, const Solid& tool, std::span<const Eigen::Vector3d> path);

/// In place: `work` is consumed and its storage reused (set_operations.hpp, the in-place
/// variants), so a stroke costs what it touches instead of a copy of the workpiece's tree:
/// `work = carve(std::move(work), tool, path)`.
Solid carve(Solid&& work, const Solid& tool, std::span<const Eigen::Vector3d> path);
Solid add(Solid&& work, const Solid& tool, std::span<const Eigen::Vector3d> path);

/// The tool carried by a rigid motion given by consecutive poses (tool coordinates -> world): the
/// union over steps i and convex pieces C of hull(pose_i(C) ∪ pose_{i+1}(C)). Rotating between two
/// poses, a piece's points move on curves, not segments, so this is an approximation of the true
/// swept volume: it holds the straight-line interpolants (1 - s) pose_i(x) + s pose_{i+1}(x), which
/// are within the chord error e of the trajectories, and exceeds them by at most
/// 1/4 |R_i - R_{i+1}|_2 diam(C) (a hull point is a combination of two different points' images);
/// sample the motion so that both are small (splines::sample_motion, docs/motions.md). Pure
/// translations give the exact sweep of `sweep(tool, path)`. One pose gives the tool moved there.
/// \throw InvalidInput if `poses` is empty or a pose is not finite.
Solid sweep(const Solid& tool, std::span<const Eigen::Isometry3d> poses);

/// `work` minus the tool carried by the poses.
Solid carve(const Solid& work, const Solid& tool, std::span<const Eigen::Isometry3d> poses);

/// `work` united with the tool carried by the poses.
Solid add(const Solid& work, const Solid& tool, std::span<const Eigen::Isometry3d> poses);

/// In place, as carve(Solid&&, ...) along a path.
Solid carve(Solid&& work, const Solid& tool, std::span<const Eigen::Isometry3d> poses);
Solid add(Solid&& work, const Solid& tool, std::span<const Eigen::Isometry3d> poses);

}  // namespace sculpt
