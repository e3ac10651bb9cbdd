#pragma once
/// \file vertex_merge.hpp
/// Internal to mesh assembly: exact merging of the fragments' corners into vertices. A corner
/// is the implicit point s ∩ p ∩ q of three planes (Bernstein & Fussell 2009, sec. 3). Corners
/// whose planes are the same three planes up to order and orientation are the same point without
/// arithmetic; corners with different triples are candidates when their approximations share a
/// cell of a fine grid, and equal when one lies exactly on the other's three planes.

#include "bsp/assembly_faces.hpp"
#include "bsp/boundary_fragments.hpp"

namespace sculpt::detail {

struct MergedVertices {
  AssemblyVertices vertices;    ///< numbered in the order of their first corner
  std::vector<int> vertex_of;   ///< corner (fragments' corners in order) -> vertex
};

/// Vertices of the fragments' corners, merged by exact equality. Each vertex keeps the triple
/// and approximation of its first corner and the canonical ids of every plane of its corners.
MergedVertices merge_vertices(const Fragments& fragments, const PlaneIds& ids);

}  // namespace sculpt::detail
