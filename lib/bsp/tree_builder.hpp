#pragma once
/// \file tree_builder.hpp
/// Public API to build BSP trees directly (primitives, solids of revolution of Ihm & Naylor
/// 1990 sec. 6). Add planes, combine them bottom-up into nodes whose children are nodes or
/// the leaves kIn / kOut, then build(): the builder computes every node's sub-hyperplane
/// top-down (explicit stack) and removes nodes whose plane does not cut their cell (their one
/// non-empty side replaces them), so any tree of planes yields a valid solid. A caller that knows
/// every node cuts its cell (BuildOptions::nodes_cut_cells) skips that work: the tree is kept as
/// given and sub-hyperplanes are computed later, only where an algorithm needs them.
///
///   TreeBuilder b;
///   auto top = b.add_plane(kernel::make_plane(0, 0, 1, -z1));      // z <= z1 inside
///   TreeRef t = b.add_node(top, kIn, kOut);
///   Solid s = std::move(b).build(t);

#include "bsp/solid.hpp"

namespace sculpt {

struct BuildOptions {
  /// The caller guarantees that every node's plane cuts its cell (the region of its path) into two
  /// parts of positive volume: the exact image of a valid tree, or a primitive whose every node
  /// is known to carry a piece of a face. Nothing is clipped or dropped; sub-hyperplanes stay
  /// pending until a set operation or boundary extraction needs them, which checks this claim
  /// for every node it computes (std::logic_error if it is false).
  bool nodes_cut_cells = false;
  /// The grid of the planes (they are in grid units): the solid carries it (docs/kernel.md).
  kernel::Grid grid{};
};

class TreeBuilder {
 public:
  TreeBuilder();
  /// Adds a plane (grid units) and returns its index for add_node. `auxiliary`: the plane only
  /// splits space and carries no face of the solid (see kernel::PlaneTable); boundary extraction
  /// skips it. Leave it false unless that is certain.
  std::int32_t add_plane(const kernel::Plane& plane, bool auxiliary = false);
  /// Room for this many planes and nodes in all (for callers that know their tree's size); the
  /// nodes get the extra room the solid keeps for set operations in place (build_as_given).
  void reserve(std::size_t planes, std::size_t nodes);
  /// The planes added so far (references stay valid until the next add_plane).
  [[nodiscard]] const kernel::PlaneTable& planes() const { return planes_; }
  /// A node splitting by plane `plane`: `negative` on the side f < 0, `positive` on f > 0.
  TreeRef add_node(std::int32_t plane, TreeRef negative, TreeRef positive);
  /// Top-down construction: appends `count` nodes for set_node to fill and returns the first's
  /// index. A tree laid out in pre-order (the root first, each node followed by its negative
  /// subtree, then its positive one) is kept without a copy by build(..., {.nodes_cut_cells}).
  TreeRef open_nodes(std::int32_t count);
  /// Fills a node made by open_nodes; its children may be any nodes of this builder or leaves.
  void set_node(TreeRef node, std::int32_t plane, TreeRef negative, TreeRef positive) {
    const auto size = std::int64_t(nodes_.size());
    auto child_ok = [size](TreeRef c) { return c == kIn || c == kOut || (c >= 0 && c < size); };
    if (node < 0 || node >= size || plane < 0 || plane >= planes_.size() || !child_ok(negative) || !child_ok(positive))
      reject_node(node, plane, negative, positive);
    BspNode& n = nodes_[std::size_t(node)];
    if (n.plane < 0) --unset_;
    n = {plane, negative, positive};
  }
  /// A balanced tree for the convex polytope ∩ (f_i <= 0) of the given planes, as a chain in
  /// the given order (callers balance by splitting first with non-face planes).
  TreeRef add_convex_chain(const std::vector<std::int32_t>& face_planes, TreeRef inside = kIn,
                           TreeRef outside = kOut);
  /// Finishes the tree rooted at `root` (see file comment). The builder is consumed.
  Solid build(TreeRef root) &&;
  /// As build(root), for a caller that knows the solid's boundary exactly: convex fragments on
  /// this builder's planes that tile the surface between in and out (solid.hpp). The solid
  /// carries it, so set operations need not extract it from the tree.
  Solid build(TreeRef root, FragmentList boundary, const BuildOptions& options = {}) &&;
  /// As build(root), with options.
  Solid build(TreeRef root, const BuildOptions& options) &&;

 private:
  [[noreturn]] void reject_node(TreeRef node, std::int32_t plane, TreeRef negative, TreeRef positive) const;
  Solid build_with(TreeRef root, std::optional<FragmentList> boundary) &&;
  Solid build_as_given(TreeRef root, std::optional<FragmentList> boundary) &&;
  kernel::PlaneTable planes_;
  std::vector<BspNode> nodes_;
  std::int32_t unset_ = 0;  ///< opened nodes not filled yet
};

}  // namespace sculpt
