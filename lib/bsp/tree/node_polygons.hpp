#pragma once
/// \file node_polygons.hpp
/// Internal: sub-hyperplanes from a node's path. The region of a node is the intersection of the
/// half-spaces on its path from the root (Naylor et al. 1990, sec. 2), so its sub-hyperplane is
/// its plane's world polygon clipped by those half-spaces. Trees whose nodes are known to cut
/// their cells (TreeBuilder with BuildOptions::nodes_cut_cells) are stored with *pending*
/// polygons (no corners); the functions here compute them where an algorithm needs them.

#include <span>
#include <vector>

#include "bsp/tree/tree_arena.hpp"

namespace sculpt::bsp::detail {

/// True if node polygon `poly` is pending (a node's sub-hyperplane is never empty).
inline bool pending(const kernel::ConvexPolygon& poly) { return poly.corners.empty(); }

/// How a plane meets a cell.
enum class CellCut : std::int8_t {
  Cuts,      ///< in two parts of positive volume; the polygon is written
  Negative,  ///< the cell lies on the plane's negative side
  Positive,  ///< on its positive side
  Empty,     ///< the plane misses the cell: the side is not known from the clipping alone
};
/// Clips the world polygon of `plane` by the half-spaces `path` (plane indices, the cell on their
/// negative side, root first), nearest first: they bound the cell most tightly, so the polygon
/// shrinks to the cell's size at once and far constraints usually cost one box test. A path
/// plane equal to `plane` (or opposite) gives Negative (Positive); `on` is set to it.
CellCut clip_to_cell(kernel::PlaneTable& planes, std::int32_t plane, std::span<const std::int32_t> path,
                     kernel::ConvexPolygon& polygon, std::int32_t& on);

/// Computes the pending polygons of the tree whose root is `root` (the root of a whole tree: its
/// region is the world box). Throws std::logic_error if a node does not cut its cell.
void fill_node_polygons(Arena& arena, TreeRef root);

/// The polygon of a node whose path is `path`, for a node known to cut its cell (throws
/// std::logic_error otherwise).
kernel::ConvexPolygon node_polygon(Arena& arena, std::int32_t plane, std::span<const std::int32_t> path);

/// A copy of a solid's tree (planes, nodes, polygons) with every pending polygon computed; the
/// arena's plane table may grow beyond the solid's (opposites of path planes).
Arena with_node_polygons(const Solid& solid);

}  // namespace sculpt::bsp::detail
