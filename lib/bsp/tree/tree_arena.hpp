#pragma once
/// \file tree_arena.hpp
/// Internal: a mutable working copy of one or more trees (planes, nodes, sub-hyperplanes)
/// used by the tree algorithms, and compaction of a result back into a Solid.

#include <utility>
#include <vector>

#include "bsp/solid.hpp"

namespace sculpt::bsp::detail {

struct Arena {
  kernel::PlaneTable planes;
  std::vector<BspNode> nodes;
  PolygonStore polygons;
  /// Cache: index of the opposite plane, or -1 (in a branch, opposite_of[k] is plane
  /// branched_at_ + k's: see branch()).
  std::vector<std::int32_t> opposite_of;

  /// Index of the plane opposite to plane i (added on first use).
  std::int32_t opposite(std::int32_t i);
  /// An arena for a task that builds a tree on this arena's planes while this one does not
  /// change: it shares the planes (copy_planes) and reads this arena's opposites, which must
  /// outlive it. The planes it adds (from this arena's plane count on) and the opposites it makes
  /// are its own, for take_planes() to add to this arena afterwards, in the order a build on this
  /// arena would have added them.
  [[nodiscard]] Arena branch() const;
  /// What a branch added: its planes from the parent's plane count on, with their auxiliary marks
  /// and opposites (branch indices), and the opposites it made for its parent's planes.
  struct BranchPlanes {
    std::int32_t from = 0;
    std::vector<kernel::Plane> planes;
    std::vector<char> auxiliary;
    std::vector<std::int32_t> opposites;  ///< of planes[k], or -1
    std::vector<std::pair<std::int32_t, std::int32_t>> parent_opposites;
  };
  [[nodiscard]] BranchPlanes added_planes() const;
  /// A branch's plane indices mapped to this arena's: the parent's own stay, the added ones moved.
  struct PlaneMap {
    std::int32_t from = 0;
    std::vector<std::int32_t> added;
    std::int32_t operator()(std::int32_t p) const { return p < from ? p : added[std::size_t(p - from)]; }
  };
  /// Adds what a branch added to this arena, which has not changed since it branched except by
  /// earlier take_planes(); returns where each of the branch's planes is here.
  [[nodiscard]] PlaneMap take_planes(const BranchPlanes& added);
  /// Sets `planes` to a copy of `from`: its blocks are shared, none is copied until the arena
  /// writes into it (kernel/plane_table.hpp), and the table never grows by copying itself whole
  /// (growing millions of planes once copied hundreds of MB between two Ctrl-C checks, issue 35).
  void copy_planes(const kernel::PlaneTable& from);
  /// Appends a solid's tree; returns its root in the arena. Plane indices are shifted.
  TreeRef append(const Solid& solid);
  /// Takes over the storage of a solid (the arena must be empty); returns its root. Its carried
  /// boundary, if any, moves to `boundary`.
  TreeRef adopt(Solid&& solid);
  /// The boundary fragments of a solid already appended (or adopted) last, on arena planes: the
  /// carried ones, or extracted from its tree (boundary_fragments) when it carries none.
  FragmentList boundary_of(const Solid& solid);
  /// Of an adopted solid: node slots nothing reaches and plane slots nothing refers to, which
  /// reclaim_added gives to the nodes and planes an operation keeps, and the scan that finds
  /// free plane slots a slice at a time (scan_for_free_planes).
  FreeSlots free;
  /// Boundary of the tree being built, when known; compact() keeps it (and its planes).
  std::optional<FragmentList> boundary;
  FragmentBoxes boundary_boxes;  ///< of `boundary`, or empty

 private:
  /// A branch's opposite of plane i < branched_at_.
  std::int32_t parent_opposite(std::int32_t i);

