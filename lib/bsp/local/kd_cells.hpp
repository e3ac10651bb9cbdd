#pragma once
/// \file kd_cells.hpp
/// Internal: the axis-aligned subdivision the local set operations work in (local/cell_merge.hpp;
/// Campen & Kobbelt 2010, Nehring-Wirxel et al. 2021: a global subdivision whose leaves hold
/// small local BSP trees). A kd-tree over the boxes of two operands' boundary fragments: a cell
/// is split while both operands have fragments in it and there are more than a few, so cells
/// stay large where only one operand has boundary and small along the intersection; a cell of
/// one operand only is split when it holds more than a few thousand (its local tree may be read
/// for statuses, and one tree of 33,000 pieces took a quarter of a second on one core), or more
/// than 128 when its parent held both operands (next to the other's boundary, where statuses
/// are read). A cell of at most 32 that holds both is still split where a wall separates them.
///
/// Walls lie at half-integer grid coordinates (2x = odd): a fragment's support plane, whose
/// coefficients are coprime integers, is never one of them (an axis-aligned support is x = d
/// for an integer d), so no fragment lies on a wall.

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "bsp/tree/fragment_boxes.hpp"

namespace sculpt::bsp::detail {

/// A cell's walls in half grid units (odd values): lo[k] / 2 <= x_k <= hi[k] / 2.
struct CellBounds {
  std::int64_t lo[3], hi[3];
};

struct KdNode {
  CellBounds bounds;
  int axis = -1;                     ///< -1 for a leaf
  std::int64_t split = 0;            ///< half grid units (odd): the wall between the children
  std::int32_t child[2] = {-1, -1};  ///< below and above the split
  std::int32_t parent = -1;
  bool parent_mixed = false;  ///< the parent held fragments of both operands
  /// Leaves: the fragments of each operand whose boxes meet the closed cell (indices).
  std::array<std::vector<std::uint32_t>, 2> items;
};

struct KdOptions {
  std::size_t leaf_size = 32;  ///< a cell with at most this many fragments is not split
  /// A cell where one operand has no fragment is not split unless it holds more than this many:
  /// the set operation decides it by a status, but a status may read its local tree.
  std::size_t one_operand_leaf_size = 4096;
  /// The same for such a cell whose parent held both operands: it lies next to the other
  /// operand's boundary, where statuses read its local tree, whose cost grows with its pieces
  /// (sphere minus moved copy: 11-13 % fewer instructions than with one_operand_leaf_size alone;
  /// real meshes and the sphere minus a cube 0.5-0.8 % more; docs/benchmarks.md, "Session 46").
  std::size_t near_leaf_size = 128;
  int max_depth = 40;
};

struct KdCells {
  std::vector<KdNode> nodes;         ///< root first, parents before children
  std::vector<std::int32_t> leaves;  ///< node indices of the leaves, in depth-first order
};

/// The subdivision of a box around both operands' fragments (boxes[k]: operand k's fragment
/// boxes; invalid boxes meet every cell). Explicit stack; deterministic.
KdCells subdivide(const std::array<std::span<const FragmentBox>, 2>& boxes, const KdOptions& options = {});

}  // namespace sculpt::bsp::detail
