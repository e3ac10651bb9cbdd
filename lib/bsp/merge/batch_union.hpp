#pragma once
/// \file batch_union.hpp
/// Internal: the union of many solids at once. Pairwise merging re-partitions every new operand
/// by the whole accumulated tree, whose cells multiply with each union. Here each operand's
/// boundary is clipped by the trees of the operands whose boxes meet it (Naylor et al. 1990
/// sec. 5: a piece is kept where it is outside the others; where two operands bound the same
/// plane region with the same orientation, the one listed first keeps it, with opposite
/// orientations neither). The union carries that boundary; its tree is built from it
/// (autopartition.hpp) when something first reads the tree.

#include <vector>

#include "bsp/solid.hpp"

namespace sculpt::bsp::detail {

/// The regularized union of `solids` (any number, bounded or not). Every decision is exact.
Solid unite_by_boundaries(std::vector<Solid> solids);

}  // namespace sculpt::bsp::detail