  std::int32_t last_shift_ = 0;  ///< plane index shift of the last append (0 after adopt)
  // A branch: the parent's opposites, read for planes below branched_at_ (opposite_of holds the
  // branch's own from branched_at_ on), and the opposites it made for parent planes that had none.
  const std::vector<std::int32_t>* parent_opposites_ = nullptr;
  std::int32_t branched_at_ = 0;
  std::vector<std::pair<std::int32_t, std::int32_t>> parent_opposites_made_;
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

/// What an in-place operation added to an adopted solid's storage: planes at indices >=
/// first_plane, nodes at indices >= first_node; all of the boundary's fragments may have been
/// written with all_fragments.
struct AddedStorage {
  std::int32_t first_plane = 0;
  std::size_t first_node = 0;
  bool all_fragments = false;
};

/// What an in-place operation wrote in the older part of an adopted solid's storage, recorded by
/// the steps that write it (the tree merge, merge_boundaries, rebuild_region) and read by
/// reclaim_added, so that it never reads the whole solid.
struct WrittenStorage {
  /// The nodes of tree a that the merge reused (their children and pending polygons may be
  /// written), in pre-order, each once.
  std::vector<TreeRef> merged;
  /// The roots of tree a's subtrees that the merge replaced by a leaf (no longer reached).
  std::vector<TreeRef> dropped;
  /// The fragments of the boundary that were rewritten in place (indices, maybe repeated), and
  /// the first fragment from which all may have changed.
  std::vector<std::size_t> boundary_changed;
  std::size_t boundary_changed_from = 0;
};

/// What reclaim_added leaves: the root (moved if it was an added node) and the nodes the
/// operation kept (added) and freed (older), a measure of what it touched.
struct Reclaimed {
  TreeRef root = kOut;
  std::size_t nodes_touched = 0;
};
/// Drops what an in-place operation added (`added`) and left unused, and frees what it cut away
/// (`written`), in time
/// proportional to what it added and freed (the solid's older storage is not read): the added
/// nodes the result does not reach (a partitioned tree's dropped side, pruned nodes) and the
/// added planes nothing references (most of the other operand's planes, opposites made for one
/// operation) are dropped; the kept added nodes take free node slots (arena.free.nodes), then
/// go to first_node on (pre-order), the kept added planes take free plane slots
/// (arena.free.planes), then go to first_plane on (in order); the references to them are
/// rewritten. The older nodes the result no longer reaches (written.dropped's subtrees, reused
/// nodes the merge collapsed) are cleared and become free node slots for later operations.
/// While a scan for free planes is in progress, the planes that everything written refers to
/// are marked. Older nodes and planes are neither moved nor renumbered.
Reclaimed reclaim_added(Arena& arena, TreeRef root, const AddedStorage& added, const WrittenStorage& written);

/// Advances the scan for plane slots nothing refers to by about `budget` node slots and
/// boundary fragments (starting a scan if none is in progress); when the scan has reached the
/// end of both, arena.free.planes becomes the planes beyond the world box it left unmarked and
/// the scan ends. A plane nothing refers to stays so (an operation refers to its operands' live
/// planes and to planes it adds), and reclaim_added marks what operations write during the
/// scan, so an unmarked plane is unreferenced when the scan ends, however many operations it
/// spanned. Requires every node slot the tree does not reach to be free (cleared).
void scan_for_free_planes(Arena& arena, std::size_t budget);

/// The solid an in-place operation leaves in `arena` (adopted, then reclaim_added, which gave
/// `reclaimed`), taking over the arena's storage. Free plane slots are found by a scan that
/// advances by a slice per operation (scan_for_free_planes): 2 node slots or fragments per node
/// the operation kept or freed (Reclaimed::nodes_touched), at least 512, so no operation reads the whole
/// tree and its cost follows what it touched; the planes an operation leaves unreferenced are
/// found after about tree size / (2 * nodes touched) operations (docs/sculpting.md, "Strokes").
/// When more than half of the node slots are free (the operation cut away most of the tree), the
/// solid is compacted instead: that costs about what freeing them did.
Solid finish_in_place(Arena& arena, const Reclaimed& reclaimed);

/// Flips in and out leaves of the subtree at `root` in place (explicit stack).
void complement_in_place(Arena& arena, TreeRef& root);

}  // namespace sculpt::bsp::detail
