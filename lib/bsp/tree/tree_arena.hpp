#pragma once
/// \file tree_arena.hpp
/// Internal: a mutable working copy of one or more trees (planes, nodes, sub-hyperplanes)
/// used by the tree algorithms, and compaction of a result back into a Solid.

#include <vector>

#include "bsp/solid.hpp"

namespace sculpt::bsp::detail {

struct Arena {
  kernel::PlaneTable planes;
  std::vector<BspNode> nodes;
  std::vector<kernel::ConvexPolygon> polygons;
  std::vector<std::int32_t> opposite_of;  ///< cache: index of the opposite plane, or -1

  /// Index of the plane opposite to plane i (added on first use).
  std::int32_t opposite(std::int32_t i);
  /// Appends a solid's tree; returns its root in the arena. Plane indices are shifted.
  TreeRef append(const Solid& solid);
  /// Takes over the storage of a solid (the arena must be empty); returns its root. Its carried
  /// boundary, if any, moves to `boundary`.
  TreeRef adopt(Solid&& solid);
  /// The boundary fragments of a solid already appended (or adopted) last, on arena planes: the
  /// carried ones, or extracted from its tree (boundary_fragments) when it carries none.
  std::vector<BoundaryFragment> boundary_of(const Solid& solid);
  /// Of an adopted solid: plane slots nothing refers to, which reclaim_added gives to the planes
  /// an operation adds; find_free_planes() recomputes them.
  std::vector<std::int32_t> free_planes;
  std::size_t recycled_size = 0;   ///< of an adopted solid: its node storage after freed nodes were last recycled
  /// Boundary of the tree being built, when known; compact() keeps it (and its planes).
  std::optional<std::vector<BoundaryFragment>> boundary;
  FragmentBoxes boundary_boxes;  ///< of `boundary`, or empty
  /// What the last set operation wrote, for in-place operations (reclaim_added): the nodes of
  /// tree a the merge reused (their children and pending polygons may be written), in pre-order;
  /// the fragments of `boundary` merge_boundaries rewrote in place (indices, maybe repeated), and
  /// the first fragment from which all may have changed.
  std::vector<TreeRef> merged;
  std::vector<std::size_t> boundary_changed;
  std::size_t boundary_changed_from = 0;

 private:
  std::int32_t last_shift_ = 0;  ///< plane index shift of the last append (0 after adopt)
};

struct CompactOptions {
  /// Keep the buffers' spare capacity (in-place accumulation grows into it); otherwise buffers
  /// more than a quarter unused are shrunk to fit (a solid kept as a value holds no slack).
  bool keep_capacity = false;
};
/// Turns the tree reachable from `root` into a compact Solid (depth-first order, root first),
/// collapsing nodes whose two children are the same leaf and dropping unused planes. The solid
/// takes over the arena's node and polygon buffers (permuted in place).
Solid compact(Arena& arena, TreeRef root, const CompactOptions& options = {});

/// Frees the storage of nodes the tree at `root` no longer reaches without renumbering the
/// planes or moving the live nodes below the new size (for in-place operations, after each one
/// instead of compaction): nodes whose two children are the same leaf collapse (as in
/// compact()), and the live nodes beyond the live count move into the freed slots below it
/// (nodes and polygons together), children rewritten. Costs a traversal of the live tree's
/// nodes (12 bytes each), a scan of the storage and one move per freed slot below the live
/// count, so a stroke pays for what it freed and added, not for a copy of the whole tree.
/// Returns the root (a leaf if the tree collapsed).
TreeRef recycle_free_nodes(Arena& arena, TreeRef root);

/// What an in-place operation added to an adopted solid's storage: planes at indices >=
/// first_plane, nodes at indices >= first_node; the nodes below first_node whose children or
/// polygons it may have written are arena.merged, the fragments arena.boundary_changed and
/// those from arena.boundary_changed_from (all of them with all_fragments).
struct AddedStorage {
  std::int32_t first_plane = 0;
  std::size_t first_node = 0;
  bool all_fragments = false;
};
/// Drops what an in-place operation added and left unused, in time proportional to what it
/// added (the solid's older storage is not read): the added nodes the result does not reach (a
/// partitioned tree's dropped side, pruned nodes) and the added planes nothing references (most
/// of the other operand's planes, opposites made for one operation). The kept added nodes move
/// down to first_node on (pre-order), the kept added planes down to first_plane on (in order);
/// the references to them are rewritten. Nodes and planes below the marks are neither moved nor
/// renumbered. Returns the root (moved if it was an added node).
TreeRef reclaim_added(Arena& arena, TreeRef root, const AddedStorage& added);

/// Recomputes arena.free_planes: the planes (beyond the world box) that no node, no node
/// polygon and no boundary fragment refers to. Every node of the storage must be reachable (as
/// right after recycle_free_nodes): dead nodes are not told apart. A plane nothing refers to
/// stays so (an operation refers to its operands' live planes and to planes it adds), so its
/// slot can take a plane a later operation adds. One scan of the nodes, polygons and fragments,
/// no renumbering and no moves.
void find_free_planes(Arena& arena);

/// Flips in and out leaves of the subtree at `root` in place (explicit stack).
void complement_in_place(Arena& arena, TreeRef& root);

}  // namespace sculpt::bsp::detail
