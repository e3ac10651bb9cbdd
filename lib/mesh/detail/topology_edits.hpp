#pragma once
/// \file topology_edits.hpp
/// The output rounding's local edits of the cleaner's mesh (mesh/output_rounding.hpp), a
/// snap-rounding step in the manner of Fortune's vertex rounding: clusters of vertices joined by
/// edges shorter than the feature size contracted into one vertex, slivers without a short edge
/// flipped away, copies of one point that no edge joins moved apart (vertex_moves.hpp). Each edit
/// is made only if the mesh stays a closed 2-manifold, no triangle turns over or degenerates, no
/// two triangles come to meet (crossing_search.hpp), and nothing moves farther than the limit.

#include "mesh/detail/clean_mesh.hpp"
#include "mesh/output_rounding.hpp"

namespace sculpt::mesh::detail {

/// One round of local edits at feature size `delta`, counted in `report`; true if anything
/// changed.
bool sweep(CleanMesh& mesh, double delta, OutputRoundingReport& report);

}  // namespace sculpt::mesh::detail
