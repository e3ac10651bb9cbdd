#pragma once
/// \file deferred_tree.hpp
/// Internal: the tree of a set operation's result, built when it is first used. A set operation
/// computes the result's boundary from its operands' boundaries before it merges their trees
/// (merge/boundary_merge.hpp), and output (to_mesh, export, volume) needs that boundary alone, so
/// the merge can wait. A Solid holding a DeferredTree reads the boundary through it and runs
/// build() the first time anything asks for its tree (see Solid, "Deferred trees").

#include <memory>
#include <optional>

#include "bsp/solid.hpp"
#include "mesh/polygon_mesh.hpp"

namespace sculpt::bsp::detail {

class DeferredTree {
 public:
  virtual ~DeferredTree() = default;
  /// The result's boundary and the planes it is on (valid until build()).
  [[nodiscard]] virtual const kernel::PlaneTable& planes() const = 0;
  [[nodiscard]] virtual const FragmentList& boundary() const = 0;
  /// The result's status far from its boundary, when known without the tree.
  [[nodiscard]] virtual std::optional<bool> far_in() const { return std::nullopt; }
  /// The boundary as the closed triangle mesh it was made from (every vertex a grid point, in
  /// world units; used vertices only), when known: what to_mesh without cleaning returns, so a
  /// general transform of an import does not assemble its fragments again. nullptr otherwise.
  [[nodiscard]] virtual const TriangleMesh* source_mesh() const { return nullptr; }
  /// The complete result (tree, boundary, at the default grid): exactly what the operation would
  /// have returned without deferring. The object is discarded after it returns. If it throws
  /// (Cancelled by Ctrl-C, out of memory), the object is unchanged and may be called again.
  virtual Solid build() = 0;
};

}  // namespace sculpt::bsp::detail
