#pragma once
/// \file fragment_boxes.hpp
/// Internal: float boxes around boundary fragments, one per fragment and one per block of
/// fragments, so a set operation finds the fragments near the other operand quickly.

#include <cstddef>
#include <vector>

#include "kernel/convex_polygon.hpp"

namespace sculpt::bsp::detail {

/// Box around a boundary fragment (grid units, rounded outwards to float), for quick culling.
struct FragmentBox {
  float lo[3], hi[3];
  bool valid;  ///< false: unknown (a corner without a usable approximation)
};
FragmentBox fragment_box(kernel::PolygonView polygon);

/// Boxes of a solid's boundary fragments: one per fragment (same order), and one per run of
/// kBlock consecutive fragments (the union of theirs; invalid if one of them is), so a set
/// operation finds the fragments near the other operand without testing every fragment's box.
struct FragmentBoxes {
  static constexpr std::size_t kBlock = 32;
  std::vector<FragmentBox> each;
  std::vector<FragmentBox> blocks;  ///< block_count(each.size()) boxes, or empty if not computed
  static std::size_t block_count(std::size_t fragments) { return (fragments + kBlock - 1) / kBlock; }
  /// Recomputes blocks[j] from `each` (blocks must have its final size).
  void update_block(std::size_t j);
};

}  // namespace sculpt::bsp::detail
