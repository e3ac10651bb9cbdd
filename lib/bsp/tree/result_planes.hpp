#pragma once
/// \file result_planes.hpp
/// Internal: the plane table of a set operation's result, whose fragments were made on an arena
/// holding both operands' planes (local/cell_merge.cpp, merge/batch_union.cpp).

#include "bsp/fragment_list.hpp"
#include "kernel/plane_table.hpp"

namespace sculpt::bsp::detail {

/// The result's plane table. When `fragments` use at least half of `planes`, that table itself:
/// its blocks stay shared with the larger operand's table, so no plane is copied
/// (kernel/plane_table.hpp). Otherwise the planes they use, in a table of their own (the world
/// box first), and the fragments renumbered to it: a result does not keep many unused planes (so
/// a chain of operations does not pile up its operands' planes). Planes are then numbered in the
/// order of their first use, as one pass over the fragments would number them, but in chunks on
/// every core. Either way the same table for any thread count.
kernel::PlaneTable result_planes(kernel::PlaneTable&& planes, FragmentList& fragments);

}  // namespace sculpt::bsp::detail
