#pragma once
/// \file triangulate.hpp
/// Triangulation of planar polygon faces by ear clipping in the face's plane projection
/// (Meisters' two-ears theorem; ears are tested with exact orientation predicates).
/// Collinear vertices (for example vertices inserted on an edge to avoid T-junctions) are
/// never the tip of an ear, so they produce no zero-area triangles.

#include <array>
#include <span>
#include <vector>

#include "mesh/polygon_mesh.hpp"

namespace sculpt {

using IndexTriangle = std::array<int, 3>;

/// Triangles (vertex indices into `vertices`) covering the polygon `face`, each oriented like
/// the polygon (counter-clockwise seen from the side its Newell normal points to).
/// A simple planar polygon with n vertices, k of them on straight runs, gives n - 2 - k'
/// triangles of positive area (k' <= k zero-area remainders are dropped).
/// Non-simple or non-planar faces still give triangles, without guarantee of non-overlap.
/// \throw InvalidInput if the face has fewer than 3 vertices or an index is out of range.
std::vector<IndexTriangle> triangulate_polygon(const std::vector<Eigen::Vector3d>& vertices,
                                          std::span<const int> face);

/// The order in which ears are clipped.
enum class EarOrder {
  /// triangulate_polygon's: after an ear, the corner before it is tried next (a convex polygon
  /// becomes a fan around one corner).
  Fan,
  /// After an ear, the corner two further on is tried next, so that ears go round the rim first
  /// (a convex polygon is halved in rounds): triangles near the boundary are small and only a
  /// few span the polygon, which suits a search by boxes.
  Spread,
};

/// triangulate_polygon for many faces: its buffers are kept from one face to the next, so a
/// triangulation allocates nothing once they have grown.
class PolygonTriangulator {
 public:
  /// The triangles of triangulate_polygon(vertices, face) (with EarOrder::Fan; the same polygon
  /// cut otherwise with Spread), appended to `out`.
  /// \throw InvalidInput as triangulate_polygon.
  void append(const std::vector<Eigen::Vector3d>& vertices, std::span<const int> face,
              std::vector<IndexTriangle>& out, EarOrder order = EarOrder::Fan);

 private:
  std::vector<Eigen::Vector2d> points_;
  std::vector<int> next_, prev_;
};

/// The mesh with every face triangulated by triangulate_polygon (same vertices).
/// \throw InvalidInput as triangulate_polygon.
PolygonMesh triangulate(const PolygonMesh& mesh);

}  // namespace sculpt
