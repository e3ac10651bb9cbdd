#pragma once
/// \file extent_pruning.hpp
/// Internal: operand B of a set operation only matters inside operand A when the result outside
/// A does not depend on B (A − B and A ∩ B: out of A is out). Where a plane of B has all of A on
/// one closed side, B's cut by that plane only refines cells that the merge discards:
/// - a node of B on such a plane is replaced by its child on A's side before B is partitioned by
///   A's tree (Naylor et al. 1990 sec. 4: the cost of the merge is the number of A's cells that
///   B's sub-hyperplanes reach, and a plane that only touches A reaches every cell near it);
/// - a fragment of B's boundary on such a plane meets no interior point of A, so the operation
///   drops it without pushing it down A's tree.
/// Which side is decided exactly from A's boundary corners (exact predicates; boxes and the
/// floating-point filter only shortcut).

#include <algorithm>
#include <cstdint>
#include <vector>

#include "bsp/tree/tree_arena.hpp"

namespace sculpt::bsp::detail {

/// For some planes of the arena: on which closed side of the plane a bounded solid A lies.
class ExtentSides {
 public:
  /// Negative or Positive if all of A lies on that closed side of plane `p`, else Both (also
  /// for planes not computed).
  [[nodiscard]] kernel::Side of(std::int32_t p) const {
    const auto it = std::lower_bound(planes_.begin(), planes_.end(), p);
    return it != planes_.end() && *it == p ? side_[std::size_t(it - planes_.begin())] : kernel::Side::Both;
  }
  /// True if no computed plane has A on one side (nothing to prune).
  [[nodiscard]] bool none() const { return one_sided_ == 0; }

 private:
  friend ExtentSides extent_sides(Arena&, TreeRef, const FragmentList&, const FragmentBoxes&,
                                  TreeRef, const FragmentList&);
  std::vector<std::int32_t> planes_;  // sorted plane indices that were computed
  std::vector<kernel::Side> side_;    // their sides
  std::size_t one_sided_ = 0;
};

/// The sides of the planes of tree `b`'s nodes and of `b_faces`' supports with respect to solid A
/// (root `a`, boundary `a_faces` with complete boxes `a_boxes`, see complete_boxes()). Nothing is
/// computed (every plane Both) unless A is bounded: its fragments stay off the world box and
/// its tree is out there.
ExtentSides extent_sides(Arena& arena, TreeRef a, const FragmentList& a_faces,
                         const FragmentBoxes& a_boxes, TreeRef b, const FragmentList& b_faces);

/// Replaces every node of tree `b` whose plane has A on one closed side by its child on that side
/// (explicit stack) and returns the new root. Nodes below a replaced one keep their planes but
/// their cells grow, so their sub-hyperplanes become pending (fill_node_polygons recomputes them).
TreeRef prune_to_extent(Arena& arena, TreeRef b, const ExtentSides& sides);

/// Makes `boxes` the boxes of `faces` (each fragment and each block), computing what is missing.
void complete_boxes(const FragmentList& faces, FragmentBoxes& boxes);

}  // namespace sculpt::bsp::detail
