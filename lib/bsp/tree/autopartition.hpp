#pragma once
/// \file autopartition.hpp
/// Internal: a BSP tree from a closed boundary given as convex fragments (Thibault & Naylor
/// 1987, "Set operations on polyhedra using binary space partitioning trees", sec. 3): each node's
/// plane is the support of one of the fragments in its cell, chosen among a few candidates by a
/// score of splits and balance; the fragments on that plane are used up, the others are split
/// onto the two sides, and a side left without fragments is an in-cell behind and an out-cell in
/// front. Where every candidate leaves nearly all of a cell's fragments on one side (a convex
/// part: a chain, quadratic to build and deep to query), an axis-aligned plane through the median
/// of the fragments, carrying none of them, may split the cell instead (kd-tree style), if it
/// leaves fragments on both sides. Every node thus has fragments strictly inside its cell on its
/// plane or on both sides of it, so its plane cuts the cell.

#include <vector>

#include "bsp/tree/tree_arena.hpp"

namespace sculpt::bsp::detail {

struct AutopartitionOptions {
  int candidates = 5;         ///< fragments whose planes are scored per node (evenly spaced)
  int sample = 48;            ///< fragments each candidate is scored against (evenly spaced)
  double split_weight = 8.0;  ///< score = split_weight * splits + |negative - positive|
  /// The solid carries `fragments` as its boundary; otherwise it is extracted from the tree when
  /// needed (for fragments that may not tile a closed surface exactly, e.g. an unchecked mesh).
  bool carry_boundary = true;
  /// Where every candidate leaves nearly all of a cell's pieces on one side (convex parts), also
  /// try axis-aligned planes through the median of the pieces that carry none (balanced trees).
  bool auxiliary_splits = true;
  /// Score from the corners' floating-point approximations where a piece's box straddles a
  /// candidate (the splits themselves are always exact); false: exact scores.
  bool approximate_scores = true;
};

/// The solid bounded by `fragments`: convex pieces on arena planes (outward normal per `flip`)
/// that tile a closed, consistently oriented surface without overlaps, such as the boundary of
/// a regularized set operation. The solid carries them as its boundary. Explicit stack; arena
/// nodes are not used (only its planes). Empty `fragments` gives the empty solid. With `sample`
/// at least the number of fragments, each candidate is scored against all of them in order.
Solid autopartition(Arena& arena, std::vector<BoundaryFragment> fragments, const AutopartitionOptions& options = {});

}  // namespace sculpt::bsp::detail
