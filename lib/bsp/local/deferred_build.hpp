#pragma once
/// \file deferred_build.hpp
/// Internal: a solid known by its boundary alone, whose tree is built from that boundary the
/// first time something reads it (Thibault & Naylor 1987 autopartition; partition/autopartition.hpp).
/// Imports of checked meshes and the local set operations (local/cell_merge.hpp) return such
/// solids: output, volume and the next set operation read the boundary only, so a chain of
/// operations on real meshes never builds a whole tree unless a query asks for one.

#include <functional>
#include <memory>
#include <optional>

#include "bsp/partition/autopartition.hpp"
#include "bsp/tree/deferred_tree.hpp"

namespace sculpt::bsp::detail {

class DeferredBuild final : public DeferredTree {
 public:
  /// `fragments` (on `planes`) tile a closed, consistently oriented surface; `far_in` is the
  /// status far from it, when known.
  DeferredBuild(kernel::PlaneTable planes, FragmentList fragments, std::optional<bool> far_in,
                const AutopartitionOptions& options, std::shared_ptr<const TriangleMesh> source = {});
  /// The tree made by `build` instead (a solid with the same boundary: a primitive's own tree).
  DeferredBuild(kernel::PlaneTable planes, FragmentList fragments, std::optional<bool> far_in,
                std::function<Solid()> build);
  [[nodiscard]] const kernel::PlaneTable& planes() const override { return planes_; }
  [[nodiscard]] const FragmentList& boundary() const override { return fragments_; }
  [[nodiscard]] std::optional<bool> far_in() const override { return far_in_; }
  [[nodiscard]] const TriangleMesh* source_mesh() const override { return source_.get(); }
  Solid build() override;

 private:
  kernel::PlaneTable planes_;
  FragmentList fragments_;
  std::optional<bool> far_in_;
  AutopartitionOptions options_;
  std::function<Solid()> build_;
  std::shared_ptr<const TriangleMesh> source_;
};

/// The solid bounded by `fragments`, its tree deferred (see above); a leaf for no fragments
/// (then `far_in` must be known: it is the leaf's status). At the default grid. `source`: the
/// triangle mesh the fragments were made from, one per triangle (DeferredTree::source_mesh).
Solid solid_from_boundary(kernel::PlaneTable planes, FragmentList fragments, std::optional<bool> far_in,
                          const AutopartitionOptions& options = {}, std::shared_ptr<const TriangleMesh> source = {});

/// The solid bounded by `fragments` whose tree, when first used, is `build()` (which must return
/// a solid with exactly that boundary, at the default grid), e.g. a ring primitive's section-6
/// tree. At the default grid.
Solid solid_with_tree_later(kernel::PlaneTable planes, FragmentList fragments, bool far_in,
                            std::function<Solid()> build);

/// The status of `solid` far from its boundary (the region around the world box): what a deferred
/// solid knows, or the leaf its tree reaches there; nullopt if the solid's boundary reaches the
/// world box (unbounded), or if only building a deferred tree would tell (it is never built here).
std::optional<bool> far_status(const Solid& solid);

}  // namespace sculpt::bsp::detail
