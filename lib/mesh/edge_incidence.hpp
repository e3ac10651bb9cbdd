#pragma once
/// \file edge_incidence.hpp
/// Edge-face incidence of a polygon mesh as a sorted list of half-edge records, shared by
/// measures and validation (no half-edge structure is built, so non-manifold input is fine).

#include <array>
#include <string_view>
#include <vector>

#include "mesh/polygon_mesh.hpp"

namespace sculpt {

/// One face side: the edge between face corners `corner` and `corner + 1`, seen as the
/// undirected pair lo < hi; `forward` says whether the face runs lo -> hi.
struct HalfEdgeRecord {
  int lo = 0;
  int hi = 0;
  int face = 0;
  int corner = 0;
  bool forward = true;
};

/// All face sides, sorted by (lo, hi, face, corner) so that the uses of one edge are adjacent.
/// Sides whose two ends are the same vertex are skipped (see validation: degenerate faces).
std::vector<HalfEdgeRecord> sorted_edge_records(const PolygonMesh& mesh);

/// True when every edge is used exactly once in each direction (sides whose ends are one vertex
/// aside): a closed, consistently oriented surface whose sheets meet only at copies of a vertex,
/// what mesh assembly promises (bsp/assembly). \pre face indices are valid.
bool edges_paired(const PolygonMesh& mesh);

/// The face across each side of each triangle: entry k of face f is the face that uses the edge
/// from corner k to corner k + 1 of f in the other direction, when it is a triangle and these are
/// the edge's only two uses; else -1 (and all three for a face that is not a triangle).
/// \pre face indices are valid.
std::vector<std::array<int, 3>> triangle_neighbours(const PolygonMesh& mesh);

/// \throw InvalidInput naming `who` if a face has fewer than 3 corners or an index is out of range.
void check_face_indices(const PolygonMesh& mesh, std::string_view who);

}  // namespace sculpt
