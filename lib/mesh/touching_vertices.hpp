#pragma once
/// \file touching_vertices.hpp
/// Vertices that touch a face they are not a corner of. Where two parts of a solid touch at an
/// isolated point (a sphere's pole standing on a plate, a cone's base vertex on a box's edge), the
/// point is a vertex of one part and lies inside a face, or inside an edge, of the other. The
/// exact boundary then has faces that meet at a point that is a corner of only one of them, which
/// a reader of the mesh sees as faces crossing. Here such a point becomes a corner of both: the
/// face gets a copy of the vertex as a new corner (a fan around it), or the two faces along the
/// edge get one copy inserted into that edge, so that each part stays a 2-manifold and faces meet
/// only at shared corners and edges (docs/kernel.md, "Clean output").
///
/// Decided exactly: only vertices whose coordinates are exactly their exact point (the assembly's
/// `exact` flags; output_mesh's exactly_represented) are tested, against faces whose corners are
/// all exact, with mesh/predicates.hpp's exact orientation tests on the doubles.

#include <vector>

#include "mesh/polygon_mesh.hpp"

namespace sculpt {

struct TouchingVertices {
  int into_faces = 0;  ///< vertices made a corner of a face they lay inside
  int into_edges = 0;  ///< vertices inserted into an edge they lay inside (counted once per edge)
  /// Contacts left as they were: a vertex inside a face that is not star-shaped from it (a fan
  /// around the vertex would overlap), after the rounds allowed.
  int left = 0;
};

/// Inserts every vertex v with exact[v] != 0 that lies inside a face, or inside an edge, whose
/// corners are all exact and that does not have v (or a copy of v's point) as a corner: as above.
/// New vertices (copies) are appended to mesh.vertices and get exact flag 1. With `triangles`
/// (a triangulated mesh) the faces made stay triangles. `exact` must hold one flag per vertex
/// (else nothing is done). Checks for Ctrl-C (base/cancel.hpp).
/// \throw Cancelled
TouchingVertices insert_touching_vertices(PolygonMesh& mesh, std::vector<char>& exact, bool triangles);

}  // namespace sculpt
