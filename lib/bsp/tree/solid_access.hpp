#pragma once
/// \file solid_access.hpp
/// Internal: the tree algorithms' access to a Solid's storage (its low-level constructor, moving
/// the storage out for in-place operations, the boundary's boxes). Not part of the public API.

#include <utility>

#include "bsp/solid.hpp"
#include "bsp/tree/deferred_tree.hpp"

namespace sculpt::bsp::detail {

struct SolidAccess {
  using Storage = Solid::Storage;
  /// Solid's low-level constructor (planes, nodes, polygons, root, free plane slots, boundary,
  /// boundary boxes); checks sizes only (see Solid).
  template <class... Args>
  static Solid make(Args&&... args) { return Solid(std::forward<Args>(args)...); }
  /// The storage moved out of `solid`, which becomes empty.
  static Storage release(Solid&& solid) { return std::move(solid).release(); }
  /// `solid` labelled with `grid` (the tree algorithms work in grid units and build solids at
  /// the default grid; the public operations label their results).
  static Solid at_grid(Solid&& solid, const kernel::Grid& grid) {
    solid.grid_ = grid;
    return std::move(solid);
  }
  /// A solid whose tree is built on first use (deferred_tree.hpp), at the default grid.
  static Solid deferred(std::unique_ptr<DeferredTree> tree) { return Solid(std::move(tree)); }
  /// A deferred solid's status far from its boundary, if it knows it (nullopt otherwise, and for
  /// solids whose tree is built).
  static std::optional<bool> deferred_far_in(const Solid& solid) {
    return solid.deferred_ ? solid.deferred_->far_in() : std::nullopt;
  }
  /// A deferred solid's source mesh (DeferredTree::source_mesh), or nullptr.
  static const TriangleMesh* deferred_source_mesh(const Solid& solid) {
    return solid.deferred_ ? solid.deferred_->source_mesh() : nullptr;
  }
  /// The free node and plane slots in-place operations keep in a solid's storage (tree_arena.hpp).
  static const FreeSlots& free_slots(const Solid& solid) { return solid.settled().free_; }
  /// Boxes of solid.boundary() (same order), or empty if not computed.
  static const FragmentBoxes& boundary_boxes(const Solid& solid) { return solid.settled().boundary_boxes_; }
};

}  // namespace sculpt::bsp::detail
