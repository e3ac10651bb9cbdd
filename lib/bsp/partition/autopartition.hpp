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
///
/// Two ways to choose a node's plane (AutopartitionOptions::score):
/// - SplitsAndBalance: `split_weight * splits + |negative - positive|` over a sample of the
///   cell's fragments (balance in fragment counts; the batch union's choice).
/// - ExpectedDepth (Naylor, "Constructing good partitioning trees", Graphics Interface 1993): the
///   greedy estimate of the expected depth of a point query, 1 + p- T(n-) + p+ T(n+), where p+-
///   is the probability that a point of the cell lies on that side, estimated from points
///   sampled uniformly in the fragments' bounding box and carried down with the cells (Ihm &
///   Naylor 1990 sec. 6: the probability of reaching a cell is its share of the volume), n+- the
///   fragments left on that side and T(n) = log2(1 + n) the cost of a balanced subtree over n
///   fragments (0 for an empty side: a leaf). Splits are charged on top, and auxiliary planes
///   (axis-aligned, through the median of the fragments or of the cell's points, carrying no
///   fragment; only across the longest extent) compete with the face planes for every cell,
///   charged `auxiliary_cost`. While a cell still has sample points, axis-aligned planes just
///   past its fragments' box compete too: they cut off a region without boundary, whose status
///   is found after the build by pushing the node's polygon (plane ∩ cell, which the plane must
///   cut exactly) down the other child's subtree (the plane carries no boundary, so the cells
///   just across it have that status). Only the choice is estimated (in doubles, fixed seed);
///   the splits and the cut test are exact. Optionally (`separating_planes`), the scored face planes
///   moved past all of the cell's fragments compete as well.
///
/// Files: autopartition.cpp (the driver: cells on an explicit stack), piece_pool (the pieces and
/// their exact splits), plane_choice, balance_choice and depth_choice (the two scores),
/// pending_sides (the statuses of auxiliary planes' empty sides).

#include <cstddef>
#include <span>
#include <vector>

#include "bsp/tree/tree_arena.hpp"

namespace sculpt::bsp::detail {

/// How a node's plane is chosen (autopartition.hpp).
enum class PartitionScore { SplitsAndBalance, ExpectedDepth };

/// See AutopartitionOptions::volume_samples.
inline constexpr int kVolumeSamplesPerFragment = 32;

struct AutopartitionOptions {
  int candidates = 5;  ///< fragments whose planes are scored per node (evenly spaced; random for ExpectedDepth)
  int sample = 48;     ///< fragments each candidate is scored against (evenly spaced)
  /// SplitsAndBalance: score = split_weight * splits + |negative - positive|. ExpectedDepth: the
  /// charge for splitting every sampled fragment (added to the expected depth, in nodes).
  double split_weight = 8.0;
  PartitionScore score = PartitionScore::SplitsAndBalance;
  /// ExpectedDepth: points sampled uniformly in the fragments' bounding box (fixed seed) whose
  /// shares estimate the cells' volumes; each candidate is scored against at most
  /// `point_sample` of a cell's points (evenly spaced). At most kVolumeSamplesPerFragment
  /// per fragment are drawn: a small mesh (a turned box) has few cells to tell apart.
  int volume_samples = 4096;
  int point_sample = 256;
  /// ExpectedDepth: the charge (in expected nodes) of an auxiliary plane, which carries no
  /// fragment and so adds a node to the tree; higher values give smaller, less balanced trees.
  double auxiliary_cost = 0.5;
  /// ExpectedDepth: also try each scored face plane moved just past all of the cell's pieces, on
  /// either side (Naylor's separating planes: one side without pieces, handled as PendingSide).
  bool separating_planes = false;
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

/// The fewest fragments a node holds where partition_fragments() considers an auxiliary plane
/// (AutopartitionOptions::auxiliary_splits): so a tree of fewer fragments adds no plane.
inline constexpr std::size_t kAuxiliarySplitFrom = 64;

/// A node of the tree partition_fragments() grows (children: indices into its node list, or leaves).
struct PartitionNode {
  std::int32_t plane;
  TreeRef negative = kOut, positive = kOut;
  bool auxiliary = false;  ///< a splitting plane that carries no fragment
  std::int32_t parent = -1;
  int side = 0;  ///< of the parent
};
struct PartitionTree {
  std::vector<PartitionNode> nodes;  ///< parents before children
  TreeRef root = kOut;               ///< a leaf only for no fragments
};
/// The tree autopartition() builds, as a node list on arena planes (auxiliary planes it chooses
/// are added to the arena). `cell` (plane indices, root first, the cell on their negative sides)
/// bounds the region the fragments lie in: empty for the whole space; otherwise the fragments
/// must be the solid's whole boundary inside that cell (its walls excepted), and the tree gives
/// the solid there.
PartitionTree partition_fragments(Arena& arena, const FragmentList& fragments, const AutopartitionOptions& options,
                                  std::span<const std::int32_t> cell);

/// partition_fragments() appended to arena.nodes (pending polygons: each node cuts its cell);
/// returns its root, or a leaf for no fragments. The caller links it in.
TreeRef autopartition_into(Arena& arena, const FragmentList& fragments, std::span<const std::int32_t> cell,
                           const AutopartitionOptions& options = {});

/// The solid bounded by `fragments`: convex pieces on arena planes (outward normal per `flip`)
/// that tile a closed, consistently oriented surface without overlaps, such as the boundary of
/// a regularized set operation. The solid carries them as its boundary. Explicit stack; arena
/// nodes are not used (only its planes). Empty `fragments` gives the empty solid. With `sample`
/// at least the number of fragments, each candidate is scored against all of them in order.
/// The build is deterministic (a fixed seed for sampling).
Solid autopartition(Arena& arena, FragmentList fragments, const AutopartitionOptions& options = {});

}  // namespace sculpt::bsp::detail
