#pragma once
/// \file self_intersection.hpp
/// Exact detection of self-intersections of a polygon mesh: faces are triangulated, a sweep
/// over x with y/z box overlap finds candidate pairs, and each pair is decided exactly with
/// orient3d (segment-triangle tests; Guigue & Devillers 2003 give the same decisions).
/// Vertices at the same position count as the same vertex, so faces that meet at a
/// duplicated vertex (a solid touching itself at an edge or a corner) are not reported.

#include <cstddef>
#include <vector>

#include "mesh/polygon_mesh.hpp"

namespace sculpt {

/// Two faces that meet anywhere other than at their shared vertices and shared edge.
struct FacePair {
  int face_a = 0;
  int face_b = 0;
};

struct SelfIntersectionOptions {
  size_t max_pairs = 100;  ///< stop after this many pairs were found
};

/// Pairs of faces (face_a < face_b) whose closed point sets meet other than along what they
/// share: crossing, touching, overlapping coplanar faces, or the same triangle twice.
/// Degenerate triangles (collinear corners) are skipped: validation reports them separately.
/// \pre face indices are valid (see check_face_indices).
std::vector<FacePair> find_self_intersections(const PolygonMesh& mesh,
                                              SelfIntersectionOptions options = {});

/// Faces with more than three corners whose boundary crosses or touches itself (two edges that
/// are not neighbours meet), decided exactly in the projection on the coordinate plane where the
/// face's Newell normal is largest (for a zero net area, of its widest corner triangle). Faces with
/// all corners collinear are skipped (degenerate, reported elsewhere).
/// \pre face indices are valid.
std::vector<int> find_self_crossing_faces(const PolygonMesh& mesh, size_t max_faces = 100);

}  // namespace sculpt
