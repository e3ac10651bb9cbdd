#pragma once
/// \file crossing_search.hpp
/// The output rounding's searches for triangles that meet beyond what they share (exactly, with
/// triangle_pairs.hpp): all crossing pairs of the cleaner's mesh (the first time over a BoxGrid,
/// box_grid.hpp; afterwards only the triangles changed since are searched again, through the
/// cleaner's BoxHash), and the count of meetings that the local edits and vertex moves compare
/// before and after.

#include <limits>
#include <utility>
#include <vector>

#include "mesh/detail/clean_mesh.hpp"

namespace sculpt::mesh::detail {

/// Pairs (t, u), t < u, of live, non-degenerate triangles of `mesh` that meet beyond what they
/// share, sorted: the pairs that met at construction and are both unchanged since (they keep
/// their verdict; found once, kept in mesh.first_crossings), and the pairs with a triangle added
/// or moved since, searched anew.
std::vector<std::pair<int, int>> crossings(CleanMesh& mesh);

/// Pairs (triangle in `group`, live triangle outside `replaced`) that meet beyond what they
/// share, plus pairs within `group`; `group` holds corner ids with the current positions.
/// Counted up to `enough`.
int meetings(const CleanMesh& mesh, const std::vector<Tri>& group, const std::vector<int>& replaced,
             int enough = std::numeric_limits<int>::max());

/// Replacing the triangles `replaced` by `added` (corners at their current positions) would add
/// meetings of triangles: more pairs meet afterwards than before. Meetings that rounding made
/// before are not held against an edit that keeps or removes them.
bool adds_meetings(const CleanMesh& mesh, const std::vector<Tri>& added, const std::vector<int>& replaced);

}  // namespace sculpt::mesh::detail
