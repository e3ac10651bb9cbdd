#pragma once
/// \file winding_solid.hpp
/// The solid of a closed mesh whose faces may intersect each other or meet at non-manifold edges
/// (a scanned surface that touches itself, two shells written as one mesh): the region where the
/// mesh's winding number is positive (Jacobson, Kavan & Sorkine-Hornung 2013, "Robust inside-outside
/// segmentation using generalized winding numbers", take it as the meaning of such a mesh; Zhou,
/// Grinspun, Zorin & Jacobson 2016, "Mesh arrangements for solid geometry", sec. 3, label the cells of
/// the faces' arrangement the same way). Decided exactly, without an arrangement of the mesh itself:
///
/// 1. Every face (a fan of triangles of its snapped corners, so the triangles' boundaries add up to
///    the face's) is a fragment on its own exact plane; the tree is built from all of them as from a
///    clean mesh (Thibault & Naylor 1987, autopartition.hpp), so every leaf is a convex cell that no
///    face crosses, and the winding number is constant in it.
/// 2. Each node's sub-hyperplane is pushed down both of its subtrees: each resulting piece is where
///    two leaf cells meet across the node's plane. The winding number changes across it by the
///    signed number of the node's faces that cover it (decided by clipping the piece by each face's
///    edge planes until it lies inside or outside each); pieces without faces change nothing.
/// 3. Far from the mesh the winding number is 0; it is propagated from that leaf over the pieces
///    (breadth first, explicit queue), each leaf labelled in where it is positive, and the tree is
///    compacted (nodes whose sides became the same leaf go). Exact predicates only, no epsilon.

#include <cstddef>

#include "bsp/solid.hpp"
#include "mesh/polygon_mesh.hpp"

namespace sculpt {

struct WindingSolidOptions {
  /// The grid the vertices are snapped to, which the solid carries (docs/kernel.md, "World range").
  kernel::Grid grid{};
};

/// The solid and what the labelling found (for the message that says what was resolved).
struct WindingSolid {
  Solid solid;
  std::size_t cells = 0;           ///< leaf cells of the tree of all faces
  std::size_t inside_cells = 0;    ///< of them, with positive winding number
  std::size_t multiple_cells = 0;  ///< with winding number 2 or more (covered more than once)
  std::size_t negative_cells = 0;  ///< with negative winding number (inside a shell turned inwards)
};

/// The region where the winding number of `mesh` is positive, as a solid (its vertices snapped to
/// options.grid). \pre none beyond valid indices: the mesh may intersect itself, have non-manifold
/// edges and vertices, degenerate and non-planar faces. It must be closed: after snapping, every
/// edge is used as often in one direction as in the other (then the winding number is defined).
/// \throw InvalidInput for an index out of range or a face of fewer than 3 corners; RangeError for
/// coordinates outside the grid's range; GeometryError if the mesh is not closed (the message
/// lists up to three unmatched edges with their coordinates).
WindingSolid positive_winding_solid(const PolygonMesh& mesh, const WindingSolidOptions& options = {});

}  // namespace sculpt
