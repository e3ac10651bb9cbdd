#pragma once
/// \file solid.hpp
/// A solid as a BSP tree with in/out leaves (Naylor, Amanatides & Thibault 1990; Ihm & Naylor
/// 1990 sec. 6). Solids are values: copyable, every operation returns a new solid.
///
/// Storage: nodes in a flat vector (indices, no pointers); each node has a splitting plane
/// (index into the solid's PlaneTable, f > 0 is the positive side) and two children, a node
/// index or one of the leaves kOut / kIn. Each node also keeps its sub-hyperplane: the convex
/// polygon plane ∩ cell (the cell clipped to the world box), used by partitioning and boundary
/// extraction. Invariant: every node's plane cuts its cell into two parts of positive volume
/// (no empty cells), which the builder and the set operations maintain exactly.

#include <cstdint>
#include <vector>

#include "kernel/convex_polygon.hpp"

namespace sculpt {

/// Reference to a subtree: a node index (>= 0) or a leaf.
using TreeRef = std::int32_t;
inline constexpr TreeRef kOut = -1;  ///< out-cell leaf
inline constexpr TreeRef kIn = -2;   ///< in-cell leaf
inline bool is_leaf(TreeRef r) { return r < 0; }

struct BspNode {
  std::int32_t plane;   ///< index into Solid::planes()
  TreeRef negative;     ///< subtree on the side f < 0
  TreeRef positive;     ///< subtree on the side f > 0
};

class Solid {
 public:
  /// The empty solid (a single out leaf).
  Solid() = default;
  /// The solid whose tree is a single leaf: empty (false) or all of space (true).
  static Solid leaf(bool inside);

  [[nodiscard]] TreeRef root() const { return root_; }
  [[nodiscard]] bool is_empty() const { return root_ == kOut; }
  [[nodiscard]] const kernel::PlaneTable& planes() const { return planes_; }
  [[nodiscard]] const std::vector<BspNode>& nodes() const { return nodes_; }
  /// Sub-hyperplane of node i (same index as nodes()).
  [[nodiscard]] const std::vector<kernel::ConvexPolygon>& polygons() const { return polygons_; }

  /// Low-level constructor used by the tree algorithms; checks sizes only. The storage may
  /// hold nodes that are not reachable from the root (left over by in-place operations);
  /// algorithms only follow the tree from root().
  Solid(kernel::PlaneTable planes, std::vector<BspNode> nodes,
        std::vector<kernel::ConvexPolygon> polygons, TreeRef root, std::size_t compacted_size = 0);

  /// Storage moved out of a solid (which becomes empty), for in-place operations.
  struct Storage {
    kernel::PlaneTable planes;
    std::vector<BspNode> nodes;
    std::vector<kernel::ConvexPolygon> polygons;
    TreeRef root;
    std::size_t compacted_size;  ///< node count after the last compaction
  };
  Storage release() &&;

 private:
  kernel::PlaneTable planes_;
  std::vector<BspNode> nodes_;
  std::vector<kernel::ConvexPolygon> polygons_;
  TreeRef root_ = kOut;
  std::size_t compacted_size_ = 0;
};

/// Size and shape of a tree.
struct TreeStats {
  int nodes = 0;       ///< internal nodes
  int in_leaves = 0;
  int out_leaves = 0;
  int height = 0;      ///< longest root-to-leaf path, in nodes (0 for a single leaf)
  double mean_leaf_depth = 0;  ///< unweighted mean over leaves
};
TreeStats tree_stats(const Solid& solid);

}  // namespace sculpt
