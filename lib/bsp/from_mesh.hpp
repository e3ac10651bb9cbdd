#pragma once
/// \file from_mesh.hpp
/// B-rep to BSP (Thibault & Naylor 1987): each face polygon is inserted into the tree; the
/// splitting plane of every subtree is chosen among a sample of the remaining faces by a score
/// that penalizes faces it splits and imbalance between the sides (never just the first face).

#include "bsp/solid.hpp"
#include "mesh/polygon_mesh.hpp"

namespace sculpt {

struct FromMeshOptions {
  int candidates = 8;          ///< faces scored per node (sampled evenly from the remaining ones)
  double split_weight = 8.0;   ///< score = split_weight * splits + |negative - positive|
};

/// Solid bounded by a closed mesh (world units, snapped to the grid; outward orientation).
/// A face whose snapped vertices are exactly coplanar keeps one plane; otherwise each triangle of
/// its triangulation gets its own plane through its three grid points (so the boundary still
/// closes exactly; the face count of a later to_mesh can then grow). \pre the caller validated the mesh (lib/mesh/mesh_validation.hpp): closed,
/// manifold, oriented, not self-intersecting. \throw RangeError for coordinates out of range,
/// InvalidInput for faces with fewer than three non-collinear vertices.
Solid from_mesh(const PolygonMesh& mesh, const FromMeshOptions& options = {});

}  // namespace sculpt
