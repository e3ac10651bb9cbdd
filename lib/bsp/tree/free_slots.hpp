#pragma once
/// \file free_slots.hpp
/// Internal: the free storage of a solid that in-place set operations keep (bsp/tree/tree_arena.hpp,
/// reclaim_added and scan_for_free_planes): node slots nothing reaches, plane slots nothing refers
/// to, and the state of the incremental search for the latter.

#include <cstddef>
#include <cstdint>
#include <vector>

namespace sculpt::bsp::detail {

struct FreeSlots {
  /// Node slots the tree does not reach, each once; a free slot is cleared (plane 0, both
  /// children kOut, an empty polygon on plane 0), so it refers to no plane that can be freed.
  std::vector<std::int32_t> nodes;
  /// Plane slots (beyond the world box) that no reachable node, node polygon or boundary fragment
  /// refers to, each once, as found by the last completed scan (see plane_marked).
  std::vector<std::int32_t> planes;
  /// The scan for unreferenced planes in progress, done a slice per in-place operation: a mark
  /// per plane slot that existed when the scan began (empty: no scan in progress), set for every
  /// plane that the node slots and fragments scanned so far refer to, and for every plane that
  /// the nodes, polygons and fragments an operation writes during the scan refer to; the node
  /// slots before node_cursor and the fragments before fragment_cursor have been scanned.
  std::vector<bool> plane_marked;
  std::size_t node_cursor = 0;
  std::size_t fragment_cursor = 0;
};

}  // namespace sculpt::bsp::detail
