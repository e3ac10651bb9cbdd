#pragma once
/// \file cell_merge.hpp
/// Internal: a set operation computed cell by cell from its operands' boundaries, with no tree of
/// either operand (docs/bsp.md, "Local set operations"). Campen & Kobbelt 2010 and Nehring-Wirxel,
/// Trettner & Kobbelt 2021 embed local BSP trees in a global subdivision; here:
///
/// 1. A kd-tree over both operands' fragment boxes (local/kd_cells.hpp), split only where both
///    operands have boundary.
/// 2. Each fragment is clipped exactly to the leaves it meets (the walls are axis-aligned planes
///    no fragment lies on).
/// 3. In a leaf where both operands have pieces, each operand's pieces get a local tree
///    (Thibault & Naylor's autopartition over that leaf alone), and each operand's pieces are
///    pushed down the other's local tree (Naylor et al. 1990 sec. 5; tree/boundary_clipper.hpp).
/// 4. In a leaf where one operand X has no piece, X's status is uniform there: it is found from a
///    neighbouring leaf across the wall where X's pieces begin (a polygon on that wall pushed down
///    that leaf's local tree of X: the wall crosses no boundary of X there), or is X's far status
///    outside X's box. A fragment that meets only such leaves is decided whole.
///
/// Every decision is an exact predicate. The result carries its boundary and builds its tree on
/// first use (local/deferred_build.hpp). Steps 2 and 4's pushes run on every core, in fixed
/// chunks of leaves joined in order, so the result does not depend on the thread count.

#include <optional>

#include "bsp/local/kd_cells.hpp"
#include "bsp/solid.hpp"

namespace sculpt::bsp::detail {

struct CellMergeOptions {
  KdOptions cells;
};

/// The set operations (bsp/set_operations.hpp) take the cell path when both operands carry their
/// boundary and have at least this many fragments together (below it the classic merge of
/// their trees is as fast). Tests and benchmarks change it to compare the two paths; it is read
/// once per operation (atomic).
inline constexpr std::size_t kDefaultCellMergeFragments = 4096;
std::size_t cell_merge_threshold();
void set_cell_merge_threshold(std::size_t fragments);
/// Sets the threshold for a scope (tests, benchmarks) and restores the previous one after it;
/// `ClassicMergeOnly` keeps every operation on the classic merge.
class ScopedCellMergeThreshold {
 public:
  explicit ScopedCellMergeThreshold(std::size_t fragments) : saved_(cell_merge_threshold()) {
    set_cell_merge_threshold(fragments);
  }
  ~ScopedCellMergeThreshold() { set_cell_merge_threshold(saved_); }
  ScopedCellMergeThreshold(const ScopedCellMergeThreshold&) = delete;
  ScopedCellMergeThreshold& operator=(const ScopedCellMergeThreshold&) = delete;

 private:
  std::size_t saved_;
};
inline constexpr std::size_t kClassicMergeOnly = std::size_t(-1);

/// op(A, B) (op[in_a][in_b], the operation's truth table) by cells, at the default grid; nullopt
/// when an operand carries no boundary or has none (a leaf solid: the classic merge is as fast).
std::optional<Solid> merge_by_cells(const Solid& a, const Solid& b, const bool op[2][2],
                                    const CellMergeOptions& options = {});

}  // namespace sculpt::bsp::detail
