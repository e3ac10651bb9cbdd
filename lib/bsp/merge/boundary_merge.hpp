#pragma once
/// \file boundary_merge.hpp
/// Internal: the boundary of a set operation from its operands' boundaries, so the result's
/// boundary need not be extracted from its whole tree. Each fragment of one operand is pushed down
/// the other operand's tree (Thibault & Naylor 1987; Naylor et al. 1990 sec. 5): a piece inside a
/// cell gets that cell's status on both of its sides; a piece lying on a node's plane is pushed down
/// the child behind it, and each resulting piece down the child in front of it, so it gets each
/// side's status. A piece is kept where the result is in on exactly one of its sides, oriented
/// towards the out side. Where both operands bound the same plane region, only the first operand's
/// piece is kept. Every decision is an exact predicate.

#include <vector>

#include "bsp/tree/tree_arena.hpp"

namespace sculpt::bsp::detail {

class ExtentSides;

/// Fragments of op(A, B), where op[in_a][in_b] is the operation's truth table, A and B are trees
/// in the arena (roots `a`, `b`) and the fragments are on arena planes; `a_boxes` are the boxes
/// of `a_faces` (computed here where missing). The result goes to arena.boundary and
/// arena.boundary_boxes. A's fragments are reused in place: those apart from B's boundary are
/// decided by one box test (one per block of fragments apart from it) without being moved. Call
/// it before merging the trees: the merge reuses their nodes. With `a_sides` (extent_sides() of
/// A) and an op whose result out of A does not depend on B, B's fragments on planes with A on one
/// closed side are dropped without being pushed down A. With `written` (in-place operations),
/// the fragments rewritten in place are recorded there.
void merge_boundaries(Arena& arena, TreeRef a, FragmentList a_faces, FragmentBoxes a_boxes, TreeRef b,
                      const FragmentList& b_faces, const bool op[2][2], const ExtentSides* a_sides = nullptr,
                      WrittenStorage* written = nullptr);

}  // namespace sculpt::bsp::detail
