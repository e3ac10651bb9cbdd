#pragma once
/// \file vertex_merge.hpp
/// Internal to mesh assembly: exact merging of the fragments' corners into vertices. A corner
/// is the implicit point s ∩ p ∩ q of three planes (Bernstein & Fussell 2009, sec. 3). Corners
/// whose planes are the same three planes up to order and orientation are the same point without
/// arithmetic; corners with different triples are candidates when their approximations share a
/// cell of a fine grid, and equal when one lies exactly on the other's three planes.

#include "bsp/assembly/faces.hpp"
#include "bsp/tree/boundary_fragments.hpp"

namespace sculpt::bsp::detail {

/// What the later assembly stages start from.
struct MergedFragments {
  PlaneIds ids;               ///< canonical ids of the planes (canonical_plane_ids)
  AssemblyVertices vertices;  ///< numbered in the order of their first corner
  FaceList faces;             ///< the fragments in final orientation (a flipped one reversed)
};

/// Plane ids, then the fragments' corners merged into vertices by exact equality (each keeps the
/// triple and approximation of its first corner and the canonical ids of every plane of its
/// corners), and the fragments as faces on those vertices, with the plane of the edge leaving each
/// corner. Corners find their classes in order; the exact tests between classes run on every
/// core; vertices are numbered in the order of their first corner: the same result for any thread
/// count.
MergedFragments merge_vertices(FragmentsView fragments);

}  // namespace sculpt::bsp::detail
