#pragma once
/// \file tree_checks.hpp
/// The structural invariants of a solid's storage (bsp/solid.hpp), stated once for SCULPT_ASSERT
/// where trees are made: every reference from the root on is a leaf or a node index in range,
/// reached once (a tree: no shared or cyclic subtrees); every plane index a reached node, its
/// sub-hyperplane or a boundary fragment uses is in the plane table; a sub-hyperplane with
/// corners lies on its node's plane. Linear in the storage; used by the Sanitize build only.

#include "bsp/solid.hpp"

namespace sculpt::bsp::detail {

/// The first invariant the storage breaks, or nullptr when it keeps them all. `boundary` may be null.
const char* tree_storage_problem(const kernel::PlaneTable& planes, const std::vector<BspNode>& nodes,
                                 const PolygonStore& polygons, TreeRef root, const FragmentList* boundary);

}  // namespace sculpt::bsp::detail
