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

/// Solid bounded by a closed mesh (world units, snapped to the grid; planar faces, outward
/// orientation). \pre the caller validated the mesh (lib/mesh/mesh_validation.hpp): closed,
/// manifold, oriented, not self-intersecting. \throw RangeError for coordinates out of range,
/// InvalidInput for faces with fewer than three non-collinear vertices.
Solid from_mesh(const PolygonMesh& mesh, const FromMeshOptions& options = {});

}  // namespace sculpt
