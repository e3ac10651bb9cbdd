#pragma once
/// \file boundary.hpp
/// Boundary extraction (Naylor et al. 1990 sec. 5; Thibault & Naylor 1987): each node's
/// sub-hyperplane is pushed down both subtrees; the fragments with an in-cell on one side and an
/// out-cell on the other are the faces, oriented with the normal towards the out-cell. Vertices
/// are exact plane triples, merged by exact equality; vertices lying on other faces' edges are
/// inserted into those edges (no T-junctions). Where the solid touches itself along an edge or at
/// a vertex, the vertex is duplicated once per sheet so each sheet is a 2-manifold (as Manifold).

#include <Eigen/Geometry>

#include "bsp/solid.hpp"
#include "mesh/polygon_mesh.hpp"
#include "mesh/output_rounding.hpp"

namespace sculpt {

struct MeshOptions {
  bool triangulate = false;  ///< fan-triangulate the convex faces (no zero-area triangles)
  /// Round for other tools (mesh/output_rounding.hpp): no two vertices at one point, no zero-area
  /// face, no self-intersection in doubles; features below the solid's grid step may be collapsed
  /// (docs/kernel.md, "Clean output"). false: the exact boundary, each vertex correctly rounded,
  /// copies of a vertex where the solid touches itself included.
  bool clean = true;
  /// With clean = false, for a screen (the live view): a vertex is written at its double
  /// approximation when that is within 2^-20 grid steps of it, instead of correctly rounded by
  /// exact arithmetic (about a third of a faceted sphere's extraction). Not for files: such a
  /// coordinate depends on the planes the vertex was found on, not only on the point.
  bool approximate = false;
  /// With clean: what the rounding did, and the first problem left when it could not make the
  /// mesh clean (the mesh is then written as it came out; callers should say so).
  OutputRoundingReport* report = nullptr;
};

/// Closed, consistently oriented (counter-clockwise from outside) mesh of the solid's boundary,
/// in world units. The empty solid gives an empty mesh.
PolygonMesh to_mesh(const Solid& solid, const MeshOptions& options = {});

/// Volume (world units^3) from the boundary faces (divergence theorem on exact vertices).
double volume(const Solid& solid);
/// Surface area (world units^2).
double surface_area(const Solid& solid);
/// Bounding box of the boundary vertices (empty box for the empty solid).
Eigen::AlignedBox3d bounding_box(const Solid& solid);

}  // namespace sculpt
