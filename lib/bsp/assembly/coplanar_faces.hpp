#pragma once
/// \file assembly_coplanar.hpp
/// Internal to mesh assembly: the boundary fragments of one plane become larger faces again.
/// Boundary extraction cuts faces into convex fragments along every node plane (Naylor et al.
/// 1990, sec. 5); here fragments of one oriented plane that share edges are joined into simple
/// polygons, and vertices left straight by the cuts are removed.

#include "bsp/assembly/faces.hpp"

namespace sculpt::bsp::detail {

/// Faces on one oriented plane (equal or opposite planes with the same outward side) that share
/// edges become one face when their union is a simple polygon (one boundary loop). A union with
/// holes (or pinched at a vertex) becomes a few simple polygons of at most 128 corners: disks
/// grown from its first fragments in face order, each joining a neighbour whose boundary meets
/// the disk's in one path of edges and nowhere else. Untouched faces keep their order; merged
/// faces follow.
FaceList merge_coplanar_faces(FaceList faces, int vertex_count, const PlaneIds& ids);

/// A vertex with exactly two neighbours that lies exactly on the line of its two edges in every
/// face using it is a leftover of fragmentation: it is removed from those faces (a face keeps at
/// least three vertices).
FaceList remove_straight_vertices(FaceList faces, int vertex_count, const VertexGeometry& geometry);

}  // namespace sculpt::bsp::detail
