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
/// (no empty cells), which the builder and the set operations maintain exactly. A sub-hyperplane
/// may be *pending* (no corners) in trees built without clipping (BuildOptions::nodes_cut_cells):
/// algorithms compute it from the node's path when they need it (bsp/node_polygons.hpp).
///
/// A solid may also carry its boundary: convex plane-based fragments on its planes that tile
/// the surface between in- and out-cells. Set operations compute the result's boundary from the
/// operands' boundaries (each operand's fragments clipped by the other tree), so boundary
/// extraction from the whole tree is needed only for solids built without one.
///
/// Deferred trees: the result of a set operation may hold its boundary and the operation's tree
/// merge still to be done (bsp/tree/deferred_tree.hpp). The first call of anything that reads the
/// tree or the storage (root(), nodes(), polygons(), planes(), boundary(), copying, the tree
/// algorithms) runs the merge; the solid is then exactly what the operation would have returned
/// at once. grid(), has_boundary() and boundary_view() do not build it, so output (to_mesh,
/// export, volume) of a result never pays for its tree. A solid is a value for one thread: one
/// whose tree is deferred may not be read from two threads at once before it is built.
///
/// A solid carries the kernel::Grid its planes are in (world = grid units * step; docs/kernel.md,
/// "World range"): operations take it from their operands or parameters, and binary operations
/// on solids of different grids throw GridMismatch. A leaf solid (empty, or all of space) has no
/// coordinates: it combines with a solid of any grid, and the result takes the other's grid.

#include <cstdint>
#include <memory>
#include <optional>
#include <vector>

#include "base/chunked_vector.hpp"
#include "base/errors.hpp"
#include "bsp/fragment_list.hpp"
#include "bsp/tree/fragment_boxes.hpp"
#include "bsp/tree/free_slots.hpp"
#include "kernel/convex_polygon.hpp"
#include "kernel/grid.hpp"

namespace sculpt {

namespace bsp::detail {
struct SolidAccess;  // the tree algorithms' access to a solid's storage (bsp/tree/solid_access.hpp)
class DeferredTree;  // a set operation's tree merge still to be done (bsp/tree/deferred_tree.hpp)
}

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

/// The node polygons of a tree: indexed like a vector, never relocated as it grows (see
/// base/chunked_vector.hpp; in-place set operations append to a workpiece's polygons).
using PolygonStore = ChunkedVector<kernel::ConvexPolygon>;

class Solid {
 public:
  /// The empty solid (a single out leaf), at the default grid.
  Solid();
  ~Solid();
  /// A copy (builds a deferred tree first: the copy and the original share nothing).
  Solid(const Solid& other);
  Solid& operator=(const Solid& other);
  /// Moves leave `other` the empty solid (at its grid).
  Solid(Solid&& other) noexcept;
  Solid& operator=(Solid&& other) noexcept;
  /// The solid whose tree is a single leaf: empty (false) or all of space (true).
  static Solid leaf(bool inside, const kernel::Grid& grid = {});

  /// The grid of the solid's planes: world coordinates are grid units * grid().step().
  [[nodiscard]] const kernel::Grid& grid() const { return grid_; }

  [[nodiscard]] TreeRef root() const { return settled().root_; }
  [[nodiscard]] bool is_empty() const { return settled().root_ == kOut; }
  [[nodiscard]] const kernel::PlaneTable& planes() const { return settled().planes_; }
  [[nodiscard]] const std::vector<BspNode>& nodes() const { return settled().nodes_; }
  /// Sub-hyperplane of node i (same index as nodes()); no corners while pending (see above).
  [[nodiscard]] const PolygonStore& polygons() const { return settled().polygons_; }

  /// True if the solid carries its boundary fragments (results of set operations, leaves).
  [[nodiscard]] bool has_boundary() const { return deferred_ != nullptr || boundary_.has_value(); }
  /// The carried boundary fragments (planes of planes()); empty unless has_boundary().
  [[nodiscard]] const FragmentList& boundary() const;

  /// The carried boundary and the planes it is on, without building a deferred tree (see
  /// above): what output needs. Both are valid until the solid changes or its tree is built
  /// (then read planes() and boundary()). Null members if the solid carries no boundary.
  struct BoundaryView {
    const kernel::PlaneTable* planes = nullptr;
    const FragmentList* fragments = nullptr;
  };
  [[nodiscard]] BoundaryView boundary_view() const;
  /// True while the solid's tree is deferred (not built yet).
  [[nodiscard]] bool tree_deferred() const { return deferred_ != nullptr; }

 private:
  friend struct bsp::detail::SolidAccess;
  using FragmentBoxes = bsp::detail::FragmentBoxes;
  using FreeSlots = bsp::detail::FreeSlots;

  /// Low-level constructor used by the tree algorithms; checks sizes only. The storage may
  /// hold nodes that are not reachable from the root (the free slots of in-place operations);
  /// algorithms only follow the tree from root(). `boundary`, when given, must tile the
  /// solid's boundary exactly.
  Solid(kernel::PlaneTable planes, std::vector<BspNode> nodes,
        PolygonStore polygons, TreeRef root, FreeSlots free = {},
        std::optional<FragmentList> boundary = std::nullopt,
        FragmentBoxes boundary_boxes = {});

  /// Storage moved out of a solid (which becomes empty), for in-place operations.
  struct Storage {
    kernel::PlaneTable planes;
    std::vector<BspNode> nodes;
    PolygonStore polygons;
    TreeRef root;
    FreeSlots free;  ///< free node and plane slots (to reuse) and the scan for free planes
    std::optional<FragmentList> boundary;
    FragmentBoxes boundary_boxes;
  };
  Storage release() &&;

  /// A solid whose tree is deferred (see above); its grid is the default one.
  explicit Solid(std::unique_ptr<bsp::detail::DeferredTree> deferred);
  /// This solid with its deferred tree built, if it had one.
  const Solid& settled() const {
    if (deferred_) build_deferred();
    return *this;
  }
  void build_deferred() const;
  void copy_from(const Solid& other);

  // Mutable: a deferred tree is built, and stored here, on first use from a const solid (the
  // solid's value does not change; see "Deferred trees" above).
  mutable kernel::PlaneTable planes_;
  mutable std::vector<BspNode> nodes_;
  mutable PolygonStore polygons_;
  mutable TreeRef root_ = kOut;
  /// Node slots nothing reaches and plane slots nothing refers to, taken by the nodes and planes
  /// later in-place operations add (bsp/tree/tree_arena.hpp).
  mutable FreeSlots free_;
  mutable std::optional<FragmentList> boundary_ = FragmentList{};
  mutable FragmentBoxes boundary_boxes_;
  kernel::Grid grid_;
  /// The tree merge still to be done, or null (then the members above are the solid).
  mutable std::unique_ptr<bsp::detail::DeferredTree> deferred_;
};

/// Two solids of different grids given to one operation (a set operation, union_all): the
/// message names both grids. An InvalidInput, so it reaches a script as a positioned error.
class GridMismatch : public InvalidInput {
 public:
  GridMismatch(const kernel::Grid& a, const kernel::Grid& b);
};
/// The grid of a result of operands a and b: their common grid, or the grid of the one that is
/// not a leaf (see Solid). \throw GridMismatch if both have planes and their grids differ.
kernel::Grid common_grid(const Solid& a, const Solid& b);

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
