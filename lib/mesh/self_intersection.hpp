#pragma once
/// \file self_intersection.hpp
/// Exact detection of self-intersections of a polygon mesh: faces are triangulated (ear clipping
/// round the rim, EarOrder::Spread: a face with many corners gives few long triangles), a uniform
/// grid of cells over the triangles' boxes finds the pairs whose boxes overlap, pairs that share a
/// vertex whose star is certified (it projects one to one along an axis: docs/mesh_io.md) are
/// passed over, and each other pair is decided exactly with orient3d (a triangle strictly on one side of the other's plane is
/// rejected first; coplanar pairs by separating edge lines; otherwise segment-triangle tests;
/// Guigue & Devillers 2003 give the same decisions).
/// Vertices at the same position count as the same vertex, so faces that meet at a
/// duplicated vertex (a solid touching itself at an edge or a corner) are not reported.

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include <Eigen/Core>

#include "mesh/polygon_mesh.hpp"

namespace sculpt {

/// Two faces that meet anywhere other than at their shared vertices and shared edge.
struct FacePair {
  int face_a = 0;
  int face_b = 0;
};

struct SelfIntersectionOptions {
  size_t max_pairs = 100;  ///< stop after this many pairs were found
  /// Stop after this many candidate pairs (overlapping boxes) were examined, or 64 times as many
  /// pairs were scanned; the search is then incomplete. Long fan triangles of faces with thousands of corners can make the candidates
  /// quadratic in number.
  size_t max_candidates = SIZE_MAX;
  /// Optional, one flag per vertex (empty: none): nonzero marks a vertex known to be at its exact
  /// position on a boundary that is itself clean. Precondition (the caller's promise): with
  /// every vertex at its exact position, the mesh has no self-intersection as this search
  /// decides it (with the same faces, and vertices at one point counting as one). A face all of
  /// whose corners are marked is then exactly a face of that clean mesh, triangulated the same way, so
  /// two such faces cannot meet beyond what they share, and pairs of them are not examined: only
  /// pairs with a face that has an unmarked corner are. bsp's to_mesh fills it from the assembly
  /// (docs/kernel.md, "Clean output").
  std::span<const char> exact_vertices = {};
  /// The caller's promise that no two vertices used by faces have the same coordinates: the
  /// vertex indices are then the ids, and the search does not sort the vertices to find copies.
  bool distinct_vertices = false;
};

/// The pairs found, and whether the search looked at every candidate.
struct SelfIntersectionSearch {
  std::vector<FacePair> pairs;
  bool complete = true;
};

/// find_self_intersections with its budget reported.
SelfIntersectionSearch search_self_intersections(const PolygonMesh& mesh, SelfIntersectionOptions options = {});

/// Pairs of faces (face_a < face_b) whose closed point sets meet other than along what they
/// share: crossing, touching, overlapping coplanar faces, or the same triangle twice.
/// Degenerate triangles (collinear corners) are skipped: validation reports them separately.
/// \pre face indices are valid (see check_face_indices).
std::vector<FacePair> find_self_intersections(const PolygonMesh& mesh,
                                              SelfIntersectionOptions options = {});

/// Two triangles meet beyond the corners they share and the edge they share: corners are the
/// same when their ids are equal (ids_a, ids_b). Decided exactly; neither may be degenerate
/// (collinear corners).
bool triangles_meet(const std::array<int, 3>& ids_a, const std::array<Eigen::Vector3d, 3>& a,
                    const std::array<int, 3>& ids_b, const std::array<Eigen::Vector3d, 3>& b);

/// Faces with more than three corners whose boundary crosses or touches itself (two edges that
/// are not neighbours meet), decided exactly in the projection on the coordinate plane where the
/// face's Newell normal is largest (for a zero net area, of its widest corner triangle). Faces with
/// all corners collinear are skipped (degenerate, reported elsewhere).
/// \pre face indices are valid.
std::vector<int> find_self_crossing_faces(const PolygonMesh& mesh, size_t max_faces = 100);

}  // namespace sculpt
