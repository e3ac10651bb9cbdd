#pragma once
/// \file path_tree.hpp
/// The nearly balanced 2D BSP tree of a convex polygon, Ihm & Naylor 1990, section 6: the path is
/// divided into four sub-curves (one per quadrant, between its extreme vertices in x and y); the
/// chords joining their ends bound an in-cell; each sub-curve is then bisected recursively by the
/// line of its median edge (out-cell outside) and by the two chords from the sub-curve's ends to
/// the median edge's ends (in-cell between them), until only a few edges remain, which are then
/// partitioned by their own lines. Size (partitioning lines) < 3n, height O(log n).

#include <vector>

#include <Eigen/Core>

#include "bsp/convex_path.hpp"
#include "bsp/solid.hpp"

namespace sculpt::revolution::detail {

/// A 2D BSP tree of lines through path vertices; children are node indices or the leaves
/// kIn / kOut of solid.hpp. Line of node k: the directed line from
/// vertex `from` to vertex `to`; its right side (outward for an edge of the counter-clockwise
/// path) is the positive side, child `outside`; the left side is child `inside`.
struct PathTree {
  enum class Kind { Face, Chord };
  struct Node {
    int from, to;
    Kind kind;
    int inside, outside;
  };
  std::vector<Node> nodes;
  int root = kOut;

  /// kIn or kOut for a point (a point on a line goes inside); walk without recursion.
  [[nodiscard]] int classify(const ConvexPath& path, const Eigen::Vector2d& q) const;
  [[nodiscard]] int height() const;  ///< partitioning nodes on the longest root-to-leaf path
};

struct PathTreeOptions {
  int face_only_below = 6;  ///< sub-curves with at most this many edges use face lines only (paper: 6)
};

/// Builds the section 6 tree of a convex path. \throw InvalidInput if face_only_below < 2
PathTree build_path_tree(const ConvexPath& path, const PathTreeOptions& options = {});

}  // namespace sculpt::revolution::detail
