#pragma once
/// \file set_operations.hpp
/// Regularized set operations by merging BSP trees (Naylor, Amanatides & Thibault 1990):
/// the smaller tree is partitioned by the planes of the larger one, leaves are combined by the
/// operation, and subtrees that become a single leaf are collapsed. All decisions are exact.

#include <utility>
#include <vector>

#include "bsp/solid.hpp"

namespace sculpt {

Solid unite(const Solid& a, const Solid& b);      ///< a ∪ b
Solid intersect(const Solid& a, const Solid& b);  ///< a ∩ b
Solid subtract(const Solid& a, const Solid& b);   ///< a − b
Solid complement(const Solid& a);                 ///< space − a (unbounded)
/// Union of many solids at once: each operand's boundary is clipped by the trees of the operands
/// whose boxes meet it, and one tree is built from the union's boundary (merge/batch_union.hpp),
/// instead of re-partitioning every operand by the growing tree of a left-to-right fold.
Solid unite_all(std::vector<Solid> solids);

/// In-place variants: `a` is consumed and its storage reused when it is the larger tree, so
/// accumulating `acc = unite(std::move(acc), part)` costs what the merge touches, not |acc|.
Solid unite(Solid&& a, const Solid& b);
Solid intersect(Solid&& a, const Solid& b);
Solid subtract(Solid&& a, const Solid& b);

inline Solid operator|(const Solid& a, const Solid& b) { return unite(a, b); }
inline Solid operator&(const Solid& a, const Solid& b) { return intersect(a, b); }
inline Solid operator-(const Solid& a, const Solid& b) { return subtract(a, b); }
inline Solid operator|(Solid&& a, const Solid& b) { return unite(std::move(a), b); }
inline Solid operator&(Solid&& a, const Solid& b) { return intersect(std::move(a), b); }
inline Solid operator-(Solid&& a, const Solid& b) { return subtract(std::move(a), b); }

/// The parts of a solid on the negative (f < 0) and positive side of a plane (grid units),
/// as two solids (Naylor et al. 1990 sec. 3, "partitioning a tree by a plane").
std::pair<Solid, Solid> partition(const Solid& solid, const kernel::Plane& plane);

}  // namespace sculpt
